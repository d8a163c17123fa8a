// Ray-tracing throughput: the ground-truth estimator against a bare loop of Embree calls on the very same
// rays, so its overhead is a ratio measured in one run.
#pragma once

#include "obscura/trace.h"

#include <cstdint>

namespace obscura::trace {

struct TraceBenchResult {
    std::uint64_t rays = 0;          // hemisphere rays traced (primary rays not counted)
    double estimatorSeconds = 0;     // ambientObscurance() over the G-buffer, wall time
    double rawSeconds = 0;           // rtcOccluded1 / rtcIntersect1 over the same rays, wall time of the
                                     // traversal alone (ray generation excluded)
    double estimatorMrays() const { return double(rays) / estimatorSeconds * 1e-6; }
    double rawMrays() const { return double(rays) / rawSeconds * 1e-6; }
};

// Runs both on every non-sky pixel of `gbuffer`. Binary falloff uses occlusion queries, the others closest
// hits, as the estimator does.
TraceBenchResult benchObscurance(const Tracer& tracer, const GBuffer& gbuffer, const ObscuranceSettings& settings);

} // namespace obscura::trace
