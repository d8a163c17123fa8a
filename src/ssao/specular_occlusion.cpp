// GTSO: Jimenez et al. 2016, §6 (eq. 14-21) and App. B (eq. 25-26). The 4-D and 3-D tables of eq. 21 are
// integrated by sampling the GGX distribution of visible normals (Heitz 2018, "Sampling the GGX
// Distribution of Visible Normals"), whose weight for F = 1 is G2 / G1(w_o); the cap intersection is
// Tovchigrechko and Vakser 2001 (also Mazonka 2012, "Solid angle of conical surfaces, polyhedral cones,
// and intersecting spherical caps").
#include "obscura/specular_occlusion.h"

#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/sampling.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

namespace obscura::ssao {

namespace {

constexpr int kN = kSpecularTableSize;
constexpr float kHalfPi = 0.5f * kPi;
constexpr double kPiD = 3.14159265358979323846;
// VNDF samples per (roughness, theta_o) cell; with the Sobol net the tables agree with an independent
// Monte Carlo integration to about 0.01 (tests/ssao/specular_occlusion_test.cpp).
constexpr int kSamples = 2048;

// The angle between a and b whose (possibly clamped) dot product is c, as atan2 of |a x b| and c: acos(c) turns
// the rounding of a cosine near 1 into 3.5e-4 rad, which the tables' steep low-roughness slopes magnify past the
// GPU pass's bound. Neither vector need be unit; a zero one gives pi/2, as acos(0) did.
float angleBetween(Vec3 a, Vec3 b, float c) {
    const float s = length(cross(a, b));
    return s == 0.0f && c == 0.0f ? 0.5f * kPi : std::atan2(s, c);
}

// Smith Lambda for GGX at a direction of polar cosine z.
float smithLambda(float z, float alpha) {
    const float z2 = std::max(z * z, 1e-12f);
    const float tan2 = std::max(1.0f - z2, 0.0f) / z2;
    return 0.5f * (-1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
}

// Heitz 2018, listing 1: a microfacet normal distributed as GGX's visible normals seen from `view`.
Vec3 sampleVisibleNormal(Vec3 view, float alpha, Vec2 u) {
    const Vec3 vh = normalize(Vec3{alpha * view.x, alpha * view.y, view.z});
    const float lensq = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = lensq > 0.0f ? Vec3{-vh.y, vh.x, 0.0f} / std::sqrt(lensq) : Vec3{1.0f, 0.0f, 0.0f};
    const Vec3 t2 = cross(vh, t1);
    const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
    const float p1 = r * std::cos(phi);
    float p2 = r * std::sin(phi);
    const float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
    const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2));
    return normalize(Vec3{alpha * nh.x, alpha * nh.y, std::max(0.0f, nh.z)});
}

float gridStep(float range) { return range / float(kN - 1); }

// Fractional grid coordinate g in [0, kN - 1], split into a cell index and a weight. max(0, g) comes first
// because it maps NaN to 0: std::clamp would hand NaN on to int(), which is undefined for it.
void splitCoordinate(float g, int& i, float& f) {
    g = std::min(std::max(0.0f, g), float(kN - 1));
    i = std::min(int(g), kN - 2);
    f = g - float(i);
}

// Fractional grid coordinate of v in [0, range].
void gridCoordinate(float v, float range, int& i, float& f) { splitCoordinate(v / gridStep(range), i, f); }

// The 4-D table's beta axis follows the bent normal in the plane of n and w_r, so that b = n is node
// kNormalNode at every theta_o: nodes 0..kNormalNode tilt b from w_r (beta = 0) to n (beta = theta_o) in equal
// steps, the nodes above tilt it on past n in steps of (pi/2) / (kN - 1 - kNormalNode), the last on the horizon
// (beta = theta_o + pi/2; beyond it b would be below the surface). An axis uniform in beta over [0, pi] put b = n
// between two nodes, and at grazing views S falls from 1 to about 0 within one such step past b = n (the
// hemisphere about a b tilted away from w_r cuts off the lobe at the horizon), so an unoccluded pixel's S was
// interpolated across that fall: 0.53 at theta_o = 89.9 degrees, roughness 0.
constexpr int kNormalNode = 15;
constexpr float kPastNormalStep = kHalfPi / float(kN - 1 - kNormalNode);

float betaCoordinate(float beta, float thetaO) {
    if (beta > thetaO) return float(kNormalNode) + (beta - thetaO) / kPastNormalStep;
    return thetaO > 0.0f ? float(kNormalNode) * beta / thetaO : float(kNormalNode);
}

// Solid angle of the intersection of caps of half-angles a1, a2 whose axes are beta apart (Omega_i of eq. 19,
// App. B). Gauss-Bonnet on the lens gives 2 (pi - gamma - cos a1 phi1 - cos a2 phi2) (the textbook form,
// Mazonka 2012), with phi_i the lens's half-arc about axis i and gamma the angle at a corner of the lens of the
// triangle (axis 1, axis 2, corner); that sum cancels to the lens's size from terms of order 1, and its acos
// lose half the digits near +-1, so a cap of a few milliradians came out 0 in float. The same sum regrouped is
// the two cap sectors less the kite of the two triangles: 2 (phi1 (1 - cos a1) + phi2 (1 - cos a2) - E), E the
// triangle's spherical excess; here 1 - cos a = 2 sin^2(a / 2), the angles come from the half-angle formulas
// and E from L'Huilier's theorem, all of which take the triangle's sides, not cosines, so the terms cancel only
// down to the lens's size relative to the smaller cap. In double, as the reference the GPU's float is held to.
double capIntersection(double a1, double a2, double beta) {
    if (beta >= a1 + a2) return 0.0;  // disjoint
    const double s1 = std::sin(0.5 * a1), s2 = std::sin(0.5 * a2);
    const double cap1 = 4.0 * kPiD * s1 * s1, cap2 = 4.0 * kPiD * s2 * s2;
    if (beta <= std::fabs(a1 - a2)) return std::min(cap1, cap2);  // one inside the other
    if (beta >= 2.0 * kPiD - a1 - a2) return cap1 + cap2 - 4.0 * kPiD;  // together they cover the sphere
    // The half-perimeter and its differences from the sides, each from the sides themselves (s - a1 would round
    // to 0 or below where beta is within an ulp of a1 - a2), all in [0, pi).
    const double s = 0.5 * (a1 + a2 + beta), sb = std::max(0.0, 0.5 * (a1 + a2 - beta)),
                 sa1 = std::max(0.0, 0.5 * (a2 + beta - a1)), sa2 = std::max(0.0, 0.5 * (a1 + beta - a2));
    const double sinS = std::sin(s), sinB = std::sin(sb), sin1 = std::sin(sa1), sin2 = std::sin(sa2);
    const double phi1 = 2.0 * std::atan2(std::sqrt(sinB * sin1), std::sqrt(sinS * sin2));
    const double phi2 = 2.0 * std::atan2(std::sqrt(sinB * sin2), std::sqrt(sinS * sin1));
    const double excess =
        4.0 * std::atan(std::sqrt(std::tan(0.5 * s) * std::tan(0.5 * sb) * std::tan(0.5 * sa1) * std::tan(0.5 * sa2)));
    return std::max(0.0, 2.0 * (phi1 * 2.0 * s1 * s1 + phi2 * 2.0 * s2 * s2 - excess));
}

} // namespace

float visibilityConeCos(float ao) { return std::sqrt(std::clamp(1.0f - ao, 0.0f, 1.0f)); }

float visibilityConeAngle(float ao) {
    // atan2 of sin and cos (sin^2 = A), not acos(cos): near A = 0 the cosine rounds to 1 within 6e-8, which
    // acos turns into 3.5e-4 rad, and a mirror-like GTSO changes by 16 per radian there.
    return std::atan2(std::sqrt(std::clamp(ao, 0.0f, 1.0f)), visibilityConeCos(ao));
}

float specularConeCos(float roughness) { return std::exp(-2.30259f * roughness * roughness); }

float capIntersectionSolidAngle(float a1, float a2, float beta) {
    return float(capIntersection(double(a1), double(a2), double(beta)));
}

float specularOcclusionCone(float alphaV, float beta, float roughness) {
    if (std::isnan(alphaV) || std::isnan(beta) || std::isnan(roughness)) return std::numeric_limits<float>::quiet_NaN();
    // eq. 26 as 1 - cos(alpha_s) = -expm1(-2.30259 r^2): 1 - exp(-x) in float is off by up to 6e-8 / x, 3% at
    // r = 0.001.
    const double oneMinusCos = -std::expm1(-2.30259 * double(roughness) * double(roughness));
    // A mirror: the reflection ray's visibility. Strictly inside the cone, as the limit r -> 0 has it: with
    // AO = 0 (alpha_v = 0) the cone is empty and S must be 0 even for b = w_r.
    if (!(oneMinusCos > 0.0)) return beta < alphaV ? 1.0f : 0.0f;
    const double alphaS = 2.0 * std::asin(std::sqrt(0.5 * oneMinusCos));
    const double specular = 2.0 * kPiD * oneMinusCos;  // Omega_s of eq. 19
    return float(std::clamp(capIntersection(double(alphaV), alphaS, double(beta)) / specular, 0.0, 1.0));
}

float SpecularOcclusionTable::alphaVAt(int i) { return float(i) * gridStep(kHalfPi); }
float SpecularOcclusionTable::betaAt(int j, float thetaO) {
    if (j <= kNormalNode) return thetaO * float(j) / float(kNormalNode);
    return thetaO + float(j - kNormalNode) * kPastNormalStep;
}
float SpecularOcclusionTable::roughnessAt(int k) { return float(k) * gridStep(1.0f); }
float SpecularOcclusionTable::thetaOAt(int l) { return float(l) * gridStep(kHalfPi); }

SpecularOcclusionTable::SpecularOcclusionTable(bool fourD) : fourD_(fourD) {
    const int betas = fourD ? kN : 1;
    values_.assign(std::size_t(kN) * std::size_t(betas) * std::size_t(kN) * std::size_t(kN), 0.0f);
    const float alphaStep = gridStep(kHalfPi);
    parallelFor(std::size_t(kN * kN), [&](std::size_t begin, std::size_t end) {
        std::vector<Vec3> directions(kSamples);
        std::vector<float> weights(kSamples);
        for (std::size_t cell = begin; cell < end; ++cell) {
            const int k = int(cell) % kN, l = int(cell) / kN;
            const float alpha = std::max(roughnessAt(k) * roughnessAt(k), 1e-3f);
            // Exactly grazing views have no reflection; stop just short of them.
            const float thetaO = std::min(thetaOAt(l), kHalfPi - 1e-3f);
            const Vec3 view{-std::sin(thetaO), 0.0f, std::cos(thetaO)};
            const float lambdaO = smithLambda(view.z, alpha);
            const OwenSobol2D sobol{std::uint32_t(cell)};
            float total = 0.0f;
            for (int s = 0; s < kSamples; ++s) {
                const Vec3 m = sampleVisibleNormal(view, alpha, sobol(std::uint32_t(s)));
                const Vec3 wi = m * (2.0f * dot(view, m)) - view;
                directions[std::size_t(s)] = wi;
                // F = 1: the estimator of Integral f_r cos is G2 / G1(w_o) per sample.
                weights[std::size_t(s)] =
                    wi.z > 0.0f ? (1.0f + lambdaO) / (1.0f + lambdaO + smithLambda(wi.z, alpha)) : 0.0f;
                total += weights[std::size_t(s)];
            }
            for (int j = 0; j < betas; ++j) {
                // Bent normal in the plane of n and w_r, beta from w_r towards n (b = n in the 3-D table).
                const float bAngle = fourD ? thetaO - betaAt(j, thetaO) : 0.0f;
                const Vec3 b{std::sin(bAngle), 0.0f, std::cos(bAngle)};
                std::array<float, kN> bins{};
                for (int s = 0; s < kSamples; ++s) {
                    if (weights[std::size_t(s)] <= 0.0f) continue;
                    // 2 asin(|b - w| / 2) keeps its precision near 0, where acos of a dot product does not.
                    const float psi =
                        2.0f * std::asin(std::min(1.0f, 0.5f * length(b - directions[std::size_t(s)])));
                    const int first = int(std::ceil(psi / alphaStep));  // the first alpha_v whose cone holds it
                    if (first < kN) bins[std::size_t(first)] += weights[std::size_t(s)];
                }
                float running = 0.0f;
                for (int i = 0; i < kN; ++i) {
                    running += bins[std::size_t(i)];
                    values_[((std::size_t(l) * kN + std::size_t(k)) * std::size_t(betas) + std::size_t(j)) * kN +
                            std::size_t(i)] = total > 0.0f ? std::min(running / total, 1.0f) : 1.0f;
                }
            }
        }
    });
}

const SpecularOcclusionTable& SpecularOcclusionTable::fourD() {
    static const SpecularOcclusionTable table(true);
    return table;
}

const SpecularOcclusionTable& SpecularOcclusionTable::threeD() {
    static const SpecularOcclusionTable table(false);
    return table;
}

float SpecularOcclusionTable::node(int i, int j, int k, int l) const {
    const int betas = fourD_ ? kN : 1;
    if (!fourD_) j = 0;
    return values_[((std::size_t(l) * kN + std::size_t(k)) * std::size_t(betas) + std::size_t(j)) * kN + std::size_t(i)];
}

float SpecularOcclusionTable::lookup(float alphaV, float beta, float roughness, float thetaO) const {
    if (std::isnan(alphaV) || std::isnan(beta) || std::isnan(roughness) || std::isnan(thetaO))
        return std::numeric_limits<float>::quiet_NaN();
    int i, j = 0, k, l;
    float fi, fj = 0.0f, fk, fl;
    gridCoordinate(alphaV, kHalfPi, i, fi);
    if (fourD_) splitCoordinate(betaCoordinate(beta, thetaO), j, fj);
    gridCoordinate(roughness, 1.0f, k, fk);
    gridCoordinate(thetaO, kHalfPi, l, fl);
    float result = 0.0f;
    for (int dl = 0; dl < 2; ++dl)
        for (int dk = 0; dk < 2; ++dk)
            for (int dj = 0; dj < (fourD_ ? 2 : 1); ++dj)
                for (int di = 0; di < 2; ++di) {
                    float w = (di ? fi : 1.0f - fi) * (dk ? fk : 1.0f - fk) * (dl ? fl : 1.0f - fl);
                    if (fourD_) w *= dj ? fj : 1.0f - fj;
                    if (w > 0.0f) result += w * node(i + di, j + dj, k + dk, l + dl);
                }
    // The weights' float sum may exceed 1 by an ulp: 13 of 14400 pixels of a render read 1.0000001.
    return std::min(result, 1.0f);
}

float specularOcclusion(SpecularOcclusionMode mode, float ao, Vec3 bentNormal, Vec3 normal, Vec3 view,
                        float roughness) {
    const float alphaV = visibilityConeAngle(ao);
    const float nv = std::clamp(dot(normal, view), 0.0f, 1.0f);
    const Vec3 reflected = normal * (2.0f * nv) - view;
    const float thetaO = angleBetween(normal, view, nv);
    const float beta = angleBetween(bentNormal, reflected, dot(bentNormal, reflected));
    switch (mode) {
    case SpecularOcclusionMode::Lut4: return SpecularOcclusionTable::fourD().lookup(alphaV, beta, roughness, thetaO);
    // §6: the 3-D table takes the normal to be the bent normal, so theta_o = beta (the cone's angle to w_r).
    case SpecularOcclusionMode::Lut3: return SpecularOcclusionTable::threeD().lookup(alphaV, beta, roughness, beta);
    case SpecularOcclusionMode::Cone: return specularOcclusionCone(alphaV, beta, roughness);
    }
    return 1.0f;
}

namespace {

bool finiteAt(const Image& image, int x, int y) {
    bool finite = true;
    for (int c = 0; c < image.channels; ++c) finite &= std::isfinite(image.at(x, y, c));
    return finite;
}

} // namespace

void checkSpecularOcclusionInputs(const GBuffer& g, const Image& ao, const Image& bentNormal, float roughness) {
    if (!(roughness >= 0.0f && roughness <= 1.0f)) fail("roughness", "must be in [0, 1]");
    if (ao.width != g.width() || ao.height != g.height() || ao.channels != 1 || bentNormal.width != g.width() ||
        bentNormal.height != g.height() || bentNormal.channels != 3)
        fail("specular occlusion", "AO and bent-normal images must match the " + std::to_string(g.width()) + "x" +
                                       std::to_string(g.height()) + " G-buffer (1 and 3 channels)");
    // Every pixel's depth and normal is read at the camera's size: smaller planes were read past their end.
    g.validateDepthNormalShape("specular occlusion");
    g.validatePixels("specular occlusion");
    // A NaN AO or bent normal would make a NaN table coordinate; name it as a NaN depth is named. Sky pixels
    // are not read, so what they hold does not matter. The scan is branch-free; only a bad image takes the
    // loop that names the first bad pixel.
    std::atomic<bool> bad{false};
    parallelFor(std::size_t(g.height()), [&](std::size_t begin, std::size_t end) {
        bool anyBad = false;
        for (int y = int(begin); y < int(end); ++y)
            for (int x = 0; x < g.width(); ++x)
                anyBad |= !g.isSky(x, y) & !(finiteAt(ao, x, y) & finiteAt(bentNormal, x, y));
        if (anyBad) bad.store(true, std::memory_order_relaxed);
    }, 16);
    if (!bad.load()) return;
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            if (g.isSky(x, y)) continue;
            const std::string pixel = " at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
            if (!finiteAt(ao, x, y)) fail("specular occlusion", "AO" + pixel + " is " + numberText(ao.at(x, y)));
            if (!finiteAt(bentNormal, x, y)) fail("specular occlusion", "bent normal" + pixel + " is not finite");
        }
}

Image computeSpecularOcclusion(const GBuffer& g, const Image& ao, const Image& bentNormal, SpecularOcclusionMode mode,
                               float roughness) {
    checkSpecularOcclusionInputs(g, ao, bentNormal, roughness);
    // Build the table before the parallel loop, so its own parallel construction is not nested.
    if (mode == SpecularOcclusionMode::Lut4) SpecularOcclusionTable::fourD();
    if (mode == SpecularOcclusionMode::Lut3) SpecularOcclusionTable::threeD();
    Image out(g.width(), g.height(), 1, 1.0f);
    parallelFor(std::size_t(g.height()), [&](std::size_t begin, std::size_t end) {
        for (std::size_t yy = begin; yy < end; ++yy) {
            const int y = int(yy);
            for (int x = 0; x < g.width(); ++x) {
                if (g.isSky(x, y)) continue;
                const Vec3 b{bentNormal.at(x, y, 0), bentNormal.at(x, y, 1), bentNormal.at(x, y, 2)};
                const Vec3 view = normalize(-g.viewPosition(x, y));
                out.at(x, y) = specularOcclusion(mode, ao.at(x, y), b, g.viewNormal(x, y), view, roughness);
            }
        }
    });
    return out;
}

} // namespace obscura::ssao
