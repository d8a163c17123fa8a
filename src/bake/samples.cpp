// Surface samples for the least-squares bake (Sloan et al. 2013 §2.1): a minimum and a maximum number per
// face, area-proportional in between, so coarse distant geometry does not take the budget from the
// playable area; the finite-element weights (A_T / N_T in the solve) make up for the uneven density.
#include "obscura/bake.h"

#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/sampling.h"
#include "obscura/trace.h"

#include "core/face_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace obscura::bake {

SampleSet generateSamples(const WeldedMesh& mesh, const BakeSettings& settings) {
    SampleSet s;
    const std::size_t triangles = mesh.triangleCount();
    // Counted in 64 bits and checked before anything is allocated: a 32-bit running total once wrapped past
    // 2^32 samples, and the per-face writes below ran off the end of the arrays. A prefix stored in the
    // 32-bit triangleFirst is exact whenever the total passes the check. Every face has a sample at least,
    // so the check also keeps the per-sample triangle ids in range.
    s.triangleFirst.resize(triangles + 1);
    std::uint64_t total = 0;
    for (std::size_t t = 0; t < triangles; ++t) {
        s.triangleFirst[t] = std::uint32_t(total);
        const Vec3 p0 = mesh.positions[mesh.indices[3 * t]], p1 = mesh.positions[mesh.indices[3 * t + 1]],
                   p2 = mesh.positions[mesh.indices[3 * t + 2]];
        const double area = 0.5 * geometry::twiceArea(p0, p1, p2);
        const double wanted = std::ceil(area * double(settings.sampleDensity));
        total += std::uint64_t(std::clamp(wanted, double(settings.minSamplesPerFace), double(settings.maxSamplesPerFace)));
    }
    constexpr std::uint64_t kMaxSamples = std::numeric_limits<std::uint32_t>::max();
    if (total > kMaxSamples)
        fail("bake", std::to_string(total) + " samples on " + std::to_string(triangles) + " faces exceed the " +
                         std::to_string(kMaxSamples) + " that 32-bit sample ids can number; lower --max-samples-per-face, "
                         "--min-samples-per-face or --sample-density, or bake the scene in parts");
    s.triangleFirst[triangles] = std::uint32_t(total);
    s.positions.resize(total);
    s.normals.resize(total);
    s.triangles.resize(total);
    s.barycentrics.resize(total);
    s.offsets.resize(triangles);

    parallelFor(triangles, [&](std::size_t begin, std::size_t end) {
        for (std::size_t t = begin; t < end; ++t) {
            const Vec3 p0 = mesh.positions[mesh.indices[3 * t]], p1 = mesh.positions[mesh.indices[3 * t + 1]],
                       p2 = mesh.positions[mesh.indices[3 * t + 2]];
            // In double, as the weld's area test: a sliver it keeps can have a float cross product of zero.
            const Vec3 n = geometry::unitNormal(p0, p1, p2);
            // Once per face, not per sample: no sample's coordinates exceed its face's largest. Welding moved the
            // face's corners by up to their weldShift, so its samples may lie that far off the surface traced:
            // by that much more, and only that much (the weld tolerance of the whole scene's diagonal once
            // lifted every sample 1 cm over a contact shadow 5 cm deep, because of one object 100 km away).
            float shift = 0.0f;
            if (!mesh.weldShift.empty())
                for (int k = 0; k < 3; ++k) shift = std::max(shift, mesh.weldShift[mesh.indices[3 * t + std::size_t(k)]]);
            s.offsets[t] = trace::selfHitOffset(p0, p1, p2, p0) + shift;
            // The first N points of a scrambled Sobol sequence are stratified for any N; the warp
            // (1 - sqrt u, sqrt u (1 - v), sqrt u v) maps equal areas of the square to equal areas of the face.
            const OwenSobol2D sequence(hashCombine(settings.seed, std::uint32_t(t)));
            for (std::uint32_t i = s.triangleFirst[t], k = 0; i < s.triangleFirst[t + 1]; ++i, ++k) {
                const Vec2 u = sequence(k);
                const float r = std::sqrt(u.x);
                const float l1 = r * (1.0f - u.y), l2 = r * u.y;
                s.positions[i] = p0 * (1.0f - l1 - l2) + p1 * l1 + p2 * l2;
                s.normals[i] = n;
                s.triangles[i] = std::uint32_t(t);
                s.barycentrics[i] = {l1, l2};
            }
        }
    }, 256);
    return s;
}

} // namespace obscura::bake
