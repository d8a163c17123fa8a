// The bake against dense ray tracing at its own vertices: the check that least squares over surface
// samples is both accurate and smoother than evaluating obscurance at each vertex.
#pragma once

#include "obscura/bake.h"

#include <string>

namespace obscura::bake {

// Splits triangles at their edge midpoints until the longest edge is at most maxEdge * (1 + grading * r),
// r (m) the distance to `focus`, so a huge floor is fine near the objects on it and coarse far away.
// Triangles come out as soup (welding joins them); neighbours split to different depths meet at
// T-junctions, which welding leaves as cracks: fine for a measurement, not a remesher. Throws
// obscura::Error past 20 M triangles.
Scene refineScene(const Scene& scene, float maxEdge, const Bounds& focus, float grading);
// The world bounds of the instances whose own bounding-box diagonal is at most `largest` (m): the objects,
// without the floors and walls that frame them; the whole scene's bounds if there are none.
Bounds refinementFocus(const Scene& scene, float largest);

struct QualityChannel {
    double distance = 0;                   // d, m
    double bakedMae = 0, bakedMax = 0;     // least-squares bake against the reference, at welded vertices
    double pointMae = 0, pointMax = 0;     // per-vertex point sampling (settings.rays rays) against the reference
    double bakedSmoothMae = 0, pointSmoothMae = 0;  // over vertices off creases (no face turns > 30 degrees)
    double bakedJump = 0, pointJump = 0, referenceJump = 0;  // gradientJump(), 1/m
    // Where bakedMax is: the welded vertex (world space, m), its baked value (clamped to [0, 1]) and the
    // reference there, so a large max can be looked at rather than guessed at.
    Vec3 bakedMaxAt{};
    double bakedMaxValue = 0, bakedMaxReference = 0;
};

struct QualityResult {
    std::size_t vertices = 0, triangles = 0, samples = 0;
    std::size_t comparedVertices = 0;  // welded vertices in the errors
    std::size_t smoothVertices = 0;    // of those, off creases
    std::size_t hiddenVertices = 0;    // unused, or hidden (back-face test at the vertex), left out
    int referenceRays = 0;
    std::vector<QualityChannel> channels;
    double seconds = 0;
};

// Bakes the scene with `settings`, then traces the Foundation estimator (trace::ObscuranceEstimator, the
// same kernel) at every welded vertex about its normal (the normalized sum of the world normals of the
// file vertices welded there) with referenceRays rays, and with settings.rays rays for point sampling
// (another seed). Vertices hidden inside geometry (more than settings.backFaceLimit of 256 rays from the
// vertex hit back faces) are left out of the errors: nothing sees them and the reference there is
// meaningless. Obscurance mode only.
QualityResult compareWithDense(const Scene& scene, const BakeSettings& settings, int referenceRays);

} // namespace obscura::bake
