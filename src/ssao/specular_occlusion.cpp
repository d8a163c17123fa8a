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
#include <cmath>

namespace obscura::ssao {

namespace {

constexpr int kN = kSpecularTableSize;
constexpr float kHalfPi = 0.5f * kPi;
// VNDF samples per (roughness, theta_o) cell; with the Sobol net the tables agree with an independent
// Monte Carlo integration to about 0.01 (tests/ssao/specular_occlusion_test.cpp).
constexpr int kSamples = 2048;

float clampCos(float c) { return std::clamp(c, -1.0f, 1.0f); }

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

// Fractional grid coordinate of v in [0, range], split into a cell index and a weight.
void gridCoordinate(float v, float range, int& i, float& f) {
    const float g = std::clamp(v / gridStep(range), 0.0f, float(kN - 1));
    i = std::min(int(g), kN - 2);
    f = g - float(i);
}

} // namespace

float visibilityConeCos(float ao) { return std::sqrt(std::clamp(1.0f - ao, 0.0f, 1.0f)); }

float specularConeCos(float roughness) { return std::exp(-2.30259f * roughness * roughness); }

float capIntersectionSolidAngle(float a1, float a2, float beta) {
    if (beta >= a1 + a2) return 0.0f;
    if (beta <= std::fabs(a1 - a2)) return 2.0f * kPi * (1.0f - std::cos(std::min(a1, a2)));
    const float c1 = std::cos(a1), c2 = std::cos(a2), cb = std::cos(beta);
    const float s1 = std::sin(a1), s2 = std::sin(a2), sb = std::sin(beta);
    const float g = std::acos(clampCos((cb - c1 * c2) / (s1 * s2)));
    const float b1 = std::acos(clampCos((c2 - cb * c1) / (sb * s1)));
    const float b2 = std::acos(clampCos((c1 - cb * c2) / (sb * s2)));
    return std::max(0.0f, 2.0f * (kPi - g - c1 * b1 - c2 * b2));
}

float specularOcclusionCone(float alphaV, float beta, float roughness) {
    const float alphaS = std::acos(specularConeCos(roughness));
    const float specular = 2.0f * kPi * (1.0f - std::cos(alphaS));
    if (!(specular > 0.0f)) return beta <= alphaV ? 1.0f : 0.0f;  // a mirror: the reflection ray's visibility
    return std::clamp(capIntersectionSolidAngle(alphaV, alphaS, beta) / specular, 0.0f, 1.0f);
}

float SpecularOcclusionTable::alphaVAt(int i) { return float(i) * gridStep(kHalfPi); }
float SpecularOcclusionTable::betaAt(int j) { return float(j) * gridStep(kPi); }
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
                const float bAngle = fourD ? thetaO - betaAt(j) : 0.0f;
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
    int i, j = 0, k, l;
    float fi, fj = 0.0f, fk, fl;
    gridCoordinate(alphaV, kHalfPi, i, fi);
    if (fourD_) gridCoordinate(beta, kPi, j, fj);
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
    return result;
}

float specularOcclusion(SpecularOcclusionMode mode, float ao, Vec3 bentNormal, Vec3 normal, Vec3 view,
                        float roughness) {
    const float alphaV = std::acos(visibilityConeCos(ao));
    const float nv = std::clamp(dot(normal, view), 0.0f, 1.0f);
    const Vec3 reflected = normal * (2.0f * nv) - view;
    const float thetaO = std::acos(nv);
    const float beta = std::acos(clampCos(dot(bentNormal, reflected)));
    switch (mode) {
    case SpecularOcclusionMode::Lut4: return SpecularOcclusionTable::fourD().lookup(alphaV, beta, roughness, thetaO);
    case SpecularOcclusionMode::Lut3: return SpecularOcclusionTable::threeD().lookup(alphaV, thetaO, roughness, thetaO);
    case SpecularOcclusionMode::Cone: return specularOcclusionCone(alphaV, beta, roughness);
    }
    return 1.0f;
}

Image computeSpecularOcclusion(const GBuffer& g, const Image& ao, const Image& bentNormal, SpecularOcclusionMode mode,
                               float roughness) {
    if (!(roughness >= 0.0f && roughness <= 1.0f)) fail("roughness", "must be in [0, 1]");
    if (ao.width != g.width() || ao.height != g.height() || ao.channels != 1 || bentNormal.width != g.width() ||
        bentNormal.height != g.height() || bentNormal.channels != 3)
        fail("specular occlusion", "AO and bent-normal images must match the " + std::to_string(g.width()) + "x" +
                                       std::to_string(g.height()) + " G-buffer (1 and 3 channels)");
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
