// Hemisphere maps (the Owen-scrambled Sobol points are inline in sampling.h).
#include "obscura/sampling.h"

#include <cmath>

namespace obscura {

namespace {
// sin and cos on [-pi/4, pi/4] by Taylor polynomials to x^9 / x^8: error below 2e-9, far under float's
// resolution, and about a fifth of the cost of the libm calls in the per-ray loop.
inline void sinCosQuarter(float x, float& s, float& c) {
    float x2 = x * x;
    s = x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
    c = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320))));
}
} // namespace

Vec3 cosineHemisphere(Vec2 u) {
    // Concentric map of the square onto the disk, then lift to the hemisphere (Malley's method).
    float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
    float x = 0.0f, y = 0.0f;
    if (a != 0.0f || b != 0.0f) {
        float s, c;
        if (std::fabs(a) > std::fabs(b)) {
            sinCosQuarter((kPi / 4.0f) * (b / a), s, c);  // phi = (pi/4)(b/a)
            x = a * c;
            y = a * s;
        } else {
            sinCosQuarter((kPi / 4.0f) * (a / b), s, c);  // phi = pi/2 - (pi/4)(a/b)
            x = b * s;
            y = b * c;
        }
    }
    float z = std::sqrt(std::fmax(0.0f, 1.0f - x * x - y * y));
    return {x, y, z};
}

CosineHemisphereSet::CosineHemisphereSet(int count) {
    for (int i = 0; i < count; ++i) {
        // Unscrambled Sobol: the per-point shift supplies the randomness.
        auto index = std::uint32_t(i);
        std::uint32_t y = 0, v = 1u << 31;
        for (std::uint32_t k = index; k; k >>= 1, v ^= v >> 1)
            if (k & 1u) y ^= v;
        float phi = 2.0f * kPi * toUnitFloat(y);
        sin2_.push_back(toUnitFloat(OwenSobol2D::reverseBits(index)));
        cosPhi_.push_back(std::cos(phi));
        sinPhi_.push_back(std::sin(phi));
    }
}

CosineHemisphereSet::Shift CosineHemisphereSet::shift(std::uint32_t seed) {
    float phi = 2.0f * kPi * toUnitFloat(hashCombine(seed, 0x68e31da4u));
    return {toUnitFloat(hashCombine(seed, 0xb5297a4du)), std::cos(phi), std::sin(phi)};
}

Vec3 uniformHemisphere(Vec2 u) {
    float z = u.x;
    float r = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
    float phi = 2.0f * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

} // namespace obscura
