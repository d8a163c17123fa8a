// loadScene: picks the loader by file extension.
#include "obscura/scene_io.h"

#include "obscura/error.h"
#include "scene/loader_common.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace obscura {

namespace {

std::string lowerCase(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

} // namespace

bool isSceneFileExtension(const std::string& extension) {
    const std::string ext = lowerCase(extension);
    return ext == ".gltf" || ext == ".glb" || ext == ".obj" || ext == ".ply";
}

Scene loadScene(const std::string& path, LoadInfo* info) {
    loader::checkSceneFile(path);
    const std::string ext = lowerCase(std::filesystem::path(path).extension().string());
    if (ext == ".gltf" || ext == ".glb") return loadGltf(path, info);
    if (ext == ".obj") return loadObj(path, info);
    if (ext == ".ply") return loadPly(path, info);
    fail(path, "unknown scene format '" + ext + "' (expected .gltf, .glb, .obj or .ply)");
}

} // namespace obscura
