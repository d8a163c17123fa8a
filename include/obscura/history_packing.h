// The packed history of spatio-temporal GTAO (GtaoTemporalSettings::packedHistory): 32-bit words that the
// C++ reference (src/ssao/gtao_temporal.cpp) and the compute pass (gtao_temporal.comp) encode and decode with
// this one source, compiled as both C++ and GLSL, so both quantize to the same bits.
//
// - visibility and history length in one word: visibility as unorm16 (steps of 1/65535), the length in
//   steps of 1/32 frame (whole frames exact, up to 2047);
// - a unit vector (world normal, world bent normal) in one word: octahedral (Cigolle et al. 2014, "A Survey
//   of Efficient Representations for Independent Unit Vectors"), two snorm16, within 6.5e-5 rad of the
//   vector (the worst of 4 million random directions; tests/ssao/history_packing_test.cpp bounds it by 7.0e-5).
// Each is a history plane of one word where the float layout takes 2 or 3.
//
// Only exactly rounded operations are used (+, -, * and / of floats, floor, comparisons, integer bit
// operations): the products that feed a rounding are `precise` in GLSL so that no compiler fuses them, and
// the scale factors are powers of two or given as bit patterns. A GPU whose division is not exactly rounded
// can still differ in the last bit of a vector code now and then.
#ifndef OBSCURA_HISTORY_PACKING_H
#define OBSCURA_HISTORY_PACKING_H

#ifdef __cplusplus
#include "obscura/math.h"

#include <bit>
#include <cmath>
#include <cstdint>
namespace obscura::ssao {
#define OBSCURA_PACK_UINT std::uint32_t
#define OBSCURA_PACK_VEC3 Vec3
#define OBSCURA_PACK_PRECISE
#define OBSCURA_PACK_INLINE inline
inline float packFloor(float x) { return std::floor(x); }
inline float packAbs(float x) { return std::fabs(x); }
inline float packFromBits(std::uint32_t bits) { return std::bit_cast<float>(bits); }
inline Vec3 packNormalize(Vec3 v) { return normalize(v); }
#else
#define OBSCURA_PACK_UINT uint
#define OBSCURA_PACK_VEC3 vec3
#define OBSCURA_PACK_PRECISE precise
#define OBSCURA_PACK_INLINE
#define packFloor floor
#define packAbs abs
#define packFromBits uintBitsToFloat
#define packNormalize normalize3  // the shader's normalize, written out as the C++ one computes it
#endif

// 1 / 65535 and 1 / 32767 rounded to the nearest float, as bit patterns, so that no compiler's constant
// folding can differ.
OBSCURA_PACK_INLINE float packInverse65535() { return packFromBits(0x37800080u); }
OBSCURA_PACK_INLINE float packInverse32767() { return packFromBits(0x38000100u); }

// x in [0, 1] -> 0..65535, to nearest (x is clamped; a NaN packs as 0, not through an undefined conversion).
OBSCURA_PACK_INLINE OBSCURA_PACK_UINT packUnorm16(float x) {
    const float c = x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;
    OBSCURA_PACK_PRECISE const float scaled = c * 65535.0f + 0.5f;
    return OBSCURA_PACK_UINT(packFloor(scaled));
}
OBSCURA_PACK_INLINE float unpackUnorm16(OBSCURA_PACK_UINT q) { return float(q) * packInverse65535(); }

// x in [-1, 1] -> -32767..32767 to nearest (x is clamped; a NaN packs as -1), stored offset as 1..65535 so
// that the rounding sees no negative number; code 0 is unused.
OBSCURA_PACK_INLINE OBSCURA_PACK_UINT packSnorm16(float x) {
    const float c = x > -1.0f ? (x < 1.0f ? x : 1.0f) : -1.0f;
    OBSCURA_PACK_PRECISE const float scaled = c * 32767.0f + 32767.5f;  // 0.5..65534.5
    return OBSCURA_PACK_UINT(packFloor(scaled)) + 1u;
}
OBSCURA_PACK_INLINE float unpackSnorm16(OBSCURA_PACK_UINT q) { return (float(q) - 32768.0f) * packInverse32767(); }

// Visibility in [0, 1] and a history length in [0, 2047] frames in one word.
OBSCURA_PACK_INLINE OBSCURA_PACK_UINT packVisibilityLength(float visibility, float length) {
    OBSCURA_PACK_PRECISE const float scaled = length * 32.0f + 0.5f;
    const float frames = packFloor(scaled);
    return packUnorm16(visibility) | (OBSCURA_PACK_UINT(frames < 65535.0f ? frames : 65535.0f) << 16);
}
OBSCURA_PACK_INLINE float unpackVisibility(OBSCURA_PACK_UINT word) { return unpackUnorm16(word & 0xffffu); }
OBSCURA_PACK_INLINE float unpackLength(OBSCURA_PACK_UINT word) { return float(word >> 16) * 0.03125f; }

// The octahedral fold of the lower hemisphere: (x, y) -> ((1 - |y|) sign x, (1 - |x|) sign y), sign 0 = +1.
OBSCURA_PACK_INLINE float packFoldX(float x, float y) { return (1.0f - packAbs(y)) * (x >= 0.0f ? 1.0f : -1.0f); }
OBSCURA_PACK_INLINE float packFoldY(float x, float y) { return (1.0f - packAbs(x)) * (y >= 0.0f ? 1.0f : -1.0f); }

// A unit vector in one word; the zero vector (sky) packs as +z.
OBSCURA_PACK_INLINE OBSCURA_PACK_UINT packOctahedral(OBSCURA_PACK_VEC3 n) {
    const float l1 = packAbs(n.x) + packAbs(n.y) + packAbs(n.z);
    float x = 0.0f, y = 0.0f;
    if (l1 > 0.0f) {
        x = n.x / l1;
        y = n.y / l1;
    }
    if (n.z < 0.0f) {
        const float fx = packFoldX(x, y), fy = packFoldY(x, y);
        x = fx;
        y = fy;
    }
    return packSnorm16(x) | (packSnorm16(y) << 16);
}
OBSCURA_PACK_INLINE OBSCURA_PACK_VEC3 unpackOctahedral(OBSCURA_PACK_UINT word) {
    float x = unpackSnorm16(word & 0xffffu), y = unpackSnorm16(word >> 16);
    const float z = 1.0f - packAbs(x) - packAbs(y);
    if (z < 0.0f) {
        const float fx = packFoldX(x, y), fy = packFoldY(x, y);
        x = fx;
        y = fy;
    }
    return packNormalize(OBSCURA_PACK_VEC3(x, y, z));
}

#ifdef __cplusplus
} // namespace obscura::ssao
#endif
#undef OBSCURA_PACK_INLINE
#undef OBSCURA_PACK_PRECISE
#undef OBSCURA_PACK_VEC3
#undef OBSCURA_PACK_UINT

#endif
