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
        // Said here, with why: sanitizeScene's "no triangles" named no cause for a file of points or lines.
        if (scene_.instances.empty() && info_.skippedPrimitives > 0)
            bad("no triangles: its " + std::to_string(info_.skippedPrimitives) + " primitive" +
                (info_.skippedPrimitives == 1 ? " is" : "s are") + " points or lines (modes 0-3), which are not read");
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
            if (node.mesh >= 0) {
                checkPlacement(node, n);
                addInstances(node, n, world);
            }
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world});
        }
    }

    static std::string nodeName(const tinygltf::Node& node, std::size_t n) {
        return "node " + std::to_string(n) + (node.name.empty() ? "" : " '" + node.name + "'");
    }

    // What would place a mesh elsewhere than its node's transform, or move its vertices, is refused rather than
    // read wrong: the geometry baked and traced must be the geometry a viewer draws.
    void checkPlacement(const tinygltf::Node& node, std::size_t n) const {
        // A skinned mesh is placed by its joints; the node's own transform is ignored (glTF 3.7.3.3). Baked at
        // the node's transform, a cube skinned in place but under a node 50 m up read A = 1 in the air.
        if (node.skin >= 0)
            bad(nodeName(node, n) + " has a skinned mesh (skin " + std::to_string(node.skin) +
                "), placed by its joints, which are not read; remove the skin to bake the mesh where its node puts it");
        // Instanced by the extension, one node draws many copies; read without it, one. Files list it in
        // extensionsUsed only, not always in extensionsRequired.
        if (node.extensions.count("EXT_mesh_gpu_instancing"))
            bad(nodeName(node, n) + " uses EXT_mesh_gpu_instancing, which is not supported");
        if (std::size_t(node.mesh) >= model_.meshes.size()) return;  // addInstances names it
        const tinygltf::Mesh& mesh = model_.meshes[std::size_t(node.mesh)];
        // The default pose moves the vertices by the weighted morph targets (glTF 3.7.2.2); the base shape alone is
        // right only where every weight is 0.
        const std::vector<double>& weights = node.weights.empty() ? mesh.weights : node.weights;
        bool morphed = false;
        for (const tinygltf::Primitive& prim : mesh.primitives) morphed = morphed || !prim.targets.empty();
        for (double w : weights)
            if (morphed && w != 0.0)
                bad(nodeName(node, n) + ": mesh " + std::to_string(node.mesh) + " has morph target weight " +
                    numberText(w) + "; morph targets are not applied, so only weights of 0 can be read");
    }

    Mat4 localTransform(const tinygltf::Node& node, std::size_t n) const {
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) bad("node " + std::to_string(n) + ": matrix must have 16 numbers");
            // An affine matrix (glTF 5.25: it must decompose to TRS). A last row other than 0, 0, 0, 1 divided the
            // sampled points by w while the ray tracer, which takes three rows, did not.
            const std::vector<double>& mx = node.matrix;
            if (mx[3] != 0.0 || mx[7] != 0.0 || mx[11] != 0.0 || mx[15] != 1.0)
                bad(nodeName(node, n) + ": matrix's last row is (" + numberText(mx[3]) + ", " +
                    numberText(mx[7]) + ", " + numberText(mx[11]) + ", " + numberText(mx[15]) +
                    "), not (0, 0, 0, 1)");
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
        std::string where = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(p);
        if (prim.mode < 0 || prim.mode > 6) bad(where + ": mode " + std::to_string(prim.mode) + " is not a glTF mode (0-6)");
        if (!loader::isTriangleMode(prim.mode)) {
            ++info_.skippedPrimitives;
        } else {
            Mesh m = readPrimitive(prim, where);
            if (prim.attributes.count("COLOR_0")) ++info_.colouredPrimitives;
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
        if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP || prim.mode == TINYGLTF_MODE_TRIANGLE_FAN)
            m.indices = listFromStripOrFan(m.indices, prim.mode == TINYGLTF_MODE_TRIANGLE_FAN);
        else if (m.indices.size() % 3 != 0)
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

    // Triangle i of a strip is (v_i, v_i+1+i%2, v_i+2-i%2), keeping each triangle's winding; of a fan
    // (v_i+1, v_i+2, v_0) (glTF 3.7.2.1). The vertices, and so the bake's per-vertex output, stay the file's.
    static std::vector<std::uint32_t> listFromStripOrFan(const std::vector<std::uint32_t>& v, bool fan) {
        std::vector<std::uint32_t> out;
        for (std::size_t i = 0; i + 2 < v.size(); ++i) {
            if (fan)
                out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
            else
                out.insert(out.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
        }
        return out;
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
        // The schema's minimum: an empty accessor holds no geometry, and the bake's output would repeat it.
        if (v.count == 0) bad(name + " has count 0 (glTF requires at least 1)");
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
