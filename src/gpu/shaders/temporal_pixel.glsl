// The accumulation of gtao_temporal.comp (Jimenez, Wu, Pesce and Jarabo 2016, "Practical Realtime Strategies for
// Accurate Indirect Occlusion", §4.1): temporalPixel, the body of step 4 of ssao::GtaoTemporal::frame, with
// the camera and history helpers it reads, and accumulateLatticePixel, which runs it for one lattice pixel and
// writes the pass's outputs. gtao_temporal.comp's header compares it with src/ssao/gtao_temporal.cpp. One
// source for gtao_temporal.comp and gtao_temporal_fused.comp, which runs GTAO, the reconstruction and this in
// one dispatch.
//
// It declares the history's buffers, at kTemporalBindingPreviousDepth ... kTemporalBindingBentViewOut, which
// both shaders bind there. The including shader declares, before the #include: GtaoTemporalConstants k
// (temporal_layouts.h); the specialization constants kBentNormal, kPackedHistory, kDepthCopy and
// kPackedNormals and the constant kHistoryStep (temporal_layouts.h's kTemporalSpec*); the buffers depthPlane
// and normalWords; latticeWidth(), latticeHeight() and pixelIndex(x, y); and includes temporal_filters.glsl
// (finiteDepth) and normal_plane.glsl (loadNormal).
#ifndef OBSCURA_GPU_TEMPORAL_PIXEL_GLSL
#define OBSCURA_GPU_TEMPORAL_PIXEL_GLSL

#include "obscura/history_packing.h"

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
    // The four taps' history, loaded together before the tests below read it: tested as it arrived, a tap's
    // normal was asked for only once its depth had passed, and its visibility once its normal had, three round
    // trips to memory one after the other. The loads are clamped to the lattice; the tests still skip the taps
    // outside it and those of no weight, so the sums are the same. On an H100 (2026-11-27) the grid's
    // accumulation went to 0.873 / 0.919 of its time at 1920x1080 / 3840x2160 (its 5x5 window), 0.932 / 0.977
    // with the spatio-temporal target's flags, though it takes 8-9 more registers (39-40, from 30-32).
    float tapDepth[4], tapVisibility[4], tapLength[4];
    vec3 tapNormal[4], tapBent[4];
    [[unroll]] for (int t = 0; t < 4; ++t) {
        const int tx = clamp(x0 + (t & 1), 0, w - 1), ty = clamp(y0 + (t >> 1), 0, h - 1);
        const uint ti = uint(ty) * uint(w) + uint(tx);
        tapDepth[t] = previousDepthAt(ti, tx, ty);
        tapNormal[t] = previousNormalWorldAt(ti);
        tapVisibility[t] = previousVisibilityAt(ti);
        tapLength[t] = previousLengthAt(ti);
        tapBent[t] = kBentNormal != 0 ? previousBentWorldAt(ti) : vec3(0.0);
    }
    float weightSum = 0.0, historyVisibility = 0.0, historyLength = 0.0;
    vec3 historyBent = vec3(0.0);
    [[unroll]] for (int t = 0; t < 4; ++t) {
        const int tx = x0 + (t & 1), ty = y0 + (t >> 1);
        const float bw = ((t & 1) != 0 ? fx : 1.0 - fx) * ((t >> 1) != 0 ? fy : 1.0 - fy);
        if (bw <= 0.0 || tx < 0 || ty < 0 || tx >= w || ty >= h) continue;
        const float pd = tapDepth[t];
        // Disocclusion: the previous frame saw another surface there, or one facing elsewhere.
        if (!finiteDepth(pd) || abs(pd - expectedDepth) > k.rejectDepth * expectedDepth) continue;
        if (dot3(tapNormal[t], nWorld) < k.rejectNormalCos) continue;
        weightSum += bw;
        historyVisibility += bw * tapVisibility[t];
        if (kBentNormal != 0) historyBent += tapBent[t] * bw;
        historyLength += bw * tapLength[t];
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

// Lattice pixel p (element i of the history planes, of depth `depth`) from its filtered values spatial[0..3]
// (visibility, view bent normal): main's last lines, after its filter, which the CPU frame's step 4 and its
// copies for the next frame are: the accumulation, the view bent normal and the writes of every output.
void accumulateLatticePixel(ivec2 p, uint i, float depth, float spatial[4]) {
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

#endif
