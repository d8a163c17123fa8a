// The constants and resources of the spatio-temporal GTAO shaders (Jimenez et al. 2016, "Practical Realtime
// Strategies for Accurate Indirect Occlusion", §4.1): reconstruct_interleaved.comp, upsample_depth_aware.comp
// and gtao_temporal.comp, with gtao.comp's grid-step variant. Shared by each shader and its host side in
// src/gpu (gtao_temporal_pass.cpp), compiled as both C++ and GLSL like layouts.h. Plain 32-bit ints and
// floats only, so std430 and C++ lay the push constants out alike; the static_asserts below hold C++ to it.
//
// A "guide" plane is a depth or normal plane read at a stride: grid pixel (x, y) is element
// (y guideStep) guideWidth + x guideStep. Step 1 reads a plane of the grid's own size; step 2 reads the
// full-resolution G-buffer at (2x, 2y), which is what the half-resolution frame's grid depth and normals
// are (src/ssao/gtao_temporal.cpp), so the frame needs no subsampled copies of them.
#ifndef OBSCURA_GPU_TEMPORAL_LAYOUTS_H
#define OBSCURA_GPU_TEMPORAL_LAYOUTS_H

#include "obscura/reconstruct_window.h"

#ifdef __cplusplus
#include <cstddef>
namespace obscura::gpu {
#define OBSCURA_CONST inline constexpr
#else
#define OBSCURA_CONST const
#endif

// The workgroups of the spatio-temporal passes: kUpsampleWorkgroup* the upsampling's, kAccumulationWorkgroup*
// the accumulation's and the reconstruction's. All three once had one size; its history: on an H100
// (2026-11-25, visibility only, 1920x1080) 16x4 took the accumulation 0.104 ms instead of 0.115 with 8x8,
// its variant without history 0.081 instead of 0.087, and the half-resolution accumulation 0.061 instead of
// 0.069; 32x2 was slower at full resolution. 16x8 keeps the 16-pixel rows and halves the share of a
// shared-memory tile's apron (grid_tile.glsl: 18x10 slots for 128 pixels instead of 18x6 for 64): on the
// H100 (2026-11-26, 3 rounds in one run) the grid's accumulation with the 5x5 window took 0.901 of 16x4's
// time at 1920x1080 and 0.902 at 3840x2160, the half-resolution frame's 0.937; the upsampling did not move.
// Since then the accumulation and the reconstruction (gtao_temporal.comp, reconstruct_interleaved.comp and
// their grid_tile.glsl) have workgroups of their own, 32x4: a warp is one row of 32 lattice pixels, so each
// strided load of the G-buffer spans one row instead of two, and the 5x5 window's tile, at 2.25 slots per
// pixel instead of 1.88, did not lose for it. On an H200 (2026-11-26, 3 rounds in one run) the grid's
// accumulation took 0.884 / 0.886 of 16x8's time at 1920x1080 / 3840x2160 with the 5x5 window and
// 0.994 / 0.979 with the spatio-temporal target's flags. The upsampling in 32x4 took 0.995 to 1.012 of its
// 16x8 time in two calls, where its unchanged shader read 0.999 to 1.007 (noise): no gain, so it keeps 16x8.
// The host dispatches the size the compiled shaders declare, so shaders swapped in through
// OBSCURA_SHADER_DIR may try another (bench/gpu-candidates).
OBSCURA_CONST int kUpsampleWorkgroupX = 16;
OBSCURA_CONST int kUpsampleWorkgroupY = 8;
OBSCURA_CONST int kAccumulationWorkgroupX = 32;
OBSCURA_CONST int kAccumulationWorkgroupY = 4;

// ---- gtao.comp's variant (layouts.h has its bindings) ----
// constant_id of the grid step: invocation (x, y) evaluates full-resolution pixel (step x, step y) with the
// interleave index of (x, y) and writes element y ceil(width / step) + x. 1 (the default, what an engine
// that sets no specialization gets) is the plain full-resolution pass; 2 is the half-resolution frame.
OBSCURA_CONST int kGtaoSpecGridStep = 0;

// ---- reconstruct_interleaved.comp: ssao::reconstructInterleaved ----
// constant_id of the channel count of values and output: 1 (visibility) or 3 (bent normals, renormalised).
OBSCURA_CONST int kReconstructSpecChannels = 0;
// constant_id of the window (GtaoTemporalSettings::alternatingWindow): -1 (the default) the 5x5 window; 0..3
// the 4x4 window of that phase, 4..7 the 2x2 one (obscura/reconstruct_window.h),
// ssao::reconstructWindowPhase(settings, frameIndex): one pipeline per phase.
OBSCURA_CONST int kReconstructSpecWindowPhase = 1;
// constant_id of the guide normals' layout, as gtao.comp's kGtaoSpecPackedNormals (layouts.h): 0 3 floats per
// element, 1 one octahedral word.
OBSCURA_CONST int kReconstructSpecPackedNormals = 2;
struct ReconstructConstants {
    int width;         // grid size, px
    int height;
    int guideWidth;    // elements per row of the guide planes
    int guideStep;     // 1, or 2 for the half-resolution grid read from the full G-buffer

    float depthSigma;  // GtaoTemporalSettings::depthSigma, (0, 1]
    int pad0;
    int pad1;
    int pad2;
};
OBSCURA_CONST int kReconstructBindingValues = 0;  // width * height * channels, the raw interleaved values
OBSCURA_CONST int kReconstructBindingDepth = 1;   // guide linear depths, +inf for sky
OBSCURA_CONST int kReconstructBindingNormal = 2;  // guide view normals, 3 floats per element (or a word,
                                                  // kReconstructSpecPackedNormals)
OBSCURA_CONST int kReconstructBindingOutput = 3;  // width * height * channels
OBSCURA_CONST int kReconstructBindingCount = 4;
OBSCURA_CONST int kReconstructPushConstantBytes = 32;

// ---- upsample_depth_aware.comp: ssao::upsampleDepthAware ----
// constant_id of the channel count (1 or 3), as above.
OBSCURA_CONST int kUpsampleSpecChannels = 0;
// constant_id of the low-resolution values' encoding: 0 (the default) floats; 1, one channel of the packed
// visibility-and-length words of obscura/history_packing.h (the accumulation's visibility plane with
// kTemporalSpecPackedHistory and kTemporalSpecHistoryStep 2), upsampled as the visibility they decode to.
OBSCURA_CONST int kUpsampleSpecPackedLow = 1;
// constant_id of the output's encoding (1 channel only): 0 (the default) a float per pixel; 1 unorm16
// visibility (obscura/history_packing.h's packUnorm16, steps of 1/65535), two pixels to a word, pixel 2i of a
// row in the low half and 2i + 1 in the high half, rows of upsamplePackedRowWords(width) words: what an
// R16_UNORM image with an even row pitch holds, a sixteenth of a 1/4096 step, for an engine that reads AO
// at 16 bits anyway.
OBSCURA_CONST int kUpsampleSpecPackedOut = 2;
// constant_id of the full-resolution normals' layout (kUpsampleBindingNormal): 0, 3 floats a pixel; 1, one
// octahedral word (normal_plane.glsl).
OBSCURA_CONST int kUpsampleSpecPackedNormals = 3;
#ifdef __cplusplus
inline constexpr int upsamplePackedRowWords(int width) { return (width + 1) / 2; }
#endif
struct UpsampleConstants {
    int width;         // full-resolution size, px
    int height;
    int lowWidth;      // low-resolution size, px
    int lowHeight;

    int guideWidth;    // elements per row of the low-resolution depth guide
    int guideStep;     // 1, or 2 when it is the full-resolution depth read at (2x, 2y)
    float depthSigma;  // GtaoTemporalSettings::depthSigma, (0, 1]
    int pad0;
};
OBSCURA_CONST int kUpsampleBindingLow = 0;       // lowWidth * lowHeight * channels
OBSCURA_CONST int kUpsampleBindingLowDepth = 1;  // guide linear depths of the low-resolution pixels
OBSCURA_CONST int kUpsampleBindingDepth = 2;     // width * height linear depths, +inf for sky
OBSCURA_CONST int kUpsampleBindingOutput = 3;    // width * height * channels; sky 1 (1 channel) or 0; with
                                                 // kUpsampleSpecPackedOut, height rows of (width + 1) / 2 words
// width * height view normals, read with 3 channels only, at a pixel none of whose taps is a surface (its
// own normal is then its bent normal, as ssao::upsampleDepthAware gives it)
OBSCURA_CONST int kUpsampleBindingNormal = 4;
OBSCURA_CONST int kUpsampleBindingCount = 5;
OBSCURA_CONST int kUpsamplePushConstantBytes = 32;

// ---- gtao_temporal.comp: steps 2 or 3, and 4, of ssao::GtaoTemporal::frame ----
// The spatial filter of each pixel, then reprojection and exponential accumulation. Filled by
// gpu::gtaoTemporalConstants (obscura/gpu_temporal.h); each field names the expression of
// src/ssao/gtao_temporal.cpp it stands for.
// constant_id of the grid step, which picks the filter: 1, the grid is the full-resolution raw interleaved
// GTAO output, reconstructed here (step 2); 2, it is the half-resolution grid reconstructed by
// reconstruct_interleaved.comp, upsampled here (step 3). The grid's depth and normals are the G-buffer's
// at every step-th pixel. With kTemporalSpecHistoryStep 2 (below) and grid step 2, the grid is the raw
// half-resolution GTAO output, reconstructed here as at full resolution.
OBSCURA_CONST int kTemporalSpecGridStep = 0;
// constant_id of GtaoTemporalSettings::depthSigma, (0, 1], a float: the filters' depth tolerance.
OBSCURA_CONST int kTemporalSpecDepthSigma = 1;
// constant_id of the bent normals: 1 (the default) filters and accumulates them; 0 visibility alone (with
// gtao.comp's kGtaoSpecBentNormal 0): kTemporalBindingGridBent, PreviousBentWorld, BentWorldOut and
// BentViewOut are left untouched, so any storage buffer may stand there. Visibility and history length come
// out the same either way.
OBSCURA_CONST int kTemporalSpecBentNormal = 2;
// constant_id of GtaoTemporalSettings::packedHistory: 0 (the default) keeps the history as floats, the
// planes below; 1 as the packed words of obscura/history_packing.h: the visibility plane holds visibility
// and length in one word per pixel, the normal and bent-normal planes one word per pixel each, and
// kTemporalBindingPreviousLength and LengthOut are left untouched.
OBSCURA_CONST int kTemporalSpecPackedHistory = 3;
// constant_id of the depth copy: 1 (the default) copies the frame's depth into kTemporalBindingDepthOut for
// the next frame; 0 leaves DepthOut untouched, and kTemporalBindingPreviousDepth is then the previous
// frame's own depth buffer, which the caller keeps unchanged until this frame has run.
OBSCURA_CONST int kTemporalSpecDepthCopy = 4;
// constant_id of the history's lattice (GtaoTemporalSettings::gridHistory): 1 (the default), the history
// has a pixel per G-buffer pixel; 2, with grid step 2, it is the half-resolution grid's: the invocations
// cover the grid, each reconstructs its grid pixel from the raw GTAO output (as at full resolution) and
// accumulates it there, and every history plane and BentViewOut below has one element per grid pixel
// where the list says width * height. upsample_depth_aware.comp then brings the visibility plane (with
// kUpsampleSpecPackedLow when packed) and BentViewOut to full resolution.
OBSCURA_CONST int kTemporalSpecHistoryStep = 5;
// constant_id of the reconstruction's window where this pass reconstructs (grid step = history step), as
// kReconstructSpecWindowPhase: -1 the 5x5 window, 0..3 the 4x4 window of that phase, 4..7 the 2x2 one.
OBSCURA_CONST int kTemporalSpecWindowPhase = 6;
// constant_id of the normals' layout (kTemporalBindingNormal), as gtao.comp's kGtaoSpecPackedNormals.
OBSCURA_CONST int kTemporalSpecPackedNormals = 7;
// The previous camera's size, and so its aspect, are the current one's: the frame rejects a size change.
// 128 bytes, Vulkan's guaranteed push-constant size (lavapipe's too).
struct GtaoTemporalConstants {
    int width;                    // g.width(), px
    int height;                   // g.height()
    float maxHistory;             // float(temporal_.maxHistory) where the history is used (temporal_.temporal
                                  // && frame_ > 0), else 0: that frame takes none
    float tanHalfFovY;            // g.camera.tanHalfFovY(), for g.viewPosition(x, y)

    float aspect;                 // g.camera.aspect(), = previousCamera_.aspect()
    float previousTanHalfFovY;    // previousCamera_.tanHalfFovY(), for previousCamera_.pixelFromView
    float rejectDepth;            // temporal_.rejectDepth, (0, 1]
    float rejectNormalCos;        // temporal_.rejectNormalCos, [-1, 1]

    // Rows 0..2 of g.camera.worldFromView(), 4 floats each. viewFromWorld's rotation, the only part of it
    // the frame uses, is its transpose bit for bit (Camera builds both from the same axes).
    float worldFromView[12];
    float previousViewFromWorld[12];  // rows 0..2 of previousCamera_.viewFromWorld()
};
// Storage buffers (float arrays, std430). Inputs of the current frame:
OBSCURA_CONST int kTemporalBindingDepth = 0;       // width * height linear depths, +inf for sky
OBSCURA_CONST int kTemporalBindingNormal = 1;      // width * height * 3 view normals (or words,
                                                   // kTemporalSpecPackedNormals)
// The grid of ceil(width / step) x ceil(height / step) pixels the filter reads:
OBSCURA_CONST int kTemporalBindingGridVisibility = 2;  // 1 float per grid pixel, visibility
OBSCURA_CONST int kTemporalBindingGridBent = 3;        // 3 floats per grid pixel, view bent normals
// The history the previous frame wrote (read only when maxHistory > 0; bound either way), as floats or,
// with kTemporalSpecPackedHistory, packed words (the sizes below are the float layout's):
OBSCURA_CONST int kTemporalBindingPreviousDepth = 4;        // width * height linear depths
OBSCURA_CONST int kTemporalBindingPreviousNormalWorld = 5;  // width * height * 3 world normals, sky 0
OBSCURA_CONST int kTemporalBindingPreviousVisibility = 6;   // width * height accumulated visibility
OBSCURA_CONST int kTemporalBindingPreviousBentWorld = 7;    // width * height * 3 accumulated world bent normals
OBSCURA_CONST int kTemporalBindingPreviousLength = 8;       // width * height frames accumulated
// Outputs: the next frame's history (the same five planes) and the view-space bent normals.
OBSCURA_CONST int kTemporalBindingDepthOut = 9;            // a copy of the depth input
OBSCURA_CONST int kTemporalBindingNormalWorldOut = 10;
OBSCURA_CONST int kTemporalBindingVisibilityOut = 11;     // the frame's visibility, sky 1
OBSCURA_CONST int kTemporalBindingBentWorldOut = 12;
OBSCURA_CONST int kTemporalBindingLengthOut = 13;         // 1 where history was rejected or absent
OBSCURA_CONST int kTemporalBindingBentViewOut = 14;       // the frame's view-space bent normals, sky 0
OBSCURA_CONST int kTemporalBindingCount = 15;
OBSCURA_CONST int kTemporalPushConstantBytes = 128;

// ---- gtao_temporal_fused.comp: GTAO, the reconstruction and the accumulation on the grid, one dispatch ----
// The half-resolution frame with the grid's history (kTemporalSpecHistoryStep 2) runs gtao.comp over the grid,
// then gtao_temporal.comp, which reconstructs each grid pixel from the raw values of the pixels around it and
// accumulates it. Fused, a workgroup evaluates GTAO for kFusedWorkgroupX x kFusedWorkgroupY grid pixels into
// shared memory, then reconstructs and accumulates those whose whole window lies among them: the inner
// (kFusedWorkgroupX - side + 1) x (kFusedWorkgroupY - side + 1) for a window of `side` taps a side
// (fusedOutputTile). The raw values never reach memory, the grid's depth and normals are read once, and a
// dispatch and its barrier are gone; the pixels of the border are evaluated again by the neighbouring
// workgroups (with the 2x2 windows, 31 of every 256: 1.14x the GTAO work). Each value is the same arithmetic
// as the two passes'. The host dispatches the workgroup size the compiled shader declares, so a shader swapped
// in through OBSCURA_SHADER_DIR may try another (bench/gpu-candidates).
OBSCURA_CONST int kFusedWorkgroupX = 16;
OBSCURA_CONST int kFusedWorkgroupY = 16;
// Specialization constants: gtao.comp's modes and gtao_temporal.comp's variants, under their own ids.
OBSCURA_CONST int kFusedSpecSampling = 0;        // kGtaoSpecSampling's values (GtaoConstants::sampling)
OBSCURA_CONST int kFusedSpecWeighting = 1;       // GtaoConstants::weighting
OBSCURA_CONST int kFusedSpecThicknessMode = 2;   // GtaoConstants::thicknessMode
OBSCURA_CONST int kFusedSpecBeyondRadius = 3;    // GtaoConstants::beyondRadius
OBSCURA_CONST int kFusedSpecPackedNormals = 4;   // as kGtaoSpecPackedNormals
OBSCURA_CONST int kFusedSpecBentNormal = 5;      // as kTemporalSpecBentNormal (0: visibility alone)
OBSCURA_CONST int kFusedSpecDepthSigma = 6;      // as kTemporalSpecDepthSigma, a float
OBSCURA_CONST int kFusedSpecPackedHistory = 7;   // as kTemporalSpecPackedHistory
OBSCURA_CONST int kFusedSpecDepthCopy = 8;       // as kTemporalSpecDepthCopy
OBSCURA_CONST int kFusedSpecWindowPhase = 9;     // as kTemporalSpecWindowPhase: -1 5x5, 0..3 4x4, 4..7 2x2
// The push constants are the GTAO pass's GtaoConstants (layouts.h's kGtaoPushConstantBytes); the
// accumulation's GtaoTemporalConstants are a storage buffer's (kFusedBindingTemporalConstants): both together
// exceed the 128 bytes of push constants every device offers.
// Storage buffers: gtao_temporal.comp's (kTemporalBinding*, with the grid's lattice: the depth and normal
// inputs, the history and the outputs), but for the two that held the raw grid, which the fused pass keeps in
// shared memory:
OBSCURA_CONST int kFusedBindingDepthMips = kTemporalBindingGridVisibility;        // as kGtaoBindingDepthMips
OBSCURA_CONST int kFusedBindingTemporalConstants = kTemporalBindingGridBent;      // this frame's GtaoTemporalConstants
OBSCURA_CONST int kFusedBindingCount = kTemporalBindingCount;
#ifdef __cplusplus
// Grid pixels a workgroup of `workgroupSide` invocations along an axis accumulates along it with the window
// of windowPhase (obscura/reconstruct_window.h): those whose window lies among its evaluated pixels.
inline constexpr int fusedOutputTile(int windowPhase, int workgroupSide) {
    return workgroupSide - ssao::reconstructWindowSide(windowPhase) + 1;
}
#endif

#ifdef __cplusplus
static_assert(sizeof(ReconstructConstants) == kReconstructPushConstantBytes &&
                  offsetof(ReconstructConstants, depthSigma) == 16,
              "ReconstructConstants is std430");
static_assert(sizeof(UpsampleConstants) == kUpsamplePushConstantBytes && offsetof(UpsampleConstants, guideWidth) == 16,
              "UpsampleConstants is std430");
static_assert(sizeof(GtaoTemporalConstants) == kTemporalPushConstantBytes &&
                  offsetof(GtaoTemporalConstants, aspect) == 16 &&
                  offsetof(GtaoTemporalConstants, worldFromView) == 32 &&
                  offsetof(GtaoTemporalConstants, previousViewFromWorld) == 80,
              "GtaoTemporalConstants is std430");
static_assert(fusedOutputTile(4, kFusedWorkgroupX) == 15 && fusedOutputTile(-1, kFusedWorkgroupY) == 12,
              "the 2x2 and 5x5 windows' tiles");
} // namespace obscura::gpu
#endif
#undef OBSCURA_CONST

#endif
