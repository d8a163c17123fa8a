// Multi-bounce AO: Jimenez et al. 2016, "Practical Realtime Strategies for Accurate Indirect Occlusion",
// §5, eq. 10, per pixel and colour channel; one invocation per pixel. multiBounce below is
// ssao::multiBounce (include/obscura/multibounce.h) term for term; sky pixels get 1, as the CLI's GTAO
// frame does.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lighting_layouts.h"

layout(local_size_x = kLightingWorkgroupX, local_size_y = kLightingWorkgroupY, local_size_z = 1) in;

layout(push_constant, std430) uniform Constants { MultiBounceConstants k; };
layout(std430, binding = kMultiBounceBindingDepth) readonly buffer DepthPlane { float depth[]; };
layout(std430, binding = kMultiBounceBindingVisibility) readonly buffer Visibility { float visibility[]; };
layout(std430, binding = kMultiBounceBindingAlbedo) readonly buffer Albedo { float albedo[]; };
layout(std430, binding = kMultiBounceBindingOutput) writeonly buffer Output { float result[]; };

float multiBounce(float ao, float rho) {
    const float a = 2.0404 * rho - 0.3324;
    const float b = 4.7951 * rho - 0.6417;
    const float c = 2.7552 * rho + 0.6903;
    const float g = ((a * ao - b) * ao + c) * ao;
    return g > ao ? g : ao;
}

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= k.width || p.y >= k.height) return;
    const uint x = uint(p.y) * uint(k.width) + uint(p.x);
    const bool sky = !(depth[x] < 1e30);
    for (uint c = 0; c < 3; ++c) result[3 * x + c] = sky ? 1.0 : multiBounce(visibility[x], albedo[3 * x + c]);
}
