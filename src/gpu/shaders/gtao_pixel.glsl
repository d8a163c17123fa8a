// The GTAO pixel of gtao.comp (Jimenez, Wu, Pesce and Jarabo 2016, "Practical Realtime Strategies for
// Accurate Indirect Occlusion", §4, eq. 5-9, App. A; the visibility bitmask after Therrien et al. 2023):
// gtaoPixel and its helpers, which gtao.comp's header compares line for line with src/ssao/gtao.cpp. One
// source for gtao.comp, which evaluates one pixel per invocation, and gtao_temporal_fused.comp, which
// evaluates the grid pixels of its workgroup and accumulates them in the same dispatch.
//
// The including shader declares, before the #include:
//   GtaoConstants k (obscura/gtao_constants.h), the push constants;
//   the specialization constants kSampling, kWeighting, kThicknessMode, kBeyondRadius and kPackedNormals
//   (layouts.h's kGtaoSpec*);
//   the buffers depthPlane (floats), normalWords (normal_plane.glsl) and depthMips (floats);
// and, when the sampling reads the MIP chain, sets mipBase2..4 before calling gtaoPixel (as gtao.comp's main).
#ifndef OBSCURA_GPU_GTAO_PIXEL_GLSL
#define OBSCURA_GPU_GTAO_PIXEL_GLSL
const float kPi = 3.14159265358979323846;
const float kHalfPi = 0.5 * kPi;

// ---- obscura/sampling.h ----
uint hash32(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
uint hashCombine(uint seed, uint value) { return hash32(seed ^ (value + 0x9e3779b9u + (seed << 6) + (seed >> 2))); }
float toUnitFloat(uint x) { return float(x >> 8) * (1.0 / 16777216.0); }

// ---- obscura/math.h ----
#include "vector_math.glsl"

// ---- src/ssao/gtao.cpp ----
float saturate(float v) { return clamp(v, 0.0, 1.0); }
float lerp(float a, float b, float t) { return a + (b - a) * t; }
float signOf(float v) { return v < 0.0 ? -1.0 : 1.0; }
// std::lround for v >= 0: halves away from zero; v - float(r) is exact for v < 2^23.
int roundHalfUp(float v) {
    const int r = int(v);
    return v - float(r) >= 0.5 ? r + 1 : r;
}
// std::atan2, whose (0, 0) GLSL leaves undefined.
float atan2(float y, float x) { return x == 0.0 && y == 0.0 ? 0.0 : atan(y, x); }

float arcIntegral(float t, float n) { return signOf(t) * (0.5 * t * sin(n) - 0.25 * cos(2.0 * t - n) + 0.25 * cos(n)); }
float uniformArcIntegral(float t) { return signOf(t) * (1.0 - cos(t)); }

void bentIntegrals(float t, float n, out float alongV, out float alongT) {
    const float cn = cos(n), sn = sin(n), c = cos(t), s = sin(t);
    const float a = cn * (-c * c * c / 3.0) + sn * (s * s * s / 3.0) + cn / 3.0;
    const float b = cn * (s * s * s / 3.0) + sn * (-c + c * c * c / 3.0) + sn * (2.0 / 3.0);
    alongV = signOf(t) * a;
    alongT = signOf(t) * b;
}

#include "normal_plane.glsl"

vec3 viewPosition(float px, float py, float depth) {
    return vec3((px * k.viewFromPixelMulX + k.viewFromPixelAddX) * depth,
                (py * k.viewFromPixelMulY + k.viewFromPixelAddY) * depth, -depth);
}

float depthAt(int x, int y) { return depthPlane[uint(y) * uint(k.width) + uint(x)]; }

// Where levels 2-4 start in the chain (level 1 at 0), set once by main: gtaoMipOffset loops over the levels,
// and these are the same for every sample.
uint mipBase2 = 0u, mipBase3 = 0u, mipBase4 = 0u;

// GtaoDepthMips::at
float mipAt(int level, int x, int y) {
    const uint base = level == 1 ? 0u : level == 2 ? mipBase2 : level == 3 ? mipBase3 : mipBase4;
    return depthMips[base + uint(y) * uint(gtaoMipSize(k.width, level)) + uint(x)];
}

bool samplePosition(int level, bool planar, float sx, float sy, int cx, int cy, out vec3 result) {
    result = vec3(0.0);
    const int ix = int(sx), iy = int(sy);
    if (ix == cx && iy == cy) return false;
    if (gtaoSamplingReadsMips(kSampling) && level > 0) {
        const int tx = ix >> level, ty = iy >> level;
        const float w = mipAt(level, tx, ty);
        if (!(w > 0.0)) return false;
        result = viewPosition(gtaoMipCentre(tx, level, k.width), gtaoMipCentre(ty, level, k.height), 1.0 / w);
        return true;
    }
    const float nearest = depthAt(ix, iy);
    if (!(nearest < 1e30)) return false;
    const float gx = sx - 0.5, gy = sy - 0.5;
    if (planar && k.width > 1 && k.height > 1) {
        const int bx = int(floor(gx)), by = int(floor(gy));
        const int ox = bx == ix ? ix - 1 : ix, oy = by == iy ? iy - 1 : iy;
        const ivec2 quads[4] = ivec2[4](ivec2(bx, by), ivec2(ox, by), ivec2(bx, oy), ivec2(ox, oy));
        [[unroll]] for (int q = 0; q < 4; ++q) {
            const int x0 = clamp(quads[q].x, 0, k.width - 2);
            const int y0 = clamp(quads[q].y, 0, k.height - 2);
            if (ix < x0 || ix > x0 + 1 || iy < y0 || iy > y0 + 1) continue;
            const float w00 = 1.0 / depthAt(x0, y0), w10 = 1.0 / depthAt(x0 + 1, y0);
            const float w01 = 1.0 / depthAt(x0, y0 + 1), w11 = 1.0 / depthAt(x0 + 1, y0 + 1);
            if (!(w00 > 2e-30 && w10 > 2e-30 && w01 > 2e-30 && w11 > 2e-30)) continue;  // as gtao.cpp: 1e30 is sky
            const float crossTerm = abs(w00 + w11 - w10 - w01);
            if (crossTerm > 1e-4 * max(max(w00, w10), max(w01, w11))) continue;
            const float fx = gx - float(x0), fy = gy - float(y0);
            const float w = (w00 * (1.0 - fx) + w10 * fx) * (1.0 - fy) + (w01 * (1.0 - fx) + w11 * fx) * fy;
            if (!(w > 0.0)) return false;  // past the plane's vanishing line: sky, as the CPU's
            result = viewPosition(sx, sy, 1.0 / w);
            return true;
        }
    }
    result = viewPosition(float(ix) + 0.5, float(iy) + 0.5, nearest);
    return true;
}

struct ArcWeights {
    float visibility;
    float alongV, alongT;
};
ArcWeights arc(float t0, float t1, float n) {
    ArcWeights w;
    if (kWeighting == GTAO_WEIGHTING_UNIFORM)
        w.visibility = 0.5 * (uniformArcIntegral(t1) - uniformArcIntegral(t0));
    else
        w.visibility = arcIntegral(t1, n) - arcIntegral(t0, n);
    float v0, v1, s0, s1;
    bentIntegrals(t0, n, v0, s0);
    bentIntegrals(t1, n, v1, s1);
    w.alongV = v1 - v0;
    w.alongT = s1 - s0;
    return w;
}

const int kBayer[16] = int[16](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);
int interleaveIndex(int x, int y) { return kBayer[(y & 3) * 4 + (x & 3)]; }

struct GtaoPixel {
    float visibility;
    vec3 bentNormal;
};

// gtaoSideReach (gtao.cpp): the screen radius or the distance to the border less the first step, at least 0.
float sideReach(float px, float py, float dx, float dy, float screenRadius) {
    const float tx = dx > 0.0 ? (float(k.width) - px) / dx : dx < 0.0 ? -px / dx : 1e30;
    const float ty = dy > 0.0 ? (float(k.height) - py) / dy : dy < 0.0 ? -py / dy : 1e30;
    return max(min(screenRadius, min(tx, ty) - k.minStepPixels), 0.0);
}

GtaoPixel gtaoPixel(int x, int y, int interleave) {
    GtaoPixel result = GtaoPixel(1.0, vec3(0.0));
    const uint c = uint(y) * uint(k.width) + uint(x);
    const float depth = depthPlane[c];
    if (!(depth < 1e30)) return result;
    const vec3 p = viewPosition(float(x) + 0.5, float(y) + 0.5, depth);
    const vec3 v = -p * inversesqrt(dot3(p, p));
    const vec3 normal = loadNormal(c);
    result.bentNormal = normal;

    const float screenRadius = min(k.radius * k.focalPixels / depth, k.maxRadiusPixels);
    if (screenRadius < k.minStepPixels) return result;

    float sliceJitter = 0.5, stepJitter = 0.5;
    if (k.interleaved != 0) {
        const int rotation = ((k.frameIndex % kGtaoRotations) + kGtaoRotations) % kGtaoRotations;
        sliceJitter = (float(interleave) + (float(rotation) + 0.5) / float(kGtaoRotations)) / 16.0;
        stepJitter = fract(0.5 + 0.6180340 * float(interleave) + 0.3819660 * float(rotation));
    } else if (k.noiseMode != 0) {
        const uint h = hashCombine(hashCombine(uint(x), uint(y)), uint(k.frameIndex));
        sliceJitter = toUnitFloat(h);
        stepJitter = toUnitFloat(hash32(h));
    }

    float visibility = 0.0, unoccluded = 0.0;
    vec3 bent = vec3(0.0);
    for (int slice = 0; slice < k.sliceCount; ++slice) {
        const float phi = (float(slice) + sliceJitter) / float(k.sliceCount) * kPi;
        const float cosPhi = cos(phi), sinPhi = sin(phi);
        const vec3 direction = vec3(cosPhi, sinPhi, 0.0);
        const vec3 tangent = direction - v * dot3(direction, v);
        const vec3 t = tangent * inversesqrt(dot3(tangent, tangent));
        const vec3 axis = cross3(t, v);
        const vec3 projectedNormal = normal - axis * dot3(normal, axis);
        const float projectedLength2 = dot3(projectedNormal, projectedNormal);
        if (!(projectedLength2 > 1e-12)) continue;
        const float invProjectedLength = inversesqrt(projectedLength2);
        const float projectedLength = projectedLength2 * invProjectedLength;
        const float cosN = saturate(dot3(projectedNormal, v) * invProjectedLength);
        const float n = signOf(dot3(projectedNormal, t)) * acos(cosN);
        const float sinN = sin(n);

        // cos(n + pi/2) and cos(n - pi/2)
        const float lowCos0 = -sinN, lowCos1 = sinN;
        float horizonCos0 = lowCos0, horizonCos1 = lowCos1;
        uint occluded = 0u;
        // Each side marches over what the image holds (gtaoSideReach): steps spread past the border were dropped,
        // and a larger radius found less occlusion.
        const float reach0 = sideReach(float(x) + 0.5, float(y) + 0.5, cosPhi, -sinPhi, screenRadius);
        const float reach1 = sideReach(float(x) + 0.5, float(y) + 0.5, -cosPhi, sinPhi, screenRadius);

        for (int step = 0; step < k.stepsPerSide; ++step) {
            float s = (float(step) + stepJitter) / float(k.stepsPerSide);
            // std::pow(s, 1) is s exactly; the GPU's pow (exp2 of log2) is not.
            s = k.stepPower == 1.0 ? s : pow(s, k.stepPower);
            [[unroll]] for (int side = 0; side < 2; ++side) {
                const float offset = s * (side == 0 ? reach0 : reach1) + k.minStepPixels;
                // gtaoMipLevel: the largest l <= mipLevels with 2^l <= offset * mipTexelScale, by its highest bit.
                const int level =
                    gtaoSamplingReadsMips(kSampling) ? clamp(findMSB(int(offset * k.mipTexelScale)), 0, k.mipLevels) : 0;
                const bool planar = gtaoSamplingPlanarAt(kSampling, offset, k.mipTexelScale);
                const float sign = side == 0 ? 1.0 : -1.0;
                const float sx = float(x) + 0.5 + sign * offset * cosPhi;
                const float sy = float(y) + 0.5 - sign * offset * sinPhi;
                if (!(sx >= 0.0 && sy >= 0.0 && sx < float(k.width) && sy < float(k.height))) continue;
                vec3 sp;
                if (!samplePosition(level, planar, sx, sy, x, y, sp)) continue;
                const vec3 delta = sp - p;
                const float distance2 = dot3(delta, delta);
                if (!(distance2 > 0.0)) continue;
                const float invDistance = inversesqrt(distance2);
                const float distance = distance2 * invDistance;
                const float weight = saturate((k.radius - distance) * k.falloffInvRange);

                if (kThicknessMode == GTAO_THICKNESS_BITMASK) {
                    if (weight <= 0.0) continue;
                    const vec3 back = sp + normalize3(sp) * k.bitmaskThickness - p;
                    const float tFront = atan2(dot3(delta, t), dot3(delta, v));
                    const float tBack = atan2(dot3(back, t), dot3(back, v));
                    const float a = (min(tFront, tBack) - (n - kHalfPi)) / kPi;
                    const float b = (max(tFront, tBack) - (n - kHalfPi)) / kPi;
                    if (abs(tFront - tBack) > kPi) continue;
                    const int first = roundHalfUp(saturate(a) * GTAO_BITMASK_SECTORS);
                    const int last = roundHalfUp(saturate(b) * GTAO_BITMASK_SECTORS);
                    for (int i = first; i < last; ++i) occluded |= 1u << i;
                    continue;
                }
                const float lowCos = side == 0 ? lowCos0 : lowCos1;
                const float rawCos = dot3(delta, v) * invDistance;
                float sampleCos = lerp(lowCos, rawCos, weight);
                if (kBeyondRadius == GTAO_BEYOND_COLUMN && distance > k.falloffFrom) {
                    const vec3 u = sp * inversesqrt(dot3(sp, sp));
                    const float du = dot3(delta, u);
                    const float disc = du * du - (distance - k.falloffFrom) * (distance + k.falloffFrom);
                    if (du < 0.0 && disc >= 0.0) {
                        const vec3 entry = delta + u * (-du - sqrt(disc));
                        const float entryLength2 = dot3(entry, entry);
                        if (entryLength2 > 0.0) sampleCos = max(sampleCos, dot3(entry, v) * inversesqrt(entryLength2));
                    }
                }
                float horizonCos = side == 0 ? horizonCos0 : horizonCos1;
                // Without the heuristic, gtaoConstants sets thicknessBlend to 0, and the lerp below keeps the
                // horizon: the update is a plain maximum, which the compiler cannot see in a push constant.
                if (kThicknessMode != GTAO_THICKNESS_HEURISTIC)
                    horizonCos = max(horizonCos, sampleCos);
                else if (sampleCos >= horizonCos)
                    horizonCos = sampleCos;
                else if (rawCos < horizonCos)  // the CPU's: lower by direction, pulling as much as it counts
                    horizonCos = lerp(horizonCos, rawCos, k.thicknessBlend * weight);
                if (side == 0) horizonCos0 = horizonCos;
                else horizonCos1 = horizonCos;
            }
        }

        float sliceVisibility = 0.0, alongV = 0.0, alongT = 0.0;
        if (kThicknessMode == GTAO_THICKNESS_BITMASK) {
            for (int i = 0; i < GTAO_BITMASK_SECTORS; ++i) {
                if ((occluded & (1u << i)) != 0u) continue;
                const float t0 = n - kHalfPi + kPi * float(i) / GTAO_BITMASK_SECTORS;
                const ArcWeights w = arc(t0, t0 + kPi / GTAO_BITMASK_SECTORS, n);
                sliceVisibility += w.visibility;
                alongV += w.alongV;
                alongT += w.alongT;
            }
        } else {
            float h0 = -acos(clamp(horizonCos1, -1.0, 1.0));
            float h1 = acos(clamp(horizonCos0, -1.0, 1.0));
            h0 = h0 - n < -kHalfPi + 2e-3 ? n - kHalfPi : min(h0, n + kHalfPi);
            h1 = h1 - n > kHalfPi - 2e-3 ? n + kHalfPi : max(h1, n - kHalfPi);
            const ArcWeights w = arc(h0, h1, n);
            sliceVisibility = w.visibility;
            alongV = w.alongV;
            alongT = w.alongT;
        }
        const float normalScale = kWeighting == GTAO_WEIGHTING_UNIFORM ? 1.0 : projectedLength;
        visibility += normalScale * sliceVisibility;
        const ArcWeights open = arc(n - kHalfPi, n + kHalfPi, n);
        // arc(n - pi/2, n + pi/2, n).visibility in closed form: n sin n + cos n, or 1 uniformly weighted
        unoccluded += normalScale * (kWeighting == GTAO_WEIGHTING_UNIFORM ? 1.0 : n * sinN + cosN);
        bent += (v * (alongV - open.alongV) + t * (alongT - open.alongT)) * projectedLength;
    }
    if (unoccluded > 0.0) result.visibility = saturate(visibility / unoccluded);
    const vec3 b = normalize3(bent / float(k.sliceCount) + normal * (2.0 / 3.0));
    if (dot3(b, b) > 0.0) result.bentNormal = b;
    return result;
}

#endif
