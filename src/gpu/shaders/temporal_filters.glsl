// The two spatial filters of spatio-temporal GTAO: Jimenez, Wu, Pesce and Jarabo 2016, "Practical Realtime
// Strategies for Accurate Indirect Occlusion", §4.1 (the depth-aware gather over the 4x4 pattern, and
// evaluation at half resolution). One source for reconstruct_interleaved.comp and upsample_depth_aware.comp,
// which run a filter as a pass of its own, and gtao_temporal.comp, which runs it for its own pixel inside
// the accumulation, so that the filtered planes never go through memory.
//
// reconstructInterleaved and upsampleDepthAware are the loop bodies of the functions of those names in
// src/ssao/gtao_temporal.cpp line for line, and tapWeight is ssao::tapWeight (obscura/bilateral.h); read them
// side by side. The differences are GLSL's: dot and normalize are written out as the C++ ones compute them,
// std::fabs is abs, finiteDepth reads `< 1e30` as the CPU does, and one call filters several channels with
// the same weights, where the CPU calls once per image (each channel's arithmetic is the same). What remains
// is the GPU's exp.
//
// The including shader declares, before the #include, the grid the filters read:
//   kGridChannels                  1 (visibility), 3 (a bent normal) or 4 (visibility, then the bent normal)
//   float gridDepth(int x, int y)  linear depth of grid pixel (x, y), +inf for sky
//   vec3 gridNormal(int x, int y)  its view normal (the reconstruction's guide; the upsampling reads none)
//   float gridValue(int x, int y, int c)
// and may define GRID_OUTSIDE_IS_SKY as an expression of its specialization constants that is true where
// gridDepth gives +inf for the pixels just outside the grid (a shared-memory tile whose apron is marked so):
// the reconstruction's taps then skip them by their sky test and need no bounds tests.
#ifndef OBSCURA_GPU_TEMPORAL_FILTERS_GLSL
#define OBSCURA_GPU_TEMPORAL_FILTERS_GLSL

#include "obscura/reconstruct_window.h"

#include "vector_math.glsl"  // ---- obscura/math.h ----

#ifndef GRID_OUTSIDE_IS_SKY
#define GRID_OUTSIDE_IS_SKY false
#endif
// On an H100 (2026-11-26) leaving the bounds tests to the sky test took the grid's accumulation with the 5x5
// window to 0.941 of its time at 1920x1080 and 0.949 at 3840x2160: only workgroups at the image's border
// ever find a tap outside, and every tap paid for the tests.
const bool kGridOutsideIsSky = GRID_OUTSIDE_IS_SKY;

// ---- obscura/bilateral.h ----
float tapWeight(float spatial, float d, vec3 n, float di, vec3 ni, float invTwoSigmaD2, bool useNormal) {
    float dd = di - d;
    float w = spatial * exp(-dd * dd * invTwoSigmaD2);
    if (useNormal) w *= max(0.0, dot3(n, ni));
    return w;
}

// ---- src/ssao/gtao_temporal.cpp ----
bool finiteDepth(float d) { return d < 1e30; }

// The channels are a scalar (visibility) unless kGridChannels is 3, and a unit vector from channel
// kGridChannels - 3 on when kGridChannels is 3 or 4.
const bool kGridScalar = kGridChannels != 3;
const bool kGridVector = kGridChannels >= 3;
const int kGridVectorFirst = kGridChannels - 3;

// The reconstruction of grid pixel (x, y) of a w x h grid, channel by channel in result[0..kGridChannels).
// windowPhase -1 gathers the 5x5 window, 0..3 the 4x4 window of that phase, 4..7 the 2x2 one
// (obscura/reconstruct_window.h, ssao::reconstructInterleaved);
// the callers pass a specialization constant, so the loops' bounds are known when the pipeline is made.
void reconstructInterleaved(int x, int y, int w, int h, float depthSigma, int windowPhase, out float result[4]) {
    for (int c = 0; c < 4; ++c) result[c] = c < kGridChannels ? gridValue(x, y, c) : 0.0;  // Image out = values
    const float d = gridDepth(x, y);
    if (!finiteDepth(d)) return;
    const vec3 n = gridNormal(x, y);
    const float sigma = depthSigma * d;
    const float invTwoSigma2 = 1.0 / (2.0 * sigma * sigma);
    const int side = reconstructWindowSide(windowPhase);
    const int firstX = reconstructWindowFirst(windowPhase, 0), lastX = firstX + side - 1;
    const int firstY = reconstructWindowFirst(windowPhase, 1), lastY = firstY + side - 1;
    float sum[4] = float[4](0.0, 0.0, 0.0, 0.0), weightSum = 0.0;
    for (int dy = firstY; dy <= lastY; ++dy) {
        const int yy = y + dy;
        if (!kGridOutsideIsSky && (yy < 0 || yy >= h)) continue;
        for (int dx = firstX; dx <= lastX; ++dx) {
            const int xx = x + dx;
            if (!kGridOutsideIsSky && (xx < 0 || xx >= w)) continue;
            // Outside the grid with kGridOutsideIsSky: +inf, skipped here as the CPU's bounds test skips it.
            const float di = gridDepth(xx, yy);
            if (!finiteDepth(di)) continue;
            const float spatial = reconstructWindowWeight(windowPhase, dx, dy);
            const float wt = tapWeight(spatial, d, n, di, gridNormal(xx, yy), invTwoSigma2, true);
            for (int c = 0; c < kGridChannels; ++c) sum[c] += wt * gridValue(xx, yy, c);
            weightSum += wt;
        }
    }
    if (!(weightSum > 0.0)) return;
    if (kGridScalar) result[0] = sum[0] / weightSum;
    if (kGridVector) {
        const int b = kGridVectorFirst;
        const vec3 v = normalize3(vec3(sum[b], sum[b + 1], sum[b + 2]));
        if (dot3(v, v) > 0.0) {
            result[b] = v.x;
            result[b + 1] = v.y;
            result[b + 2] = v.z;
        }
    }
}

// The bent normal, result[kGridVectorFirst..+3), set to v (no-op without one).
void setGridVector(inout float result[4], vec3 v) {
    if (!kGridVector) return;
    const int b = kGridVectorFirst;
    result[b] = v.x;
    result[b + 1] = v.y;
    result[b + 2] = v.z;
}

// The upsampling's bent normal, result[kGridVectorFirst..+3), renormalized in place (no-op without one).
void normalizeGridVector(inout float result[4]) {
    if (!kGridVector) return;
    const int b = kGridVectorFirst;
    const vec3 v = normalize3(vec3(result[b], result[b + 1], result[b + 2]));
    result[b] = v.x;
    result[b + 1] = v.y;
    result[b + 2] = v.z;
}

// The upsampling of upsampleDepthAware below, past the taps' positions: grid pixels x0..x1 x y0..y1 and the
// pixel's place fx, fy between them. A caller that knows them without the conversions (a 2x2 block's
// invocation) calls it directly. False where the pixel is a surface but none of its taps is: a feature
// thinner than the grid's spacing against the sky. The CPU gives such a pixel visibility 1 (result holds it)
// and its own view normal, normalized, as the bent normal, which only the caller can read: it calls
// setGridVector(result, normalize3(its normal)) with a bent normal among the channels.
bool upsampleDepthAwareAt(int x0, int y0, int x1, int y1, float fx, float fy, float d, float depthSigma,
                          out float result[4]) {
    // Image out(w, h, channels, channels == 1 ? 1 : 0): an unoccluded sky, no bent normal.
    for (int c = 0; c < 4; ++c) result[c] = kGridScalar && c == 0 ? 1.0 : 0.0;
    if (!finiteDepth(d)) return true;
    const int tx[4] = int[4](x0, x1, x0, x1), ty[4] = int[4](y0, y0, y1, y1);
    const float bilinear[4] = float[4]((1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy);
    const float sigma = depthSigma * d;
    // A pixel that stands on a grid pixel of its own depth (every other pixel of every other row, where the
    // grid's depth is the G-buffer's): its only tap with a bilinear weight is that grid pixel, weighted
    // 1 * exp(-0 * invTwoSigma2) = 1 exactly, so the loop below would return that pixel's values (the vector
    // renormalized), with no rounding on the way. Taken here without the exp and the two divisions, the
    // same bits. 2 sigma^2 must be a normal float for invTwoSigma2 to be finite (else the loop's weight is NaN).
    // On an H200 (2026-11-26, 3 rounds in one run) the upsampling took 0.952-0.978 of its time without this
    // copy in gtao-half and gtao-temporal-grid at 1920x1080 and 3840x2160 (0.0443 -> 0.0422 ms at 3840x2160
    // with the spatio-temporal target's flags).
    const float twoSigma2 = 2.0 * sigma * sigma;
    if (fx == 0.0 && fy == 0.0 && gridDepth(x0, y0) == d && twoSigma2 >= 1.17549435e-38) {
        for (int c = 0; c < kGridChannels; ++c) result[c] = gridValue(x0, y0, c);
        normalizeGridVector(result);
        return true;
    }
    const float invTwoSigma2 = 1.0 / twoSigma2;
    float sum[4] = float[4](0.0, 0.0, 0.0, 0.0), weightSum = 0.0, bestDiff = 1e30;
    int best = -1;
    for (int t = 0; t < 4; ++t) {
        const float di = gridDepth(tx[t], ty[t]);
        if (!finiteDepth(di)) continue;
        if (abs(di - d) < bestDiff) {
            bestDiff = abs(di - d);
            best = t;
        }
        if (bilinear[t] <= 0.0) continue;
        const float wt = tapWeight(bilinear[t], d, vec3(0.0), di, vec3(0.0), invTwoSigma2, false);
        for (int c = 0; c < kGridChannels; ++c) sum[c] += wt * gridValue(tx[t], ty[t], c);
        weightSum += wt;
    }
    if (best < 0) return false;
    // No tap on this surface (a thin feature between the samples): take the closest in depth.
    if (!(weightSum > 1e-4)) {
        for (int c = 0; c < kGridChannels; ++c) result[c] = gridValue(tx[best], ty[best], c);
        return true;
    }
    for (int c = 0; c < kGridChannels; ++c) result[c] = sum[c] / weightSum;
    normalizeGridVector(result);
    return true;
}

// The upsampling to full-resolution pixel (x, y) of depth d from the lowWidth x lowHeight grid, channel by
// channel in result[0..kGridChannels). False as upsampleDepthAwareAt.
bool upsampleDepthAware(int x, int y, float d, int lowWidth, int lowHeight, float depthSigma, out float result[4]) {
    const float gx = 0.5 * float(x), gy = 0.5 * float(y);
    const int x0 = min(int(gx), lowWidth - 1), y0 = min(int(gy), lowHeight - 1);
    const int x1 = min(x0 + 1, lowWidth - 1), y1 = min(y0 + 1, lowHeight - 1);
    const float fx = gx - float(x0), fy = gy - float(y0);
    return upsampleDepthAwareAt(x0, y0, x1, y1, fx, fy, d, depthSigma, result);
}

#endif
