// The standard error that ObscuranceEstimator::estimate reports from two nets of a point's rays, held against
// the spread of the estimate itself over independent seeds (the direction sets' random shifts), on the ceiling
// of closed_form_test.cpp: the figure `obscura compare` reports as the reference's noise.
#include "obscura/builtin_scenes.h"
#include "obscura/camera.h"
#include "obscura/trace.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace obscura;
using namespace obscura::trace;

namespace {

const Vec3 kUp{0, 1, 0};

struct Spread {
    double actual;    // standard deviation of A over seeds
    double reported;  // RMS of the reported standard errors
};

Spread spreadOver(const Tracer& tracer, const ObscuranceSettings& s, int seeds) {
    const ObscuranceEstimator estimator(tracer, s);
    double sum = 0, sumSq = 0, reportedSq = 0;
    for (int i = 0; i < seeds; ++i) {
        const ObscuranceEstimator::Estimate e = estimator.estimate({0.2f, 0, -0.1f}, kUp, kUp, std::uint32_t(i));
        EXPECT_EQ(e.value, estimator({0.2f, 0, -0.1f}, kUp, kUp, std::uint32_t(i)));
        const double a = double(e.value), se = double(e.standardError);
        sum += a;
        sumSq += a * a;
        reportedSq += se * se;
    }
    const double mean = sum / seeds;
    return {std::sqrt(std::max(0.0, sumSq / seeds - mean * mean) * seeds / (seeds - 1)), std::sqrt(reportedSq / seeds)};
}

} // namespace

// Measured ratios reported / actual over 2000 seeds: binary 0.94 to 1.43, alchemy 1.28 to 1.70, exponential
// 1.48 to 1.85, at 8 to 1024 rays and at 100 (no power of 2: plain halves of 100 rays read 4.7 times the
// spread). The bound [0.8, 2.2] holds the figure to "the noise, erring high", and fails on the halves of 100.
// (Elsewhere it errs higher: 2.4 to 2.8 at a point of corner, exponential falloff, 1024 rays.)
TEST(StandardError, MatchesTheSpreadOverSeeds) {
    BuiltinScene scene = makeBuiltinScene("ceiling");
    Tracer tracer(scene.scene);
    for (Falloff falloff : {Falloff::Binary, Falloff::Exponential, Falloff::Alchemy})
        for (int rays : {8, 16, 64, 100, 256, 1024}) {
            ObscuranceSettings s;
            s.falloff = falloff;
            s.radius = 2.0f;
            s.alchemyU = 0.5f;
            s.rays = rays;
            const Spread spread = spreadOver(tracer, s, 2000);
            ASSERT_GT(spread.actual, 1e-5) << "falloff " << int(falloff) << ", " << rays << " rays";
            EXPECT_GE(spread.reported / spread.actual, 0.8) << "falloff " << int(falloff) << ", " << rays << " rays";
            EXPECT_LE(spread.reported / spread.actual, 2.2) << "falloff " << int(falloff) << ", " << rays << " rays";
        }
}

// No occluder within reach: every ray misses, A = 1 with no noise. Under 8 rays: NaN. The image
// overload gives each surface pixel its error and the sky 0.
TEST(StandardError, IsZeroWithoutNoiseAndNaNUnderEightRays) {
    BuiltinScene plane = makeBuiltinScene("plane");
    Tracer tracer(plane.scene);
    ObscuranceSettings s;
    s.rays = 64;
    const ObscuranceEstimator estimator(tracer, s);
    const ObscuranceEstimator::Estimate open = estimator.estimate({1, 0, 2}, kUp, kUp, 3);
    EXPECT_EQ(open.value, 1.0f);
    EXPECT_EQ(open.standardError, 0.0f);
    // Nets of 1 or 2 rays tell nothing (at 4 rays a binary point under the ceiling read 22 times its spread).
    for (int rays : {1, 2, 4, 7}) {
        s.rays = rays;
        EXPECT_TRUE(std::isnan(ObscuranceEstimator(tracer, s).estimate({1, 0, 2}, kUp, kUp, 3).standardError)) << rays;
    }
    s.rays = 8;
    EXPECT_EQ(ObscuranceEstimator(tracer, s).estimate({1, 0, 2}, kUp, kUp, 3).standardError, 0.0f);

    BuiltinScene demo = makeBuiltinScene("demo");
    Tracer demoTracer(demo.scene);
    Camera camera = demo.camera;
    camera.width = 24;
    camera.height = 16;
    const GBuffer g = renderGBuffer(demoTracer, camera);
    s.rays = 16;
    Image standardError;
    const Image ao = ambientObscurance(demoTracer, g, s, {}, &standardError);
    ASSERT_EQ(standardError.width, 24);
    ASSERT_EQ(standardError.height, 16);
    EXPECT_EQ(ao.pixels, ambientObscurance(demoTracer, g, s).pixels);
    int noisy = 0, sky = 0;
    for (std::size_t i = 0; i < ao.pixels.size(); ++i) {
        EXPECT_GE(standardError.pixels[i], 0.0f);
        EXPECT_LE(standardError.pixels[i], 0.5f);
        if (!(g.depth.pixels[i] < 1e30f)) {
            EXPECT_EQ(standardError.pixels[i], 0.0f);
            ++sky;
        }
        noisy += standardError.pixels[i] > 0.0f;
    }
    EXPECT_GT(sky, 0);
    EXPECT_GT(noisy, 24 * 16 / 4);
}
