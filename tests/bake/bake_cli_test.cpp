// `obscura bake` and `obscura scenes --generate` end to end: outputs carry what they promise, the input
// is never touched, bad input gives one line and no output.
#include "cli/cli_harness.h"
#include "obscura/scene_io.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

using Result = obscura::clitest::CliResult;

Result run(const std::string& args) { return obscura::clitest::runCli(args); }

std::string data(const std::string& name) { return std::string(OBSCURA_TEST_DATA) + "/" + name; }

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

nlohmann::json glbJson(const std::string& path) {
    std::string bytes = readBytes(path);
    if (bytes.size() < 20) return {};
    std::uint32_t length;
    std::memcpy(&length, bytes.data() + 12, 4);
    return nlohmann::json::parse(bytes.substr(20, length));
}

class BakeCli : public obscura::clitest::CliTest {};

// `args` run with files limited to `bytes` (a full disk): a write past it fails with EFBIG, SIGXFSZ being
// ignored in the child, which inherits both. The limit is lifted again before returning.
Result runWithFileSizeLimit(const std::string& args, rlim_t bytes) {
    struct rlimit before {};
    if (getrlimit(RLIMIT_FSIZE, &before) != 0) return {};
    struct rlimit small = before;
    small.rlim_cur = bytes;
    void (*oldHandler)(int) = signal(SIGXFSZ, SIG_IGN);
    Result r;
    if (setrlimit(RLIMIT_FSIZE, &small) == 0) {
        r = run(args);
        setrlimit(RLIMIT_FSIZE, &before);
    }
    signal(SIGXFSZ, oldHandler);
    return r;
}

const std::string kFast = " --rays 8 --max-samples-per-face 4 -q ";

} // namespace

TEST_F(BakeCli, GeneratedLevelBakesToGlbWithAttributesPerInstance) {
    Result g = run("scenes --generate level --triangles 6000 --seed 3 -o " + path("level.glb"));
    ASSERT_EQ(g.code, 0) << g.out;
    Result g2 = run("scenes --generate level --triangles 6000 --seed 3 -o " + path("level2.glb"));
    ASSERT_EQ(g2.code, 0) << g2.out;
    EXPECT_EQ(readBytes(path("level.glb")), readBytes(path("level2.glb"))) << "same seed, same file";
    obscura::Scene level = obscura::loadScene(path("level.glb"));
    EXPECT_GE(level.triangleCount(), 6000u);
    EXPECT_LT(level.triangleCount(), 7000u);
    EXPECT_GT(level.instances.size(), level.meshes.size()) << "props stay instanced in the generated file";

    const std::string input = readBytes(path("level.glb"));
    Result r = run("bake " + path("level.glb") + " -o " + path("baked.glb") + " --report " + path("bake.json") + kFast);
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.find('\r'), std::string::npos) << "no progress bar when stderr is not a terminal";
    EXPECT_EQ(readBytes(path("level.glb")), input) << "input modified";
    nlohmann::json j = glbJson(path("baked.glb"));
    ASSERT_TRUE(j.contains("nodes"));
    EXPECT_EQ(j["meshes"].size(), j["nodes"].size()) << "each instance baked into a mesh of its own";
    for (const auto& mesh : j["meshes"])
        for (const auto& prim : mesh["primitives"]) {
            const auto& a = prim["attributes"];
            ASSERT_TRUE(a.contains("COLOR_0") && a.contains("_AO_SHORT") && a.contains("_AO_LONG")) << a.dump();
            const auto count = j["accessors"][a["POSITION"].get<int>()]["count"];
            EXPECT_EQ(j["accessors"][a["COLOR_0"].get<int>()]["count"], count);
            EXPECT_EQ(j["accessors"][a["_AO_LONG"].get<int>()]["type"], "SCALAR");
        }
    obscura::Scene baked = obscura::loadScene(path("baked.glb"));
    EXPECT_EQ(baked.triangleCount(), level.triangleCount());

    nlohmann::json report = nlohmann::json::parse(readBytes(path("bake.json")));
    for (const char* key : {"samples", "rays", "invalid_samples", "mrays_per_s", "stage_seconds"}) EXPECT_TRUE(report.contains(key)) << key;
    for (const char* key : {"process_geometry", "sample", "bvh_build", "trace", "least_squares_solve", "write"})
        EXPECT_TRUE(report["stage_seconds"].contains(key)) << key;
    EXPECT_EQ(report["rays"].get<std::uint64_t>(), report["samples"].get<std::uint64_t>() * 8);
}

TEST_F(BakeCli, GltfInputKeepsItsNodesAndGetsAttributes) {
    Result r = run("bake " + data("hierarchy.gltf") + " -o " + path("h.gltf") + kFast);
    ASSERT_EQ(r.code, 0) << r.out;
    nlohmann::json in = nlohmann::json::parse(readBytes(data("hierarchy.gltf")));
    nlohmann::json out = nlohmann::json::parse(readBytes(path("h.gltf")));
    ASSERT_EQ(out["nodes"].size(), in["nodes"].size());
    for (std::size_t i = 0; i < in["nodes"].size(); ++i) EXPECT_EQ(out["nodes"][i].value("name", ""), in["nodes"][i].value("name", ""));
    for (const auto& mesh : out["meshes"])
        for (const auto& prim : mesh["primitives"]) EXPECT_TRUE(prim["attributes"].contains("COLOR_0")) << prim.dump();
    EXPECT_EQ(obscura::loadScene(path("h.gltf")).triangleCount(), obscura::loadScene(data("hierarchy.gltf")).triangleCount());
}

// A strip and a fan (skipped once, so they neither occluded nor were baked) get their attributes per file vertex
// like a triangle list; a COLOR_0 the bake replaces is said.
TEST_F(BakeCli, StripsAndFansAreBakedAndAReplacedColourIsSaid) {
    // Two unit squares side by side in z = 0, 4 corners each: strip order, then fan order 1 m to the right.
    const float xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 1, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0,
                         1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};  // then white COLOR_0
    std::ofstream(path("strips.bin"), std::ios::binary).write(reinterpret_cast<const char*>(xyz), sizeof xyz);
    std::ofstream(path("strips.gltf"))
        << R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}], "meshes": [{"primitives": [)"
           R"({"attributes": {"POSITION": 0, "COLOR_0": 2}, "mode": 5}, {"attributes": {"POSITION": 1}, "mode": 6}]}],)"
           R"( "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},)"
           R"({"bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3"},)"
           R"({"bufferView": 0, "byteOffset": 96, "componentType": 5126, "count": 4, "type": "VEC3"}],)"
           R"( "bufferViews": [{"buffer": 0, "byteLength": 192}], "buffers": [{"byteLength": 192, "uri": "strips.bin"}]})";
    Result r = run("bake " + path("strips.gltf") + " -o " + path("strips_out.gltf") + " --rays 8 -q");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("the COLOR_0 of 1 primitive is replaced by the baked grey"), std::string::npos) << r.out;
    nlohmann::json out = nlohmann::json::parse(readBytes(path("strips_out.gltf")));
    for (const auto& prim : out["meshes"][0]["primitives"]) {
        EXPECT_TRUE(prim["attributes"].contains("_AO_SHORT")) << prim.dump();
        EXPECT_EQ(out["accessors"][prim["attributes"]["COLOR_0"].get<int>()]["count"], 4) << prim.dump();
    }
    EXPECT_EQ(obscura::loadScene(path("strips_out.gltf")).triangleCount(), 4u);
    // Without a COLOR_0 in the input, nothing is said.
    Result plain = run("bake " + data("hierarchy.gltf") + " -o " + path("h2.gltf") + kFast);
    ASSERT_EQ(plain.code, 0) << plain.out;
    EXPECT_EQ(plain.out.find("COLOR_0"), std::string::npos) << plain.out;
}

TEST_F(BakeCli, OcclusionToPlyAndCsv) {
    Result r = run("bake " + data("cube.obj") + " --mode occlusion --distance 2 -o " + path("cube.ply") + kFast);
    ASSERT_EQ(r.code, 0) << r.out;
    // The summary names the distance the bake used (it once printed --distances' default, 2,300).
    const Result said =
        run("bake " + data("cube.obj") + " --mode occlusion --distance 2 --rays 8 --max-samples-per-face 4 -o " +
            path("said.csv"));
    ASSERT_EQ(said.code, 0) << said.out;
    EXPECT_NE(said.out.find("(occlusion, d = 2 m,"), std::string::npos) << said.out;
    const std::string ply = readBytes(path("cube.ply"));
    EXPECT_NE(ply.find("property float quality"), std::string::npos);
    obscura::Scene back = obscura::loadScene(path("cube.ply"));
    EXPECT_EQ(back.triangleCount(), 12u);
    r = run("bake " + data("cube.obj") + " -o " + path("cube.csv") + kFast);
    ASSERT_EQ(r.code, 0) << r.out;
    std::ifstream csv(path("cube.csv"));
    std::string header, line;
    std::getline(csv, header);
    EXPECT_EQ(header, "index,x,y,z,short,long,blended");
    int rows = 0;
    while (std::getline(csv, line)) {
        ++rows;
        float x, y, z, s, l, b;
        int i;
        ASSERT_EQ(std::sscanf(line.c_str(), "%d,%f,%f,%f,%f,%f,%f", &i, &x, &y, &z, &s, &l, &b), 7) << line;
        // A lone cube: every face sees an open hemisphere, nothing occludes it.
        EXPECT_NEAR(s, 1.0f, 1e-6f);
        EXPECT_NEAR(b, 0.97f * l + 0.03f * s, 1e-5f);
    }
    EXPECT_EQ(rows, int(obscura::loadScene(data("cube.obj")).meshes[0].positions.size() +
                        obscura::loadScene(data("cube.obj")).meshes[1].positions.size()));
}

TEST_F(BakeCli, BadInputIsOneLineAndNoOutput) {
    const std::string out = " -o " + path("o.glb");
    expectFailure("bake " + path("missing.glb") + out + kFast, {"missing.glb", "no such file"});
    expectFailure("bake " + data("bad_json.gltf") + out + kFast, {"bad_json.gltf"});
    expectFailure("bake " + data("cube.obj") + out + " --rays 0 -q", {"--rays"});
    expectFailure("bake " + data("cube.obj") + out + " --blend 1.5 -q", {"--blend"});
    expectFailure("bake " + data("cube.obj") + out + " --distances 2,3,4 -q", {"--distances"});
    expectFailure("bake " + data("cube.obj") + out + " --distances -1 -q", {"--distances"});
    // --distance once fell back to --distances' default for any value not above 0, NaN included, and said nothing.
    for (const char* bad : {"nan", "-1", "0", "-inf"})
        expectFailure("bake " + data("cube.obj") + out + " --distance " + bad + " -q", {"--distance", "expected a distance"});
    expectFailure("bake " + data("cube.obj") + out + " --distance \"\" -q", {"--distance: empty value"}, 2);
    expectFailure("bake " + data("cube.obj") + out + " --alpha -1 -q", {"--alpha"});
    // A size_t once took -1 as 2^64 - 1.
    expectFailure("bake " + data("cube.obj") + out + " --raw-embree-check -1 -q", {"--raw-embree-check: must be in [0, 1000000000], got -1"});
    expectFailure("bake " + data("cube.obj") + out + " --raw-embree-check 1000000001 -q", {"--raw-embree-check"});
    // The flag as the user typed it, as every other flag's message has it (ThreadLimit's own says "threads").
    expectFailure("bake " + data("cube.obj") + out + " --threads -1 -q", {"--threads: must be in [0, 1024]", "got -1"});
    expectFailure("bake " + data("cube.obj") + out + " --threads 1025 -q", {"--threads: must be in [0, 1024]", "got 1025"});
    expectFailure("bake " + data("cube.obj") + out + " --mode fuzzy -q", {"--mode"});
    // A cap under the default minimum names both flags and their values.
    expectFailure("bake " + data("cube.obj") + out + " --max-samples-per-face 2 -q",
                  {"--min-samples-per-face: 3 is above --max-samples-per-face 2"});
    expectFailure("bake " + data("cube.obj") + out + " --min-samples-per-face 0 -q", {"--min-samples-per-face", "got 0"});
    expectFailure("bake " + data("cube.obj") + out + " --crease-angle 200 -q", {"--crease-angle"});
    expectFailure("bake " + data("cube.obj") + out + " --linear-solver qr -q", {"--linear-solver"});
    expectFailure("bake " + data("cube.obj") + " -o " + path("o.png") + kFast, {"o.png", "unsupported output format"});
    expectFailure("bake " + data("cube.obj") + " -o " + path("nodir/o.glb") + kFast, {"does not exist"});
    // An instance that scales its triangle to nothing: the bake's refusal names the input.
    {
        std::ofstream flat(path("flat.gltf"));
        flat << R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0, "scale": [0, 0, 0]}],)"
                R"( "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],)"
                R"( "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],)"
                R"( "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"byteLength": 36, "uri": )"
                R"("data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
    }
    expectFailure("bake " + path("flat.gltf") + out + kFast, {"flat.gltf: bake: no triangles left after welding"});
    fs::copy_file(data("quad.glb"), path("quad.glb"));
    const std::string before = readBytes(path("quad.glb"));
    Result r = run("bake " + path("quad.glb") + " -o " + path("quad.glb") + kFast);
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_NE(r.out.find("input"), std::string::npos) << r.out;
    EXPECT_EQ(readBytes(path("quad.glb")), before);
    expectFailure("scenes --generate maze -o " + path("m.glb"), {"--generate"});
    expectFailure("scenes --generate level --triangles 10 -o " + path("m.glb"), {"--triangles"});
}

TEST_F(BakeCli, DistancesAreParsedStrictly) {
    const std::string out = " -o " + path("o.csv");
    const std::string bake = "bake " + data("cube.obj") + out + " --rays 4 --max-samples-per-face 4 -q ";
    // getline once dropped the trailing empty item: "1," was one distance while ",2" and "1,,2" failed.
    for (const char* bad : {"1,", ",2", "1,,2", ",", "1, ", "2,300,4"})
        expectFailure(bake + "--distances \"" + bad + "\"", {"--distances", "expected one or two distances"});
    // Channel 0 is _AO_SHORT and takes --blend's weight: the order is not free.
    for (const char* bad : {"300,2", "2,2"})
        expectFailure(bake + "--distances " + bad, {"--distances", "the short distance must be less than the long one"});
    // strtof read hex floats; inf was refused by the bake after a message that offered it.
    for (const char* bad : {"0x1p1", "2,0x1p9", "inf", "2,inf", "nan", "1e7", "abc"})
        expectFailure(bake + "--distances " + bad, {"--distances", "expected a distance in (0, 1e6] m, got"});
    for (const char* bad : {"0x1p1", "inf", "-1"})
        expectFailure(bake + "--distance " + bad, {"--distance: expected a distance in (0, 1e6] m, got"});
    const Result inf = run(bake + "--distance inf");
    EXPECT_EQ(inf.out.find("or \"inf\""), std::string::npos) << "offers the inf it refuses: " << inf.out;
    // Given together, one of the two once won without a word.
    expectFailure(bake + "--distance 2 --distances 1,300", {"--distance", "cannot be given with --distances"});
    expectFailure(bake + "--distances 1,300 --distance 2", {"--distance", "cannot be given with --distances"});
    // Spaces around a number are taken on either side, as parseVec3 takes them ("2 " was once refused, " 2" not).
    for (const char* good : {" 2", "2 ", " 2 , 300 ", "0.5,2"}) {
        const Result r = run(bake + "--distances \"" + good + "\"");
        EXPECT_EQ(r.code, 0) << good << ": " << r.out;
    }
    for (const char* good : {" 2", "2 "}) {
        const Result r = run(bake + "--distance \"" + good + "\"");
        EXPECT_EQ(r.code, 0) << good << ": " << r.out;
    }
    // Read as the same numbers: the CSV's first vertex under --distances " 0.5 , 2 " is that of "0.5,2" to the
    // last digit (tolerance 0: the same settings give the same bits).
    ASSERT_EQ(run(bake + "--distances \" 0.5 , 2 \"").code, 0);
    std::ifstream spaced(path("o.csv"));
    std::string header, a, b;
    std::getline(spaced, header);
    std::getline(spaced, a);
    ASSERT_EQ(run(bake + "--distances 0.5,2").code, 0);
    std::ifstream plain(path("o.csv"));
    std::getline(plain, header);
    std::getline(plain, b);
    EXPECT_EQ(a, b);
}

TEST_F(BakeCli, FailedReportLeavesNoOutput) {
    const std::string args = " -o " + path("x.csv") + " --report ";
    const std::string fast = " --rays 4 --max-samples-per-face 4 -q";
    // The report's directory takes no files: found before the bake, nothing written.
    expectFailure("bake plane" + args + "/proc/r.json" + fast, {"/proc/r.json", "cannot write"});
    // The report's write itself fails, after the output's (here: a 512-byte file size limit, which the 115-byte
    // CSV of the plane meets and the ~1 kB report does not): the output is removed again.
    const Result r = runWithFileSizeLimit("bake plane" + args + path("r.json") + fast, 512);
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_NE(r.out.find("r.json: write failed"), std::string::npos) << r.out;
    EXPECT_EQ(entries(), 0u) << "output or report left behind: " << r.out;
    // Without the limit both files are written.
    const Result ok = run("bake plane" + args + path("r.json") + fast);
    EXPECT_EQ(ok.code, 0) << ok.out;
    EXPECT_TRUE(fs::exists(path("x.csv")));
    EXPECT_TRUE(fs::exists(path("r.json")));
}

// The baked copy of a glTF file edits the file's JSON, so what the bake does not touch is the input's: tinygltf's
// model, which it went through before, dropped extensions and extras on accessors, buffer views, buffers, skins,
// samplers and animation targets, named samplers, gave an infinite perspective camera "zfar": 0 (invalid), and
// wrote an image held as a data URI as {"bufferView": -1}. Every input property is compared, the meshes and the
// nodes after the bake's own changes: new attributes, and clones for the second user of a mesh.
TEST_F(BakeCli, GltfOutputKeepsWhatTheBakeDoesNotTouch) {
    for (const char* name : {"bake_keeps_extras.gltf", "bake_keeps_complex.gltf", "bake_keeps_data_uri_image.gltf"})
        for (const char* ext : {".gltf", ".glb"}) {
            const std::string out = path(std::string("k") + ext), what = std::string(name) + " to " + ext;
            const Result r = run("bake " + data(name) + " -o " + out + kFast);
            ASSERT_EQ(r.code, 0) << what << ": " << r.out;
            const nlohmann::json in = nlohmann::json::parse(readBytes(data(name)));
            const nlohmann::json got = std::string(ext) == ".glb" ? glbJson(out) : nlohmann::json::parse(readBytes(out));
            for (const auto& [key, value] : in.items()) {
                if (key == "meshes" || key == "nodes" || key == "buffers") continue;
                if (key == "accessors" || key == "bufferViews") {  // the bake appends its own
                    ASSERT_GE(got[key].size(), value.size()) << what << ": " << key;
                    for (std::size_t i = 0; i < value.size(); ++i) EXPECT_EQ(got[key][i], value[i]) << what << ": " << key << i;
                    continue;
                }
                EXPECT_EQ(got[key], value) << what << ": " << key;
            }
            for (std::size_t b = 0; b < in["buffers"].size(); ++b) {
                nlohmann::json kept = in["buffers"][b], written = got["buffers"][b];
                for (const char* k : {"uri", "byteLength"}) {
                    kept.erase(k);
                    written.erase(k);
                }
                EXPECT_EQ(written, kept) << what << ": buffer " << b;
            }
            // Nodes: the same but for the mesh, which is the same mesh or a clone of it.
            const nlohmann::json& meshes = got["meshes"];
            for (std::size_t n = 0; n < in["nodes"].size(); ++n) {
                nlohmann::json node = got["nodes"][n];
                if (!in["nodes"][n].contains("mesh")) {
                    EXPECT_EQ(node, in["nodes"][n]) << what << ": node " << n;
                    continue;
                }
                const nlohmann::json& before = in["meshes"][in["nodes"][n]["mesh"].get<std::size_t>()];
                nlohmann::json after = meshes[node["mesh"].get<std::size_t>()];
                node["mesh"] = in["nodes"][n]["mesh"];
                EXPECT_EQ(node, in["nodes"][n]) << what << ": node " << n;
                after["name"] = before.value("name", "");
                if (!before.contains("name")) after.erase("name");
                for (auto& prim : after["primitives"])
                    for (const char* k : {"COLOR_0", "_AO_SHORT", "_AO_LONG"}) prim["attributes"].erase(k);
                nlohmann::json plain = before;
                for (auto& prim : plain["primitives"])
                    for (const char* k : {"COLOR_0", "_AO_SHORT", "_AO_LONG"}) prim["attributes"].erase(k);
                EXPECT_EQ(after, plain) << what << ": node " << n << "'s mesh";
            }
        }
    // The infinite camera stays infinite, and the node of the other scene ("other-scene", node 5) that shares
    // mesh 0 with the baked nodes keeps the mesh as it was: no AO of theirs.
    ASSERT_EQ(run("bake " + data("bake_keeps_complex.gltf") + " -o " + path("c.gltf") + kFast).code, 0);
    const nlohmann::json c = nlohmann::json::parse(readBytes(path("c.gltf")));
    EXPECT_FALSE(c["cameras"][0]["perspective"].contains("zfar"));
    EXPECT_EQ(c["nodes"][5]["mesh"], 0);
    for (const auto& prim : c["meshes"][0]["primitives"]) EXPECT_FALSE(prim["attributes"].contains("COLOR_0"));
    EXPECT_NE(c["nodes"][1]["mesh"], 0);
}

// Baking a baked file with one distance wrote the new _AO_SHORT beside the old bake's _AO_LONG.
TEST_F(BakeCli, RebakingWithOneDistanceLeavesNoOldChannel) {
    ASSERT_EQ(run("bake " + data("hierarchy.gltf") + " -o " + path("two.gltf") + kFast).code, 0);
    ASSERT_EQ(run("bake " + path("two.gltf") + " -o " + path("one.gltf") + " --distance 1" + kFast).code, 0);
    const nlohmann::json two = nlohmann::json::parse(readBytes(path("two.gltf")));
    const nlohmann::json one = nlohmann::json::parse(readBytes(path("one.gltf")));
    EXPECT_TRUE(two["meshes"][0]["primitives"][0]["attributes"].contains("_AO_LONG"));
    for (const auto& mesh : one["meshes"])
        for (const auto& prim : mesh["primitives"]) {
            EXPECT_TRUE(prim["attributes"].contains("_AO_SHORT")) << prim.dump();
            EXPECT_FALSE(prim["attributes"].contains("_AO_LONG")) << prim.dump();
        }
}

// A file without scenes whose node outside the tree names child 2000000000 (the loader never visits it)
// crashed the writer; an object whose only triangle was dropped as degenerate was written as an accessor of
// count 0 and a buffer view of 0 bytes, both invalid glTF.
TEST_F(BakeCli, GltfOutputSurvivesNodesOutsideTheTreeAndEmptiedMeshes) {
    const Result r = run("bake " + data("orphan_bad_child.gltf") + " -o " + path("o.gltf") + kFast);
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(obscura::loadScene(path("o.gltf")).triangleCount(), obscura::loadScene(data("orphan_bad_child.gltf")).triangleCount());
    const Result d = run("bake " + data("dropped_object.obj") + " -o " + path("d.gltf") + kFast);
    ASSERT_EQ(d.code, 0) << d.out;
    const nlohmann::json j = nlohmann::json::parse(readBytes(path("d.gltf")));
    for (const auto& a : j["accessors"]) EXPECT_GE(a["count"].get<int>(), 1) << a.dump();
    for (const auto& v : j["bufferViews"]) EXPECT_GE(v["byteLength"].get<int>(), 1) << v.dump();
    EXPECT_EQ(j["nodes"].size(), 1u);
}

// tinygltf never checks its writes: with the disk full (a 1 kB file size limit) a truncated .glb was renamed
// into place and the bake exited 0. Both writers now fail, naming the file, and leave nothing.
TEST_F(BakeCli, AFullDiskLeavesNoGltf) {
    const Result fromGltf = runWithFileSizeLimit("bake " + data("hierarchy.gltf") + " -o " + path("h.glb") + kFast, 1024);
    const Result fromObj = runWithFileSizeLimit("bake " + data("cube.obj") + " -o " + path("c.gltf") + kFast, 1024);
    // The .glb a scene is written to whole (not the input's edited JSON) said "would be 18446744073709551615
    // bytes, past the 4 GiB a .glb can state": its failed stream's position, -1.
    const Result objToGlb = runWithFileSizeLimit("bake " + data("cube.obj") + " -o " + path("c.glb") + kFast, 1024);
    EXPECT_EQ(objToGlb.code, 1) << objToGlb.out;
    EXPECT_NE(objToGlb.out.find("c.glb: write failed (disk full?)"), std::string::npos) << objToGlb.out;
    EXPECT_EQ(fromGltf.code, 1) << fromGltf.out;
    EXPECT_NE(fromGltf.out.find("h.glb: write failed"), std::string::npos) << fromGltf.out;
    EXPECT_EQ(fromObj.code, 1) << fromObj.out;
    EXPECT_NE(fromObj.out.find("c.gltf: write failed"), std::string::npos) << fromObj.out;
    EXPECT_EQ(entries(), 0u);
}
