// Ground-Truth Specular Occlusion: Jimenez et al. 2016, "Practical Realtime Strategies for Accurate
// Indirect Occlusion", §6 (eq. 14-21) and App. B (eq. 25-26), one invocation per pixel; the mode (4-D
// table, 3-D table, cone intersection) is a specialization constant.
//
// The CPU reference is src/ssao/specular_occlusion.cpp: specularOcclusion, gridCoordinate,
// SpecularOcclusionTable::lookup, capIntersectionSolidAngle and specularOcclusionCone below are its
// functions of the same names. The table is a 3-D texture (lighting_layouts.h gives the packing).
//
// Interpolation: kSpecularLookupFetch reads the 2^d nodes with texelFetch and weighs them in float as the
// CPU's multilinear lookup does; kSpecularLookupHardware lets the sampler's trilinear filter do it (the 4-D
// table: two filtered reads along theta_o, lerped here). The fetch variant is the one the public pass uses.
// tests/gpu/lighting_gpu_test.cpp measures both: on lavapipe, which filters with float weights, they agree
// with the CPU alike (max 3.8e-4); but filtering hardware quantises the sub-texel weight to
// subTexelPrecisionBits (8 on most GPUs, 4 the Vulkan minimum), and neighbouring nodes of these tables differ
// by up to 1.0 (the mirror's step), so the quantisation alone could reach 2e-3 (8 bits) to 3e-2 (4 bits).
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lighting_layouts.h"
#include "vector_math.glsl"

layout(local_size_x = kLightingWorkgroupX, local_size_y = kLightingWorkgroupY, local_size_z = 1) in;

layout(constant_id = kSpecularSpecMode) const int kMode = kSpecularModeLut4;
layout(constant_id = kSpecularSpecLookup) const int kLookup = kSpecularLookupFetch;
layout(constant_id = kSpecularSpecPackedNormals) const int kPackedNormals = 0;

layout(push_constant, std430) uniform Constants { SpecularConstants k; };
layout(std430, binding = kSpecularBindingDepth) readonly buffer DepthPlane { float depth[]; };
layout(std430, binding = kSpecularBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };
layout(std430, binding = kSpecularBindingAo) readonly buffer AoPlane { float ao[]; };
layout(std430, binding = kSpecularBindingBentNormal) readonly buffer BentPlane { float bent[]; };
layout(binding = kSpecularBindingTable) uniform sampler3D table;
layout(std430, binding = kSpecularBindingOutput) writeonly buffer Output { float result[]; };

const float kPi = 3.14159265358979;
const float kHalfPi = 0.5 * kPi;

// Fractional grid coordinate g in [0, tableSize - 1]: a cell index and a weight.
void splitCoordinate(float g, out int i, out float f) {
    const int n = k.tableSize;
    g = clamp(g, 0.0, float(n - 1));
    i = min(int(g), n - 2);
    f = g - float(i);
}

// Fractional grid coordinate of v in [0, range] on tableSize nodes.
void gridCoordinate(float v, float range, out int i, out float f) {
    splitCoordinate(v / (range / float(k.tableSize - 1)), i, f);
}

// The 4-D table's beta axis follows the bent normal: node kNormalNode is b = n at every theta_o, the nodes
// below tilt b towards w_r (node 0: beta = 0), those above tilt it past n towards the horizon (the last: beta =
// theta_o + pi/2). SpecularOcclusionTable::betaAt and the CPU's betaCoordinate.
const int kNormalNode = 15;
float betaCoordinate(float beta, float thetaO) {
    if (beta > thetaO) return float(kNormalNode) + (beta - thetaO) / (kHalfPi / float(k.tableSize - 1 - kNormalNode));
    return thetaO > 0.0 ? float(kNormalNode) * beta / thetaO : float(kNormalNode);
}

float node4(int i, int j, int kk, int l) { return texelFetch(table, ivec3(i, j, l * k.tableSize + kk), 0).r; }
float node3(int i, int kk, int l) { return texelFetch(table, ivec3(i, kk, l), 0).r; }

// SpecularOcclusionTable::lookup: the same loop order and weights; beta is ignored by the 3-D table.
float lookup(float alphaV, float beta, float roughness, float thetaO) {
    const bool fourD = kMode == kSpecularModeLut4;
    int i, j = 0, kk, l;
    float fi, fj = 0.0, fk, fl;
    gridCoordinate(alphaV, kHalfPi, i, fi);
    if (fourD) splitCoordinate(betaCoordinate(beta, thetaO), j, fj);
    gridCoordinate(roughness, 1.0, kk, fk);
    gridCoordinate(thetaO, kHalfPi, l, fl);
    if (kLookup == kSpecularLookupHardware) {
        // Texel centres at (index + 0.5) / size; the filter interpolates i, j (or kk) and the z axis.
        const vec3 size = vec3(textureSize(table, 0));
        if (fourD) {
            const vec2 xy = (vec2(float(i) + fi, float(j) + fj) + 0.5) / size.xy;
            const float z0 = (float(l * k.tableSize + kk) + fk + 0.5) / size.z;
            const float z1 = (float((l + 1) * k.tableSize + kk) + fk + 0.5) / size.z;
            return mix(texture(table, vec3(xy, z0)).r, texture(table, vec3(xy, z1)).r, fl);
        }
        return texture(table, (vec3(float(i) + fi, float(kk) + fk, float(l) + fl) + 0.5) / size).r;
    }
    float r = 0.0;
    for (int dl = 0; dl < 2; ++dl)
        for (int dk = 0; dk < 2; ++dk)
            for (int dj = 0; dj < (fourD ? 2 : 1); ++dj)
                for (int di = 0; di < 2; ++di) {
                    float w = (di != 0 ? fi : 1.0 - fi) * (dk != 0 ? fk : 1.0 - fk) * (dl != 0 ? fl : 1.0 - fl);
                    if (fourD) w *= dj != 0 ? fj : 1.0 - fj;
                    if (w > 0.0)
                        r += w * (fourD ? node4(i + di, j + dj, kk + dk, l + dl) : node3(i + di, kk + dk, l + dl));
                }
    return r;
}

// The CPU's angleBetween: atan of |a x b| and the (clamped) cosine c, exact where acos of a cosine near 1 is not.
float angleBetween(vec3 a, vec3 b, float c) {
    const float s = length3(cross3(a, b));
    return s == 0.0 && c == 0.0 ? 0.5 * kPi : atan(s, c);
}

// The CPU's capIntersection in float: two cap sectors less the kite of the triangle (axis 1, axis 2, a corner
// of the lens), with the angles from the half-angle formulas and the excess from L'Huilier's theorem, so that a
// cap of a few milliradians keeps its digits (the textbook 2 (pi - gamma - cos a1 b1 - cos a2 b2) lost them all).
float capIntersectionSolidAngle(float a1, float a2, float beta) {
    if (beta >= a1 + a2) return 0.0;
    const float s1 = sin(0.5 * a1), s2 = sin(0.5 * a2);
    const float cap1 = 4.0 * kPi * s1 * s1, cap2 = 4.0 * kPi * s2 * s2;
    if (beta <= abs(a1 - a2)) return min(cap1, cap2);
    if (beta >= 2.0 * kPi - a1 - a2) return cap1 + cap2 - 4.0 * kPi;
    const float s = 0.5 * (a1 + a2 + beta), sb = max(0.0, 0.5 * (a1 + a2 - beta));
    const float sa1 = max(0.0, 0.5 * (a2 + beta - a1)), sa2 = max(0.0, 0.5 * (a1 + beta - a2));
    // atan(y, x) is undefined for x = y = 0; the branches above leave at most one of them 0.
    const float phi1 = 2.0 * atan(sqrt(sin(sb) * sin(sa1)), max(sqrt(sin(s) * sin(sa2)), 1e-30));
    const float phi2 = 2.0 * atan(sqrt(sin(sb) * sin(sa2)), max(sqrt(sin(s) * sin(sa1)), 1e-30));
    const float excess = 4.0 * atan(sqrt(tan(0.5 * s) * tan(0.5 * sb) * tan(0.5 * sa1) * tan(0.5 * sa2)));
    return max(0.0, 2.0 * (phi1 * 2.0 * s1 * s1 + phi2 * 2.0 * s2 * s2 - excess));
}

float specularOcclusionCone(float alphaV, float beta, float roughness) {
    // eq. 26 as 1 - cos(alpha_s): GLSL has no expm1, and 1 - exp(-x) in float keeps few digits below x = 0.01,
    // where the series' next term is below 5e-8 of it.
    const float x = 2.30259 * roughness * roughness;
    const float oneMinusCos = x < 0.01 ? x * (1.0 - x * (0.5 - x / 6.0)) : 1.0 - exp(-x);
    if (!(oneMinusCos > 0.0)) return beta < alphaV ? 1.0 : 0.0;  // a mirror: strictly inside, as the CPU's
    const float alphaS = 2.0 * asin(sqrt(0.5 * oneMinusCos));
    const float specular = 2.0 * kPi * oneMinusCos;
    return clamp(capIntersectionSolidAngle(alphaV, alphaS, beta) / specular, 0.0, 1.0);
}

#include "normal_plane.glsl"

vec3 vec3At(uint i, bool bentPlane) {
    return bentPlane ? vec3(bent[3 * i], bent[3 * i + 1], bent[3 * i + 2]) : loadNormal(i);
}

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= k.width || p.y >= k.height) return;
    const uint x = uint(p.y) * uint(k.width) + uint(p.x);
    if (!(depth[x] < 1e30)) {
        result[x] = 1.0;
        return;
    }
    // normalize(-viewPosition): the depth cancels, so the ray through the pixel centre at depth 1.
    const vec2 c = vec2(p) + 0.5;
    const vec3 view = normalize(-vec3(c.x * k.viewFromPixelMulX + k.viewFromPixelAddX,
                                      c.y * k.viewFromPixelMulY + k.viewFromPixelAddY, -1.0));
    const vec3 n = vec3At(x, false), b = vec3At(x, true);
    // Eq. 18, as the CPU's visibilityConeAngle: atan of sin and cos keeps alpha_v exact where A -> 0.
    const float a = clamp(ao[x], 0.0, 1.0);
    const float alphaV = atan(sqrt(a), sqrt(1.0 - a));
    const float nv = clamp(dot(n, view), 0.0, 1.0);
    const vec3 reflected = n * (2.0 * nv) - view;
    const float thetaO = angleBetween(n, view, nv);
    const float beta = angleBetween(b, reflected, dot(b, reflected));
    float s;
    if (kMode == kSpecularModeLut4) s = lookup(alphaV, beta, k.roughness, thetaO);
    else if (kMode == kSpecularModeLut3) s = lookup(alphaV, beta, k.roughness, beta);  // n taken as b (§6)
    else s = specularOcclusionCone(alphaV, beta, k.roughness);
    result[x] = s;
}
