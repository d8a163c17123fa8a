// Nine-coefficient spherical-harmonic irradiance, after Ramamoorthi and Hanrahan 2001, "An Efficient
// Representation for Irradiance Environment Maps" (SIGGRAPH): project radiance onto l <= 2, scale band l
// by the clamped-cosine factor A_l, evaluate.
//
// The real basis is the standard one written in the unit direction (x, y, z) (z is its polar axis even
// though Obscura's world up is +Y); projection and evaluation both use basis() below, so the choice of
// axis cannot make them disagree.
#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace obscura::render {

namespace {

using std::numbers::pi;

// Exact normalisations; they round to the familiar 0.282095, 0.488603, 1.092548, 0.315392, 0.546274.
const double kY00 = 0.5 * std::sqrt(1.0 / pi);
const double kY1 = std::sqrt(3.0 / (4.0 * pi));
const double kY2a = 0.5 * std::sqrt(15.0 / pi); // (2,-2) xy, (2,-1) yz, (2,1) xz
const double kY20 = 0.25 * std::sqrt(5.0 / pi);  // (2,0) (3z^2 - 1)
const double kY22 = 0.25 * std::sqrt(15.0 / pi); // (2,2) (x^2 - y^2)

// Y_lm(d) in SH9's order.
std::array<double, 9> basis(double x, double y, double z) {
    return {kY00,
            kY1 * y, kY1 * z, kY1 * x,
            kY2a * x * y, kY2a * y * z, kY20 * (3.0 * z * z - 1.0), kY2a * x * z, kY22 * (x * x - y * y)};
}

// Integrals over one texel's patch of sphere of the monomials the basis is made of. Sampling the basis at
// the texel centre leaves an O(texel^2) bias (0.05% of the irradiance at 64x32); integrating exactly
// makes the projection exact for the piecewise-constant image, so a constant map gives pi L to
// rounding. With d = (sin t sin p, cos t, -sin t cos p) and dOmega = sin t dt dp every monomial splits
// into a polar integral times an azimuthal one.
struct Polar { // integrals over [t0, t1] of f(t) sin t dt
    double one, c, s, cc, sc, ss; // f = 1, cos, sin, cos^2, sin cos, sin^2
};
struct Azimuth { // integrals over [p0, p1] of g(p) dp
    double one, s, c, ss, cc, sc;
};

Polar polar(double t0, double t1) {
    double c0 = std::cos(t0), c1 = std::cos(t1), s0 = std::sin(t0), s1 = std::sin(t1);
    Polar r{};
    r.one = c0 - c1;
    r.c = 0.5 * (s1 * s1 - s0 * s0);
    r.s = 0.5 * (t1 - t0) - 0.25 * (std::sin(2.0 * t1) - std::sin(2.0 * t0));
    r.cc = (c0 * c0 * c0 - c1 * c1 * c1) / 3.0;
    r.sc = (s1 * s1 * s1 - s0 * s0 * s0) / 3.0;
    r.ss = r.one - r.cc;
    return r;
}

Azimuth azimuth(double p0, double p1) {
    double c0 = std::cos(p0), c1 = std::cos(p1), s0 = std::sin(p0), s1 = std::sin(p1);
    double halfSin2 = 0.25 * (std::sin(2.0 * p1) - std::sin(2.0 * p0));
    Azimuth r{};
    r.one = p1 - p0;
    r.s = c0 - c1;
    r.c = s1 - s0;
    r.ss = 0.5 * r.one - halfSin2;
    r.cc = 0.5 * r.one + halfSin2;
    r.sc = 0.5 * (s1 * s1 - s0 * s0);
    return r;
}

// Integral of each basis function over the texel.
std::array<double, 9> texelWeights(const Polar& t, const Azimuth& p) {
    double one = t.one * p.one;
    double x = t.s * p.s, y = t.c * p.one, z = -t.s * p.c;
    double xy = t.sc * p.s, yz = -t.sc * p.c, xz = -t.ss * p.sc;
    double xx = t.ss * p.ss, yy = t.cc * p.one, zz = t.ss * p.cc;
    return {kY00 * one,
            kY1 * y, kY1 * z, kY1 * x,
            kY2a * xy, kY2a * yz, kY20 * (3.0 * zz - one), kY2a * xz, kY22 * (xx - yy)};
}

} // namespace

SH9 projectEnvironment(const Image& equirect) {
    if (equirect.empty()) fail("environment", "image is empty");
    if (equirect.channels < 3)
        fail("environment", "needs at least 3 channels (RGB), got " + std::to_string(equirect.channels));
    const int w = equirect.width, h = equirect.height, ch = equirect.channels;

    std::vector<Azimuth> columns(static_cast<std::size_t>(w));
    for (int i = 0; i < w; ++i)
        columns[std::size_t(i)] = azimuth(2.0 * pi * (double(i) / w - 0.5), 2.0 * pi * (double(i + 1) / w - 0.5));

    // One partial sum per row, added in row order afterwards, so any thread split gives the same bits.
    std::vector<std::array<double, 27>> rows(static_cast<std::size_t>(h));
    // The first texel of each row that is not a radiance (non-finite or negative), -1 where all are. A negative
    // texel would subtract light in every direction its lobes reach; an HDR edited by hand or a difference image
    // can hold one, and the composite would then show it as darkening nowhere near where it is.
    std::vector<int> rowBad(std::size_t(h), -1);
    parallelFor(std::size_t(h), [&](std::size_t begin, std::size_t end) {
        for (std::size_t j = begin; j < end; ++j) {
            Polar t = polar(pi * double(j) / h, pi * double(j + 1) / h);
            std::array<double, 27> sum{};
            const float* texel = &equirect.pixels[j * std::size_t(w) * std::size_t(ch)];
            for (int i = 0; i < w; ++i, texel += ch) {
                const bool radiance = texel[0] >= 0 && texel[1] >= 0 && texel[2] >= 0 && std::isfinite(texel[0]) &&
                                      std::isfinite(texel[1]) && std::isfinite(texel[2]);
                if (!radiance && rowBad[j] < 0) rowBad[j] = i;
                std::array<double, 9> wgt = texelWeights(t, columns[std::size_t(i)]);
                for (int k = 0; k < 9; ++k)
                    for (int c = 0; c < 3; ++c) sum[std::size_t(k * 3 + c)] += wgt[std::size_t(k)] * double(texel[c]);
            }
            rows[j] = sum;
        }
    });

    std::array<double, 27> total{};
    for (int j = 0; j < h; ++j) {
        if (const int i = rowBad[std::size_t(j)]; i >= 0) {
            const float* texel = &equirect.pixels[(std::size_t(j) * std::size_t(w) + std::size_t(i)) * std::size_t(ch)];
            fail("environment", "radiance at pixel (" + std::to_string(i) + ", " + std::to_string(j) + ") is (" +
                                    numberText(texel[0]) + ", " + numberText(texel[1]) + ", " + numberText(texel[2]) +
                                    "): must be finite and non-negative");
        }
        for (std::size_t k = 0; k < 27; ++k) total[k] += rows[std::size_t(j)][k];
    }
    // Finite texels can still sum past a float (a constant 3e38 gave L00 = inf, and an inf frame): irradiance()
    // is at most about 6.2 max|L_lm| (the sum of A_l max|Y_lm|), so a margin of 8 keeps it finite.
    for (std::size_t k = 0; k < 27; ++k)
        if (!(std::fabs(total[k]) < double(std::numeric_limits<float>::max()) / 8.0))
            fail("environment", "radiance is too large: its irradiance would overflow a float (SH coefficient " +
                                    numberText(total[k]) + ")");
    SH9 sh;
    for (int k = 0; k < 9; ++k)
        for (int c = 0; c < 3; ++c) sh.coefficients[std::size_t(k)][c] = float(total[std::size_t(k * 3 + c)]);
    return sh;
}

namespace {
// R&H's A_l: the clamped cosine's zonal coefficient times sqrt(4pi / (2l + 1)) (Funk-Hecke).
constexpr double kA[9] = {pi,
                          2.0 * pi / 3.0, 2.0 * pi / 3.0, 2.0 * pi / 3.0,
                          pi / 4.0, pi / 4.0, pi / 4.0, pi / 4.0, pi / 4.0};
} // namespace

std::array<double, 9> irradianceScales() {
    // basis() of the monomials' coefficient 1: its normalisations.
    const std::array<double, 9> n = {kY00, kY1, kY1, kY1, kY2a, kY2a, kY20, kY2a, kY22};
    std::array<double, 9> s{};
    for (std::size_t k = 0; k < 9; ++k) s[k] = kA[k] * n[k];
    return s;
}

Vec3 irradiance(const SH9& sh, Vec3 n) {
    const double* a = kA;
    std::array<double, 9> y = basis(double(n.x), double(n.y), double(n.z));
    double e[3] = {0, 0, 0};
    for (std::size_t k = 0; k < 9; ++k)
        for (int c = 0; c < 3; ++c) e[c] += a[k] * double(sh.coefficients[k][c]) * y[k];
    // Nine coefficients ring: a bright, small source can push the opposite side below zero.
    return {float(std::max(e[0], 0.0)), float(std::max(e[1], 0.0)), float(std::max(e[2], 0.0))};
}

} // namespace obscura::render
