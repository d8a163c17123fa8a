// tinygltf's reading of a .gltf or .glb (Khronos glTF 2.0, sections 3.6 "Binary Data Storage" and 4 "GLB File
// Format"), shared by the loader and the bake's writer, which reads its input again to edit it.
#pragma once

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace obscura::loader {

// Reads `path` (a .glb with `binary`) into `model`, its images left undecoded. Throws obscura::Error naming
// `path` with one line for anything tinygltf refuses or throws (a buffer's byteLength of 0 once escaped as
// "internal: vector::_M_range_check", exit 3), and for a buffer URI naming something other than a regular file
// (a FIFO blocked the load for good; a directory read as "out of memory").
void readTinyGltf(const std::string& path, bool binary, tinygltf::Model& model);

// The nodes the scene hangs from: the roots of the document's "scene", or of scene 0 when it names none, or with
// no scenes every node that is nobody's child (a child index out of range is left to the nodes' own checks).
// Throws obscura::Error naming `path` for a "scene" that is not one of the scenes (it read scene 0 silently).
std::vector<int> sceneRoots(const tinygltf::Model& model, const std::string& path);

// Whether a primitive of this mode is read as triangles: TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN (glTF 3.7.2.1).
// The loader and the writer agree on it, so the writer's primitives follow the loader's meshes.
inline bool isTriangleMode(int mode) { return mode == 4 || mode == 5 || mode == 6; }

} // namespace obscura::loader
