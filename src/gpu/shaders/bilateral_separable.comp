// One 1-D pass of the separable cross-bilateral blur: McGuire et al. 2011, "The Alchemy Screen-Space Ambient
// Obscurance Algorithm", Fig. 6 (horizontal, then vertical), as a compute pass; one invocation per pixel.
//
// The CPU reference is src/ssao/bilateral_separable.cpp; beginCentres, addTap and finishCentres below are
// its functions of the same names for one centre instead of eight. The differences: exp2 is the GPU's
// instead of a degree-3 polynomial (relative error 7.5e-5), and taps outside the image are skipped instead
// of read as sky padding that weighs 2^-125.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "layouts.h"

layout(local_size_x = kBilateralWorkgroupX, local_size_y = kBilateralWorkgroupY, local_size_z = 1) in;

layout(constant_id = kBilateralSpecUseNormal) const int kUseNormal = 0;  // = k.useNormal (layouts.h)

layout(push_constant, std430) uniform Constants { BilateralConstants k; };
layout(std430, binding = kBilateralBindingDepth) readonly buffer DepthPlane { float depth[]; };
layout(std430, binding = kBilateralBindingNormal) readonly buffer NormalPlane { float normal[]; };
layout(std430, binding = kBilateralBindingLogSpatial) readonly buffer Spatial { float logSpatial[]; };
layout(std430, binding = kBilateralBindingInput) readonly buffer Input { float aoIn[]; };
layout(std430, binding = kBilateralBindingOutput) writeonly buffer Output { float aoOut[]; };

// The running state of a centre.
struct Centre {
    float d, c;
    vec3 n;
    float sum, wsum;
};

Centre beginCentres(uint x) {
    Centre q;
    q.d = depth[x];
    q.c = k.depthScale / (q.d * q.d);  // 0 on sky: its output is its input anyway
    q.n = kUseNormal != 0 ? vec3(normal[3 * x], normal[3 * x + 1], normal[3 * x + 2]) : vec3(0.0);
    q.sum = 0.0;
    q.wsum = 0.0;
    return q;
}

void addTap(inout Centre q, uint o, float logSpatial) {
    const float dd = depth[o] - q.d;
    float w = exp2(logSpatial - dd * dd * q.c);
    if (kUseNormal != 0) w *= max(0.0, dot(q.n, vec3(normal[3 * o], normal[3 * o + 1], normal[3 * o + 2])));
    q.sum += w * aoIn[o];
    q.wsum += w;
}

// A centre on sky or with no weight (impossible for a surface: its own tap counts) keeps its input.
void finishCentres(Centre q, uint x) {
    const bool keep = q.d < 1e30 && q.wsum > 0.0;
    aoOut[x] = keep ? q.sum / q.wsum : aoIn[x];
}

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= k.width || p.y >= k.height) return;
    const uint x = uint(p.y) * uint(k.width) + uint(p.x);
    // Taps inside the image along the axis: t in [tFirst, tLast], t * stride apart in memory.
    const int along = k.axis == 0 ? p.x : p.y, length = k.axis == 0 ? k.width : k.height;
    const int stride = k.axis == 0 ? 1 : k.width;
    const int tFirst = max(-k.radius, -along), tLast = min(k.radius, length - 1 - along);
    Centre q = beginCentres(x);
    for (int t = tFirst; t <= tLast; ++t) addTap(q, uint(int(x) + t * stride), logSpatial[t + k.radius]);
    finishCentres(q, x);
}
