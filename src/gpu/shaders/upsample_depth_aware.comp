// Depth-aware upsampling of half-resolution GTAO: Jimenez, Wu, Pesce and Jarabo 2016, "Practical Realtime
// Strategies for Accurate Indirect Occlusion", §4.1 (evaluation at half resolution), as a pass of its own:
// one invocation per full-resolution pixel; 1 or 3 channels by specialization constant. The filter is
// temporal_filters.glsl's upsampleDepthAware; here the low-resolution depth is a guide plane read at a
// stride (temporal_layouts.h), and `low` and `outValues` are the buffers below.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "temporal_layouts.h"

layout(local_size_x = kTemporalWorkgroupX, local_size_y = kTemporalWorkgroupY, local_size_z = 1) in;

layout(constant_id = kUpsampleSpecChannels) const int kGridChannels = 1;

layout(push_constant, std430) uniform Constants { UpsampleConstants k; };
layout(std430, binding = kUpsampleBindingLow) readonly buffer Low { float low[]; };
layout(std430, binding = kUpsampleBindingLowDepth) readonly buffer LowDepth { float lowDepthPlane[]; };
layout(std430, binding = kUpsampleBindingDepth) readonly buffer DepthPlane { float depthPlane[]; };
layout(std430, binding = kUpsampleBindingOutput) writeonly buffer Output { float outValues[]; };

float gridDepth(int x, int y) {
    return lowDepthPlane[uint(y * k.guideStep) * uint(k.guideWidth) + uint(x * k.guideStep)];
}
vec3 gridNormal(int x, int y) { return vec3(0.0); }  // the upsampling weighs by depth alone
float gridValue(int x, int y, int c) {
    return low[(uint(y) * uint(k.lowWidth) + uint(x)) * uint(kGridChannels) + uint(c)];
}

#include "temporal_filters.glsl"

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= k.width || p.y >= k.height) return;
    float result[4];
    const float d = depthPlane[uint(p.y) * uint(k.width) + uint(p.x)];
    upsampleDepthAware(p.x, p.y, d, k.lowWidth, k.lowHeight, k.depthSigma, result);
    const uint i = (uint(p.y) * uint(k.width) + uint(p.x)) * uint(kGridChannels);
    for (int c = 0; c < kGridChannels; ++c) outValues[i + uint(c)] = result[c];
}
