// Baked vertex attributes written into a copy of a glTF 2.0 file (the bake's output for glTF input), by editing
// the file's own JSON. The Khronos glTF 2.0 specification governs the layout: §3.6 buffers, buffer views and
// accessors, §4.4 the binary container. What the bake does not touch stays as the input wrote it: extensions
// and extras on every object, cameras (an infinite perspective has no zfar), samplers, skins, animations,
// images (data URIs included) and the key order. A round trip through tinygltf's model lost each of those.
#include "obscura/gltf_writer.h"

#include "obscura/error.h"
#include "obscura/image_io.h"
#include "scene/gltf_json_check.h"
#include "scene/gltf_output.h"
#include "scene/gltf_read.h"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace obscura {

namespace {

using Json = nlohmann::ordered_json;

constexpr int kFloat = 5126;        // accessor componentType FLOAT
constexpr int kArrayBuffer = 34962;  // bufferView target ARRAY_BUFFER

// RFC 4648 base64, for buffers embedded as data URIs.
std::string base64(const std::vector<unsigned char>& bytes) {
    static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const std::uint32_t v = std::uint32_t(bytes[i]) << 16 | std::uint32_t(bytes[i + 1]) << 8 | bytes[i + 2];
        for (int shift : {18, 12, 6, 0}) out += digits[(v >> shift) & 63];
    }
    if (const std::size_t rest = bytes.size() - i; rest > 0) {
        const std::uint32_t v = std::uint32_t(bytes[i]) << 16 | (rest == 2 ? std::uint32_t(bytes[i + 1]) << 8 : 0);
        out += digits[(v >> 18) & 63];
        out += digits[(v >> 12) & 63];
        out += rest == 2 ? digits[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

// New float accessors at the end of buffer 0, each in a buffer view of its own aligned to 4 bytes.
class JsonBufferWriter {
public:
    JsonBufferWriter(Json& document, std::vector<unsigned char>& buffer) : j_(document), buffer_(buffer) {}

    int addFloats(const float* v, std::size_t count, int components) {
        while (buffer_.size() % 4) buffer_.push_back(0);
        const std::size_t bytes = count * std::size_t(components) * sizeof(float);
        Json view = {{"buffer", 0}, {"byteOffset", buffer_.size()}, {"byteLength", bytes}, {"target", kArrayBuffer}};
        const auto* p = reinterpret_cast<const unsigned char*>(v);
        buffer_.insert(buffer_.end(), p, p + bytes);
        Json& views = j_["bufferViews"];
        views.push_back(std::move(view));
        Json accessor = {{"bufferView", views.size() - 1},
                         {"componentType", kFloat},
                         {"count", count},
                         {"type", components == 3 ? "VEC3" : "SCALAR"}};
        Json& accessors = j_["accessors"];
        accessors.push_back(std::move(accessor));
        return int(accessors.size() - 1);
    }

private:
    Json& j_;
    std::vector<unsigned char>& buffer_;
};

struct Target {
    int node;
    std::size_t primitive;
};

// The loader's order: the default scene's roots (every parentless node without scenes), depth first,
// children in order; per node with a mesh, its triangle primitives. `reached` marks the nodes visited.
// The loader checks only the nodes it visits: a node outside the tree may name any child. The file is read again
// here, after the bake: one changed meanwhile must fail as the loader would, not index past its nodes or loop.
std::vector<Target> loaderOrder(const tinygltf::Model& model, const std::string& path, std::vector<char>& reached) {
    const std::vector<int> roots = loader::sceneRoots(model, path);
    reached.assign(model.nodes.size(), 0);
    std::vector<Target> targets;
    for (int r : roots) {
        std::vector<int> stack{r};
        while (!stack.empty()) {
            const int n = stack.back();
            stack.pop_back();
            if (n < 0 || std::size_t(n) >= model.nodes.size() || reached[std::size_t(n)])
                fail(path, "changed while it was baked (node " + std::to_string(n) + " is out of range or reached twice)");
            reached[std::size_t(n)] = 1;
            const tinygltf::Node& node = model.nodes[std::size_t(n)];
            if (node.mesh >= 0 && std::size_t(node.mesh) >= model.meshes.size())
                fail(path, "changed while it was baked (node " + std::to_string(n) + " names mesh " +
                               std::to_string(node.mesh) + ", out of range)");
            if (node.mesh >= 0)
                for (std::size_t p = 0; p < model.meshes[std::size_t(node.mesh)].primitives.size(); ++p)
                    if (loader::isTriangleMode(model.meshes[std::size_t(node.mesh)].primitives[p].mode))
                        targets.push_back({n, p});
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back(*c);
        }
    }
    return targets;
}

void appendLittleEndian32(std::string& out, std::uint32_t v) {
    for (int shift = 0; shift < 32; shift += 8) out += char((v >> shift) & 0xff);
}

} // namespace

void writeGltfWithAttributes(const std::string& inputPath, const Scene& scene, const std::string& path,
                             const InstanceAttributes& attributes) {
    const bool binary = gltfOutputIsBinary(path);
    checkInstanceAttributes(scene, &attributes, path);
    // tinygltf reads the buffers (data URIs, files beside the input, a .glb's binary chunk) and gives the
    // structure the order is found in; the JSON is what is edited and written.
    tinygltf::Model model;
    const bool inputBinary = fileExtension(inputPath) == ".glb";
    loader::readTinyGltf(inputPath, inputBinary, model);
    Json j = Json::parse(loader::readGltfJsonText(inputPath, inputBinary), nullptr, false);
    if (j.is_discarded() || !j.is_object()) fail(inputPath, "not valid JSON");

    std::vector<char> reached;
    const std::vector<Target> targets = loaderOrder(model, inputPath, reached);
    if (targets.size() != scene.instances.size())
        fail(inputPath, "has " + std::to_string(targets.size()) + " triangle primitives placed by nodes, the scene " +
                            std::to_string(scene.instances.size()) + " instances (was it loaded from this file?)");

    std::vector<std::vector<unsigned char>> buffers;
    for (tinygltf::Buffer& b : model.buffers) buffers.push_back(std::move(b.data));
    if (buffers.empty()) {
        buffers.emplace_back();
        j["buffers"] = Json::array({Json::object()});
    }
    JsonBufferWriter writer(j, buffers[0]);
    std::map<int, int> meshOfNode;  // node -> the mesh it writes into (its own clone after the first user)
    std::map<int, int> firstUser;   // mesh -> the node that keeps the original
    // A mesh that a node outside the baked tree also uses (another scene's) stays as it was, for that node.
    for (std::size_t n = 0; n < model.nodes.size(); ++n)
        if (!reached[n] && model.nodes[n].mesh >= 0) firstUser.try_emplace(model.nodes[n].mesh, int(n));
    Json& nodes = j["nodes"];
    Json& meshes = j["meshes"];
    for (std::size_t i = 0; i < targets.size(); ++i) {
        const int n = targets[i].node;
        const tinygltf::Node& node = model.nodes[std::size_t(n)];
        if (!meshOfNode.count(n)) {
            if (firstUser.try_emplace(node.mesh, n).second) {
                meshOfNode[n] = node.mesh;
            } else {
                Json clone = meshes[std::size_t(node.mesh)];
                if (clone.contains("name") && clone["name"].is_string() && !clone["name"].get<std::string>().empty())
                    clone["name"] = clone["name"].get<std::string>() + " (" +
                                    (node.name.empty() ? "node " + std::to_string(n) : node.name) + ")";
                meshes.push_back(std::move(clone));
                meshOfNode[n] = int(meshes.size() - 1);
                nodes[std::size_t(n)]["mesh"] = meshOfNode[n];
            }
        }
        const tinygltf::Primitive& source = model.meshes[std::size_t(node.mesh)].primitives[targets[i].primitive];
        const std::size_t first = attributes.first[i], vertices = attributes.first[i + 1] - first;
        const auto position = source.attributes.find("POSITION");
        if (position == source.attributes.end() || position->second < 0 ||
            std::size_t(position->second) >= model.accessors.size())
            fail(inputPath, "changed while it was baked (node " + std::to_string(n) + " primitive " +
                                std::to_string(targets[i].primitive) + " has no POSITION accessor)");
        const tinygltf::Accessor& positions = model.accessors[std::size_t(position->second)];
        if (positions.count != vertices)
            fail(inputPath, "node " + std::to_string(n) + " primitive " + std::to_string(targets[i].primitive) + " has " +
                                std::to_string(positions.count) + " positions, the scene " + std::to_string(vertices));
        Json& written = meshes[std::size_t(meshOfNode[n])]["primitives"][targets[i].primitive]["attributes"];
        // An earlier bake's channels go: a one-distance bake writes no _AO_LONG, and the old one would stay.
        for (const char* old : {"_AO_SHORT", "_AO_LONG"}) written.erase(old);
        for (const VertexAttribute& a : attributes.attributes)
            written[a.name] =
                writer.addFloats(a.data.data() + first * std::size_t(a.components), vertices, a.components);
    }

    // Every buffer goes inside the output: a .glb carries buffer 0 as its binary chunk and the others as data
    // URIs, a .gltf all as data URIs, so the file is one piece and the rename is the whole write.
    Json& bufferList = j["buffers"];
    for (std::size_t b = 0; b < buffers.size(); ++b) {
        Json& entry = bufferList[b];
        entry["byteLength"] = buffers[b].size();
        if (binary && b == 0)
            entry.erase("uri");
        else
            entry["uri"] = "data:application/octet-stream;base64," + base64(buffers[b]);
    }
    writeGltfFile(path, [&](std::ostream& out) {
        if (!binary) {
            out << j.dump(2) << '\n';
            return;
        }
        // §4.4: a 12-byte header, then the JSON chunk padded with spaces and the BIN chunk padded with zeros, each
        // to 4 bytes; lengths are 32-bit.
        std::string text = j.dump();
        while (text.size() % 4) text += ' ';
        std::vector<unsigned char>& bin = buffers[0];
        while (bin.size() % 4) bin.push_back(0);
        const std::uint64_t total = 12 + 8 + std::uint64_t(text.size()) + (bin.empty() ? 0 : 8 + std::uint64_t(bin.size()));
        if (total > 0xffffffffu)
            fail(path, "would be " + std::to_string(total) + " bytes, past the 4 GiB a .glb can state; write .gltf");
        std::string head = "glTF";
        appendLittleEndian32(head, 2);
        appendLittleEndian32(head, std::uint32_t(total));
        appendLittleEndian32(head, std::uint32_t(text.size()));
        head += "JSON";
        out << head << text;
        if (bin.empty()) return;
        std::string binHead;
        appendLittleEndian32(binHead, std::uint32_t(bin.size()));
        binHead += std::string("BIN\0", 4);
        out << binHead;
        out.write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
    });
}

} // namespace obscura
