// Ray tracing on Embree 3: the scene's BVH, primary rays into a GBuffer, and Monte Carlo ground truth of
// ambient occlusion and obscurance, against which every screen-space and baked method is measured.
//
// Errors: constructing a Tracer throws obscura::Error if Embree cannot create its device or scene.
// intersect()/occluded() and the estimators are hot paths and check nothing.
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/image.h"
#include "obscura/sampling.h"
#include "obscura/scene.h"

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>

namespace obscura::trace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Falloff g(t) of the obscurance integral A = 1 - (1/pi) * Integral g(t(w)) cos(theta) dw over the
// hemisphere, where t(w) is the distance to the first hit in direction w and a miss contributes 0.
enum class Falloff {
    // Ambient occlusion: g = 1 for t < radius, else 0, so A = (1/pi) Integral V_r(w) cos(theta) dw.
    Binary,
    // Alchemy (McGuire et al. 2011, eq. 4-7): g(t) = scale * u * t / max(u, t)^2 for t < radius, else 0.
    Alchemy,
    // Exponential kernel (Sloan et al. 2013, eq. 1): A = (1/pi) Integral rho(t) cos dw with
    // rho(t) = 1 - exp(a t), a = ln(0.5) / d; that is g(t) = exp(a t) (a miss has rho = 1, g = 0).
    Exponential,
};

struct ObscuranceSettings {
    Falloff falloff = Falloff::Binary;
    float radius = kInfinity;       // r: m, (0, inf]; Binary and Alchemy ignore hits at t >= r
    float alchemyU = 0.05f;         // u of Alchemy's g(t): m, > 0 (the paper plots u = 0.05 r and 0.1 r)
    float alchemyScale = 1.0f;      // multiplies Alchemy's g(t): >= 0; not eq. 10's sigma itself, but sigma / u
                                    // for the paper's form and pi * scale for the chapter's (rayTracedEquivalent)
    float halfDistance = 2.0f;      // d of the exponential kernel: m, > 0 (rho(d) = 1/2); Sloan uses 2 and 300
    int rays = 256;                 // rays per point: [1, 1<<20]; cosine-weighted, stratified (shifted Sobol)
    std::uint32_t seed = 0;         // any value; the same seed gives the same bits on any thread count

    void validate() const;          // throws obscura::Error naming the bad field
    // How far the falloff reads, m: d for the exponential one, else r. The far-from-origin check holds it against
    // float precision (rayReachProblem).
    float reach() const { return falloff == Falloff::Exponential ? halfDistance : radius; }
    // The weight g(t) of a hit at distance t (pass kInfinity for a miss).
    float weight(float t) const;
};

struct Hit {
    float t = kInfinity;
    std::uint32_t instance = 0;    // index into Scene::instances
    std::uint32_t primitive = 0;   // triangle index within the instance's mesh
    float u = 0, v = 0;            // barycentrics of vertices 1 and 2
    Vec3 geometricNormal;          // world space, unit, the triangle's winding side (not flipped to the ray)
};

class Tracer {
public:
    // Builds one Embree scene per mesh and a top-level scene of instances. The Scene must outlive the
    // Tracer; it is referenced, not copied.
    explicit Tracer(const Scene& scene);
    ~Tracer();
    Tracer(const Tracer&) = delete;
    Tracer& operator=(const Tracer&) = delete;

    const Scene& scene() const { return scene_; }
    Bounds bounds() const { return bounds_; }

    // Closest hit in (tnear, tfar); false on a miss. No checks.
    bool intersect(Vec3 origin, Vec3 direction, float tnear, float tfar, Hit& hit) const;
    // Distance to the closest hit in (tnear, tfar), kInfinity on a miss; cheaper than intersect(). No checks.
    float closestDistance(Vec3 origin, Vec3 direction, float tnear, float tfar) const;
    // True if anything is hit in (tnear, tfar). No checks.
    bool occluded(Vec3 origin, Vec3 direction, float tnear, float tfar) const;

    // Interpolated vertex normal at a hit, world space, unit; the geometric normal for a mesh without one normal
    // per position. Not flipped: a file's normals may disagree with its winding, so callers orient both normals
    // to the side they need (e.g. towards the camera).
    Vec3 shadingNormal(const Hit& hit) const;
    Vec3 albedo(const Hit& hit) const;
    Vec3 hitPoint(Vec3 origin, Vec3 direction, const Hit& hit) const { return origin + direction * hit.t; }
    // The hit's point from its barycentrics on the world-space triangle: on the triangle's plane to the
    // rounding of its own coordinates, where hitPoint is off it by the rounding of the ray's origin (a camera
    // 100 km out puts that a centimetre or more off). With `offset`, also selfHitOffset for rays leaving it,
    // from the same world-space triangle.
    Vec3 surfacePoint(const Hit& hit, float* offset = nullptr) const;
    // Distance to move a ray origin along the geometric normal so that the ray does not hit the triangle it starts
    // on (see trace::selfHitOffset). For a point p on hit's triangle, found by a ray from `origin`.
    float selfHitOffset(const Hit& hit, Vec3 origin, Vec3 p) const;
    // For a point p on a surface with unit geometric normal ng whose triangle is not known: one ray down ng
    // finds the triangle. Where it finds none, the offset of a triangle of aspect ratio 100 spanning the scene.
    float selfHitOffset(Vec3 p, Vec3 ng) const;

    // The Embree scene handle (RTCScene), for benchmarks that call Embree directly.
    void* embreeScene() const;

private:
    std::array<Vec3, 3> worldTriangle(const Hit& hit) const;  // the hit triangle's corners in world space

    struct Impl;
    std::unique_ptr<Impl> impl_;
    const Scene& scene_;
    Bounds bounds_;
};

// Distance to move a ray origin at p, on the triangle (a, b, c) (world space, m), along the triangle's normal so
// that the ray does not hit that triangle again. Embree intersects in float: the plane it tests lies within a few
// float ulps of the coordinates involved (the vertices', the point's) times the triangle's aspect ratio
// (longest edge^2 / twice its area), so the offset is 2.5e-7 of the largest |coordinate| times the aspect ratio,
// at least 4. `scale` adds a coordinate magnitude the point was computed from (a primary ray's origin), or 0.
// Measured once (2026-11-28, a scratch program not kept in the repository) on random planes 1 m to 100 km from
// the origin, 0.96 M cosine-distributed rays each: self-hits stop
// at 5e-7 x the largest coordinate for aspect ratios up to 10, at 5e-6 for 100 and at 5e-5 for 1000, so the
// offset is twice to five times what each needed. (A fixed 1e-4 of |p| was 100 times too large for well-shaped
// triangles: 0.1 m at 1 km from the origin, which took a 1 m gap's occlusion from 0.25 to 0.20.)
float selfHitOffset(Vec3 a, Vec3 b, Vec3 c, Vec3 p, float scale = 0.0f);
// The least offset any ray leaving a surface within `bounds` gets (selfHitOffset of the best-shaped triangle at the
// point of the box nearest the origin, by the largest |coordinate|), m. A scene far from the origin has little
// float precision left: 8 m rooms 1e7 m out start every ray some 10 m off its surface, past any radius, and
// ray-traced AO came out 1 everywhere. Callers compare it with their reach (r, d) and refuse or warn.
float selfHitOffsetFloor(const Bounds& bounds);
// Why rays of this reach (r, or d for the exponential falloff; m) from surfaces within `bounds`, named `scene` in the
// text, start too far off those surfaces: "" when selfHitOffsetFloor is under 1% of the reach. From 25% (`refuse`
// set) AO reads 1 everywhere, and ObscuranceEstimator and bake::traceSamples throw with this text; between, the
// AO is lighter, and the CLI warns.
std::string rayReachProblem(const Bounds& bounds, float reach, const std::string& scene, bool& refuse);

using Progress = std::function<void(double fraction)>;

struct GBufferSettings {
    int supersample = 1;   // N: N x N sub-samples per pixel averaged into albedo, [1, 16]
};

// One primary ray through each pixel centre gives depth and normal (view space); albedo is averaged over
// N x N stratified sub-samples, so pictures are antialiased while depth and normal stay exact.
GBuffer renderGBuffer(const Tracer& tracer, const Camera& camera, const GBufferSettings& settings = {},
                      const Progress& progress = {});

// Estimates obscurance at many points with one set of settings, sharing the precomputed ray directions.
// Thread-safe: operator() may be called from any number of threads.
class ObscuranceEstimator {
public:
    // Validates the settings (throws obscura::Error).
    ObscuranceEstimator(const Tracer& tracer, const ObscuranceSettings& settings);

    // Obscurance A in [0,1] at world point p with hemisphere axis n (unit) and geometric normal ng (unit,
    // either side: it is turned to n's side for the origin offset). `pointId` seeds the point's rays, with
    // settings.seed. `offset` moves the rays' origin along ng (Tracer::selfHitOffset); below 0, the offset for a
    // point on a triangle not known. Hot path: no checks.
    float operator()(Vec3 p, Vec3 n, Vec3 ng, std::uint32_t pointId, float offset = -1.0f) const;

    // The same A, and the standard error of A estimated from two nets of the point's rays (its first 2h, h the
    // largest power of 2 up to N/2): on the high side, as the nets of one shifted sequence are anticorrelated:
    // 0.94 to 1.8 times the spread of A over seeds under the closed-form ceiling, 2.4 to 2.8 at a point of
    // corner. NaN under 8 rays (nets of 1 or 2 rays tell nothing: at 4, 22 times the spread).
    struct Estimate {
        float value = 1.0f;
        float standardError = std::numeric_limits<float>::quiet_NaN();
    };
    Estimate estimate(Vec3 p, Vec3 n, Vec3 ng, std::uint32_t pointId, float offset = -1.0f) const;

    // The pieces of operator(), for benchmarks that trace the very same rays by other means.
    struct PointFrame {
        Vec3 origin, t, b, n;
        CosineHemisphereSet::Shift shift;
    };
    PointFrame frame(Vec3 p, Vec3 n, Vec3 ng, std::uint32_t pointId, float offset = -1.0f) const;
    Vec3 direction(const PointFrame& f, int i) const {
        Vec3 l = directions_.direction(i, f.shift);
        return f.t * l.x + f.b * l.y + f.n * l.z;
    }
    // Rays ignore hits beyond this distance (r, or where the exponential weight drops below 2^-24).
    float maxDistance() const { return tfar_; }
    const ObscuranceSettings& settings() const { return settings_; }

private:
    const Tracer& tracer_;
    ObscuranceSettings settings_;
    CosineHemisphereSet directions_;
    float tfar_;
};

// One point; builds the direction set on every call, so prefer ObscuranceEstimator for many points.
float ambientObscurance(const Tracer& tracer, Vec3 p, Vec3 n, Vec3 ng, const ObscuranceSettings& settings,
                        std::uint32_t pointId);

// Per-pixel obscurance of a G-buffer rendered from this tracer's scene: each pixel's primary ray is traced
// again for the exact hit point and geometric normal; the hemisphere is about the G-buffer normal. Sky
// pixels get 1. Returns a 1-channel image. Deterministic for a seed, any thread count. Throws obscura::Error for
// a G-buffer that does not match its camera (GBuffer::validate) or a camera that is not valid. `standardError`, if given,
// gets each pixel's ObscuranceEstimator::Estimate::standardError (sky: 0; NaN under 8 rays).
Image ambientObscurance(const Tracer& tracer, const GBuffer& gbuffer, const ObscuranceSettings& settings,
                        const Progress& progress = {}, Image* standardError = nullptr);

} // namespace obscura::trace
