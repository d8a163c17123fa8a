// Writing glTF 2.0 (.gltf with embedded buffers, or .glb), optionally with extra per-vertex attributes per
// instance (a bake's results). Both writers go through writeAtomically: a failure leaves no partial file.
//
// Errors: throw obscura::Error("<path>: <problem>").
#pragma once

#include "obscura/scene.h"

#include <string>
#include <vector>

namespace obscura {

// A per-vertex attribute for every instance of a scene: instance i's values are
// data[components * first[i] .. components * first[i + 1]), one per vertex of its mesh, in the mesh's order.
struct VertexAttribute {
    std::string name;      // a glTF semantic: "COLOR_0" or an application-specific "_NAME"
    int components = 1;    // 1 (SCALAR) or 3 (VEC3)
    std::vector<float> data;
};
struct InstanceAttributes {
    std::vector<std::size_t> first;          // per instance + 1
    std::vector<VertexAttribute> attributes;
};

// The whole scene: one node per instance (matrix), one material per mesh (baseColorFactor), positions,
// normals and 32-bit indices. Meshes placed several times are shared, unless `attributes` is given: then
// every instance gets a mesh of its own (sharing the geometry's accessors) carrying its attributes.
void writeGltf(const Scene& scene, const std::string& path, const InstanceAttributes* attributes = nullptr);

// The glTF file `inputPath` as it is plus the attributes on each triangle primitive: its JSON is edited, so every
// property the bake does not touch (extensions and extras included) is written as the input had it. `scene`
// must be loadGltf(inputPath): its instances are matched to the file's (node, primitive) pairs in the loader's
// order. A mesh used by several nodes (or by a node outside the baked scene) is cloned for the second and later
// baked nodes, so each instance keeps its own values. An existing attribute of the same name is replaced, and
// an earlier bake's _AO_SHORT and _AO_LONG are removed. Images are not rewritten: URIs (data URIs too) and
// buffer views are kept as they are. Every buffer is embedded (.glb: buffer 0 as the binary chunk).
void writeGltfWithAttributes(const std::string& inputPath, const Scene& scene, const std::string& path,
                             const InstanceAttributes& attributes);

} // namespace obscura
