// glTF 2.0 writer on tinygltf for scenes written from scratch (generated levels, baked OBJ/PLY), and what both
// glTF writers share (gltf_output.h). A loaded file with attributes added is gltf_attribute_writer.cpp's.
#include "obscura/gltf_writer.h"

#include "obscura/error.h"
#include "obscura/image_io.h"
#include "scene/gltf_output.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>

namespace obscura {

namespace {

// Writes no image files (a scene from scratch has none).
bool keepImage(const std::string*, const std::string*, const tinygltf::Image*, bool, std::string*, void*) { return false; }

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
    const bool binary = gltfOutputIsBinary(path);
    tinygltf::TinyGLTF gltf;
    gltf.SetImageWriter(keepImage, nullptr);
    writeGltfFile(path, [&](std::ostream& out) {
        if (!gltf.WriteGltfSceneToStream(&model, out, !binary, binary)) fail(path, "cannot write the glTF file");
        // A failed stream's tellp is -1, which read as 2^64 - 1 bytes "past the 4 GiB" on a full disk.
        if (!out) fail(path, "write failed (disk full?)");
        // A .glb states its length in 32 bits, which tinygltf truncates without a word; the temporary goes.
        if (binary && std::uint64_t(out.tellp()) > 0xffffffffu)
            fail(path, "would be " + std::to_string(std::uint64_t(out.tellp())) +
                           " bytes, past the 4 GiB a .glb can state; write .gltf");
    });
}

} // namespace

bool gltfOutputIsBinary(const std::string& path) {
    const std::string ext = fileExtension(path);
    if (ext != ".glb" && ext != ".gltf") fail(path, "unsupported glTF extension (expected .gltf or .glb)");
    return ext == ".glb";
}

void checkInstanceAttributes(const Scene& scene, const InstanceAttributes* a, const std::string& path) {
    if (!a) return;
    if (a->first.size() != scene.instances.size() + 1) fail(path, "attribute offsets do not match the scene's instances");
    for (std::size_t i = 0; i < scene.instances.size(); ++i)
        if (a->first[i + 1] - a->first[i] != scene.meshes[scene.instances[i].mesh].positions.size())
            fail(path, "attribute count of instance " + std::to_string(i) + " does not match its mesh");
    for (const VertexAttribute& attr : a->attributes)
        if (attr.data.size() != a->first.back() * std::size_t(attr.components))
            fail(path, "attribute " + attr.name + " has the wrong size");
}

void writeGltfFile(const std::string& path, const std::function<void(std::ostream&)>& write) {
    writeAtomically(path, [&](const std::string& temp) {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) fail(path, "cannot write the glTF file");
        write(out);
        out.close();
        if (out.fail()) fail(path, "write failed (disk full?)");
    });
}

void writeGltf(const Scene& scene, const std::string& path, const InstanceAttributes* attributes) {
    checkInstanceAttributes(scene, attributes, path);
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
        Geometry g{-1, -1, -1, -1};
        // A mesh whose every triangle was dropped: glTF has no accessor of count 0, and it would show nothing.
        if (mesh.indices.empty()) {
            geometry.push_back(g);
            continue;
        }
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
        if (geometry[inst.mesh].positions < 0) continue;
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

} // namespace obscura
