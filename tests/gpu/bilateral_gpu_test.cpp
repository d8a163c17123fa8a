// The separable cross-bilateral blur as a compute pass (src/gpu/shaders/bilateral_separable.comp) against
// ssao::bilateralFilter's separable mode, on lavapipe in CI, with validation on and no message allowed.
#include "blur_test_util.h"
#include "gpu_test_util.h"

#include "obscura/alchemy.h"
#include "obscura/bilateral.h"
#include "obscura/error.h"
#include "obscura/gpu.h"

#include <gtest/gtest.h>

#include <string>

namespace obscura::gpu {

// The CPU filter weighs taps with a degree-3 polynomial exp2 (relative error 7.5e-5) and fused multiply-adds
// where the CPU has them; the shader uses the GPU's exp2 and skips the taps outside the image that the CPU
// reads as sky padding weighing 2^-125. Each output is a weighted mean of AO values in [0, 1]; weights off by
// a relative e move it by at most 2e, so 1.5e-4 bounds the polynomial's share. Measured on lavapipe
// (2026-11-23, LLVM 15.0.6): max 2.2e-5 over these cases. Bound 2e-4 (the issue asks for 2e-3), on the raw AO
// of the estimator at the default blur, with the normal weight on, and at radius 1 and 32.
TEST(GpuBilateral, SeparableMatchesTheCpuFilter) {
    OBSCURA_GPU_CONTEXT(context);
    ssao::BilateralSettings paper;
    ssao::BilateralSettings normals;
    normals.normalWeight = ssao::NormalWeight::On;
    ssao::BilateralSettings narrow;
    narrow.radius = 1;
    narrow.depthSigma = 0.01f;
    ssao::BilateralSettings wide;
    wide.radius = 32;
    wide.normalWeight = ssao::NormalWeight::On;
    testing::expectBlursMatchCpu(context,
                                 {{"radius 6", paper},
                                  {"radius 6 normals", normals},
                                  {"radius 1 sigma 0.01", narrow},
                                  {"radius 32 normals", wide}},
                                 "", 2e-4);
    EXPECT_EQ(testing::validationReport(context), "");
}

// The same checks and messages as ssao::bilateralFilter; no blur is a copy (the 2-D filter: bilateral_2d_gpu_test).
TEST(GpuBilateral, RejectsBadInputAsTheCpuFilterDoes) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("corner", 24, 16);
    const Image ao(24, 16, 1, 0.5f);
    ssao::BilateralSettings radius;
    radius.radius = 33;
    const Image small(8, 8, 1);
    Image nanAo = ao;
    nanAo.at(7, 3) = NAN;
    for (const auto& [image, s] : {std::pair{ao, radius}, std::pair{small, ssao::BilateralSettings{}},
                                   std::pair{nanAo, ssao::BilateralSettings{}}}) {
        const std::string cpu = testing::errorMessage([&] { ssao::bilateralFilter(image, g, s); });
        EXPECT_NE(cpu, "no error");
        EXPECT_EQ(testing::errorMessage([&] { bilateralFilter(context, image, g, s); }), cpu);
    }
    GBuffer nanDepth = g;
    nanDepth.depth.at(9, 4) = NAN;
    const std::string cpu = testing::errorMessage([&] { ssao::bilateralFilter(ao, nanDepth, ssao::BilateralSettings{}); });
    EXPECT_NE(cpu.find("depth at pixel (9, 4) is nan"), std::string::npos) << cpu;
    EXPECT_EQ(testing::errorMessage([&] { bilateralFilter(context, ao, nanDepth, ssao::BilateralSettings{}); }), cpu);
    ssao::BilateralSettings none;
    none.mode = ssao::BlurMode::None;
    EXPECT_EQ(bilateralFilter(context, ao, g, none).pixels, ao.pixels);
    EXPECT_EQ(testing::validationReport(context), "");
}

} // namespace obscura::gpu
