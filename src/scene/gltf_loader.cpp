// glTF 2.0 loader (.gltf, .glb) on tinygltf: node hierarchy to instances, triangle primitives to meshes.
#include "obscura/error.h"
#include "obscura/scene_io.h"
#include "scene/gltf_json_check.h"
#include "scene/gltf_read.h"
#include "scene/loader_common.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <numeric>

namespace obscura {

namespace {

// A checked view of one accessor's elements: after construction every element lies inside its buffer.
struct ElementView {
    const unsigned char* base = nullptr;  // null only for no elements
    std::size_t stride = 0;
    std::size_t count = 0;
};

class GltfReader {
public:
    GltfReader(const tinygltf::Model& model, const std::string& path, LoadInfo& info)
        : model_(model), path_(path), info_(info) {}

    Scene read() {
        // Compressed or quantized geometry would read as garbage (or as the zeros of a missing buffer view), and
        // instances placed by EXT_mesh_gpu_instancing would be left out (one copy where the file has many).
        for (const std::string& ext : model_.extensionsRequired)
            if (ext == "KHR_draco_mesh_compression" || ext == "EXT_meshopt_compression" ||
                ext == "KHR_mesh_quantization" || ext == "EXT_mesh_gpu_instancing")
                bad("requires extension " + ext + ", which is not supported");
        for (int r : loader::sceneRoots(model_, path_)) visit(r);
        return std::move(scene_);
    }

private:
    [[noreturn]] void bad(const std::string& problem) const { fail(path_, problem); }

    // Depth-first with an explicit stack, so a deep hierarchy cannot overflow the call stack. glTF nodes
    // form trees; holding a hostile file to that (each node reached once) also stops cycles, which would
    // loop forever, and shared children, which can multiply the work exponentially with depth.
    void visit(int root) {
        struct Entry {
            int node;
            Mat4 parent;
        };
        visited_.resize(model_.nodes.size(), 0);
        std::vector<Entry> stack{{root, Mat4::identity()}};
        while (!stack.empty()) {
            Entry e = stack.back();
            stack.pop_back();
            if (e.node < 0 || std::size_t(e.node) >= model_.nodes.size())
                bad("node " + std::to_string(e.node) + " out of range (" + std::to_string(model_.nodes.size()) +
                    " nodes)");
            const auto n = std::size_t(e.node);
            if (visited_[n])
                bad("node " + std::to_string(n) + " is reached twice (a cycle or a second parent; nodes must form trees)");
            visited_[n] = 1;
            const tinygltf::Node& node = model_.nodes[n];
            Mat4 world = e.parent * localTransform(node, n);
            if (node.mesh >= 0) addInstances(node, n, world);
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world});
        }
    }

    Mat4 localTransform(const tinygltf::Node& node, std::size_t n) const {
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) bad("node " + std::to_string(n) + ": matrix must have 16 numbers");
            float v[16];
            for (int i = 0; i < 16; ++i) v[i] = float(node.matrix[std::size_t(i)]);
            return Mat4::fromColumnMajor(v);
        }
        auto vec = [&](const std::vector<double>& x, std::size_t size, const char* what, std::vector<double> dflt) {
            if (x.empty()) return dflt;
            if (x.size() != size) bad("node " + std::to_string(n) + ": " + what + " must have " + std::to_string(size) + " numbers");
            return x;
        };
        std::vector<double> t = vec(node.translation, 3, "translation", {0, 0, 0});
        std::vector<double> q = vec(node.rotation, 4, "rotation", {0, 0, 0, 1});
        std::vector<double> s = vec(node.scale, 3, "scale", {1, 1, 1});
        // Writers round quaternions to a few digits; renormalize so the rotation does not also scale.
        double ql = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        if (ql > 0) for (double& c : q) c /= ql;
        const double x = q[0], y = q[1], z = q[2], w = q[3];
        const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                                {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                                {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
        Mat4 m;  // T * R * S
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) m.m[i][j] = float(r[i][j] * s[std::size_t(j)]);
            m.m[i][3] = float(t[std::size_t(i)]);
        }
        return m;
    }

    void addInstances(const tinygltf::Node& node, std::size_t n, const Mat4& world) {
        if (std::size_t(node.mesh) >= model_.meshes.size())
            bad("node " + std::to_string(n) + ": mesh " + std::to_string(node.mesh) + " out of range (" +
                std::to_string(model_.meshes.size()) + " meshes)");
        const tinygltf::Mesh& mesh = model_.meshes[std::size_t(node.mesh)];
        const std::string name = node.name.empty() ? "node" + std::to_string(n) : node.name;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            int index = meshFor(node.mesh, p);
            if (index >= 0) scene_.instances.push_back(Instance{std::uint32_t(index), world, name});
        }
    }

    // One Mesh per (mesh, primitive), made on first use and shared by every node that uses it.
    int meshFor(int meshIndex, std::size_t p) {
        auto key = std::make_pair(meshIndex, p);
        if (auto it = made_.find(key); it != made_.end()) return it->second;
        const tinygltf::Mesh& src = model_.meshes[std::size_t(meshIndex)];
        const tinygltf::Primitive& prim = src.primitives[p];
        int index = -1;
        if (prim.mode != TINYGLTF_MODE_TRIANGLES) {
            ++info_.skippedPrimitives;
        } else {
            std::string where = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(p);
            Mesh m = readPrimitive(prim, where);
            m.name = src.name.empty() ? std::string("mesh").append(std::to_string(meshIndex)) : src.name;
            if (src.primitives.size() > 1) m.name.append("#").append(std::to_string(p));
            index = int(scene_.meshes.size());
            scene_.meshes.push_back(std::move(m));
        }
        made_[key] = index;
        return index;
    }

    Mesh readPrimitive(const tinygltf::Primitive& prim, const std::string& where) {
        Mesh m;
        auto pos = prim.attributes.find("POSITION");
        if (pos == prim.attributes.end()) bad(where + " has no POSITION");
        m.positions = readVec3(pos->second, "POSITION");
        if (auto nrm = prim.attributes.find("NORMAL"); nrm != prim.attributes.end()) {
            m.normals = readVec3(nrm->second, "NORMAL");
            if (m.normals.size() != m.positions.size())
                bad(where + " has " + std::to_string(m.normals.size()) + " normals for " +
                    std::to_string(m.positions.size()) + " positions");
            // Files store unit normals to a few digits. Non-finite ones stay, for sanitizeScene to report.
            for (Vec3& n : m.normals)
                if (isFinite(n)) n = normalize(n);
        }
        if (prim.indices >= 0) {
            m.indices = readIndices(prim.indices);
        } else {
            m.indices.resize(m.positions.size());
            std::iota(m.indices.begin(), m.indices.end(), 0u);
        }
        if (m.indices.size() % 3 != 0)
            bad(where + " has " + std::to_string(m.indices.size()) + " indices, not a multiple of 3");
        if (prim.material >= 0) {
            if (std::size_t(prim.material) >= model_.materials.size())
                bad(where + ": material " + std::to_string(prim.material) + " out of range (" +
                    std::to_string(model_.materials.size()) + " materials)");
            const std::vector<double>& c = model_.materials[std::size_t(prim.material)].pbrMetallicRoughness.baseColorFactor;
            if (c.size() >= 3) m.baseColor = {float(c[0]), float(c[1]), float(c[2])};
        }
        return m;
    }

    const tinygltf::Accessor& accessor(int index, const char* role) const {
        if (index < 0 || std::size_t(index) >= model_.accessors.size())
            bad(std::string(role) + " accessor " + std::to_string(index) + " out of range (" +
                std::to_string(model_.accessors.size()) + " accessors)");
        return model_.accessors[std::size_t(index)];
    }

    // Every byte the view can reach is checked here, once, against the buffer view and the buffer.
    ElementView view(int index, const tinygltf::Accessor& acc, std::size_t elementSize, const char* role) const {
        const std::string name = std::string(role) + " accessor " + std::to_string(index);
        if (acc.sparse.isSparse) bad(name + ": sparse accessors are not supported");
        ElementView v;
        v.count = acc.count;
        v.stride = elementSize;
        // No buffer view: every element is zero (glTF 3.6.2.4, sparse accessors aside, which are refused), no
        // geometry at all, and a 200-byte file could state billions of them.
        if (acc.bufferView < 0) bad(name + " has no buffer view (its " + std::to_string(acc.count) + " elements would all be 0)");
        if (std::size_t(acc.bufferView) >= model_.bufferViews.size())
            bad(name + ": buffer view " + std::to_string(acc.bufferView) + " out of range (" +
                std::to_string(model_.bufferViews.size()) + " buffer views)");
        const tinygltf::BufferView& bv = model_.bufferViews[std::size_t(acc.bufferView)];
        if (bv.buffer < 0 || std::size_t(bv.buffer) >= model_.buffers.size())
            bad(name + ": buffer " + std::to_string(bv.buffer) + " out of range (" +
                std::to_string(model_.buffers.size()) + " buffers)");
        const std::vector<unsigned char>& data = model_.buffers[std::size_t(bv.buffer)].data;
        if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
            bad(name + ": buffer view " + std::to_string(acc.bufferView) + " reads past the end of its buffer (" +
                std::to_string(bv.byteOffset) + " + " + std::to_string(bv.byteLength) + " bytes, buffer has " +
                std::to_string(data.size()) + ")");
        if (bv.byteStride != 0) {
            if (bv.byteStride < elementSize)
                bad(name + ": byteStride " + std::to_string(bv.byteStride) + " is smaller than an element (" +
                    std::to_string(elementSize) + " bytes)");
            v.stride = bv.byteStride;
        }
        if (v.count == 0) return v;
        // (count - 1) * stride + elementSize + byteOffset <= byteLength, written so nothing overflows.
        const std::size_t avail = bv.byteLength;
        bool fits = acc.byteOffset <= avail && elementSize <= avail - acc.byteOffset &&
                    (v.count - 1) <= (avail - acc.byteOffset - elementSize) / v.stride;
        if (!fits)
            bad(name + " reads past the end of its buffer view (" + std::to_string(v.count) + " elements of " +
                std::to_string(elementSize) + " bytes, stride " + std::to_string(v.stride) + ", offset " +
                std::to_string(acc.byteOffset) + "; the view has " + std::to_string(avail) + " bytes)");
        v.base = data.data() + bv.byteOffset + acc.byteOffset;
        return v;
    }

    std::vector<Vec3> readVec3(int index, const char* role) const {
        const tinygltf::Accessor& acc = accessor(index, role);
        if (acc.type != TINYGLTF_TYPE_VEC3 || acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            bad(std::string(role) + " accessor " + std::to_string(index) + " must be float VEC3");
        ElementView v = view(index, acc, 3 * sizeof(float), role);
        std::vector<Vec3> out(v.count);
        if (!v.base) return out;
        for (std::size_t i = 0; i < v.count; ++i) {
            float f[3];
            std::memcpy(f, v.base + i * v.stride, sizeof f);  // buffers need not be float-aligned
            out[i] = {f[0], f[1], f[2]};
        }
        return out;
    }

    std::vector<std::uint32_t> readIndices(int index) const {
        const tinygltf::Accessor& acc = accessor(index, "index");
        std::size_t size = 0;
        switch (acc.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
        default: bad("index accessor " + std::to_string(index) + " must be unsigned byte, short or int");
        }
        if (acc.type != TINYGLTF_TYPE_SCALAR) bad("index accessor " + std::to_string(index) + " must be SCALAR");
        ElementView v = view(index, acc, size, "index");
        std::vector<std::uint32_t> out(v.count, 0);
        if (!v.base) return out;
        for (std::size_t i = 0; i < v.count; ++i) {
            const unsigned char* p = v.base + i * v.stride;
            if (size == 1) {
                out[i] = p[0];
            } else if (size == 2) {
                std::uint16_t x;
                std::memcpy(&x, p, 2);
                out[i] = x;
            } else {
                std::memcpy(&out[i], p, 4);
            }
        }
        return out;
    }

    const tinygltf::Model& model_;
    const std::string& path_;
    LoadInfo& info_;
    Scene scene_;
    std::map<std::pair<int, std::size_t>, int> made_;  // (mesh, primitive) -> Scene mesh, -1 if skipped
    std::vector<char> visited_;                        // per node, over all roots
};

} // namespace

Scene loadGltf(const std::string& path, LoadInfo* info) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    tinygltf::Model model;
    loader::readTinyGltf(path, ext == ".glb", model);
    // tinygltf keeps the default of a property of the wrong type (an offset of 1e10 read as 0) unsaid.
    loader::checkGltfJson(path, ext == ".glb");

    loader::InfoSink out(info);
    Scene scene = GltfReader(model, path, *out).read();
    for (Mesh& m : scene.meshes) computeSmoothNormals(m);
    return loader::finishLoad(std::move(scene), path, out);
}

} // namespace obscura
