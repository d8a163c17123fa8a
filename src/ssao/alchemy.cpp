// Alchemy screen-space ambient obscurance: McGuire et al. 2011, "The Alchemy Screen-Space Ambient
// Obscurance Algorithm", eq. 10, with the spiral sampling and the alternative formulation of "Where Corners
// Stay Dark" (Alchemy SSAO in an IBL renderer). Contract in include/obscura/alchemy.h.
#include "obscura/alchemy.h"
#include "alchemy_row.h"

#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/sampling.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <string>
#include <type_traits>

namespace obscura::ssao {

namespace {

bool isSkyDepth(float d) { return !(d < 1e30f); }

// Exact floor without a libm call (SSE2 has no rounding instruction): truncate, then step down below zero.
inline int floorToInt(float v) {
    const int i = int(v);
    return i - (float(i) > v ? 1 : 0);
}

// 4 x 4 Bayer order: neighbouring pixels get rotations far apart, so a small blur sees all of them.
constexpr int kBayer4[16] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};

template <class T> void checkRange(bool ok, const char* field, const std::string& range, T value) {
    if constexpr (std::is_integral_v<T>) {
        if (!ok) fail(field, "must be in " + range + ", is " + std::to_string(value));
    } else {
        if (!ok) fail(field, "must be in " + range + ", is " + numberText(value));
    }
}

} // namespace

void AlchemySettings::validate() const {
    checkRange(radius > 0.0f && radius <= 1e4f, "radius", "(0, 1e4] m", radius);
    checkRange(intensity >= 0.0f && intensity <= 1000.0f, "intensity", "[0, 1000]", intensity);
    checkRange(contrast >= 0.01f && contrast <= 100.0f, "contrast", "[0.01, 100]", contrast);
    checkRange(bias >= 0.0f && bias <= 1.0f, "bias", "[0, 1] m", bias);
    checkRange(epsilon > 0.0f && epsilon <= 1.0f, "epsilon", "(0, 1] m^2", epsilon);
    checkRange(samples >= 1 && samples <= kAlchemyMaxSamples, "samples", "[1, 1024]", samples);
    checkRange(maxRadiusPixels >= 1.0f && maxRadiusPixels <= 4096.0f, "max-radius-px", "[1, 4096] px",
               maxRadiusPixels);
    checkRange(lodRadiusPixels >= 0.0f && lodRadiusPixels <= 4096.0f, "lod-radius-px", "[0, 4096] px",
               lodRadiusPixels);
    // The level of detail keeps one offset table per sample count; 256 counts x 16 classes is 4 MB.
    if (lodRadiusPixels > 0.0f && samples > 256) fail("samples", "at most 256 with the level of detail on");
    checkRange(guardBand >= 0 && guardBand <= 1024, "guard-band", "[0, 1024] px", guardBand);
}

AlchemySettings alchemyPreset(const std::string& name) {
    AlchemySettings s;
    s.formulation = AlchemyFormulation::Chapter;
    if (name == "scene") {
        s.radius = 0.05f;
        s.intensity = 2.0f;
        s.contrast = 3.0f;
    } else if (name == "closeup") {
        s.radius = 0.08f;
        s.intensity = 1.7f;
        s.contrast = 2.2f;
    } else {
        fail("preset", "unknown alchemy preset '" + name + "' (scene, closeup)");
    }
    return s;
}

namespace {

// The one message for a band that leaves no pixel, wherever the band is first applied: the estimator's
// constants, or the crop a caller makes of its G-buffer before it (which would otherwise size an image by a
// negative count).
void checkGuardBand(int guardBand, int width, int height) {
    if (guardBand < 0 || width <= 2 * guardBand || height <= 2 * guardBand)
        fail("guard-band", std::to_string(guardBand) + " px leaves nothing of a " + std::to_string(width) + "x" +
                               std::to_string(height) + " buffer");
}

} // namespace

AlchemyConstants alchemyConstants(const AlchemySettings& s, const Camera& camera) {
    s.validate();
    camera.validate();
    checkGuardBand(s.guardBand, camera.width, camera.height);
    AlchemyConstants k{};
    k.width = camera.width;
    k.height = camera.height;
    k.guardBand = s.guardBand;
    k.formulation = s.formulation == AlchemyFormulation::Paper ? kAlchemyPaper : kAlchemyChapter;
    k.samples = s.samples;
    k.minSamples = s.lodRadiusPixels > 0.0f ? std::max(1, s.samples / 4) : s.samples;
    k.seed = s.seed;
    const Camera::PixelToView view = camera.viewFromPixelAffine();
    k.viewScaleX = view.mulX;
    k.viewOffsetX = view.addX;
    k.viewScaleY = view.mulY;
    k.viewOffsetY = view.addY;
    k.focalPixels = camera.focalPixels();
    k.radius = s.radius;
    k.radius2 = s.radius * s.radius;
    k.maxRadiusPixels = s.maxRadiusPixels;
    k.lodRadiusPixels = s.lodRadiusPixels;
    k.bias = s.bias;
    k.contrast = s.contrast;
    if (s.formulation == AlchemyFormulation::Paper) {
        k.denominator = s.epsilon;
        k.intensity = 2.0f * s.intensity;
    } else {
        const float c = 0.1f * s.radius;  // the chapter's near clamp
        k.denominator = c * c;
        k.intensity = 2.0f * kPi * c * s.intensity;
    }
    return k;
}

Camera guardBandCamera(const Camera& camera, int guardBand) {
    // No band, the very camera: the round trip through tan and atan in float moved 75 degrees to 75.0000153 at a
    // height of 91, and render --ao alchemy's G-buffer no longer matched its camera.json (AO 0.036 apart in ao).
    if (guardBand == 0) return camera;
    Camera c = camera;
    c.width = camera.width + 2 * guardBand;
    c.height = camera.height + 2 * guardBand;
    // Same focal length in pixels: tan(fov'/2) grows with the height.
    constexpr double pi = 3.14159265358979323846;
    const double t = std::tan(double(camera.fovY) * pi / 360.0) * double(c.height) / double(camera.height);
    c.fovY = float(2.0 * std::atan(t) * 180.0 / pi);
    return c;
}

Image cropGuardBand(const Image& image, int g) {
    if (g == 0) return image;
    checkGuardBand(g, image.width, image.height);
    Image out(image.width - 2 * g, image.height - 2 * g, image.channels);
    out.channelNames = image.channelNames;
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < image.channels; ++c) out.at(x, y, c) = image.at(x + g, y + g, c);
    return out;
}

GBuffer cropGuardBand(const GBuffer& g, const Camera& innerCamera, int guardBand) {
    GBuffer out;
    out.camera = innerCamera;
    out.depth = cropGuardBand(g.depth, guardBand);
    out.normal = g.normal.empty() ? Image() : cropGuardBand(g.normal, guardBand);
    out.albedo = g.albedo.empty() ? Image() : cropGuardBand(g.albedo, guardBand);
    out.motion = g.motion.empty() ? Image() : cropGuardBand(g.motion, guardBand);
    return out;
}

Image normalsFromDepth(const Image& depth, const Camera& camera) {
    const int w = depth.width, h = depth.height;
    Image out(w, h, 3);
    auto position = [&](int x, int y) { return camera.viewFromPixel(float(x) + 0.5f, float(y) + 0.5f, depth.at(x, y)); };
    auto usable = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && !isSkyDepth(depth.at(x, y)); };
    // How badly the neighbour at (x + dx, y + dy) fits the centre's surface, relative, +inf if unusable. The
    // depth difference (the rule that keeps silhouettes apart) alone ties at a crease seen symmetrically,
    // where both neighbours are equally far in depth; so where the next pixel exists, the test is whether
    // the two pixels on that side continue the centre's plane: 1/depth is affine in screen space on a
    // plane, so 2/d1 - 1/d2 - 1/d0 vanishes exactly there and not across a crease or a silhouette.
    auto misfit = [&](int x, int y, int dx, int dy) {
        if (!usable(x + dx, y + dy)) return INFINITY;
        const float d0 = depth.at(x, y), d1 = depth.at(x + dx, y + dy);
        if (!usable(x + 2 * dx, y + 2 * dy)) return std::fabs(d1 - d0) / d0;
        const float d2 = depth.at(x + 2 * dx, y + 2 * dy);
        return std::fabs(2.0f / d1 - 1.0f / d2 - 1.0f / d0) * d0;
    };
    // Whether the neighbour at (x + dx, y + dy) is taken over the one opposite. Where only one side has a second
    // neighbour (the other is next to the border or the sky), a plane test and a depth step are not comparable:
    // a steep surface's own neighbour steps far in depth while the pixel across a crease passes a plane test
    // fairly well, and a pixel one in from the border took its difference across the crease (33 degrees off).
    // There the long side is taken if it continues the centre's plane (kPlaneMisfit, far above rounding, far
    // below a crease's), else the short one.
    constexpr float kPlaneMisfit = 1e-4f;
    auto prefer = [&](int x, int y, int dx, int dy) {
        // Only one side there: that one, whatever its misfit. A misfit that overflowed to inf (depths 1e29 and
        // 1e-10 side by side) or went NaN (a depth of 0) tied with the missing side's inf, and the pixel off the
        // image was read.
        if (const bool useA = usable(x + dx, y + dy); useA != usable(x - dx, y - dy)) return useA;
        const float a = misfit(x, y, dx, dy), b = misfit(x, y, -dx, -dy);
        const bool longA = usable(x + dx, y + dy) && usable(x + 2 * dx, y + 2 * dy);
        const bool longB = usable(x - dx, y - dy) && usable(x - 2 * dx, y - 2 * dy);
        if (longA != longB && a < INFINITY && b < INFINITY) return longA ? a <= kPlaneMisfit : b > kPlaneMisfit;
        return a <= b;
    };
    parallelFor(std::size_t(h), [&](std::size_t y0, std::size_t y1) {
        for (int y = int(y0); y < int(y1); ++y)
            for (int x = 0; x < w; ++x) {
                Vec3 n{0, 0, 1};
                if (!isSkyDepth(depth.at(x, y))) {
                    // Scaled by 1/depth before any product: at depths of 1e21 the cross product's squares overflowed
                    // float and the normal came out NaN (`ao` then blamed a normal buffer it had made itself). The
                    // directions do not change; 1e-30 bounds the scale for depths nearer than any scene.
                    const float scale = 1.0f / std::max(depth.at(x, y), 1e-30f);
                    const Vec3 unscaled = position(x, y), p = unscaled * scale;
                    const bool alongX = usable(x - 1, y) || usable(x + 1, y), alongY = usable(x, y - 1) || usable(x, y + 1);
                    const Vec3 ddx = !alongX ? Vec3{}
                                     : (prefer(x, y, 1, 0) ? position(x + 1, y) - unscaled : unscaled - position(x - 1, y)) * scale;
                    const Vec3 ddy = !alongY ? Vec3{}
                                     : (prefer(x, y, 0, 1) ? position(x, y + 1) - unscaled : unscaled - position(x, y - 1)) * scale;
                    if (alongX && alongY) {
                        // Pixel y grows downwards, so cross(ddy, ddx) points out of a camera-facing plane.
                        n = normalize(cross(ddy, ddx));
                        if (dot(n, p) > 0.0f) n = -n;
                    } else if (alongX || alongY) {
                        // One axis only (an image one pixel wide or tall, a one-pixel-wide strip against the sky):
                        // the normal across that tangent in the plane of the tangent and the view ray. Facing the
                        // camera outright made an open plane's 1-pixel-wide column fully occluded (A = 0).
                        const Vec3 t = alongX ? ddx : ddy;
                        const Vec3 across = t * (dot(p, t) / dot(t, t)) - p;  // 0 for a tangent along the ray
                        n = dot(across, across) > 0.0f ? normalize(across) : -normalize(p);
                    } else {
                        n = -normalize(p);
                    }
                }
                for (int c = 0; c < 3; ++c) out.at(x, y, c) = n[c];
            }
    });
    return out;
}

AlchemyInput alchemyInput(const GBuffer& g, bool rebuildNormals) {
    AlchemyInput in;
    in.width = g.width();
    in.height = g.height();
    in.depth = g.depth.pixels.data();
    if (rebuildNormals) {
        in.rebuiltNormals = normalsFromDepth(g.depth, g.camera);
        in.normal = in.rebuiltNormals.pixels.data();
    } else {
        in.normal = g.normal.pixels.data();
    }
    return in;
}

SpiralTable alchemySpiral(const AlchemyConstants& k) {
    SpiralTable t;
    t.maxSamples = k.samples;
    t.minSamples = k.minSamples;
    const double shift = double(toUnitFloat(hash32(k.seed)));
    for (int count = k.minSamples; count <= k.samples; ++count)
        for (int cls = 0; cls < kAlchemyPixelClasses; ++cls) {
            const double phi = 2.0 * double(kPi) * (double(kBayer4[cls]) + shift) / kAlchemyPixelClasses;
            const double turns = 7.0 * count / 9.0;
            std::vector<float> o(2 * std::size_t(count));
            for (int i = 0; i < count; ++i) {
                const double alpha = (i + 0.5) / count;
                const double theta = 2.0 * double(kPi) * alpha * turns + phi;
                o[2 * std::size_t(i)] = float(alpha * std::cos(theta));
                o[2 * std::size_t(i) + 1] = float(alpha * std::sin(theta));
            }
            t.offsets.push_back(std::move(o));
        }
    const std::size_t n = std::size_t(k.samples);
    t.rowX.resize(kAlchemyPixelClasses * n);
    t.rowY.resize(kAlchemyPixelClasses * n);
    for (int row = 0; row < kAlchemyClassTile; ++row)
        for (int col = 0; col < kAlchemyClassTile; ++col) {
            const float* o = t.at(k.samples, row * kAlchemyClassTile + col);
            for (std::size_t i = 0; i < n; ++i) {
                const std::size_t j = std::size_t(row) * kAlchemyClassTile * n + kAlchemyClassTile * i + std::size_t(col);
                t.rowX[j] = o[2 * i];
                t.rowY[j] = o[2 * i + 1];
            }
        }
    return t;
}

float alchemyPixel(const AlchemyConstants& k, const AlchemyInput& in, const SpiralTable& spiral, int x, int y) {
    const std::size_t c = std::size_t(y) * std::size_t(k.width) + std::size_t(x);
    const float d = in.depth[c];
    if (isSkyDepth(d)) return 1.0f;
    const float fx = float(x) + 0.5f, fy = float(y) + 0.5f;
    const float cx = (fx * k.viewScaleX + k.viewOffsetX) * d, cy = (fy * k.viewScaleY + k.viewOffsetY) * d, cz = -d;
    const float nx = in.normal[3 * c], ny = in.normal[3 * c + 1], nz = in.normal[3 * c + 2];
    const float radiusPixels = std::min(k.radius * k.focalPixels / d, k.maxRadiusPixels);
    int count = k.samples;
    if (k.lodRadiusPixels > 0.0f && radiusPixels < k.lodRadiusPixels)
        count = std::clamp(int(std::ceil(float(k.samples) * radiusPixels / k.lodRadiusPixels)), k.minSamples, k.samples);
    const float* offsets = spiral.at(count, (y % kAlchemyClassTile) * kAlchemyClassTile + x % kAlchemyClassTile);
    // Paper: + z_C beta with z_C < 0; chapter: - bias. Both are one constant per pixel.
    const float shift = k.formulation == kAlchemyPaper ? cz * k.bias : -k.bias;
    // The paper drops samples at |v| >= r, the chapter's step() keeps |v| = r: one ulp of r^2 apart.
    const float radius2 = k.formulation == kAlchemyPaper ? k.radius2 : std::nextafter(k.radius2, INFINITY);
    const bool paper = k.formulation == kAlchemyPaper;
    float sum = 0.0f;
    for (int i = 0; i < count; ++i) {
        const int sx = floorToInt(fx + offsets[2 * i] * radiusPixels);
        const int sy = floorToInt(fy + offsets[2 * i + 1] * radiusPixels);
        if (unsigned(sx) >= unsigned(k.width) || unsigned(sy) >= unsigned(k.height)) continue;  // unseen: empty
        // A sky sample (+inf) becomes a point 1e18 m away: finite arithmetic, and far outside the radius.
        const float ds = std::min(in.depth[std::size_t(sy) * std::size_t(k.width) + std::size_t(sx)], 1e18f);
        const float vx = ((float(sx) + 0.5f) * k.viewScaleX + k.viewOffsetX) * ds - cx;
        const float vy = ((float(sy) + 0.5f) * k.viewScaleY + k.viewOffsetY) * ds - cy;
        const float vz = -ds - cz;
        const float vv = vx * vx + vy * vy + vz * vz;
        const float vn = std::max(0.0f, vx * nx + vy * ny + vz * nz + shift);
        const float term = vn / (paper ? vv + k.denominator : std::max(k.denominator, vv));
        // Heaviside term as a 0/1 factor: the test is data-dependent, so a branch would mispredict.
        sum += term * float(vv < radius2);
    }
    const float a = std::max(0.0f, 1.0f - k.intensity / float(count) * sum);
    return k.contrast == 1.0f ? a : std::pow(a, k.contrast);
}

// What a CPU without AVX2 and FMA runs (x86-64 CPUs with them take alchemyRowAvx2). Built for the baseline
// only, so the tests that call it check the very code those CPUs run; fp-contract is off in ISO C++ mode, so it
// performs alchemyPixel's exact operations and gives its bits.
bool alchemyRowPortable(const AlchemyConstants& k, const AlchemyInput& in, const SpiralTable& spiral, int y, int x0,
                        int x1, float* out) {
    constexpr int kMax = 64;
    const int n = x1 - x0;
    assert(n >= 0 && n <= kMax);
    float fx[kMax], cx[kMax], cy[kMax], cz[kMax], nx[kMax], ny[kMax], nz[kMax], rpx[kMax], shift[kMax], sum[kMax];
    const std::size_t rowStart = std::size_t(y) * std::size_t(k.width);
    const bool paper = k.formulation == kAlchemyPaper;
    const float fy = float(y) + 0.5f;
    bool bad = false;
    for (int j = 0; j < n; ++j) {
        const std::size_t c = rowStart + std::size_t(x0 + j);
        const float d = in.depth[c];
        bad |= !pixelValid(d, &in.normal[3 * c]);
        fx[j] = float(x0 + j) + 0.5f;
        cx[j] = (fx[j] * k.viewScaleX + k.viewOffsetX) * d;
        cy[j] = (fy * k.viewScaleY + k.viewOffsetY) * d;
        cz[j] = -d;
        nx[j] = in.normal[3 * c];
        ny[j] = in.normal[3 * c + 1];
        nz[j] = in.normal[3 * c + 2];
        rpx[j] = std::min(k.radius * k.focalPixels / d, k.maxRadiusPixels);
        shift[j] = paper ? cz[j] * k.bias : -k.bias;
        sum[j] = 0.0f;
    }
    if (bad) return false;  // a NaN centre would reach a float-to-int conversion
    // The offsets of the four pixel classes of this row, interleaved: sample i of class (x mod 4) is at 4 i + x mod 4.
    const std::size_t classRow = std::size_t(y % kAlchemyClassTile) * kAlchemyClassTile * std::size_t(k.samples);
    const float* ox = spiral.rowX.data() + classRow;
    const float* oy = spiral.rowY.data() + classRow;
    const float radius2 = paper ? k.radius2 : std::nextafter(k.radius2, INFINITY);
    const int width = k.width, height = k.height;
    for (int i = 0; i < k.samples; ++i) {
        float oxr[kMax], oyr[kMax];  // this sample's offset for each pixel of the segment
        for (int j = 0; j < n; ++j) {
            oxr[j] = ox[4 * std::size_t(i) + std::size_t((x0 + j) & 3)];
            oyr[j] = oy[4 * std::size_t(i) + std::size_t((x0 + j) & 3)];
        }
        for (int j = 0; j < n; ++j) {
            const int sx = floorToInt(fx[j] + oxr[j] * rpx[j]);
            const int sy = floorToInt(fy + oyr[j] * rpx[j]);
            const bool inside = (unsigned(sx) < unsigned(width)) & (unsigned(sy) < unsigned(height));
            // An off-screen sample reads the centre instead and is then multiplied by 0.
            const int index = inside ? sy * width + sx : y * width + x0 + j;
            const float ds = std::min(in.depth[index], 1e18f);
            const float vx = ((float(sx) + 0.5f) * k.viewScaleX + k.viewOffsetX) * ds - cx[j];
            const float vy = ((float(sy) + 0.5f) * k.viewScaleY + k.viewOffsetY) * ds - cy[j];
            const float vz = -ds - cz[j];
            const float vv = vx * vx + vy * vy + vz * vz;
            const float vn = std::max(0.0f, vx * nx[j] + vy * ny[j] + vz * nz[j] + shift[j]);
            const float term = vn / (paper ? vv + k.denominator : std::max(k.denominator, vv));
            sum[j] += term * float((vv < radius2) & inside);
        }
    }
    for (int j = 0; j < n; ++j) {
        const float a = std::max(0.0f, 1.0f - k.intensity / float(k.samples) * sum[j]);
        const float v = k.contrast == 1.0f ? a : std::pow(a, k.contrast);
        out[j] = isSkyDepth(in.depth[rowStart + std::size_t(x0 + j)]) ? 1.0f : v;
    }
    return true;
}

bool alchemyRow(const AlchemyConstants& k, const AlchemyInput& in, const SpiralTable& spiral, int y, int x0, int x1,
                float* out) {
#ifdef OBSCURA_HAVE_ALCHEMY_AVX2
    static const bool avx2 = detail::haveAvx2Fma();
    if (avx2) return detail::alchemyRowAvx2(k, in, spiral, y, x0, x1, out);
#endif
    return alchemyRowPortable(k, in, spiral, y, x0, x1, out);
}

void validateAlchemyGBuffer(const GBuffer& g, const AlchemySettings& s) {
    const std::string what = "alchemy G-buffer";
    if (!s.normalsFromDepth) return g.validate(what);
    GBuffer depthOnly;
    depthOnly.camera = g.camera;
    depthOnly.depth = g.depth;
    depthOnly.normal = Image(g.width(), g.height(), 3);  // validate() wants one; it is rebuilt
    depthOnly.validate(what);
}

Image alchemyAO(const GBuffer& g, const AlchemySettings& s) {
    const AlchemyConstants k = alchemyConstants(s, g.camera);
    const std::string what = "alchemy G-buffer";
    if (s.normalsFromDepth || s.guardBand > 0) {
        validateAlchemyGBuffer(g, s);
    } else {
        // The pixels are checked where the kernel reads them anyway (the row kernels check the centres they
        // load; the level-of-detail path scans its tile): the G-buffer comes from memory once, not twice.
        g.validateShape(what);
    }
    const bool checkHere = !s.normalsFromDepth && s.guardBand == 0;
    std::atomic<bool> bad{false};
    const AlchemyInput in = alchemyInput(g, s.normalsFromDepth);
    const SpiralTable spiral = alchemySpiral(k);
    const int gb = k.guardBand, w = k.width - 2 * gb, h = k.height - 2 * gb;
    Image out(w, h, 1);
    // Tiles of 64 x 16 pixels: neighbouring pixels sample overlapping discs, so a tile's samples share a
    // footprint of (64 + 2 R_px) x (16 + 2 R_px) depths that stays in cache, where a whole row's would not.
    constexpr int kTileW = 64, kTileH = 16;
    const int tilesX = (w + kTileW - 1) / kTileW, tilesY = (h + kTileH - 1) / kTileH;
    parallelFor(std::size_t(tilesX) * std::size_t(tilesY), [&](std::size_t t0, std::size_t t1) {
        for (std::size_t t = t0; t < t1; ++t) {
            const int x0 = int(t % std::size_t(tilesX)) * kTileW, y0 = int(t / std::size_t(tilesX)) * kTileH;
            const int x1 = std::min(w, x0 + kTileW), y1 = std::min(h, y0 + kTileH);
            auto row = [&](int y) { return &out.pixels[std::size_t(y) * std::size_t(w)]; };
            if (k.minSamples == k.samples) {
                for (int y = y0; y < y1; ++y)
                    if (!alchemyRow(k, in, spiral, y + gb, x0 + gb, x1 + gb, row(y) + x0))
                        bad.store(true, std::memory_order_relaxed);
                continue;
            }
            // A tile with a bad centre is not computed (a NaN depth would reach a float-to-int conversion).
            if (checkHere && !g.pixelsValid(x0, x1, y0, y1)) {
                bad.store(true, std::memory_order_relaxed);
                continue;
            }
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) row(y)[x] = alchemyPixel(k, in, spiral, x + gb, y + gb);
        }
    });
    if (bad.load()) {
        g.validate(what);  // throws, naming the first bad pixel
        fail(what, "has a pixel with a bad depth or normal");  // not reached: a row reports only bad centres
    }
    return out;
}

trace::ObscuranceSettings rayTracedEquivalent(const AlchemySettings& s, int rays) {
    s.validate();
    trace::ObscuranceSettings t;
    t.falloff = trace::Falloff::Alchemy;
    t.radius = s.radius;
    t.rays = rays;
    if (s.formulation == AlchemyFormulation::Paper) {
        // sigma t / (t^2 + eps) ~ sigma t / max(eps, t^2) = (sigma / u) u t / max(u, t)^2 with u^2 = eps.
        t.alchemyU = std::sqrt(s.epsilon);
        t.alchemyScale = s.intensity / t.alchemyU;
    } else {
        // scale (2 pi c / n) sum -> scale c Integral (v.n) / max(c^2, v.v) dw = (1/pi) Integral pi scale g_c cos dw.
        t.alchemyU = 0.1f * s.radius;
        t.alchemyScale = kPi * s.intensity;
    }
    return t;
}

} // namespace obscura::ssao
