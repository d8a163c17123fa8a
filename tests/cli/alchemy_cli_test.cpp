// `obscura render --ao alchemy`, `obscura ao` and `obscura compare`: good runs write what they promise (the
// AO of `ao` on a render's own buffers is the render's AO bit for bit); bad input gives one line naming the
// file or flag, a non-zero exit and no output.
#include "obscura/image_io.h"

#include "cli/cli_harness.h"
#include "scoped_env.h"

#include "obscura/gpu.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace {

using Result = obscura::clitest::CliResult;

Result run(const std::string& args) { return obscura::clitest::runCli(args); }

class AlchemyCli : public obscura::clitest::CliTest {};

} // namespace

TEST_F(AlchemyCli, RenderAndAoAgreeBitForBit) {
    for (const std::string blur : {"none", "separable", "2d"}) {
        Result r = run("render demo --size 64x36 -q --ao alchemy --ao-samples 16 --blur " + blur + " -o " +
                       path("f.png") + " --aov-dir " + path("aov"));
        ASSERT_EQ(r.code, 0) << r.out;
        EXPECT_NE(r.out.find("16 samples"), std::string::npos) << r.out;
        r = run("ao --depth " + path("aov/depth.exr") + " --normal " + path("aov/normal.exr") + " --camera " +
                path("aov/camera.json") + " --ao-samples 16 --blur " + blur + " -o " + path("ao.exr"));
        ASSERT_EQ(r.code, 0) << r.out;
        obscura::Image a = obscura::readExr(path("aov/ao.exr")), b = obscura::readExr(path("ao.exr"));
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_EQ(a.pixels, b.pixels) << blur;
        double mean = 0;
        for (float v : a.pixels) mean += double(v);
        EXPECT_LT(mean / double(a.pixels.size()), 0.99);  // the room has occlusion
    }
}

// Normals from another tool are often stored under R, G, B, which an EXR keeps as B, G, R: read in that order,
// x and z swapped and the AO changed. Under either names, and as RGBA, the AO is the render's own.
TEST_F(AlchemyCli, NormalsNamedRgbAreReadAsXyz) {
    Result r = run("render demo --size 64x36 -q --ao alchemy --ao-samples 16 --blur none -o " + path("f.png") +
                   " --aov-dir " + path("aov"));
    ASSERT_EQ(r.code, 0) << r.out;
    obscura::Image normal = obscura::readExr(path("aov/normal.exr"));
    ASSERT_EQ(normal.channelNames, (std::vector<std::string>{"X", "Y", "Z"}));
    normal.channelNames = {"R", "G", "B"};
    obscura::writeExr(path("rgb-normal.exr"), normal);
    r = run("ao --depth " + path("aov/depth.exr") + " --normal " + path("rgb-normal.exr") + " --camera " +
            path("aov/camera.json") + " --ao-samples 16 --blur none -o " + path("ao.exr"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(obscura::readExr(path("ao.exr")).pixels, obscura::readExr(path("aov/ao.exr")).pixels);

    // As an engine dumps them: R, G, B and an alpha, which is left out.
    obscura::Image rgba(normal.width, normal.height, 4, 1.0f);
    rgba.channelNames = {"R", "G", "B", "A"};
    for (std::size_t i = 0; i < normal.pixelCount(); ++i)
        for (std::size_t c = 0; c < 3; ++c) rgba.pixels[4 * i + c] = normal.pixels[3 * i + c];
    obscura::writeExr(path("rgba-normal.exr"), rgba);
    r = run("ao --depth " + path("aov/depth.exr") + " --normal " + path("rgba-normal.exr") + " --camera " +
            path("aov/camera.json") + " --ao-samples 16 --blur none -o " + path("ao.exr"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(obscura::readExr(path("ao.exr")).pixels, obscura::readExr(path("aov/ao.exr")).pixels);
    // Four channels of which the last is no alpha are still refused.
    rgba.channelNames = {"R", "G", "B", "W"};
    obscura::writeExr(path("rgbw-normal.exr"), rgba);
    expectFailure("ao --depth " + path("aov/depth.exr") + " --normal " + path("rgbw-normal.exr") + " --camera " +
                      path("aov/camera.json") + " -o " + path("x.exr"),
                  {"rgbw-normal.exr", "normal needs 3 channels, has 4"});
}

// G-buffers as renderers write them. A depth beside colour channels (R, G, B, A and Z) or an alpha (A, Z) was
// refused though --help promised "a channel named Z"; a normal buffer's alpha before X, Y, Z (XYZA) too. Each
// now gives the render's own AO. A normal buffer passed as --depth is still refused, naming its channels. A sky
// written as the far plane (1e4) blamed the normals, whose zero there was never wrong; camera.json numbers past
// the float range were reported as the infinity they were cast to; a depth whose data window is offset in its
// display window was read as if it began at the origin.
TEST_F(AlchemyCli, GBufferFilesAsRenderersWriteThem) {
    Result r = run("render demo --size 48x32 -q --ao alchemy --ao-samples 8 --blur none -o " + path("f.png") +
                   " --aov-dir " + path("aov"));
    ASSERT_EQ(r.code, 0) << r.out;
    const obscura::Image depth = obscura::readExr(path("aov/depth.exr")), normal = obscura::readExr(path("aov/normal.exr"));
    const obscura::Image expected = obscura::readExr(path("aov/ao.exr"));
    const std::string camera = " --camera " + path("aov/camera.json") + " --ao-samples 8 --blur none -o " + path("ao.exr");
    const auto packed = [](const obscura::Image& from, std::vector<std::string> names, int at, float fill) {
        obscura::Image out(from.width, from.height, int(names.size()), fill);
        out.channelNames = std::move(names);
        for (std::size_t i = 0; i < from.pixelCount(); ++i)
            for (int c = 0; c < from.channels; ++c)
                out.pixels[i * std::size_t(out.channels) + std::size_t(at + c)] = from.pixels[i * std::size_t(from.channels) + std::size_t(c)];
        return out;
    };
    // readExr orders a layer R, G, B, A, then X, Y, Z: the depth lands last, the normals' alpha first.
    obscura::writeExr(path("rgbaz.exr"), packed(depth, {"R", "G", "B", "A", "Z"}, 4, 0.5f));
    obscura::writeExr(path("az.exr"), packed(depth, {"A", "Z"}, 1, 1.0f));
    obscura::writeExr(path("xyza.exr"), packed(normal, {"A", "X", "Y", "Z"}, 1, 1.0f));
    for (const auto& [d, n] : {std::pair{"rgbaz.exr", "aov/normal.exr"}, std::pair{"az.exr", "xyza.exr"}}) {
        r = run(std::string("ao --depth ") + path(d) + " --normal " + path(n) + camera);
        ASSERT_EQ(r.code, 0) << d << " " << n << ": " << r.out;
        EXPECT_EQ(obscura::readExr(path("ao.exr")).pixels, expected.pixels) << d << " " << n;
    }
    expectFailure("ao --depth " + path("aov/normal.exr") + camera,
                  {"normal.exr", "depth needs 1 channel or one named Z, has 3 (X, Y, Z)"});

    obscura::Image farPlane = depth;
    for (float& d : farPlane.pixels)
        if (std::isinf(d)) d = 1e4f;
    obscura::writeExr(path("far.exr"), farPlane);
    expectFailure("ao --depth " + path("far.exr") + " --normal " + path("aov/normal.exr") + camera,
                  {"normal.exr", "is zero where", "far.exr has depth 10000", "write sky as +inf"});

    std::ifstream in(path("aov/camera.json"));
    nlohmann::json json = nlohmann::json::parse(in);
    json["position"][0] = 1e39;
    std::ofstream(path("far-camera.json")) << json.dump();
    expectFailure("ao --depth " + path("aov/depth.exr") + " --camera " + path("far-camera.json") + " -o " + path("x.exr"),
                  {"far-camera.json", "\"position\" is 1e+39, beyond what a float holds"});

    {
        const Imath::Box2i display({0, 0}, {depth.width - 1, depth.height - 1});
        const Imath::Box2i data({5, 3}, {depth.width + 4, depth.height + 2});
        Imf::Header header(display, data);
        header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
        Imf::FrameBuffer frame;
        char* base = reinterpret_cast<char*>(const_cast<float*>(depth.pixels.data())) -
                     (std::ptrdiff_t(data.min.y) * depth.width + data.min.x) * std::ptrdiff_t(sizeof(float));
        frame.insert("Z", Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * std::size_t(depth.width)));
        Imf::OutputFile out(path("offset.exr").c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(depth.height);
    }
    expectFailure("ao --depth " + path("offset.exr") + camera,
                  {"offset.exr", "data window (5, 3)-(52, 34) is not its display window (0, 0)-(47, 31)"});
}

// What `ao` once took or refused without reason: --method alchemy-chapter with --ao-formulation paper ran the
// chapter's formulation without a word (and --method alchemy with chapter printed "alchemy"); a NaN normal
// under a sky pixel, which is never read, was refused, and a NaN under a surface was named by a linear index;
// a guard band wider than the buffers was refused without naming its flag.
TEST_F(AlchemyCli, AoRefusesContradictionsAndReadsOnlySurfaceNormals) {
    Result r = run("render demo --size 48x32 -q --ao alchemy --ao-samples 8 --blur none -o " + path("f.png") +
                   " --aov-dir " + path("aov"));
    ASSERT_EQ(r.code, 0) << r.out;
    const std::string in = "ao --depth " + path("aov/depth.exr") + " --camera " + path("aov/camera.json") +
                           " --ao-samples 8 --blur none ";
    expectFailure(in + "--method alchemy-chapter --ao-formulation paper -o " + path("x.exr"),
                  {"--ao-formulation", "contradicts --method alchemy-chapter"});
    expectFailure(in + "--method alchemy --ao-formulation chapter -o " + path("x.exr"),
                  {"--ao-formulation", "contradicts --method alchemy"});
    // A preset is the chapter's calibration: with --method alchemy it switched to the chapter's formulation
    // without a word. With alchemy-chapter it runs.
    expectFailure(in + "--method alchemy --ao-preset scene -o " + path("x.exr"),
                  {"--ao-preset", "--method alchemy-chapter"});
    ASSERT_EQ(run(in + "--method alchemy-chapter --ao-preset scene -o " + path("p.exr")).code, 0);
    r = run(in + "--method alchemy-chapter --ao-formulation chapter --normal " + path("aov/normal.exr") + " -o " +
            path("a.exr"));
    ASSERT_EQ(r.code, 0) << r.out;
    r = run(in + "--method alchemy-chapter --normal " + path("aov/normal.exr") + " -o " + path("b.exr"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(obscura::readExr(path("a.exr")).pixels, obscura::readExr(path("b.exr")).pixels);

    const obscura::Image depth = obscura::readExr(path("aov/depth.exr"));
    obscura::Image normal = obscura::readExr(path("aov/normal.exr"));
    int skyX = -1, skyY = -1, surfaceX = -1, surfaceY = -1;
    for (int y = 0; y < depth.height; ++y)
        for (int x = 0; x < depth.width; ++x)
            (std::isinf(depth.at(x, y)) ? skyX : surfaceX) = x, (std::isinf(depth.at(x, y)) ? skyY : surfaceY) = y;
    ASSERT_GE(skyX, 0) << "the demo view has sky";
    ASSERT_GE(surfaceX, 0);
    normal.at(skyX, skyY, 1) = std::nanf("");
    obscura::writeExr(path("sky-nan.exr"), normal);
    r = run(in + "--normal " + path("sky-nan.exr") + " -o " + path("c.exr"));
    ASSERT_EQ(r.code, 0) << r.out;
    r = run(in + "--normal " + path("aov/normal.exr") + " -o " + path("d.exr"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(obscura::readExr(path("c.exr")).pixels, obscura::readExr(path("d.exr")).pixels);
    normal.at(surfaceX, surfaceY, 0) = std::nanf("");
    obscura::writeExr(path("surface-nan.exr"), normal);
    expectFailure(in + "--normal " + path("surface-nan.exr") + " -o " + path("x.exr"),
                  {"surface-nan.exr", "normal at pixel (" + std::to_string(surfaceX) + ", " + std::to_string(surfaceY) +
                                          ") is not finite"});
    expectFailure(in + "--ao-guard-band 16 -o " + path("x.exr"), {"--ao-guard-band", "depth.exr", "48x32"});
    EXPECT_FALSE(fs::exists(path("x.exr")));
}

// --blur-normal-weight: auto is off for the separable blur and on for the 2-D one, so "on" changes the
// separable result near the room's creases and "off" the 2-D one, and the matching setting changes nothing.
TEST_F(AlchemyCli, BlurNormalWeightFlag) {
    Result r = run("render demo --size 64x36 -q --ao alchemy --blur none -o " + path("f.png") + " --aov-dir " + path("aov"));
    ASSERT_EQ(r.code, 0) << r.out;
    auto ao = [&](const std::string& flags) {
        const Result a = run("ao --depth " + path("aov/depth.exr") + " --normal " + path("aov/normal.exr") + " --camera " +
                             path("aov/camera.json") + " " + flags + " -o " + path("ao.exr"));
        EXPECT_EQ(a.code, 0) << a.out;
        return obscura::readExr(path("ao.exr")).pixels;
    };
    EXPECT_EQ(ao("--blur separable"), ao("--blur separable --blur-normal-weight off"));
    EXPECT_NE(ao("--blur separable"), ao("--blur separable --blur-normal-weight on"));
    EXPECT_EQ(ao("--blur 2d"), ao("--blur 2d --blur-normal-weight on"));
    EXPECT_NE(ao("--blur 2d"), ao("--blur 2d --blur-normal-weight off"));
}

// `ao --gpu` runs the same passes as Vulkan compute: on lavapipe the estimator gives alchemyPixel's values
// and the CPU's row kernel agrees with those to ~1e-5, and the GPU blurs agree with the CPU's to 2e-4
// (tests/gpu), so the two outputs agree within 2e-3 everywhere (measured on lavapipe at 96x54: max 4.9e-6
// unblurred, 1.4e-5 separable).
// In the Gpu* group of tests, which the asan build runs without leak detection (tests/CMakeLists.txt): the
// child process loads the Vulkan driver.
class GpuCli : public obscura::clitest::CliTest {};

TEST_F(GpuCli, AlchemyAoMatchesTheCpu) {
    if (obscura::gpu::deviceCount() == 0) GTEST_SKIP() << "no Vulkan device: the GPU path is not run";
    Result r = run("render demo --size 96x54 -q --ao alchemy --blur none -o " + path("f.png") + " --aov-dir " + path("aov"));
    ASSERT_EQ(r.code, 0) << r.out;
    const std::string in = "ao --depth " + path("aov/depth.exr") + " --normal " + path("aov/normal.exr") + " --camera " +
                           path("aov/camera.json");
    for (const std::string blur : {"none", "separable", "2d"}) {
        r = run(in + " --blur " + blur + " -o " + path("cpu.exr"));
        ASSERT_EQ(r.code, 0) << r.out;
        {
            // The child inherits it; a message would print a warning.
            const obscura::testutil::ScopedEnv validation("OBSCURA_VALIDATION", "1");
            r = run(in + " --gpu --blur " + blur + " -o " + path("gpu.exr"));
        }
        ASSERT_EQ(r.code, 0) << r.out;
        EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;  // no validation message
        const obscura::Image cpu = obscura::readExr(path("cpu.exr")), gpu = obscura::readExr(path("gpu.exr"));
        ASSERT_EQ(cpu.pixels.size(), gpu.pixels.size());
        for (std::size_t i = 0; i < cpu.pixels.size(); ++i) ASSERT_NEAR(cpu.pixels[i], gpu.pixels[i], 2e-3f) << blur << " " << i;
    }
    expectFailure(in + " --gpu --gpu-device 99 -o " + path("x.exr"), {"--gpu-device", "99"});
}

TEST_F(AlchemyCli, PresetsGuardBandAndDepthOnlyInput) {
    for (const char* preset : {"scene", "closeup"}) {
        Result r = run(std::string("render demo --size 48x32 -q --ao alchemy --ao-preset ") + preset +
                       " --ao-guard-band 6 -o " + path("f.png") + " --aov-dir " + path("aov"));
        ASSERT_EQ(r.code, 0) << r.out;
        EXPECT_NE(r.out.find("chapter"), std::string::npos) << r.out;
        obscura::Image ao = obscura::readExr(path("aov/ao.exr"));
        EXPECT_EQ(ao.width, 48);
        EXPECT_EQ(ao.height, 32);
    }
    Result r = run("ao --depth " + path("aov/depth.exr") + " --camera " + path("aov/camera.json") + " -o " + path("d.exr"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(fs::is_regular_file(path("d.exr")));
    // The combined G-buffer EXR of `obscura gbuffer` works as both --depth and --normal.
    ASSERT_EQ(run("gbuffer demo --size 48x32 -q -o " + path("g.exr")).code, 0);
    r = run("ao --depth " + path("g.exr") + " --normal " + path("g.exr") + " --camera " + path("g.camera.json") +
            " -o " + path("c.exr"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(obscura::readExr(path("c.exr")).width, 48);
}

TEST_F(AlchemyCli, AoRejectsBadBuffers) {
    ASSERT_EQ(run("gbuffer corner --size 24x16 -q -o " + path("g")).code, 0);
    const std::string cam = " --camera " + path("g/camera.json");
    obscura::Image depth = obscura::readExr(path("g/depth.exr"));
    depth.at(5, 7) = NAN;
    obscura::writeExr(path("nan.exr"), depth);
    expectFailure("ao --depth " + path("nan.exr") + cam + " -o " + path("ao.exr"), {"nan.exr", "(5, 7)"});
    expectFailure("ao --depth " + path("missing.exr") + cam + " -o " + path("ao.exr"), {"missing.exr"});
    expectFailure("ao --depth " + path("g/normal.exr") + cam + " -o " + path("ao.exr"), {"normal.exr", "1 channel"});
    // A one-channel PNG read as depth once passed: its codes / 255 are no meters (and a 16-bit one lost 8 bits).
    // Radiance HDR holds no negative value, which normals need.
    obscura::Image grey(24, 16, 1, 0.5f);
    obscura::writePng(path("depth.png"), grey);
    expectFailure("ao --depth " + path("depth.png") + cam + " -o " + path("ao.exr"),
                  {"--depth: ", "depth.png: linear depth in meters is read from .exr files, not .png"});
    EXPECT_FALSE(fs::exists(path("ao.exr")));
    expectFailure("ao --depth " + path("g/depth.exr") + " --normal " + path("n.hdr") + cam + " -o " + path("ao.exr"),
                  {"--normal: ", "n.hdr: a unit normal buffer is read from .exr files, not .hdr"});
    ASSERT_EQ(run("gbuffer corner --size 20x16 -q -o " + path("small")).code, 0);
    expectFailure("ao --depth " + path("small/depth.exr") + cam + " -o " + path("ao.exr"), {"depth.exr", "20x16", "24x16"});
    expectFailure("ao --depth " + path("g/depth.exr") + " --normal " + path("small/normal.exr") + cam + " -o " +
                      path("ao.exr"),
                  {"normal.exr", "20x16"});
    { std::ofstream(path("bad.json")) << "{\"width\": 24,"; }
    expectFailure("ao --depth " + path("g/depth.exr") + " --camera " + path("bad.json") + " -o " + path("ao.exr"), {"bad.json"});
    expectFailure("ao --depth " + path("g/depth.exr") + cam + " --ao-samples 0 -o " + path("ao.exr"), {"--ao-samples"});
    // ao's flag is --method (compare's is --methods, which the message named)
    expectFailure("ao --depth " + path("g/depth.exr") + cam + " --method bogus -o " + path("ao.exr"),
                  {"error: --method: unknown AO method 'bogus'"});
    expectFailure("ao --depth " + path("g/depth.exr") + cam + " --blur-radius 40 -o " + path("ao.exr"), {"--blur-radius"});
    expectFailure("ao --depth " + path("g/depth.exr") + cam + " --ao-radius 0 -o " + path("ao.exr"), {"--ao-radius"});
    expectFailure("ao --depth " + path("g/depth.exr") + cam + " --ao-guard-band 12 -o " + path("ao.exr"), {"guard-band"});
    // A band of at least half the height but less than half the width: the crop of the buffer came first and sized
    // an image by a negative height ("internal: cannot create std::vector larger than max_size()").
    expectFailure("ao --depth " + path("g/depth.exr") + cam + " --ao-guard-band 9 -o " + path("ao.exr"),
                  {"--ao-guard-band: 9 px on every side leaves nothing of", "depth.exr's 24x16 pixels"});
    expectFailure("ao --depth " + path("g/depth.exr") + cam + " -o " + path("ao.png"), {"ao.png", "unsupported"});
    // Normals that are not unit vectors: another buffer (albedo), or unit normals stored as n * 0.5 + 0.5.
    // Sky pixels are not checked: the corner's sky normals are 0.
    expectFailure("ao --depth " + path("g/depth.exr") + " --normal " + path("g/albedo.exr") + cam + " -o " +
                      path("ao.exr"),
                  {"albedo.exr", "has length", "outside [0.9, 1.1]", "unit view-space normals"});
    obscura::Image normal = obscura::readExr(path("g/normal.exr"));
    obscura::Image encoded = normal;
    for (float& v : encoded.pixels) v = v * 0.5f + 0.5f;
    obscura::writeExr(path("encoded.exr"), encoded);
    expectFailure("ao --depth " + path("g/depth.exr") + " --normal " + path("encoded.exr") + cam + " -o " +
                      path("ao.exr"),
                  {"encoded.exr", "n * 0.5 + 0.5"});
    // 5% short everywhere is inside the tolerance (half-float storage, interpolated normals), 15% is not; the
    // accepted ones are made unit, so the AO is the unit normals' within float rounding (Alchemy's v.n scaled
    // with the length: AO moved by up to 0.082 for normals 1.09 long, 0.090 for 0.91).
    ASSERT_EQ(run("ao --depth " + path("g/depth.exr") + " --normal " + path("g/normal.exr") + cam + " -o " +
                  path("unit_ao.exr")).code, 0);
    // 1e20: finite, its squares not (the message said "length inf").
    for (const auto& [scale, ok] : {std::pair{0.95f, true}, std::pair{1.09f, true}, std::pair{0.85f, false},
                                    std::pair{1e20f, false}}) {
        obscura::Image scaled = normal;
        for (float& v : scaled.pixels) v *= scale;
        obscura::writeExr(path("scaled.exr"), scaled);
        const std::string args = "ao --depth " + path("g/depth.exr") + " --normal " + path("scaled.exr") + cam +
                                 " -o " + path("scaled_ao.exr");
        if (ok) {
            EXPECT_EQ(run(args).code, 0) << scale;
            const obscura::Image unit = obscura::readExr(path("unit_ao.exr"));
            const obscura::Image scaledAo = obscura::readExr(path("scaled_ao.exr"));
            ASSERT_EQ(unit.pixels.size(), scaledAo.pixels.size());
            for (std::size_t i = 0; i < unit.pixels.size(); ++i)
                EXPECT_NEAR(scaledAo.pixels[i], unit.pixels[i], 1e-5f) << scale << " pixel " << i;
        } else if (scale < 1.0f) {
            expectFailure(args, {"scaled.exr", "has length 0.8"});
        } else {
            expectFailure(args, {"scaled.exr", "has length", "outside [0.9, 1.1]"});
            const std::string out = run(args).out;
            EXPECT_EQ(out.find("length inf"), std::string::npos) << out;
            EXPECT_TRUE(out.find("e+19") != std::string::npos || out.find("e+20") != std::string::npos) << out;
        }
    }
    // Sky written as a finite 1e31, which every pass reads as sky: its zero normals are not checked either
    // (the plane's view has a row of sky at this size).
    ASSERT_EQ(run("gbuffer plane --size 24x16 -q -o " + path("sky")).code, 0);
    obscura::Image farSky = obscura::readExr(path("sky/depth.exr"));
    int skyPixels = 0;
    for (float& d : farSky.pixels)
        if (std::isinf(d)) d = 1e31f, ++skyPixels;
    ASSERT_GT(skyPixels, 0);
    obscura::writeExr(path("far_sky.exr"), farSky);
    const Result farSkyRun = run("ao --depth " + path("far_sky.exr") + " --normal " + path("sky/normal.exr") +
                                 " --camera " + path("sky/camera.json") + " -o " + path("far_sky_ao.exr"));
    EXPECT_EQ(farSkyRun.code, 0) << farSkyRun.out;
}

TEST_F(AlchemyCli, RenderRejectsBadAlchemyFlags) {
    const std::string base = "render plane --size 32x18 -q --ao alchemy -o " + path("f.png");
    expectFailure(base + " --ao-intensity -1", {"--ao-intensity"});
    expectFailure(base + " --ao-contrast 0", {"--ao-contrast"});
    expectFailure(base + " --ao-radius inf", {"--ao-radius", "finite"});
    expectFailure(base + " --ao-preset loud", {"--ao-preset"}, 2);
    expectFailure(base + " --blur box", {"--blur"}, 2);
    expectFailure(base + " --blur-normal-weight sometimes", {"--blur-normal-weight"}, 2);
    expectFailure(base + " --ao-max-radius-px 0", {"--ao-max-radius"});
    expectFailure(base + " --ao-lod-radius-px -3", {"--ao-lod-radius"});
    expectFailure(base + " --ao-lod-radius-px 8 --ao-samples 300", {"--ao-samples", "level of detail"});
}

TEST_F(AlchemyCli, CompareReportsMetricsAndWritesThePicture) {
    Result r = run("compare corner --methods alchemy,alchemy-chapter --size 48x32 --rays 64 --json -o " + path("c.png"));
    ASSERT_EQ(r.code, 0) << r.out;
    for (const char* key : {"\"mae\"", "\"rmse\"", "\"bias\"", "\"max\"", "\"alchemy-chapter\"", "\"surface_pixels\""})
        EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
    obscura::Image sheet = obscura::readPng(path("c.png"));
    EXPECT_EQ(sheet.width, 4 * 48 + 5 * 4);
    EXPECT_GT(sheet.height, 2 * 32);
    r = run("compare corner --size 48x32 --rays 16 -q -o " + path("t.png"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("MAE"), std::string::npos) << r.out;
    // The blur's normal weight reaches compare: on the corner's creases it changes the separable result.
    auto mae = [&](const std::string& flags) {
        const Result c = run("compare corner --methods alchemy --size 48x32 --rays 16 --blur separable --json " + flags +
                             " -o " + path("b.png"));
        EXPECT_EQ(c.code, 0) << c.out;
        return nlohmann::json::parse(c.out)["methods"][0]["mae"].get<double>();
    };
    EXPECT_NE(mae("--blur-normal-weight on"), mae("--blur-normal-weight off"));
    EXPECT_EQ(mae("--blur-normal-weight auto"), mae("--blur-normal-weight off"));
    expectFailure("compare corner --methods alchemy,nope --size 48x32 -o " + path("x.png"), {"nope", "alchemy"});
    expectFailure("compare corner --rays 0 --size 48x32 -o " + path("x.png"), {"--rays"});
}

// The reference is a Monte Carlo estimate, and its noise went into every MAE and RMSE unreported (and the help
// called it exact): at 1 ray the gtao row read MAE 0.096 against 0.015 at 4096. Its RMS standard error is now
// reported beside each row and in the JSON: null under 8 rays, falling as 1/sqrt(rays), near 0 where the
// reference is; each falloff's reference lists the parameters that falloff reads, and only those.
TEST_F(AlchemyCli, CompareReportsTheReferencesNoise) {
    const auto json = [&](int rays) {
        const Result r = run("compare corner --methods alchemy,gtao --size 32x24 -q --json --rays " + std::to_string(rays) +
                             " -o " + path("n.png"));
        EXPECT_EQ(r.code, 0) << r.out;
        return nlohmann::json::parse(r.out);
    };
    const nlohmann::json one = json(1), four = json(4), few = json(16), many = json(1024);
    EXPECT_TRUE(one["methods"][1]["reference"]["noise"].is_null()) << one.dump();
    EXPECT_TRUE(four["methods"][1]["reference"]["noise"].is_null()) << four.dump();
    for (int m : {0, 1}) {
        const double noiseFew = few["methods"][m]["reference"]["noise"].get<double>();
        const double noiseMany = many["methods"][m]["reference"]["noise"].get<double>();
        // 64 times the rays: an eighth of the noise for independent rays, less for stratified ones.
        EXPECT_GT(noiseFew, 0.0) << m;
        EXPECT_LT(noiseMany, noiseFew / 6.0) << m;
        // The noise is part of the RMSE (E[RMSE^2] = RMSE^2 of the method + noise^2, within its high side).
        EXPECT_LT(noiseMany, many["methods"][m]["rmse"].get<double>()) << m;
    }
    const nlohmann::json& alchemy = many["methods"][0]["reference"];
    const nlohmann::json& binary = many["methods"][1]["reference"];
    EXPECT_EQ(alchemy["falloff"], "alchemy");
    EXPECT_TRUE(alchemy.contains("u") && alchemy.contains("scale")) << alchemy.dump();
    EXPECT_EQ(binary["falloff"], "binary");
    EXPECT_FALSE(binary.contains("u") || binary.contains("scale")) << binary.dump();
    EXPECT_EQ(many["seed"], 0);
    EXPECT_EQ(many["blur"]["mode"], "none");
    // Floats go out as their shortest decimal: the alchemy reference's u is 0.01 m, not 0.009999999776.
    EXPECT_EQ(alchemy["u"].dump(), "0.01");
    EXPECT_EQ(alchemy["radius"].dump(), "0.5");
    const Result table = run("compare corner --methods gtao --size 32x24 -q --rays 4 -o " + path("t.png"));
    EXPECT_NE(table.out.find("ref noise"), std::string::npos) << table.out;
    EXPECT_NE(table.out.find("raise --rays"), std::string::npos) << table.out;
}

// An ignored flag is said to be ignored once, and not then refused: --gtao-slices with no GTAO method warned
// "ignored", then failed on its clash with --samples; --gtao-mip-ratio was warned of twice; --blur-radius with
// --blur none said nothing.
TEST_F(AlchemyCli, CompareWarnsOnceOfIgnoredFlags) {
    const std::string base = "compare corner -q --size 8x6 --rays 4 -o " + path("x.png") + " ";
    Result r = run(base + "--methods alchemy --samples 12 --gtao-slices 2");
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("warning: --gtao-slices: applies to the gtao methods"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("obscura: error"), std::string::npos) << r.out;
    r = run(base + "--methods alchemy --gtao-mip-ratio 3");
    EXPECT_EQ(r.code, 0) << r.out;
    const auto count = [](const std::string& text, const std::string& what) {
        std::size_t n = 0;
        for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
        return n;
    };
    EXPECT_EQ(count(r.out, "--gtao-mip-ratio"), 1u) << r.out;
    r = run(base + "--blur-radius 3 --blur-normal-weight on");
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("warning: --blur-radius: applies to a blur, and --blur is none"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("warning: --blur-normal-weight: applies to a blur"), std::string::npos) << r.out;
    r = run(base + "--blur separable --blur-radius 3");
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
    // Still an error where both are read.
    expectFailure(base + "--methods gtao --samples 12 --gtao-slices 2", {"--gtao-slices", "--samples"});
}

// The error column is sRGB-encoded as the other three are: the plane's sky there is sRGB(0.2) = 124, not
// 0.2 * 255 = 51, and the legend's blue end sRGB(0.05, 0.13, 0.71) = (64, 100, 219), not (13, 33, 181). A
// small --range prints with the digits it needs (0.004, not 0.00), 0.125 in full (not 0.12).
TEST_F(AlchemyCli, CompareEncodesTheErrorColumnAndPrintsASmallRange) {
    const Result r = run("compare plane --size 32x24 --rays 4 --range 0.004 -o " + path("c.png"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("+-0.004)"), std::string::npos) << r.out;
    const Result eighth = run("compare corner --size 32x24 --rays 4 --range 0.125 -q -o " + path("e.png"));
    EXPECT_NE(eighth.out.find("+-0.125)"), std::string::npos) << eighth.out;
    const obscura::Image sheet = obscura::readPng(path("c.png"));
    const int column = 4 + 3 * (32 + 4);
    EXPECT_NEAR(sheet.at(column + 1, 5, 0) * 255.0f, 124.0f, 1.0f);
    const int legendY = sheet.height - (12 * 2 + 3 * 4) + 4;  // scale 2, gap 4: the ramp's first row
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(sheet.at(column, legendY, c) * 255.0f, (std::array<float, 3>{64, 100, 219}[c]), 1.5f) << c;
}
