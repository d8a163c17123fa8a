// Spatio-temporal GTAO on the half-resolution grid in one dispatch: Jimenez, Wu, Pesce and Jarabo 2016,
// "Practical Realtime Strategies for Accurate Indirect Occlusion", §4 (the GTAO integral) and §4.1 (the
// depth-aware reconstruction of the interleaved pattern, reprojection and exponential accumulation).
//
// With the grid's history the frame is gtao.comp over the grid, then gtao_temporal.comp, which reconstructs
// each grid pixel from the raw values of its window and accumulates it. Here a workgroup evaluates GTAO for
// its kFusedWorkgroupX x kFusedWorkgroupY grid pixels into shared memory (gtaoPixel, gtao_pixel.glsl, the
// same function gtao.comp calls, at the same pixel with the same interleave index), then reconstructs and
// accumulates the inner pixels, whose whole window lies among them (temporal_filters.glsl and
// temporal_pixel.glsl, as gtao_temporal.comp). Workgroups overlap by the window's side less one, so the
// border's pixels are evaluated by two or four of them; each evaluation is the same arithmetic, so the values
// are those the two passes give. What goes: the raw values' round trip through memory, the second reads of
// the grid's depth and normals, and a dispatch with its barrier (temporal_layouts.h counts the cost).
//
// The constants: gtao_pixel.glsl reads `k`, the GTAO pass's push constants; temporal_pixel.glsl reads its own
// `k` (GtaoTemporalConstants), which here is a storage buffer's, by the macro around its #include: both
// blocks together exceed the 128 bytes of push constants every device offers.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "obscura/gtao_constants.h"
#include "obscura/gtao_mips.h"
#include "layouts.h"
#include "temporal_layouts.h"

// The workgroup: the block of grid pixels it evaluates. The host reads the size back from the compiled shader.
const int kBlockX = kFusedWorkgroupX;
const int kBlockY = kFusedWorkgroupY;
layout(local_size_x = kBlockX, local_size_y = kBlockY, local_size_z = 1) in;

layout(constant_id = kFusedSpecSampling) const int kSampling = GTAO_SAMPLING_PLANAR;
layout(constant_id = kFusedSpecWeighting) const int kWeighting = GTAO_WEIGHTING_COSINE;
layout(constant_id = kFusedSpecThicknessMode) const int kThicknessMode = GTAO_THICKNESS_NONE;
layout(constant_id = kFusedSpecBeyondRadius) const int kBeyondRadius = GTAO_BEYOND_COLUMN;
layout(constant_id = kFusedSpecPackedNormals) const int kPackedNormals = 0;
layout(constant_id = kFusedSpecBentNormal) const int kBentNormal = 1;
layout(constant_id = kFusedSpecDepthSigma) const float kDepthSigma = 0.05;
layout(constant_id = kFusedSpecPackedHistory) const int kPackedHistory = 0;
layout(constant_id = kFusedSpecDepthCopy) const int kDepthCopy = 1;
layout(constant_id = kFusedSpecWindowPhase) const int kWindowPhase = 4;
const int kHistoryStep = 2;  // the grid's history: one element per grid pixel

layout(push_constant, std430) uniform Constants { GtaoConstants k; };
layout(std430, binding = kTemporalBindingDepth) readonly buffer DepthPlane { float depthPlane[]; };
layout(std430, binding = kTemporalBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };
layout(std430, binding = kFusedBindingDepthMips) readonly buffer DepthMips { float depthMips[]; };
layout(std430, binding = kFusedBindingTemporalConstants) readonly buffer TemporalConstants {
    GtaoTemporalConstants frameConstants;
};
// The history's buffers: temporal_pixel.glsl's, at gtao_temporal.comp's bindings.

#include "gtao_pixel.glsl"

// ---- the grid: ceil(width / 2) x ceil(height / 2), the G-buffer's depth and normals at (2x, 2y) ----
int latticeWidth() { return (k.width + 1) / 2; }
int latticeHeight() { return (k.height + 1) / 2; }
uint pixelIndex(int x, int y) { return uint(2 * y) * uint(k.width) + uint(2 * x); }

// The evaluated pixels: grid pixel tileOrigin + (x, y) in slot y kBlockX + x. Slots of pixels outside the
// grid hold an infinite depth and nothing else: the reconstruction skips taps there as sky, with no bounds
// tests (GRID_OUTSIDE_IS_SKY, temporal_filters.glsl).
const int kTileSlots = kBlockX * kBlockY;
const int kGridChannels = kBentNormal != 0 ? 4 : 1;
shared float tileDepth[kTileSlots];
shared float tileNormal[3][kTileSlots];
// Visibility, then the bent normal's 3 channels, whose slots shrink to 1 without bent normals: shared memory
// that is declared costs resident workgroups whether or not it is used (grid_tile.glsl).
const int kBentSlots = kBentNormal != 0 ? kTileSlots : 1;
shared float tileVisibility[kTileSlots];
shared float tileBent[3][kBentSlots];
ivec2 tileOrigin;
int tileIndex(int x, int y) { return (y - tileOrigin.y) * kBlockX + (x - tileOrigin.x); }
float gridDepth(int x, int y) { return tileDepth[tileIndex(x, y)]; }
vec3 gridNormal(int x, int y) {
    const int s = tileIndex(x, y);
    return vec3(tileNormal[0][s], tileNormal[1][s], tileNormal[2][s]);
}
float gridValue(int x, int y, int c) {
    const int s = tileIndex(x, y);
    return c == 0 ? tileVisibility[s] : tileBent[c - 1][s];
}
#define GRID_OUTSIDE_IS_SKY true

#include "temporal_filters.glsl"
#define k frameConstants
#include "temporal_pixel.glsl"
#undef k

void main() {
    const int w = latticeWidth(), h = latticeHeight();
    const ivec2 l = ivec2(gl_LocalInvocationID.xy);
    // The grid pixels this workgroup accumulates (fusedOutputTile along each axis), and the block it evaluates:
    // theirs and their windows' (obscura/reconstruct_window.h).
    const ivec2 inner = ivec2(kBlockX, kBlockY) - reconstructWindowSide(kWindowPhase) + 1;
    const ivec2 outOrigin = ivec2(gl_WorkGroupID.xy) * inner;
    tileOrigin = outOrigin + ivec2(reconstructWindowFirst(kWindowPhase, 0), reconstructWindowFirst(kWindowPhase, 1));
    const ivec2 g = tileOrigin + l;
    const int s = l.y * kBlockX + l.x;
    if (g.x >= 0 && g.y >= 0 && g.x < w && g.y < h) {
        if (gtaoSamplingReadsMips(kSampling)) {
            mipBase2 = uint(gtaoMipOffset(k.width, k.height, 2));
            mipBase3 = uint(gtaoMipOffset(k.width, k.height, 3));
            mipBase4 = uint(gtaoMipOffset(k.width, k.height, 4));
        }
        // gtao.comp's main with kGridStep 2 at grid pixel g, and the guide the reconstruction reads there.
        const GtaoPixel px = gtaoPixel(2 * g.x, 2 * g.y, interleaveIndex(g.x, g.y));
        const uint c = pixelIndex(g.x, g.y);
        tileDepth[s] = depthPlane[c];
        const vec3 n = loadNormal(c);
        tileNormal[0][s] = n.x;
        tileNormal[1][s] = n.y;
        tileNormal[2][s] = n.z;
        tileVisibility[s] = px.visibility;
        if (kBentNormal != 0) {
            tileBent[0][s] = px.bentNormal.x;
            tileBent[1][s] = px.bentNormal.y;
            tileBent[2][s] = px.bentNormal.z;
        }
    } else {
        tileDepth[s] = uintBitsToFloat(0x7f800000u);
    }
    barrier();
    // gtao_temporal.comp's main with kHistoryStep 2 at the inner pixels.
    const ivec2 p = outOrigin + l;
    if (l.x >= inner.x || l.y >= inner.y || p.x >= w || p.y >= h) return;
    const uint i = uint(p.y) * uint(w) + uint(p.x);
    const float depth = gridDepth(p.x, p.y);
    float spatial[4];
    reconstructInterleaved(p.x, p.y, w, h, kDepthSigma, kWindowPhase, spatial);
    accumulateLatticePixel(p, i, depth, spatial);
}
