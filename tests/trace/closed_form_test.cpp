// Ray-traced ambient occlusion and obscurance against closed forms.
//
// Every estimate uses N = 4096 cosine-weighted rays, so A_hat = 1 - mean(g_i) with g_i in [0, 1]. The
// standard error of an i.i.d. estimate is sigma = sqrt(Var g / N) <= sqrt(A (1 - A) / N) (a [0,1] variable
// with mean m has variance at most m (1 - m)); at A = 0.5 that is 0.0078. The Sobol directions are
// stratified, which only lowers the error, so |A_hat - A| <= 3 sigma is a bound the estimator must meet.
// Where a mean over P points with independent seeds is checked, the bound is 3 sigma / sqrt(P), which
// also catches a small bias.
#include "obscura/builtin_scenes.h"
#include "obscura/mesh_builder.h"
#include "obscura/trace.h"
#include "trace/closed_form_scenes.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace obscura;
using namespace obscura::trace;

namespace {

constexpr int kRays = 4096;

double sigma(double a, int rays = kRays) { return std::sqrt(std::max(a * (1.0 - a), 1e-12) / rays); }

ObscuranceSettings occlusion(float radius) {
    ObscuranceSettings s;
    s.falloff = Falloff::Binary;
    s.radius = radius;
    s.rays = kRays;
    return s;
}

const Vec3 kUp{0, 1, 0};

// Mean estimate over `points` seeds at the same point.
double meanOver(const Tracer& tracer, Vec3 p, Vec3 n, ObscuranceSettings s, int points) {
    double sum = 0;
    for (int i = 0; i < points; ++i) sum += double(ambientObscurance(tracer, p, n, n, s, std::uint32_t(i)));
    return sum / points;
}

} // namespace

TEST(ClosedForm, OpenPlaneIsUnoccluded) {
    BuiltinScene s = makeBuiltinScene("plane");
    Tracer tracer(s.scene);
    for (float r : {0.5f, 2.0f, kInfinity})
        for (Vec3 p : {Vec3{0, 0, 0}, Vec3{3, 0, -7}, Vec3{-50, 0, 20}})
            EXPECT_EQ(ambientObscurance(tracer, p, kUp, kUp, occlusion(r), 1), 1.0f) << "r " << r;
}

TEST(ClosedForm, FootOfAnInfiniteWallIsOneHalf) {
    // Every direction with a -Z component hits the wall: exactly half of the cosine-weighted hemisphere.
    const Scene scene = test::wallAndFloor();
    Tracer tracer(scene);
    const double expected = 0.5;
    for (float z : {1e-3f, 0.05f}) {
        float a = ambientObscurance(tracer, {0, 0, z}, kUp, kUp, occlusion(kInfinity), 7);
        EXPECT_NEAR(a, expected, 3 * sigma(expected)) << "distance from wall " << z << " (sigma 0.0078)";
    }
    double mean = meanOver(tracer, {0, 0, 0.01f}, kUp, occlusion(kInfinity), 16);
    EXPECT_NEAR(mean, expected, 3 * sigma(expected) / 4);
}

namespace {
// Cosine-weighted fraction of directions from the origin (normal +Y) that leave through a planar polygon
// above it: Lambert's contour integral, F = (1 / 2 pi) sum_i angle(v_i, v_i+1) * n . unit(v_i x v_i+1).
double polygonFormFactor(const std::vector<Vec3>& v) {
    double f = 0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        Vec3 a = normalize(v[i]), b = normalize(v[(i + 1) % v.size()]);
        Vec3 c = cross(a, b);
        f += std::acos(std::clamp(double(dot(a, b)), -1.0, 1.0)) * double(normalize(c).y);
    }
    return std::fabs(f) / (2 * M_PI);
}
} // namespace

// The built-in `corner`: a point on the wall x = 0 half a metre above the floor, its normal +X as the wall's
// winding gives it (the bake takes a face's normal from its winding). Binary occlusion within d = 2: the floor
// blocks the cosine-weighted directions with d_y < -0.25, the circular segment of the projected unit disk
// (acos(0.25) - 0.25 sqrt(1 - 0.0625)) / pi = 0.3425, so the value is 0.6575 (Simpson in double). Both walls
// were wound to face away from the floor: the wall point read 1, and the floor at the corner baked 0.948
// with 5 of 32 samples invalid.
TEST(ClosedForm, CornerWallsFaceTheFloorQuadrant) {
    const BuiltinScene s = makeBuiltinScene("corner");
    const Mesh& m = s.scene.meshes[0];
    for (std::size_t t = 0; t < m.indices.size() / 3; ++t) {
        const Vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                   c = m.positions[m.indices[3 * t + 2]];
        EXPECT_GT(dot(cross(b - a, c - a), Vec3{1, 1, 1}), 0.0f) << "triangle " << t << " faces out of the corner";
    }
    Tracer tracer(s.scene);
    Hit hit;
    ASSERT_TRUE(tracer.intersect({5, 0.5f, 5}, {-1, 0, 0}, 0.0f, kInfinity, hit));
    EXPECT_NEAR(hit.geometricNormal.x, 1.0f, 1e-6f);
    const double expected = 1.0 - (std::acos(0.25) - 0.25 * std::sqrt(1.0 - 0.0625)) / 3.14159265358979323846;
    const double mean = meanOver(tracer, {0, 0.5f, 5}, hit.geometricNormal, occlusion(2.0f), 8);
    EXPECT_NEAR(mean, expected, 3 * sigma(expected) / std::sqrt(8.0));
}

TEST(ClosedForm, FloorCentreOfAWell) {
    // Round well of radius a, depth h: the opening subtends a cone of half-angle atan(a/h), whose
    // cosine-weighted measure is sin^2 = a^2 / (a^2 + h^2) = 0.2 for a = 1, h = 2.
    BuiltinScene s = makeBuiltinScene("well");
    Tracer tracer(s.scene);
    const double a = builtin::kWellRadius, h = builtin::kWellDepth;
    const double expected = a * a / (a * a + h * h);
    // The mesh is a 256-gon inscribed in the circle; Lambert's formula on that polygon says how far that
    // moves the answer (about 1e-4), far inside the tolerance.
    std::vector<Vec3> opening;
    for (int i = 0; i < builtin::kWellSegments; ++i) {
        double t = 2 * M_PI * i / builtin::kWellSegments;
        opening.push_back({float(a * std::cos(t)), float(h), float(-a * std::sin(t))});
    }
    EXPECT_NEAR(polygonFormFactor(opening), expected, 2e-4);

    Vec3 floor{0, -float(h), 0};
    float one = ambientObscurance(tracer, floor, kUp, kUp, occlusion(kInfinity), 3);
    EXPECT_NEAR(one, expected, 3 * sigma(expected)) << "sigma " << sigma(expected);
    EXPECT_NEAR(meanOver(tracer, floor, kUp, occlusion(kInfinity), 16), expected, 3 * sigma(expected) / 4);
}

// The same floor through the per-pixel path (G-buffer, then ambientObscurance of the image), seen straight
// down from 3 m to 100 km above: the point was the ray's origin + t d, off the floor by the rounding of the
// camera's coordinates, and the offset that covered it scaled with the camera's distance times the fan
// triangle's aspect ratio (about 41): 1 m at 100 km, where the floor read 0.51 (0.217 at 10 km). The point
// is now the hit's barycentric one. The centre pixel of 3x3 (its ray is the axis) over 64 seeds: within
// 3 sigma / 8.
TEST(ClosedForm, FloorCentreOfAWellSeenFromFarAway) {
    BuiltinScene s = makeBuiltinScene("well");
    Tracer tracer(s.scene);
    const double a = builtin::kWellRadius, h = builtin::kWellDepth;
    const double expected = a * a / (a * a + h * h);
    for (float height : {3.0f, 1e4f, 1e5f}) {
        Camera c;
        c.position = {0.0f, height, 0.0f};
        c.target = {0.0f, -float(h), 0.0f};
        c.up = {0.0f, 0.0f, -1.0f};
        c.width = c.height = 3;
        // A 0.2 m square of floor, or the narrowest view a camera takes (0.35 m at 10 km, 3.5 m at 100 km).
        c.fovY = std::max(0.002f, float(2.0 * std::atan(0.1 / (double(height) + h)) * 180.0 / M_PI));
        c.nearZ = 1.0f;
        c.farZ = height + 100.0f;
        const GBuffer g = renderGBuffer(tracer, c);
        ObscuranceSettings os = occlusion(kInfinity);
        ASSERT_FALSE(g.isSky(1, 1)) << "camera " << height << " m up";
        double sum = 0;
        for (std::uint32_t seed = 0; seed < 64; ++seed) {
            os.seed = seed;
            sum += double(ambientObscurance(tracer, g, os).at(1, 1));
        }
        EXPECT_NEAR(sum / 64, expected, 3 * sigma(expected) / 8) << "camera " << height << " m up";
    }
}

TEST(ClosedForm, UnderAnInfiniteCeiling) {
    // Ceiling at height h over the point: a ray at angle theta hits at t = h / cos(theta). Within radius d,
    // the unoccluded directions are cos(theta) < h / d, whose cosine-weighted measure is (h/d)^2 for d > h,
    // and 1 (nothing within reach) for d <= h.
    BuiltinScene s = makeBuiltinScene("ceiling");
    Tracer tracer(s.scene);
    const double h = builtin::kCeilingHeight;
    for (double d : {1.25, 2.0, 4.0}) {
        double expected = h * h / (d * d);
        float a = ambientObscurance(tracer, {0, 0, 0}, kUp, kUp, occlusion(float(d)), 11);
        EXPECT_NEAR(a, expected, 3 * sigma(expected)) << "d " << d;
        EXPECT_NEAR(meanOver(tracer, {0.3f, 0, -0.2f}, kUp, occlusion(float(d)), 16), expected, 3 * sigma(expected) / 4)
            << "d " << d;
    }
    EXPECT_EQ(ambientObscurance(tracer, {0, 0, 0}, kUp, kUp, occlusion(0.9f), 1), 1.0f);
    EXPECT_NEAR(ambientObscurance(tracer, {0, 0, 0}, kUp, kUp, occlusion(kInfinity), 1), 0.0f, 1e-3);
}

TEST(ClosedForm, ExponentialObscuranceUnderACeiling) {
    // rho(t) = 1 - exp(a t), a = ln(0.5)/d; A = (1/pi) Integral rho cos dw = 1 - 2 Integral_0^1 exp(a h / mu) mu dmu.
    // With s = 1/mu: Integral_1^inf exp(-x s) 2 / s^3 ds = 2 E_3(x), x = h ln2 / d, and
    // E_3(x) = (exp(-x) (1 - x) + x^2 E_1(x)) / 2, so A = 1 - exp(-x) (1 - x) - x^2 E_1(x).
    BuiltinScene s = makeBuiltinScene("ceiling");
    Tracer tracer(s.scene);
    const double h = builtin::kCeilingHeight;
    for (double d : {0.5, 2.0, 300.0}) {
        double x = h * std::log(2.0) / d;
        double e1 = -std::expint(-x);
        double expected = 1.0 - std::exp(-x) * (1.0 - x) - x * x * e1;
        ObscuranceSettings es;
        es.falloff = Falloff::Exponential;
        es.halfDistance = float(d);
        es.rays = kRays;
        EXPECT_NEAR(ambientObscurance(tracer, {0, 0, 0}, kUp, kUp, es, 5), expected, 3 * sigma(expected)) << "d " << d;
        EXPECT_NEAR(meanOver(tracer, {0, 0, 0}, kUp, es, 16), expected, 3 * sigma(expected) / 4 + 1e-4) << "d " << d;
    }
}

TEST(ClosedForm, AlchemyObscuranceUnderACeiling) {
    // g(t) = s u t / max(u, t)^2 for t < r. Under a ceiling at height h with mu = cos(theta), t = h / mu:
    //  - where t > u, g = s u mu / h, and Integral 2 mu g dmu over mu in (h/r, 1) = s (2u / 3h) (1 - (h/r)^3);
    //  - where t < u (mu > h/u, only when h < u), g = s h / (u mu), contributing s (2h/u) (1 - h/u), and the
    //    t > u part then runs over mu in (h/r, h/u): s (2u / 3h) ((h/u)^3 - (h/r)^3).
    BuiltinScene s = makeBuiltinScene("ceiling");
    Tracer tracer(s.scene);
    const double h = builtin::kCeilingHeight;
    struct Case {
        double u, r, scale;
    };
    for (Case c : {Case{0.05, 2.0, 1.0}, Case{0.05, 2.0, 10.0}, Case{0.2, 1e30, 4.0}, Case{2.0, 1e30, 1.0}}) {
        double occluded;
        double cut = c.r > 1e29 ? 0.0 : std::pow(h / c.r, 3);
        if (h >= c.u)
            occluded = c.scale * (2 * c.u / (3 * h)) * (1 - cut);
        else
            occluded = c.scale * ((2 * h / c.u) * (1 - h / c.u) + (2 * c.u / (3 * h)) * (std::pow(h / c.u, 3) - cut));
        double expected = 1.0 - occluded;
        ObscuranceSettings as;
        as.falloff = Falloff::Alchemy;
        as.alchemyU = float(c.u);
        as.alchemyScale = float(c.scale);
        as.radius = c.r > 1e29 ? kInfinity : float(c.r);
        as.rays = kRays;
        EXPECT_NEAR(meanOver(tracer, {0, 0, 0}, kUp, as, 8), expected, 3 * sigma(expected) / std::sqrt(8.0) + 1e-4)
            << "u " << c.u << " r " << c.r << " scale " << c.scale;
    }
}

TEST(ClosedForm, WeightsOfTheFalloffs) {
    ObscuranceSettings s;
    s.falloff = Falloff::Exponential;
    s.halfDistance = 2.0f;
    EXPECT_NEAR(s.weight(2.0f), 0.5f, 1e-6);  // rho(d) = 1/2
    EXPECT_NEAR(s.weight(0.0f), 1.0f, 1e-6);
    EXPECT_EQ(s.weight(kInfinity), 0.0f);
    s.falloff = Falloff::Alchemy;
    s.alchemyU = 0.1f;
    s.radius = 1.0f;
    EXPECT_NEAR(s.weight(0.1f), 1.0f, 1e-6);   // peak at t = u
    EXPECT_NEAR(s.weight(0.05f), 0.5f, 1e-6);  // rising t / u below u
    EXPECT_NEAR(s.weight(0.5f), 0.2f, 1e-6);   // u / t above u
    EXPECT_EQ(s.weight(1.0f), 0.0f);           // cut at r
}

// The same floor and ceiling 1 m apart, tilted and carried 1 km and 5 km from the origin, with the positions
// stored in world space as a level's are: occlusion within d = 2 is (h/d)^2 = 0.25 wherever the scene is.
// Rays leave a point offset along the normal by a few float ulps of its coordinates; a fixed 1e-4 of |p| put
// them 0.1 m up at 1 km (0.20) and 0.5 m up at 5 km (0.06). The tolerance adds the bias that the offset itself
// may cause: (h^2 - (h - o)^2) / d^2 for an offset o of 2.5e-7 x the largest coordinate x the aspect ratio 4.
TEST(ClosedForm, OcclusionUnderACeilingDoesNotDependOnWhereTheSceneIs) {
    const double h = builtin::kCeilingHeight, d = 2.0, expected = (h / d) * (h / d);
    const Mat4 rotation = Mat4::rotation(normalize(Vec3{0.3f, 0.2f, 1.0f}), 0.7f);
    for (float distance : {0.0f, 1000.0f, 5000.0f}) {
        SCOPED_TRACE(distance);
        BuiltinScene s = makeBuiltinScene("ceiling");
        const Vec3 shift = normalize(Vec3{1.0f, -0.4f, 0.6f}) * distance;
        for (Mesh& m : s.scene.meshes) {
            for (Vec3& p : m.positions) p = transformPoint(rotation, p) + shift;
            for (Vec3& n : m.normals) n = transformVector(rotation, n);
        }
        Tracer tracer(s.scene);
        const double largest = double(distance) + std::sqrt(2.0) * double(builtin::kPlaneHalfSize) + 2.0;
        const double offset = 2.5e-7 * largest * 4.0;
        const double bias = (h * h - (h - offset) * (h - offset)) / (d * d);
        const Vec3 up = transformVector(rotation, kUp);

        // Points given by the caller: the tracer finds their triangle for the offset.
        double sum = 0;
        const int points = 16;
        for (int i = 0; i < points; ++i) {
            const Vec3 p = transformPoint(rotation, {0.37f * float(i % 4) - 0.5f, 0, 0.29f * float(i / 4) - 0.4f}) + shift;
            sum += double(ambientObscurance(tracer, p, up, up, occlusion(float(d)), std::uint32_t(i)));
        }
        EXPECT_NEAR(sum / points, expected, 3 * sigma(expected) / std::sqrt(double(points)) + bias);

        // Points found by primary rays: a camera 0.5 m above the floor looking straight down.
        Camera camera;
        camera.position = transformPoint(rotation, {0, 0.5f, 0}) + shift;
        camera.target = transformPoint(rotation, {0, 0, 0}) + shift;
        camera.up = transformVector(rotation, {0, 0, -1});
        camera.width = camera.height = 8;
        ObscuranceSettings settings = occlusion(float(d));
        settings.rays = 1024;
        const Image ao = ambientObscurance(tracer, renderGBuffer(tracer, camera), settings);
        double mean = 0;
        for (float a : ao.pixels) mean += double(a);
        mean /= double(ao.pixels.size());
        EXPECT_NEAR(mean, expected, 3 * sigma(expected, 1024 * 64) + bias);
    }
}
