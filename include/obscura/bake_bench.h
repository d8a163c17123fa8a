// Trace-stage throughput of the bake against bare Embree calls on the same rays, for the "fraction of raw
// Embree" figure: raw rtcIntersect1 over the rays of every stride-th sample (a uniform subset of the
// bake's rays), timed without ray generation.
#pragma once

#include "obscura/bake.h"

#include <cstdint>

namespace obscura::bake {

RawTraceResult benchRawEmbree(const trace::Tracer& tracer, const SampleSet& samples, const BakeSettings& settings,
                              std::size_t stride);

} // namespace obscura::bake
