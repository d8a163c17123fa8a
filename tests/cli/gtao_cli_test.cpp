// `obscura render --ao gtao`: the AOVs it promises, the frame loop, and one-line errors with no output.
#include "obscura/image_io.h"

#include "cli/cli_harness.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using Result = obscura::clitest::CliResult;

Result run(const std::string& args) { return obscura::clitest::runCli(args); }

class GtaoCli : public obscura::clitest::CliTest {};

} // namespace

TEST_F(GtaoCli, WritesFrameAndAovs) {
    Result r = run("render well --ao gtao --ao-quality low --size 64x48 --ao-output all --multibounce "
                   "--specular-occlusion cone -q -o " + path("f.png") + " --aov-dir " + path("aov"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(fs::exists(path("f.png")));
    for (const char* name : {"ao.exr", "bent_normal.exr", "ao_multibounce.exr", "specular_occlusion.exr"})
        EXPECT_TRUE(fs::exists(path("aov/") + name)) << name;
    obscura::Image ao = obscura::readExr(path("aov/ao.exr"));
    obscura::Image mb = obscura::readExr(path("aov/ao_multibounce.exr"));
    ASSERT_EQ(ao.width, 64);
    ASSERT_EQ(mb.channels, 3);
    float lo = 1.0f;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            lo = std::min(lo, ao.at(x, y));
            EXPECT_GE(mb.at(x, y, 0), ao.at(x, y) - 1e-6f);  // G(A, rho) >= A
        }
    EXPECT_LT(lo, 0.5f);  // the well's floor is occluded
}

TEST_F(GtaoCli, FramesWriteEveryFrame) {
    Result r = run("render corner --ao gtao --frames 3 --size 48x32 -q -o " + path("f.exr") + " --aov-dir " + path("aov"));
    ASSERT_EQ(r.code, 0) << r.out;
    for (const char* name : {"ao_0000.exr", "ao_0001.exr", "ao_0002.exr", "ao.exr", "camera.json"})
        EXPECT_TRUE(fs::exists(path("aov/") + name)) << name;
    // The last frame's ao.exr is frame 2's.
    obscura::Image last = obscura::readExr(path("aov/ao.exr")), two = obscura::readExr(path("aov/ao_0002.exr"));
    EXPECT_EQ(last.pixels, two.pixels);
}

TEST_F(GtaoCli, BadInputFailsWithOneLine) {
    struct Case {
        std::string args, needle;
    };
    const Case cases[] = {{"--ao-radius inf", "--ao-radius"},
                          {"--frames 0", "--frames"},
                          {"--roughness 2", "--roughness"},
                          {"--ao-output all", "--aov-dir"},
                          {"--gtao-falloff-start 1.5", "--gtao-falloff-start"},
                          {"--gtao-step-power 9", "--gtao-step-power"},
                          {"--gtao-sampling mip --gtao-mip-ratio 100", "--gtao-mip-ratio"},
                          {"--gtao-half-blur-radius 3", "--gtao-half-res"},
                          {"--gtao-half-res --gtao-half-blur-radius 33", "--gtao-half-blur-radius"},
                          {"--gtao-half-res --frames 3 --gtao-half-blur-radius 1", "--gtao-half-blur-radius"},
                          {"--gtao-jitter --gtao-interleave", "--gtao-interleave"},
                          {"--gtao-packed-history --frames 1", "--gtao-packed-history"},
                          {"--gtao-packed-history --frames 3 --gtao-mode spatial", "--gtao-packed-history"},
                          {"--gtao-grid-history --frames 3", "--gtao-grid-history"},
                          {"--gtao-alternating-window --frames 3 --gtao-mode spatial", "--gtao-alternating-window"},
                          {"--gtao-alternating-window-size 2 --frames 3", "--gtao-alternating-window-size"},
                          {"--gtao-alternating-window --gtao-alternating-window-size 3 --frames 3",
                           "--gtao-alternating-window-size"},
                          {"--gtao-grid-history --gtao-half-res", "--gtao-grid-history"},  // the full mode
                          {"--gtao-slices 65", "--gtao-slices"},
                          {"--gtao-steps 257", "--gtao-steps"},
                          {"--gtao-jitter --frames 3", "--gtao-jitter"},
                          {"--gtao-jitter --gtao-mode spatial", "--gtao-jitter"}};
    for (const Case& c : cases) {
        Result r = run("render plane --ao gtao --size 32x32 -q -o " + path("f.png") + " " + c.args);
        EXPECT_EQ(r.code, 1) << c.args << ": " << r.out;
        EXPECT_EQ(r.out.rfind("obscura: error: ", 0), 0u) << r.out;
        EXPECT_NE(r.out.find(c.needle), std::string::npos) << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
        EXPECT_FALSE(fs::exists(path("f.png"))) << c.args;
    }
    for (const char* args : {"--ao-quality extreme", "--gtao-beyond-radius sideways", "--gtao-sampling bilinear"}) {
        Result r = run("render plane --ao gtao " + std::string(args) + " -o " + path("f.png"));
        EXPECT_EQ(r.code, 2) << args << ": " << r.out;
    }
}

TEST_F(GtaoCli, CompareMeasuresGtaoAgainstRayTracedAo) {
    Result r = run("compare well --methods gtao,gtao-ultra --size 48x48 --camera-from 0,3,0 --camera-to 0,-2,0 "
                   "--camera-up 0,0,-1 --rays 64 -q --json -o " + path("c.png"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("\"gtao\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"gtao-ultra\""), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(path("c.png")));
}

// --samples sets GTAO's slice count in whole slices of 2 x steps per side, 1 to 64: 5 ran 6 (the high preset's
// 3 steps, 1 slice) and 1024 ran 384 without a word. The count taken is reported, and warned about where it is
// not the one asked for; Alchemy takes any count.
TEST_F(GtaoCli, CompareReportsTheSamplesItTakesAndWhatItIgnores) {
    const std::string compare = "compare corner --size 32x24 --rays 4 -q --json -o " + path("c.png") + " --methods gtao,alchemy ";
    Result r = run(compare + "--samples 5");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("warning: --samples 5: gtao takes 6 samples per pixel"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("warning: --samples 5: alchemy"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"samples_per_pixel\": 6"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"samples_per_pixel\": 5"), std::string::npos) << r.out;
    r = run(compare + "--samples 12");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
    r = run(compare + "--samples 1024");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("gtao takes 384 samples per pixel"), std::string::npos) << r.out;
    // --gtao-mip-ratio changes only the methods whose samples switch on distance; the others ignored it silently.
    r = run(compare + "--gtao-mip-ratio 3");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("warning: --gtao-mip-ratio: no method of --methods reads it"), std::string::npos) << r.out;
    r = run("compare corner --size 32x24 --rays 4 -q --json -o " + path("c.png") + " --methods gtao,gtao-mip --gtao-mip-ratio 3");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
}

// render --ao gtao warns of the GTAO flags its other flags leave unread, as ao and compare do: the mip ratio under
// a sampling that does not read it, and the falloff's fade under the bitmask thickness, which counts an occluder
// within the radius whole.
TEST_F(GtaoCli, RenderWarnsOfFlagsItsSettingsDoNotRead) {
    const std::string render = "render corner --size 16x9 -q -o " + path("f.exr") + " --ao gtao ";
    Result r = run(render + "--gtao-mip-ratio 3");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("warning: --gtao-mip-ratio: --gtao-sampling planar does not read it"), std::string::npos)
        << r.out;
    r = run(render + "--gtao-mip-ratio 3 --gtao-sampling planar-nearest");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
    r = run(render + "--gtao-thickness bitmask --gtao-falloff-start 0.5");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("warning: --gtao-falloff-start: the bitmask thickness counts every occluder within the "
                         "radius whole"),
              std::string::npos)
        << r.out;
    r = run(render + "--gtao-thickness heuristic --gtao-falloff-start 0.5");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
}

// --gtao-sampling reaches the kernel: on the open plane planar samples give exactly 1 everywhere and nearest
// (and mip, and planar-mip) ones darken a few far pixels (tests/ssao/gtao_test.cpp,
// NearestSamplingDarkensAnOpenPlaneSlightly). Planar-nearest darkens none below 0.999 (its far samples alone
// are nearest) but leaves some pixels a little below planar's 1.
TEST_F(GtaoCli, SamplingFlagReachesTheKernel) {
    for (const char* sampling : {"planar", "nearest", "mip", "planar-mip", "planar-nearest"}) {
        Result r = run("render plane --ao gtao --size 160x90 -q -o " + path("f.png") + " --aov-dir " + path("aov") +
                       " --gtao-sampling " + sampling);
        ASSERT_EQ(r.code, 0) << r.out;
        const obscura::Image ao = obscura::readExr(path("aov/ao.exr"));
        int darker = 0, belowOne = 0;
        for (float v : ao.pixels) {
            darker += v < 0.999f;
            belowOne += v < 1.0f;
        }
        if (std::string(sampling) == "planar") {
            EXPECT_EQ(darker, 0);
        } else if (std::string(sampling) == "planar-nearest") {
            EXPECT_EQ(darker, 0);
            EXPECT_GT(belowOne, 0);
        } else {
            EXPECT_GT(darker, 0);
        }
    }
}

// --gtao-alternating-window-size reaches the reconstruction: after 5 frames the AO of the 2x2 windows differs
// from the 4x4 windows' and from the 5x5 window's (which of them is nearer ray tracing is
// GtaoTemporal.GridHistorySamplingsAgainstRayTracing's to say).
TEST_F(GtaoCli, AlternatingWindowSizeReachesTheReconstruction) {
    const std::string base = "render stairs --ao gtao --size 96x54 --frames 5 --gtao-half-res --gtao-grid-history -q "
                             "-o " + path("f.png") + " --aov-dir ";
    const char* variants[3] = {"", "--gtao-alternating-window",
                               "--gtao-alternating-window --gtao-alternating-window-size 2"};
    obscura::Image ao[3];
    for (int i = 0; i < 3; ++i) {
        const std::string aovs = path("aov" + std::to_string(i));
        Result r = run(base + aovs + " " + variants[i]);
        ASSERT_EQ(r.code, 0) << r.out;
        ao[i] = obscura::readExr(aovs + "/ao.exr");
    }
    auto meanDifference = [](const obscura::Image& a, const obscura::Image& b) {
        double sum = 0;
        for (std::size_t i = 0; i < a.pixels.size(); ++i) sum += std::fabs(double(a.pixels[i]) - double(b.pixels[i]));
        return sum / double(a.pixels.size());
    };
    EXPECT_GT(meanDifference(ao[2], ao[1]), 1e-4);
    EXPECT_GT(meanDifference(ao[2], ao[0]), 1e-4);
}

// gtao-nearest is a method of compare: the high preset with nearest-pixel samples, whose error against ray
// tracing is within 0.005 of gtao's on the well seen from above (measured 2026-11-25 at 48x48: 0.01341
// against 0.01341).
TEST_F(GtaoCli, CompareMeasuresNearestSampling) {
    Result r = run("compare well --methods gtao,gtao-nearest --size 48x48 --camera-from 0,3,0 --camera-to 0,-2,0 "
                   "--camera-up 0,0,-1 --rays 64 -q --json -o " + path("c.png"));
    ASSERT_EQ(r.code, 0) << r.out;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["methods"].size(), 2u);
    EXPECT_EQ(j["methods"][1]["name"], "gtao-nearest");
    const double planar = j["methods"][0]["mae"], nearest = j["methods"][1]["mae"];
    EXPECT_GT(nearest, 0.0);
    EXPECT_NEAR(nearest, planar, 0.005);
}

// `render` takes the flags of every --ao method; one given with another method is ignored, and says so on
// stderr (a warning, not an error: a script may pass one set of flags to every method) without a change to
// the frame.
TEST_F(GtaoCli, FlagsOfAnotherMethodWarn) {
    auto render = [&](const std::string& flags) {
        const Result r = run("render corner --size 48x32 -q -o " + path("f.png") + " --aov-dir " + path("aov") + " " +
                             flags);
        EXPECT_EQ(r.code, 0) << flags << ": " << r.out;
        return std::make_pair(r.out, obscura::readExr(path("aov/ao.exr")).pixels);
    };
    const auto [plainOut, plain] = render("--ao gtao");
    EXPECT_EQ(plainOut.find("warning"), std::string::npos) << plainOut;
    const auto [out, withAlchemyFlags] = render("--ao gtao --blur-radius 1000 --ao-samples 4 --ao-rays 8");
    EXPECT_EQ(withAlchemyFlags, plain);
    EXPECT_NE(out.find("warning: --blur-radius: applies to --ao alchemy, not --ao gtao; ignored"), std::string::npos)
        << out;
    EXPECT_NE(out.find("warning: --ao-samples: applies to --ao alchemy"), std::string::npos) << out;
    EXPECT_NE(out.find("warning: --ao-rays: applies to --ao raytraced, not --ao gtao"), std::string::npos) << out;
    const auto [alchemyOut, alchemy] = render("--ao alchemy");
    const auto [alchemyGtaoOut, alchemyWithGtaoFlags] = render("--ao alchemy --gtao-slices 7 --frames 3");
    EXPECT_EQ(alchemyWithGtaoFlags, alchemy);
    EXPECT_EQ(alchemyOut.find("warning"), std::string::npos) << alchemyOut;
    EXPECT_NE(alchemyGtaoOut.find("warning: --gtao-slices: applies to --ao gtao, not --ao alchemy"), std::string::npos)
        << alchemyGtaoOut;
    EXPECT_NE(alchemyGtaoOut.find("warning: --frames: applies to --ao gtao"), std::string::npos) << alchemyGtaoOut;

    // The composite is diffuse: specular occlusion shows only as its AOV (--ao-output all), where it is written;
    // otherwise it was computed on every frame for nothing (30 times the frame's time on stairs at 64x36).
    const auto [specularOut, withSpecular] = render("--ao gtao --specular-occlusion lut4 --roughness 0.1");
    EXPECT_EQ(withSpecular, plain);
    EXPECT_NE(specularOut.find("warning: --specular-occlusion: is written only as specular_occlusion.exr"),
              std::string::npos)
        << specularOut;
    EXPECT_FALSE(fs::exists(path("aov/specular_occlusion.exr")));
    const auto [roughnessOut, withRoughness] = render("--ao gtao --roughness 0.1");
    EXPECT_NE(roughnessOut.find("warning: --roughness: applies to --specular-occlusion; ignored"), std::string::npos)
        << roughnessOut;
    const auto [allOut, all] = render("--ao gtao --specular-occlusion lut4 --ao-output all");
    EXPECT_EQ(allOut.find("warning"), std::string::npos) << allOut;
    EXPECT_TRUE(fs::exists(path("aov/specular_occlusion.exr")));

    // --gpu-packed-normals belongs to both screen-space methods.
    const auto [raytracedOut, raytraced] = render("--ao raytraced --ao-rays 4 --gpu-packed-normals");
    EXPECT_NE(raytracedOut.find("warning: --gpu-packed-normals: applies to --ao alchemy or gtao, not --ao raytraced"),
              std::string::npos)
        << raytracedOut;

    // compare: the GTAO flags with no GTAO method among --methods.
    const std::string compare = "compare corner --size 32x24 --rays 4 -q -o " + path("c.png") + " --methods ";
    Result r = run(compare + "alchemy --gtao-slices 5");
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("warning: --gtao-slices: applies to the gtao methods, and --methods has none; ignored"),
              std::string::npos)
        << r.out;
    r = run(compare + "alchemy,gtao --gtao-slices 5");
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
}

// `ao --ao-radius` sets the GTAO methods' radius too (their default 1 m): the same bits as `render --ao gtao`
// with that radius on the buffers render wrote, and the other Alchemy flags warn with a GTAO method.
TEST_F(GtaoCli, AoRadiusReachesTheGtaoMethods) {
    auto renderAo = [&](const std::string& flags, const std::string& aovDir) {
        const Result r = run("render corner --ao gtao --size 48x32 -q -o " + path("f.png") + " --aov-dir " +
                             path(aovDir) + " " + flags);
        EXPECT_EQ(r.code, 0) << flags << ": " << r.out;
        return obscura::readExr(path(aovDir + "/ao.exr")).pixels;
    };
    const std::vector<float> metre = renderAo("", "one"), quarter = renderAo("--ao-radius 0.25", "quarter");
    EXPECT_NE(metre, quarter);
    auto ao = [&](const std::string& flags) {
        const Result r = run("ao --method gtao --depth " + path("one/depth.exr") + " --normal " + path("one/normal.exr") +
                             " --camera " + path("one/camera.json") + " -o " + path("a.exr") + " --blur none " + flags);
        EXPECT_EQ(r.code, 0) << flags << ": " << r.out;
        return std::make_pair(r.out, obscura::readExr(path("a.exr")).pixels);
    };
    EXPECT_EQ(ao("").second, metre);
    EXPECT_EQ(ao("--ao-radius 1").second, metre);
    EXPECT_EQ(ao("--ao-radius 0.25").second, quarter);
    const auto [out, withSamples] = ao("--ao-samples 4");
    EXPECT_EQ(withSamples, metre);
    EXPECT_NE(out.find("warning: --ao-samples: applies to the alchemy methods, not gtao; ignored"), std::string::npos)
        << out;
    expectFailure("ao --method gtao --depth " + path("one/depth.exr") + " --camera " + path("one/camera.json") +
                      " --normal " + path("one/normal.exr") + " -o " + path("b.exr") + " --ao-radius 0",
                  {"--ao-radius", "(0, 1e4]", "is 0"});
    EXPECT_FALSE(fs::exists(path("b.exr")));
}

// --gtao-slices, --gtao-steps, --gtao-jitter and --gtao-interleave reach the kernel in render, ao and compare:
// the preset's own counts change nothing, other counts, the jitter and the interleave change the AO, and
// `render` and `ao` agree bit for bit (the gtao-half method with render's --gtao-half-res too)
// on the same buffers; compare refuses --samples with --gtao-slices (both set the slices), and `ao` the flags
// with an Alchemy method.
TEST_F(GtaoCli, SliceFlagsReachTheKernel) {
    auto render = [&](const std::string& flags) {
        const Result r = run("render corner --ao gtao --size 48x32 -q -o " + path("f.png") + " --aov-dir " +
                             path("aov") + " " + flags);
        EXPECT_EQ(r.code, 0) << flags << ": " << r.out;
        return obscura::readExr(path("aov/ao.exr")).pixels;
    };
    const std::vector<float> high = render("");
    EXPECT_EQ(render("--gtao-slices 3 --gtao-steps 3"), high);
    EXPECT_NE(render("--gtao-slices 1"), high);
    EXPECT_NE(render("--gtao-steps 5"), high);
    const std::vector<float> jittered = render("--gtao-slices 2 --gtao-steps 4 --gtao-jitter");
    EXPECT_NE(render("--gtao-slices 2 --gtao-steps 4"), jittered);
    const std::vector<float> interleaved = render("--gtao-slices 2 --gtao-steps 4 --gtao-interleave");
    EXPECT_NE(interleaved, jittered);
    EXPECT_NE(render("--gtao-slices 2 --gtao-steps 4"), interleaved);

    const std::string buffers = "ao --method gtao --depth " + path("aov/depth.exr") + " --normal " +
                                path("aov/normal.exr") + " --camera " + path("aov/camera.json") + " -o " + path("ao.exr");
    Result r = run(buffers + " --blur none --gtao-slices 2 --gtao-steps 4 --gtao-jitter");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(obscura::readExr(path("ao.exr")).pixels, render("--gtao-slices 2 --gtao-steps 4 --gtao-jitter"));
    // The gtao-half method: 2 interleaved slices x 4 steps at half resolution, --blur on the grid; render's
    // --gtao-half-res with the same counts and a 5-tap grid blur gives the same bits.
    r = run("ao --method gtao-half --depth " + path("aov/depth.exr") + " --normal " + path("aov/normal.exr") +
            " --camera " + path("aov/camera.json") + " -o " + path("ao.exr") + " --blur separable --blur-radius 2");
    ASSERT_EQ(r.code, 0) << r.out;
    const std::vector<float> half = render("--gtao-half-res --gtao-slices 2 --gtao-steps 4 --gtao-interleave");
    EXPECT_EQ(obscura::readExr(path("ao.exr")).pixels, half);
    EXPECT_NE(half, interleaved);
    EXPECT_NE(render("--gtao-half-res --gtao-slices 2 --gtao-steps 4 --gtao-interleave --gtao-half-blur-radius 0"), half);
    expectFailure("ao --method alchemy --depth " + path("aov/depth.exr") + " --camera " + path("aov/camera.json") +
                      " -o " + path("a.exr") + " --gtao-steps 4",
                  {"--gtao-steps", "alchemy"});

    const std::string compare = "compare corner --methods gtao --size 48x32 --rays 16 -q --json -o " + path("c.png");
    auto mae = [&](const std::string& flags) {
        const Result c = run(compare + " " + flags);
        EXPECT_EQ(c.code, 0) << flags << ": " << c.out;
        return nlohmann::json::parse(c.out)["methods"][0]["mae"].get<double>();
    };
    EXPECT_EQ(mae("--gtao-slices 3 --gtao-steps 3"), mae(""));
    EXPECT_NE(mae("--gtao-slices 2 --gtao-steps 4 --gtao-jitter"), mae(""));
    EXPECT_NE(mae("--gtao-slices 2 --gtao-steps 4 --gtao-interleave"), mae("--gtao-slices 2 --gtao-steps 4"));
    // --blur-radius reaches compare's blur: the default radius is 6, another changes the error.
    EXPECT_EQ(mae("--blur separable --blur-radius 6"), mae("--blur separable"));
    EXPECT_NE(mae("--blur separable --blur-radius 2"), mae("--blur separable"));
    expectFailure(compare + " --blur separable --blur-radius 0", {"--blur-radius", "[1, 32]"});
    expectFailure(compare + " --samples 12 --gtao-slices 2", {"--gtao-slices", "--samples"});
    EXPECT_FALSE(fs::exists(path("a.exr")));
}

// --gtao-mip-ratio reaches the registry's methods in ao and compare: `ao --method gtao-half-planar-nearest`
// with ratio 2 (planar samples within 4 px) gives render's bits for the same configuration, and not the
// default ratio's; 7, the default, changes nothing, nor does any ratio for planar samples, which never read
// it. compare reports the ratio in its JSON; a ratio out of [2, 64], or one given to an Alchemy method,
// fails with one line naming the flag and writes nothing.
TEST_F(GtaoCli, MipRatioReachesAoAndCompare) {
    const std::string half = "--gtao-half-res --gtao-slices 2 --gtao-steps 4 --gtao-interleave --gtao-sampling "
                             "planar-nearest";
    auto render = [&](const std::string& flags) {
        const Result r = run("render corner --ao gtao --size 96x64 -q -o " + path("f.png") + " --aov-dir " +
                             path("aov") + " " + flags);
        EXPECT_EQ(r.code, 0) << flags << ": " << r.out;
        return obscura::readExr(path("aov/ao.exr")).pixels;
    };
    const std::vector<float> rendered = render(half + " --gtao-mip-ratio 2");
    const std::string buffers = "ao --depth " + path("aov/depth.exr") + " --normal " + path("aov/normal.exr") +
                                " --camera " + path("aov/camera.json") + " -o " + path("ao.exr");
    auto ao = [&](const std::string& flags) {
        const Result r = run(buffers + " " + flags);
        EXPECT_EQ(r.code, 0) << flags << ": " << r.out;
        return obscura::readExr(path("ao.exr")).pixels;
    };
    const std::string halfMethod = "--method gtao-half-planar-nearest --blur separable --blur-radius 2";
    EXPECT_EQ(ao(halfMethod + " --gtao-mip-ratio 2"), rendered);
    EXPECT_NE(ao(halfMethod), rendered);
    EXPECT_EQ(ao("--method gtao-planar-nearest --gtao-mip-ratio 7"), ao("--method gtao-planar-nearest"));
    EXPECT_NE(ao("--method gtao-planar-nearest --gtao-mip-ratio 2"), ao("--method gtao-planar-nearest"));
    EXPECT_EQ(ao("--method gtao --gtao-mip-ratio 2"), ao("--method gtao"));

    const std::string compare = "compare corner --methods gtao-planar-nearest --size 96x64 --rays 16 -q --json -o " +
                                path("c.png");
    const Result plain = run(compare);
    const Result ratio2 = run(compare + " --gtao-mip-ratio 2");
    ASSERT_EQ(plain.code, 0) << plain.out;
    ASSERT_EQ(ratio2.code, 0) << ratio2.out;
    const nlohmann::json a = nlohmann::json::parse(plain.out), b = nlohmann::json::parse(ratio2.out);
    EXPECT_FALSE(a.contains("gtao_mip_ratio"));
    EXPECT_EQ(b["gtao_mip_ratio"].get<double>(), 2.0);
    EXPECT_NE(a["methods"][0]["mae"].get<double>(), b["methods"][0]["mae"].get<double>());

    fs::remove(path("ao.exr"));
    fs::remove(path("c.png"));
    expectFailure(compare + " --gtao-mip-ratio 1", {"--gtao-mip-ratio", "[2, 64]"});
    expectFailure(buffers + " --method gtao-mip --gtao-mip-ratio 65", {"--gtao-mip-ratio", "[2, 64]"});
    expectFailure(buffers + " --method alchemy --gtao-mip-ratio 2", {"--gtao-mip-ratio", "alchemy"});
    EXPECT_FALSE(fs::exists(path("ao.exr")));
    EXPECT_FALSE(fs::exists(path("c.png")));
}
