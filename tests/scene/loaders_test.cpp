// Tests for the glTF, OBJ and PLY loaders and loadScene on the hand-made fixtures in tests/data.
#include "obscura/error.h"
#include "obscura/scene_io.h"
#include "scene/gltf_json_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace obscura {
namespace {

namespace fs = std::filesystem;

std::string data(const std::string& name) { return std::string(OBSCURA_TEST_DATA) + "/" + name; }

void expectNear(Vec3 a, Vec3 b, float tol = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

Vec3 world(const Scene& s, std::size_t instance, std::size_t vertex) {
    const Instance& inst = s.instances.at(instance);
    return transformPoint(inst.worldFromObject, s.meshes.at(inst.mesh).positions.at(vertex));
}

std::string loadError(const std::string& path) {
    try {
        loadScene(path);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

// The message must name the file and say what is wrong, on one line.
void expectLoadError(const std::string& file, const std::string& problem) {
    SCOPED_TRACE(file);
    EXPECT_THROW(loadScene(data(file)), Error);
    std::string msg = loadError(data(file));
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
    EXPECT_NE(msg.find(problem), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

// A directory of its own under the test temp dir, removed at the end.
class TempDir {
public:
    TempDir() : path_(fs::path(testing::TempDir()) / ("obscura_loaders_" + std::to_string(::getpid()))) {
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    std::string path() const { return path_.string(); }
    std::string write(const std::string& name, const std::string& bytes) const {
        std::string p = (path_ / name).string();
        std::ofstream(p, std::ios::binary) << bytes;
        return p;
    }

private:
    fs::path path_;
};

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// ---- glTF -------------------------------------------------------------------------------------------

TEST(LoaderGltf, QuadInstancesShareOneMesh) {
    LoadInfo info;
    Scene s = loadScene(data("quad.gltf"), &info);
    // The points primitive is skipped; "scene": 1 picks nodes left and right, not other_scene.
    EXPECT_EQ(info.skippedPrimitives, 1u);
    EXPECT_EQ(info.droppedTriangles, 0u);
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.instances.size(), 2u);
    EXPECT_EQ(s.instances[0].mesh, 0u);
    EXPECT_EQ(s.instances[1].mesh, 0u);
    EXPECT_EQ(s.instances[0].name, "left");
    EXPECT_EQ(s.instances[1].name, "right");
    const Mesh& m = s.meshes[0];
    EXPECT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.triangleCount(), 2u);
    EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(m.baseColor, (Vec3{0.25f, 0.5f, 0.75f}));
    ASSERT_EQ(m.normals.size(), 4u);
    for (Vec3 n : m.normals) EXPECT_EQ(n, (Vec3{0, 0, 1}));  // computed: the file has none
    expectNear(world(s, 0, 2), {-1, 1, 0});
    expectNear(world(s, 1, 2), {4, 1, 1});
    EXPECT_EQ(s.triangleCount(), 4u);
}

TEST(LoaderGltf, GlbWithInterleavedNormalsAndByteIndices) {
    Scene s = loadScene(data("quad.glb"));
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.instances.size(), 1u);
    const Mesh& m = s.meshes[0];
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.positions[2], (Vec3{1, 1, 0}));
    EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    for (Vec3 n : m.normals) EXPECT_EQ(n, (Vec3{0, 0, 1}));  // stored as (0,0,2), normalized
    EXPECT_EQ(m.baseColor, (Vec3{1, 0, 0.5f}));
}

// parent = T(0,0,1) R(z, 90 deg) S(2), child = T(1,0,0): a local x step of the child's triangle becomes
// 2 world units along +y. No "scenes": the roots (parent, matrix) are found by parentage.
TEST(LoaderGltf, HierarchyComposesParentAndChildAndMatrix) {
    Scene s = loadScene(data("hierarchy.gltf"));
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.instances.size(), 2u);
    EXPECT_EQ(s.instances[0].name, "child");
    expectNear(world(s, 0, 0), {0, 2, 1});
    expectNear(world(s, 0, 1), {0, 4, 1});
    expectNear(world(s, 0, 2), {-2, 2, 1});
    // matrix (column-major): scale x by 3, translate (0,5,0)
    EXPECT_EQ(s.instances[1].name, "matrix");
    expectNear(world(s, 1, 0), {0, 5, 0});
    expectNear(world(s, 1, 1), {3, 5, 0});
    expectNear(world(s, 1, 2), {0, 6, 0});
    Bounds b = s.bounds();
    expectNear(b.lo, {-2, 2, 0});
    expectNear(b.hi, {3, 6, 1});
}

TEST(LoaderGltf, BadJson) { expectLoadError("bad_json.gltf", "parse error"); }
TEST(LoaderGltf, TruncatedGlb) { expectLoadError("truncated.glb", "Invalid glTF binary"); }
TEST(LoaderGltf, AccessorOutOfRange) {
    expectLoadError("accessor_out_of_range.gltf", "POSITION accessor 0 reads past the end of its buffer view");
}
TEST(LoaderGltf, IndexOutOfRange) {
    EXPECT_EQ(loadError(data("bad_index.gltf")), data("bad_index.gltf") + ": mesh 'quad#0': index 7 out of range (4 vertices)");
}

// Hand-edited variants of a one-triangle file, each lying in one way that a careless reader would follow
// into a crash, a hang or a read past the buffer.
TEST(LoaderGltf, LyingFilesGiveErrors) {
    struct Case {
        std::string scenes, nodes, accessor, view, expected;
    };
    const std::string scenes = R"("scenes": [{"nodes": [0]}],)", node = R"({"mesh": 0})";
    const std::string acc = R"({"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3")";
    const std::string view = R"({"buffer": 0, "byteLength": 36})";
    const Case cases[] = {
        {scenes, R"({"mesh": 0, "children": [1]}, {"children": [0]})", acc + "}", view, "node 0 is reached twice"},
        {scenes, R"({"mesh": 0, "children": [1, 1]}, {"mesh": 0})", acc + "}", view, "node 1 is reached twice"},
        {scenes, R"({"mesh": 0, "children": [5]})", acc + "}", view, "node 5 out of range (1 nodes)"},
        {scenes, R"({"mesh": 3})", acc + "}", view, "mesh 3 out of range (1 meshes)"},
        {"", node, acc + R"(, "count": 4611686018427387904})", view, "reads past the end of its buffer view"},
        {"", node, acc + R"(, "byteOffset": 9223372036854775808})", view, "reads past the end of its buffer view"},
        {"", node, acc + "}", R"({"buffer": 0, "byteLength": 36, "byteStride": 4})", "byteStride 4 is smaller"},
        {"", node, acc + "}", R"({"buffer": 0, "byteOffset": 12, "byteLength": 36})", "past the end of its buffer"},
        {"", node, R"({"bufferView": 0, "componentType": 5123, "count": 3, "type": "VEC3"})", view,
         "must be float VEC3"},
        {R"("extensionsUsed": ["KHR_draco_mesh_compression"], "extensionsRequired": ["KHR_draco_mesh_compression"],)",
         node, acc + "}", view, "requires extension KHR_draco_mesh_compression, which is not supported"},
        {R"("extensionsUsed": ["EXT_mesh_gpu_instancing"], "extensionsRequired": ["EXT_mesh_gpu_instancing"],)",
         node, acc + "}", view, "requires extension EXT_mesh_gpu_instancing, which is not supported"},
        // Values of the wrong type, which tinygltf replaced by the default (an offset of 0, no translation).
        {"", node, acc + "}", R"({"buffer": 0, "byteOffset": 1e10, "byteLength": 36})",
         "bufferViews[0].byteOffset must be a non-negative integer, got 10000000000.0"},
        {"", node, acc + R"(, "byteOffset": 0.5})", view, "accessors[0].byteOffset must be a non-negative integer, got 0.5"},
        {"", node, R"({"bufferView": 0, "componentType": 5126, "count": "3", "type": "VEC3"})", view,
         "'count' property is not a positive integer"},  // a required property: tinygltf's own check
        {"", R"({"mesh": 0, "translation": "abc"})", acc + "}", view,
         R"(nodes[0].translation must be an array of 3 numbers, got "abc")"},
        {"", R"({"mesh": 0, "rotation": [0, 0, 0, "1"]})", acc + "}", view, "nodes[0].rotation must be an array of 4 numbers"},
        {"", R"({"mesh": -1})", acc + "}", view, "nodes[0].mesh must be a non-negative integer, got -1"},
        {R"("scenes": [{"nodes": [0.0]}],)", node, acc + "}", view, "scenes[0].nodes must hold non-negative integers"},
        // A colour of the wrong type was read as the default grey; a "scene" past the scenes as scene 0.
        {R"("materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5]}}],)", node, acc + "}", view,
         "materials[0].pbrMetallicRoughness.baseColorFactor must be an array of 4 numbers, got [0.5]"},
        {R"("materials": [{"pbrMetallicRoughness": "red"}],)", node, acc + "}", view,
         "materials[0].pbrMetallicRoughness must be an object"},
        {R"("scene": 3, "scenes": [{"nodes": [0]}],)", node, acc + "}", view, R"("scene": 3 is out of range (1 scenes))"},
        // No buffer view: all zeros, and a 200-byte file once allocated 1.2 GB for these (count 2^64 - 1 escaped
        // as "internal: cannot create std::vector larger than max_size()").
        {"", node, R"({"componentType": 5126, "count": 30000000, "type": "VEC3"})", view,
         "POSITION accessor 0 has no buffer view (its 30000000 elements would all be 0)"},
        {"", node, R"({"componentType": 5126, "count": 18446744073709551615, "type": "VEC3"})", view,
         "POSITION accessor 0 has no buffer view"},
        // Placed or shaped otherwise than the node's transform says: read as it was, the bake was wrong silently.
        {R"("skins": [{"joints": [0]}],)", R"({"mesh": 0, "skin": 0, "name": "hero"})", acc + "}", view,
         "node 0 'hero' has a skinned mesh (skin 0), placed by its joints, which are not read"},
        {R"("extensionsUsed": ["EXT_mesh_gpu_instancing"],)",
         R"({"mesh": 0, "extensions": {"EXT_mesh_gpu_instancing": {"attributes": {}}}})", acc + "}", view,
         "node 0 uses EXT_mesh_gpu_instancing, which is not supported"},
        {"", R"({"mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 2]})", acc + "}", view,
         "node 0: matrix's last row is (0, 0, 0, 2), not (0, 0, 0, 1)"},
        {"", node, acc + R"(, "count": 0})", view, "POSITION accessor 0 has count 0 (glTF requires at least 1)"},
    };
    TempDir dir;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.expected);
        std::string json = R"({"asset": {"version": "2.0"}, )" + c.scenes + R"( "nodes": [)" + c.nodes +
                           R"(], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "accessors": [)" +
                           c.accessor + R"(], "bufferViews": [)" + c.view +
                           R"(], "buffers": [{"byteLength": 36, "uri": )"
                           R"("data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
        std::string path = dir.write("lying.gltf", json);
        std::string msg = loadError(path);
        EXPECT_NE(msg.find(path + ": "), std::string::npos) << msg;
        EXPECT_NE(msg.find(c.expected), std::string::npos) << msg;
    }
}

// Meshes whose primitives differ from the one-triangle template: positions from a .bin beside the file.
std::string primitivesGltf(const TempDir& dir, const std::string& meshes, const std::string& nodes = R"({"mesh": 0})") {
    // A unit square, corners in strip order (0,0), (1,0), (0,1), (1,1), then in fan order (0,0), (1,0), (1,1), (0,1).
    const float xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    dir.write("square.bin", std::string(reinterpret_cast<const char*>(xyz), sizeof xyz));
    return dir.write("primitives.gltf",
                     R"({"asset": {"version": "2.0"}, "nodes": [)" + nodes + R"(], "meshes": )" + meshes +
                         R"(, "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},)"
                         R"({"bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3"}],)"
                         R"( "bufferViews": [{"buffer": 0, "byteLength": 96}], "buffers": [{"byteLength": 96, "uri": "square.bin"}]})");
}

// A data: URI that does not decode to its byteLength was quoted whole in the message, one line of 1.4 MB for a
// 1 MB buffer. The contents are cut; the message still names the file and the buffer.
TEST(LoaderGltf, AnUndecodableDataUriIsNotQuotedWhole) {
    TempDir dir;
    const std::string uri = "data:application/octet-stream;base64," + std::string(40000, 'A');
    const std::string path = dir.write(
        "long.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 30004, "uri": ")" + uri + R"("}]})");
    const std::string msg = loadError(path);
    EXPECT_NE(msg.find(path + ": "), std::string::npos) << msg.substr(0, 400);
    EXPECT_NE(msg.find("characters)"), std::string::npos) << msg.substr(0, 400);
    EXPECT_LT(msg.size(), 400u) << msg.substr(0, 400);
}

// Strips and fans are triangles too (glTF 3.7.2.1): read in the file's vertex order with every triangle's
// winding kept, so each faces +z as the square does. They were skipped, and occluded nothing.
TEST(LoaderGltf, StripsAndFansAreReadAsTriangles) {
    TempDir dir;
    for (const auto& [mode, accessor] : {std::pair{5, 0}, std::pair{6, 1}}) {
        SCOPED_TRACE(mode);
        LoadInfo info;
        const Scene s = loadScene(primitivesGltf(dir, R"([{"primitives": [{"attributes": {"POSITION": )" +
                                                          std::to_string(accessor) + R"(}, "mode": )" +
                                                          std::to_string(mode) + "}]}]"),
                                  &info);
        EXPECT_EQ(info.skippedPrimitives, 0u);
        ASSERT_EQ(s.meshes.size(), 1u);
        const Mesh& m = s.meshes[0];
        EXPECT_EQ(m.positions.size(), 4u);
        ASSERT_EQ(m.indices.size(), 6u);
        for (std::size_t t = 0; t < 6; t += 3) {
            const Vec3 n = cross(m.positions[m.indices[t + 1]] - m.positions[m.indices[t]],
                                 m.positions[m.indices[t + 2]] - m.positions[m.indices[t]]);
            EXPECT_NEAR(n.z, 1.0f, 1e-6f) << t;  // each half of the unit square, facing +z
        }
        for (Vec3 n : m.normals) expectNear(n, {0, 0, 1});
    }
}

// Morph targets are not applied: weights of 0 (the base shape) load; any other weight, on the mesh or on the node
// that overrides it, is refused. Points alone are "no triangles", said with why.
TEST(LoaderGltf, MorphWeightsModesAndPointsAreChecked) {
    TempDir dir;
    const std::string morphed = R"([{"primitives": [{"attributes": {"POSITION": 0}, "mode": 5, "targets": [{"POSITION": 1}]}], )";
    EXPECT_NO_THROW(loadScene(primitivesGltf(dir, morphed + R"("weights": [0]}])")));
    std::string msg = loadError(primitivesGltf(dir, morphed + R"("weights": [1]}])"));
    EXPECT_NE(msg.find("node 0: mesh 0 has morph target weight 1; morph targets are not applied"), std::string::npos) << msg;
    msg = loadError(primitivesGltf(dir, morphed + R"("weights": [0]}])", R"({"mesh": 0, "weights": [0.5]})"));
    EXPECT_NE(msg.find("has morph target weight 0.5"), std::string::npos) << msg;
    msg = loadError(primitivesGltf(dir, R"([{"primitives": [{"attributes": {"POSITION": 0}, "mode": 9}]}])"));
    EXPECT_NE(msg.find("mesh 0 primitive 0: mode 9 is not a glTF mode (0-6)"), std::string::npos) << msg;
    msg = loadError(primitivesGltf(dir, R"([{"primitives": [{"attributes": {"POSITION": 0}, "mode": 0}, )"
                                        R"({"attributes": {"POSITION": 1}, "mode": 1}]}])"));
    EXPECT_NE(msg.find("no triangles: its 2 primitives are points or lines (modes 0-3), which are not read"),
              std::string::npos)
        << msg;
}

// The type check leaves the contents of data: URIs out of what it parses by following the JSON's strings: names
// with escaped quotes, escaped backslashes and "data:" in them load as they are, and the check still reaches
// the properties after them. The node's name has an escaped quote before "\"data:x\"", so a scan that ends a
// string at any quote takes that second escaped quote for an opening one, cuts "data:x\" out of the name and
// leaves JSON that does not parse.
TEST(LoaderGltf, EscapedQuotesInNamesDoNotConfuseTheTypeCheck) {
    TempDir dir;
    const std::string json =
        R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0, "name": "\" \"data:x\" b \\", "translation": [1, 2, 3]}],)"
        R"( "meshes": [{"name": "\\\"data:", "primitives": [{"attributes": {"POSITION": 0}}]}],)"
        R"( "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],)"
        R"( "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"byteLength": 36, "uri": )"
        R"("data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
    const Scene s = loadScene(dir.write("names.gltf", json));
    ASSERT_EQ(s.instances.size(), 1u);
    expectNear(world(s, 0, 0), {1, 2, 3});
    // The same document with a translation of the wrong type after the names: the check still reaches it.
    std::string wrong = json;
    wrong.replace(wrong.find("[1, 2, 3]"), 9, R"("1, 2, 3")");
    const std::string path = dir.write("names_wrong.gltf", wrong);
    EXPECT_NE(loadError(path).find(path + ": nodes[0].translation must be an array of 3 numbers"), std::string::npos)
        << loadError(path);
}

// What the scan leaves out, exactly. Each case defeats a shortcut: ending a string at any quote (the first),
// taking a quote after any backslash for an escaped one (the second: "\\" ends the name, so "data:b" that
// follows is a real URI), and looking for "data: anywhere (the third).
TEST(LoaderGltf, DataUriContentsAreLeftOutAndNothingElse) {
    struct Case {
        std::string in, out;
    };
    const Case cases[] = {
        {R"({"n": "\" \"data:x\" y", "uri": "data:abc"})", R"({"n": "\" \"data:x\" y", "uri": ""})"},
        {R"({"n": "a \\", "uri": "data:b", "m": "\"data:c\""})", R"({"n": "a \\", "uri": "", "m": "\"data:c\""})"},
        {R"({"n": "x\"data:y", "images": [{"uri": "data:image/png;base64,iVBO"}, {"uri": "file.png"}]})",
         R"({"n": "x\"data:y", "images": [{"uri": ""}, {"uri": "file.png"}]})"},
        {R"({"uri": "data:", "n": "unterminated \"data:z)", R"({"uri": "", "n": "unterminated \"data:z)"},
        {"", ""},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.in);
        EXPECT_EQ(loader::withoutDataUris(c.in), c.out);
    }
}

// What tinygltf throws or what a buffer's URI names is the file's error too: a .glb whose buffer states 0 bytes
// (an exception escaped as "internal: vector::_M_range_check", exit 3), a URI naming a FIFO (the load blocked for
// good) or a directory ("out of memory").
TEST(LoaderGltf, BuffersThatCannotBeReadAreTheFilesError) {
    std::string bytes = readBytes(data("quad.glb"));
    const std::size_t at = bytes.find("\"buffers\":[{\"byteLength\":104}]");
    ASSERT_NE(at, std::string::npos);
    bytes.replace(at, 30, "\"buffers\":[{\"byteLength\":0}]  ");  // the same length: the chunk still holds
    TempDir dir;
    const std::string glb = dir.write("empty_buffer.glb", bytes);
    std::string msg = loadError(glb);
    EXPECT_EQ(msg.rfind(glb + ": not a valid glTF file", 0), 0u) << msg;

    ASSERT_EQ(::mkfifo((dir.path() + "/fifo").c_str(), 0600), 0);
    for (const std::string uri : {"fifo", "."}) {
        const std::string path = dir.write("uri.gltf", R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}],)"
            R"( "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],)"
            R"( "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],)"
            R"( "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"byteLength": 36, "uri": ")" + uri + R"("}]})");
        msg = loadError(path);
        EXPECT_EQ(msg, path + ": File read error : " + dir.path() + "/" + uri + " : not a regular file");
    }
}

// A .glb's JSON chunk is checked too: quad.glb with its second accessor's byteOffset 12 written as -2.
TEST(LoaderGltf, GlbJsonChunkIsTypeChecked) {
    std::string bytes = readBytes(data("quad.glb"));
    ASSERT_GE(bytes.size(), 20u);
    const auto u32 = [&](std::size_t at) {
        return std::uint32_t(std::uint8_t(bytes[at])) | std::uint32_t(std::uint8_t(bytes[at + 1])) << 8 |
               std::uint32_t(std::uint8_t(bytes[at + 2])) << 16 | std::uint32_t(std::uint8_t(bytes[at + 3])) << 24;
    };
    std::string json = bytes.substr(20, u32(12));
    const std::size_t at = json.find("\"byteOffset\":12");
    ASSERT_NE(at, std::string::npos) << json;
    json.replace(at, 15, "\"byteOffset\":-2");  // the same length, so the chunk's header still holds
    bytes.replace(20, json.size(), json);
    TempDir dir;
    const std::string path = dir.write("negative.glb", bytes);
    const std::string msg = loadError(path);
    EXPECT_NE(msg.find(path + ": "), std::string::npos) << msg;
    EXPECT_NE(msg.find("accessors[1].byteOffset must be a non-negative integer, got -2"), std::string::npos) << msg;
}

// ---- OBJ --------------------------------------------------------------------------------------------

TEST(LoaderObj, CubeSplitsByMaterialWithKdColours) {
    Scene s = loadScene(data("cube.obj"));
    ASSERT_EQ(s.meshes.size(), 2u);
    ASSERT_EQ(s.instances.size(), 2u);
    const Mesh& grey = s.meshes[0];
    const Mesh& red = s.meshes[1];
    EXPECT_EQ(grey.name, "cube/grey");
    EXPECT_EQ(red.name, "cube/red");
    EXPECT_EQ(grey.positions.size(), 8u);
    EXPECT_EQ(grey.triangleCount(), 10u);
    EXPECT_EQ(red.positions.size(), 4u);
    EXPECT_EQ(red.triangleCount(), 2u);
    EXPECT_EQ(s.triangleCount(), 12u);
    EXPECT_EQ(grey.baseColor, (Vec3{0.5f, 0.5f, 0.5f}));
    EXPECT_EQ(red.baseColor, (Vec3{0.75f, 0.125f, 0.25f}));
    // No vn lines: normals computed. The flat top is exact; the corner at the origin (three grey faces,
    // quads fan-split differently) is the symmetric diagonal thanks to angle weighting.
    for (Vec3 n : red.normals) EXPECT_EQ(n, (Vec3{0, 1, 0}));
    ASSERT_EQ(grey.positions[0], (Vec3{0, 0, 0}));
    const float k = 1 / std::sqrt(3.0f);
    expectNear(grey.normals[0], {-k, -k, -k});
    Bounds b = s.bounds();
    EXPECT_EQ(b.lo, (Vec3{0, 0, 0}));
    EXPECT_EQ(b.hi, (Vec3{1, 1, 1}));
}

TEST(LoaderObj, PolygonIsFanTriangulatedWithFileNormals) {
    Scene s = loadScene(data("polygon.obj"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    EXPECT_EQ(m.positions.size(), 5u);
    EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
    // The file's normal, not the geometric (0,0,1): every corner has one.
    for (Vec3 n : m.normals) expectNear(n, {0, 0.6f, 0.8f});
    EXPECT_EQ(m.baseColor, Mesh{}.baseColor);  // no material
}

TEST(LoaderObj, MissingMtlIsNotAnError) {
    Scene s = loadScene(data("missing_mtl.obj"));
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].triangleCount(), 1u);
    EXPECT_EQ(s.meshes[0].baseColor, Mesh{}.baseColor);
}

TEST(LoaderObj, DegenerateTriangleIsDroppedAndCounted) {
    LoadInfo info;
    Scene s = loadScene(data("degenerate.obj"), &info);
    EXPECT_EQ(info.droppedTriangles, 1u);
    EXPECT_EQ(s.triangleCount(), 1u);
}

TEST(LoaderObj, BadIndex) {
    expectLoadError("bad_index.obj", "out of range");
    EXPECT_EQ(loadError(data("bad_index.obj")), data("bad_index.obj") + ": line 4: vertex 9 out of range (3 vertices)");
}
TEST(LoaderObj, NanVertex) {
    expectLoadError("nan_vertex.obj", "not a finite number");
    EXPECT_EQ(loadError(data("nan_vertex.obj")),
              data("nan_vertex.obj") + ": line 4: vertex coordinate 'nan' is not a finite number");
}
TEST(LoaderObj, NoFaces) { expectLoadError("empty.obj", "no faces"); }

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

// Each file lies in one way that tinyobjloader read as something else (0 for 'nan' or 'abc', atoi's wrap
// and saturation for indices, 1 for '1.7'); each must be an error naming the line and the problem.
TEST(LoaderObj, MalformedVariantsGiveErrors) {
    struct Case {
        std::string text, expected;
    };
    const Case cases[] = {
        {"v nan 0 0\n", "line 1: vertex coordinate 'nan' is not a finite number"},
        {"v 0 -inf 0\n", "line 1: vertex coordinate '-inf' is not a finite number"},
        {"v abc 0 0\n", "line 1: expected a number, got 'abc'"},
        {"v 1 2 3x\n", "line 1: expected a number, got '3x'"},
        {"v 0x1p3 0 0\n", "line 1: expected a number, got '0x1p3'"},
        {"v ++1 0 0\n", "line 1: expected a number, got '++1'"},
        {"v 5 5\n", "line 1: expected 3, 4 or 6 values after 'v' (x y z [w] or x y z r g b), got 2"},
        {"v 1 2 3 4 5\n", "line 1: expected 3, 4 or 6 values after 'v' (x y z [w] or x y z r g b), got 5"},
        {"v 1 2 3 1 1 x\n", "line 1: expected a number, got 'x'"},
        {"v 1e39 0 0\n", "line 1: vertex coordinate '1e39' is beyond float range"},
        {"v 1e400 0 0\n", "line 1: vertex coordinate '1e400' is beyond float range"},
        {"\n# c\nvn nan 0 1\n", "line 3: normal component 'nan' is not a finite number"},
        {"vn 0 1\n", "line 1: expected 3 values after 'vn', got 2"},
        {"vt 0.5 abc\n", "line 1: expected a number, got 'abc'"},
        {"vt\n", "line 1: expected 1 to 3 values after 'vt', got 0"},
        {kTriangle + "f 4294967297 2 3\n", "line 4: vertex 4294967297 out of range (3 vertices)"},
        {kTriangle + "f 1 2 99999999999999999999\n", "line 4: vertex 99999999999999999999 out of range (3 vertices)"},
        {kTriangle + "f 1 2 -99999999999999999999\n", "line 4: vertex -99999999999999999999 out of range"},
        {kTriangle + "f 1.7 2 3\n", "line 4: bad vertex reference '1.7'"},
        {kTriangle + "f 1x 2 3\n", "line 4: bad vertex reference '1x'"},
        {kTriangle + "f 1/ 2 3\n", "line 4: bad vertex reference '1/' (expected v, v/vt, v//vn or v/vt/vn)"},
        {kTriangle + "f /1 2 3\n", "line 4: bad vertex reference '/1'"},
        {kTriangle + "f 1/2/ 2 3\n", "line 4: bad vertex reference '1/2/'"},
        {kTriangle + "f 1/1/1/1 2 3\n", "line 4: bad vertex reference '1/1/1/1'"},
        {kTriangle + "f 0 1 2\n", "line 4: vertex index 0 in '0'"},
        {kTriangle + "f -5 -2 -1\n", "line 4: vertex -5 out of range (3 vertices)"},  // as written, not fixed up
        {kTriangle + "f 1 2 9\n", "line 4: vertex 9 out of range (3 vertices)"},
        {kTriangle + "vn 0 0 1\nf 1//1 2//1 3//2\n", "line 5: normal 2 out of range (1 normal)"},
        {kTriangle + "f 1//-2 2//1 3//1\n", "line 4: normal -2 out of range (0 normals)"},
        {kTriangle + "f 1/1 2/1 3/1\n", "line 4: texture coordinate 1 out of range (0 texture coordinates)"},
        {kTriangle + "f 1 2 3\nl 1 0\n", "line 5: vertex index 0"},
        {kTriangle + "f 1 2 3\np 7\n", "line 5: vertex 7 out of range (3 vertices)"},
        // A forward reference is checked at the end, against the final count, naming its line.
        {"f 1 2 4\n" + kTriangle, "line 1: vertex 4 out of range (3 vertices)"},
        {"v 0 0 0\nv 1 0 0\n", "no faces"},
        {kTriangle + "f 1 2\n", "no faces"},
    };
    TempDir dir;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.text);
        const std::string path = dir.write("bad.obj", c.text);
        const std::string msg = loadError(path);
        EXPECT_NE(msg.find(path + ": " + c.expected), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

// The forms the spec allows, each read as it says: w and vertex colours read past, texture coordinates
// referenced, '+' signs, a valid zero tinyobjloader read as NaN, CRLF and CR line ends, a continued line,
// comments at the end of a line, unknown and ignored statements.
TEST(LoaderObj, ValidFormsAreRead) {
    TempDir dir;
    const std::string text = "# header\r\n"
                             "\r\n"
                             "v 0e999 +0 -0 1.0\r\n"           // w
                             "v 1 0 0 0.5 0.5 0.5\r\n"          // vertex colour
                             "v 0 1 1e-400 # a comment\r"       // underflow is zero; lone CR
                             "v 1 1 \\\r\n"                      // continued
                             "  0\n"
                             "vt 0.5 0.5\nvt 1\nvt 0 0 0\n"
                             "vn 0 0 1\n"
                             "vp 0.5\ncstype bezier\ns off\ns 1\nfoo bar\n"
                             "l 1 2\np -1\n"
                             "f 1/1/1 2/2/1 3/3/1\n"
                             "f +2//+1 4//1 -2//-1\n";
    const Scene s = loadScene(dir.write("forms.obj", text));
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    EXPECT_EQ(m.name, "object0");
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.positions[0], (Vec3{0, 0, 0}));
    EXPECT_EQ(m.positions[1], (Vec3{1, 0, 0}));
    EXPECT_EQ(m.positions[2], (Vec3{0, 1, 0}));
    EXPECT_EQ(m.positions[3], (Vec3{1, 1, 0}));
    EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2}));
    for (Vec3 n : m.normals) EXPECT_EQ(n, (Vec3{0, 0, 1}));
}

TEST(LoaderObj, NegativeIndicesCountBackFromTheLastSoFar) {
    TempDir dir;
    const std::string text = kTriangle + "f -3 -2 -1\nv 5 0 0\nv 6 0 0\nv 5 1 0\nf -3 -2 -1\n";
    const Scene s = loadScene(dir.write("relative.obj", text));
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    ASSERT_EQ(m.positions.size(), 6u);
    EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}));
    EXPECT_EQ(m.positions[3], (Vec3{5, 0, 0}));
    EXPECT_EQ(m.positions[5], (Vec3{5, 1, 0}));
}

// tinyobjloader resolved positive indices against the whole file, so faces above their vertices loaded.
TEST(LoaderObj, FacesMayNameVerticesDefinedLater) {
    TempDir dir;
    const Scene s = loadScene(dir.write("forward.obj", "f 1 2 3\n" + kTriangle));
    EXPECT_EQ(s.triangleCount(), 1u);
}

// tinyobjloader kept vertex counts in an unsigned char: 300 corners wrapped to 44.
TEST(LoaderObj, PolygonOf300VerticesIsFanTriangulated) {
    std::string text;
    const int n = 300;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * 3.14159265358979 * i / n;
        text += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    text += "f";
    for (int i = 1; i <= n; ++i) {
        text += ' ';  // appended apart: GCC 12 warns of a false overlap (-Wrestrict) in " " + to_string(i)
        text += std::to_string(i);
    }
    text += "\n";
    TempDir dir;
    LoadInfo info;
    const Scene s = loadScene(dir.write("circle.obj", text), &info);
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    EXPECT_EQ(info.droppedTriangles, 0u);
    EXPECT_EQ(m.positions.size(), std::size_t(n));
    ASSERT_EQ(m.triangleCount(), std::size_t(n - 2));
    EXPECT_EQ(m.indices[3 * (n - 3)], 0u);
    EXPECT_EQ(m.indices[3 * (n - 3) + 2], std::uint32_t(n - 1));
}

// A face of one or two corners has no area: dropped and counted with the degenerate triangles.
TEST(LoaderObj, ShortFacesAreDroppedAndCounted) {
    TempDir dir;
    LoadInfo info;
    const Scene s = loadScene(dir.write("short.obj", kTriangle + "f 1 2\nf 1 2 3\nf 3\n"), &info);
    EXPECT_EQ(s.triangleCount(), 1u);
    EXPECT_EQ(info.droppedTriangles, 2u);
}

// Shapes and their names as tinyobjloader made them: a shape per 'o' or 'g' line, the material carried
// across, group names joined, an unnamed shape numbered by its place in tinyobjloader's list (where an
// object of lines only counts when an 'o' line ends it), one mesh per material in order of first use.
TEST(LoaderObj, ShapesAndMaterialsAreGroupedAsBefore) {
    TempDir dir;
    dir.write("m.mtl", "newmtl a\nKd 0.25 0.5 0.75\nnewmtl b\nKd 0.5\n");
    const std::string text = kTriangle + "v 1 1 0\n"
                                         "mtllib m.mtl\n"
                                         "f 1 2 3\n"             // object0, no material
                                         "usemtl a\n"
                                         "f 2 4 3\n"             // object0/a
                                         "g left right\n"
                                         "f 1 2 3\n"             // 'left right/a': the material carries over
                                         "usemtl b\nf 2 4 3\n"   // 'left right/b'
                                         "usemtl a\nf 1 2 4\n"   // back into 'left right/a'
                                         "usemtl nothing\nf 1 2 3\n"  // unknown: the default colour
                                         "o   named thing  \n"
                                         "f 1 2 3\n"             // 'named thing/nothing' is no material
                                         "o\nl 1 2\n"            // shape 3, listed for its line
                                         "o\nf 1 2 3\n";         // unnamed: object4
    const Scene s = loadScene(dir.write("groups.obj", text));
    std::vector<std::string> names;
    for (const Mesh& m : s.meshes) names.push_back(m.name);
    EXPECT_EQ(names, (std::vector<std::string>{"object0", "object0/a", "left right/a", "left right/b", "left right",
                                               "named thing", "object4"}));
    ASSERT_EQ(s.meshes.size(), 7u);
    EXPECT_EQ(s.meshes[1].baseColor, (Vec3{0.25f, 0.5f, 0.75f}));
    EXPECT_EQ(s.meshes[2].triangleCount(), 2u);
    EXPECT_EQ(s.meshes[3].baseColor, (Vec3{0.5f, 0.5f, 0.5f}));  // 'Kd 0.5' is grey, not red
    EXPECT_EQ(s.meshes[4].baseColor, Mesh{}.baseColor);
    EXPECT_EQ(s.meshes[0].baseColor, Mesh{}.baseColor);
    // A 'g' line after faces only: no shape listed for the lines before it, so the next is object0 again.
    const Scene t = loadScene(dir.write("lines.obj", kTriangle + "l 1 2\ng\nf 1 2 3\n"));
    EXPECT_EQ(t.meshes.at(0).name, "object0");
}

// Several libraries on one line, all read; a material defined twice keeps its first definition; usemtl
// may come before mtllib; a material without Kd gets the default colour; a library in a subdirectory
// resolves against the .obj's directory, and one with an escaped space is one name.
TEST(LoaderObj, MaterialLibraries) {
    TempDir dir;
    fs::create_directories(fs::path(dir.write("x", "")).parent_path() / "sub");
    dir.write("one.mtl", "# first\nnewmtl a\nKd 0.25 0.25 0.25\n");
    dir.write("sub/two words.mtl", "newmtl a\nKd 1 0 0\nnewmtl b\r\nKd 0 0.5 0\r\nnewmtl plain\nNs 10\n");
    const std::string text = kTriangle + "usemtl b\nf 1 2 3\nusemtl a\nf 1 2 3\nusemtl plain\nf 1 2 3\n"
                                         "mtllib one.mtl missing.mtl sub/two\\ words.mtl\n";
    const Scene s = loadScene(dir.write("libs.obj", text));
    ASSERT_EQ(s.meshes.size(), 3u);
    EXPECT_EQ(s.meshes[0].name, "object0/b");
    EXPECT_EQ(s.meshes[0].baseColor, (Vec3{0, 0.5f, 0}));
    EXPECT_EQ(s.meshes[1].name, "object0/a");
    EXPECT_EQ(s.meshes[1].baseColor, (Vec3{0.25f, 0.25f, 0.25f}));
    EXPECT_EQ(s.meshes[2].name, "object0/plain");
    EXPECT_EQ(s.meshes[2].baseColor, Mesh{}.baseColor);
}

TEST(LoaderObj, MalformedMtlGivesErrorsNamingIt) {
    struct Case {
        std::string mtl, expected;
    };
    const Case cases[] = {
        {"newmtl a\nKd abc 0.5 0.5\n", "line 2: expected a number, got 'abc'"},
        {"newmtl a\nKd 0.5 0.5\n", "line 2: expected 1 or 3 values after 'Kd', got 2"},
        {"newmtl a\n\nKd nan\n", "line 3: Kd value 'nan' is not a finite number"},
        {"newmtl a\nKd xyz 1 1 1\n", "line 2: 'Kd xyz' is not supported (expected 'Kd r g b')"},
        {"newmtl\nKd 1 1 1\n", "line 1: 'newmtl' without a name"},
    };
    TempDir dir;
    const std::string obj = dir.write("m.obj", "mtllib m.mtl\nusemtl a\n" + kTriangle + "f 1 2 3\n");
    for (const Case& c : cases) {
        SCOPED_TRACE(c.mtl);
        const std::string mtl = dir.write("m.mtl", c.mtl);
        const std::string msg = loadError(obj);
        EXPECT_NE(msg.find(mtl + ": " + c.expected), std::string::npos) << msg;
    }
    // Kd outside [0, 1] on a material in use is sanitizeScene's error, naming the mesh.
    dir.write("m.mtl", "newmtl a\nKd 1.5 0 0\n");
    EXPECT_NE(loadError(obj).find("mesh 'object0/a' has base colour (1.5, 0, 0), outside [0, 1]"), std::string::npos)
        << loadError(obj);
}

// Normals: a group where one corner has none is positions only, with computed normals; with a normal on
// every corner, one position with two normals is two vertices.
TEST(LoaderObj, NormalsPerGroup) {
    TempDir dir;
    const std::string quad = kTriangle + "v 1 1 0\nvn 0 0 2\nvn 0 1 0\n";
    const Scene mixed = loadScene(dir.write("mixed.obj", quad + "f 1//1 2//1 3\nf 2//2 4//2 3//2\n"));
    ASSERT_EQ(mixed.meshes.size(), 1u);
    EXPECT_EQ(mixed.meshes[0].positions.size(), 4u);
    for (Vec3 n : mixed.meshes[0].normals) expectNear(n, {0, 0, 1});  // computed from the faces
    const Scene hard = loadScene(dir.write("hard.obj", quad + "f 1//1 2//1 3//1\nf 2//2 4//2 3//2\n"));
    const Mesh& m = hard.meshes.at(0);
    ASSERT_EQ(m.positions.size(), 6u);
    EXPECT_EQ(m.normals[0], (Vec3{0, 0, 1}));  // (0,0,2) normalized
    EXPECT_EQ(m.normals[3], (Vec3{0, 1, 0}));
    EXPECT_EQ(m.positions[3], m.positions[1]);
}

// ---- PLY --------------------------------------------------------------------------------------------

TEST(LoaderPly, AsciiQuadWithNormalsColoursAndAnUnknownElement) {
    Scene s = loadScene(data("quad_ascii.ply"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    EXPECT_EQ(m.name, "quad_ascii");
    EXPECT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.positions[2], (Vec3{1, 1, 0}));
    EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    for (Vec3 n : m.normals) EXPECT_EQ(n, (Vec3{0, 0, 1}));
    EXPECT_EQ(m.baseColor, (Vec3{0.5f, 0, 0.5f}));  // two red and two blue vertices (uchar 255)
}

TEST(LoaderPly, BinaryLittleEndianSkipsUnknownPropertiesAndElements) {
    Scene s = loadScene(data("quad_binary.ply"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.positions[0], (Vec3{0, 0, 0}));
    EXPECT_EQ(m.positions[2], (Vec3{1, 1, 0}));  // z read past the unknown 'confidence' = 9.5
    EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    for (Vec3 n : m.normals) EXPECT_EQ(n, (Vec3{0, 0, 1}));  // computed
    EXPECT_EQ(m.baseColor, (Vec3{0.25f, 0.375f, 0.75f}));     // float colours averaged
}

TEST(LoaderPly, BinaryBigEndianWithShortsAndAListElementFirst) {
    Scene s = loadScene(data("quad_binary_be.ply"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.positions[1], (Vec3{2, 0, 0}));
    EXPECT_EQ(m.positions[2], (Vec3{2, 2, 0}));
    EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(m.baseColor, (Vec3{1, 0, 0}));  // ushort 65535 is full intensity
}

TEST(LoaderPly, TruncatedBinary) {
    expectLoadError("truncated_binary.ply", "truncated");
    EXPECT_EQ(loadError(data("truncated_binary.ply")),
              data("truncated_binary.ply") + ": truncated: expected 4 vertices, got 2");
}
TEST(LoaderPly, BadHeader) {
    EXPECT_EQ(loadError(data("bad_header.ply")), data("bad_header.ply") + ": line 4: unknown property type 'flt'");
}
TEST(LoaderPly, BadIndex) {
    EXPECT_EQ(loadError(data("bad_index.ply")), data("bad_index.ply") + ": face 0: index 5 out of range (3 vertices)");
}

TEST(LoaderPly, MalformedAsciiVariantsGiveErrors) {
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    struct Case {
        std::string text, expected;
    };
    const Case cases[] = {
        {"", "line 1: not a PLY file"},
        {"solid cube\n", "line 1: not a PLY file"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", "line 5: the header has no end_header"},
        {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "line 3: property before any element"},
        {"ply\nformat binary_middle_endian 1.0\nend_header\n", "line 2: unknown format 'binary_middle_endian'"},
        {"ply\nformat ascii 2.0\nend_header\n", "line 2: unsupported format version '2.0'"},
        {"ply\nelement vertex 3\nend_header\n", "line 3: end_header before any format line"},
        {"ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", "line 3: element count '-3' is not"},
        {"ply\nformat ascii 1.0\nelephant vertex 3\nend_header\n", "line 3: unknown header keyword 'elephant'"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\nelement face 0\n"
         "property list uchar int vertex_indices\nend_header\n0 0\n",
         "line 3: the vertex element has no x, y, z"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n" +
             body, "no face element"},
        {header + "0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n", "line 11: expected a number, got 'abc'"},
        {header + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", "line 13: expected an integer, got '1.5'"},
        {header + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "face 0: index -1 out of range (3 vertices)"},
        {header + "0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n", "vertex 2 of mesh 'bad' has a non-finite position"},
        {header + "0 0 0\n1 0 0\n", "truncated: expected 3 vertices, got 2"},
        {header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "truncated: expected 1 face, got 0"},
        {"ply\nformat ascii 1.0\nelement vertex 1000000\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n" + body,
         "truncated: expected 1000000 vertices, got 4"},
        // Integers must fit the declared type, as a binary file's would: inf and 1e30 passed the integer test
        // and met an undefined integer cast.
        {header + "0 0 0\n1 0 0\n0 1 0\ninf 0 1 2\n", "line 13: 'inf' does not fit the declared type uchar"},
        {header + "0 0 0\n1 0 0\n0 1 0\n256 0 1 2\n", "line 13: '256' does not fit the declared type uchar"},
        {header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 1e30\n", "line 13: '1e30' does not fit the declared type int"},
        // More rows than the header declares: the header and the data disagree.
        {header + body + "3 0 2 1\n", "line 14: data after the last element"},
    };
    TempDir dir;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.expected);
        std::string path = dir.write("bad.ply", c.text);
        std::string msg = loadError(path);
        EXPECT_NE(msg.find(path + ": " + c.expected), std::string::npos) << msg;
    }
    // Windows line endings and a leading '+' are fine.
    std::string crlf;
    for (char ch : header + "+0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n") crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
    EXPECT_EQ(loadScene(dir.write("crlf.ply", crlf)).triangleCount(), 1u);
}

// An element declared with no properties has rows of nothing: a header claiming 1e18 of them loads at once
// (the rows were once read one by one, for centuries), in ASCII and binary files alike.
TEST(LoaderPly, ElementWithoutPropertiesHoldsNothing) {
    TempDir dir;
    const std::string header = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                               "element junk 1000000000000000000\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    EXPECT_EQ(loadScene(dir.write("a.ply", "ply\nformat ascii 1.0\n" + header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"))
                  .triangleCount(),
              1u);
    std::string binary = "ply\nformat binary_little_endian 1.0\n" + header;
    const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    binary.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    const std::int32_t corners[3] = {0, 1, 2};
    binary += char(3);
    binary.append(reinterpret_cast<const char*>(corners), sizeof corners);
    EXPECT_EQ(loadScene(dir.write("b.ply", binary)).triangleCount(), 1u);
    // Bytes after the last row: the header and the data disagree.
    EXPECT_NE(loadError(dir.write("c.ply", binary + "xyz")).find("3 bytes after the last element"), std::string::npos);
}

// Colours are held to [0, 1] vertex by vertex, after scaling by the type's full intensity (127 for a char,
// as its negative half is not light): (2, 2, 2), (-1, -1, -1) and (0.5, 0.5, 0.5) once averaged to a grey.
TEST(LoaderPly, ColoursAreCheckedPerVertexAtTheirTypesScale) {
    TempDir dir;
    // Three vertices with the given colour values (three per vertex) of type `type`.
    auto file = [](const std::string& type, const std::string (&colours)[3]) {
        std::string text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "property " + type + " red\nproperty " + type + " green\nproperty " + type + " blue\n"
                           "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
        const char* xyz[3] = {"0 0 0 ", "1 0 0 ", "0 1 0 "};
        for (int v = 0; v < 3; ++v) text += xyz[v] + colours[v] + "\n";
        return text + "3 0 1 2\n";
    };
    const std::string floats = dir.write("float.ply", file("float", {"2 2 2", "-1 -1 -1", "0.5 0.5 0.5"}));
    EXPECT_EQ(loadError(floats), floats + ": vertex 0 has colour (2, 2, 2), outside [0, 1]");
    const std::string chars = dir.write("char.ply", file("char", {"1 1 1", "-1 -1 -1", "1 1 1"}));
    EXPECT_EQ(loadError(chars), chars + ": vertex 1 has colour (-0.007874016, -0.007874016, -0.007874016), outside [0, 1]");
    const Scene full = loadScene(dir.write("full.ply", file("char", {"127 127 127", "127 127 127", "127 127 127"})));
    EXPECT_EQ(full.meshes.at(0).baseColor, (Vec3{1, 1, 1}));
}

// A zero normal in a file is an error naming the vertex: it once reached the G-buffer as (0, 0, 0), which
// `ao` then refused in the G-buffer Obscura had written.
TEST(LoaderScene, ZeroLengthNormalsAreErrors) {
    TempDir dir;
    const std::string ply = dir.write("n.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                               "property float y\nproperty float z\nproperty float nx\nproperty float ny\n"
                                               "property float nz\nelement face 1\nproperty list uchar int vertex_indices\n"
                                               "end_header\n0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n3 0 1 2\n");
    EXPECT_EQ(loadError(ply), ply + ": vertex 1 of mesh 'n' has a zero-length normal");
    const std::string obj = dir.write("n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
    EXPECT_EQ(loadError(obj), obj + ": vertex 0 of mesh 'object0' has a zero-length normal");
}

// A directory named like a scene file is named as one, for every format.
TEST(LoaderScene, DirectoryIsNotASceneFile) {
    TempDir dir;
    for (const char* name : {"d.ply", "d.obj", "d.gltf", "d.glb"}) {
        const std::string path = dir.path() + "/" + name;
        fs::create_directory(path);
        EXPECT_EQ(loadError(path), path + ": is a directory, not a scene file");
    }
}

// ---- loadScene and robustness -----------------------------------------------------------------------

TEST(LoaderScene, MissingFile) {
    EXPECT_EQ(loadError(data("nope.obj")), data("nope.obj") + ": no such file");
}

TEST(LoaderScene, UnknownExtensionAndCaseInsensitiveDispatch) {
    TempDir dir;
    std::string xyz = dir.write("points.xyz", "0 0 0\n");
    EXPECT_EQ(loadError(xyz), xyz + ": unknown scene format '.xyz' (expected .gltf, .glb, .obj or .ply)");
    std::string upper = dir.write("QUAD.PLY", readBytes(data("quad_ascii.ply")));
    EXPECT_EQ(loadScene(upper).meshes.at(0).positions.size(), 4u);
}

// Every prefix of every fixture, and every byte of the binary ones overwritten, must load or throw Error:
// never crash, hang or read out of bounds (run under -DOBSCURA_SANITIZE=ON to see the last).
TEST(LoaderScene, CorruptCopiesLoadOrThrowError) {
    TempDir dir;
    auto tryLoad = [](const std::string& path) {
        try {
            loadScene(path);
        } catch (const Error&) {
        }
    };
    for (const char* name : {"quad.gltf", "quad.glb", "hierarchy.gltf", "cube.obj", "polygon.obj", "quad_ascii.ply",
                             "quad_binary.ply", "quad_binary_be.ply"}) {
        SCOPED_TRACE(name);
        const std::string bytes = readBytes(data(name));
        ASSERT_FALSE(bytes.empty());
        for (std::size_t n = 0; n < bytes.size(); ++n) tryLoad(dir.write(name, bytes.substr(0, n)));
        const std::string ext = fs::path(name).extension().string();
        if (ext == ".glb" || std::string(name).find("binary") != std::string::npos) {
            for (std::size_t i = 0; i < bytes.size(); ++i) {
                std::string b = bytes;
                b[i] = char(~b[i]);
                tryLoad(dir.write(name, b));
            }
        }
    }
}

} // namespace
} // namespace obscura
