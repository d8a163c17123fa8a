// Monte Carlo ground truth of ambient occlusion and obscurance: A = 1 - (1/pi) Integral g(t(w)) cos dw,
// estimated with cosine-weighted, stratified directions, so A ~ 1 - (1/N) sum g(t_i).
// Falloffs: binary within r; Alchemy's g(t) = u t / max(u,t)^2 (McGuire et al. 2011, eq. 4-7); the
// exponential kernel rho(t) = 1 - exp(a t), a = ln(0.5)/d (Sloan et al. 2013, eq. 1).
#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/trace.h"
#include "trace/primary_ray.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <string>

namespace obscura::trace {

void ObscuranceSettings::validate() const {
    if (!(radius > 0.0f)) fail("ao-radius", "must be > 0 (or inf), got " + numberText(radius));
    if (!(alchemyU > 0.0f) || !std::isfinite(alchemyU)) fail("ao-u", "must be a finite value > 0");
    if (!(alchemyScale >= 0.0f) || !std::isfinite(alchemyScale)) fail("ObscuranceSettings::alchemyScale", "must be a finite value >= 0");
    if (!(halfDistance > 0.0f) || !std::isfinite(halfDistance)) fail("ao-distance", "must be a finite value > 0");
    if (rays < 1 || rays > (1 << 20)) fail("ao-rays", "must be in [1, 1048576], got " + std::to_string(rays));
}

float ObscuranceSettings::weight(float t) const {
    switch (falloff) {
    case Falloff::Binary: return t < radius ? 1.0f : 0.0f;
    case Falloff::Alchemy: {
        if (!(t < radius)) return 0.0f;
        float m = std::max(alchemyU, t);
        return alchemyScale * alchemyU * t / (m * m);
    }
    case Falloff::Exponential:
        return std::isfinite(t) ? std::exp(std::log(0.5f) / halfDistance * t) : 0.0f;
    }
    return 0.0f;
}

ObscuranceEstimator::ObscuranceEstimator(const Tracer& tracer, const ObscuranceSettings& settings)
    : tracer_(tracer), settings_(settings), directions_((settings.validate(), settings.rays)),
      // Beyond 24 d the exponential weight exp(a t) is below 2^-24, under float resolution of A.
      tfar_(settings.falloff == Falloff::Exponential ? 24.0f * settings.halfDistance : settings.radius) {
    bool refuse = false;
    const std::string why = rayReachProblem(tracer.bounds(), settings.reach(), "the scene", refuse);
    if (refuse) fail(settings.falloff == Falloff::Exponential ? "ao-distance" : "ao-radius", why);
}

ObscuranceEstimator::PointFrame ObscuranceEstimator::frame(Vec3 p, Vec3 n, Vec3 ng, std::uint32_t pointId,
                                                           float offset) const {
    PointFrame f;
    if (dot(ng, n) < 0.0f) ng = -ng;
    f.origin = p + ng * (offset >= 0.0f ? offset : tracer_.selfHitOffset(p, ng));
    f.n = n;
    orthonormalBasis(n, f.t, f.b);
    f.shift = CosineHemisphereSet::shift(hashCombine(settings_.seed, pointId));
    return f;
}

float ObscuranceEstimator::operator()(Vec3 p, Vec3 n, Vec3 ng, std::uint32_t pointId, float offset) const {
    return estimate(p, n, ng, pointId, offset).value;
}

ObscuranceEstimator::Estimate ObscuranceEstimator::estimate(Vec3 p, Vec3 n, Vec3 ng, std::uint32_t pointId,
                                                            float offset) const {
    const PointFrame f = frame(p, n, ng, pointId, offset);
    const int rays = settings_.rays;
    // Summed in parts [0, h), [h, 2h), [2h, N) with h the largest power of 2 up to N/2: the first two are nets of
    // the Sobol sequence each, and their difference measures the estimate's noise. (Halves of a count that is no
    // power of 2 are no nets, and their difference read 3 to 5 times the noise at 100 rays.)
    const int h = int(std::bit_floor(unsigned(rays / 2)));
    const int bounds[4] = {0, h, 2 * h, rays};
    double sums[3] = {0.0, 0.0, 0.0};
    for (int part = 0; part < 3; ++part) {
        if (settings_.falloff == Falloff::Binary) {
            int hits = 0;
            for (int i = bounds[part]; i < bounds[part + 1]; ++i)
                hits += tracer_.occluded(f.origin, direction(f, i), 0.0f, tfar_);
            sums[part] = hits;
        } else {
            for (int i = bounds[part]; i < bounds[part + 1]; ++i)
                sums[part] += double(settings_.weight(tracer_.closestDistance(f.origin, direction(f, i), 0.0f, tfar_)));
        }
    }
    Estimate e;
    // Alchemy's g may exceed 1 with a large scale; A is clamped as its eq. 10 clamps.
    e.value = float(std::clamp(1.0 - (sums[0] + sums[1] + sums[2]) / double(rays), 0.0, 1.0));
    // Two independent means of h rays differ by d with E[d^2] = 2 Var(mean of h), and the mean of N rays has
    // about h/N of that variance: Var = d^2 h / (2 N). The two nets of one shifted sequence are anticorrelated,
    // so this errs high: 0.94 to 1.8 times the spread over seeds at a point under the closed-form ceiling, 8 to
    // 1024 rays (standard_error_test); a probe of corner (exponential, 1024 rays) read 2.4 to 2.8. The parts are
    // clamped as A is: where Alchemy's g drives both past full occlusion, A has no noise.
    // Nets of 1 or 2 rays tell nothing: at 4 rays a binary point read 22 times its spread over seeds.
    if (h >= 4) {
        const double d = std::clamp(1.0 - sums[0] / h, 0.0, 1.0) - std::clamp(1.0 - sums[1] / h, 0.0, 1.0);
        e.standardError = float(std::abs(d) * std::sqrt(double(h) / (2.0 * double(rays))));
    }
    return e;
}

float ambientObscurance(const Tracer& tracer, Vec3 p, Vec3 n, Vec3 ng, const ObscuranceSettings& settings,
                        std::uint32_t pointId) {
    return ObscuranceEstimator(tracer, settings)(p, n, ng, pointId);
}

Image ambientObscurance(const Tracer& tracer, const GBuffer& g, const ObscuranceSettings& s, const Progress& progress,
                        Image* standardError) {
    // The G-buffer is read per pixel: an empty one, or one smaller than its camera, was read past its end, and
    // a NaN field of view reached Embree's own assert.
    try {
        g.camera.validate();
    } catch (const Error& e) {
        fail("ambientObscurance", e.what());
    }
    g.validate("ambientObscurance");
    const ObscuranceEstimator estimate(tracer, s);
    const Camera& cam = g.camera;
    const Mat4 worldFromView = cam.worldFromView();
    Image ao(cam.width, cam.height, 1, 1.0f);
    ao.channelNames = {"Y"};
    if (standardError) *standardError = Image(cam.width, cam.height, 1, 0.0f);
    std::atomic<int> rowsDone{0};
    parallelFor(std::size_t(cam.height), [&](std::size_t y0, std::size_t y1) {
        for (auto y = int(y0); y < int(y1); ++y) {
            for (int x = 0; x < cam.width; ++x) {
                Vec3 p, n, ng;
                float offset;
                if (pixelSurface(tracer, g, worldFromView, x, y, p, n, ng, offset)) {
                    const ObscuranceEstimator::Estimate e = estimate.estimate(
                        p, n, ng, std::uint32_t(y) * std::uint32_t(cam.width) + std::uint32_t(x), offset);
                    ao.at(x, y) = e.value;
                    if (standardError) standardError->at(x, y) = e.standardError;
                }
            }
            int done = ++rowsDone;
            if (progress) progress(double(done) / double(cam.height));
        }
    });
    return ao;
}

} // namespace obscura::trace
