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
// temporalPixel below is the body of step 4 of ssao::GtaoTemporal::frame (src/ssao/gtao_temporal.cpp) line
// for line, with `return` for its `continue`; main adds the last loop (back to view space) and the copies
// the CPU makes of depth and world normals for the next frame. Read them side by side. The differences are
// GLSL's: dot and normalize are written out as the C++ ones compute them; the cameras are the push
// constants (temporal_layouts.h says which expression each field is), so viewPosition and pixelFromView are
// Camera::viewFromPixel and Camera::pixelFromView with the same operations in the same order;
// transformPoint omits the CPU's division by w, which is 1 exactly for these affine matrices and finite
// points; the history planes are the buffers `previous*`. Nothing transcendental is evaluated after the
// filter, so only contraction of a multiply-add by the GPU's compiler can round differently there.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "temporal_layouts.h"

layout(local_size_x = kTemporalWorkgroupX, local_size_y = kTemporalWorkgroupY, local_size_z = 1) in;

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
// The history planes hold 32-bit words: floats' bits, or with kPackedHistory the packed words of
// obscura/history_packing.h (visibility + length in the visibility plane, one word per normal).
layout(std430, binding = kTemporalBindingPreviousDepth) readonly buffer PreviousDepth { uint previousDepth[]; };
layout(std430, binding = kTemporalBindingPreviousNormalWorld) readonly buffer PreviousNormalWorld {
    uint previousNormalWorld[];
};
layout(std430, binding = kTemporalBindingPreviousVisibility) readonly buffer PreviousVisibility {
    uint previousVisibility[];
};
layout(std430, binding = kTemporalBindingPreviousBentWorld) readonly buffer PreviousBentWorld {
    uint previousBentWorld[];
};
layout(std430, binding = kTemporalBindingPreviousLength) readonly buffer PreviousLength { uint previousLength[]; };
layout(std430, binding = kTemporalBindingDepthOut) writeonly buffer DepthOut { uint depthOut[]; };
layout(std430, binding = kTemporalBindingNormalWorldOut) writeonly buffer NormalWorldOut { uint normalWorldOut[]; };
layout(std430, binding = kTemporalBindingVisibilityOut) writeonly buffer VisibilityOut { uint visibilityOut[]; };
layout(std430, binding = kTemporalBindingBentWorldOut) writeonly buffer BentWorldOut { uint bentWorldOut[]; };
layout(std430, binding = kTemporalBindingLengthOut) writeonly buffer LengthOut { uint lengthOut[]; };
layout(std430, binding = kTemporalBindingBentViewOut) writeonly buffer BentViewOut { float bentViewOut[]; };

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
// The reconstruction reads the grid from a shared-memory tile (grid_tile.glsl): on an H100 (2026-11-25,
// visibility only, 1920x1080, full resolution) the pass took 0.086 ms instead of 0.136 without history (the
// spatial variant) and 0.115 instead of 0.159 with it. The upsampling reads 4 grid pixels straight from
// memory, with a tile of one slot.
#define GRID_TILE_SLOTS (kReconstructs ? kGridTileHeight * kGridTileStride : 1)
#define GRID_TILE_REACH (kWindowPhase >= 4 ? 1 : 2)  // the 2x2 windows reach 1 (obscura/reconstruct_window.h)
#include "grid_tile.glsl"
float gridDepth(int x, int y) { return kReconstructs ? gridTileDepth(x, y) : gridDepthAt(x, y); }
vec3 gridNormal(int x, int y) { return kReconstructs ? gridTileNormal(x, y) : gridNormalAt(x, y); }
float gridValue(int x, int y, int c) { return kReconstructs ? gridTileValue(x, y, c) : gridValueAt(x, y, c); }

#include "temporal_filters.glsl"
#include "obscura/history_packing.h"

// ---- obscura/math.h ----
// transformVector(m, v) for a matrix given as 3 rows of 4 floats.
vec3 transformVector(float m[12], vec3 v) {
    return vec3(m[0] * v.x + m[1] * v.y + m[2] * v.z, m[4] * v.x + m[5] * v.y + m[6] * v.z,
                m[8] * v.x + m[9] * v.y + m[10] * v.z);
}
vec3 transformPoint(float m[12], vec3 p) {
    return vec3(m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3], m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
                m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]);
}
// transformVector(viewFromWorld, v): viewFromWorld's rotation is worldFromView's transposed.
vec3 viewFromWorldVector(vec3 v) {
    return vec3(k.worldFromView[0] * v.x + k.worldFromView[4] * v.y + k.worldFromView[8] * v.z,
                k.worldFromView[1] * v.x + k.worldFromView[5] * v.y + k.worldFromView[9] * v.z,
                k.worldFromView[2] * v.x + k.worldFromView[6] * v.y + k.worldFromView[10] * v.z);
}

// ---- obscura/camera.h ----
// g.viewPosition(x, y): Camera::viewFromPixel at the pixel's centre.
vec3 viewPosition(int x, int y, float depth) {
    const float px = float(x) + 0.5, py = float(y) + 0.5;
    const float t = k.tanHalfFovY;
    const float ndcX = 2.0 * px / float(k.width) - 1.0;
    const float ndcY = 1.0 - 2.0 * py / float(k.height);
    return vec3(ndcX * t * k.aspect * depth, ndcY * t * depth, -depth);
}
// previousCamera_.pixelFromView(p, &depth).
vec2 previousPixelFromView(vec3 p, out float depth) {
    const float d = -p.z;
    depth = d;
    const float t = k.previousTanHalfFovY;
    const float ndcX = p.x / (d * t * k.aspect);
    const float ndcY = p.y / (d * t);
    return vec2((ndcX + 1.0) * 0.5 * float(k.width), (1.0 - ndcY) * 0.5 * float(k.height));
}

// ---- src/ssao/gtao_temporal.cpp: the history images, read from their planes ----
// previousDepth_, previousNormalWorld_, accumulated_, bentWorld_ and historyLength_ at lattice pixel i. With
// kPackedHistory the CPU stores the values the packed words decode to, so both read the same floats.
// previousDepth_ is the history's copy (kDepthCopy), of the lattice's size, or the caller's depth buffer of
// the last frame, of the full size, read where lattice pixel (x, y) stands.
float previousDepthAt(uint i, int x, int y) {
    return uintBitsToFloat(previousDepth[kDepthCopy != 0 ? i : pixelIndex(x, y)]);
}
vec3 previousNormalWorldAt(uint i) {
    if (kPackedHistory != 0) return unpackOctahedral(previousNormalWorld[i]);
    return uintBitsToFloat(uvec3(previousNormalWorld[3 * i], previousNormalWorld[3 * i + 1], previousNormalWorld[3 * i + 2]));
}
vec3 previousBentWorldAt(uint i) {
    if (kPackedHistory != 0) return unpackOctahedral(previousBentWorld[i]);
    return uintBitsToFloat(uvec3(previousBentWorld[3 * i], previousBentWorld[3 * i + 1], previousBentWorld[3 * i + 2]));
}
float previousVisibilityAt(uint i) {
    return kPackedHistory != 0 ? unpackVisibility(previousVisibility[i]) : uintBitsToFloat(previousVisibility[i]);
}
float previousLengthAt(uint i) {
    return kPackedHistory != 0 ? unpackLength(previousVisibility[i]) : uintBitsToFloat(previousLength[i]);
}

// Pixel (x, y) of the loop: `visibility` comes in as the spatial result and leaves accumulated, `bent` is
// the spatial result's view bent normal; the other three come in as the CPU's initial values (0, 1, 0).
// Without bent normals (kBentNormal 0) their lines are skipped; nothing else reads them.
// (x, y) is a lattice pixel, standing at pixel (px, py) = (kHistoryStep x, kHistoryStep y).
void temporalPixel(int x, int y, vec3 bent, inout float visibility, inout vec3 newBentWorld, inout float newLength,
                   inout vec3 normalWorld) {
    const int w = latticeWidth(), h = latticeHeight();
    const uint pi = pixelIndex(x, y);
    const float depth = depthPlane[pi];
    if (!finiteDepth(depth)) return;  // g.isSky(px, py)
    const vec3 viewNormal = loadNormal(pi);
    const vec3 nWorld = normalize3(transformVector(k.worldFromView, viewNormal));
    normalWorld = nWorld;
    vec3 currentBent = normalize3(transformVector(k.worldFromView, bent));
    newBentWorld = currentBent;
    if (k.maxHistory == 0.0) return;  // !useHistory
    const vec3 world = transformPoint(k.worldFromView, viewPosition(kHistoryStep * x, kHistoryStep * y, depth));
    float expectedDepth = 0.0;
    const vec2 prev = previousPixelFromView(transformPoint(k.previousViewFromWorld, world), expectedDepth);
    if (!(expectedDepth > 0.0)) return;
    // Scaled by 1 or 1/2, exact either way, as the CPU scales (a division need not be correctly rounded).
    const float toLattice = kHistoryStep == 1 ? 1.0 : 0.5;
    const float gx = (prev.x - 0.5) * toLattice, gy = (prev.y - 0.5) * toLattice;
    const int x0 = int(floor(gx)), y0 = int(floor(gy));
    const float fx = gx - float(x0), fy = gy - float(y0);
    float weightSum = 0.0, historyVisibility = 0.0, historyLength = 0.0;
    vec3 historyBent = vec3(0.0);
    for (int t = 0; t < 4; ++t) {
        const int tx = x0 + (t & 1), ty = y0 + (t >> 1);
        const float bw = ((t & 1) != 0 ? fx : 1.0 - fx) * ((t >> 1) != 0 ? fy : 1.0 - fy);
        if (bw <= 0.0 || tx < 0 || ty < 0 || tx >= w || ty >= h) continue;
        const uint ti = uint(ty) * uint(w) + uint(tx);
        const float pd = previousDepthAt(ti, tx, ty);
        // Disocclusion: the previous frame saw another surface there, or one facing elsewhere.
        if (!finiteDepth(pd) || abs(pd - expectedDepth) > k.rejectDepth * expectedDepth) continue;
        if (dot3(previousNormalWorldAt(ti), nWorld) < k.rejectNormalCos) continue;
        weightSum += bw;
        historyVisibility += bw * previousVisibilityAt(ti);
        if (kBentNormal != 0) historyBent += previousBentWorldAt(ti) * bw;
        historyLength += bw * previousLengthAt(ti);
    }
    // Less than a quarter of the footprint confirmed: too little to trust.
    if (weightSum < 0.25) return;
    historyVisibility /= weightSum;
    historyLength /= weightSum;
    historyBent = historyBent / weightSum;
    const float alpha = 1.0 / min(historyLength + 1.0, k.maxHistory);
    visibility = historyVisibility + (visibility - historyVisibility) * alpha;
    if (kBentNormal != 0) {
        vec3 blended = normalize3(historyBent + (currentBent - historyBent) * alpha);
        if (dot3(blended, blended) > 0.0) newBentWorld = blended;
    }
    newLength = min(historyLength + 1.0, k.maxHistory);
}

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    const int w = latticeWidth(), h = latticeHeight();
    if (kReconstructs) loadGridTile(w, h);
    if (p.x >= w || p.y >= h) return;
    const uint i = uint(p.y) * uint(w) + uint(p.x);
    const float depth = depthPlane[pixelIndex(p.x, p.y)];
    // Step 2 (full resolution, or the grid's history) or 3 (half) of the CPU frame, for this lattice pixel
    // alone: its filtered visibility and view bent normal.
    float spatial[4];
    if (kReconstructs)
        reconstructInterleaved(p.x, p.y, w, h, kDepthSigma, kWindowPhase, spatial);
    else
        upsampleDepthAware(p.x, p.y, depth, gridWidth(), gridHeight(), kDepthSigma, spatial);
    float visibility = spatial[0];
    vec3 newBentWorld = vec3(0.0), normalWorld = vec3(0.0);
    float newLength = 1.0;
    temporalPixel(p.x, p.y, vec3(spatial[1], spatial[2], spatial[3]), visibility, newBentWorld, newLength,
                  normalWorld);
    // result_.bentNormal: sky pixels 0, the others back in view space.
    const vec3 bentView = finiteDepth(depth) ? normalize3(viewFromWorldVector(newBentWorld)) : vec3(0.0);
    if (kDepthCopy != 0) depthOut[i] = floatBitsToUint(depth);  // previousDepth_ = g.depth, or the grid's depth
    if (kBentNormal != 0)
        for (uint c = 0; c < 3; ++c) bentViewOut[3 * i + c] = bentView[c];
    if (kPackedHistory != 0) {
        visibilityOut[i] = packVisibilityLength(visibility, newLength);
        normalWorldOut[i] = packOctahedral(normalWorld);
        if (kBentNormal != 0) bentWorldOut[i] = packOctahedral(newBentWorld);
        return;
    }
    visibilityOut[i] = floatBitsToUint(visibility);
    lengthOut[i] = floatBitsToUint(newLength);
    for (uint c = 0; c < 3; ++c) normalWorldOut[3 * i + c] = floatBitsToUint(normalWorld[c]);
    if (kBentNormal != 0)
        for (uint c = 0; c < 3; ++c) bentWorldOut[3 * i + c] = floatBitsToUint(newBentWorld[c]);
}
