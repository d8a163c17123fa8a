// GtaoSampling::PlanarNearest: planar horizon samples within 2 mipDistanceRatio pixels of the centre, the
// nearest pixel beyond (Jimenez et al. 2016 sample the depth buffer; which point of a pixel stands for a
// sample is ours, docs/QUALITY.md). Nearest samples of a slice a little off a pixel axis stay on the
// centre's row for their first steps, up to half a pixel off the slice line, and at grazing angles that
// point rises above the slice's plane: a false horizon, near the pixel only. Far samples are off the line
// by a small angle. So planar near samples should keep planar's error at nearly nearest's cost.
#include "ssao/gtao_scenes.h"

#include "obscura/builtin_scenes.h"
#include "obscura/gtao.h"
#include "obscura/trace.h"

#include <gtest/gtest.h>

#include <cstdio>

using namespace obscura;
using namespace obscura::ssao;

namespace {

struct OwnView {
    explicit OwnView(const char* name, int width, int height)
        : scene(makeBuiltinScene(name)), tracer(scene.scene), g(renderAt(tracer, scene.camera, width, height)) {}
    static GBuffer renderAt(const trace::Tracer& tracer, Camera camera, int width, int height) {
        camera.width = width;
        camera.height = height;
        return trace::renderGBuffer(tracer, camera);
    }
    BuiltinScene scene;  // the tracer keeps a reference to it
    trace::Tracer tracer;
    GBuffer g;
};

} // namespace

// With a ratio whose near zone (2 x 64 pixels) covers every sample of a small image, PlanarNearest is
// Planar bit for bit; with the smallest ratio (near zone 4 pixels) it differs from both Planar and Nearest.
TEST(GtaoPlanarNearest, IsPlanarInsideItsNearZone) {
    const OwnView view("stairs", 96, 64);
    GtaoSettings planar;
    planar.sampling = GtaoSampling::Planar;
    GtaoSettings wide = planar;
    wide.sampling = GtaoSampling::PlanarNearest;
    wide.mipDistanceRatio = 64.0f;
    const Image a = computeGtao(view.g, planar).visibility, b = computeGtao(view.g, wide).visibility;
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    for (size_t i = 0; i < a.pixels.size(); ++i) ASSERT_EQ(a.pixels[i], b.pixels[i]) << "pixel " << i;

    GtaoSettings narrow = wide;
    narrow.mipDistanceRatio = 2.0f;
    GtaoSettings nearest = planar;
    nearest.sampling = GtaoSampling::Nearest;
    const Image c = computeGtao(view.g, narrow).visibility, d = computeGtao(view.g, nearest).visibility;
    EXPECT_GT(test::meanAbsoluteError(view.g, a, c), 0.0);
    EXPECT_GT(test::meanAbsoluteError(view.g, c, d), 0.0);
}

// Rotated slices (2 jittered slices of 4 steps, the configuration of the half-resolution and denoised
// studies) on the own views of stairs and well, where nearest samples lose to planar ones
// (docs/QUALITY.md), against ray-traced AO of the same radius (256 rays). PlanarNearest must stay within
// 0.001 MAE of Planar and below Nearest on both.
TEST(GtaoPlanarNearest, KeepsPlanarErrorWithRotatedSlices) {
    for (const char* name : {"stairs", "well"}) {
        const OwnView view(name, 320, 180);
        const Image reference = test::rayTracedReference(view.tracer, view.g, 1.0f, 256);
        auto error = [&](GtaoSampling sampling) {
            GtaoSettings s;
            applyQuality(s, GtaoQuality::High);
            s.sampling = sampling;
            GtaoSliceOverride{2, 4, true}.apply(s);
            return test::meanAbsoluteError(view.g, computeGtao(view.g, s).visibility, reference);
        };
        const double planar = error(GtaoSampling::Planar), nearest = error(GtaoSampling::Nearest),
                     planarNearest = error(GtaoSampling::PlanarNearest);
        std::printf("%s own view, 2x4 jittered: MAE planar %.4f, nearest %.4f, planar-nearest %.4f\n", name, planar,
                    nearest, planarNearest);
        EXPECT_LE(planarNearest, planar + 0.001) << name;
        EXPECT_LT(planarNearest, nearest) << name;
    }
}
