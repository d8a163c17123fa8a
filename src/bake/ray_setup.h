// The rays of one bake sample, shared by traceSamples and the raw-Embree throughput check so both trace
// exactly the same rays.
#pragma once

#include "obscura/bake.h"
#include "obscura/sampling.h"
#include "obscura/trace.h"

#include <algorithm>

namespace obscura::bake::detail {

struct SampleFrame {
    Vec3 origin, t, b, n;
    CosineHemisphereSet::Shift shift;
    Vec3 direction(const CosineHemisphereSet& set, int i) const {
        const Vec3 l = set.direction(i, shift);
        return t * l.x + b * l.y + n * l.z;
    }
};

inline SampleFrame sampleFrame(const trace::Tracer& tracer, const SampleSet& samples, std::size_t s, std::uint32_t seed) {
    SampleFrame f;
    const Vec3 p = samples.positions[s];
    f.n = samples.normals[s];
    orthonormalBasis(f.n, f.t, f.b);
    f.origin = p + f.n * tracer.selfHitOffset(p);
    f.shift = CosineHemisphereSet::shift(hashCombine(seed, std::uint32_t(s)));
    return f;
}

// Occlusion needs hits within the largest d; beyond 24 d the exponential weight exp(a t) is below 2^-24,
// under float resolution of A.
inline float rayFar(const BakeSettings& settings) {
    const float d = *std::max_element(settings.distances.begin(), settings.distances.end());
    return settings.mode == Mode::Occlusion ? d : 24.0f * d;
}

} // namespace obscura::bake::detail
