// Scene files: glTF 2.0 (.gltf, .glb), Wavefront OBJ (+ .mtl Kd), PLY (ASCII and binary).
//
// Errors: throws obscura::Error("<path>: <problem>") for a missing file, an unknown extension, a truncated
// or corrupt file, an empty mesh and NaN/Inf vertex data. Degenerate triangles are not an error: they are
// dropped and counted in LoadInfo::droppedTriangles, for the caller to report in one warning line.
#pragma once

#include "obscura/scene.h"

#include <string>

namespace obscura {

struct LoadInfo {
    std::size_t droppedTriangles = 0;
    std::size_t skippedPrimitives = 0;  // glTF primitives that are not triangles (points, lines)
    std::size_t colouredPrimitives = 0; // glTF triangle primitives with a COLOR_0, which the bake's glTF replaces
};

// Dispatches on the extension. The result has normals for every mesh (computed when the file has none)
// and passed sanitizeScene().
Scene loadScene(const std::string& path, LoadInfo* info = nullptr);
// Whether loadScene reads files of this extension (".gltf", ".glb", ".obj", ".ply"; any case).
bool isSceneFileExtension(const std::string& extension);

// glTF: the default scene's node hierarchy with TRS or matrix transforms; a mesh referenced by several
// nodes becomes one Mesh per primitive with several Instances; baseColorFactor gives Mesh::baseColor.
Scene loadGltf(const std::string& path, LoadInfo* info = nullptr);
// OBJ: one Mesh per (object, material) run of faces, polygons fan-triangulated; Kd from the .mtl.
Scene loadObj(const std::string& path, LoadInfo* info = nullptr);
// PLY: the "vertex" (x,y,z[,nx,ny,nz][,red,green,blue]) and "face" (vertex_indices | vertex_index)
// elements; other elements and properties are skipped. One Mesh; vertex colours average into baseColor.
Scene loadPly(const std::string& path, LoadInfo* info = nullptr);

} // namespace obscura
