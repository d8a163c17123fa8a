// Diffuse image-based compositing: albedo x SH irradiance / pi x AO (Ramamoorthi and Hanrahan 2001, "An
// Efficient Representation for Irradiance Environment Maps", eq. 13), or x G(A, albedo) per channel for
// multi-bounce AO (Jimenez et al. 2016, eq. 10); sky pixels show the equirect environment. One invocation
// per pixel.
//
// The CPU reference is render::shade (src/render/composite.cpp) with render::irradiance and
// render::sampleEquirect (src/render/sh_irradiance.cpp, environment.cpp); irradiance, equirectFromDirection
// and sampleEquirect below are those functions. The differences: the irradiance sums in float instead of
// double (its A_l N_lm L_lm products are formed in double on the host), and atan is the GPU's.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lighting_layouts.h"
#include "vector_math.glsl"

layout(local_size_x = kLightingWorkgroupX, local_size_y = kLightingWorkgroupY, local_size_z = 1) in;

layout(constant_id = kShadeSpecPackedNormals) const int kPackedNormals = 0;

layout(push_constant, std430) uniform Constants { ShadeConstants k; };
layout(std430, binding = kShadeBindingDepth) readonly buffer DepthPlane { float depth[]; };
layout(std430, binding = kShadeBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };
layout(std430, binding = kShadeBindingAlbedo) readonly buffer AlbedoPlane { float albedo[]; };
layout(std430, binding = kShadeBindingOcclusion) readonly buffer Occlusion { float occlusion[]; };
layout(std430, binding = kShadeBindingIrradiance) readonly buffer Irradiance { vec4 sh[9]; };
layout(binding = kShadeBindingEnvironment) uniform sampler2D environment;
layout(std430, binding = kShadeBindingColor) writeonly buffer Color { float color[]; };
layout(std430, binding = kShadeBindingLighting) writeonly buffer Lighting { float lighting[]; };

const float kPi = 3.14159265358979;

#include "normal_plane.glsl"

vec3 worldFromView(vec3 v) {
    return vec3(dot(vec3(k.worldFromView[0], k.worldFromView[1], k.worldFromView[2]), v),
                dot(vec3(k.worldFromView[4], k.worldFromView[5], k.worldFromView[6]), v),
                dot(vec3(k.worldFromView[8], k.worldFromView[9], k.worldFromView[10]), v));
}

// render::irradiance: sh[i] already holds A_l N_lm L_lm, so the basis is the bare monomials.
vec3 irradiance(vec3 n) {
    const float basis[9] = float[9](1.0, n.y, n.z, n.x, n.x * n.y, n.y * n.z, 3.0 * n.z * n.z - 1.0, n.x * n.z,
                                    n.x * n.x - n.y * n.y);
    vec3 e = vec3(0.0);
    for (int i = 0; i < 9; ++i) e += sh[i].rgb * basis[i];
    return max(e, vec3(0.0));
}

vec2 equirectFromDirection(vec3 dir) {
    const float horizontal = sqrt(dir.x * dir.x + dir.z * dir.z);
    const float theta = atan(horizontal, dir.y);
    const float phi = horizontal > 0.0 ? atan(dir.x, -dir.z) : 0.0;  // the pole: u = 0.5, as the CPU's
    float u = phi / (2.0 * kPi) + 0.5;
    if (u >= 1.0) u -= 1.0;
    return vec2(u, theta / kPi);
}

vec3 texel(int x, int y) { return texelFetch(environment, ivec2(x, y), 0).rgb; }

// Bilinear between texel centres, the azimuth wrapping and the polar angle clamped, by hand: the CPU's
// weights in float rather than the sampler's quantised ones.
vec3 sampleEquirect(vec3 dir) {
    if (k.envWidth == 0) return vec3(0.0);
    const vec2 uv = equirectFromDirection(dir);
    const float fx = uv.x * float(k.envWidth) - 0.5, fy = uv.y * float(k.envHeight) - 0.5;
    const float x0f = floor(fx), y0f = floor(fy);
    const float tx = fx - x0f, ty = fy - y0f;
    const int w = k.envWidth;
    const int x0 = ((int(x0f) % w) + w) % w, x1 = ((int(x0f) + 1) % w + w) % w;
    const int y0 = clamp(int(y0f), 0, k.envHeight - 1), y1 = clamp(int(y0f) + 1, 0, k.envHeight - 1);
    const vec3 top = texel(x0, y0) * (1.0 - tx) + texel(x1, y0) * tx;
    const vec3 bottom = texel(x0, y1) * (1.0 - tx) + texel(x1, y1) * tx;
    return top * (1.0 - ty) + bottom * ty;
}

void store(uint x, vec3 c, vec3 l) {
    for (uint i = 0; i < 3; ++i) {
        color[3 * x + i] = c[i];
        lighting[3 * x + i] = l[i];
    }
}

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= k.width || p.y >= k.height) return;
    const uint x = uint(p.y) * uint(k.width) + uint(p.x);
    if (!(depth[x] < 1e30)) {
        // Camera::viewRayDirection: the ray through the pixel centre at depth 1.
        const vec2 c = vec2(p) + 0.5;
        const vec3 view = normalize(vec3(c.x * k.viewFromPixelMulX + k.viewFromPixelAddX,
                                         c.y * k.viewFromPixelMulY + k.viewFromPixelAddY, -1.0));
        store(x, sampleEquirect(normalize(worldFromView(view))), vec3(0.0));  // no surface to light
        return;
    }
    const vec3 n = normalize3(worldFromView(loadNormal(x)));  // a zero normal stays zero, as on the CPU
    const vec3 light = irradiance(n) * (1.0 / kPi);
    const vec3 a = vec3(albedo[3 * x], albedo[3 * x + 1], albedo[3 * x + 2]);
    vec3 o = vec3(1.0);
    if (k.aoChannels == 1) o = vec3(occlusion[x]);
    if (k.aoChannels == 3) o = vec3(occlusion[3 * x], occlusion[3 * x + 1], occlusion[3 * x + 2]);
    store(x, a * light * o, light);
}
