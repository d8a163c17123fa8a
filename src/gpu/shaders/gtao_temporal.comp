// The temporal accumulation of spatio-temporal GTAO: Jimenez, Wu, Pesce and Jarabo 2016, "Practical Realtime
// Strategies for Accurate Indirect Occlusion", §4.1 (reprojection into an exponential accumulation buffer
// that gathers the 6 per-frame rotations). One invocation per pixel of the history's lattice: every pixel, or
// with kHistoryStep 2 every pixel of the half-resolution grid.
//
// The pass starts with the spatial filter of its own lattice pixel (temporal_filters.glsl): at full
// resolution, and on the grid with kHistoryStep 2, the 4x4 reconstruction of the GTAO pass's raw interleaved
// values; at half resolution with the history at full resolution, the depth-aware upsampling of the
// reconstructed grid. The CPU writes the filtered planes and reads them back here; fused, they stay in
// registers, which removes the planes' round trip through memory and a pass with its barrier, and gives the
// same values (each pixel's filter reads only the grid, which no invocation here writes).
//
// temporalPixel (temporal_pixel.glsl) is the body of step 4 of ssao::GtaoTemporal::frame
// (src/ssao/gtao_temporal.cpp) line for line, with `return` for its `continue`; accumulateLatticePixel there
// adds the last loop (back to view space) and the copies the CPU makes of depth and world normals for the
// next frame. Read them side by side. The differences are
// GLSL's: dot and normalize are written out as the C++ ones compute them; the cameras are the push
// constants (temporal_layouts.h says which expression each field is), so viewPosition and pixelFromView are
// Camera::viewFromPixel and Camera::pixelFromView with the same operations in the same order;
// transformPoint omits the CPU's division by w, which is 1 exactly for these affine matrices and finite
// points; the history planes are the buffers `previous*`. Nothing transcendental is evaluated after the
// filter, so only contraction of a multiply-add by the GPU's compiler can round differently there.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "temporal_layouts.h"

layout(local_size_x = kAccumulationWorkgroupX, local_size_y = kAccumulationWorkgroupY, local_size_z = 1) in;

layout(constant_id = kTemporalSpecGridStep) const int kGridStep = 1;
layout(constant_id = kTemporalSpecDepthSigma) const float kDepthSigma = 0.05;
layout(constant_id = kTemporalSpecBentNormal) const int kBentNormal = 1;
layout(constant_id = kTemporalSpecPackedHistory) const int kPackedHistory = 0;
layout(constant_id = kTemporalSpecDepthCopy) const int kDepthCopy = 1;
layout(constant_id = kTemporalSpecHistoryStep) const int kHistoryStep = 1;
layout(constant_id = kTemporalSpecWindowPhase) const int kWindowPhase = -1;
layout(constant_id = kTemporalSpecPackedNormals) const int kPackedNormals = 0;

layout(push_constant, std430) uniform Constants { GtaoTemporalConstants k; };
layout(std430, binding = kTemporalBindingDepth) readonly buffer DepthPlane { float depthPlane[]; };
layout(std430, binding = kTemporalBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };
layout(std430, binding = kTemporalBindingGridVisibility) readonly buffer GridVisibility { float gridVisibility[]; };
layout(std430, binding = kTemporalBindingGridBent) readonly buffer GridBent { float gridBent[]; };

// ---- the grid the filter reads (temporal_filters.glsl): visibility, then the bent normal if any ----
const int kGridChannels = kBentNormal != 0 ? 4 : 1;
int gridWidth() { return (k.width + kGridStep - 1) / kGridStep; }
int gridHeight() { return (k.height + kGridStep - 1) / kGridStep; }
// The history's lattice, which the invocations cover: every pixel, or with kHistoryStep 2 the grid
// (temporal_layouts.h). The filter reconstructs a lattice pixel from the raw grid when the two are one,
// and upsamples it from the reconstructed grid when the lattice is the full image over a half-resolution grid.
const bool kReconstructs = kGridStep == kHistoryStep;
int latticeWidth() { return (k.width + kHistoryStep - 1) / kHistoryStep; }
int latticeHeight() { return (k.height + kHistoryStep - 1) / kHistoryStep; }
// The full-resolution pixel where lattice pixel (x, y) stands, as an index into the G-buffer's planes.
uint pixelIndex(int x, int y) { return uint(y * kHistoryStep) * uint(k.width) + uint(x * kHistoryStep); }
// The grid's depth and normals are the G-buffer's at every kGridStep-th pixel (temporal_layouts.h).
uint guide(int x, int y) { return uint(y * kGridStep) * uint(k.width) + uint(x * kGridStep); }
float gridDepthAt(int x, int y) { return depthPlane[guide(x, y)]; }
#include "normal_plane.glsl"
vec3 gridNormalAt(int x, int y) { return loadNormal(guide(x, y)); }
float gridValueAt(int x, int y, int c) {
    const uint i = uint(y) * uint(gridWidth()) + uint(x);
    return c == 0 ? gridVisibility[i] : gridBent[3 * i + uint(c - 1)];
}
// The reconstruction with the 5x5 and 4x4 windows reads the grid from a shared-memory tile (grid_tile.glsl):
// on an H100 (2026-11-25, visibility only, 1920x1080, full resolution) the pass took 0.086 ms instead of 0.136
// without history (the spatial variant) and 0.115 instead of 0.159 with it. The 2x2 windows gather 4 taps, all
// within one pixel of their own: they read them from memory, where the neighbouring invocations' reads leave
// them in the caches, without the tile's loads, its barrier and its shared memory (which costs resident
// workgroups); on the H100 (2026-11-26, the spatio-temporal target's flags) that took the grid's accumulation
// to 0.934 of the tiled time at 3840x2160 (0.0577 ms instead of 0.0618) and 0.926 at 1920x1080. The
// upsampling reads 4 grid pixels straight from memory too. Where the tile is not filled it is one slot.
const bool kTiled = kReconstructs && kWindowPhase < 4;
#define GRID_TILE_SLOTS (kTiled ? kGridTileHeight * kGridTileStride : 1)
#define GRID_OUTSIDE_IS_SKY kTiled  // only the tile marks the pixels outside the grid as sky
#include "grid_tile.glsl"
float gridDepth(int x, int y) { return kTiled ? gridTileDepth(x, y) : gridDepthAt(x, y); }
vec3 gridNormal(int x, int y) { return kTiled ? gridTileNormal(x, y) : gridNormalAt(x, y); }
float gridValue(int x, int y, int c) { return kTiled ? gridTileValue(x, y, c) : gridValueAt(x, y, c); }

#include "temporal_filters.glsl"
#include "temporal_pixel.glsl"

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    const int w = latticeWidth(), h = latticeHeight();
    if (kTiled) loadGridTile(w, h);
    if (p.x >= w || p.y >= h) return;
    const uint i = uint(p.y) * uint(w) + uint(p.x);
    const float depth = depthPlane[pixelIndex(p.x, p.y)];
    // Step 2 (full resolution, or the grid's history) or 3 (half) of the CPU frame, for this lattice pixel
    // alone: its filtered visibility and view bent normal.
    float spatial[4];
    if (kReconstructs)
        reconstructInterleaved(p.x, p.y, w, h, kDepthSigma, kWindowPhase, spatial);
    else if (!upsampleDepthAware(p.x, p.y, depth, gridWidth(), gridHeight(), kDepthSigma, spatial))
        setGridVector(spatial, normalize3(loadNormal(pixelIndex(p.x, p.y))));  // no surface among the taps
    accumulateLatticePixel(p, i, depth, spatial);
}
