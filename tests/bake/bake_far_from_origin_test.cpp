// The bake of a floor under a ceiling, tilted and carried far from the origin with its positions in world space,
// as a large level's are: the baked occlusion must not depend on where the scene sits.
#include "obscura/bake.h"

#include "bake/bake_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace obscura;
using namespace obscura::bake;

// Binary occlusion within d = 2 under a ceiling 1 m up is (h/d)^2 = 0.25. Each sample's rays leave it offset
// along the normal by a few float ulps of its coordinates (and the weld tolerance); a fixed 1e-4 of |p| put
// them 0.1 m up at 1 km and baked 0.20. Bound: the mean over interior floor vertices within 0.001 (as in
// BakeClosedForm) plus the bias the offset itself may cause, (h^2 - (h - o)^2) / d^2, for an offset o of
// 2.5e-7 x the largest coordinate x the aspect ratio 4, plus the weld distance.
TEST(BakeClosedForm, OcclusionUnderCeilingDoesNotDependOnWhereTheSceneIs) {
    const double h = 1.0, d = 2.0, expected = 0.25;
    const Mat4 rotation = Mat4::rotation(normalize(Vec3{0.3f, 0.2f, 1.0f}), 0.7f);
    for (float distance : {0.0f, 1000.0f, 5000.0f}) {
        SCOPED_TRACE(distance);
        Scene scene;
        scene.add(fixtures::grid(-4, 4, -4, 4, 0, 16));
        scene.add(fixtures::grid(-100, 100, -100, 100, float(h), 1, true));
        const std::vector<Vec3> floorBefore = scene.meshes[0].positions;
        const Vec3 shift = normalize(Vec3{1.0f, -0.4f, 0.6f}) * distance;
        for (Mesh& m : scene.meshes)
            for (Vec3& p : m.positions) p = transformPoint(rotation, p) + shift;
        BakeSettings settings;
        settings.mode = Mode::Occlusion;
        settings.distances = {float(d)};
        settings.rays = 256;
        const BakeResult r = bakeScene(scene, settings);

        const double largest = double(distance) + 100.0 * std::sqrt(2.0) + 2.0;
        const double weld = double(settings.weldTolerance) * double(length(scene.bounds().size()));
        const double offset = 2.5e-7 * largest * 4.0 + weld;
        const double bias = (h * h - (h - offset) * (h - offset)) / (d * d);
        double mean = 0;
        int count = 0;
        for (std::size_t v = 0; v < floorBefore.size(); ++v) {
            if (std::fabs(floorBefore[v].x) > 3 || std::fabs(floorBefore[v].z) > 3) continue;
            mean += double(r.values[r.instanceFirst[0] + v]);
            ++count;
        }
        mean /= count;
        EXPECT_NEAR(mean, expected, 0.001 + bias);
        EXPECT_EQ(r.invalidSamples, 0u);
    }
}
