// The constants and resources of the compute shaders in this folder, shared by each shader and its host
// side in src/gpu (compiled as both C++ and GLSL, like obscura/alchemy_constants.h). The host also checks
// the binding count and push-constant size against the compiled shader (gpu::reflect), so a binding added on
// one side only fails at pipeline creation, not in a wrong image.
#ifndef OBSCURA_GPU_LAYOUTS_H
#define OBSCURA_GPU_LAYOUTS_H

#ifdef __cplusplus
#include <cstddef>
namespace obscura::gpu {
#define OBSCURA_CONST inline constexpr
#else
#define OBSCURA_CONST const
#endif

// constant_ids of a workgroup size given by specialization constants (local_size_x_id, local_size_y_id),
// whose defaults are the size. Code that reads gl_WorkGroupSize then reads the size the module runs with:
// glslang folds a literal size into the code, so a module rewritten to another size (tests/gpu/spirv_edit.h)
// would run the old size's arithmetic. The host never sets them: its variants take constant_ids from 0
// (ComputePipeline refuses a module whose size is one of those) and it dispatches by their defaults (reflect).
OBSCURA_CONST int kSpecWorkgroupSizeX = 100;
OBSCURA_CONST int kSpecWorkgroupSizeY = 101;

// ---- alchemy.comp (src/gpu/alchemy_pass.cpp) ----
// Storage buffers of set 0 (float arrays, std430).
OBSCURA_CONST int kAlchemyBindingDepth = 0;   // width * height linear depths, +inf for sky
OBSCURA_CONST int kAlchemyBindingNormal = 1;  // width * height * 3 view normals, or with kAlchemySpecPackedNormals 1
                                              // width * height octahedral words (normal_plane.glsl)
OBSCURA_CONST int kAlchemyBindingSpiral = 2;  // SpiralTable::offsets, concatenated (see alchemySpiralAt)
OBSCURA_CONST int kAlchemyBindingOutput = 3;  // (width - 2 guardBand) * (height - 2 guardBand) obscurance
OBSCURA_CONST int kAlchemyBindingCount = 4;
// The push constants are one AlchemyConstants.
OBSCURA_CONST int kAlchemyPushConstantBytes = 96;
// constant_id of the normals' layout, as gtao.comp's kGtaoSpecPackedNormals (also alchemy_blur_row.comp's).
OBSCURA_CONST int kAlchemySpecPackedNormals = 0;

// ---- bilateral_separable.comp (src/gpu/bilateral_pass.cpp) ----
// One 1-D pass of the separable cross-bilateral blur (src/ssao/bilateral_separable.cpp): a tap t in
// [-radius, radius] along `axis` weighs 2^(logSpatial[t + radius] - dd^2 depthScale / d^2), dd = d_t - d,
// times max(0, N . N_t) when useNormal is 1.
struct BilateralConstants {
    int width;         // px
    int height;        // px
    int radius;        // taps on each side, [1, kBilateralMaxRadius]
    int axis;          // 0: horizontal (x), 1: vertical (y)

    int useNormal;     // 0 or 1
    float depthScale;  // log2(e) / (2 depthSigma^2)
    // Where the depth and normal planes (the guide) hold pixel (x, y): at (x, y) guideStep, in rows of
    // guideWidth pixels. 0 or 1: planes of the image's own size (guideWidth unused); 2: full-resolution planes
    // under a half-resolution image (pixel (x, y) at (2x, 2y), gtao_half_res.h).
    int guideStep;
    int guideWidth;    // px, with guideStep 2
};

// Storage buffers of set 0 (float arrays, std430).
OBSCURA_CONST int kBilateralBindingDepth = 0;       // width * height linear depths, +inf for sky
OBSCURA_CONST int kBilateralBindingNormal = 1;      // width * height * 3 view normals
OBSCURA_CONST int kBilateralBindingLogSpatial = 2;  // 2 radius + 1 log2 spatial weights, tap t at [t + radius]
OBSCURA_CONST int kBilateralBindingInput = 3;       // width * height AO, the pass's input
OBSCURA_CONST int kBilateralBindingOutput = 4;      // width * height AO, the pass's output
OBSCURA_CONST int kBilateralBindingCount = 5;
OBSCURA_CONST int kBilateralPushConstantBytes = 32;
// The shader's workgroup is 256 invocations in a row; what they cover depends on the axis: the horizontal
// pass, 1 line of 256 pixels; the vertical pass, 8 columns of 32 pixels. Dispatch ceil(width / TileX) x
// ceil(height / TileY) workgroups for each (bilateralGroups).
OBSCURA_CONST int kBilateralWorkgroupX = 256;
OBSCURA_CONST int kBilateralWorkgroupY = 1;
OBSCURA_CONST int kBilateralHorizontalTileX = 256;
OBSCURA_CONST int kBilateralHorizontalTileY = 1;
OBSCURA_CONST int kBilateralVerticalTileX = 8;
OBSCURA_CONST int kBilateralVerticalTileY = 32;
// bilateral_tiled.comp: both passes in one dispatch, from shared memory. A workgroup of
// kBilateralTiledWorkgroupX x kBilateralTiledWorkgroupY invocations loads a square of kBilateralTiledTile
// pixels with `radius` more on each side, blurs its rows, then its columns, and writes the square; its
// bindings and push constants are bilateral_separable's (axis unused). For radius <= kBilateralTiledMaxRadius;
// dispatch ceil(width / Tile) x ceil(height / Tile) workgroups.
OBSCURA_CONST int kBilateralTiledWorkgroupX = 32;
OBSCURA_CONST int kBilateralTiledWorkgroupY = 8;
OBSCURA_CONST int kBilateralTiledTile = 32;
OBSCURA_CONST int kBilateralTiledMaxRadius = 8;
// bilateral_2d.comp: one invocation per pixel, dispatched over width x height.
OBSCURA_CONST int kBilateral2DWorkgroupX = 8;
OBSCURA_CONST int kBilateral2DWorkgroupY = 8;
// The largest radius: the shader's shared-memory lines hold this many taps on each side.
OBSCURA_CONST int kBilateralMaxRadius = 32;
// constant_id of the normal weight in both blurs (bilateral_separable, bilateral_2d): BilateralConstants::
// useNormal, which the host sets from the constants it pushes. A specialization constant so that the variant
// without it (the separable default) holds no normal reads: as with gtao.comp's modes, a branch on the push
// constant leaves the compiler both paths.
OBSCURA_CONST int kBilateralSpecUseNormal = 0;
// constant_id of the normals' layout where the blur reads them (useNormal 1), as gtao.comp's
// kGtaoSpecPackedNormals: 0 3 floats per pixel, 1 one octahedral word (also bilateral_2d.comp's).
OBSCURA_CONST int kBilateralSpecPackedNormals = 1;
// constant_id of the unrolled taps (bilateral_taps.glsl) in bilateral_separable and bilateral_tiled: 1 where
// the radius is kBilateralUnrolledRadius (the default) and the normal weight is off (bilateralSpecUnrolled),
// so that the other variants hold only the tap loop; their code cost the 5-tap blur 5-7% on an H100.
OBSCURA_CONST int kBilateralSpecUnrolled = 2;
OBSCURA_CONST int kBilateralUnrolledRadius = 6;

// ---- alchemy_blur_row.comp (src/gpu/alchemy_pass.cpp) ----
// Alchemy AO and the horizontal pass of its separable blur in one dispatch: a workgroup evaluates a row of
// kBilateralHorizontalTileX output pixels and radius more on each side into shared memory and blurs them
// there, so the raw AO never goes through memory; bilateral_separable.comp's vertical pass follows. The
// push constants are an AlchemyConstants, then a BilateralConstants for the output grid (axis 0, no normal
// weight); bindings 0-2 are alchemy.comp's.
OBSCURA_CONST int kAlchemyBlurBindingLogSpatial = 3;  // 2 radius + 1 log2 spatial weights, as the blur's
OBSCURA_CONST int kAlchemyBlurBindingOutput = 4;      // out width * out height AO, blurred along rows
OBSCURA_CONST int kAlchemyBlurBindingCount = 5;
OBSCURA_CONST int kAlchemyBlurPushConstantBytes = 128;  // 96 + 32; 128 is every device's minimum limit

// ---- gtao.comp (src/gpu/gtao_pass.cpp) ----
// Storage buffers of set 0 (float arrays, std430).
OBSCURA_CONST int kGtaoBindingDepth = 0;       // width * height linear depths, +inf for sky
OBSCURA_CONST int kGtaoBindingNormal = 1;      // width * height * 3 view normals, or with kGtaoSpecPackedNormals 1
                                               // width * height octahedral words (normal_plane.glsl)
OBSCURA_CONST int kGtaoBindingVisibility = 2;  // width * height visibility, the pass's output
OBSCURA_CONST int kGtaoBindingBentNormal = 3;  // width * height * 3 bent normals, the pass's output
OBSCURA_CONST int kGtaoBindingDepthMips = 4;   // GTAO_SAMPLING_(PLANAR_)MIP: the coarse levels (gtao_mips.comp's);
                                               // other modes leave it untouched: bind any storage buffer
OBSCURA_CONST int kGtaoBindingCount = 5;
// constant_id of the bent-normal output (the grid step's is kGtaoSpecGridStep, temporal_layouts.h): 1 (the
// default) writes the bent normals; 0 computes visibility alone, for callers that want AO only (as XeGTAO
// does by default), and leaves kGtaoBindingBentNormal untouched: bind any storage buffer there.
OBSCURA_CONST int kGtaoSpecBentNormal = 1;
// constant_ids of the modes of GtaoConstants: sampling, weighting, thicknessMode and beyondRadius. The
// kernel branches on these specialization constants, not on the push constants the CPU kernel reads, so
// that a variant's code holds nothing of the modes it does not use: a branch on a push constant is uniform,
// but the compiler keeps both paths, and their registers. On lavapipe (2026-11-25, high preset, 640x360) the
// unused bitmask path cost 27% of the pass, and behind a push-constant branch nearest sampling saved 12 ms
// of the 41 it saves specialized. The host sets them
// from the constants it pushes (recordGtao), so both always agree; an engine that records gtao.comp
// itself sets each from its GtaoConstants field.
OBSCURA_CONST int kGtaoSpecSampling = 2;
OBSCURA_CONST int kGtaoSpecWeighting = 3;
OBSCURA_CONST int kGtaoSpecThicknessMode = 4;
OBSCURA_CONST int kGtaoSpecBeyondRadius = 5;
// constant_id of the normals' layout: 0 (the default) 3 floats per pixel, 1 one octahedral word per pixel
// (obscura/history_packing.h's packOctahedral; normal_plane.glsl).
OBSCURA_CONST int kGtaoSpecPackedNormals = 6;
// The push constants are one GtaoConstants (obscura/gtao_constants.h).
OBSCURA_CONST int kGtaoPushConstantBytes = 104;
// 32x2: a warp is one row of 32 pixels, which holds each direction of the 4x4 interleave (the half-resolution,
// spatial and temporal variants) 8 times, so that more of a warp's samples share cache lines. On an H100
// (2026-11-25, visibility only) 16x4 took the interleaved pass 0.244 ms instead of 0.274 with 8x8 at 1920x1080,
// and 32x2 gained 1-3% more. Since then every configuration a target is held to runs the interleaved pass
// with planar-nearest samples, and there 32x2 took 0.930 of 16x4's time (gtao-half, 1920x1080), 0.915
// (3840x2160) and 0.932 on the spatio-temporal grid (2026-11-26, 3 rounds in one run); the plain pass, no
// target's, lost 2.0% and 1.2%. The host dispatches the size the compiled shader declares, so a shader
// swapped in through OBSCURA_SHADER_DIR may try another (bench/gpu-candidates). gtao.comp declares it through
// kSpecWorkgroupSizeX and Y, so that a mapping of invocations to pixels may read it from gl_WorkGroupSize.
OBSCURA_CONST int kGtaoWorkgroupX = 32;
OBSCURA_CONST int kGtaoWorkgroupY = 2;
OBSCURA_CONST int kGtaoRotations = 6;  // ssao::kGtaoRotations, which GLSL cannot include

// ---- gtao_mips.comp (src/gpu/gtao_pass.cpp) ----
// The coarse levels of GTAO_SAMPLING_(PLANAR_)MIP's depth MIP chain (obscura/gtao_mips.h: layout, filter) in one
// dispatch: a workgroup of GTAO_MIP_WORKGROUP^2 invocations makes an 8x8 tile of level 1 from 16x16 depths,
// then 4x4, 2x2 and 1x1 of levels 2-4 from shared memory, as XeGTAO's prefilter does.
struct GtaoMipConstants {
    int width;   // of the depth buffer, pixels
    int height;
    int levels;  // coarse levels to write, [1, GTAO_MAX_MIP_LEVELS]
    int pad0;
};
OBSCURA_CONST int kGtaoMipsBindingDepth = 0;  // width * height linear depths, +inf for sky
OBSCURA_CONST int kGtaoMipsBindingChain = 1;  // gtaoMipOffset(width, height, levels + 1) inverse depths, the output
OBSCURA_CONST int kGtaoMipsBindingCount = 2;
OBSCURA_CONST int kGtaoMipsPushConstantBytes = 16;

#ifdef __cplusplus
// bilateral_separable.comp's workgroups along x and y for a width x height image and pass `axis`.
inline constexpr int bilateralGroupsX(int axis, int width) {
    const int tile = axis == 0 ? kBilateralHorizontalTileX : kBilateralVerticalTileX;
    return (width + tile - 1) / tile;
}
inline constexpr int bilateralGroupsY(int axis, int height) {
    const int tile = axis == 0 ? kBilateralHorizontalTileY : kBilateralVerticalTileY;
    return (height + tile - 1) / tile;
}
// kBilateralSpecUnrolled's value for a blur of this radius, with or without the normal weight.
inline constexpr int bilateralSpecUnrolled(int radius, int useNormal) {
    return radius == kBilateralUnrolledRadius && useNormal == 0 ? 1 : 0;
}
// alchemy_blur_row.comp's workgroups along x: each blurs a segment of its tile (one pixel per invocation,
// kBilateralHorizontalTileX as embedded) less radius at each end.
inline constexpr int alchemyBlurRowGroupsX(int width, int radius, int tile = kBilateralHorizontalTileX) {
    const int outputs = tile - 2 * radius;
    return (width + outputs - 1) / outputs;
}
static_assert(kBilateralHorizontalTileX * kBilateralHorizontalTileY == kBilateralWorkgroupX * kBilateralWorkgroupY &&
                  kBilateralVerticalTileX * kBilateralVerticalTileY == kBilateralWorkgroupX * kBilateralWorkgroupY &&
                  kBilateralWorkgroupY == 1 && kBilateralWorkgroupX >= 2 * kBilateralMaxRadius + 1,
              "each pass's tile has one pixel per invocation, and one row of invocations loads the weights");
static_assert(kBilateralTiledWorkgroupX == kBilateralTiledTile && kBilateralTiledTile % kBilateralTiledWorkgroupY == 0 &&
                  kBilateralTiledWorkgroupX * kBilateralTiledWorkgroupY >= 2 * kBilateralTiledMaxRadius + 1,
              "bilateral_tiled.comp: a row of invocations spans the tile, whose rows the workgroup's rows share out, "
              "and the workgroup loads the weights");
static_assert(sizeof(GtaoMipConstants) == kGtaoMipsPushConstantBytes, "GtaoMipConstants keeps its std430 layout");
static_assert(kAlchemyPushConstantBytes + kBilateralPushConstantBytes == kAlchemyBlurPushConstantBytes &&
                  kAlchemyBlurPushConstantBytes <= 128,
              "alchemy_blur_row.comp pushes both passes' constants, within the limit every device has");
static_assert(sizeof(BilateralConstants) == kBilateralPushConstantBytes &&
                  offsetof(BilateralConstants, useNormal) == 16 && offsetof(BilateralConstants, depthScale) == 20,
              "BilateralConstants keeps its std430 layout");
} // namespace obscura::gpu
#endif
#undef OBSCURA_CONST

#endif
