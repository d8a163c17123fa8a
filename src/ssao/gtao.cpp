// GTAO CPU reference: Jimenez et al. 2016, "Practical Realtime Strategies for Accurate Indirect
// Occlusion", §4 (eq. 5-9) and App. A (eq. 22-23); the visibility bitmask follows Therrien et al. 2023,
// "Screen Space Indirect Lighting with Visibility Bitmask".
//
// Angles in a slice are measured from the view vector V, positive towards the slice's in-plane direction
// T (V, T orthonormal), so a direction in the slice is cos(t) V + sin(t) T and the slice's share of the
// sphere carries the Jacobian |sin t| (eq. 3). The hemisphere of the normal is [n - pi/2, n + pi/2],
// n the signed angle of the normal projected into the slice.
#include "obscura/gtao.h"

#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace obscura::ssao {

namespace {

constexpr float kHalfPi = 0.5f * kPi;

float saturate(float v) { return std::clamp(v, 0.0f, 1.0f); }
float mix(float a, float b, float t) { return a + (b - a) * t; }
float signOf(float v) { return v < 0.0f ? -1.0f : 1.0f; }

// Integral from 0 to t of cos(s - n) |sin s| ds: eq. 7's inner integral is arcIntegral(h1) - arcIntegral(h0).
float arcIntegral(float t, float n) {
    return signOf(t) * (0.5f * t * std::sin(n) - 0.25f * std::cos(2.0f * t - n) + 0.25f * std::cos(n));
}
// Integral from 0 to t of |sin s| ds, App. A's uniformly weighted arc.
float uniformArcIntegral(float t) { return signOf(t) * (1.0f - std::cos(t)); }

// Integrals from 0 to t of (cos s, sin s) cos(s - n) |sin s| ds: the V and T components of the
// cosine-weighted mean direction of an arc, for the bent normal.
void bentIntegrals(float t, float n, float& alongV, float& alongT) {
    float cn = std::cos(n), sn = std::sin(n), c = std::cos(t), s = std::sin(t);
    float a = cn * (-c * c * c / 3.0f) + sn * (s * s * s / 3.0f) + cn / 3.0f;
    float b = cn * (s * s * s / 3.0f) + sn * (-c + c * c * c / 3.0f) + sn * (2.0f / 3.0f);
    alongV = signOf(t) * a;
    alongT = signOf(t) * b;
}

Vec3 viewPosition(const GtaoConstants& c, float px, float py, float depth) {
    return {(px * c.viewFromPixelMulX + c.viewFromPixelAddX) * depth,
            (py * c.viewFromPixelMulY + c.viewFromPixelAddY) * depth, -depth};
}

float fract(float v) { return v - std::floor(v); }

// View-space point of the depth buffer at continuous image position (sx, sy). Inverse depth is affine in
// the image over a plane, so where a 2x2 quad of pixels agrees with one plane (its bilinear cross term
// vanishes) it is interpolated, and the point lies on the slice line exactly; at grazing angles snapping
// to a pixel centre would move the point off the slice by many metres of depth and find false horizons.
// The quad around (sx, sy) is tried first, then the three other quads that hold the nearest pixel as a
// corner (extrapolating an affine function is exact too): that keeps the interpolation at a surface's
// edge against the sky, at its corners (where only the diagonal quad lies on the surface) and at the image
// border. Across an edge or a silhouette, and always where `planar` is false (gtaoSamplingPlanarAt: NEAREST
// and MIP, and PLANAR_NEAREST from 2 / mipTexelScale pixels out), the nearest pixel's own point is used.
// With GTAO_SAMPLING_MIP and PLANAR_MIP, from level 1 the point is that of the chain's texel holding the
// nearest pixel (obscura/gtao_mips.h); below, MIP reads as NEAREST and PLANAR_MIP as PLANAR. False for sky, for
// (sx, sy) past the vanishing line of the plane a quad finds there, or for (sx, sy) in the centre pixel (cx, cy).
bool samplePosition(const GtaoConstants& c, const GBuffer& g, const GtaoDepthMips* mips, int level, bool planar,
                    float sx, float sy, int cx, int cy, Vec3& out) {
    const int ix = int(sx), iy = int(sy);
    if (ix == cx && iy == cy) return false;
    if (level > 0) {
        const int tx = ix >> level, ty = iy >> level;
        const float w = mips->at(level, tx, ty);
        if (!(w > 0.0f)) return false;
        out = viewPosition(c, gtaoMipCentre(tx, level, c.width), gtaoMipCentre(ty, level, c.height), 1.0f / w);
        return true;
    }
    const float nearest = g.depth.at(ix, iy);
    if (!(nearest < 1e30f)) return false;
    const float gx = sx - 0.5f, gy = sy - 0.5f;
    if (planar && c.width > 1 && c.height > 1) {
        // The quad around (sx, sy) has the nearest pixel (ix, iy) as a corner; ox, oy pick the other quads.
        const int bx = int(std::floor(gx)), by = int(std::floor(gy));
        const int ox = bx == ix ? ix - 1 : ix, oy = by == iy ? iy - 1 : iy;
        const int quads[4][2] = {{bx, by}, {ox, by}, {bx, oy}, {ox, oy}};
        for (const auto& quad : quads) {
            const int x0 = std::clamp(quad[0], 0, c.width - 2);
            const int y0 = std::clamp(quad[1], 0, c.height - 2);
            if (ix < x0 || ix > x0 + 1 || iy < y0 || iy > y0 + 1) continue;
            // Inverse depths: at most 1e-30 for sky (a depth of 1e30 or more, +inf's 0 included), which fails
            // the test below. It once took only +inf for sky: a sky of 1e30 (FORMATS.md allows it) passed with
            // w = 1e-30, and a quad across the sky's edge bent the AO there by up to 0.34. The bound 2e-30 stays
            // clear of the reciprocal's rounding at 1e30 (a depth between 5e29 and 1e30 just reads no plane).
            const float w00 = 1.0f / g.depth.at(x0, y0), w10 = 1.0f / g.depth.at(x0 + 1, y0);
            const float w01 = 1.0f / g.depth.at(x0, y0 + 1), w11 = 1.0f / g.depth.at(x0 + 1, y0 + 1);
            if (!(w00 > 2e-30f && w10 > 2e-30f && w01 > 2e-30f && w11 > 2e-30f)) continue;
            const float cross = std::fabs(w00 + w11 - w10 - w01);
            if (cross > 1e-4f * std::max(std::max(w00, w10), std::max(w01, w11))) continue;
            const float fx = gx - float(x0), fy = gy - float(y0);
            const float w = (w00 * (1.0f - fx) + w10 * fx) * (1.0f - fy) + (w01 * (1.0f - fx) + w11 * fx) * fy;
            // The nearest pixel's own plane puts (sx, sy) past its vanishing line: that is sky, and the
            // nearest pixel's centre, off the slice line, once made a false horizon on open ground.
            if (!(w > 0.0f)) return false;
            out = viewPosition(c, sx, sy, 1.0f / w);
            return true;
        }
    }
    out = viewPosition(c, float(ix) + 0.5f, float(iy) + 0.5f, nearest);
    return true;
}

// Arc [t0, t1] (t0 <= t1) of a slice as a share of the visibility and of the bent-normal vector.
struct ArcWeights {
    float visibility;
    float alongV, alongT;
};
ArcWeights arc(const GtaoConstants& c, float t0, float t1, float n) {
    ArcWeights w{};
    if (c.weighting == GTAO_WEIGHTING_UNIFORM)
        w.visibility = 0.5f * (uniformArcIntegral(t1) - uniformArcIntegral(t0));
    else
        w.visibility = arcIntegral(t1, n) - arcIntegral(t0, n);
    float v0, v1, s0, s1;
    bentIntegrals(t0, n, v0, s0);
    bentIntegrals(t1, n, v1, s1);
    w.alongV = v1 - v0;
    w.alongT = s1 - s0;
    return w;
}

} // namespace

void GtaoSettings::validate() const {
    auto check = [](bool ok, const char* field, const char* range) {
        if (!ok) fail(std::string("gtao-") + field, std::string("must be in ") + range);
    };
    check(radius > 0.0f && radius <= 1e4f, "radius", "(0, 1e4] m");
    check(falloffStart >= 0.0f && falloffStart <= 1.0f, "falloff-start", "[0, 1] (a fraction of the radius)");
    check(sliceCount >= 1 && sliceCount <= 64, "slices", "[1, 64]");
    check(stepsPerSide >= 1 && stepsPerSide <= 256, "steps", "[1, 256]");
    check(maxRadiusPixels >= 1.0f && maxRadiusPixels <= 8192.0f, "max-radius-pixels", "[1, 8192]");
    check(stepPower >= 1.0f && stepPower <= 4.0f, "step-power", "[1, 4]");
    check(thicknessBlend >= 0.0f && thicknessBlend < 1.0f, "thickness-blend", "[0, 1)");
    check(bitmaskThickness > 0.0f && bitmaskThickness <= 1e4f, "bitmask-thickness", "(0, 1e4] m");
    check(depthMipLevels >= 0 && depthMipLevels <= GTAO_MAX_MIP_LEVELS, "depth-mips", "[0, 4]");
    check(mipDistanceRatio >= 2.0f && mipDistanceRatio <= 64.0f, "mip-ratio", "[2, 64]");
    if (jitter && interleave)
        fail("gtao-interleave", "rotates the slices by the 4x4 pattern, which --gtao-jitter rotates by a hash: give one");
}

void applyQuality(GtaoSettings& settings, GtaoQuality quality) {
    static constexpr int kTable[4][2] = {{1, 2}, {2, 2}, {3, 3}, {9, 3}};
    settings.sliceCount = kTable[int(quality)][0];
    settings.stepsPerSide = kTable[int(quality)][1];
}

void GtaoSliceOverride::apply(GtaoSettings& settings) const {
    if (slices != 0) settings.sliceCount = slices;
    if (steps != 0) settings.stepsPerSide = steps;
    settings.jitter = jitter;
    settings.interleave = interleave;
}

GtaoQuality parseQuality(const std::string& name) {
    if (name == "low") return GtaoQuality::Low;
    if (name == "medium") return GtaoQuality::Medium;
    if (name == "high") return GtaoQuality::High;
    if (name == "ultra") return GtaoQuality::Ultra;
    fail("gtao quality", "'" + name + "' is not one of low, medium, high, ultra");
}

const char* qualityName(GtaoQuality quality) {
    static const char* kNames[] = {"low", "medium", "high", "ultra"};
    return kNames[int(quality)];
}

const char* gtaoSamplingName(GtaoSampling sampling) {
    static const char* kNames[kGtaoSamplingCount] = {"planar", "nearest", "mip", "planar-mip", "planar-nearest"};
    return kNames[int(sampling)];
}

int interleaveIndex(int x, int y) {
    // 4x4 Bayer order: neighbours take directions half the pattern apart.
    static constexpr int kBayer[16] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};
    return kBayer[(y & 3) * 4 + (x & 3)];
}

namespace {
// The enum's values are the shaders' GTAO_SAMPLING_* codes, so that a mode added to one without the other
// stops the build here.
static_assert(int(GtaoSampling::Planar) == GTAO_SAMPLING_PLANAR &&
                  int(GtaoSampling::Nearest) == GTAO_SAMPLING_NEAREST &&
                  int(GtaoSampling::Mip) == GTAO_SAMPLING_MIP &&
                  int(GtaoSampling::PlanarMip) == GTAO_SAMPLING_PLANAR_MIP &&
                  int(GtaoSampling::PlanarNearest) == GTAO_SAMPLING_PLANAR_NEAREST &&
                  kGtaoSamplingCount == GTAO_SAMPLING_PLANAR_NEAREST + 1,
              "GtaoSampling and GTAO_SAMPLING_* list the modes in the same order");
int samplingCode(GtaoSampling s) { return int(s); }
} // namespace

int gtaoDepthMipLevels(const GtaoSettings& s) {
    return gtaoSamplingReadsMips(samplingCode(s.sampling)) ? s.depthMipLevels : 0;
}

std::string gtaoSamplingText(const GtaoSettings& s) {
    auto number = [](float v) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", double(v));
        return std::string(text);
    };
    const std::string mips = "depth MIP samples (" + std::to_string(s.depthMipLevels + 1) + " levels, ratio " +
                             number(s.mipDistanceRatio) + ")";
    switch (s.sampling) {
    case GtaoSampling::Nearest: return "nearest-pixel samples";
    case GtaoSampling::Mip: return mips;
    case GtaoSampling::PlanarMip: return "planar + " + mips;
    case GtaoSampling::PlanarNearest:
        return "planar samples within " + number(2.0f * s.mipDistanceRatio) + " px, nearest-pixel ones beyond";
    case GtaoSampling::Planar: break;
    }
    return "";
}

GtaoConstants gtaoConstants(const GtaoSettings& s, const Camera& camera, int frameIndex, bool interleaved) {
    GtaoConstants c{};
    c.width = camera.width;
    c.height = camera.height;
    const Camera::PixelToView view = camera.viewFromPixelAffine();
    c.viewFromPixelMulX = view.mulX;
    c.viewFromPixelAddX = view.addX;
    c.viewFromPixelMulY = view.mulY;
    c.viewFromPixelAddY = view.addY;
    c.focalPixels = camera.focalPixels();
    c.radius = s.radius;
    c.falloffFrom = s.radius * s.falloffStart;
    // A hard cut still needs a finite slope: 1e-5 r wide is far below any depth's precision.
    c.falloffInvRange = 1.0f / std::max(s.radius - c.falloffFrom, 1e-5f * s.radius);
    c.maxRadiusPixels = s.maxRadiusPixels;
    // The first sample must leave the centre pixel, or it would find the point itself.
    c.minStepPixels = 1.0f;
    c.stepPower = s.stepPower;
    c.thicknessBlend = s.thickness == GtaoThickness::Heuristic ? s.thicknessBlend : 0.0f;
    c.bitmaskThickness = s.bitmaskThickness;
    c.sliceCount = s.sliceCount;
    c.stepsPerSide = s.stepsPerSide;
    c.weighting = s.weighting == GtaoWeighting::Uniform ? GTAO_WEIGHTING_UNIFORM : GTAO_WEIGHTING_COSINE;
    c.thicknessMode = s.thickness == GtaoThickness::Bitmask    ? GTAO_THICKNESS_BITMASK
                      : s.thickness == GtaoThickness::Heuristic ? GTAO_THICKNESS_HEURISTIC
                                                                : GTAO_THICKNESS_NONE;
    c.interleaved = interleaved || s.interleave ? 1 : 0;
    c.noiseMode = s.jitter ? 1 : 0;
    c.frameIndex = frameIndex;
    c.beyondRadius = s.beyondRadius == GtaoBeyondRadius::Column ? GTAO_BEYOND_COLUMN : GTAO_BEYOND_DROP;
    c.sampling = samplingCode(s.sampling);
    c.mipLevels = gtaoDepthMipLevels(s);
    c.mipTexelScale = 1.0f / s.mipDistanceRatio;
    return c;
}

GtaoPixel gtaoPixel(const GtaoConstants& c, const GBuffer& g, int x, int y) {
    return gtaoPixel(c, g, x, y, interleaveIndex(x, y));
}

GtaoPixel gtaoPixel(const GtaoConstants& c, const GBuffer& g, int x, int y, int interleave) {
    if (c.mipLevels > 0) fail("gtao", "mip sampling needs the depth MIP chain (buildGtaoDepthMips)");
    return gtaoPixel(c, g, nullptr, x, y, interleave);
}

float gtaoSideReach(float px, float py, float dx, float dy, const GtaoConstants& c, float screenRadius) {
    const float tx = dx > 0.0f ? (float(c.width) - px) / dx : dx < 0.0f ? -px / dx : 1e30f;
    const float ty = dy > 0.0f ? (float(c.height) - py) / dy : dy < 0.0f ? -py / dy : 1e30f;
    // Less the first step's offset, so the last step stays inside; never below 0, which would turn the march.
    return std::max(std::min(screenRadius, std::min(tx, ty) - c.minStepPixels), 0.0f);
}

GtaoPixel gtaoPixel(const GtaoConstants& c, const GBuffer& g, const GtaoDepthMips* mips, int x, int y, int interleave) {
    GtaoPixel out;
    const float depth = g.depth.at(x, y);
    if (!(depth < 1e30f)) return out;
    const Vec3 p = viewPosition(c, float(x) + 0.5f, float(y) + 0.5f, depth);
    const Vec3 v = normalize(-p);
    const Vec3 normal = g.viewNormal(x, y);
    out.bentNormal = normal;

    const float screenRadius = std::min(c.radius * c.focalPixels / depth, c.maxRadiusPixels);
    // Nothing but the pixel itself lies within reach.
    if (screenRadius < c.minStepPixels) return out;

    float sliceJitter = 0.5f, stepJitter = 0.5f;
    if (c.interleaved) {
        const int rotation = ((c.frameIndex % kGtaoRotations) + kGtaoRotations) % kGtaoRotations;
        // 16 pattern directions, each rotation shifts them by 1/6 of their spacing: 96 in all.
        sliceJitter = (float(interleave) + (float(rotation) + 0.5f) / float(kGtaoRotations)) / 16.0f;
        stepJitter = fract(0.5f + 0.6180340f * float(interleave) + 0.3819660f * float(rotation));
    } else if (c.noiseMode) {
        std::uint32_t h = hashCombine(hashCombine(std::uint32_t(x), std::uint32_t(y)), std::uint32_t(c.frameIndex));
        sliceJitter = toUnitFloat(h);
        stepJitter = toUnitFloat(hash32(h));
    }

    float visibility = 0.0f, unoccluded = 0.0f;
    Vec3 bent{};
    for (int slice = 0; slice < c.sliceCount; ++slice) {
        const float phi = (float(slice) + sliceJitter) / float(c.sliceCount) * kPi;
        const float cosPhi = std::cos(phi), sinPhi = std::sin(phi);
        // Screen y grows downwards, view y upwards.
        const Vec3 direction{cosPhi, sinPhi, 0.0f};
        const Vec3 t = normalize(direction - v * dot(direction, v));
        const Vec3 axis = cross(t, v);
        const Vec3 projectedNormal = normal - axis * dot(normal, axis);
        const float projectedLength = length(projectedNormal);
        if (!(projectedLength > 1e-6f)) continue;  // normal along the slice axis: the slice has no weight
        const float cosN = saturate(dot(projectedNormal, v) / projectedLength);
        const float n = signOf(dot(projectedNormal, t)) * std::acos(cosN);

        // Horizon cosines on the +T side (0) and the -T side (1), starting at the normal's horizon.
        const float lowCos0 = std::cos(n + kHalfPi), lowCos1 = std::cos(n - kHalfPi);
        float horizonCos0 = lowCos0, horizonCos1 = lowCos1;
        std::uint32_t occluded = 0;  // bitmask mode: sector k covers [n - pi/2 + k pi/32, + pi/32)
        // Each side marches over what the image holds: its steps spread over the screen radius or the distance to
        // the border, whichever is shorter. (Spread over the whole radius, the steps past the border were dropped,
        // so a larger radius found less occlusion: a corner at r = 100 m came out open.)
        const float reach[2] = {gtaoSideReach(float(x) + 0.5f, float(y) + 0.5f, cosPhi, -sinPhi, c, screenRadius),
                                gtaoSideReach(float(x) + 0.5f, float(y) + 0.5f, -cosPhi, sinPhi, c, screenRadius)};

        for (int step = 0; step < c.stepsPerSide; ++step) {
            const float s = std::pow((float(step) + stepJitter) / float(c.stepsPerSide), c.stepPower);
            for (int side = 0; side < 2; ++side) {
                const float offset = s * reach[side] + c.minStepPixels;
                const int level = c.mipLevels > 0 ? gtaoMipLevel(offset, c.mipTexelScale, c.mipLevels) : 0;
                const bool planar = gtaoSamplingPlanarAt(c.sampling, offset, c.mipTexelScale);
                const float sign = side == 0 ? 1.0f : -1.0f;
                const float sx = float(x) + 0.5f + sign * offset * cosPhi;
                const float sy = float(y) + 0.5f - sign * offset * sinPhi;
                if (!(sx >= 0.0f && sy >= 0.0f && sx < float(c.width) && sy < float(c.height))) continue;
                Vec3 sp;
                if (!samplePosition(c, g, mips, level, planar, sx, sy, x, y, sp)) continue;
                const Vec3 delta = sp - p;
                const float distance = length(delta);
                if (!(distance > 0.0f)) continue;
                const float weight = saturate((c.radius - distance) * c.falloffInvRange);

                if (c.thicknessMode == GTAO_THICKNESS_BITMASK) {
                    if (weight <= 0.0f) continue;
                    // The occluder spans from its front face to `thickness` farther along its view ray.
                    const Vec3 back = sp + normalize(sp) * c.bitmaskThickness - p;
                    const float tFront = std::atan2(dot(delta, t), dot(delta, v));
                    const float tBack = std::atan2(dot(back, t), dot(back, v));
                    float a = (std::min(tFront, tBack) - (n - kHalfPi)) / kPi;
                    float b = (std::max(tFront, tBack) - (n - kHalfPi)) / kPi;
                    // A back point wrapping past -pi lands on the far end; a front point is never behind P.
                    if (std::fabs(tFront - tBack) > kPi) continue;
                    const int first = int(std::lround(saturate(a) * GTAO_BITMASK_SECTORS));
                    const int last = int(std::lround(saturate(b) * GTAO_BITMASK_SECTORS));
                    for (int k = first; k < last; ++k) occluded |= 1u << k;
                    continue;
                }
                const float lowCos = side == 0 ? lowCos0 : lowCos1;
                const float rawCos = dot(delta, v) / distance;
                float sampleCos = mix(lowCos, rawCos, weight);
                if (c.beyondRadius == GTAO_BEYOND_COLUMN && distance > c.falloffFrom) {
                    // The column behind the sample, sp + u t for t >= 0 (u = its view ray), enters the sphere
                    // of full weight about p where |delta + u t| = falloffFrom: the smaller root of
                    // t^2 + 2 (delta.u) t + |delta|^2 - falloffFrom^2 = 0, if the column heads towards p.
                    const Vec3 u = normalize(sp);
                    const float du = dot(delta, u);
                    const float disc = du * du - (distance - c.falloffFrom) * (distance + c.falloffFrom);
                    if (du < 0.0f && disc >= 0.0f) {
                        const Vec3 entry = delta + u * (-du - std::sqrt(disc));
                        const float entryLength = length(entry);
                        if (entryLength > 0.0f) sampleCos = std::max(sampleCos, dot(entry, v) / entryLength);
                    }
                }
                float& horizonCos = side == 0 ? horizonCos0 : horizonCos1;
                if (sampleCos >= horizonCos)
                    horizonCos = sampleCos;
                else if (rawCos < horizonCos)  // eq. 9: past a thin occluder the horizon decays towards lower samples
                    // Whether a sample is lower is a matter of its direction, not of its falloff, and it pulls by
                    // as much as it counts: samples past r (weight 0, faded to the low horizon) and the faded
                    // samples of a soft falloff once read as lower ones, and wiped out a wall's occlusion as the
                    // step count grew.
                    horizonCos = mix(horizonCos, rawCos, c.thicknessBlend * weight);
            }
        }

        float sliceVisibility = 0.0f, alongV = 0.0f, alongT = 0.0f;
        if (c.thicknessMode == GTAO_THICKNESS_BITMASK) {
            for (int k = 0; k < GTAO_BITMASK_SECTORS; ++k) {
                if (occluded & (1u << k)) continue;
                const float t0 = n - kHalfPi + kPi * float(k) / GTAO_BITMASK_SECTORS;
                ArcWeights w = arc(c, t0, t0 + kPi / GTAO_BITMASK_SECTORS, n);
                sliceVisibility += w.visibility;
                alongV += w.alongV;
                alongT += w.alongT;
            }
        } else {
            float h0 = -std::acos(std::clamp(horizonCos1, -1.0f, 1.0f));
            float h1 = std::acos(std::clamp(horizonCos0, -1.0f, 1.0f));
            // Samples on the surface's own plane come back within float noise of its horizon (up to 5e-4 rad
            // where acos is steep); they are that horizon, so an open surface integrates exactly like `open`.
            // Snapping moves a slice's A by at most 2e-3^2 / 2 under the cosine weighting, whose integrand
            // vanishes at the hemisphere's edge, and by at most 1e-3 under App. A's uniform one (|sin s| / 2 <= 1/2).
            h0 = h0 - n < -kHalfPi + 2e-3f ? n - kHalfPi : std::min(h0, n + kHalfPi);
            h1 = h1 - n > kHalfPi - 2e-3f ? n + kHalfPi : std::max(h1, n - kHalfPi);
            ArcWeights w = arc(c, h0, h1, n);
            sliceVisibility = w.visibility;
            alongV = w.alongV;
            alongT = w.alongT;
        }
        // eq. 8: the projected normal's length restores the cosine against the true normal.
        const float normalScale = c.weighting == GTAO_WEIGHTING_UNIFORM ? 1.0f : projectedLength;
        visibility += normalScale * sliceVisibility;
        // The slice with nothing in the way: n sin n + cos n (cosine), 1 (uniform), computed by the same
        // arithmetic as an open arc so that an open surface gives exactly 1. Its bent-normal part is a control
        // variate: subtracted here, its average over phi, (2/3) N, added back after the loop.
        const ArcWeights open = arc(c, n - kHalfPi, n + kHalfPi, n);
        unoccluded += normalScale * open.visibility;
        bent += (v * (alongV - open.alongV) + t * (alongT - open.alongT)) * projectedLength;
    }
    // Eq. 8 averages over phi, where the unoccluded values average to exactly 1; dividing by their sum
    // over the slices actually taken (a ratio estimator) keeps an open surface at 1 for any slice count and
    // any view angle, and tends to eq. 8 as the slice count grows.
    if (unoccluded > 0.0f) out.visibility = saturate(visibility / unoccluded);
    const Vec3 b = normalize(bent / float(c.sliceCount) + normal * (2.0f / 3.0f));
    if (dot(b, b) > 0.0f) out.bentNormal = b;
    return out;
}

void checkGtaoBuffers(const GBuffer& gbuffer, const GtaoConstants& constants) {
    if (gbuffer.width() != constants.width || gbuffer.height() != constants.height ||
        gbuffer.depth.width != constants.width || gbuffer.depth.height != constants.height ||
        gbuffer.normal.width != constants.width || gbuffer.normal.height != constants.height)
        fail("gtao", "G-buffer depth is " + std::to_string(gbuffer.depth.width) + "x" +
                         std::to_string(gbuffer.depth.height) + " and normal " + std::to_string(gbuffer.normal.width) +
                         "x" + std::to_string(gbuffer.normal.height) + ", but the constants are for " +
                         std::to_string(constants.width) + "x" + std::to_string(constants.height));
    // The kernel and the depth MIPs index the planes as 1 and 3 floats per pixel: a depth of 2 channels was read
    // from the wrong places, one of none from an empty image.
    if (gbuffer.depth.channels != 1 || gbuffer.normal.channels != 3)
        fail("gtao", "G-buffer depth has " + std::to_string(gbuffer.depth.channels) + " channels and normal " +
                         std::to_string(gbuffer.normal.channels) + "; they must have 1 and 3");
    if (constants.mipLevels < 0 || constants.mipLevels > GTAO_MAX_MIP_LEVELS)
        fail("gtao", "the constants ask for " + std::to_string(constants.mipLevels) +
                         " depth MIP levels; the chain has 0 to " + std::to_string(GTAO_MAX_MIP_LEVELS));
    // A NaN depth or normal would give NaN visibility without a word (and reach float-to-int conversions on
    // the CPU); as ssao::alchemyAO does, name the first bad pixel instead.
    gbuffer.validatePixels("gtao");
    // The constants' projection comes from this camera: a field of view of 0, 180 or NaN made the screen radius
    // NaN or negative, and every pixel came out unoccluded without a word (ssao::alchemyAO refuses it). An empty
    // G-buffer has nothing to project and gives empty images.
    if (gbuffer.depth.pixelCount() > 0) gbuffer.camera.validate();
}

GtaoResult computeGtao(const GBuffer& gbuffer, const GtaoConstants& constants) {
    checkGtaoBuffers(gbuffer, constants);
    GtaoResult r;
    r.visibility = Image(constants.width, constants.height, 1, 1.0f);
    r.bentNormal = Image(constants.width, constants.height, 3, 0.0f);
    if (constants.width < 1 || constants.height < 1) return r;
    const GtaoDepthMips mips = buildGtaoDepthMips(gbuffer.depth, constants.mipLevels);
    parallelFor(std::size_t(constants.height), [&](std::size_t begin, std::size_t end) {
        for (std::size_t yy = begin; yy < end; ++yy) {
            const int y = int(yy);
            for (int x = 0; x < constants.width; ++x) {
                GtaoPixel px = gtaoPixel(constants, gbuffer, &mips, x, y, interleaveIndex(x, y));
                r.visibility.at(x, y) = px.visibility;
                r.bentNormal.at(x, y, 0) = px.bentNormal.x;
                r.bentNormal.at(x, y, 1) = px.bentNormal.y;
                r.bentNormal.at(x, y, 2) = px.bentNormal.z;
            }
        }
    });
    return r;
}

GtaoResult computeGtao(const GBuffer& gbuffer, const GtaoSettings& settings) {
    settings.validate();
    return computeGtao(gbuffer, gtaoConstants(settings, gbuffer.camera));
}

} // namespace obscura::ssao
