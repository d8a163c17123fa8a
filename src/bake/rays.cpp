// Obscurance rays of the bake (Sloan et al. 2013 §2-2.1): cosine-weighted stratified directions about the
// face normal; one closest hit per direction gives the obscurance at every distance, A = mean of
// rho(t_i), rho(t) = 1 - exp(a t), a = ln(0.5)/d (eq. 1, with the cosine in the sampling density), and the
// back-face count that invalidates samples inside closed geometry or under floors.
#include "obscura/bake.h"

#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/sampling.h"
#include "obscura/trace.h"
#include "obscura/trace_stream.h"

#include "bake/ray_setup.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

namespace obscura::bake {

void BakeSettings::validate() const {
    if (distances.empty() || distances.size() > 2)
        fail("--distances", "expected 1 or 2 distances, got " + std::to_string(distances.size()));
    for (float d : distances)
        if (!(d > 0.0f && d <= 1e6f)) fail("--distances", "each distance must be in (0, 1e6] m, got " + std::to_string(d));
    if (rays < 1 || rays > 65536) fail("--rays", "must be in [1, 65536], got " + std::to_string(rays));
    if (!(alpha >= 0.0f && alpha <= 1e6f)) fail("--alpha", "must be in [0, 1e6], got " + std::to_string(alpha));
    if (maxSamplesPerFace < 1 || maxSamplesPerFace > 4096)
        fail("--max-samples-per-face", "must be in [1, 4096], got " + std::to_string(maxSamplesPerFace));
    if (minSamplesPerFace < 1 || minSamplesPerFace > maxSamplesPerFace)
        fail("--min-samples-per-face", "must be in [1, max-samples-per-face = " + std::to_string(maxSamplesPerFace) +
                                           "], got " + std::to_string(minSamplesPerFace));
    if (!(sampleDensity > 0.0f && sampleDensity <= 1e6f))
        fail("--sample-density", "must be in (0, 1e6] samples per m^2, got " + std::to_string(sampleDensity));
    if (!(backFaceLimit >= 0.0f && backFaceLimit <= 1.0f))
        fail("--back-face-limit", "must be in [0, 1], got " + std::to_string(backFaceLimit));
    if (!(weldTolerance >= 0.0f && weldTolerance <= 1e-2f))
        fail("--weld-tolerance", "must be in [0, 0.01] (relative to the scene diagonal), got " + std::to_string(weldTolerance));
}

RayResults traceSamples(const trace::Tracer& tracer, const SampleSet& samples, const BakeSettings& settings,
                        const Progress& progress) {
    RayResults r;
    r.channels = settings.channels();
    const std::size_t count = samples.size();
    const auto channels = std::size_t(r.channels);
    r.values.assign(count * channels, 1.0f);
    r.valid.assign(count, 1);

    const int rays = settings.rays;
    const auto rayCount = std::size_t(rays);
    const CosineHemisphereSet directions(rays);
    const trace::HitStream stream(tracer);
    float a[2] = {0, 0}, d[2] = {0, 0};
    for (std::size_t c = 0; c < channels; ++c) {
        d[c] = settings.distances[c];
        a[c] = std::log(0.5f) / d[c];
    }
    const bool occlusion = settings.mode == Mode::Occlusion;
    const float tfar = detail::rayFar(settings);
    const auto backLimit = int(std::floor(double(settings.backFaceLimit) * rays));

    std::atomic<std::size_t> done{0}, invalid{0};
    const std::size_t grain = 64;
    parallelFor(count, [&](std::size_t begin, std::size_t end) {
        std::vector<Vec3> dirs(rayCount);
        std::vector<float> t(rayCount);
        std::vector<std::uint8_t> back(rayCount);
        std::size_t localInvalid = 0;
        for (std::size_t s = begin; s < end; ++s) {
            const detail::SampleFrame frame = detail::sampleFrame(tracer, samples, s, settings.seed);
            for (int i = 0; i < rays; ++i) dirs[std::size_t(i)] = frame.direction(directions, i);
            stream.closestHits(frame.origin, dirs.data(), rays, tfar, t.data(), back.data());
            int backCount = 0;
            double sum[2] = {0, 0};
            for (int i = 0; i < rays; ++i) {
                const float ti = t[std::size_t(i)];
                backCount += back[std::size_t(i)];
                for (std::size_t c = 0; c < channels; ++c) {
                    if (occlusion)
                        sum[c] += ti >= d[c] ? 1.0 : 0.0;
                    else
                        sum[c] += std::isfinite(ti) ? double(1.0f - std::exp(a[c] * ti)) : 1.0;
                }
            }
            for (std::size_t c = 0; c < channels; ++c) r.values[s * channels + c] = float(sum[c] / rays);
            if (backCount > backLimit) {
                r.valid[s] = 0;
                ++localInvalid;
            }
        }
        invalid += localInvalid;
        const std::size_t finished = done += end - begin;
        if (progress) progress(double(finished) / double(count));
    }, grain);
    r.rays = std::uint64_t(count) * std::uint64_t(rays);
    r.invalidSamples = invalid;
    return r;
}

} // namespace obscura::bake
