// Throughput of the obscurance estimator against bare Embree calls on identical rays.
#include "obscura/trace_bench.h"

#include "obscura/parallel.h"
#include "trace/primary_ray.h"

#include "trace/embree_ray.h"

#include <atomic>
#include <chrono>

namespace obscura::trace {

namespace {

double now() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

struct RayBatch {
    std::vector<float> ox, oy, oz, dx, dy, dz, tfar;
    void clear() {
        for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz, &tfar}) v->clear();
    }
};

} // namespace

TraceBenchResult benchObscurance(const Tracer& tracer, const GBuffer& g, const ObscuranceSettings& s) {
    TraceBenchResult result;
    const Camera& cam = g.camera;
    const Mat4 worldFromView = cam.worldFromView();


    // The same rays as the estimator, generated row by row outside the timed part.
    auto scene = static_cast<RTCScene>(tracer.embreeScene());
    const ObscuranceEstimator estimator(tracer, s);
    const float tfar = estimator.maxDistance();
    const bool binary = s.falloff == Falloff::Binary;
    RayBatch batch;
    std::atomic<std::uint64_t> hits{0};
    const int rowsPerBatch = 8;
    for (int y0 = 0; y0 < cam.height; y0 += rowsPerBatch) {
        batch.clear();
        for (int y = y0; y < std::min(cam.height, y0 + rowsPerBatch); ++y)
            for (int x = 0; x < cam.width; ++x) {
                Vec3 p, n, ng;
                float offset;
                if (!pixelSurface(tracer, g, worldFromView, x, y, p, n, ng, offset)) continue;
                auto f = estimator.frame(p, n, ng, std::uint32_t(y) * std::uint32_t(cam.width) + std::uint32_t(x),
                                         offset);
                for (int i = 0; i < s.rays; ++i) {
                    Vec3 w = estimator.direction(f, i);
                    batch.ox.push_back(f.origin.x);
                    batch.oy.push_back(f.origin.y);
                    batch.oz.push_back(f.origin.z);
                    batch.dx.push_back(w.x);
                    batch.dy.push_back(w.y);
                    batch.dz.push_back(w.z);
                    batch.tfar.push_back(tfar);
                }
            }
        const std::size_t count = batch.ox.size();
        double t1 = now();
        parallelFor(count, [&](std::size_t begin, std::size_t end) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            std::uint64_t local = 0;
            for (std::size_t i = begin; i < end; ++i) {
                RTCRayHit rh = makeRayHit({batch.ox[i], batch.oy[i], batch.oz[i]}, {batch.dx[i], batch.dy[i], batch.dz[i]},
                                          0.0f, batch.tfar[i]);
                if (binary) {
                    rtcOccluded1(scene, &context, &rh.ray);
                    local += rh.ray.tfar < 0.0f;
                } else {
                    rtcIntersect1(scene, &context, &rh);
                    local += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
                }
            }
            hits += local;  // keeps the loop from being optimised away
        }, 4096);
        result.rawSeconds += now() - t1;
        result.rays += count;
    }
    // The estimator second, so neither side gets a cold cache or a cold thread pool the other did not.
    double t0 = now();
    Image ao = ambientObscurance(tracer, g, s);
    result.estimatorSeconds = now() - t0;
    (void)ao;
    return result;
}

} // namespace obscura::trace
