// Depth-aware upsampling of half-resolution GTAO: Jimenez, Wu, Pesce and Jarabo 2016, "Practical Realtime
// Strategies for Accurate Indirect Occlusion", §4.1 (evaluation at half resolution). One invocation per
// full-resolution pixel; 1 or 3 channels by specialization constant.
//
// upsampleDepthAware below is src/ssao/gtao_temporal.cpp's loop body line for line, and tapWeight is
// ssao::tapWeight (obscura/bilateral.h) with useNormal clear; read them side by side. The differences are
// GLSL's: std::fabs is abs, normalize is written out as the C++ one computes it, the low-resolution depth
// is a guide plane read at a stride (temporal_layouts.h). What remains is the GPU's exp.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "temporal_layouts.h"

layout(local_size_x = kTemporalWorkgroupX, local_size_y = kTemporalWorkgroupY, local_size_z = 1) in;

layout(constant_id = kUpsampleSpecChannels) const int kChannels = 1;

layout(push_constant, std430) uniform Constants { UpsampleConstants k; };
layout(std430, binding = kUpsampleBindingLow) readonly buffer Low { float low[]; };
layout(std430, binding = kUpsampleBindingLowDepth) readonly buffer LowDepth { float lowDepthPlane[]; };
layout(std430, binding = kUpsampleBindingDepth) readonly buffer DepthPlane { float depthPlane[]; };
layout(std430, binding = kUpsampleBindingOutput) writeonly buffer Output { float outValues[]; };

// ---- obscura/math.h ----
float dot3(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
vec3 normalize3(vec3 a) {
    const float l = sqrt(dot3(a, a));
    return l > 0.0 ? a / l : vec3(0.0);
}

// ---- obscura/bilateral.h ----
float tapWeight(float spatial, float d, vec3 n, float di, vec3 ni, float invTwoSigmaD2, bool useNormal) {
    float dd = di - d;
    float w = spatial * exp(-dd * dd * invTwoSigmaD2);
    if (useNormal) w *= max(0.0, dot3(n, ni));
    return w;
}

// ---- src/ssao/gtao_temporal.cpp ----
bool finiteDepth(float d) { return d < 1e30; }

float lowDepthAt(int x, int y) {
    return lowDepthPlane[uint(y * k.guideStep) * uint(k.guideWidth) + uint(x * k.guideStep)];
}
float lowAt(int x, int y, int c) { return low[(uint(y) * uint(k.lowWidth) + uint(x)) * uint(kChannels) + uint(c)]; }

// The output of pixel (x, y), channel by channel in result[0..kChannels).
void upsampleDepthAware(int x, int y, out float result[3]) {
    for (int c = 0; c < 3; ++c) result[c] = kChannels == 1 ? 1.0 : 0.0;  // Image out(w, h, channels, ...)
    const float d = depthPlane[uint(y) * uint(k.width) + uint(x)];
    if (!finiteDepth(d)) return;
    const float gx = 0.5 * float(x), gy = 0.5 * float(y);
    const int x0 = min(int(gx), k.lowWidth - 1), y0 = min(int(gy), k.lowHeight - 1);
    const int x1 = min(x0 + 1, k.lowWidth - 1), y1 = min(y0 + 1, k.lowHeight - 1);
    const float fx = gx - float(x0), fy = gy - float(y0);
    const int tx[4] = int[4](x0, x1, x0, x1), ty[4] = int[4](y0, y0, y1, y1);
    const float bilinear[4] = float[4]((1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy);
    const float sigma = k.depthSigma * d;
    const float invTwoSigma2 = 1.0 / (2.0 * sigma * sigma);
    float sum[3] = float[3](0.0, 0.0, 0.0), weightSum = 0.0, bestDiff = 1e30;
    int best = -1;
    for (int t = 0; t < 4; ++t) {
        const float di = lowDepthAt(tx[t], ty[t]);
        if (!finiteDepth(di)) continue;
        if (abs(di - d) < bestDiff) {
            bestDiff = abs(di - d);
            best = t;
        }
        if (bilinear[t] <= 0.0) continue;
        const float wt = tapWeight(bilinear[t], d, vec3(0.0), di, vec3(0.0), invTwoSigma2, false);
        for (int c = 0; c < kChannels; ++c) sum[c] += wt * lowAt(tx[t], ty[t], c);
        weightSum += wt;
    }
    if (best < 0) return;
    // No tap on this surface (a thin feature between the samples): take the closest in depth.
    if (!(weightSum > 1e-4)) {
        for (int c = 0; c < kChannels; ++c) result[c] = lowAt(tx[best], ty[best], c);
        return;
    }
    for (int c = 0; c < kChannels; ++c) result[c] = sum[c] / weightSum;
    if (kChannels == 3) {
        const vec3 v = normalize3(vec3(result[0], result[1], result[2]));
        result = float[3](v.x, v.y, v.z);
    }
}

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= k.width || p.y >= k.height) return;
    float result[3];
    upsampleDepthAware(p.x, p.y, result);
    const uint i = (uint(p.y) * uint(k.width) + uint(p.x)) * uint(kChannels);
    for (int c = 0; c < kChannels; ++c) outValues[i + uint(c)] = result[c];
}
