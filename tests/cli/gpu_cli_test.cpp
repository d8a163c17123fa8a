// `--gpu` on render, ao and compare, and `bench --gpu`: the commands run the Vulkan passes and agree with
// their CPU paths. On lavapipe with the validation layers on (a message would print a warning, which fails
// the test). In the Gpu* group, which the asan build runs without leak detection (tests/CMakeLists.txt):
// the child processes load the Vulkan driver.
#include "cli/cli_harness.h"
#include "gpu/spirv_edit.h"
#include "scoped_env.h"

#include "obscura/gpu.h"
#include "obscura/gpu_shaders.h"
#include "obscura/gtao_mips.h"
#include "obscura/image_io.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

namespace {

using obscura::clitest::CliResult;
using obscura::clitest::runCli;

struct Difference {
    double mean = 0, max = 0;
};

Difference difference(const obscura::Image& a, const obscura::Image& b) {
    Difference d;
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.channels, b.channels);
    if (a.pixels.size() != b.pixels.size() || a.pixels.empty()) return {1e9, 1e9};
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const double e = std::fabs(double(a.pixels[i]) - double(b.pixels[i]));
        d.mean += e;
        d.max = std::max(d.max, e);
    }
    d.mean /= double(a.pixels.size());
    return d;
}

class GpuCommands : public obscura::clitest::CliTest {
protected:
    void SetUp() override {
        CliTest::SetUp();
        if (obscura::gpu::deviceCount() == 0) GTEST_SKIP() << "no Vulkan device: the GPU paths are not run";
    }
    // Runs a command that must succeed on the GPU with validation on and no validation message.
    CliResult runGpu(const std::string& args) {
        const obscura::testutil::ScopedEnv validation("OBSCURA_VALIDATION", "1");
        CliResult r = runCli(args + " --gpu");
        EXPECT_EQ(r.code, 0) << args << "\n" << r.out;
        EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
        return r;
    }
    // `bench --gpu ARGS --json` without and with FLAG: the two reports, each checked to say whether FLAG was
    // given (its JSON field `field`), and to hold `cases` cases.
    std::pair<nlohmann::json, nlohmann::json> benchWithout(const std::string& args, const std::string& flag,
                                                           const char* field, std::size_t cases) {
        const nlohmann::json a = nlohmann::json::parse(runGpu(args).out);
        const nlohmann::json b = nlohmann::json::parse(runGpu(args + " " + flag).out);
        EXPECT_EQ(a[field], false) << field;
        EXPECT_EQ(b[field], true) << field;
        EXPECT_EQ(a["cases"].size(), cases);
        EXPECT_EQ(b["cases"].size(), cases);
        return {a, b};
    }
    // The bytes per frame of case i that the flag of benchWithout saved.
    static double bytesSaved(const nlohmann::json& without, const nlohmann::json& with, int i) {
        return without["cases"][i]["bytes_per_frame"].get<double>() - with["cases"][i]["bytes_per_frame"].get<double>();
    }
    // `render ARGS` on the GPU without and with FLAG, a way of dispatching that must not change the result: the
    // summary with it says `summary`, and the frames and the AO of both agree, to the bit on lavapipe (1e-6
    // elsewhere).
    void expectSameRenderWith(const std::string& args, const std::string& flag, const std::string& summary) {
        const std::string base = "render " + args + " -q";
        runGpu(base + " -o " + path("a.exr") + " --aov-dir " + path("a"));
        const CliResult with = runGpu(base + " " + flag + " -o " + path("b.exr") + " --aov-dir " + path("b"));
        EXPECT_NE(with.out.find(summary), std::string::npos) << with.out;
        const double bound = with.out.find("llvmpipe") != std::string::npos ? 0.0 : 1e-6;
        EXPECT_LE(difference(obscura::readExr(path("a.exr")), obscura::readExr(path("b.exr"))).max, bound)
            << args << " " << flag;
        EXPECT_LE(difference(obscura::readExr(path("a/ao.exr")), obscura::readExr(path("b/ao.exr"))).max, bound)
            << args << " " << flag;
    }
    // `render ARGS` on the CPU and on the GPU, each with its AOVs: the linear frames (EXR) and the AO.
    struct Pair {
        Difference frame, ao;
    };
    Pair renderBoth(const std::string& args) {
        const std::string base = "render " + args + " -q";
        const CliResult cpu = runCli(base + " -o " + path("cpu.exr") + " --aov-dir " + path("cpu"));
        EXPECT_EQ(cpu.code, 0) << cpu.out;
        const CliResult gpu = runGpu(base + " -o " + path("gpu.exr") + " --aov-dir " + path("gpu"));
        EXPECT_NE(gpu.out.find(", on "), std::string::npos) << "the device is named: " << gpu.out;
        return {difference(obscura::readExr(path("cpu.exr")), obscura::readExr(path("gpu.exr"))),
                difference(obscura::readExr(path("cpu/ao.exr")), obscura::readExr(path("gpu/ao.exr")))};
    }
};

// --gpu-fused-blur: the estimator and the blur's horizontal pass in one dispatch give the frame and the AO of
// the three dispatches (the same bits on lavapipe; 1e-6 elsewhere), with and without a guard band, and say so
// in the summary; without --gpu or with another blur it fails in one line, writing nothing.
TEST_F(GpuCommands, RenderAlchemyFusedBlurMatchesTheSeparatePasses) {
    for (const char* band : {"0", "12"})
        expectSameRenderWith(std::string("stairs --size 97x61 --ao alchemy --ao-guard-band ") + band,
                             "--gpu-fused-blur", "rows fused into the estimator");
    expectFailure("render --ao alchemy --gpu-fused-blur -o " + path("c.png"), {"--gpu-fused-blur", "--gpu"});
    expectFailure("render --ao alchemy --gpu --gpu-fused-blur --blur 2d -o " + path("c.png"), {"--gpu-fused-blur"});
    expectFailure("render --ao gtao --gpu --gpu-fused-blur -o " + path("c.png"), {"--gpu-fused-blur", "alchemy"});
    EXPECT_FALSE(std::filesystem::exists(path("c.png")));
}

// --gpu-tiled-blur: the blur's two passes in one tiled dispatch give the frame and the AO of the two
// dispatches (the same bits on lavapipe; 1e-6 elsewhere), with the normal weight too, and say so; it fails in
// one line without --gpu, with another blur, a radius its tile cannot hold, or beside --gpu-fused-blur.
TEST_F(GpuCommands, RenderAlchemyTiledBlurMatchesTheTwoPasses) {
    for (const char* extra : {"", " --blur-normal-weight on --blur-radius 8"})
        expectSameRenderWith(std::string("cabinet --size 77x45 --ao alchemy") + extra, "--gpu-tiled-blur",
                             "both passes in one tiled dispatch");
    expectFailure("render --ao alchemy --gpu-tiled-blur -o " + path("c.png"), {"--gpu-tiled-blur", "--gpu"});
    expectFailure("render --ao alchemy --gpu --gpu-tiled-blur --blur 2d -o " + path("c.png"), {"--gpu-tiled-blur"});
    expectFailure("render --ao alchemy --gpu --gpu-tiled-blur --blur-radius 9 -o " + path("c.png"),
                  {"--gpu-tiled-blur", "up to 8"});
    expectFailure("render --ao alchemy --gpu --gpu-tiled-blur --gpu-fused-blur -o " + path("c.png"),
                  {"--gpu-tiled-blur", "--gpu-fused-blur"});
    EXPECT_FALSE(std::filesystem::exists(path("c.png")));
}

// The bound: `render --gpu --ao gtao` and the CPU path give frames whose mean absolute difference is
// at most 1e-3 (linear radiance, which is about 0.1-1 on these views). Measured on lavapipe (Mesa 22.3.6,
// LLVM 15.0.6), 2026-11-28, the 13 cases below: frame mean 4.4e-6 to 1.6e-5 (the largest: stairs with nearest
// samples), AO max 6.4e-5 to 1.5e-4 (the "[ measured ]" lines of a run).
TEST_F(GpuCommands, RenderGtaoMatchesTheCpu) {
    const char* cases[] = {
        "demo --size 96x54 --ao gtao",
        "stairs --size 97x55 --ao gtao --ao-quality ultra --multibounce --specular-occlusion lut4 --ao-output all",
        "well --size 64x48 --ao gtao --frames 3",                                 // temporal
        "demo --size 75x41 --ao gtao --frames 2 --gtao-mode spatial --gtao-half-res",
        "corner --size 70x40 --ao gtao --frames 3 --gtao-half-res --gtao-packed-history",
        "stairs --size 81x47 --ao gtao --frames 3 --gtao-sampling nearest",  // temporal, nearest samples
        "demo --size 99x57 --ao gtao --gtao-sampling mip",                     // depth MIP chain
        "stairs --size 81x47 --ao gtao --frames 3 --gtao-sampling planar-mip --gtao-half-res",  // temporal, half
        "demo --size 75x41 --ao gtao --gtao-half-res --gtao-slices 2 --gtao-steps 4 --gtao-interleave",  // full, half
        "well --size 70x40 --ao gtao --gtao-half-res --gtao-half-blur-radius 0",
        "demo --size 97x55 --ao gtao --frames 3 --gtao-half-res --gtao-grid-history --gtao-packed-history",
        "stairs --size 81x47 --ao gtao --frames 5 --gtao-alternating-window",
        "demo --size 97x55 --ao gtao --frames 5 --gtao-half-res --gtao-grid-history --gtao-alternating-window "
        "--gtao-alternating-window-size 2",
    };
    for (const char* c : cases) {
        const Pair d = renderBoth(c);
        EXPECT_LE(d.frame.mean, 1e-3) << c;
        EXPECT_LE(d.ao.max, 2e-3) << c;
        if (std::string(c).find("--specular-occlusion") != std::string::npos) {  // written with --ao-output all only
            EXPECT_LE(difference(obscura::readExr(path("cpu/specular_occlusion.exr")),
                                 obscura::readExr(path("gpu/specular_occlusion.exr"))).max, 2e-3) << c;
        }
        std::printf("[ measured ] render %s: frame mean |diff| %.2e, AO max |diff| %.2e\n", c, d.frame.mean, d.ao.max);
    }
}

// --gpu-packed-normals and --gpu-packed-output (gpu::GtaoTemporalFormats, gpu::AlchemyFormats): the
// spatio-temporal target's configuration with the G-buffer's normals as octahedral words and a 16-bit
// visibility, and the Alchemy target's with the words and the tiled blur, match the CPU's float frames within
// the bounds of every other GPU frame and say so in their summaries; each flag refuses what it cannot serve
// in one line, writing nothing.
TEST_F(GpuCommands, RenderPackedFormatsMatchTheCpu) {
    const std::string args = "render demo --size 97x55 --ao gtao --frames 5 --gtao-half-res --gtao-grid-history "
                             "--gtao-packed-history --gtao-alternating-window --gtao-alternating-window-size 2 "
                             "--gtao-sampling planar-nearest -q";
    const CliResult cpu = runCli(args + " -o " + path("cpu.exr") + " --aov-dir " + path("cpu"));
    ASSERT_EQ(cpu.code, 0) << cpu.out;
    const CliResult gpu = runGpu(args + " --gpu-packed-normals --gpu-packed-output -o " + path("gpu.exr") +
                                 " --aov-dir " + path("gpu"));
    EXPECT_NE(gpu.out.find(", octahedral normals, 16-bit visibility)"), std::string::npos) << gpu.out;
    const Difference frame = difference(obscura::readExr(path("cpu.exr")), obscura::readExr(path("gpu.exr")));
    const Difference ao = difference(obscura::readExr(path("cpu/ao.exr")), obscura::readExr(path("gpu/ao.exr")));
    EXPECT_LE(frame.mean, 1e-3);
    EXPECT_LE(ao.max, 2e-3);
    std::printf("[ measured ] packed formats: frame mean |diff| %.2e, AO max |diff| %.2e\n", frame.mean, ao.max);

    // The Alchemy estimator with the words, and the blur in one tiled dispatch (the Alchemy target's variant).
    const std::string alchemy = "render stairs --size 81x47 --ao alchemy -q";
    ASSERT_EQ(runCli(alchemy + " -o " + path("a_cpu.exr") + " --aov-dir " + path("a_cpu")).code, 0);
    const CliResult alchemyGpu = runGpu(alchemy + " --gpu-packed-normals --gpu-tiled-blur -o " + path("a_gpu.exr") +
                                        " --aov-dir " + path("a_gpu"));
    EXPECT_NE(alchemyGpu.out.find(", octahedral normals)"), std::string::npos) << alchemyGpu.out;
    EXPECT_LE(difference(obscura::readExr(path("a_cpu/ao.exr")), obscura::readExr(path("a_gpu/ao.exr"))).max, 2e-3);
    expectFailure(alchemy + " -o " + path("y.png") + " --gpu --gpu-packed-normals --ao-normals-from-depth",
                  {"--gpu-packed-normals", "--ao-normals-from-depth"});

    const std::string base = "render demo --size 48x32 --ao gtao -q -o " + path("x.png");
    expectFailure(base + " --frames 3 --gpu-packed-normals", {"--gpu-packed-normals", "needs --gpu"});
    expectFailure(base + " --gpu --gpu-packed-normals", {"--gpu-packed-normals", "spatial or temporal mode"});
    expectFailure(base + " --gpu --frames 3 --gtao-half-res --gpu-packed-output",
                  {"--gpu-packed-output", "--gtao-grid-history"});
}

// --gpu-fused-temporal (gpu::GtaoTemporalDispatch::Fused): the spatio-temporal target's configuration with
// GTAO and the accumulation in one dispatch gives the frame of the two dispatches (bit for bit on lavapipe,
// GpuGtaoTemporal.FusedPassGivesTheFrameOfTheThreeDispatches; here within the bound any GPU frame keeps to the
// CPU's) and says so in its summary; it refuses, in one line, a run without --gpu or the grid's history.
TEST_F(GpuCommands, RenderFusedTemporalGivesTheFrameOfTheTwoDispatches) {
    const std::string args = "render stairs --size 91x53 --ao gtao --frames 5 --gtao-half-res --gtao-grid-history "
                             "--gtao-packed-history --gtao-alternating-window --gtao-alternating-window-size 2 "
                             "--gtao-sampling planar-nearest --ao-output all -q --gpu";
    const CliResult separate = runGpu(args + " -o " + path("two.exr") + " --aov-dir " + path("two"));
    ASSERT_EQ(separate.code, 0) << separate.out;
    const CliResult fused = runGpu(args + " --gpu-fused-temporal -o " + path("one.exr") + " --aov-dir " + path("one"));
    ASSERT_EQ(fused.code, 0) << fused.out;
    EXPECT_NE(fused.out.find(", GTAO and accumulation in one dispatch)"), std::string::npos) << fused.out;
    EXPECT_EQ(separate.out.find("one dispatch"), std::string::npos) << separate.out;
    const Difference ao = difference(obscura::readExr(path("two/ao.exr")), obscura::readExr(path("one/ao.exr")));
    const Difference bent =
        difference(obscura::readExr(path("two/bent_normal.exr")), obscura::readExr(path("one/bent_normal.exr")));
    // The same values: on lavapipe, where the test suite runs, the same bits; elsewhere within the bounds of
    // any GPU frame against the CPU's, as a compiler may contract a multiply-add in one shader and not the other.
    if (fused.out.find("llvmpipe") != std::string::npos) {
        EXPECT_EQ(ao.max, 0.0);
        EXPECT_EQ(bent.max, 0.0);
    }
    EXPECT_LE(ao.max, 2e-3);
    EXPECT_LE(bent.max, 1e-2);
    std::printf("[ measured ] fused against two dispatches: AO max |diff| %.2e, bent normal max %.2e\n", ao.max,
                bent.max);
    const std::string base = "render demo --size 48x32 --ao gtao -q -o " + path("x.png");
    expectFailure(base + " --frames 3 --gtao-half-res --gtao-grid-history --gpu-fused-temporal",
                  {"--gpu-fused-temporal", "needs --gpu"});
    expectFailure(base + " --gpu --frames 3 --gtao-half-res --gpu-fused-temporal",
                  {"--gpu-fused-temporal", "--gtao-grid-history"});
    EXPECT_FALSE(std::filesystem::exists(path("x.png")));
}

// The GPU computes the bent normal only where something reads it (GtaoOutputs; RenderGtaoMatchesTheCpu runs
// the AO-only frames). Asked for with --ao-output, the last frame's bent_normal.exr matches the CPU's to the
// passes' bound (1e-2 per component, tests/gpu), with one frame and with the history.
TEST_F(GpuCommands, RenderGtaoBentNormalOnlyWhenAskedFor) {
    for (const char* c : {"well --size 64x48 --ao gtao --ao-output bent-normal",
                          "well --size 64x48 --ao gtao --frames 2 --ao-output bent-normal",
                          "well --size 63x47 --ao gtao --gtao-half-res --ao-output bent-normal"}) {
        const Pair d = renderBoth(c);
        EXPECT_LE(d.frame.mean, 1e-3) << c;
        const Difference bent =
            difference(obscura::readExr(path("cpu/bent_normal.exr")), obscura::readExr(path("gpu/bent_normal.exr")));
        EXPECT_LE(bent.max, 1e-2) << c;
        std::printf("[ measured ] render %s: bent normal max |diff| %.2e\n", c, bent.max);
    }
}

TEST_F(GpuCommands, RenderAlchemyAndRayTracedMatchTheCpu) {
    for (const char* c : {"corner --size 64x40 --ao alchemy --blur 2d", "demo --size 64x40 --ao raytraced --ao-rays 8"}) {
        const Pair d = renderBoth(c);
        EXPECT_LE(d.frame.mean, 1e-4) << c;
        EXPECT_LE(d.ao.max, 2e-3) << c;
    }
}

TEST_F(GpuCommands, AoGtaoMatchesTheCpu) {
    CliResult r = runCli("render well --size 64x48 -q --ao none -o " + path("f.png") + " --aov-dir " + path("aov"));
    ASSERT_EQ(r.code, 0) << r.out;
    const std::string in = "ao --depth " + path("aov/depth.exr") + " --normal " + path("aov/normal.exr") + " --camera " +
                           path("aov/camera.json");
    for (const std::string method : {"gtao", "gtao-ultra"}) {
        r = runCli(in + " --method " + method + " --blur separable -o " + path("cpu.exr"));
        ASSERT_EQ(r.code, 0) << r.out;
        r = runGpu(in + " --method " + method + " --blur separable -o " + path("gpu.exr"));
        EXPECT_NE(r.out.find(method + " AO on"), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find("on CPU"), std::string::npos) << r.out;
        EXPECT_LE(difference(obscura::readExr(path("cpu.exr")), obscura::readExr(path("gpu.exr"))).max, 2e-3) << method;
    }
}

TEST_F(GpuCommands, CompareGivesTheCpuErrors) {
    const std::string args = "compare corner --methods alchemy,gtao --size 48x32 --rays 32 --blur separable --json -o ";
    CliResult cpu = runCli(args + path("cpu.png"));
    ASSERT_EQ(cpu.code, 0) << cpu.out;
    CliResult gpu = runGpu(args + path("gpu.png"));
    const nlohmann::json c = nlohmann::json::parse(cpu.out), g = nlohmann::json::parse(gpu.out);
    EXPECT_EQ(c["device"], "CPU");
    EXPECT_NE(g["device"], "CPU");
    ASSERT_EQ(c["methods"].size(), 2u);
    ASSERT_EQ(g["methods"].size(), 2u);
    // Same reference rays (same seed); the methods differ by at most 2e-3 per pixel, so their errors do too.
    for (int i = 0; i < 2; ++i)
        for (const char* key : {"mae", "rmse", "bias"})
            EXPECT_NEAR(c["methods"][i][key].get<double>(), g["methods"][i][key].get<double>(), 2e-3) << key << " " << i;
}

// bench --gpu at a tiny size with a few frames: the harness runs every case and reports what the issue asks
// (per-pass ms, Mpixel/s, bytes per frame and their share of the ceiling, device and driver).
TEST_F(GpuCommands, BenchGpuReportsEveryCase) {
    const CliResult r = runCli("bench --gpu --sizes 40x24,33x19 --frames 3 --warmup 1 --inputs 2 --json");
    ASSERT_EQ(r.code, 0) << r.out;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_FALSE(j["device"].get<std::string>().empty());
    EXPECT_FALSE(j["driver"].get<std::string>().empty());
    EXPECT_EQ(j["frames"], 3);
    ASSERT_EQ(j["cases"].size(), 16u);  // 8 cases x 2 sizes
    // Each case's passes, and the shaders its frames dispatched by their src/gpu/shaders names: scripts/gpu-waiting
    // times a changed shader in the cases that name it, so a case must name every shader it runs and no other.
    struct Expected {
        std::set<std::string> passes;
        std::vector<std::string> shaders;  // sorted
    };
    const std::map<std::string, Expected> expected = {
        {"alchemy", {{"alchemy", "blur"}, {"alchemy", "bilateral_separable"}}},
        {"alchemy-fused", {{"alchemy-rows", "blur-columns"}, {"alchemy_blur_row", "bilateral_separable"}}},
        {"gtao", {{"gtao", "blur"}, {"bilateral_separable", "gtao"}}},
        {"gtao-half", {{"gtao", "blur", "upsample"}, {"bilateral_separable", "gtao", "upsample_depth_aware"}}},
        // At full resolution the last pass reconstructs its own pixel; at half it upsamples its own pixel.
        {"gtao-spatial", {{"gtao", "resolve"}, {"gtao", "gtao_temporal"}}},
        {"gtao-temporal", {{"gtao", "temporal"}, {"gtao", "gtao_temporal"}}},
        {"gtao-temporal-half",
         {{"gtao", "denoise", "temporal"}, {"gtao", "gtao_temporal", "reconstruct_interleaved"}}},
        // With the grid's history the accumulation reconstructs its grid pixel, and the upsampling comes last.
        {"gtao-temporal-grid",
         {{"gtao", "temporal", "upsample"}, {"gtao", "gtao_temporal", "upsample_depth_aware"}}}};
    for (const auto& c : j["cases"]) {
        const std::string name = c["case"];
        ASSERT_TRUE(expected.count(name)) << name;
        EXPECT_EQ(c["shaders"].get<std::vector<std::string>>(), expected.at(name).shaders) << name;
        // A frame's time is its passes' added up (gpu_bench.h), so the passes are named, in order, and
        // timed; the frames' split into passes is checked by benchGpuCase itself (each frame must time the
        // first frame's passes), which the batched run below exercises.
        std::set<std::string> seen;
        for (const auto& p : c["passes"]) {
            seen.insert(p["name"].get<std::string>());
            EXPECT_GE(p["min_ms"].get<double>(), 0.0);
            EXPECT_LE(p["min_ms"].get<double>(), p["median_ms"].get<double>());
        }
        EXPECT_EQ(seen, expected.at(name).passes) << name;
        const double ms = c["median_ms"].get<double>();
        EXPECT_GT(ms, 0.0) << name;
        EXPECT_LE(c["min_ms"].get<double>(), ms) << name;
        const double px = c["width"].get<double>() * c["height"].get<double>();
        EXPECT_NEAR(c["mpixels_per_s"].get<double>(), px / (ms * 1e3), 1e-6 * px / (ms * 1e3)) << name;
        // At least the depth and normals read and one float per pixel written.
        EXPECT_GE(c["bytes_per_frame"].get<double>(), px * 20) << name;
        EXPECT_NEAR(c["fraction_of_peak"].get<double>(), c["gbytes_per_s"].get<double>() / 3000.0, 1e-9) << name;
    }
    // The fused Alchemy case neither writes nor reads back the raw AO, nor reads depth a third time.
    for (std::size_t i = 0; i + 1 < j["cases"].size(); ++i)
        if (j["cases"][i]["case"] == "alchemy") {
            const auto& a = j["cases"][i];
            const auto& f = j["cases"][i + 1];
            ASSERT_EQ(f["case"], "alchemy-fused");
            EXPECT_EQ(a["bytes_per_frame"].get<double>() - f["bytes_per_frame"].get<double>(),
                      12.0 * a["width"].get<double>() * a["height"].get<double>());
        }
    // --frames-per-submit: frames recorded back to back in one submission, here 3 per submission over 2
    // warm-up and 5 timed frames (so one submission holds both, and the last holds 1); the same passes per
    // case, each frame's split checked as it is read (above), with validation on (the barriers between the
    // frames of a submission included).
    const CliResult batched = [&] {
        const obscura::testutil::ScopedEnv validation("OBSCURA_VALIDATION", "1");
        return runCli("bench --gpu --sizes 24x16 --frames 5 --warmup 2 --inputs 2 --frames-per-submit 3 --json");
    }();
    ASSERT_EQ(batched.code, 0) << batched.out;
    EXPECT_EQ(batched.out.find("warning"), std::string::npos) << batched.out;
    const nlohmann::json bj = nlohmann::json::parse(batched.out.substr(batched.out.find('{')));
    EXPECT_EQ(j["frames_per_submit"], 1);
    EXPECT_EQ(bj["frames_per_submit"], 3);
    EXPECT_EQ(bj["validation"], true);
    ASSERT_EQ(bj["cases"].size(), 8u);
    for (const auto& c : bj["cases"]) {
        std::set<std::string> seen;
        for (const auto& p : c["passes"]) {
            seen.insert(p["name"].get<std::string>());
            EXPECT_GT(p["min_ms"].get<double>(), 0.0);
        }
        EXPECT_EQ(seen, expected.at(c["case"].get<std::string>()).passes) << c["case"];
    }

    const CliResult table = runCli("bench --gpu --sizes 32x20 --cases gtao --frames 2 --warmup 0 --inputs 1");
    ASSERT_EQ(table.code, 0) << table.out;
    for (const char* needle : {"Mpixel/s", "%peak", "gtao", "32x20", "median of 2 frames"})
        EXPECT_NE(table.out.find(needle), std::string::npos) << needle << " in " << table.out;

    // --visibility-only: the same passes without the bent normal's planes. Per pixel, the GTAO case writes 3
    // floats less; the full-resolution temporal case 15 less (3 raw written and read, 3 history read and
    // written, 3 view out).
    const std::string small = "bench --gpu --sizes 40x24 --frames 2 --warmup 0 --inputs 1 --cases gtao,gtao-temporal --json";
    const CliResult withBent = runCli(small), aoOnly = runCli(small + " --visibility-only");
    ASSERT_EQ(withBent.code, 0) << withBent.out;
    ASSERT_EQ(aoOnly.code, 0) << aoOnly.out;
    const nlohmann::json b = nlohmann::json::parse(withBent.out), a = nlohmann::json::parse(aoOnly.out);
    EXPECT_EQ(b["bent_normals"], true);
    EXPECT_EQ(a["bent_normals"], false);
    ASSERT_EQ(a["cases"].size(), 2u);
    const double px = 40 * 24;
    EXPECT_EQ(b["cases"][0]["bytes_per_frame"].get<double>() - a["cases"][0]["bytes_per_frame"].get<double>(), px * 12);
    EXPECT_EQ(b["cases"][1]["bytes_per_frame"].get<double>() - a["cases"][1]["bytes_per_frame"].get<double>(), px * 60);
    EXPECT_NE(a["cases"][1]["description"].get<std::string>().find("visibility only"), std::string::npos);

    // --packed-history: the temporal case's history is 3 words per pixel, read and written, instead of 9
    // (depth, world normal, visibility + length, world bent normal: 1 + 1 + 1 + 1 against 1 + 3 + 1 + 3 + 1).
    const CliResult packed = runCli(small + " --packed-history");
    ASSERT_EQ(packed.code, 0) << packed.out;
    const nlohmann::json p = nlohmann::json::parse(packed.out);
    EXPECT_EQ(p["packed_history"], true);
    EXPECT_EQ(b["cases"][0]["bytes_per_frame"], p["cases"][0]["bytes_per_frame"]);  // no history in `gtao`
    EXPECT_EQ(b["cases"][1]["bytes_per_frame"].get<double>() - p["cases"][1]["bytes_per_frame"].get<double>(),
              px * 4 * 2 * (9 - 4));

    // --keep-previous-depth: the history writes no copy of depth, one float per pixel less.
    const CliResult kept = runCli(small + " --keep-previous-depth");
    ASSERT_EQ(kept.code, 0) << kept.out;
    const nlohmann::json k = nlohmann::json::parse(kept.out);
    EXPECT_EQ(k["keep_previous_depth"], true);
    EXPECT_EQ(b["cases"][1]["bytes_per_frame"].get<double>() - k["cases"][1]["bytes_per_frame"].get<double>(), px * 4);

    // --gtao-sampling nearest: the same buffers (the extra reads of planar samples hit in cache), said in the
    // report and in each GTAO case's description.
    const CliResult nearest = runCli(small + " --gtao-sampling nearest");
    ASSERT_EQ(nearest.code, 0) << nearest.out;
    const nlohmann::json n = nlohmann::json::parse(nearest.out);
    EXPECT_EQ(b["gtao_sampling"], "planar");
    EXPECT_EQ(n["gtao_sampling"], "nearest");
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(b["cases"][i]["bytes_per_frame"], n["cases"][i]["bytes_per_frame"]);
        EXPECT_NE(n["cases"][i]["description"].get<std::string>().find("nearest-pixel samples"), std::string::npos);
        EXPECT_EQ(b["cases"][i]["description"].get<std::string>().find("nearest"), std::string::npos);
    }

    // --gtao-sampling mip: said in the report and the descriptions; the chain's pass adds its compulsory
    // traffic (the depth read once, the chain written once and read once) to both GTAO cases.
    const CliResult mip = runCli(small + " --gtao-sampling mip");
    ASSERT_EQ(mip.code, 0) << mip.out;
    const nlohmann::json m = nlohmann::json::parse(mip.out);
    EXPECT_EQ(m["gtao_sampling"], "mip");
    const double chain = 4.0 * double(obscura::ssao::gtaoMipOffset(40, 24, 5));
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(m["cases"][i]["bytes_per_frame"].get<double>() - b["cases"][i]["bytes_per_frame"].get<double>(),
                  px * 4 + 2 * chain);
        EXPECT_NE(m["cases"][i]["description"].get<std::string>().find("depth MIP samples (5 levels, ratio 7)"),
                  std::string::npos);
    }
    EXPECT_EQ(m["gtao_mip_ratio"], 7.0);
    const CliResult mip4 = runCli(small + " --gtao-sampling mip --gtao-mip-ratio 3.5");
    ASSERT_EQ(mip4.code, 0) << mip4.out;
    const nlohmann::json m4 = nlohmann::json::parse(mip4.out);
    EXPECT_EQ(m4["gtao_mip_ratio"], 3.5);
    EXPECT_NE(m4["cases"][0]["description"].get<std::string>().find("ratio 3.5)"), std::string::npos);

    // --gtao-slices, --gtao-steps, --gtao-jitter: the counts in the report and the descriptions (the temporal
    // cases keep --temporal-slices, and only the gtao case is jittered); the same buffers.
    const CliResult counts = runCli(small + " --gtao-slices 2 --gtao-steps 4 --gtao-jitter");
    ASSERT_EQ(counts.code, 0) << counts.out;
    const nlohmann::json c = nlohmann::json::parse(counts.out);
    EXPECT_EQ(b["gtao_slices"], 0);
    EXPECT_EQ(c["gtao_slices"], 2);
    EXPECT_EQ(c["gtao_steps"], 4);
    EXPECT_EQ(c["gtao_jitter"], true);
    EXPECT_NE(b["cases"][0]["description"].get<std::string>().find("GTAO high (3 slices x 3 steps per side, r"),
              std::string::npos);
    EXPECT_NE(c["cases"][0]["description"].get<std::string>().find("GTAO (2 slices x 4 steps per side, jittered, r"),
              std::string::npos);
    EXPECT_NE(c["cases"][1]["description"].get<std::string>().find("(1 slice x 4 steps per side, 4x4 interleave"),
              std::string::npos);
    for (int i = 0; i < 2; ++i) EXPECT_EQ(b["cases"][i]["bytes_per_frame"], c["cases"][i]["bytes_per_frame"]);

    // The gtao-half case: 2 slices x 4 steps with the 4x4 interleave and a 5-tap grid blur unless told
    // otherwise (--gtao-* counts, --gtao-jitter, --half-blur-radius); the same buffers either way.
    const std::string half = "bench --gpu --sizes 40x24 --frames 2 --warmup 0 --inputs 1 --json --cases gtao-half";
    const CliResult h0 = runCli(half), h1 = runCli(half + " --gtao-slices 3 --gtao-jitter --half-blur-radius 4");
    ASSERT_EQ(h0.code, 0) << h0.out;
    ASSERT_EQ(h1.code, 0) << h1.out;
    const nlohmann::json j0 = nlohmann::json::parse(h0.out), j1 = nlohmann::json::parse(h1.out);
    EXPECT_EQ(j0["half_blur_radius"], 2);
    EXPECT_EQ(j1["half_blur_radius"], 4);
    EXPECT_NE(j0["cases"][0]["description"].get<std::string>().find(
                  "half resolution (2 slices x 4 steps per side, 4x4 interleave, r 1 m)"),
              std::string::npos)
        << j0["cases"][0]["description"];
    EXPECT_NE(j0["cases"][0]["description"].get<std::string>().find("5 taps per axis"), std::string::npos);
    EXPECT_NE(j1["cases"][0]["description"].get<std::string>().find("(3 slices x 4 steps per side, jittered, r 1 m)"),
              std::string::npos)
        << j1["cases"][0]["description"];
    EXPECT_NE(j1["cases"][0]["description"].get<std::string>().find("9 taps per axis"), std::string::npos);
    EXPECT_EQ(j0["cases"][0]["bytes_per_frame"], j1["cases"][0]["bytes_per_frame"]);
    expectFailure(half + " --half-blur-radius 0", {"half-blur-radius", "[1, 32]"});
    // --half-blur 2d: one dispatch, so one pass of guide, input and output over the grid instead of two.
    const CliResult h2 = runCli(half + " --half-blur 2d");
    ASSERT_EQ(h2.code, 0) << h2.out;
    const nlohmann::json j2 = nlohmann::json::parse(h2.out);
    EXPECT_EQ(j0["half_blur"], "separable");
    EXPECT_EQ(j2["half_blur"], "2d");
    EXPECT_NE(j2["cases"][0]["description"].get<std::string>().find("2-D bilateral there, 5x5 taps"), std::string::npos)
        << j2["cases"][0]["description"];
    EXPECT_EQ(j0["cases"][0]["bytes_per_frame"].get<double>() - j2["cases"][0]["bytes_per_frame"].get<double>(),
              12.0 * 20 * 12);  // a 40x24 image's 20x12 grid
    std::set<std::string> twoD;
    for (const auto& pass : j2["cases"][0]["passes"]) twoD.insert(pass["name"].get<std::string>());
    EXPECT_EQ(twoD, (std::set<std::string>{"gtao", "blur", "upsample"}));
    expectFailure(half + " --half-blur box", {"--half-blur"}, 2);  // a bad command line

    // --blur-radius: the gtao case's blur taps, in the report and the description; the same buffers.
    const CliResult taps = runCli(small + " --blur-radius 2");
    ASSERT_EQ(taps.code, 0) << taps.out;
    const nlohmann::json t = nlohmann::json::parse(taps.out);
    EXPECT_EQ(b["blur_radius"], 6);
    EXPECT_EQ(t["blur_radius"], 2);
    EXPECT_NE(b["cases"][0]["description"].get<std::string>().find("13 taps per axis"), std::string::npos);
    EXPECT_NE(t["cases"][0]["description"].get<std::string>().find("5 taps per axis"), std::string::npos);
    EXPECT_EQ(b["cases"][0]["bytes_per_frame"], t["cases"][0]["bytes_per_frame"]);

    // --ao-radius: the GTAO cases' radius, in the report and the descriptions; the same buffers.
    const CliResult small4 = runCli(small + " --ao-radius 0.25");
    ASSERT_EQ(small4.code, 0) << small4.out;
    const nlohmann::json q = nlohmann::json::parse(small4.out);
    EXPECT_EQ(b["gtao_radius_m"], 1.0);
    EXPECT_EQ(q["gtao_radius_m"], 0.25);
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(b["cases"][i]["bytes_per_frame"], q["cases"][i]["bytes_per_frame"]);
        EXPECT_NE(b["cases"][i]["description"].get<std::string>().find("r 1 m"), std::string::npos);
        EXPECT_NE(q["cases"][i]["description"].get<std::string>().find("r 0.25 m"), std::string::npos);
    }
}

// --blur-tiled: the separable blurs of the alchemy, gtao and gtao-half cases in one dispatch (the fused
// alchemy case keeps its own), said in the report and the descriptions, with half the blur's bytes; radii the
// tile cannot hold fail in one line naming the flag.
TEST_F(GpuCommands, BenchGpuBlurTiled) {
    const auto [a, b] = benchWithout("bench --gpu --sizes 40x24 --frames 2 --warmup 0 --inputs 1 --json "
                                     "--cases alchemy,alchemy-fused,gtao,gtao-half",
                                     "--blur-tiled", "blur_tiled", 4);
    if (HasFailure()) return;
    for (int i = 0; i < 4; ++i) {
        const std::string name = b["cases"][i]["case"];
        const std::string description = b["cases"][i]["description"];
        const bool applies = name != "alchemy-fused";
        EXPECT_EQ(description.find("one tiled dispatch") != std::string::npos, applies) << description;
        EXPECT_EQ(a["cases"][i]["description"].get<std::string>().find("tiled"), std::string::npos);
        // One dispatch of the blur's two moves depth + AO in and AO out (4 + 4 + 4 bytes per pixel it blurs).
        const double blurred = name == "gtao-half" ? 20.0 * 12.0 : 40.0 * 24.0;
        EXPECT_DOUBLE_EQ(bytesSaved(a, b, i), applies ? blurred * 12.0 : 0.0) << name;
        std::set<std::string> passes;
        for (const auto& p : b["cases"][i]["passes"]) passes.insert(p["name"].get<std::string>());
        EXPECT_EQ(passes.count(applies ? "blur" : "blur-columns"), 1u) << name;
        // The shaders a case names are what it ran: the tiled shader in place of the separable one.
        const auto names = [](const nlohmann::json& c) { return c["shaders"].get<std::set<std::string>>(); };
        EXPECT_EQ(names(b["cases"][i]).count("bilateral_tiled"), applies ? 1u : 0u) << name;
        EXPECT_EQ(names(b["cases"][i]).count("bilateral_separable"), applies ? 0u : 1u) << name;
        EXPECT_EQ(names(a["cases"][i]).count("bilateral_tiled"), 0u) << name;
    }
    expectFailure("bench --gpu --blur-tiled --blur-radius 9", {"--blur-tiled", "up to 8", "--blur-radius is 9"});
    // Twice the same size or case printed two rows, of which scripts/gpu-ab kept the second alone.
    expectFailure("bench --gpu --sizes 8x8,16x8,8x8", {"--sizes", "8x8 is given twice"});
    expectFailure("bench --gpu --cases gtao,alchemy,gtao", {"--cases", "gtao is given twice"});
    expectFailure("bench --gpu --blur-tiled --half-blur-radius 12", {"--blur-tiled", "--half-blur-radius is 12"});
}

// --alternating-window reaches the temporal cases (not the spatial one, which has no history to average the
// windows): 6 frames, so that every phase's pipelines run; the bytes do not change. That the phases reach the
// shaders is GpuGtaoTemporal.AlternatingWindowMatchesTheCpuReference's to check.
TEST_F(GpuCommands, BenchGpuAlternatingWindow) {
    const auto [a, b] = benchWithout("bench --gpu --sizes 40x24 --frames 6 --warmup 0 --inputs 2 --json "
                                     "--visibility-only --cases gtao-spatial,gtao-temporal,gtao-temporal-half,"
                                     "gtao-temporal-grid",
                                     "--alternating-window", "alternating_window", 4);
    if (HasFailure()) return;
    for (int i = 0; i < 4; ++i) {
        const std::string name = b["cases"][i]["case"];
        const std::string description = b["cases"][i]["description"];
        EXPECT_EQ(description.find("window alternating") != std::string::npos, name != "gtao-spatial") << description;
        EXPECT_EQ(a["cases"][i]["description"].get<std::string>().find("alternating"), std::string::npos);
        EXPECT_EQ(a["cases"][i]["bytes_per_frame"], b["cases"][i]["bytes_per_frame"]) << name;
        EXPECT_NE(description.find("4x4 reconstruction") != std::string::npos, name == "gtao-spatial") << description;
    }
    EXPECT_EQ(b["alternating_window_size"], 4);
    // --alternating-window-size 2: the 2x2 windows, named in the description and the report.
    const nlohmann::json c = nlohmann::json::parse(
        runGpu("bench --gpu --sizes 40x24 --frames 6 --warmup 0 --inputs 2 --json --visibility-only "
               "--cases gtao-temporal-grid --alternating-window --alternating-window-size 2")
            .out);
    EXPECT_EQ(c["alternating_window_size"], 2);
    EXPECT_NE(c["cases"][0]["description"].get<std::string>().find("2x2 reconstruction, its window alternating"),
              std::string::npos)
        << c["cases"][0]["description"];
    expectFailure("bench --gpu --alternating-window-size 2", {"--alternating-window-size", "--alternating-window"});
    expectFailure("bench --gpu --alternating-window --alternating-window-size 3", {"--alternating-window-size"});
}

// --packed-normals reaches every case: the descriptions say so and the bytes fall by 8 per normal read. That
// the words reach the shaders is GpuPackedNormals' and
// GpuGtaoTemporal.PackedNormalsGiveTheFrameOfTheirDecodedNormals's to check.
TEST_F(GpuCommands, BenchGpuPackedNormals) {
    const auto [a, b] = benchWithout("bench --gpu --sizes 40x24 --frames 2 --warmup 0 --inputs 2 --json "
                                     "--visibility-only --cases alchemy,alchemy-fused,gtao,gtao-half,gtao-spatial,"
                                     "gtao-temporal-grid",
                                     "--packed-normals", "packed_normals", 6);
    if (HasFailure()) return;
    // Normal reads: the estimator's and the GTAO pass's per pixel (960) or grid pixel (240; the half-resolution
    // blur weighs by depth alone), and the spatio-temporal accumulation's (or resolve's) per pixel of its lattice.
    const double reads[6] = {960, 960, 960, 240, 2 * 960, 2 * 240};
    for (int i = 0; i < 6; ++i) {
        const std::string name = b["cases"][i]["case"];
        const std::string description = b["cases"][i]["description"];
        EXPECT_NE(description.find("octahedral normals"), std::string::npos) << name;
        EXPECT_EQ(a["cases"][i]["description"].get<std::string>().find("octahedral"), std::string::npos) << name;
        EXPECT_DOUBLE_EQ(bytesSaved(a, b, i), 8.0 * reads[i]) << name;
    }
}

// --packed-output reaches the gtao-temporal-grid case alone: its visibility plane, 4 bytes a pixel, becomes
// 2 (40 is even: 20 words a row).
TEST_F(GpuCommands, BenchGpuPackedOutput) {
    const auto [a, b] = benchWithout("bench --gpu --sizes 40x24 --frames 2 --warmup 0 --inputs 2 --json "
                                     "--visibility-only --cases gtao-half,gtao-temporal-half,gtao-temporal-grid",
                                     "--packed-output", "packed_output", 3);
    if (HasFailure()) return;
    for (int i = 0; i < 3; ++i) {
        const std::string name = b["cases"][i]["case"];
        const bool applies = name == "gtao-temporal-grid";
        EXPECT_EQ(b["cases"][i]["description"].get<std::string>().find("unorm16 output") != std::string::npos, applies)
            << name;
        EXPECT_DOUBLE_EQ(bytesSaved(a, b, i), applies ? 2.0 * 40 * 24 : 0.0) << name;
    }
}

// --fused-temporal reaches the gtao-temporal-grid case alone: one dispatch for GTAO and the accumulation
// (its "temporal" pass, no "gtao" pass), without the raw visibility's write and read or the accumulation's
// second read of the grid's depth and normals (1 + 1 + 1 + 3 floats per grid pixel; 20x12 at 40x24). That
// the values are the three dispatches' is GpuGtaoTemporal.FusedPassGivesTheFrameOfTheThreeDispatches's to check.
TEST_F(GpuCommands, BenchGpuFusedTemporal) {
    const auto [a, b] = benchWithout("bench --gpu --sizes 40x24 --frames 3 --warmup 0 --inputs 2 --json "
                                     "--visibility-only --cases gtao-half,gtao-temporal-half,gtao-temporal-grid",
                                     "--fused-temporal", "fused_temporal", 3);
    if (HasFailure()) return;
    for (int i = 0; i < 3; ++i) {
        const std::string name = b["cases"][i]["case"];
        const bool applies = name == "gtao-temporal-grid";
        EXPECT_EQ(b["cases"][i]["description"].get<std::string>().find("in one dispatch") != std::string::npos,
                  applies)
            << name;
        EXPECT_DOUBLE_EQ(bytesSaved(a, b, i), applies ? 4.0 * 6 * 20 * 12 : 0.0) << name;
        std::set<std::string> before, after;
        for (const auto& p : a["cases"][i]["passes"]) before.insert(p["name"].get<std::string>());
        for (const auto& p : b["cases"][i]["passes"]) after.insert(p["name"].get<std::string>());
        EXPECT_EQ(before.count("gtao"), 1u) << name;
        EXPECT_EQ(after.count("gtao"), applies ? 0u : 1u) << name;
        if (applies) {
            EXPECT_EQ(after, (std::set<std::string>{"temporal", "upsample"}));
        }
    }
}

// --pipeline-stats and --pipeline-internals: what the driver says of each pipeline the cases compiled, or,
// where it lacks VK_KHR_pipeline_executable_properties (lavapipe in Mesa 22.3), a note naming the device while
// the timings still come; a folder that cannot be made fails in one line, and a run that fails on its scene
// leaves no folder made (empty folders were left).
TEST_F(GpuCommands, BenchGpuPipelineStatistics) {
    const std::string args = "bench --gpu --sizes 24x16 --frames 1 --warmup 0 --inputs 1 --cases alchemy,gtao";
    const CliResult r = runGpu(args + " --json --pipeline-internals " + path("internals"));
    const nlohmann::json j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["cases"].size(), 2u);
    if (!j["pipeline_statistics"].get<bool>()) {
        EXPECT_EQ(j.count("pipelines"), 0u);
        const std::string note = j["pipeline_statistics_note"];
        EXPECT_NE(note.find(j["device"].get<std::string>()), std::string::npos) << note;
        EXPECT_NE(note.find("VK_KHR_pipeline_executable_properties"), std::string::npos) << note;
        const CliResult table = runGpu(args + " --pipeline-stats");
        EXPECT_NE(table.out.find("pipelines: " + j["device"].get<std::string>()), std::string::npos) << table.out;
        EXPECT_NE(table.out.find("alchemy "), std::string::npos) << "the timings still come: " << table.out;
    } else {
        // Every shader the two cases dispatch, each with an executable and a statistic, and its files written.
        std::set<std::string> shaders;
        for (const auto& p : j["pipelines"]) {
            const std::string name = p["pipeline"];
            shaders.insert(name.substr(0, name.find('<')));
            EXPECT_EQ(p["error"], "") << name;
            ASSERT_GE(p["executables"].size(), 1u) << name;
            for (const auto& x : p["executables"]) {
                EXPECT_GE(x["statistics"].size(), 1u) << name;
                for (const auto& f : x["internal_files"])
                    EXPECT_TRUE(std::filesystem::exists(f.get<std::string>())) << f;
            }
        }
        for (const char* s : {"alchemy", "bilateral_separable", "gtao"}) EXPECT_EQ(shaders.count(s), 1u) << s;
    }
    std::filesystem::create_directories(path("d"));
    { std::ofstream(path("d/file")) << "x"; }
    expectFailure(args + " --gpu --pipeline-internals " + path("d/file/sub"), {"--pipeline-internals", "d/file/sub"});
    expectFailure(args + " --pipeline-internals " + path("new/a/b") + " --scene " + path("nosuch.glb"), {"nosuch.glb"});
    EXPECT_FALSE(std::filesystem::exists(path("new")));
    // --gtao-mip-ratio where the sampling reads no ratio: warned of, as render warns (it was silent).
    const CliResult ratio = runCli("bench --gpu --sizes 8x8 --frames 1 --warmup 0 --inputs 1 --cases alchemy --gtao-mip-ratio 5");
    EXPECT_EQ(ratio.code, 0) << ratio.out;
    EXPECT_NE(ratio.out.find("warning: --gtao-mip-ratio"), std::string::npos) << ratio.out;
    EXPECT_NE(ratio.out.find("--gtao-sampling planar does not read it"), std::string::npos) << ratio.out;
}

TEST_F(GpuCommands, BenchGpuRejectsBadArguments) {
    expectFailure("bench --gpu --frames 0", {"--frames", "[1, 100000]"});
    expectFailure("bench --gpu --cases gtao,nope", {"--cases", "nope", "gtao-temporal"});
    expectFailure("bench --gpu --sizes 0x10", {"--sizes"});
    expectFailure("bench --gpu --inputs 40", {"--inputs"});
    expectFailure("bench --gpu --peak-gbps 0", {"--peak-gbps"});
    expectFailure("bench --gpu --gtao-sampling bilinear", {"--gtao-sampling", "planar,nearest,mip,planar-mip,planar-nearest"}, 2);
    expectFailure("bench --gpu --ao-radius 0", {"--ao-radius", "(0, 1e4] m"});
    expectFailure("bench --gpu --gtao-mip-ratio 1", {"--gtao-mip-ratio", "[2, 64]"});
    expectFailure("bench --gpu --gtao-slices 65", {"--gtao-slices", "[1, 64]"});
    expectFailure("bench --gpu --blur-radius 33", {"--blur-radius", "[1, 32]"});
    expectFailure("bench --gpu --gtao-steps -1", {"--gtao-steps", "[1, 256]"});
    expectFailure("bench --gpu --frames-per-submit 0", {"--frames-per-submit", "[1, 64]"});
    expectFailure("bench --gpu --frames-per-submit 65", {"--frames-per-submit", "[1, 64]"});
    expectFailure("bench --gpu --gpu-device 99 --sizes 8x8 --frames 1", {"--gpu-device", "99"});
    expectFailure("bench", {"bench", "--gpu"}, 2);  // a command line that asks for nothing: a usage error
}

// OBSCURA_SHADER_DIR: NAME.spv there replaces the embedded shader NAME, for timing a changed shader without a
// rebuild. A copy of the embedded gtao module runs; a file that is not SPIR-V, a module whose layout is not
// the host's, and a folder that does not exist each fail in one line naming what is wrong.
TEST_F(GpuCommands, ShaderDirReplacesEmbeddedShaders) {
    const std::string bench = "bench --gpu --sizes 24x16 --cases gtao --frames 2 --warmup 0 --inputs 1 --json";
    std::filesystem::create_directories(path("same"));
    const obscura::gpu::ShaderCode gtao = obscura::gpu::shaderCode("gtao");
    obscura::gpu::testing::writeModule(path("same/gtao.spv"), gtao.words, gtao.wordCount);
    obscura::testutil::ScopedEnv shaderDir("OBSCURA_SHADER_DIR", path("same"));
    const CliResult same = runCli(bench);
    EXPECT_EQ(same.code, 0) << same.out;

    // The blur's module where the GTAO pass's belongs: the host's layout check (bindings, push constants) names
    // it. The GTAO pass takes its workgroup size from the module; the blur, which dispatches by its header's,
    // refuses the GTAO module's size first (set here, so that the message does not follow the embedded size).
    std::filesystem::create_directories(path("swapped"));
    const obscura::gpu::ShaderCode blur = obscura::gpu::shaderCode("bilateral_separable");
    obscura::gpu::testing::writeModule(path("swapped/gtao.spv"), blur.words, blur.wordCount);
    shaderDir.set(path("swapped"));
    expectFailure(bench, {"shader gtao", "the host binds"});
    std::filesystem::create_directories(path("blur"));
    const std::vector<std::uint32_t> gtao16x4 = obscura::gpu::testing::withWorkgroupSize(
        std::vector<std::uint32_t>(gtao.words, gtao.words + gtao.wordCount), 16, 4);
    obscura::gpu::testing::writeModule(path("blur/bilateral_separable.spv"), gtao16x4.data(), gtao16x4.size());
    shaderDir.set(path("blur"));
    expectFailure(bench, {"shader bilateral_separable", "has workgroups of 16x4x1, the host dispatches 256x1"});

    std::filesystem::create_directories(path("bad"));
    const std::uint32_t junk[6] = {1, 2, 3, 4, 5, 6};
    obscura::gpu::testing::writeModule(path("bad/gtao.spv"), junk, 6);
    shaderDir.set(path("bad"));
    expectFailure(bench, {path("bad/gtao.spv"), "is not SPIR-V"});
    // The magic number, then an instruction that says it is longer than the file: named by its file (it was
    // "SPIR-V: truncated instruction", which named nothing).
    const std::uint32_t truncated[6] = {0x07230203u, 0x00010500u, 0, 10, 0, (9u << 16) | 17u};
    obscura::gpu::testing::writeModule(path("bad/gtao.spv"), truncated, 6);
    expectFailure(bench, {path("bad/gtao.spv") + ": is not a module the host can read (SPIR-V:"});

    shaderDir.set(path("nowhere"));
    expectFailure(bench, {"OBSCURA_SHADER_DIR", "nowhere", "is not a folder"});
}

// The GPU holds the environment as one texture. One wider than the device can hold was refused only after the
// scene was traced, in the device's words ("cannot hold a 16385x2 texture") without naming --env's file. The
// CPU path takes it; the GPU path now refuses it before any work, naming the file and the limit.
TEST_F(GpuCommands, RenderRefusesAnEnvironmentPastTheDevicesTextureLimit) {
    std::uint32_t limit = 0;
    {
        obscura::gpu::Context context;
        limit = context.device().maxImageDimension2D;
    }
    ASSERT_GT(limit, 0u);
    obscura::writeExr(path("wide.exr"), obscura::Image(int(limit) + 1, 1, 3, 0.5f));
    expectFailure("render plane --size 16x8 -q --ao gtao --gpu --env " + path("wide.exr") + " -o " + path("f.png"),
                  {path("wide.exr") + ": " + std::to_string(limit + 1) + "x1 exceeds the " + std::to_string(limit) +
                   " texels a side"});
    obscura::writeExr(path("fits.exr"), obscura::Image(int(limit), 1, 3, 0.5f));
    const CliResult fits = runCli("render plane --size 16x8 -q --ao gtao --gpu --env " + path("fits.exr") + " -o " + path("g.png"));
    EXPECT_EQ(fits.code, 0) << fits.out;
}

TEST_F(GpuCommands, RenderRejectsABadDevice) {
    expectFailure("render plane --size 16x8 -q --ao gtao --gpu --gpu-device 99 -o " + path("f.png"), {"--gpu-device", "99"});
    expectFailure("render plane --size 16x8 -q --ao gtao --gpu --gpu-device -4 -o " + path("f.png"), {"--gpu-device"});
    // Without --gpu the device flag was ignored without a word, and the work ran on the CPU.
    expectFailure("render plane --size 16x8 -q --ao gtao --gpu-device 3 -o " + path("f.png"), {"--gpu-device: needs --gpu"});
    expectFailure("ao --depth nowhere.exr --camera nowhere.json --gpu-device 0 -o " + path("f.exr"),
                  {"--gpu-device: needs --gpu"});
    // OBSCURA_VALIDATION is 0 or 1: "true" left the validation layers off, silently.
    obscura::testutil::ScopedEnv validation("OBSCURA_VALIDATION", "true");
    expectFailure("render plane --size 16x8 -q --ao gtao --gpu -o " + path("f.png"),
                  {"OBSCURA_VALIDATION: must be 0 or 1, got 'true'"});
}

} // namespace
