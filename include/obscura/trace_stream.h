// Closest hits of a bundle of rays from one origin, with the side of the surface each ray hit: what a bake
// needs per sample (distance for the obscurance kernel, back-face flag for invalidation), in one call.
//
// Hot path: checks nothing. Thread-safe: any number of threads may call closestHits() at once.
#pragma once

#include "obscura/trace.h"

#include <cstdint>
#include <vector>

namespace obscura::trace {

class HitStream {
public:
    // The Tracer (and its Scene) must outlive this object.
    explicit HitStream(const Tracer& tracer);

    // For each of `count` rays origin + t * directions[i], t in (0, tfar): t[i] is the closest hit distance
    // (kInfinity on a miss) and backFacing[i] is 1 when the ray hit the back of a triangle, the side from
    // which its corners appear clockwise (for a mirroring instance, as placed in the world).
    void closestHits(Vec3 origin, const Vec3* directions, int count, float tfar, float* t,
                     std::uint8_t* backFacing) const;

private:
    void* scene_;                          // RTCScene
    std::vector<Mat4> objectFromWorld_;    // per instance, for the object-space normals of instanced hits
    std::vector<std::uint8_t> mirrored_;   // per instance: its transform mirrors
};

} // namespace obscura::trace
