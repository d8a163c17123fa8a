// Constants the GTAO kernel reads (Jimenez et al. 2016, "Practical Realtime Strategies for Accurate
// Indirect Occlusion"), shared by the C++ reference and the GLSL compute pass: plain 32-bit ints and
// floats only, no vectors, so std140/std430 and C++ lay it out identically.
//
// One pure function, obscura::ssao::gtaoConstants() (obscura/gtao.h), fills it from the user's settings,
// the camera and the image size; the kernels read nothing else besides the G-buffer.
#ifndef OBSCURA_GTAO_CONSTANTS_H
#define OBSCURA_GTAO_CONSTANTS_H

#ifdef __cplusplus
#include <cstdint>
namespace obscura::ssao {
using uint = std::uint32_t;
#endif

// Integer codes shared with GLSL (no enums there).
#define GTAO_WEIGHTING_COSINE 0   // eq. 5: cosine-weighted, radiometrically correct
#define GTAO_WEIGHTING_UNIFORM 1  // App. A, eq. 22-23: uniformly weighted hemisphere
#define GTAO_THICKNESS_NONE 0     // plain maximum horizon (eq. 6)
#define GTAO_THICKNESS_HEURISTIC 1  // eq. 9: exponential decay of the horizon past thin occluders
#define GTAO_THICKNESS_BITMASK 2  // 32 sectors per slice, occluders of constant thickness
#define GTAO_BITMASK_SECTORS 32
#define GTAO_BEYOND_DROP 0        // a sample farther than r does not count
#define GTAO_BEYOND_COLUMN 1      // ... but the depth buffer's column behind it does, where it comes within r
#define GTAO_SAMPLING_PLANAR 0    // a horizon sample interpolates inverse depth over a planar 2x2 quad
#define GTAO_SAMPLING_NEAREST 1   // ... or takes the nearest pixel's point: one read instead of five
#define GTAO_SAMPLING_MIP 2       // ... or, farther out, the point of a coarser level of a depth MIP chain
                                  // (obscura/gtao_mips.h); nearest where no coarser level is fine enough
#define GTAO_SAMPLING_PLANAR_MIP 3  // the chain farther out, planar samples nearer
#define GTAO_SAMPLING_PLANAR_NEAREST 4  // planar samples nearer, nearest-pixel ones farther out (no chain)

struct GtaoConstants {
    int width;                 // image size, pixels
    int height;
    float viewFromPixelMulX;   // view x / depth = px * mulX + addX (px continuous, centre at +0.5)
    float viewFromPixelMulY;
    float viewFromPixelAddX;
    float viewFromPixelAddY;
    float focalPixels;         // pixels spanned by 1 m at 1 m depth
    float radius;              // r: m; occluders beyond r do not count
    float falloffFrom;         // m; the linear fade of a sample's weight starts here and ends at r
    float falloffInvRange;     // 1 / (r - falloffFrom), 1/m (huge for a hard cut at r)
    float maxRadiusPixels;     // the search radius on screen is clamped to this, pixels
    float minStepPixels;       // the first sample is at least this far, pixels (skips the centre pixel)
    float stepPower;           // step distribution: s_k = ((k + jitter) / steps)^power, power >= 1
    float thicknessBlend;      // eq. 9 blend factor in [0, 1): 0 = plain maximum
    float bitmaskThickness;    // assumed occluder thickness for the bitmask, m
    int sliceCount;            // slice directions per pixel, >= 1
    int stepsPerSide;          // samples on each side of the slice, >= 1
    int weighting;             // GTAO_WEIGHTING_*
    int thicknessMode;         // GTAO_THICKNESS_*
    int interleaved;           // 1: slices rotated by the 4x4 pattern and the frame's rotation (of 6)
    int noiseMode;             // 0: fixed slice angles and step offsets; 1: per-pixel hashed jitter
    int frameIndex;            // selects the temporal rotation (of 6) and the jitter
    int beyondRadius;          // GTAO_BEYOND_*: what a sample farther than the full-weight distance stands for
    int sampling;              // GTAO_SAMPLING_*: how a horizon sample reads the depth buffer
    int mipLevels;             // GTAO_SAMPLING_(PLANAR_)MIP: coarse levels of the chain, [0, GTAO_MAX_MIP_LEVELS]; else 0
    float mipTexelScale;       // 1 / GtaoSettings::mipDistanceRatio: with (PLANAR_)MIP the widest texel a sample may
                               // read per pixel of its distance; with PLANAR_NEAREST, samples from 2 / mipTexelScale
                               // pixels out read the nearest pixel; the other modes ignore it
};

#ifdef __cplusplus
#define OBSCURA_FN inline
#else
#define OBSCURA_FN
#endif
// Whether a GTAO_SAMPLING_* mode reads the depth MIP chain.
OBSCURA_FN bool gtaoSamplingReadsMips(int sampling) {
    return sampling == GTAO_SAMPLING_MIP || sampling == GTAO_SAMPLING_PLANAR_MIP;
}
// Whether a sample offsetPixels from the centre that reads level 0 is planar: always with PLANAR and
// PLANAR_MIP, never with NEAREST and MIP, and with PLANAR_NEAREST nearer than 2 / texelScale pixels (where
// MIP sampling would still read level 0).
OBSCURA_FN bool gtaoSamplingPlanarAt(int sampling, float offsetPixels, float texelScale) {
    return sampling == GTAO_SAMPLING_PLANAR || sampling == GTAO_SAMPLING_PLANAR_MIP ||
           (sampling == GTAO_SAMPLING_PLANAR_NEAREST && offsetPixels * texelScale < 2.0f);
}
#undef OBSCURA_FN

#ifdef __cplusplus
static_assert(sizeof(GtaoConstants) == 26 * 4, "GtaoConstants must stay 26 scalars (std430 layout)");
static_assert(alignof(GtaoConstants) == 4, "GtaoConstants holds 32-bit scalars only");
} // namespace obscura::ssao
#endif

#endif
