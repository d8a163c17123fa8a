// The GTAO compute pass (src/gpu/shaders/gtao.comp) against the CPU reference ssao::computeGtao, on
// lavapipe in CI, with validation on and no message allowed.
#include "gpu_test_util.h"
#include "gtao_difference.h"
#include "spirv_edit.h"
#include "ssao/gtao_scenes.h"

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/gtao_pass.h"
#include "gpu/shaders/layouts.h"
#include "gpu/spirv.h"

#include "obscura/alchemy.h"
#include "obscura/error.h"
#include "obscura/gpu.h"
#include "obscura/gtao.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

namespace obscura::gpu {
namespace {

using testing::GtaoDifference;
using testing::kBentBound;
using testing::kVisibilityBound;

// Pixels allowed beyond the bounds. The kernel has one discontinuity in the angles the GPU computes with
// its own sin, cos, acos and atan: the bitmask rounds each occluder's angular span to 32 sectors, so an edge
// within rounding of a sector boundary moves one sector of one slice (a sector weighs at most pi/32 = 0.098
// of its slice's open share, the integrand being <= 1; averaged over 3 slices, a few hundredths of
// visibility: the largest difference measured is 0.022). Every other
// option is continuous in them except where a sample lands within rounding of a pixel edge or of r. Any
// device: at most 0.1% of the pixels. Lavapipe (measured 2026-11-23, Mesa llvmpipe, LLVM 15.0.6): none
// without the bitmask, and at most 0.05% with it (measured 6 of 22263 on stairs, 2 of 10800 on the well).
int allowedBeyond(const Context& context, const ssao::GtaoConstants& k) {
    const int pixels = k.width * k.height;
    if (context.device().name.rfind("llvmpipe", 0) != 0) return pixels / 1000;
    return k.thicknessMode == GTAO_THICKNESS_BITMASK ? pixels / 2000 : 0;
}

// Runs both kernels on the constants, prints the differences and checks them against the bounds.
void expectMatch(Context& context, const GBuffer& g, const ssao::GtaoConstants& k, const std::string& name) {
    const ssao::GtaoResult gpu = computeGtao(context, g, k);
    const ssao::GtaoResult cpu = ssao::computeGtao(g, k);
    ASSERT_EQ(gpu.visibility.pixels.size(), cpu.visibility.pixels.size()) << name;
    ASSERT_EQ(gpu.bentNormal.pixels.size(), cpu.bentNormal.pixels.size()) << name;
    const GtaoDifference d = testing::compareGtao(gpu, cpu);
    std::printf("[ measured ] %s %dx%d: visibility max %.3g (%.3g within bounds), bent max %.3g (%.3g), "
                "%d px beyond, %d occluded, %.3f ms on the GPU\n",
                name.c_str(), k.width, k.height, d.visibility, d.visibilityRest, d.bent, d.bentRest, d.beyond,
                d.occluded, context.lastPassMs());
    EXPECT_LE(d.visibilityRest, kVisibilityBound) << name;
    EXPECT_LE(d.bentRest, kBentBound) << name;
    EXPECT_LE(d.beyond, allowedBeyond(context, k)) << name;
    EXPECT_GT(d.occluded, k.width * k.height / 50) << name;
}

ssao::GtaoSettings preset(ssao::GtaoQuality quality) {
    ssao::GtaoSettings s;
    ssao::applyQuality(s, quality);
    return s;
}

} // namespace

// The acceptance test of the pass: four built-in scenes at sizes including 333 x 197 (odd in both axes and
// not a multiple of the 8 x 8 workgroup) and the presets low, high and ultra. Bounds: 2e-3 on visibility and
// 1e-2 on each bent-normal component (allowedBeyond above for the pixels past them). Measured on lavapipe
// (2026-11-23, Mesa llvmpipe, LLVM 15.0.6), visibility / bent-normal max: demo high 333x197 1.2e-4 / 2.7e-3,
// well low 160x96 9.9e-5 / 2.1e-4, well ultra 6.5e-5 / 1.1e-4, stairs high 128x80 8.0e-5 / 1.6e-4, corner
// ultra 96x64 8.8e-5 / 1.1e-4; no pixel beyond the bounds. What remains is the GPU's trigonometry, rounded
// differently from libm (acos feeds the horizon angles, cos and sin the integrals).
TEST(GpuGtao, MatchesTheCpuReferenceOnScenesAndPresets) {
    OBSCURA_GPU_CONTEXT(context);
    const auto run = [&](const char* scene, int w, int h, ssao::GtaoQuality quality) {
        const GBuffer g = testing::render(scene, w, h);
        expectMatch(context, g, ssao::gtaoConstants(preset(quality), g.camera),
                    std::string(scene) + " " + ssao::qualityName(quality));
    };
    run("demo", 333, 197, ssao::GtaoQuality::High);
    run("well", 160, 96, ssao::GtaoQuality::Low);
    run("well", 160, 96, ssao::GtaoQuality::Ultra);
    run("stairs", 128, 80, ssao::GtaoQuality::High);
    run("corner", 96, 64, ssao::GtaoQuality::Ultra);
    EXPECT_EQ(testing::validationReport(context), "");
}

// Every option of GtaoConstants on an odd-sized stairs view and on the well (where the column beyond the
// radius matters), frame 3 for the jitter hash; interleaved slices on three frames (frame 11 wraps the 6
// rotations). Same bounds. Measured on lavapipe (as above), visibility / bent-normal max, stairs 181x123 and
// well 120x90: uniform 5.7e-5 / 1.5e-4 and 2.1e-4 / 1.1e-4; heuristic thickness 8.4e-5 / 9.6e-5 and
// 7.4e-5 / 1.1e-4; beyond radius drop 8.2e-5 / 1.5e-4 and 8.5e-5 / 1.1e-4; jitter 1.0e-4 / 1.5e-4 and
// 8.6e-5 / 1.6e-4; falloff 0.5 with step power 2 (the GPU's pow) 8.8e-5 / 9.9e-5 and 7.4e-5 / 9.7e-5;
// nearest samples (2026-11-25) 8.5e-5 / 1.0e-4 and 7.4e-5 / 1.1e-4; mip samples (2026-11-25) 8.5e-5 /
// 1.0e-4 and 7.4e-5 / 1.1e-4, with ratio 2 8.5e-5 / 1.0e-4 and 9.9e-5 / 1.2e-4, planar-mip 8.2e-5 / 1.5e-4
// and 7.2e-5 / 1.1e-4; interleaved 1.4e-4 / up to
// 3.4e-4 on each frame. Bitmask thickness: 2.2e-2 / 2.4e-2 and 5.1e-3 / 6.5e-3 over
// all pixels from 6 and 2 pixels beyond the bounds (the size of one sector of one slice, see allowedBeyond),
// and 8.7e-4 / 1.5e-3 and 7.3e-4 / 1.1e-3 on the rest.
TEST(GpuGtao, MatchesTheCpuReferenceWithEveryOption) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("stairs", 181, 123);
    const GBuffer well = testing::render("well", 120, 90);
    const ssao::GtaoSettings high = preset(ssao::GtaoQuality::High);
    ssao::GtaoSettings uniform = high;
    uniform.weighting = ssao::GtaoWeighting::Uniform;
    ssao::GtaoSettings heuristic = high;
    heuristic.thickness = ssao::GtaoThickness::Heuristic;
    ssao::GtaoSettings bitmask = high;
    bitmask.thickness = ssao::GtaoThickness::Bitmask;
    ssao::GtaoSettings drop = high;
    drop.beyondRadius = ssao::GtaoBeyondRadius::Drop;
    ssao::GtaoSettings jitter = high;
    jitter.jitter = true;
    ssao::GtaoSettings falloff = high;
    falloff.falloffStart = 0.5f;
    falloff.stepPower = 2.0f;
    falloff.radius = 0.7f;
    ssao::GtaoSettings nearest = high;
    nearest.sampling = ssao::GtaoSampling::Nearest;
    ssao::GtaoSettings mip = high;
    mip.sampling = ssao::GtaoSampling::Mip;
    ssao::GtaoSettings mipFine = mip;  // reads every level at these sizes
    mipFine.mipDistanceRatio = 2.0f;
    ssao::GtaoSettings planarMip = mip;
    planarMip.sampling = ssao::GtaoSampling::PlanarMip;
    ssao::GtaoSettings planarNearest = high;
    planarNearest.sampling = ssao::GtaoSampling::PlanarNearest;
    ssao::GtaoSettings planarNearestJittered = planarNearest;  // rotated slices, near zone of 4 pixels
    planarNearestJittered.jitter = true;
    planarNearestJittered.mipDistanceRatio = 2.0f;
    for (const auto& [name, s] :
         {std::pair{"uniform", uniform}, std::pair{"heuristic thickness", heuristic},
          std::pair{"bitmask thickness", bitmask}, std::pair{"beyond radius drop", drop}, std::pair{"jitter", jitter},
          std::pair{"falloff 0.5, step power 2", falloff}, std::pair{"nearest samples", nearest},
          std::pair{"mip samples", mip}, std::pair{"mip samples, ratio 2", mipFine},
          std::pair{"planar-mip samples", planarMip}, std::pair{"planar-nearest samples", planarNearest},
          std::pair{"planar-nearest samples, jitter, ratio 2", planarNearestJittered}}) {
        expectMatch(context, g, ssao::gtaoConstants(s, g.camera, 3), std::string("stairs ") + name);
        expectMatch(context, well, ssao::gtaoConstants(s, well.camera, 3), std::string("well ") + name);
    }
    for (int frame : {0, 4, 11}) {
        const std::string name = "interleaved frame " + std::to_string(frame);
        expectMatch(context, g, ssao::gtaoConstants(preset(ssao::GtaoQuality::Low), g.camera, frame, true),
                    "stairs " + name);
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// gtao_mips.comp against ssao::buildGtaoDepthMips: every texel of every level, at sizes odd in both axes,
// smaller than a workgroup's 16x16 pixels and a single row, on a scene with sky. The GPU's 1 / depth may
// round differently (Vulkan allows 2.5 ulp), and the means carry that on: bound 1e-6 relative, measured on
// lavapipe (2026-11-25) 0 (bit-identical).
TEST(GpuGtao, DepthMipChainMatchesTheCpuChain) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    for (const auto& [scene, w, h, levels] : {std::tuple{"demo", 333, 197, 4}, std::tuple{"stairs", 13, 7, 4},
                                              std::tuple{"corner", 40, 1, 3}, std::tuple{"plane", 1, 1, 2}}) {
        const GBuffer g = testing::render(scene, w, h);
        ssao::GtaoSettings settings;
        settings.sampling = ssao::GtaoSampling::Mip;
        settings.depthMipLevels = levels;
        const ssao::GtaoConstants k = ssao::gtaoConstants(settings, g.camera);
        const ssao::GtaoDepthMips cpu = ssao::buildGtaoDepthMips(g.depth, levels);
        const std::size_t pixels = std::size_t(w) * std::size_t(h);
        const Buffer depth = upload(c, g.depth.pixels.data(), pixels * sizeof(float));
        const Buffer chain = gtaoDepthMipsBuffer(c, w, h, levels);
        c.submit([&](VkCommandBuffer cmd) { recordGtaoDepthMips(c, cmd, depth, chain, k); });
        std::vector<float> gpu(cpu.texels.size());
        ASSERT_EQ(gpu.size(), gtaoDepthMipsFloats(w, h, levels));
        download(c, chain, gpu.data(), gpu.size() * sizeof(float));
        double worst = 0.0;
        int skyMismatch = 0, sky = 0;
        for (std::size_t i = 0; i < gpu.size(); ++i) {
            sky += cpu.texels[i] == 0.0f;
            if ((gpu[i] == 0.0f) != (cpu.texels[i] == 0.0f)) ++skyMismatch;
            else if (cpu.texels[i] != 0.0f)
                worst = std::max(worst, std::fabs(double(gpu[i]) / double(cpu.texels[i]) - 1.0));
        }
        std::printf("[ measured ] chain %s %dx%d, %d levels: %zu texels (%d sky), max relative difference %.3g\n",
                    scene, w, h, levels, gpu.size(), sky, worst);
        EXPECT_EQ(skyMismatch, 0) << scene;
        EXPECT_LE(worst, 1e-6) << scene;
        if (std::string(scene) == "demo") {
            EXPECT_GT(sky, 0);  // the sky rule is exercised
        }
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// Visibility alone (kGtaoSpecBentNormal 0, the AO-only variant an engine without bent-normal lighting
// binds) gives the full pass's visibility bit for bit and leaves the bent-normal buffer as it was.
TEST(GpuGtao, VisibilityOnlyGivesTheSameVisibility) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    ssao::GtaoSettings bitmask = preset(ssao::GtaoQuality::High);
    bitmask.thickness = ssao::GtaoThickness::Bitmask;
    for (const auto& [scene, w, h, settings] :
         {std::tuple{"demo", 333, 197, preset(ssao::GtaoQuality::High)}, std::tuple{"stairs", 160, 96, bitmask}}) {
        const GBuffer g = testing::render(scene, w, h);
        const ssao::GtaoConstants k = ssao::gtaoConstants(settings, g.camera);
        const std::size_t pixels = std::size_t(w) * std::size_t(h);
        const std::vector<float> sentinel(3 * pixels, 42.0f);
        const Buffer depth = upload(c, g.depth.pixels.data(), pixels * sizeof(float));
        const Buffer normal = upload(c, g.normal.pixels.data(), 3 * pixels * sizeof(float));
        const Buffer visibility(c, pixels * sizeof(float), MemoryUse::Device);
        const Buffer visibilityOnly(c, pixels * sizeof(float), MemoryUse::Device);
        const Buffer bent(c, 3 * pixels * sizeof(float), MemoryUse::Device);
        const Buffer untouched = upload(c, sentinel.data(), sentinel.size() * sizeof(float));
        const Buffer noChain = gtaoDepthMipsBuffer(c, w, h, k.mipLevels);  // 0 levels: the placeholder
        c.submit([&](VkCommandBuffer cmd) {
            recordGtao(c, cmd, {depth, normal, visibility, bent, noChain}, k);
            recordGtao(c, cmd, {depth, normal, visibilityOnly, untouched, noChain}, k, 1, false);
        });
        std::vector<float> a(pixels), b(pixels), left(3 * pixels);
        download(c, visibility, a.data(), pixels * sizeof(float));
        download(c, visibilityOnly, b.data(), pixels * sizeof(float));
        download(c, untouched, left.data(), left.size() * sizeof(float));
        EXPECT_EQ(a, b) << scene;
        EXPECT_EQ(left, sentinel) << scene;
        EXPECT_GT(std::count_if(a.begin(), a.end(), [](float v) { return v < 0.99f; }), std::ptrdiff_t(pixels / 50));
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The public AO-only call (GtaoOutputs::Visibility): the full call's visibility bit for bit, no bent normal.
TEST(GpuGtao, PublicVisibilityOnlyGivesTheSameVisibility) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("demo", 121, 77);
    const ssao::GtaoSettings settings = preset(ssao::GtaoQuality::High);
    const ssao::GtaoResult full = computeGtao(context, g, settings);
    const ssao::GtaoResult aoOnly = computeGtao(context, g, settings, GtaoOutputs::Visibility);
    EXPECT_EQ(full.visibility.pixels, aoOnly.visibility.pixels);
    EXPECT_EQ(full.bentNormal.pixelCount(), g.depth.pixelCount());
    EXPECT_TRUE(aoOnly.bentNormal.empty());
    EXPECT_GT(std::count_if(aoOnly.visibility.pixels.begin(), aoOnly.visibility.pixels.end(),
                            [](float v) { return v < 0.99f; }),
              std::ptrdiff_t(g.depth.pixelCount() / 50));
    EXPECT_EQ(testing::validationReport(context), "");
}

// The pass dispatches by the workgroup size its module declares (ComputePipeline::kShadersOwnSize), so that a
// candidate shader may try another size without a rebuilt host (bench/gpu-candidates). The embedded module
// rewritten to 24 x 3 workgroups (which divide neither side of 333 x 197), loaded through OBSCURA_SHADER_DIR
// into a context of its own, gives the same visibility and bent normals bit for bit, plain and with the 4x4
// interleave: each invocation evaluates its own pixel.
TEST(GpuGtao, AnotherWorkgroupSizeGivesTheSameResult) {
    OBSCURA_GPU_CONTEXT(context);
    const std::vector<std::uint32_t> words =
        testing::withWorkgroupSize({shaders::gtao.words, shaders::gtao.words + shaders::gtao.count}, 24, 3);
    ASSERT_EQ(reflect({words.data(), words.size()}).localSize[0], 24u);
    testing::ContextWithModule other("gtao", words);
    const GBuffer g = testing::render("cabinet", 333, 197);
    ssao::GtaoSettings interleaved = preset(ssao::GtaoQuality::High);
    interleaved.interleave = true;
    for (const ssao::GtaoSettings& s : {preset(ssao::GtaoQuality::High), interleaved}) {
        const ssao::GtaoResult embedded = computeGtao(context, g, s), resized = computeGtao(other.context(), g, s);
        EXPECT_EQ(resized.visibility.pixels, embedded.visibility.pixels) << "interleave " << s.interleave;
        EXPECT_EQ(resized.bentNormal.pixels, embedded.bentNormal.pixels) << "interleave " << s.interleave;
    }
    EXPECT_EQ(testing::validationReport(other.context()), "");
    // The equality above says something only if the rewritten module ran: the same loading with a size no
    // device has is refused, naming it.
    testing::ContextWithModule huge("gtao", testing::withWorkgroupSize(words, 65536, 1));
    const std::string refused = testing::errorMessage(
        [&] { computeGtao(huge.context(), testing::render("plane", 16, 8), preset(ssao::GtaoQuality::High)); });
    EXPECT_NE(refused.find("65536x1x1, beyond the device's limits"), std::string::npos) << refused;
    // The size's specialization constants keep their defaults because the host sets only its variants'
    // constant_ids: a module whose size takes one of those (here the beyond-radius mode's) is refused, naming it.
    std::vector<std::uint32_t> clash = words;
    bool renumbered = false;
    for (std::size_t i = 5; i < clash.size() && (clash[i] >> 16) != 0; i += clash[i] >> 16)
        if ((clash[i] & 0xffffu) == spirv::OpDecorate && (clash[i] >> 16) == 4 &&
            clash[i + 2] == spirv::DecorationSpecId && clash[i + 3] == std::uint32_t(kSpecWorkgroupSizeX)) {
            clash[i + 3] = std::uint32_t(kGtaoSpecBeyondRadius);
            renumbered = true;
        }
    ASSERT_TRUE(renumbered) << "gtao.comp's size is not specialization constant " << kSpecWorkgroupSizeX;
    testing::ContextWithModule clashing("gtao", clash);
    const std::string clashed = testing::errorMessage(
        [&] { computeGtao(clashing.context(), testing::render("plane", 16, 8), preset(ssao::GtaoQuality::High)); });
    EXPECT_NE(clashed.find("takes its workgroup size from constant_id " + std::to_string(kGtaoSpecBeyondRadius)),
              std::string::npos)
        << clashed;
    EXPECT_EQ(testing::validationReport(context), "");
}

// A radius past the image: the shader spreads each side's steps over what the image holds, as the CPU does
// (gtaoSideReach), at every sampling.
TEST(GpuGtao, ARadiusPastTheImageMatchesTheCpu) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("corner", 96, 64);
    for (ssao::GtaoSampling sampling : {ssao::GtaoSampling::Planar, ssao::GtaoSampling::PlanarMip}) {
        ssao::GtaoSettings s = preset(ssao::GtaoQuality::High);
        s.radius = 100.0f;
        s.maxRadiusPixels = 8192.0f;
        s.sampling = sampling;
        expectMatch(context, g, ssao::gtaoConstants(s, g.camera), std::string("r 100, ") + ssao::gtaoSamplingName(sampling));
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// A sky of 1e30 is the sky of +inf on the GPU too (gtao_pixel.glsl's planar quad took only +inf, as the CPU's
// did): the same visibility within the pass's bound.
TEST(GpuGtao, ASkyOf1e30IsTheSkyOfInfinity) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("demo", 160, 90);
    const GBuffer inf = test::withSkyHole(g, 60, 30, 100, 60, INFINITY);
    const GBuffer big = test::withSkyHole(g, 60, 30, 100, 60, 1e30f);
    ssao::GtaoSettings s = preset(ssao::GtaoQuality::High);
    s.sampling = ssao::GtaoSampling::Planar;
    const ssao::GtaoConstants k = ssao::gtaoConstants(s, inf.camera);
    const ssao::GtaoResult a = computeGtao(context, inf, k), b = computeGtao(context, big, k);
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.visibility.pixels.size(); ++i)
        worst = std::max(worst, std::fabs(a.visibility.pixels[i] - b.visibility.pixels[i]));
    EXPECT_LE(worst, kVisibilityBound);
    EXPECT_EQ(testing::validationReport(context), "");
}

// The host sets specialization constant_ids 0 to n - 1. A module that declared as many but numbered one past them
// passed the count check, and that constant kept its default without a word; it is refused, naming it. A
// pipeline whose making throws leaves nothing behind: a null entry once crashed the context's next submission,
// from any pass (here Alchemy's), and the same call fails again with the same message.
TEST(GpuGtao, ASpecializationConstantPastTheHostsIsRefused) {
    std::vector<std::uint32_t> words(shaders::gtao.words, shaders::gtao.words + shaders::gtao.count);
    bool renumbered = false;
    for (std::size_t i : testing::decorations(words, spirv::DecorationSpecId))
        if (words[i + 3] == std::uint32_t(kGtaoSpecBeyondRadius)) {
            words[i + 3] = 40;
            renumbered = true;
        }
    ASSERT_TRUE(renumbered);
    testing::ContextWithModule other("gtao", words);
    const GBuffer g = testing::render("plane", 16, 8);
    for (int attempt = 0; attempt < 2; ++attempt) {
        const std::string refused =
            testing::errorMessage([&] { computeGtao(other.context(), g, preset(ssao::GtaoQuality::High)); });
        EXPECT_NE(refused.find(", 40; the host sets constant_ids 0 to"), std::string::npos)
            << refused;
    }
    const Image ao = alchemyAO(other.context(), g, ssao::AlchemySettings{});
    EXPECT_EQ(ao.pixelCount(), g.depth.pixelCount());
    EXPECT_EQ(testing::validationReport(other.context()), "");
}

// lavapipe ends every loop of a shader invocation after 65535 iterations in all, silently: GTAO with 64 slices x
// 256 planar steps came out up to 0.44 below the CPU's visibility on a 64x48 view, with no error and exit 0.
// checkGtaoLoopBudget refuses what could run past it, naming the driver's limit. The budget is held to the
// result: at 64 slices, the most steps it allows for each sampling (and for the bitmask, whose sectors it
// counts) give the CPU's visibility within the usual bounds, and one step more is refused. Elsewhere (a real
// GPU) there is no such limit and the test has nothing to check.
TEST(GpuGtao, LavapipeRefusesWhatItsLoopLimitWouldCutShort) {
    OBSCURA_GPU_CONTEXT(context);
    if (context.device().driver.find("llvmpipe") == std::string::npos)
        GTEST_SKIP() << "not lavapipe: " << context.device().driver;
    const GBuffer g = testing::render("demo", 64, 48);
    struct Case {
        const char* name;
        ssao::GtaoSampling sampling;
        ssao::GtaoThickness thickness;
        int steps;  // the most allowed at 64 slices; 256 is the most there is
    };
    for (const Case& c : {Case{"planar", ssao::GtaoSampling::Planar, ssao::GtaoThickness::None, 65},
                          Case{"planar-nearest", ssao::GtaoSampling::PlanarNearest, ssao::GtaoThickness::None, 65},
                          Case{"mip", ssao::GtaoSampling::Mip, ssao::GtaoThickness::None, 92},
                          Case{"planar-mip", ssao::GtaoSampling::PlanarMip, ssao::GtaoThickness::None, 43},
                          Case{"nearest", ssao::GtaoSampling::Nearest, ssao::GtaoThickness::None, 256},
                          Case{"planar, bitmask", ssao::GtaoSampling::Planar, ssao::GtaoThickness::Bitmask, 11}}) {
        ssao::GtaoSettings s = preset(ssao::GtaoQuality::High);
        s.sampling = c.sampling;
        s.thickness = c.thickness;
        s.sliceCount = 64;
        s.stepsPerSide = c.steps;
        expectMatch(context, g, ssao::gtaoConstants(s, g.camera), std::string("64 x ") + std::to_string(c.steps) +
                                                                    " " + c.name);
        if (c.steps == 256) continue;
        s.stepsPerSide = c.steps + 1;
        const std::string refused = testing::errorMessage([&] { computeGtao(context, g, s); });
        EXPECT_NE(refused.find("ends a shader's loops after 65535 iterations"), std::string::npos) << refused;
        // The budget it is held to is named: "about 59200" alone read as under 65535.
        EXPECT_NE(refused.find("past the 58981 it is held to"), std::string::npos) << refused;
        EXPECT_NE(refused.find("64 slices x " + std::to_string(c.steps + 1) + " steps"), std::string::npos)
            << refused;
        EXPECT_NE(refused.find("at most " + std::to_string(64 * c.steps) + " slices x steps"), std::string::npos)
            << refused;
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The same validation and messages as ssao::computeGtao.
TEST(GpuGtao, RejectsBadInputAsTheCpuPassDoes) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("plane", 16, 16);
    const auto with = [](auto change) {
        ssao::GtaoSettings s;
        change(s);
        return s;
    };
    for (const ssao::GtaoSettings& s : {with([](auto& b) { b.radius = -1; }), with([](auto& b) { b.sliceCount = 65; }),
                                        with([](auto& b) { b.thicknessBlend = 1; })})
        testing::expectSameError([&] { ssao::computeGtao(g, s); }, [&] { computeGtao(context, g, s); });
    GBuffer small = g;
    small.normal = Image(8, 8, 3);
    GBuffer twoChannels = g;
    twoChannels.normal = Image(16, 16, 2);
    const ssao::GtaoConstants k = ssao::gtaoConstants(ssao::GtaoSettings{}, g.camera);
    ssao::GtaoConstants wider = k;
    wider.width = 17;
    for (const auto& [buffer, constants] : {std::pair{small, k}, std::pair{twoChannels, k}, std::pair{g, wider}})
        testing::expectSameError([&] { ssao::computeGtao(buffer, constants); },
                                 [&] { computeGtao(context, buffer, constants); });
    // A NaN or zero depth and a NaN normal: one message naming the first bad pixel, on both paths (the
    // shader checks nothing; a NaN would come out as NaN visibility).
    GBuffer nanDepth = g, zeroDepth = g, nanNormal = g;
    nanDepth.depth.at(3, 5) = std::nanf("");
    zeroDepth.depth.at(7, 2) = 0.0f;
    nanNormal.normal.at(9, 11, 1) = std::nanf("");
    for (const auto& [buffer, pixel] : {std::pair{nanDepth, "(3, 5)"}, std::pair{zeroDepth, "(7, 2)"},
                                        std::pair{nanNormal, "(9, 11)"}}) {
        testing::expectSameError([&] { ssao::computeGtao(buffer, k); }, [&] { computeGtao(context, buffer, k); });
        EXPECT_NE(testing::errorMessage([&] { computeGtao(context, buffer, k); }).find(pixel), std::string::npos)
            << pixel;
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

} // namespace obscura::gpu
