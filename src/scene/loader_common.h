// Small pieces every scene loader shares.
#pragma once

#include "obscura/error.h"
#include "obscura/scene_io.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace obscura::loader {

// The first non-blank line of a library's message: our messages are one line, theirs may be several.
inline std::string firstLine(const std::string& s) {
    std::size_t begin = s.find_first_not_of(" \t\r\n");
    if (begin == std::string::npos) return {};
    std::string line = s.substr(begin, s.find('\n', begin) - begin);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    return line;
}

// A scene file must exist and be a file: a directory named x.ply once reached the C++ library's "basic_filebuf::
// underflow error reading the file: Is a directory", without the path, and x.gltf read as out of memory.
inline void checkSceneFile(const std::string& path) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(status)) fail(path, "no such file");
    if (std::filesystem::is_directory(status)) fail(path, "is a directory, not a scene file");
    if (!std::filesystem::is_regular_file(status)) fail(path, "not a regular file");
}

// The whole file, for the text and PLY readers that parse it in memory.
inline std::string readWholeFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open for reading");
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) fail(path, "read error");
    return bytes;
}

// The caller's LoadInfo, reset, or a local one when the caller passed none.
class InfoSink {
public:
    explicit InfoSink(LoadInfo* info) : out_(info ? *info : local_) { out_ = LoadInfo{}; }
    LoadInfo& operator*() { return out_; }
    LoadInfo* operator->() { return &out_; }

private:
    LoadInfo local_;
    LoadInfo& out_;
};

// The end of every load: checks and drops degenerate triangles, counting them in the caller's info.
inline Scene finishLoad(Scene scene, const std::string& path, InfoSink& info) {
    sanitizeScene(scene, path, &info->droppedTriangles);
    return scene;
}

} // namespace obscura::loader
