// gpu::prepareGBuffer against ssao::prepareGBuffer on lavapipe with validation on: every depth convention
// and normal source on three scenes and sizes, one of them odd.
#include "gpu_test_util.h"

#include "obscura/depth_prep.h"
#include "obscura/gpu_prep.h"

#include <gtest/gtest.h>

#include <cmath>

namespace obscura::gpu {
namespace {

// An engine's buffers for a G-buffer: device depth under the convention, world normals in unorm encoding.
struct EngineBuffers {
    Image deviceDepth, normals;
};
EngineBuffers engineBuffers(const GBuffer& g, const ssao::DepthPrepSettings& s) {
    const ssao::DepthPrepConstants k = ssao::depthPrepConstants(s, g.camera);
    EngineBuffers e{Image(g.width(), g.height(), 1), Image(g.width(), g.height(), 4, 1.0f)};
    const Mat4 r = g.camera.worldFromView();
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            e.deviceDepth.at(x, y) = ssao::deviceDepthFromLinear(g.depth.at(x, y), k);
            const Vec3 n = g.viewNormal(x, y);
            for (int c = 0; c < 3; ++c)
                e.normals.at(x, y, c) = (r.m[c][0] * n.x + r.m[c][1] * n.y + r.m[c][2] * n.z) * 0.5f + 0.5f;
        }
    return e;
}

// Measured on lavapipe (2026-11-23): depth and decoded normals equal bit for bit (the same float
// expressions); normals rebuilt from depth differ by up to 2.2e-5 (stairs 333x197; well 1.5e-6): the shader
// rebuilds positions with the affine form of Camera::viewFromPixel, and a cross product of two short
// differences amplifies the rounding. The bound on those is 1e-4, two orders below what moves AO visibly.
TEST(GpuDepthPrep, MatchesTheCpu) {
    OBSCURA_GPU_CONTEXT(context);
    struct Case {
        const char* scene;
        int w, h;
        ssao::DepthConvention depth;
        ssao::NormalSource normals;
    };
    for (const Case& c : {Case{"demo", 64, 40, ssao::DepthConvention::Standard, ssao::NormalSource::World},
                          Case{"stairs", 333, 197, ssao::DepthConvention::Reversed, ssao::NormalSource::FromDepth},
                          Case{"corner", 50, 31, ssao::DepthConvention::ReversedInfinite, ssao::NormalSource::World},
                          Case{"well", 40, 40, ssao::DepthConvention::Reversed, ssao::NormalSource::FromDepth},
                          // Neighbours along one axis only: the normal across that tangent (both sides).
                          Case{"plane", 1, 37, ssao::DepthConvention::Standard, ssao::NormalSource::FromDepth},
                          Case{"stairs", 53, 1, ssao::DepthConvention::Standard, ssao::NormalSource::FromDepth}}) {
        const GBuffer g = testing::render(c.scene, c.w, c.h);
        ssao::DepthPrepSettings s;
        s.depth = c.depth;
        s.normals = c.normals;
        s.unormNormals = true;
        const EngineBuffers e = engineBuffers(g, s);
        const GBuffer cpu = ssao::prepareGBuffer(e.deviceDepth, e.normals, g.camera, s);
        const GBuffer gpu = prepareGBuffer(context, e.deviceDepth, e.normals, g.camera, s);
        float depthDiff = 0.0f, normalDiff = 0.0f;
        for (std::size_t i = 0; i < cpu.depth.pixels.size(); ++i) {
            const float a = cpu.depth.pixels[i], b = gpu.depth.pixels[i];
            if (!(a < 1e30f)) {
                ASSERT_FALSE(b < 1e30f) << c.scene << " " << i;
            } else {
                depthDiff = std::max(depthDiff, std::fabs(a - b) / a);
            }
            for (int k = 0; k < 3; ++k)
                normalDiff = std::max(normalDiff, std::fabs(cpu.normal.pixels[3 * i + k] - gpu.normal.pixels[3 * i + k]));
        }
        EXPECT_LE(depthDiff, 1e-6f) << c.scene;
        EXPECT_LE(normalDiff, c.normals == ssao::NormalSource::FromDepth ? 1e-4f : 1e-6f) << c.scene;
        std::printf("%s %dx%d: depth %.2g, normal %.2g\n", c.scene, c.w, c.h, double(depthDiff), double(normalDiff));
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

TEST(GpuDepthPrep, SameErrorsAsTheCpu) {
    OBSCURA_GPU_CONTEXT(context);
    Camera cam;
    cam.width = 8;
    cam.height = 4;
    ssao::DepthPrepSettings s;
    Image z(8, 4, 1, 0.5f), n(8, 4, 3, 0.0f);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) n.at(x, y, 2) = 1.0f;
    Image nanDepth = z;
    nanDepth.at(2, 3) = NAN;
    Image zeroNormal = n;
    zeroNormal.at(6, 0, 2) = 0.0f;
    // Finite, but its squared length overflows: it normalized to (0, 0, 0), which both passes took.
    Image hugeNormal = n;
    hugeNormal.at(5, 2, 0) = hugeNormal.at(5, 2, 1) = 1e30f;
    EXPECT_EQ(testing::errorMessage([&] { ssao::prepareGBuffer(z, hugeNormal, cam, s, "f.exr"); }),
              "f.exr: the normal at pixel (5, 2) is not a finite non-zero vector");
    for (const auto& [depth, normals] : {std::pair{nanDepth, n}, std::pair{z, zeroNormal}, std::pair{z, hugeNormal},
                                         std::pair{Image(8, 3, 1), n}})
        testing::expectSameError([&] { ssao::prepareGBuffer(depth, normals, cam, s, "f.exr"); },
                                 [&] { prepareGBuffer(context, depth, normals, cam, s, "f.exr"); });
    EXPECT_EQ(testing::validationReport(context), "");
}

} // namespace
} // namespace obscura::gpu
