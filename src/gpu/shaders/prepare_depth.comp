// Depth and normal preparation: an engine's device depth and normals as the G-buffer the other passes read
// (obscura/depth_prep.h); one invocation per pixel. The CPU reference is ssao::prepareGBuffer
// (src/ssao/depth_prep.cpp): linearDepthFromDevice is the shared header's, viewNormal is its function of
// the same name. Normals rebuilt from depth come from normals_from_depth.comp after this pass.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "obscura/depth_prep_constants.h"
#include "prep_layouts.h"

layout(local_size_x = kDepthPrepWorkgroupX, local_size_y = kDepthPrepWorkgroupY, local_size_z = 1) in;

layout(push_constant, std430) uniform Constants { DepthPrepConstants k; };
layout(std430, binding = kPrepBindingDeviceDepth) readonly buffer DeviceDepth { float deviceDepth[]; };
layout(std430, binding = kPrepBindingNormalIn) readonly buffer NormalIn { float normalIn[]; };
layout(std430, binding = kPrepBindingDepth) writeonly buffer DepthPlane { float depth[]; };
layout(std430, binding = kPrepBindingNormal) writeonly buffer NormalPlane { float normal[]; };

vec3 viewNormal(uint i) {
    const uint base = i * uint(k.normalChannels);
    vec3 n = vec3(normalIn[base], normalIn[base + 1], normalIn[base + 2]);
    if (k.unorm != 0) n = n * 2.0 - vec3(1.0);
    if (k.normals == kNormalsWorld)
        n = vec3(dot(vec3(k.viewFromWorld0[0], k.viewFromWorld0[1], k.viewFromWorld0[2]), n),
                 dot(vec3(k.viewFromWorld1[0], k.viewFromWorld1[1], k.viewFromWorld1[2]), n),
                 dot(vec3(k.viewFromWorld2[0], k.viewFromWorld2[1], k.viewFromWorld2[2]), n));
    return n * (1.0 / sqrt(dot(n, n)));
}

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= k.width || p.y >= k.height) return;
    const uint i = uint(p.y) * uint(k.width) + uint(p.x);
    const float d = linearDepthFromDevice(deviceDepth[i], k);
    depth[i] = d;
    // Rebuilt normals are written by normals_from_depth.comp, which reads every depth of this pass.
    if (k.normals == kNormalsFromDepth) return;
    const vec3 n = d < 1e30 ? viewNormal(i) : vec3(0.0);
    normal[3 * i] = n.x;
    normal[3 * i + 1] = n.y;
    normal[3 * i + 2] = n.z;
}
