// tinygltf's reading of a glTF file; see gltf_read.h.
#include "scene/gltf_read.h"

#include "obscura/error.h"
#include "scene/loader_common.h"

#include <filesystem>
#include <new>
#include <string>
#include <system_error>
#include <vector>

namespace obscura::loader {

namespace {

// Textures are ignored, so images are never decoded; this also keeps a missing or corrupt texture from
// failing the load of otherwise good geometry.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

// tinygltf's own FileExists opens the file, which blocks on a FIFO until someone writes to it.
bool fileExists(const std::string& file, void*) {
    std::error_code ec;
    return std::filesystem::exists(std::filesystem::status(file, ec));
}

// tinygltf's own reader, for regular files only: it opens whatever a buffer's URI names.
bool readRegularFile(std::vector<unsigned char>* out, std::string* err, const std::string& file, void* user) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(std::filesystem::status(file, ec))) {
        if (err) *err += "not a regular file";  // tinygltf puts "File read error : NAME : " before it
        return false;
    }
    return tinygltf::ReadWholeFile(out, err, file, user);
}

// tinygltf quotes a data: URI it cannot decode whole: a 1 MB buffer gave a 1.4 MB line. Its contents are
// left out; the message keeps what names the buffer.
std::string withoutDataUris(std::string text) {
    for (std::size_t at = text.find("data:"); at != std::string::npos; at = text.find("data:", at + 1)) {
        const std::size_t comma = text.find(',', at), end = text.find_first_of(" \"'\n", at);
        if (comma == std::string::npos || (end != std::string::npos && comma > end)) continue;
        const std::size_t stop = end == std::string::npos ? text.size() : end;
        if (stop - comma > 16) text.replace(comma + 1, stop - comma - 1, "... (" + std::to_string(stop - comma - 1) + " characters)");
    }
    return text;
}

} // namespace

void readTinyGltf(const std::string& path, bool binary, tinygltf::Model& model) {
    checkSceneFile(path);
    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(skipImage, nullptr);
    gltf.SetFsCallbacks({&fileExists, &tinygltf::ExpandFilePath, &readRegularFile, &tinygltf::WriteWholeFile,
                         nullptr});
    std::string err, warn;
    bool ok = false;
    try {
        ok = binary ? gltf.LoadBinaryFromFile(&model, &err, &warn, path) : gltf.LoadASCIIFromFile(&model, &err, &warn, path);
    } catch (const std::bad_alloc&) {
        fail(path, "not a valid glTF file (a size it states is too large to read)");
    } catch (const std::exception& e) {
        fail(path, std::string("not a valid glTF file (") + firstLine(e.what()) + ")");
    }
    // tinygltf can fill err and still succeed (a misaligned chunk), so only the return value decides.
    if (!ok) fail(path, err.empty() ? "not a valid glTF file" : withoutDataUris(firstLine(err)));
}

std::vector<int> sceneRoots(const tinygltf::Model& model, const std::string& path) {
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        const int s = model.defaultScene < 0 ? 0 : model.defaultScene;
        if (std::size_t(s) >= model.scenes.size())
            fail(path, "\"scene\": " + std::to_string(s) + " is out of range (" + std::to_string(model.scenes.size()) +
                           " scenes)");
        return model.scenes[std::size_t(s)].nodes;
    }
    std::vector<char> isChild(model.nodes.size(), 0);
    for (const tinygltf::Node& node : model.nodes)
        for (int c : node.children)
            if (c >= 0 && std::size_t(c) < isChild.size()) isChild[std::size_t(c)] = 1;
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
        if (!isChild[i]) roots.push_back(int(i));
    return roots;
}

} // namespace obscura::loader
