// The Alchemy compute pass (src/gpu/shaders/alchemy.comp) against the CPU reference ssao::alchemyPixel, on
// lavapipe in CI, with validation on and no message allowed.
#include "gpu_test_util.h"
#include "spirv_edit.h"

#include "gpu/alchemy_pass.h"
#include "gpu/image_planes.h"
#include "gpu/spirv.h"
#include "gpu/shaders/layouts.h"

#include "obscura/alchemy.h"
#include "obscura/error.h"
#include "obscura/gpu.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace obscura::gpu {
namespace {

ssao::AlchemySettings chapter() {
    ssao::AlchemySettings s;
    s.formulation = ssao::AlchemyFormulation::Chapter;
    return s;
}

// The chapter's "scene" preset (scale 2, contrast 3: the pow path) at r = 0.5 m, so that the corners of
// these small views darken (at the preset's 5 cm, 0 to 2% of their pixels are occluded).
ssao::AlchemySettings contrastCurve() {
    ssao::AlchemySettings s = ssao::alchemyPreset("scene");
    s.radius = 0.5f;
    return s;
}

// ssao::alchemyPixel for every output pixel: the scalar reference the shader mirrors.
Image reference(const GBuffer& g, const ssao::AlchemySettings& s) {
    const ssao::AlchemyConstants k = ssao::alchemyConstants(s, g.camera);
    const ssao::AlchemyInput in = ssao::alchemyInput(g, s.normalsFromDepth);
    const ssao::SpiralTable spiral = ssao::alchemySpiral(k);
    Image out(k.width - 2 * k.guardBand, k.height - 2 * k.guardBand, 1);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            out.at(x, y) = ssao::alchemyPixel(k, in, spiral, x + k.guardBand, y + k.guardBand);
    return out;
}

struct Difference {
    double max = 0;      // over all pixels
    double maxRest = 0;  // over the pixels within the bound
    int beyond = 0;      // pixels beyond the bound
    int occluded = 0;    // reference pixels below 1: the comparison is not vacuous
};

Difference compare(const Image& gpu, const Image& cpu, double bound) {
    Difference d;
    for (std::size_t i = 0; i < cpu.pixels.size(); ++i) {
        const double diff = std::fabs(double(gpu.pixels[i]) - double(cpu.pixels[i]));
        d.max = std::max(d.max, diff);
        if (diff > bound) ++d.beyond;
        else d.maxRest = std::max(d.maxRest, diff);
        d.occluded += cpu.pixels[i] < 1.0f;
    }
    return d;
}

} // namespace

// The acceptance test of the pass: three built-in scenes at three sizes (333 x 197 is odd in both axes and
// not a multiple of the 8 x 8 workgroup), both formulations and a contrast curve. The shader performs
// alchemyPixel's operations in its order; a GPU may still round differently (fused multiply-adds, a division
// within 2.5 ulp, pow), and a sample whose |v| lies within that rounding of r then falls on the other side of
// the radius and moves its pixel by one term. Bound: 2e-3 on every pixel but at most 0.1% of them. On
// lavapipe (llvmpipe) the measured difference is 0 except through pow (contrast != 1): max 4.2e-7, no pixel
// beyond 2e-3 (2026-11-23, LLVM 15.0.6); there every pixel is held to 1e-6, which catches any change to the
// kernel's arithmetic.
TEST(GpuAlchemy, MatchesTheCpuReference) {
    OBSCURA_GPU_CONTEXT(context);
    struct Case {
        const char* scene;
        int w, h;
    };
    for (const Case& c : {Case{"demo", 333, 197}, Case{"corner", 160, 96}, Case{"cabinet", 256, 144}}) {
        const GBuffer g = testing::render(c.scene, c.w, c.h);
        const bool lavapipe = context.device().name.rfind("llvmpipe", 0) == 0;
        for (const auto& [name, s] : {std::pair{"paper", ssao::AlchemySettings{}}, std::pair{"chapter", chapter()},
                                      std::pair{"contrast 3", contrastCurve()}}) {
            const Image gpu = alchemyAO(context, g, s);
            const Image cpu = reference(g, s);
            ASSERT_EQ(gpu.width, cpu.width);
            ASSERT_EQ(gpu.height, cpu.height);
            const Difference d = compare(gpu, cpu, 2e-3);
            std::printf("[ measured ] %s %dx%d %s: max %.3g (%d px beyond 2e-3, max %.3g on the rest), %d occluded, "
                        "%.3f ms on the GPU\n",
                        c.scene, c.w, c.h, name, d.max, d.beyond, d.maxRest, d.occluded, context.lastPassMs());
            EXPECT_LE(d.beyond, c.w * c.h / 1000) << c.scene << " " << name;
            EXPECT_LE(d.maxRest, 2e-3) << c.scene << " " << name;
            EXPECT_GT(d.occluded, c.w * c.h / 20) << c.scene << " " << name;
            if (lavapipe) {
                EXPECT_LE(d.max, 1e-6) << c.scene << " " << name;
            }
            if (context.device().timestampPeriodNs > 0) {
                EXPECT_GT(context.lastPassMs(), 0.0);
            }
        }
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The settings that change what the shader does besides the formulation: the level of detail (per-pixel
// sample counts read from the concatenated spiral table), a guard band (cropped output), normals rebuilt
// from depth, more samples and another seed. Same bounds as above, but for the rebuilt normals: they come
// from normals_from_depth.comp, whose normals differ from ssao::normalsFromDepth's by up to 2.2e-5
// (tests/gpu/depth_prep_gpu_test.cpp), which moved AO by up to 8.2e-6 here on lavapipe (2026-11-23); held
// to 2e-5 there.
TEST(GpuAlchemy, MatchesTheCpuReferenceWithEverySetting) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("stairs", 181, 123);
    ssao::AlchemySettings lod;
    lod.lodRadiusPixels = 40.0f;
    ssao::AlchemySettings band = chapter();
    band.guardBand = 9;
    ssao::AlchemySettings rebuilt;
    rebuilt.normalsFromDepth = true;
    ssao::AlchemySettings many = chapter();
    many.samples = 64;
    many.contrast = 2.0f;
    many.seed = 7;
    for (const auto& [name, s] : {std::pair{"lod", lod}, std::pair{"guard band", band},
                                  std::pair{"normals from depth", rebuilt}, std::pair{"64 samples", many}}) {
        const Image gpu = alchemyAO(context, g, s);
        const Image cpu = reference(g, s);
        ASSERT_EQ(gpu.width, cpu.width);
        ASSERT_EQ(gpu.height, cpu.height);
        const Difference d = compare(gpu, cpu, 2e-3);
        std::printf("[ measured ] stairs 181x123 %s: max %.3g (%d px beyond 2e-3)\n", name, d.max, d.beyond);
        EXPECT_LE(d.beyond, gpu.width * gpu.height / 1000) << name;
        EXPECT_LE(d.maxRest, 2e-3) << name;
        if (context.device().name.rfind("llvmpipe", 0) == 0) {
            EXPECT_LE(d.max, s.normalsFromDepth ? 2e-5 : 1e-6) << name;
        }
    }
    // The level of detail is exercised: some pixels of this view get fewer samples than without it.
    const Image full = reference(g, ssao::AlchemySettings{});
    const Image reduced = reference(g, lod);
    int fewer = 0;
    for (std::size_t i = 0; i < full.pixels.size(); ++i) fewer += full.pixels[i] != reduced.pixels[i];
    EXPECT_GT(fewer, 100);
    EXPECT_EQ(testing::validationReport(context), "");
}

// The same validation and messages as ssao::alchemyAO.
TEST(GpuAlchemy, RejectsBadInputAsTheCpuPassDoes) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("plane", 16, 16);
    ssao::AlchemySettings radius;
    radius.radius = -1;
    ssao::AlchemySettings band;
    band.guardBand = 8;
    GBuffer nan = g;
    nan.depth.at(3, 4) = NAN;
    GBuffer small = g;
    small.normal = Image(8, 8, 3);
    ssao::AlchemySettings rebuilt;
    rebuilt.normalsFromDepth = true;
    for (const auto& [buffer, s] : {std::pair{g, radius}, std::pair{g, band}, std::pair{nan, ssao::AlchemySettings{}},
                                    std::pair{small, ssao::AlchemySettings{}}, std::pair{nan, rebuilt}}) {
        const std::string cpu = testing::errorMessage([&] { ssao::alchemyAO(buffer, s); });
        EXPECT_NE(cpu, "no error");
        EXPECT_EQ(testing::errorMessage([&] { alchemyAO(context, buffer, s); }), cpu);
    }
    // With normals rebuilt from depth the G-buffer needs none.
    GBuffer depthOnly = g;
    depthOnly.normal = Image();
    EXPECT_EQ(alchemyAO(context, depthOnly, rebuilt).pixels, ssao::alchemyAO(depthOnly, rebuilt).pixels);
    EXPECT_EQ(testing::validationReport(context), "");
}

// alchemyAOBlurred: the estimator and the blur's horizontal pass in one dispatch, then the vertical pass,
// against the three dispatches it replaces (alchemyAO, then bilateralFilter on the guard band's inner
// G-buffer) and against the CPU path. The two GPU paths compute the same values in the same order, so on
// lavapipe they agree to the bit (held to 0 there; 1e-6 elsewhere, where a compiler may round the two
// modules differently); the CPU bound is bilateralFilter's own, 2e-3 (tests/gpu/bilateral_gpu_test.cpp).
// Sizes: odd in both axes, narrower than a workgroup's row, and rows of 2 and 4 workgroups (333 pixels at
// radius 6, 244 each; 600 at radius 32, 192 each), so that the seams between them are compared; radius 6 (the
// default), 1 and 32 (the tile's largest), a guard band, normals rebuilt from depth.
TEST(GpuAlchemy, FusedRowBlurMatchesTheSeparatePasses) {
    OBSCURA_GPU_CONTEXT(context);
    const bool lavapipe = context.device().name.rfind("llvmpipe", 0) == 0;
    ssao::AlchemySettings band = chapter();
    band.guardBand = 9;
    ssao::AlchemySettings rebuilt;
    rebuilt.normalsFromDepth = true;
    ssao::BilateralSettings narrow, wide;
    narrow.radius = 1;
    wide.radius = 32;
    struct Case {
        const char* scene;
        int w, h;
        ssao::AlchemySettings alchemy;
        ssao::BilateralSettings blur;
    };
    const Case cases[] = {{"demo", 333, 197, {}, {}},      {"stairs", 181, 123, band, {}},
                          {"corner", 600, 40, {}, wide},    {"cabinet", 97, 61, rebuilt, narrow},
                          {"demo", 257, 33, contrastCurve(), {}}};
    for (const Case& c : cases) {
        const GBuffer g = testing::render(c.scene, c.w, c.h);
        const GBuffer inner = ssao::cropGuardBand(g, ssao::guardBandCamera(g.camera, -c.alchemy.guardBand),
                                                  c.alchemy.guardBand);
        const Image fused = alchemyAOBlurred(context, g, c.alchemy, c.blur);
        const Image separate = bilateralFilter(context, alchemyAO(context, g, c.alchemy), inner, c.blur);
        const Image cpu = ssao::bilateralFilter(ssao::alchemyAO(g, c.alchemy), inner, c.blur);
        ASSERT_EQ(fused.width, separate.width);
        ASSERT_EQ(fused.height, separate.height);
        const Difference d = compare(fused, separate, 0.0);
        const Difference toCpu = compare(fused, cpu, 2e-3);
        std::printf("[ measured ] %s %dx%d, radius %d: fused against separate passes max %.3g, against the CPU "
                    "max %.3g, %d occluded\n",
                    c.scene, c.w, c.h, c.blur.radius, d.max, toCpu.max, toCpu.occluded);
        EXPECT_LE(d.max, lavapipe ? 0.0 : 1e-6) << c.scene << " " << c.w << "x" << c.h;
        EXPECT_LE(toCpu.beyond, c.w * c.h / 1000) << c.scene;
        EXPECT_GT(toCpu.occluded, fused.width * fused.height / 50) << c.scene;  // not a vacuous comparison
    }
    // The fused pass blurs separably by depth alone; other blurs fail in one message.
    const GBuffer g = testing::render("plane", 16, 16);
    ssao::BilateralSettings twoD{ssao::BlurMode::TwoD}, normals;
    normals.normalWeight = ssao::NormalWeight::On;
    for (const ssao::BilateralSettings& blur : {twoD, normals})
        EXPECT_NE(testing::errorMessage([&] { alchemyAOBlurred(context, g, {}, blur); }).find("no normal weight"),
                  std::string::npos);
    ssao::AlchemySettings bad;
    bad.radius = -1;
    EXPECT_EQ(testing::errorMessage([&] { alchemyAOBlurred(context, g, bad, {}); }),
              testing::errorMessage([&] { ssao::alchemyAO(g, bad); }));
    EXPECT_EQ(testing::validationReport(context), "");
}

// An engine may dispatch fewer workgroups along a row than it has segments (docs/INTEGRATION.md): each then
// takes every segment from its index on, and the image is the same, bit for bit. Rows of 2 and 4 segments
// (333 pixels at radius 6, 244 each; 600 at radius 32, 192 each) in 1, 2 and 3 workgroups: one workgroup
// for the whole row, one per pair, and a row of 4 in 3, whose first workgroup takes segments 0 and 3.
TEST(GpuAlchemy, FusedRowsInFewerWorkgroupsTakeEverySegment) {
    OBSCURA_GPU_CONTEXT(context);
    ssao::BilateralSettings wide;
    wide.radius = 32;
    struct Case {
        const char* scene;
        int w, h;
        ssao::BilateralSettings blur;
        int segments;
    };
    for (const Case& c : {Case{"demo", 333, 61, {}, 2}, Case{"corner", 600, 40, wide, 4}}) {
        ASSERT_EQ(alchemyBlurRowGroupsX(c.w, c.blur.radius), c.segments) << c.scene;
        const GBuffer g = testing::render(c.scene, c.w, c.h);
        const Image each = alchemyAOBlurred(context, g, {}, c.blur);
        for (std::uint32_t groups = 1; groups < std::uint32_t(c.segments); ++groups) {
            const Image fewer = alchemyAOBlurredInRowGroups(context, g, {}, c.blur, {}, groups);
            ASSERT_EQ(fewer.width, each.width);
            EXPECT_EQ(fewer.pixels, each.pixels) << c.scene << ", " << groups << " workgroups a row";
        }
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The fused rows dispatch by the width their module declares (a candidate may try another), each workgroup
// blurring that width less the radius at each end. A module whose row is no wider than 2 radius, or that is
// more than one row, is refused in one line naming the shader, before anything is dispatched.
TEST(GpuAlchemy, FusedRowsRefuseAWorkgroupThatCannotHoldTheirApron) {
    const std::vector<std::uint32_t> embedded(shaders::alchemy_blur_row.words,
                                              shaders::alchemy_blur_row.words + shaders::alchemy_blur_row.count);
    ASSERT_EQ(reflect({embedded.data(), embedded.size()}).localSize[0], std::uint32_t(kBilateralHorizontalTileX));
    const GBuffer g = testing::render("plane", 40, 8);
    for (const auto& [x, y] : {std::pair{12u, 1u}, std::pair{256u, 2u}}) {
        testing::ContextWithModule other("alchemy_blur_row", testing::withWorkgroupSize(embedded, x, y));
        const std::string refused = testing::errorMessage([&] { alchemyAOBlurred(other.context(), g, {}, {}); });
        EXPECT_NE(refused.find("shader alchemy_blur_row: has workgroups of " + std::to_string(x) + "x" +
                               std::to_string(y)),
                  std::string::npos)
            << refused;
        EXPECT_NE(refused.find("more than 2 radius (12)"), std::string::npos) << refused;
        EXPECT_EQ(testing::validationReport(other.context()), "");
    }
}


// gpu::AlchemyFormats::packedNormals: the public passes upload the normals as octahedral words and give, bit for
// bit, the obscurance of the same calls fed the words' decoded normals, with and without the fused row blur and
// with a guard band; which is not the float normals' (the decoding is there to see). With normals rebuilt from
// depth there are none to pack, and the call says so.
TEST(GpuAlchemy, PackedNormalsGiveTheObscuranceOfTheirDecodedNormals) {
    OBSCURA_GPU_CONTEXT(context);
    ssao::AlchemySettings band;
    band.guardBand = 7;
    for (const ssao::AlchemySettings& s : {ssao::AlchemySettings{}, band}) {
        const GBuffer g = testing::render("demo", 133, 77);
        GBuffer decoded = g;
        decoded.normal = unpackNormals(packNormals(g.normal), g.width(), g.height());
        const AlchemyFormats packed{.packedNormals = true};
        const Image words = alchemyAO(context, g, s, packed), floats = alchemyAO(context, g, s);
        EXPECT_EQ(words.pixels, alchemyAO(context, decoded, s).pixels) << s.guardBand;
        EXPECT_NE(words.pixels, floats.pixels) << s.guardBand;
        EXPECT_LE(compare(words, floats, 2e-3).max, 2e-3);
        EXPECT_EQ(alchemyAOBlurred(context, g, s, {}, packed).pixels, alchemyAOBlurred(context, decoded, s, {}).pixels);
    }
    ssao::AlchemySettings rebuilt;
    rebuilt.normalsFromDepth = true;
    const GBuffer g = testing::render("plane", 16, 16);
    EXPECT_NE(testing::errorMessage([&] { alchemyAO(context, g, rebuilt, {.packedNormals = true}); })
                  .find("normalsFromDepth"),
              std::string::npos);
    EXPECT_EQ(testing::validationReport(context), "");
}

// The estimator dispatches by the workgroup size its module declares (ComputePipeline::kShadersOwnSize), so that
// a candidate shader may try another size without a rebuilt host (bench/gpu-candidates). The embedded module
// with its workgroup size rewritten to 24 x 3 (which divides neither side of 333 x 197, nor is a multiple of a
// warp), loaded through OBSCURA_SHADER_DIR into a context of its own, must give the same image: each invocation
// evaluates its own pixel whatever its workgroup. Bit for bit, as the instructions are the same. A size beyond
// the device's limits is refused by the host, not left to the driver.
TEST(GpuAlchemy, AnotherWorkgroupSizeGivesTheSameImage) {
    OBSCURA_GPU_CONTEXT(context);
    const std::vector<std::uint32_t> words = testing::withWorkgroupSize(
        {shaders::alchemy.words, shaders::alchemy.words + shaders::alchemy.count}, 24, 3);
    const SpirvLayout layout = reflect({words.data(), words.size()});
    ASSERT_EQ(layout.localSize[0], 24u);
    ASSERT_EQ(layout.localSize[1], 3u);
    testing::ContextWithModule other("alchemy", words);
    ssao::AlchemySettings band;
    band.guardBand = 5;
    for (const ssao::AlchemySettings& s : {ssao::AlchemySettings{}, band}) {
        const GBuffer g = testing::render("demo", 333, 197);
        const Image embedded = alchemyAO(context, g, s), resized = alchemyAO(other.context(), g, s);
        EXPECT_EQ(resized.width, embedded.width);
        EXPECT_EQ(resized.height, embedded.height);
        EXPECT_EQ(resized.pixels, embedded.pixels) << "guard band " << s.guardBand;
    }
    EXPECT_EQ(testing::validationReport(other.context()), "");

    // A size beyond every device's limits (65536 invocations in a row) is refused in one line naming the
    // shader and the limits, before Vulkan sees the pipeline.
    const std::vector<std::uint32_t> embedded(shaders::alchemy.words, shaders::alchemy.words + shaders::alchemy.count);
    testing::ContextWithModule huge("alchemy", testing::withWorkgroupSize(embedded, 65536, 1));
    const std::string refused =
        testing::errorMessage([&] { alchemyAO(huge.context(), testing::render("plane", 16, 8), {}); });
    EXPECT_NE(refused.find("shader alchemy"), std::string::npos) << refused;
    EXPECT_NE(refused.find("65536x1x1, beyond the device's limits"), std::string::npos) << refused;
    EXPECT_EQ(testing::validationReport(huge.context()), "");
    EXPECT_EQ(testing::validationReport(context), "");
}

} // namespace obscura::gpu
