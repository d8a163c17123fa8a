// glTF 2.0 writer on tinygltf: scenes from scratch (generated levels, baked OBJ/PLY) and a loaded file
// with extra vertex attributes added (baked glTF), keeping everything else the file had.
#include "obscura/gltf_writer.h"

#include "obscura/error.h"
#include "obscura/image_io.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <map>

namespace obscura {

namespace {

// Writes no image files; returning false tells tinygltf to keep each image's URI as it was.
bool keepImage(const std::string*, const std::string*, const tinygltf::Image*, bool, std::string*, void*) { return false; }
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

class BufferWriter {
public:
    BufferWriter(tinygltf::Model& model) : model_(model) {
        if (model_.buffers.empty()) model_.buffers.emplace_back();
    }

    int add(const void* data, std::size_t bytes, std::size_t count, int componentType, int type, int target) {
        std::vector<unsigned char>& buffer = model_.buffers[0].data;
        while (buffer.size() % 4) buffer.push_back(0);  // accessors need component alignment
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = buffer.size();
        view.byteLength = bytes;
        view.target = target;
        const auto* p = static_cast<const unsigned char*>(data);
        buffer.insert(buffer.end(), p, p + bytes);
        model_.bufferViews.push_back(view);
        tinygltf::Accessor acc;
        acc.bufferView = int(model_.bufferViews.size() - 1);
        acc.byteOffset = 0;
        acc.componentType = componentType;
        acc.count = count;
        acc.type = type;
        model_.accessors.push_back(acc);
        return int(model_.accessors.size() - 1);
    }

    int addVec3(const std::vector<Vec3>& v, bool withBounds) {
        int a = add(v.data(), v.size() * sizeof(Vec3), v.size(), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                    TINYGLTF_TARGET_ARRAY_BUFFER);
        if (withBounds) {  // required on POSITION
            Bounds b;
            for (Vec3 p : v) b.extend(p);
            model_.accessors[std::size_t(a)].minValues = {b.lo.x, b.lo.y, b.lo.z};
            model_.accessors[std::size_t(a)].maxValues = {b.hi.x, b.hi.y, b.hi.z};
        }
        return a;
    }

    int addFloats(const float* v, std::size_t count, int components) {
        return add(v, count * std::size_t(components) * sizeof(float), count, TINYGLTF_COMPONENT_TYPE_FLOAT,
                   components == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_SCALAR, TINYGLTF_TARGET_ARRAY_BUFFER);
    }

private:
    tinygltf::Model& model_;
};

void addAttributes(BufferWriter& writer, tinygltf::Primitive& prim, const InstanceAttributes& a, std::size_t instance) {
    const std::size_t first = a.first[instance], count = a.first[instance + 1] - first;
    for (const VertexAttribute& attr : a.attributes)
        prim.attributes[attr.name] =
            writer.addFloats(attr.data.data() + first * std::size_t(attr.components), count, attr.components);
}

void save(tinygltf::Model& model, const std::string& path) {
    const bool binary = fileExtension(path) == ".glb";
    if (!binary && fileExtension(path) != ".gltf") fail(path, "unsupported glTF extension (expected .gltf or .glb)");
    writeAtomically(path, [&](const std::string& temp) {
        tinygltf::TinyGLTF gltf;
        gltf.SetImageWriter(keepImage, nullptr);
        // embedBuffers: a .gltf is written as one self-contained file, so the rename is the whole write.
        if (!gltf.WriteGltfSceneToFile(&model, temp, false, true, !binary, binary))
            fail(path, "cannot write the glTF file");
    });
}

void checkAttributes(const Scene& scene, const InstanceAttributes* a, const std::string& path) {
    if (!a) return;
    if (a->first.size() != scene.instances.size() + 1) fail(path, "attribute offsets do not match the scene's instances");
    for (std::size_t i = 0; i < scene.instances.size(); ++i)
        if (a->first[i + 1] - a->first[i] != scene.meshes[scene.instances[i].mesh].positions.size())
            fail(path, "attribute count of instance " + std::to_string(i) + " does not match its mesh");
    for (const VertexAttribute& attr : a->attributes)
        if (attr.data.size() != a->first.back() * std::size_t(attr.components))
            fail(path, "attribute " + attr.name + " has the wrong size");
}

} // namespace

void writeGltf(const Scene& scene, const std::string& path, const InstanceAttributes* attributes) {
    checkAttributes(scene, attributes, path);
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "obscura";
    BufferWriter writer(model);
    struct Geometry {
        int positions, normals, indices, material;
    };
    std::vector<Geometry> geometry;
    std::vector<int> sharedMesh(scene.meshes.size(), -1);
    for (const Mesh& mesh : scene.meshes) {
        Geometry g;
        g.positions = writer.addVec3(mesh.positions, true);
        g.normals = mesh.normals.size() == mesh.positions.size() ? writer.addVec3(mesh.normals, false) : -1;
        g.indices = writer.add(mesh.indices.data(), mesh.indices.size() * 4, mesh.indices.size(),
                               TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        tinygltf::Material mat;
        mat.name = mesh.name;
        mat.pbrMetallicRoughness.baseColorFactor = {mesh.baseColor.x, mesh.baseColor.y, mesh.baseColor.z, 1.0};
        model.materials.push_back(mat);
        g.material = int(model.materials.size() - 1);
        geometry.push_back(g);
    }
    auto makeMesh = [&](std::uint32_t m, const std::string& name) {
        tinygltf::Primitive prim;
        prim.attributes["POSITION"] = geometry[m].positions;
        if (geometry[m].normals >= 0) prim.attributes["NORMAL"] = geometry[m].normals;
        prim.indices = geometry[m].indices;
        prim.material = geometry[m].material;
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        tinygltf::Mesh out;
        out.name = name;
        out.primitives.push_back(prim);
        model.meshes.push_back(out);
        return int(model.meshes.size() - 1);
    };
    tinygltf::Scene root;
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        int meshIndex;
        if (attributes) {
            meshIndex = makeMesh(inst.mesh, scene.meshes[inst.mesh].name);
            addAttributes(writer, model.meshes.back().primitives[0], *attributes, i);
        } else {
            if (sharedMesh[inst.mesh] < 0) sharedMesh[inst.mesh] = makeMesh(inst.mesh, scene.meshes[inst.mesh].name);
            meshIndex = sharedMesh[inst.mesh];
        }
        tinygltf::Node node;
        node.name = inst.name;
        node.mesh = meshIndex;
        bool identity = true;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) identity = identity && inst.worldFromObject.m[r][c] == (r == c ? 1.0f : 0.0f);
        if (!identity) {
            node.matrix.resize(16);
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) node.matrix[std::size_t(c * 4 + r)] = inst.worldFromObject.m[r][c];
        }
        model.nodes.push_back(node);
        root.nodes.push_back(int(model.nodes.size() - 1));
    }
    model.scenes.push_back(root);
    model.defaultScene = 0;
    save(model, path);
}

void writeGltfWithAttributes(const std::string& inputPath, const Scene& scene, const std::string& path,
                             const InstanceAttributes& attributes) {
    checkAttributes(scene, &attributes, path);
    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(skipImage, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const bool ok = fileExtension(inputPath) == ".glb" ? gltf.LoadBinaryFromFile(&model, &err, &warn, inputPath)
                                                        : gltf.LoadASCIIFromFile(&model, &err, &warn, inputPath);
    if (!ok) fail(inputPath, "not a valid glTF file");

    // The loader's order: the default scene's roots, depth first, children in order; per node with a mesh,
    // its triangle primitives. The loader has already rejected cycles and out-of-range references.
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        int s = model.defaultScene;
        if (s < 0 || std::size_t(s) >= model.scenes.size()) s = 0;
        roots = model.scenes[std::size_t(s)].nodes;
    } else {
        std::vector<char> isChild(model.nodes.size(), 0);
        for (const tinygltf::Node& node : model.nodes)
            for (int c : node.children) isChild[std::size_t(c)] = 1;
        for (std::size_t i = 0; i < model.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(int(i));
    }
    struct Target {
        int node;
        std::size_t primitive;
    };
    std::vector<Target> targets;
    for (int r : roots) {
        std::vector<int> stack{r};
        while (!stack.empty()) {
            int n = stack.back();
            stack.pop_back();
            const tinygltf::Node& node = model.nodes[std::size_t(n)];
            if (node.mesh >= 0)
                for (std::size_t p = 0; p < model.meshes[std::size_t(node.mesh)].primitives.size(); ++p)
                    if (model.meshes[std::size_t(node.mesh)].primitives[p].mode == TINYGLTF_MODE_TRIANGLES)
                        targets.push_back({n, p});
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back(*c);
        }
    }
    if (targets.size() != scene.instances.size())
        fail(inputPath, "has " + std::to_string(targets.size()) + " triangle primitives placed by nodes, the scene " +
                            std::to_string(scene.instances.size()) + " instances (was it loaded from this file?)");

    BufferWriter writer(model);
    std::map<int, int> meshOfNode;  // node -> the mesh it writes into (its own clone after the first user)
    std::map<int, int> firstUser;   // mesh -> the node that keeps the original
    for (std::size_t i = 0; i < targets.size(); ++i) {
        const int n = targets[i].node;
        tinygltf::Node& node = model.nodes[std::size_t(n)];
        if (!meshOfNode.count(n)) {
            auto [it, first] = firstUser.try_emplace(node.mesh, n);
            if (first) {
                meshOfNode[n] = node.mesh;
            } else {
                tinygltf::Mesh clone = model.meshes[std::size_t(node.mesh)];
                clone.name += clone.name.empty() ? "" : " (" + (node.name.empty() ? "node " + std::to_string(n) : node.name) + ")";
                model.meshes.push_back(clone);
                node.mesh = int(model.meshes.size() - 1);
                meshOfNode[n] = node.mesh;
            }
        }
        tinygltf::Primitive& prim = model.meshes[std::size_t(meshOfNode[n])].primitives[targets[i].primitive];
        const std::size_t vertices = attributes.first[i + 1] - attributes.first[i];
        const tinygltf::Accessor& positions = model.accessors[std::size_t(prim.attributes.at("POSITION"))];
        if (positions.count != vertices)
            fail(inputPath, "node " + std::to_string(n) + " primitive " + std::to_string(targets[i].primitive) + " has " +
                                std::to_string(positions.count) + " positions, the scene " + std::to_string(vertices));
        addAttributes(writer, prim, attributes, i);
    }
    // Our data now lives in buffer 0, which a .glb carries as its binary chunk.
    model.buffers[0].uri.clear();
    save(model, path);
}

} // namespace obscura
