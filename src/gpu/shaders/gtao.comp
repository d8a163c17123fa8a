// Ground-Truth Ambient Occlusion as a compute pass: Jimenez, Wu, Pesce and Jarabo 2016, "Practical Realtime
// Strategies for Accurate Indirect Occlusion", §4 (eq. 5-9) and App. A (eq. 22-23); the visibility bitmask
// follows Therrien et al. 2023, "Screen Space Indirect Lighting with Visibility Bitmask". One invocation
// per pixel.
//
// gtaoPixel (gtao_pixel.glsl) is src/ssao/gtao.cpp's gtaoPixel line for line, with the same names and helpers (and
// hash32, hashCombine, toUnitFloat and interleaveIndex of obscura/sampling.h and gtao.cpp, in the same
// integer arithmetic); read them side by side. The differences are GLSL's: Vec3 is vec3, but dot, length,
// normalize and cross are written out as the C++ ones compute them (a GPU's built-ins may fuse or use an
// inverse square root); mix is `lerp`, since GLSL's mix rounds differently; the G-buffer planes are the
// buffers `depthPlane` and `normalPlane` (C++: g.depth, g.normal) and the MIP chain `depthMips` (C++:
// mips, made by gtao_mips.comp), the result `out` is `result` (a GLSL keyword); std::lround is roundHalfUp
// (its arguments are >= 0); std::atan2(0, 0) is atan2's 0. The constants are the push constants `k`, filled
// by ssao::gtaoConstants().
// What remains is the GPU's sin, cos, acos, atan and pow, which round differently from libm: tests/gpu
// measure the difference.
//
// Where the arithmetic differs on purpose, for speed, each change gives the same value up to rounding:
// - an inverse square root takes the place of length3 and a division for the view vector, the slice
//   tangent, the projected normal, a sample's distance and cosine, and the column test's vectors;
// - the open slice's visibility, arc(n - pi/2, n + pi/2, n).visibility, is in closed form, n sin n + cos n
//   (1 uniformly weighted), and the lowest horizon cosines cos(n +- pi/2) are -+sin n;
// - the planar quad loop and the two sides are unrolled;
// - without the thickness heuristic the horizon update is a plain maximum (gtaoConstants sets thicknessBlend
//   to 0 then, so the lerp keeps the horizon), chosen by the thickness mode's specialization constant.
// On an H100 (2026-11-25, 1920x1080, high, visibility only) the first three took the pass from 0.237 to
// 0.212 ms with planar samples and from 0.126 to 0.121 ms with nearest ones; the plain maximum took 0.965x
// the pass's time there (2026-11-26; docs/PERFORMANCE.md).
//
// With the specialization constant kGtaoSpecBentNormal 0 (layouts.h) the pass writes visibility alone. The
// modes of the constants (sampling, weighting, thickness, beyond radius) are specialization constants too,
// so that each variant compiles without the others' code.
// The grid step (a specialization constant, temporal_layouts.h) is the loop of step 1 of
// ssao::GtaoTemporal::frame (src/ssao/gtao_temporal.cpp): with step 2 each invocation evaluates every other
// pixel in x and y, with the interleave index of its place in the half-resolution grid.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "obscura/gtao_constants.h"
#include "obscura/gtao_mips.h"
#include "layouts.h"
#include "temporal_layouts.h"

// The size as specialization constants of those defaults (layouts.h, kSpecWorkgroupSizeX): gl_WorkGroupSize is
// then the size a module rewritten to another runs with, not one glslang folded into the code.
layout(local_size_x = kGtaoWorkgroupX, local_size_y = kGtaoWorkgroupY, local_size_z = 1,
       local_size_x_id = kSpecWorkgroupSizeX, local_size_y_id = kSpecWorkgroupSizeY) in;

layout(constant_id = kGtaoSpecGridStep) const int kGridStep = 1;
layout(constant_id = kGtaoSpecBentNormal) const int kBentNormal = 1;
// The constants' modes, as specialization constants (layouts.h says why); recordGtao sets each from the
// GtaoConstants field named beside it, which the shader does not read.
layout(constant_id = kGtaoSpecSampling) const int kSampling = GTAO_SAMPLING_PLANAR;             // k.sampling
layout(constant_id = kGtaoSpecWeighting) const int kWeighting = GTAO_WEIGHTING_COSINE;          // k.weighting
layout(constant_id = kGtaoSpecThicknessMode) const int kThicknessMode = GTAO_THICKNESS_NONE;    // k.thicknessMode
layout(constant_id = kGtaoSpecBeyondRadius) const int kBeyondRadius = GTAO_BEYOND_COLUMN;       // k.beyondRadius
layout(constant_id = kGtaoSpecPackedNormals) const int kPackedNormals = 0;

layout(push_constant, std430) uniform Constants { GtaoConstants k; };
layout(std430, binding = kGtaoBindingDepth) readonly buffer DepthPlane { float depthPlane[]; };
layout(std430, binding = kGtaoBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };
layout(std430, binding = kGtaoBindingVisibility) writeonly buffer Visibility { float visibilityOut[]; };
layout(std430, binding = kGtaoBindingBentNormal) writeonly buffer BentNormal { float bentNormalOut[]; };
layout(std430, binding = kGtaoBindingDepthMips) readonly buffer DepthMips { float depthMips[]; };

#include "gtao_pixel.glsl"

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    const int gridWidth = (k.width + kGridStep - 1) / kGridStep, gridHeight = (k.height + kGridStep - 1) / kGridStep;
    if (p.x >= gridWidth || p.y >= gridHeight) return;
    if (gtaoSamplingReadsMips(kSampling)) {
        mipBase2 = uint(gtaoMipOffset(k.width, k.height, 2));
        mipBase3 = uint(gtaoMipOffset(k.width, k.height, 3));
        mipBase4 = uint(gtaoMipOffset(k.width, k.height, 4));
    }
    const GtaoPixel px = gtaoPixel(p.x * kGridStep, p.y * kGridStep, interleaveIndex(p.x, p.y));
    const uint i = uint(p.y) * uint(gridWidth) + uint(p.x);
    visibilityOut[i] = px.visibility;
    if (kBentNormal == 0) return;  // AO only: the compiler drops the bent normal's arithmetic with its output
    bentNormalOut[3 * i] = px.bentNormal.x;
    bentNormalOut[3 * i + 1] = px.bentNormal.y;
    bentNormalOut[3 * i + 2] = px.bentNormal.z;
}
