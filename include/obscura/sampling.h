// Seeded hashes, a low-discrepancy sequence, and hemisphere sampling.
//
// Everything is a pure function of its arguments, so any split of the work over threads or machines gives
// the same bits for the same seed.
#pragma once

#include "obscura/math.h"

#include <cstdint>
#include <vector>

namespace obscura {

// 32-bit integer hash with good avalanche (the "lowbias32" finaliser).
constexpr std::uint32_t hash32(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
constexpr std::uint32_t hashCombine(std::uint32_t seed, std::uint32_t value) {
    return hash32(seed ^ (value + 0x9e3779b9u + (seed << 6) + (seed >> 2)));
}
// Uniform float in [0, 1) from the top 24 bits.
constexpr float toUnitFloat(std::uint32_t x) { return float(x >> 8) * (1.0f / 16777216.0f); }

// Point `index` of the 2-D Sobol sequence (its first two dimensions, a (0,2)-sequence), Owen-scrambled
// by `seed` with the hash-based nested uniform scramble (Laine and Karras 2011; Burley 2020). Any prefix of
// 2^k points has one point in each of the 2^k elementary intervals of every shape, so N rays are
// stratified for any N, and each point is uniformly distributed, so estimates are unbiased.
class OwenSobol2D {
public:
    explicit OwenSobol2D(std::uint32_t seed)
        : seedX_(hashCombine(seed, 0x2545f491u)), seedY_(hashCombine(seed, 0x9e3779b9u)) {}

    Vec2 operator()(std::uint32_t index) const {
        // The scramble is reverse(LK(reverse(v))); for x = reverse(index) the inner reversal cancels, and
        // for y the second dimension is built from bit-reversed direction numbers directly.
        std::uint32_t x = reverseBits(laineKarras(index, seedX_));
        std::uint32_t y = reverseBits(laineKarras(sobolDim1Reversed(index), seedY_));
        return {toUnitFloat(x), toUnitFloat(y)};
    }

    static constexpr std::uint32_t reverseBits(std::uint32_t x) {
        x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
        x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
        x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
        x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
        return (x >> 16) | (x << 16);
    }

private:
    // A hash in which each bit depends only on the bits below it: applied to bit-reversed values it is a
    // nested uniform scramble.
    static constexpr std::uint32_t laineKarras(std::uint32_t x, std::uint32_t seed) {
        x += seed;
        x ^= x * 0x6c50b47cu;
        x ^= x * 0xb82f1e52u;
        x ^= x * 0xc7afe638u;
        x ^= x * 0x8d22f6e6u;
        return x;
    }
    // Second Sobol dimension with bit-reversed direction numbers: v_0 = 1, v_k = v_{k-1} ^ (v_{k-1} << 1).
    static constexpr std::uint32_t sobolDim1Reversed(std::uint32_t index) {
        std::uint32_t result = 0, v = 1u;
        for (; index; index >>= 1, v ^= v << 1)
            if (index & 1u) result ^= v;
        return result;
    }

    std::uint32_t seedX_, seedY_;
};

inline Vec2 sobol2D(std::uint32_t index, std::uint32_t seed) { return OwenSobol2D(seed)(index); }

// Cosine-weighted direction about +Z from a point in [0,1)^2 through the concentric disk map (Shirley and
// Chiu 1997), which keeps the stratification of the input. pdf = cos(theta) / pi.
Vec3 cosineHemisphere(Vec2 u);
// Uniform direction about +Z, pdf = 1 / (2 pi).
Vec3 uniformHemisphere(Vec2 u);

// N cosine-weighted directions about +Z for many points at little cost per ray. The base set is the first N
// Sobol points in the polar parameters (s = sin^2(theta), phi / 2pi), an equal-area map of the square onto
// the cosine-weighted hemisphere; each point draws one random toroidal shift (Cranley and Patterson 1976)
// of both parameters. Every ray is then uniformly distributed in the square, so estimates are unbiased,
// and the N rays of a point keep the net's stratification up to the shift.
class CosineHemisphereSet {
public:
    explicit CosineHemisphereSet(int count);
    int size() const { return int(sin2_.size()); }

    struct Shift {
        float sin2;        // added to sin^2(theta), modulo 1
        float cosPhi, sinPhi;  // rotation of the azimuth
    };
    static Shift shift(std::uint32_t seed);

    // Direction i about +Z under `shift`. Hot path: no checks.
    Vec3 direction(int i, const Shift& sh) const {
        float s2 = sin2_[std::size_t(i)] + sh.sin2;
        s2 = s2 >= 1.0f ? s2 - 1.0f : s2;
        float r = std::sqrt(s2);
        float c = cosPhi_[std::size_t(i)] * sh.cosPhi - sinPhi_[std::size_t(i)] * sh.sinPhi;
        float s = sinPhi_[std::size_t(i)] * sh.cosPhi + cosPhi_[std::size_t(i)] * sh.sinPhi;
        return {r * c, r * s, std::sqrt(1.0f - s2)};
    }

private:
    std::vector<float> sin2_, cosPhi_, sinPhi_;
};

} // namespace obscura
