// The 2-D cross-bilateral blur as a compute pass (src/gpu/shaders/bilateral_2d.comp) against
// ssao::bilateralFilter's TwoD mode, on lavapipe in CI, with validation on and no message allowed.
#include "blur_test_util.h"
#include "gpu_test_util.h"

#include "obscura/alchemy.h"
#include "obscura/bilateral.h"
#include "obscura/gpu.h"

#include <gtest/gtest.h>

#include <string>

namespace obscura::gpu {

// The CPU filter weighs taps with a degree-6 polynomial exp (relative error < 2e-5), the shader with the
// GPU's exp2; each output is a weighted mean of AO values in [0, 1], so weights off by a relative e move it by
// at most 2e. Measured on lavapipe (2026-11-23, LLVM 15.0.6): max 1.9e-6 over these cases (cabinet 256x144,
// radius 2). Bound 2e-4 (the issue asks for 2e-3; 4e-5 is the polynomial's share), on the raw AO of the
// estimator at the default 2-D blur (radius 6, normal weight on), a narrow one, and one without normals.
TEST(GpuBilateral2D, MatchesTheCpuFilter) {
    OBSCURA_GPU_CONTEXT(context);
    ssao::BilateralSettings chapter;
    chapter.mode = ssao::BlurMode::TwoD;
    ssao::BilateralSettings narrow = chapter;
    narrow.radius = 2;
    narrow.depthSigma = 0.01f;
    ssao::BilateralSettings depthOnly = chapter;
    depthOnly.radius = 3;
    depthOnly.normalWeight = ssao::NormalWeight::Off;
    testing::expectBlursMatchCpu(context,
                                 {{"radius 6 normals", chapter},
                                  {"radius 2 sigma 0.01", narrow},
                                  {"radius 3 depth only", depthOnly}},
                                 "2-D ", 2e-4);
    EXPECT_EQ(testing::validationReport(context), "");
}

// The same checks and messages as ssao::bilateralFilter in 2-D mode.
TEST(GpuBilateral2D, RejectsBadInputAsTheCpuFilterDoes) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("corner", 24, 16);
    ssao::BilateralSettings s;
    s.mode = ssao::BlurMode::TwoD;
    ssao::BilateralSettings sigma = s;
    sigma.depthSigma = 0.0f;
    const Image ao(24, 16, 1, 0.5f), small(8, 8, 1);
    testing::expectSameError([&] { ssao::bilateralFilter(ao, g, sigma); }, [&] { bilateralFilter(context, ao, g, sigma); });
    testing::expectSameError([&] { ssao::bilateralFilter(small, g, s); }, [&] { bilateralFilter(context, small, g, s); });
    EXPECT_EQ(testing::validationReport(context), "");
}

} // namespace obscura::gpu
