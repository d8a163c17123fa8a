// The 4x4 interleave reconstruction of spatio-temporal GTAO: Jimenez, Wu, Pesce and Jarabo 2016, "Practical
// Realtime Strategies for Accurate Indirect Occlusion", §4.1 (the depth-aware spatial denoiser over the 4x4
// pattern). One invocation per grid pixel; 1 or 3 channels by specialization constant.
//
// reconstructInterleaved below is src/ssao/gtao_temporal.cpp's loop body line for line, and tapWeight is
// ssao::tapWeight (obscura/bilateral.h) with useNormal set; read them side by side. The differences are
// GLSL's: dot is written out as the C++ one computes it, finiteDepth reads `< 1e30` as the CPU does, and
// the grid's depth and normals are guide planes read at a stride (temporal_layouts.h), `values` and `out`
// are the buffers below. What remains is the GPU's exp.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "temporal_layouts.h"

layout(local_size_x = kTemporalWorkgroupX, local_size_y = kTemporalWorkgroupY, local_size_z = 1) in;

layout(constant_id = kReconstructSpecChannels) const int kChannels = 1;

layout(push_constant, std430) uniform Constants { ReconstructConstants k; };
layout(std430, binding = kReconstructBindingValues) readonly buffer Values { float values[]; };
layout(std430, binding = kReconstructBindingDepth) readonly buffer DepthPlane { float depthPlane[]; };
layout(std430, binding = kReconstructBindingNormal) readonly buffer NormalPlane { float normalPlane[]; };
layout(std430, binding = kReconstructBindingOutput) writeonly buffer Output { float outValues[]; };

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

uint guide(int x, int y) { return uint(y * k.guideStep) * uint(k.guideWidth) + uint(x * k.guideStep); }
float depthAt(int x, int y) { return depthPlane[guide(x, y)]; }
vec3 normalAt(int x, int y) {
    const uint i = 3 * guide(x, y);
    return vec3(normalPlane[i], normalPlane[i + 1], normalPlane[i + 2]);
}
float valueAt(int x, int y, int c) { return values[(uint(y) * uint(k.width) + uint(x)) * uint(kChannels) + uint(c)]; }

// The output of pixel (x, y), channel by channel in result[0..kChannels).
void reconstructInterleaved(int x, int y, out float result[3]) {
    const int w = k.width, h = k.height;
    for (int c = 0; c < 3; ++c) result[c] = c < kChannels ? valueAt(x, y, c) : 0.0;  // Image out = values
    const float d = depthAt(x, y);
    if (!finiteDepth(d)) return;
    const vec3 n = normalAt(x, y);
    const float sigma = k.depthSigma * d;
    const float invTwoSigma2 = 1.0 / (2.0 * sigma * sigma);
    float sum[3] = float[3](0.0, 0.0, 0.0), weightSum = 0.0;
    for (int dy = -2; dy <= 2; ++dy) {
        const int yy = y + dy;
        if (yy < 0 || yy >= h) continue;
        for (int dx = -2; dx <= 2; ++dx) {
            const int xx = x + dx;
            if (xx < 0 || xx >= w) continue;
            const float di = depthAt(xx, yy);
            if (!finiteDepth(di)) continue;
            const float spatial = (dx == -2 || dx == 2 ? 0.5 : 1.0) * (dy == -2 || dy == 2 ? 0.5 : 1.0);
            const float wt = tapWeight(spatial, d, n, di, normalAt(xx, yy), invTwoSigma2, true);
            for (int c = 0; c < kChannels; ++c) sum[c] += wt * valueAt(xx, yy, c);
            weightSum += wt;
        }
    }
    if (!(weightSum > 0.0)) return;
    if (kChannels == 3) {
        const vec3 v = normalize3(vec3(sum[0], sum[1], sum[2]));
        if (dot3(v, v) > 0.0) result = float[3](v.x, v.y, v.z);
    } else {
        for (int c = 0; c < kChannels; ++c) result[c] = sum[c] / weightSum;
    }
}

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= k.width || p.y >= k.height) return;
    float result[3];
    reconstructInterleaved(p.x, p.y, result);
    const uint i = (uint(p.y) * uint(k.width) + uint(p.x)) * uint(kChannels);
    for (int c = 0; c < kChannels; ++c) outValues[i + uint(c)] = result[c];
}
