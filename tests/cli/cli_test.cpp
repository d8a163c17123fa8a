// The obscura command line: each bad-input class gives one line naming the file or flag, a non-zero exit
// and no output file; good runs write what they promise.
#include "cli/cli_harness.h"
#include "obscura/image_io.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fs = std::filesystem;

namespace {

using Result = obscura::clitest::CliResult;

Result run(const std::string& args) { return obscura::clitest::runCli(args); }

std::string data(const std::string& name) { return std::string(OBSCURA_TEST_DATA) + "/" + name; }

class Cli : public obscura::clitest::CliTest {};

const std::string kFast = " --size 32x18 --ao-rays 4 -q ";

} // namespace

TEST_F(Cli, MissingSceneFile) { expectFailure("render " + path("nope.glb") + kFast + "-o " + path("f.png"), {"nope.glb", "no such file"}); }

TEST_F(Cli, UnknownSceneExtension) {
    write("scene.xyz", "hello");
    expectFailure("render " + path("scene.xyz") + kFast + "-o " + path("f.png"), {"scene.xyz", "unknown scene format"});
}

TEST_F(Cli, CorruptSceneFiles) {
    for (const char* bad : {"bad_json.gltf", "truncated.glb", "accessor_out_of_range.gltf", "bad_index.obj",
                            "truncated_binary.ply", "bad_header.ply"})
        expectFailure("render " + data(bad) + kFast + "-o " + path("f.png"), {bad});
}

TEST_F(Cli, EmptyMeshAndNonFiniteVertices) {
    expectFailure("render " + data("empty.obj") + kFast + "-o " + path("f.png"), {"empty.obj"});
    expectFailure("render " + data("nan_vertex.obj") + kFast + "-o " + path("f.png"), {"nan_vertex.obj", "finite"});
}

TEST_F(Cli, CorruptEnvironmentImages) {
    write("sky.exr", std::string("not an exr at all, just text"));
    expectFailure("render plane --env " + path("sky.exr") + kFast + "-o " + path("f.png"), {"sky.exr"});
    write("sky.hdr", std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 4\n\x02\x02"));
    expectFailure("render plane --env " + path("sky.hdr") + kFast + "-o " + path("f.png"), {"sky.hdr"});
    expectFailure("render plane --env " + path("missing.hdr") + kFast + "-o " + path("f.png"), {"missing.hdr"});
    // A PNG is display values, not radiance; it was read as radiance before.
    ASSERT_EQ(run("render plane --size 32x18 -q -o " + path("sky.png")).code, 0);
    expectFailure("render plane --env " + path("sky.png") + kFast + "-o " + path("f.png"),
                  {"--env: ", "sky.png: an environment's linear radiance is read from .hdr or .exr files, not .png"});
    EXPECT_FALSE(fs::exists(path("f.png")));
}

TEST_F(Cli, ZeroImageSize) {
    expectFailure("render plane --size 0x0 -q -o " + path("f.png"), {"--size", "at least 1x1"});
    expectFailure("gbuffer plane --size 64x0 -q -o " + path("g.exr"), {"--size"});
}

TEST_F(Cli, BadFlagValues) {
    expectFailure("render plane --size 32x18 -q --ao-rays 0 -o " + path("f.png"), {"ao-rays"});
    expectFailure("render plane --size 32x18 -q --fov 200 -o " + path("f.png"), {"--fov"});
    expectFailure("render plane" + kFast + "--ao-radius -1 -o " + path("f.png"), {"--ao-radius"});
    // The alchemy falloff's u was named "alchemy-u", a flag no command has.
    expectFailure("render plane" + kFast + "--ao-falloff alchemy --ao-u nan -o " + path("f.png"), {"ao-u: must be"});
    expectFailure("render plane" + kFast + "--camera-from 1,2 -o " + path("f.png"), {"--camera-from"});
    expectFailure("render plane" + kFast + "--ao bogus -o " + path("f.png"), {"--ao"}, 2);
    expectFailure("render plane --ao-rays 4 -q --size 12xfoo -o " + path("f.png"), {"--size"});
    expectFailure("render plane" + kFast + "-o " + path("f.jpg"), {"f.jpg", "unsupported output format"});
    // No extension at all read "unsupported output format ''".
    expectFailure("render plane" + kFast + "-o " + path("frame"), {"frame: has no extension", ".png"});
    expectFailure("render plane" + kFast + "-o " + path("nodir/f.png"), {"does not exist"});
    expectFailure("render nosuchscene" + kFast + "-o " + path("f.png"), {"nosuchscene"});
    // A command line that names no command, or none at all: exit 2, and the word that is no command named
    // (CLI11 said only "A subcommand is required"); `bench` alone exited 1 without "(see --help)".
    expectFailure("frobnicate -o " + path("f.png"), {"unknown command 'frobnicate'", "render", "(see --help)"}, 2);
    expectFailure("bench", {"bench: needs a subcommand", "(see --help)"}, 2);
}

// An empty value ("--threads $UNSET") is a command-line error in every command, not 0 for a number or "not given"
// for a path or a vector: the command would run on a setting nobody chose.
// A directory named like a built-in scene does not hide it (a file does): `gbuffer plane -o plane` writes one,
// and running it again failed with "plane: unknown scene format ''".
TEST_F(Cli, DirectoryNamedLikeABuiltInSceneDoesNotHideIt) {
    const fs::path before = fs::current_path();
    fs::current_path(dir);
    const Result first = run("gbuffer plane --size 16x12 -q -o plane");
    const Result again = run("gbuffer plane --size 16x12 -q -o plane");
    fs::current_path(before);
    EXPECT_EQ(first.code, 0) << first.out;
    EXPECT_EQ(again.code, 0) << again.out;
    EXPECT_TRUE(fs::exists(dir / "plane" / "depth.exr"));
    // Nor does a file that is no scene file (no built-in name has an extension): a stray `demo` (a build's binary)
    // in the working directory made a plain `obscura render` fail with "demo: unknown scene format ''".
    std::ofstream(dir / "demo") << "#!/bin/sh\n";
    fs::current_path(dir);
    const Result stray = run("render --size 16x12 -q -o stray.png");
    fs::current_path(before);
    EXPECT_EQ(stray.code, 0) << stray.out;
    EXPECT_TRUE(fs::exists(dir / "stray.png"));
}

TEST_F(Cli, EmptyValuesAreRefused) {
    const std::string out = " -o " + path("f.png");
    for (const char* flag : {"--threads", "--ao-radius", "--camera-from", "--aov-dir", "--env", "--size"})
        expectFailure("render plane" + kFast + flag + " \"\"" + out, {std::string(flag) + ": empty value"}, 2);
    expectFailure("gbuffer \"\" -q -o " + path("g.exr"), {"scene: empty value"}, 2);
    expectFailure("ao --depth \"\" --camera c.json -o " + path("a.exr"), {"--depth: empty value"}, 2);
    expectFailure("bench --gpu --sizes \"\"", {"--sizes: empty value"}, 2);
    EXPECT_FALSE(fs::exists(path("f.png")));
    EXPECT_FALSE(fs::exists(path("g.exr")));
    // Flags that take no value are untouched, and the defaults of options not given are not values.
    const Result ok = run("render plane" + kFast + out);
    EXPECT_EQ(ok.code, 0) << ok.out;
}

TEST_F(Cli, RenderWritesFrameAndAovs) {
    Result r = run("render demo" + kFast + "-o " + path("f.png") + " --aov-dir " + path("aov"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(fs::is_regular_file(path("f.png")));
    for (const char* f : {"ao.exr", "depth.exr", "normal.exr", "albedo.exr", "lighting.exr", "camera.json"})
        EXPECT_TRUE(fs::is_regular_file(path("aov/") + f)) << f;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

// Each falloff of --ao raytraced reads its own parameters: exponential d alone (its rays reach 24 d), binary r,
// alchemy r and u. The others' flags changed nothing, and the summary echoed the ignored r as if it had
// applied; now each is a warning and the summary names what the falloff read.
// A flag said to be ignored is not then refused for its value: "--ao-distance: ... ignored" was followed by
// "error: --ao-distance: must be a finite value > 0". Flags that are read are still checked, and first:
// --supersample 0 was refused only after the scene and the environment had been read.
TEST_F(Cli, IgnoredFlagsAreNotValidated) {
    const std::string render = "render plane --size 16x9 -q -o " + path("f.png") + " ";
    for (const auto& [args, warning] : std::vector<std::pair<std::string, std::string>>{
             {"--ao none --ao-distance -1", "--ao-distance: applies to --ao raytraced"},
             {"--ao alchemy --ao-rays 0", "--ao-rays: applies to --ao raytraced"},
             {"--ao none --ao-falloff alchemy --ao-u -5", "--ao-u: applies to --ao raytraced"},
             {"--ao raytraced --ao-distance -1", "--ao-distance: applies to --ao-falloff exponential"},
             {"--ao-falloff exponential --ao-radius -1", "--ao-radius: applies to the binary and alchemy falloffs"},
             {"--ao none --ao-radius -1", "--ao-radius: applies to --ao raytraced, alchemy or gtao, not --ao none"}}) {
        const Result r = run(render + args);
        EXPECT_EQ(r.code, 0) << args << "\n" << r.out;
        EXPECT_NE(r.out.find("warning: " + warning), std::string::npos) << args << "\n" << r.out;
        EXPECT_EQ(r.out.find("obscura: error"), std::string::npos) << args << "\n" << r.out;
    }
    const Result exr = run("render plane --size 16x9 --ao-rays 4 -q -o " + path("f.exr") + " --exposure 100");
    EXPECT_EQ(exr.code, 0) << exr.out;
    EXPECT_NE(exr.out.find("warning: --exposure: applies to a PNG"), std::string::npos) << exr.out;
    expectFailure(render + "--ao raytraced --ao-distance -1 --ao-falloff exponential", {"--ao-distance", "> 0"});
    expectFailure(render + "--exposure 100", {"--exposure", "[-20, 20]", "100"});
    expectFailure(render + "--supersample 0 --env " + path("nosuch.exr"), {"--supersample", "[1, 16]", "got 0"});
}

TEST_F(Cli, RayTracedFalloffsWarnOfTheParametersTheyDoNotRead) {
    const std::string render = "render ceiling --size 16x9 --ao-rays 4 -o " + path("f.png") + " --ao raytraced ";
    Result r = run(render + "--ao-falloff exponential --ao-radius 0.01 --ao-distance 3");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("warning: --ao-radius: applies to the binary and alchemy falloffs, not --ao-falloff exponential"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("(exponential, d = 3 m, 4 rays)"), std::string::npos) << r.out;
    r = run(render + "--ao-falloff binary --ao-radius 2 --ao-distance 3 --ao-u 0.2");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("warning: --ao-distance: applies to --ao-falloff exponential, not --ao-falloff binary"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("warning: --ao-u: applies to --ao-falloff alchemy, not --ao-falloff binary"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("(binary, r = 2 m, 4 rays)"), std::string::npos) << r.out;
    r = run(render + "--ao-falloff alchemy --ao-radius 2 --ao-u 0.2");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("(alchemy, r = 2 m, u = 0.2 m, 4 rays)"), std::string::npos) << r.out;
}

// A closed box of side `size` m centred on (x, 0, 0), faces inward, as OBJ text.
std::string boxObj(double x, double size) {
    const double h = 0.5 * size;
    std::string obj;
    for (int k = 0; k < 8; ++k) {
        char line[128];
        std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", x + ((k & 1) ? h : -h), (k & 2) ? h : -h, (k & 4) ? h : -h);
        obj += line;
    }
    // Inward-facing quads (a room seen from inside), as triangles.
    obj += "f 1 2 4\nf 1 4 3\nf 5 7 8\nf 5 8 6\nf 1 5 6\nf 1 6 2\nf 3 4 8\nf 3 8 7\nf 1 3 7\nf 1 7 5\nf 2 6 8\nf 2 8 4\n";
    return obj;
}

// Far from the origin float precision runs out: rays leave each surface 2.5e-7 x 4 of its largest coordinate
// off it, and a room 1e7 m out traced AO of exactly 1 everywhere (at the origin, mean 0.82), bake likewise. Past
// a quarter of the reach it is an error naming the flag; from 1% a warning; near the origin nothing.
TEST_F(Cli, RayTracedAoFarFromTheOriginIsRefusedOrWarned) {
    write("far.obj", boxObj(1e7, 8));
    write("mid.obj", boxObj(5e4, 8));
    write("near.obj", boxObj(0, 8));
    const std::string flags = " --size 16x9 --ao-rays 4 -q --ao raytraced --ao-radius 1 -o " + path("f.png");
    expectFailure("render " + path("far.obj") + flags + " --camera-from 10000001,0,1 --camera-to 10000000,0,0",
                  {"--ao-radius", "far.obj is so far from the origin", "move the scene nearer the origin"});
    expectFailure("bake " + path("far.obj") + " -o " + path("b.csv") + " --rays 4 -q --distance 1",
                  {"--distance", "far.obj is so far from the origin"});
    Result r = run("render " + path("mid.obj") + flags + " --camera-from 50001,0,1 --camera-to 50000,0,0");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("warning: --ao-radius: " + path("mid.obj") + " is so far from the origin"), std::string::npos)
        << r.out;
    r = run("render " + path("near.obj") + flags + " --camera-from 1,0,1 --camera-to 0,0,0");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
}

// The default framing and a moved camera keep the scene between the near and far planes: a 40 um room was
// framed with a near plane of 0.1 mm, past the room, and a camera moved 300 m out by --camera-from kept the
// default framing's far plane (208 m for this 8 m room); both rendered as sky without a word.
TEST_F(Cli, TheCameraKeepsTheSceneBetweenItsPlanes) {
    write("tiny.obj", boxObj(0, 4e-5));
    write("room.obj", boxObj(0, 8));
    const auto surfacePixels = [&](const std::string& args) {
        const Result r = run(args + " --size 16x9 --ao-rays 4 -q -o " + path("f.png") + " --aov-dir " + path("aov"));
        EXPECT_EQ(r.code, 0) << r.out;
        const obscura::Image depth = obscura::readExr(path("aov/depth.exr"));
        return std::count_if(depth.pixels.begin(), depth.pixels.end(), [](float d) { return std::isfinite(d); });
    };
    EXPECT_GT(surfacePixels("render " + path("tiny.obj")), 0);
    EXPECT_GT(surfacePixels("render " + path("room.obj") + " --camera-from 0,1,300 --camera-to 0,0,0 --fov 5"), 0);
}

// A view of only sky has no pixel to measure: compare reported MAE, RMSE and max of 0 and exit 0, which a script
// reads as exact agreement. It is an error naming the scene, and nothing is written.
TEST_F(Cli, CompareRefusesAViewOfOnlySky) {
    expectFailure("compare plane --size 16x9 --rays 4 -q --camera-from 0,3,0 --camera-to 0,10,0.1 -o " + path("c.png"),
                  {"plane", "every pixel is sky: nothing to compare"});
}

// --aov-dir never replaces an input or the -o output, as -o itself may not: the environment read from the AOV
// folder stayed and exit 0 wrote the lighting AOV over it; -o into the folder as ao.exr held the colour frame.
TEST_F(Cli, AovDirNeverOverwritesAnInputOrTheOutput) {
    ASSERT_EQ(run("render plane" + kFast + "-o " + path("f.png") + " --aov-dir " + path("aov")).code, 0);
    const std::string env = path("aov/lighting.exr");  // a 3-channel EXR: an environment the render reads
    const auto bytes = obscura::clitest::fileBytes;
    const std::string before = bytes(env);
    expectFailure("render corner --env " + env + kFast + "-o " + path("g.png") + " --aov-dir " + path("aov"),
                  {"lighting.exr", "is the input file"});
    EXPECT_EQ(bytes(env), before);
    EXPECT_FALSE(fs::exists(path("g.png")));
    expectFailure("render corner" + kFast + "-o " + path("aov/./ao.exr") + " --aov-dir " + path("aov"),
                  {"ao.exr", "is the output"});
}

// Relative paths that do not exist yet are the same file too: `--aov-dir . -o ao.exr` wrote the colour frame
// over the AO AOV with exit 0 (the paths were compared relative, "ao.exr" against "./ao.exr"); the refusal
// came only on a second run, once the files existed.
TEST_F(Cli, AovDirSeesTheOutputThroughRelativePaths) {
    const fs::path before = fs::current_path();
    fs::current_path(dir);
    const std::size_t empty = entries();
    const Result ao = run("render plane" + kFast + "--ao none --aov-dir . -o ao.exr");
    const Result depth = run("render plane" + kFast + "--ao none --aov-dir " + dir.string() + " -o depth.exr");
    const Result file = run("render plane" + kFast + "--ao none --aov-dir ./f.exr -o f.exr");
    const std::size_t after = entries();
    fs::current_path(before);
    EXPECT_EQ(ao.code, 1) << ao.out;
    EXPECT_NE(ao.out.find("ao.exr: is the output"), std::string::npos) << ao.out;
    EXPECT_EQ(depth.code, 1) << depth.out;
    EXPECT_NE(depth.out.find("depth.exr: is the output"), std::string::npos) << depth.out;
    EXPECT_EQ(file.code, 1) << file.out;
    EXPECT_NE(file.out.find("is the -o output"), std::string::npos) << file.out;
    EXPECT_EQ(after, empty);
}

// An output directory that takes no new file fails before the work, in every command: compare traced its
// references first and then failed on -o /proc/x.png, losing --json's figures; only bake checked.
TEST_F(Cli, AnUnwritableOutputDirectoryFailsFirst) {
    expectFailure("compare corner --size 8x6 --rays 4 -q --json -o /proc/x.png", {"/proc/x.png", "cannot write"});
    expectFailure("render corner" + kFast + "-o /proc/x.png", {"/proc/x.png", "cannot write"});
    expectFailure("gbuffer corner --size 8x6 -q -o /proc/g.exr", {"/proc/g", "cannot write"});
    expectFailure("scenes --generate level --triangles 4000 -o /proc/l.glb", {"/proc/l.glb", "cannot write"});
    // Output directories too: gbuffer -o /proc/gdir rendered first, and render --aov-dir on a directory that
    // takes no file traced the whole frame.
    expectFailure("gbuffer corner --size 8x6 -q -o /proc/gdir", {"/proc/gdir", "cannot be made", "takes no new file"});
    expectFailure("render corner" + kFast + "-o " + path("f.png") + " --aov-dir /proc/self/fdinfo",
                  {"/proc/self/fdinfo", "directory takes no new file"});
}

// gbuffer writes its files all or none: a failed camera.json removed the new EXR and with it the previous one it
// had replaced, and in a directory a failed albedo.exr removed depth.exr and normal.exr and left an old
// camera.json. A name too long for the file system failed only after the render (now before), and an existing
// directory whose name has a dot was refused as an "unsupported output format".
TEST_F(Cli, GBufferWritesAllOrNone) {
    ASSERT_EQ(run("gbuffer plane --size 16x12 -q -o " + path("g.exr")).code, 0);
    const auto bytes = obscura::clitest::fileBytes;
    const std::string exr = bytes(path("g.exr")), json = bytes(path("g.camera.json"));
    // The camera's file cannot be made: a directory of its name. checkOutputPath refuses that before the work, so
    // this holds the up-front check; the writer's own all-or-none is ImageIoTest.FilesWrittenTogetherAreAllOrNone.
    fs::remove(path("g.camera.json"));
    fs::create_directory(path("g.camera.json"));
    const Result blocked = run("gbuffer corner --size 24x12 -q -o " + path("g.exr"));
    EXPECT_EQ(blocked.code, 1) << blocked.out;
    EXPECT_EQ(bytes(path("g.exr")), exr) << "the previous EXR was replaced or removed";
    fs::remove(path("g.camera.json"));
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
    std::ofstream(path("g.camera.json"), std::ios::binary) << json;
    // A name past 255 bytes: refused before the work.
    const std::string longName = std::string(250, 'a') + ".exr";  // its camera: 250 + 12 bytes
    expectFailure("gbuffer plane --size 16x12 -q -o " + path(longName), {"the file name is 262 bytes, past the 255"});
    // An existing directory named with a dot takes the four files.
    fs::create_directory(path("out.d"));
    const Result toDir = run("gbuffer plane --size 16x12 -q -o " + path("out.d"));
    EXPECT_EQ(toDir.code, 0) << toDir.out;
    for (const char* f : {"depth.exr", "normal.exr", "albedo.exr", "camera.json"})
        EXPECT_TRUE(fs::is_regular_file(path("out.d/") + f)) << f;
    expectFailure("gbuffer plane --size 16x12 -q --supersample 0 -o " + path("s.exr"), {"--supersample", "got 0"});
}

// `ao` refuses normals turned away from the camera (another convention, +Z forward or world space: Alchemy
// moved by 0.40 on average without a word), says that --normal goes unread beside --ao-normals-from-depth, and
// warns of blur flags with --blur none.
TEST_F(Cli, AoChecksTheNormalsItReads) {
    ASSERT_EQ(run("gbuffer demo --size 48x27 -q -o " + path("g.exr")).code, 0);
    obscura::Image g = obscura::readExr(path("g.exr"));
    obscura::Image flipped(g.width, g.height, 3);
    flipped.channelNames = {"N.X", "N.Y", "N.Z"};
    for (int c = 0; c < 3; ++c) {
        const auto at = std::find(g.channelNames.begin(), g.channelNames.end(), flipped.channelNames[std::size_t(c)]);
        ASSERT_NE(at, g.channelNames.end());
        const int from = int(at - g.channelNames.begin());
        for (int y = 0; y < g.height; ++y)
            for (int x = 0; x < g.width; ++x) flipped.at(x, y, c) = -g.at(x, y, from);
    }
    obscura::writeExr(path("flipped.exr"), flipped);
    const std::string ao = "ao --depth " + path("g.exr") + " --camera " + path("g.camera.json") + " -o " + path("a.exr");
    expectFailure(ao + " --normal " + path("flipped.exr"), {"flipped.exr", "normals face away from the camera"});
    const Result unread = run(ao + " --normal " + path("flipped.exr") + " --ao-normals-from-depth");
    EXPECT_EQ(unread.code, 0) << unread.out;
    EXPECT_NE(unread.out.find("warning: --normal: --ao-normals-from-depth rebuilds the normals"), std::string::npos)
        << unread.out;
    const Result blur = run(ao + " --normal " + path("g.exr") + " --blur none --blur-radius 10");
    EXPECT_EQ(blur.code, 0) << blur.out;
    EXPECT_NE(blur.out.find("warning: --blur-radius: applies to a blur, and --blur is none"), std::string::npos)
        << blur.out;
    EXPECT_EQ(run(ao + " --normal " + path("g.exr")).code, 0);
}

// --far inf wrote g.camera.json with "far": null, which `obscura ao --camera` then refused.
TEST_F(Cli, InfiniteFarIsRefused) {
    expectFailure("gbuffer plane --size 16x8 -q --far inf -o " + path("g.exr"), {"far"});
}

// 0 was the "not given" sentinel: --fov 0 ran at the scene's 60 degrees, --near 0 / --far 0 at 0.01 / 1e4.
TEST_F(Cli, ZeroFovNearFarAreRefusedNotDefaulted) {
    expectFailure("gbuffer plane --size 16x8 -q --fov 0 -o " + path("g.exr"), {"--fov"});
    expectFailure("gbuffer plane --size 16x8 -q --near 0 -o " + path("g.exr"), {"near"});
    expectFailure("gbuffer plane --size 16x8 -q --far 0 -o " + path("g.exr"), {"far"});
}

// A failing gbuffer left its output directory (nested ones too) or half its files behind.
TEST_F(Cli, FailedGBufferLeavesNothing) {
    expectFailure("gbuffer nosuchscene.obj -q -o " + path("out"), {"nosuchscene.obj"});
    expectFailure("gbuffer plane --fov 200 -q -o " + path("a/b/c"), {"--fov"});
    std::filesystem::create_directories(path("g.camera.json"));
    expectFailure("gbuffer plane --size 16x8 -q -o " + path("g.exr"), {"g.camera.json", "directory"});
    EXPECT_FALSE(std::filesystem::exists(path("g.exr")));
    std::filesystem::create_directories(path("d/normal.exr"));
    expectFailure("gbuffer plane --size 16x8 -q -o " + path("d"), {"normal.exr", "directory"});
    EXPECT_FALSE(std::filesystem::exists(path("d/depth.exr")));
}

TEST_F(Cli, DegenerateTrianglesAreAWarning) {
    Result r = run("render " + data("degenerate.obj") + kFast + "-o " + path("f.png"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("warning"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("dropped 1 degenerate triangle"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::is_regular_file(path("f.png")));
}

TEST_F(Cli, GBufferFileAndDirectory) {
    Result r = run("gbuffer corner --size 40x30 -q -o " + path("g.exr"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(fs::is_regular_file(path("g.exr")));
    EXPECT_TRUE(fs::is_regular_file(path("g.camera.json")));
    r = run("gbuffer " + data("quad.gltf") + " --size 40x30 -q -o " + path("split"));
    ASSERT_EQ(r.code, 0) << r.out;
    for (const char* f : {"depth.exr", "normal.exr", "albedo.exr", "camera.json"})
        EXPECT_TRUE(fs::is_regular_file(path("split/") + f)) << f;
}

TEST_F(Cli, ScenesListsEveryBuiltin) {
    Result r = run("scenes");
    ASSERT_EQ(r.code, 0);
    for (const char* name : {"plane", "corner", "well", "stairs", "spheres", "cabinet", "ceiling", "demo"})
        EXPECT_NE(("\n" + r.out).find(std::string("\n") + name + " "), std::string::npos) << name << " missing in\n" << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 8);
    // -o without --generate was ignored (the list printed, nothing written); --triangles -1 was reported as
    // 18446744073709551615.
    expectFailure("scenes -o " + path("x.glb"), {"--output", "give --generate level"});
    expectFailure("scenes --triangles 5", {"--triangles", "give --generate level"});  // listed the scenes, exit 0
    expectFailure("scenes --seed 9", {"--seed", "give --generate level"});
    expectFailure("scenes --generate level --triangles -1 -o " + path("x.glb"),
                  {"--triangles: must be in [4000, 200000000], got -1"});
    // The budget as --help writes it, "2e8", was "Could not convert"; a huge one was quoted as 2^63 - 1.
    expectFailure("scenes --generate level --triangles 99999999999999999999 -o " + path("x.glb"),
                  {"--triangles: must be in [4000, 200000000], got 99999999999999999999"});
    expectFailure("scenes --generate level --triangles 4.5e3.1 -o " + path("x.glb"),
                  {"--triangles: expected a whole number of triangles", "got \"4.5e3.1\""});
    expectFailure("scenes --generate level --triangles 4000.5 -o " + path("x.glb"), {"expected a whole number"});
    // Past about 1.58e8 triangles a .glb cannot state its length: refused before generating, not after.
    expectFailure("scenes --generate level --triangles 1.6e8 -o " + path("x.glb"),
                  {"--triangles: 160000000 would make a .glb past the 4 GiB", "write .gltf"});
    const Result small = run("scenes --generate level --triangles 4.5e3 -o " + path("small.glb"));
    EXPECT_EQ(small.code, 0) << small.out;
    EXPECT_NE(small.out.find("level with "), std::string::npos) << small.out;
}

TEST_F(Cli, HelpExplains) {
    Result r = run("render --help");
    EXPECT_EQ(r.code, 0);
    for (const char* flag : {"--ao", "--ao-radius", "--ao-rays", "--size", "--camera-from", "--camera-to", "--fov",
                             "--env", "--aov-dir"})
        EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
}

// An output path that names one of the command's inputs is refused before any work, and the input keeps its
// bytes: ao and render once replaced their depth buffer or environment map with their result and exited 0
// (bake already refused its input). The same file under another spelling (./name) counts.
TEST_F(Cli, OutputIsNeverAnInput) {
    const auto bytes = obscura::clitest::fileBytes;
    ASSERT_EQ(run("gbuffer corner --size 24x16 -q -o " + path("g")).code, 0);
    const std::string depth = path("g/depth.exr"), camera = path("g/camera.json");
    const std::string before = bytes(depth);
    ASSERT_FALSE(before.empty());
    expectFailure("ao --depth " + depth + " --camera " + camera + " -o " + depth, {"depth.exr", "is the input file"});
    expectFailure("ao --depth " + depth + " --normal " + path("g/normal.exr") + " --camera " + camera + " -o " +
                      path("g/./normal.exr"),
                  {"normal.exr", "is the input file"});
    expectFailure("render corner --env " + depth + kFast + "-o " + depth, {"depth.exr", "is the input file"});
    EXPECT_EQ(bytes(depth), before);
    {
        std::ofstream copy(path("quad.gltf"), std::ios::binary);
        copy << bytes(data("quad.gltf"));
    }
    expectFailure("bake " + path("quad.gltf") + " -q -o " + path("quad.gltf"), {"quad.gltf", "is the input file"});
}

// A render that fails on its flags or its output path leaves nothing behind: --aov-dir's directory was made
// before the flags were checked, and an output path naming a directory failed only after the AOVs had been
// written.
TEST_F(Cli, FailedRenderLeavesNoAovs) {
    expectFailure("render corner" + kFast + "--aov-dir " + path("new/a/b") + " --exposure 99 -o " + path("f.png"),
                  {"--exposure"});
    EXPECT_FALSE(std::filesystem::exists(path("new")));
    std::filesystem::create_directory(path("f.png"));
    expectFailure("render corner" + kFast + "--aov-dir " + path("aov") + " -o " + path("f.png"),
                  {"f.png", "is a directory"});
    // Nor on its inputs: the directory was made before the scene and the environment were read.
    expectFailure("render " + path("nosuch.glb") + kFast + "--aov-dir " + path("aov2") + " -o " + path("g.png"),
                  {"nosuch.glb"});
    EXPECT_FALSE(std::filesystem::exists(path("aov2")));
    expectFailure("render corner" + kFast + "--env " + path("nosuch.hdr") + " --aov-dir " + path("aov3") + " -o " +
                      path("g.png"),
                  {"nosuch.hdr"});
    EXPECT_FALSE(std::filesystem::exists(path("aov3")));
    // Nor on its AOVs: -o may not be one of GTAO's (bent_normal.exr was overwritten by the frame, exit 0), nor
    // the AOV directory itself (its six files were written before -o failed), and an AOV that is a directory
    // is refused before the work (four files were left behind).
    std::filesystem::create_directory(path("d1"));
    expectFailure("render corner --ao gtao --ao-output bent-normal --size 32x18 -q --aov-dir " + path("d1") + " -o " +
                      path("d1/bent_normal.exr"),
                  {"bent_normal.exr", "is the output"});
    expectFailure("render corner --ao gtao --frames 2 --size 32x18 -q --aov-dir " + path("d1") + " -o " +
                      path("d1/ao_0001.exr"),
                  {"ao_0001.exr", "is the output"});
    expectFailure("render corner" + kFast + "--aov-dir " + path("same.png") + " -o " + path("same.png"),
                  {"--aov-dir", "is the -o output"});
    std::filesystem::create_directories(path("d1/lighting.exr"));
    expectFailure("render corner" + kFast + "--aov-dir " + path("d1") + " -o " + path("g.png"),
                  {"lighting.exr", "is a directory"});
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(path("d1")), std::filesystem::directory_iterator()), 1);
}

// --exposure and --tonemap shape a PNG's display values; an .exr output is linear radiance and took them without
// a word. They are warned about there, and the EXR is the one written without them.
TEST_F(Cli, DisplayFlagsOnAnExrOutputAreWarnedAbout) {
    const auto plain = run("render corner" + kFast + "-o " + path("a.exr"));
    ASSERT_EQ(plain.code, 0) << plain.out;
    const auto flagged = run("render corner" + kFast + "--exposure 2 --tonemap reinhard -o " + path("b.exr"));
    ASSERT_EQ(flagged.code, 0) << flagged.out;
    EXPECT_NE(flagged.out.find("warning: --exposure: applies to a PNG"), std::string::npos) << flagged.out;
    EXPECT_NE(flagged.out.find("warning: --tonemap: applies to a PNG"), std::string::npos) << flagged.out;
    EXPECT_EQ(plain.out.find("warning"), std::string::npos) << plain.out;
    EXPECT_EQ(obscura::readExr(path("a.exr")).pixels, obscura::readExr(path("b.exr")).pixels);
    const auto png = run("render corner" + kFast + "--exposure 2 -o " + path("c.png"));
    ASSERT_EQ(png.code, 0) << png.out;
    EXPECT_EQ(png.out.find("warning"), std::string::npos) << png.out;
}

// A scene file that float cannot frame by default (a triangle 1e-30 m across) is named with what went wrong;
// the error once blamed "camera flags" that were never given. Given flags that fail are still theirs.
TEST_F(Cli, UnframableSceneIsNamed) {
    {
        std::ofstream obj(path("tiny.obj"));
        obj << "v 0 0 0\nv 1e-30 0 0\nv 0 1e-30 0\nf 1 2 3\n";
    }
    expectFailure("gbuffer " + path("tiny.obj") + " --size 16x12 -q -o " + path("g.exr"),
                  {"tiny.obj: cannot be framed by the default camera", "--camera-from"});
    expectFailure("gbuffer corner --size 16x12 --camera-from 1,1,1 --camera-to 1,1,1 -q -o " + path("g.exr"),
                  {"camera flags: position and target coincide"});
}
