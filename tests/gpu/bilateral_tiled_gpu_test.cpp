// The separable blur's two passes in one tiled dispatch (src/gpu/shaders/bilateral_tiled.comp) against the two
// dispatches of bilateral_separable.comp: the same arithmetic per pixel in the same order, so the same bits on
// lavapipe, at sizes below, at and across the 32-pixel tile, at radius 1 to the tiled blur's largest, with
// and without the normal weight, and with the guide at a stride of 2 (the gtao-half grid's blur); and within
// the separable tests' bound of the CPU filter. Validation on, no message allowed.
#include "blur_test_util.h"
#include "gpu_test_util.h"

#include "gpu/bilateral_pass.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/shaders/layouts.h"

#include "obscura/bilateral.h"
#include "obscura/error.h"
#include "obscura/gpu.h"
#include "obscura/gpu_shaders.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace obscura::gpu {
namespace {

// `input` (w x h) blurred with `f` (guide planes `depth` and `normal` of the guide's size) by `dispatch`.
std::vector<float> blur(Context& context, const std::vector<float>& depth, const std::vector<float>& normal,
                        const std::vector<float>& input, const SeparableBilateral& f, BlurDispatch dispatch) {
    Context::Impl& c = context.impl();
    const Buffer d = upload(c, depth.data(), depth.size() * sizeof(float));
    const Buffer n = upload(c, normal.data(), normal.size() * sizeof(float));
    const Buffer spatial = upload(c, f.logSpatial.data(), f.logSpatial.size() * sizeof(float));
    const Buffer in = upload(c, input.data(), input.size() * sizeof(float));
    const Buffer scratch(c, input.size() * sizeof(float), MemoryUse::Device);
    // Filled with a value no blur gives, so a pixel the dispatch never writes shows.
    const std::vector<float> unwritten(input.size(), -7.0f);
    const Buffer out = upload(c, unwritten.data(), unwritten.size() * sizeof(float));
    c.submit([&](VkCommandBuffer cmd) { recordSeparableBilateral(c, cmd, {d, n, spatial, in, scratch, out}, f, dispatch); });
    std::vector<float> result(input.size());
    download(c, out, result.data(), result.size() * sizeof(float));
    return result;
}

// The largest difference between `a` and `b`, and how many of `a`'s values differ from `input`'s.
struct Difference {
    double max = 0;
    int changed = 0;
};
Difference compare(const std::vector<float>& a, const std::vector<float>& b, const std::vector<float>& input) {
    Difference d;
    for (std::size_t i = 0; i < a.size(); ++i) {
        d.max = std::max(d.max, std::fabs(double(a[i]) - double(b[i])));
        d.changed += a[i] != input[i];
    }
    return d;
}

bool lavapipe(const Context& context) { return context.device().name.rfind("llvmpipe", 0) == 0; }

struct Case {
    const char* scene;
    int w, h;
    int radius;
    bool normals;
};

TEST(GpuBilateralTiled, GivesTheTwoPassesBitsAndMatchesTheCpu) {
    OBSCURA_GPU_CONTEXT(context);
    for (const Case& k : {Case{"demo", 333, 197, 6, false}, Case{"demo", 333, 197, 8, true}, Case{"corner", 31, 17, 6, false},
                          Case{"corner", 32, 32, 1, false}, Case{"cabinet", 65, 33, 8, false},
                          Case{"cabinet", 96, 70, 3, true}}) {
        const std::string label = std::string(k.scene) + " " + std::to_string(k.w) + "x" + std::to_string(k.h) +
                                  " radius " + std::to_string(k.radius) + (k.normals ? " normals" : "");
        const GBuffer g = testing::render(k.scene, k.w, k.h);
        const Image raw = testing::noisyAo(g);
        ssao::BilateralSettings s;
        s.radius = k.radius;
        s.normalWeight = k.normals ? ssao::NormalWeight::On : ssao::NormalWeight::Off;
        const SeparableBilateral f = separableBilateral(s, k.w, k.h);
        const std::vector<float> two = blur(context, g.depth.pixels, g.normal.pixels, raw.pixels, f, BlurDispatch::TwoPasses);
        const std::vector<float> tiled = blur(context, g.depth.pixels, g.normal.pixels, raw.pixels, f, BlurDispatch::Tiled);
        const Difference d = compare(tiled, two, raw.pixels);
        const double cpu = compare(tiled, ssao::bilateralFilter(raw, g, s).pixels, raw.pixels).max;
        std::printf("[ measured ] %s: tiled against two passes max %.3g, against the CPU %.3g\n", label.c_str(), d.max,
                    cpu);
        // Lavapipe rounds both alike; another device may contract differently in one of them.
        EXPECT_LE(d.max, lavapipe(context) ? 0.0 : 1e-6) << label;
        EXPECT_LE(cpu, 2e-4) << label << " (GpuBilateral.SeparableMatchesTheCpuFilter's bound)";
        EXPECT_GT(d.changed, k.w * k.h / 20) << label << ": the blur did something";
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The gtao-half grid's blur: the image is the half-resolution grid, the guide the full-resolution planes read
// at a stride of 2.
TEST(GpuBilateralTiled, ReadsAStridedGuideAsTheTwoPassesDo) {
    OBSCURA_GPU_CONTEXT(context);
    const int w = 133, h = 77, gw = (w + 1) / 2, gh = (h + 1) / 2;
    const GBuffer g = testing::render("stairs", w, h);
    const Image full = testing::noisyAo(g);
    std::vector<float> grid(std::size_t(gw) * std::size_t(gh));
    for (int y = 0; y < gh; ++y)
        for (int x = 0; x < gw; ++x) grid[std::size_t(y) * gw + x] = full.pixels[std::size_t(2 * y) * w + 2 * x];
    for (const int radius : {2, 8}) {
        ssao::BilateralSettings s;
        s.radius = radius;
        SeparableBilateral f = separableBilateral(s, gw, gh);
        f.constants.guideStep = 2;
        f.constants.guideWidth = w;
        const std::vector<float> two = blur(context, g.depth.pixels, g.normal.pixels, grid, f, BlurDispatch::TwoPasses);
        const std::vector<float> tiled = blur(context, g.depth.pixels, g.normal.pixels, grid, f, BlurDispatch::Tiled);
        const Difference d = compare(tiled, two, grid);
        EXPECT_LE(d.max, lavapipe(context) ? 0.0 : 1e-6) << "radius " << radius;
        EXPECT_GT(d.changed, gw * gh / 20) << "radius " << radius;
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

TEST(GpuBilateralTiled, RefusesARadiusItsTileCannotHold) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("corner", 24, 16);
    const Image raw(24, 16, 1, 0.5f);
    ssao::BilateralSettings s;
    s.radius = kBilateralTiledMaxRadius + 1;
    const SeparableBilateral f = separableBilateral(s, 24, 16);
    EXPECT_EQ(testing::errorMessage([&] {
                  blur(context, g.depth.pixels, g.normal.pixels, raw.pixels, f, BlurDispatch::Tiled);
              }),
              "the tiled blur: holds radii up to 8, not 9");
    EXPECT_EQ(testing::validationReport(context), "");
}

} // namespace
} // namespace obscura::gpu
