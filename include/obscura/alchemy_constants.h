// Constants of the Alchemy AO kernel, shared by the C++ reference (src/ssao/alchemy.cpp) and the GLSL
// compute pass (src/gpu/shaders/alchemy.comp, which takes them as push constants): plain 32-bit ints and
// floats, std140/std430-compatible, no vec3. The same file is #included by GLSL (the #ifdef maps the few
// C++-only parts). Filled in by one pure function,
// obscura::ssao::alchemyConstants() in obscura/alchemy.h.
#ifndef OBSCURA_ALCHEMY_CONSTANTS_H
#define OBSCURA_ALCHEMY_CONSTANTS_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
namespace obscura::ssao {
using uint = std::uint32_t;
#define OBSCURA_CONST inline constexpr
#else
#define OBSCURA_CONST const
#endif

// Formulation selector.
OBSCURA_CONST int kAlchemyPaper = 0;    // McGuire et al. 2011, eq. 10
OBSCURA_CONST int kAlchemyChapter = 1;  // "Where Corners Stay Dark": c = 0.1 R, bias subtracted, 2 pi c / n
// Per-pixel spiral rotations come from a 4 x 4 tile of pixel classes, so offsets can be precomputed per
// class and the bilateral blur (13 taps > 4 pixels) averages every rotation.
OBSCURA_CONST int kAlchemyClassTile = 4;
OBSCURA_CONST int kAlchemyPixelClasses = 16;
OBSCURA_CONST int kAlchemyMaxSamples = 1024;
// The compute pass's workgroup: one row of 256, so that a warp is one row of 32 pixels, 8 of each of the 4
// classes of a class-tile row, whose samples then fall 4 pixels apart. On an H100 (2026-11-25) rows beat
// squares among 64-invocation shapes (1920x1080: 8x8 0.085 ms, 16x4 0.062, 32x2 0.052, 64x1 0.051), and
// longer rows won again (2026-11-26, 3 rounds in one run): 256x1 took 0.974 of 64x1's time at 1920x1080 and
// 0.929 at 3840x2160 (0.1804 ms instead of 0.1942), 128x1 0.967 and 0.947. The host dispatches the size the
// compiled shader declares, so a shader swapped in through OBSCURA_SHADER_DIR may try another
// (bench/gpu-candidates).
OBSCURA_CONST int kAlchemyWorkgroupX = 256;
OBSCURA_CONST int kAlchemyWorkgroupY = 1;

struct AlchemyConstants {
    int width;               // size of the buffers the kernel reads (guard band included), px
    int height;
    int guardBand;           // px cropped on every side of the output
    int formulation;         // kAlchemyPaper or kAlchemyChapter

    int samples;             // s (paper) or n (chapter): samples per pixel at full quality, [1, 1024]
    int minSamples;          // fewest samples a distant pixel gets with the level of detail on (= samples when off)
    uint seed;               // rotation hash seed
    int pad0;

    // Pixel (px, py) at depth d -> view space: x = (px * viewScaleX + viewOffsetX) d, y = (py * viewScaleY
    // + viewOffsetY) d, z = -d (obscura::Camera::viewFromPixel).
    float viewScaleX;
    float viewOffsetX;
    float viewScaleY;
    float viewOffsetY;

    float focalPixels;       // pixels spanned by 1 m at depth 1 m: R_px = radius * focalPixels / depth
    float radius;            // r / R: world-space radius, m
    float radius2;           // radius^2, m^2: samples with v.v beyond it are dropped (Heaviside term)
    float maxRadiusPixels;   // R_px is clamped to this, px

    float lodRadiusPixels;   // R_px below which the sample count falls in proportion (0: off), px
    float bias;              // paper: beta, m, used as + z_C beta; chapter: bias, m, subtracted from v.n
    float denominator;       // paper: epsilon added to v.v (m^2); chapter: c^2 = (0.1 R)^2, floor of v.v
    float intensity;         // A = max(0, 1 - intensity / count * sum)^contrast: 2 sigma (paper), 2 pi c scale (chapter)

    float contrast;          // k, unitless
    float pad1;
    float pad2;
    float pad3;
};

#ifdef __cplusplus
static_assert(sizeof(AlchemyConstants) == 96, "AlchemyConstants must keep its std430 layout");
static_assert(offsetof(AlchemyConstants, samples) == 16 && offsetof(AlchemyConstants, viewScaleX) == 32 &&
              offsetof(AlchemyConstants, focalPixels) == 48 && offsetof(AlchemyConstants, lodRadiusPixels) == 64 &&
              offsetof(AlchemyConstants, contrast) == 80);
static_assert(sizeof(float) == 4 && sizeof(int) == 4 && sizeof(uint) == 4);
} // namespace obscura::ssao
#endif
#undef OBSCURA_CONST

#endif
