// Throughput of the bake's trace stage against bare Embree on the same rays: the rays of every stride-th
// sample, generated outside the timed part, traced with rtcIntersect1 as src/trace/trace_bench.cpp does.
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
    const CosineHemisphereSet directions(settings.rays);
    const float tfar = detail::rayFar(settings);
    std::vector<float> ox, oy, oz, dx, dy, dz;
    std::atomic<std::uint64_t> hits{0};
    const std::size_t batchSamples = 4096;
    for (std::size_t first = 0; first < samples.size(); first += batchSamples * stride) {
        for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz}) v->clear();
        for (std::size_t s = first; s < std::min(samples.size(), first + batchSamples * stride); s += stride) {
            const detail::SampleFrame f = detail::sampleFrame(tracer, samples, s, settings.seed);
            for (int i = 0; i < settings.rays; ++i) {
                const Vec3 w = f.direction(directions, i);
                ox.push_back(f.origin.x);
                oy.push_back(f.origin.y);
                oz.push_back(f.origin.z);
                dx.push_back(w.x);
                dy.push_back(w.y);
                dz.push_back(w.z);
            }
        }
        const std::size_t count = ox.size();
        const auto t0 = std::chrono::steady_clock::now();
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
        r.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        r.rays += count;
    }
    r.hits = hits;
    return r;
}

} // namespace obscura::bake
