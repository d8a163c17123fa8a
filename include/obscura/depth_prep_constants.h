// Constants of the depth and normal preparation (obscura/depth_prep.h), shared by the C++ reference
// (src/ssao/depth_prep.cpp) and the compute passes (src/gpu/shaders/prepare_depth.comp,
// normals_from_depth.comp), which take them as push constants; the same file is #included by GLSL. Filled in
// by one pure function, obscura::ssao::depthPrepConstants() in obscura/depth_prep.h.
//
// Every depth convention's linear depth is d = a / (b + c z) in the device depth z:
//   standard [0, 1] (near 0, far 1):        d = n f / (f - (f - n) z)   a = n f, b = f, c = n - f
//   reversed (near 1, far 0):               d = n f / (n + (f - n) z)   a = n f, b = n, c = f - n
//   reversed, infinite far plane:           d = n / z                   a = n,   b = 0, c = 1
// and the cleared value (sky) is z = skyZ: 1 for standard, 0 for the reversed ones.
#ifndef OBSCURA_DEPTH_PREP_CONSTANTS_H
#define OBSCURA_DEPTH_PREP_CONSTANTS_H

#ifdef __cplusplus
#include <cmath>
#include <cstddef>
namespace obscura::ssao {
#define OBSCURA_CONST inline constexpr
#define OBSCURA_FN inline
#define OBSCURA_INF INFINITY
#else
#define OBSCURA_CONST const
#define OBSCURA_FN
#define OBSCURA_INF uintBitsToFloat(0x7f800000u)
#endif

OBSCURA_CONST int kDepthStandard = 0;          // DepthConvention::Standard
OBSCURA_CONST int kDepthReversed = 1;          // DepthConvention::Reversed
OBSCURA_CONST int kDepthReversedInfinite = 2;  // DepthConvention::ReversedInfinite

OBSCURA_CONST int kNormalsView = 0;       // NormalSource::View: the input holds view-space normals
OBSCURA_CONST int kNormalsWorld = 1;      // NormalSource::World: world-space normals, rotated by viewFromWorld
OBSCURA_CONST int kNormalsFromDepth = 2;  // NormalSource::FromDepth: no input, rebuilt from the linear depth

OBSCURA_CONST int kDepthPrepWorkgroupX = 8;
OBSCURA_CONST int kDepthPrepWorkgroupY = 8;

struct DepthPrepConstants {
    int width;        // px
    int height;       // px
    int normals;      // kNormalsView, kNormalsWorld or kNormalsFromDepth
    int unorm;        // 1: normals stored as n * 0.5 + 0.5 (e.g. an RGBA8 or RGB10A2 target), 0: signed

    float a;          // d = a / (b + c z), m
    float b;
    float c;
    float skyZ;       // the device depth of the cleared (sky) pixels

    int normalChannels;  // floats per pixel of the normal input: 3 or 4 (the 4th ignored)
    int pad0;
    int pad1;
    int pad2;

    float viewFromWorld0[4];  // rows of the rotation of world into view space (xyz; w unused)
    float viewFromWorld1[4];
    float viewFromWorld2[4];

    float mulX;       // Camera::viewFromPixelAffine, for the normals rebuilt from depth
    float addX;
    float mulY;
    float addY;
};

// Linear view depth (m) of device depth z: +inf for the sky value and for a depth at or behind the far
// plane; NaN for a z outside [0, 1] (the host reports it before the pass runs).
OBSCURA_FN float linearDepthFromDevice(float z, DepthPrepConstants k) {
    if (z == k.skyZ) return OBSCURA_INF;
    float q = k.b + k.c * z;
    return q > 0.0f ? k.a / q : OBSCURA_INF;
}

#ifdef __cplusplus
static_assert(sizeof(DepthPrepConstants) == 112, "DepthPrepConstants keeps its std430 layout");
static_assert(offsetof(DepthPrepConstants, viewFromWorld0) == 48 && offsetof(DepthPrepConstants, mulX) == 96,
              "DepthPrepConstants keeps its std430 layout");
} // namespace obscura::ssao
#endif
#undef OBSCURA_CONST
#undef OBSCURA_FN
#undef OBSCURA_INF

#endif
