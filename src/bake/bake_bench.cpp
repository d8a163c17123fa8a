// Throughput of the bake's trace stage against bare Embree on the same rays: the rays of every stride-th
// sample, generated outside the timed part, traced with rtcIntersect1 as src/trace/trace_bench.cpp does.
// Batches alternate between bare Embree and the bake's own per-sample path on the same samples, so both
// see the same machine load, which on a shared machine moves more than either.
#include "obscura/bake_bench.h"

#include "obscura/parallel.h"

#include "bake/ray_setup.h"
#include "trace/embree_ray.h"

#include <atomic>
#include <chrono>

namespace obscura::bake {

RawTraceResult benchRawEmbree(const trace::Tracer& tracer, const SampleSet& samples, const BakeSettings& settings,
                              std::size_t stride) {
    RawTraceResult r;
    r.stride = stride;
    auto scene = static_cast<RTCScene>(tracer.embreeScene());
    const detail::SampleTracer sampleTracer(tracer, settings);
    const float tfar = sampleTracer.tfar();
    std::vector<float> ox, oy, oz, dx, dy, dz;
    std::vector<std::size_t> ids;
    std::vector<float> sink(samples.size() / stride * 2 + 2);
    std::atomic<std::uint64_t> hits{0};
    const std::size_t batchSamples = 4096;
    auto now = [] { return std::chrono::steady_clock::now(); };
    for (std::size_t first = 0; first < samples.size(); first += batchSamples * stride) {
        for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz}) v->clear();
        ids.clear();
        for (std::size_t s = first; s < std::min(samples.size(), first + batchSamples * stride); s += stride) {
            ids.push_back(s);
            const detail::SampleFrame f = sampleTracer.frame(samples, s);
            for (std::size_t i = 0; i < std::size_t(settings.rays); ++i) {
                const Vec3 w = sampleTracer.direction(f, i);
                ox.push_back(f.origin.x);
                oy.push_back(f.origin.y);
                oz.push_back(f.origin.z);
                dx.push_back(w.x);
                dy.push_back(w.y);
                dz.push_back(w.z);
            }
        }
        const std::size_t count = ox.size();
        auto t0 = now();
        parallelFor(count, [&](std::size_t begin, std::size_t end) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            std::uint64_t local = 0;
            for (std::size_t i = begin; i < end; ++i) {
                RTCRayHit rh = trace::makeRayHit({ox[i], oy[i], oz[i]}, {dx[i], dy[i], dz[i]}, 0.0f, tfar);
                rtcIntersect1(scene, &context, &rh);
                local += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            }
            hits += local;  // keeps the loop from being optimised away
        }, 4096);
        auto t1 = now();
        parallelFor(ids.size(), [&](std::size_t begin, std::size_t end) {
            detail::SampleTracer::Scratch scratch = sampleTracer.scratch();
            float values[2];
            for (std::size_t k = begin; k < end; ++k) {
                sampleTracer.trace(samples, ids[k], scratch, values);
                sink[(first / stride + k) % sink.size()] = values[0];
            }
        }, 16);
        auto t2 = now();
        r.seconds += std::chrono::duration<double>(t1 - t0).count();
        r.bakeSeconds += std::chrono::duration<double>(t2 - t1).count();
        r.rays += count;
    }
    r.hits = hits;
    return r;
}

} // namespace obscura::bake
