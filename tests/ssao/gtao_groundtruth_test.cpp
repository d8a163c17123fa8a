// GTAO against ray-traced ambient occlusion of the same radius (binary visibility within r, cosine
// weighting) on scenes seen from above, where the camera sees the occluders: the test first measures that
// premise by tracing (every pixel of `well` and `corner`; on `stairs` all but the floor along the flight's
// sides, whose occluders are the flight's vertical side faces).
//
// The reference is a Monte Carlo estimate with N = 1024 stratified rays per pixel: its per-pixel standard
// error is at most sqrt(A (1 - A) / N) <= 0.016 but, averaged over the image (most pixels are open and have
// no error at all), two 2048-ray references with different seeds differ by a mean absolute 0.0005
// (measured; about 0.0007 expected at 1024 rays), so the error below is GTAO's own: horizon sampling
// between the steps (it only ever misses occluders, so that part is a positive bias), slice count, the
// pixels at silhouettes and, where an occluder is hidden, the height-field assumption.
//
// Measured at 128x128, r = 1 m (MAE well / stairs / corner; docs/QUALITY.md; 96x96 is within 0.002):
//   ultra 9x3: 0.0097 / 0.0134 / 0.0129; 9x8: 0.0042 / 0.0103 / 0.0070.
//   Before the column rule and the linear steps (GtaoBeyondRadius::Drop, step power 2): ultra 0.0275 /
//   0.0236 (the earlier straight-down stairs view) / 0.0250.
//   Nearest-pixel samples (GtaoSampling::Nearest), 96x96, 2026-11-25: ultra 0.0096 / 0.0150 / 0.0127 against
//   planar 0.0096 / 0.0146 / 0.0125; high 0.0112 / 0.0144 / 0.0140 against 0.0113 / 0.0154 / 0.0135.
//   Depth MIP samples, high, 2026-11-25: Mip 0.0117 / 0.0144 / 0.0141, PlanarMip 0.0117 / 0.0154 / 0.0137.
// The bounds are the 0.02.
#include "ssao/gtao_scenes.h"

#include "obscura/gtao.h"
#include "obscura/trace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace obscura;
using namespace obscura::ssao;

TEST(GtaoGroundTruth, MatchesRayTracedFromAbove) {
    for (const char* name : {"well", "stairs", "corner"}) {
        test::TopDownView view = test::topDownView(name, 96, 96);
        trace::Tracer tracer(view.scene);
        GBuffer g = trace::renderGBuffer(tracer, view.camera);
        const double seen = test::maskFraction(g, test::occludersSeen(tracer, g, view.radius));
        EXPECT_GE(seen, std::string(name) == "stairs" ? 0.9 : 0.999) << name << ": the camera misses occluders";
        const Image reference = test::rayTracedReference(tracer, g, view.radius, 1024);

        GtaoSettings settings;
        applyQuality(settings, GtaoQuality::Ultra);
        settings.radius = view.radius;
        double ultra = test::meanAbsoluteError(g, computeGtao(g, settings).visibility, reference);
        settings.sampling = GtaoSampling::Nearest;
        double ultraNearest = test::meanAbsoluteError(g, computeGtao(g, settings).visibility, reference);
        settings.sampling = GtaoSampling::Planar;
        settings.stepsPerSide = 8;
        double steps8 = test::meanAbsoluteError(g, computeGtao(g, settings).visibility, reference);
        applyQuality(settings, GtaoQuality::High);
        double high = test::meanAbsoluteError(g, computeGtao(g, settings).visibility, reference);
        settings.sampling = GtaoSampling::Nearest;
        double highNearest = test::meanAbsoluteError(g, computeGtao(g, settings).visibility, reference);
        settings.sampling = GtaoSampling::Mip;
        double highMip = test::meanAbsoluteError(g, computeGtao(g, settings).visibility, reference);
        settings.sampling = GtaoSampling::PlanarMip;
        double highPlanarMip = test::meanAbsoluteError(g, computeGtao(g, settings).visibility, reference);
        std::printf("%s (occluders seen at %.0f%% of pixels): MAE against ray-traced AO, r = %.1f m: ultra 9x3 "
                    "%.4f (nearest samples %.4f), 9x8 %.4f, high 3x3 %.4f (nearest samples %.4f, mip %.4f, "
                    "planar-mip %.4f)\n",
                    name, 100.0 * seen, double(view.radius), ultra, ultraNearest, steps8, high, highNearest, highMip,
                    highPlanarMip);
        EXPECT_LE(ultra, 0.02) << name;
        EXPECT_LE(steps8, 0.02) << name;
        EXPECT_LE(ultraNearest, 0.02) << name;
        EXPECT_LE(high, 0.02) << name;
        EXPECT_LE(highNearest, 0.02) << name;
        EXPECT_LE(highMip, 0.02) << name;
        EXPECT_LE(highPlanarMip, 0.02) << name;
    }
}
