// loadScene: picks the loader by file extension.
#include "obscura/scene_io.h"

#include "obscura/error.h"
#include "scene/loader_common.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace obscura {

Scene loadScene(const std::string& path, LoadInfo* info) {
    loader::checkSceneFile(path);
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".gltf" || ext == ".glb") return loadGltf(path, info);
    if (ext == ".obj") return loadObj(path, info);
    if (ext == ".ply") return loadPly(path, info);
    fail(path, "unknown scene format '" + ext + "' (expected .gltf, .glb, .obj or .ply)");
}

} // namespace obscura
