// The square cross-bilateral blur of "Where Corners Stay Dark" (Alchemy SSAO in an IBL renderer) as one
// compute pass, one invocation per pixel: a (2 radius + 1)^2 window weighted by the spatial Gaussian, the
// relative depth Gaussian and max(0, N . N_t).
//
// The CPU reference is ssao::bilateral2D (src/ssao/bilateral.cpp, pass2D and accumulateTaps): the same
// taps in the same order (rows ty, then columns tx), the same weights and the same keep rule. The
// differences: the depth weight is the GPU's exp2 of the separable pass's depthScale form (the same value
// as the CPU's degree-6 polynomial exp to a relative 2e-5), and sky taps weigh exactly 0 instead of 2^-125.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "layouts.h"
#include "lighting_layouts.h"

layout(local_size_x = kBilateral2DWorkgroupX, local_size_y = kBilateral2DWorkgroupY, local_size_z = 1) in;

layout(constant_id = kBilateralSpecUseNormal) const int kUseNormal = 1;  // = k.useNormal (layouts.h)

layout(push_constant, std430) uniform Constants { BilateralConstants k; };
layout(std430, binding = kBilateralBindingDepth) readonly buffer DepthPlane { float depth[]; };
layout(constant_id = kBilateralSpecPackedNormals) const int kPackedNormals = 0;
layout(std430, binding = kBilateralBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };
layout(std430, binding = kBilateral2DBindingKernel) readonly buffer Kernel { float kernel[]; };
layout(std430, binding = kBilateralBindingInput) readonly buffer Input { float aoIn[]; };
layout(std430, binding = kBilateralBindingOutput) writeonly buffer Output { float aoOut[]; };

#include "bilateral_guide.glsl"
#include "normal_plane.glsl"

vec3 normalAt(uint i) { return loadNormal(i); }

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= k.width || p.y >= k.height) return;
    const uint x = uint(p.y) * uint(k.width) + uint(p.x);
    const float d = depth[bilateralGuideIndex(p.x, p.y)];
    // A centre on sky keeps its input (its weights would be 0 / 0).
    if (!(d < 1e30)) {
        aoOut[x] = aoIn[x];
        return;
    }
    const float c = k.depthScale / (d * d);  // 0 on sky: its output is its input anyway
    const vec3 n = kUseNormal != 0 ? normalAt(bilateralGuideIndex(p.x, p.y)) : vec3(0.0);
    float sum = 0.0, wsum = 0.0;
    for (int ty = max(-k.radius, -p.y); ty <= min(k.radius, k.height - 1 - p.y); ++ty) {
        const float ky = kernel[abs(ty)];
        for (int tx = max(-k.radius, -p.x); tx <= min(k.radius, k.width - 1 - p.x); ++tx) {
            const uint o = uint((p.y + ty) * k.width + p.x + tx);
            const uint g = bilateralGuideIndex(p.x + tx, p.y + ty);
            const float dd = depth[g] - d;
            float w = kernel[abs(tx)] * ky * exp2(-dd * dd * c);
            if (kUseNormal != 0) w *= max(0.0, dot(n, normalAt(g)));
            sum += w * aoIn[o];
            wsum += w;
        }
    }
    // No weight is impossible for a surface (its own tap counts); kept as the CPU keeps it.
    aoOut[x] = wsum > 0.0 ? sum / wsum : aoIn[x];
}
