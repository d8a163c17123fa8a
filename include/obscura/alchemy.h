// Alchemy screen-space ambient obscurance, CPU reference.
//
// McGuire, Osman, Bukowski, Hennessy 2011, "The Alchemy Screen-Space Ambient Obscurance Algorithm"
// (HPG 2011), eq. 9-10, and the formulation of "Where Corners Stay Dark" (Alchemy SSAO in an IBL renderer,
// 2026), selectable so users of either source get its numbers:
//
//   paper:   A = max(0, 1 - (2 sigma / s) sum_i max(0, v_i.n + z_C beta) H(r - |v_i|) / (v_i.v_i + eps))^k
//   chapter: A = max(0, 1 - scale (2 pi c / n) sum_i max(0, v_i.n - bias) H(R - |v_i|) / max(c^2, v_i.v_i))^k,
//            c = 0.1 R
//
// v_i runs from the pixel's view-space point C (z_C < 0) to the visible point under sample i, placed on the
// chapter's spiral in both forms: alpha = (i + 0.5) / n, screen radius h = alpha R_px, angle 2 pi alpha (7n/9)
// + phi. That departs from the paper's §2.3, which picks Q' uniformly over the disk's area (radius
// sqrt(alpha) R_px): the spiral is denser near the centre. Against the ray-traced integral at 160x120, 64
// samples, sigma 1, a scratch build with the area-uniform radius measured MAE 0.025 (corner), 0.033 (stairs),
// 0.041 (well) against the spiral's 0.037, 0.039, 0.039 (2026-11-28): neither is better everywhere, and the
// "paper" rows of docs/QUALITY.md are the spiral's. R_px = r * focal / depth (clamped to a maximum) and phi is
// a rotation per 4 x 4 pixel class. Samples off the buffer or on sky are dropped (they count in s: unseen
// space is empty, as the paper assumes).
//
// The ray-traced integral it approximates (trace::ambientObscurance with trace::Falloff::Alchemy) is
// given by rayTracedEquivalent(): were its samples uniform directions, eq. 10 would estimate
// A = 1 - (1/pi) Integral g(t) cos dw with g(t) = sigma t / (t^2 + eps) ~ sigma u t / max(u, t)^2 / u,
// u = sqrt(eps); for the chapter, g(t) = pi scale c t / max(c, t)^2. Screen-space samples and unseen
// occluders make it an approximation; docs/QUALITY.md measures how close.
//
// Errors: AlchemySettings::validate(), alchemyConstants() and alchemyAO() throw obscura::Error for bad
// settings or buffers. alchemyPixel() is the hot path and checks nothing.
#pragma once

#include "obscura/alchemy_constants.h"
#include "obscura/bilateral.h"
#include "obscura/camera.h"
#include "obscura/gbuffer.h"
#include "obscura/image.h"
#include "obscura/trace.h"

#include <cstdint>
#include <string>
#include <vector>

namespace obscura::ssao {

enum class AlchemyFormulation { Paper, Chapter };

struct AlchemySettings {
    AlchemyFormulation formulation = AlchemyFormulation::Paper;
    float radius = 0.5f;          // r (R in the chapter): m, (0, 1e4]; the paper's default 0.5 m
    // sigma (paper): m, as eq. 10's sum is per metre (so the paper's A changes with the scene's scale: 0.986 ->
    // 0.999 for a well scaled x10 with r, eps); scale (chapter): unitless. [0, 1000]; paper default 1.
    float intensity = 1.0f;
    float contrast = 1.0f;        // k: unitless, [0.01, 100]; paper default 1 (no curve)
    float bias = 1e-4f;           // beta (paper, m, multiplied by z_C) or bias (chapter, m): [0, 1]; paper 1e-4
    float epsilon = 1e-4f;        // eps of the paper's denominator: m^2, (0, 1]; paper 1e-4 (chapter: unused)
    int samples = 12;             // s: per pixel, [1, 1024]; the paper's 12
    float maxRadiusPixels = 256;  // clamp of R_px: px, [1, 4096]; bounds the cost of pixels near the camera
    // Level of detail (paper Fig. 5, Table 1): a pixel whose R_px is below this gets
    // ceil(samples * R_px / lodRadiusPixels) samples, at least max(1, samples / 4). px, [0, 4096]; 0 = off.
    float lodRadiusPixels = 0.0f;
    // Pixels the G-buffer extends beyond the output on every side (paper §3); the result is cropped.
    int guardBand = 0;            // px, [0, 1024]
    bool normalsFromDepth = false;  // ignore the G-buffer's normals and rebuild them from depth
    std::uint32_t seed = 0;       // rotation of the spiral per pixel class: any value

    void validate() const;        // throws obscura::Error naming the bad field
};

// The chapter's two calibrations: "scene" (camera several meters away: R 0.05, scale 2.0, contrast 3.0)
// and "closeup" (camera centimeters away: R 0.08, scale 1.7, contrast 2.2). Throws for another name.
AlchemySettings alchemyPreset(const std::string& name);

// Settings + camera of the buffers the kernel reads (guard band included) -> kernel constants. Pure;
// validates (throws obscura::Error).
AlchemyConstants alchemyConstants(const AlchemySettings& settings, const Camera& bufferCamera);

// The camera of a G-buffer with `guardBand` extra pixels on every side and the same focal length, so the
// inner pixels see exactly what `camera` sees. A negative guardBand gives the inner camera of a buffer that
// already has one.
Camera guardBandCamera(const Camera& camera, int guardBand);
// The inner image (or G-buffer) without its guard band.
Image cropGuardBand(const Image& image, int guardBand);
GBuffer cropGuardBand(const GBuffer& gbuffer, const Camera& innerCamera, int guardBand);

// View-space unit normals rebuilt from depth alone: on each axis the neighbour that continues the centre's plane
// is used (1/depth is affine in screen space on a plane: the pixel and the next one on each side are tested;
// where a side has only one pixel, its relative depth step), so neither a crease nor a silhouette bends the
// normals of the surface the pixel lies on. A pixel with a
// usable neighbour along one axis only takes the normal across that tangent in the plane of the tangent and
// the view ray; sky and pixels without a usable neighbour face the camera. Returns a 3-channel image.
Image normalsFromDepth(const Image& depth, const Camera& camera);

// The G-buffer as the kernel reads it, as the GPU pass will: the depth plane (one float per sample; the
// view position is rebuilt from the pixel and the constants) and the centre pixel's normal.
struct AlchemyInput {
    int width = 0, height = 0;
    const float* depth = nullptr;   // width * height linear depths, +inf for sky
    const float* normal = nullptr;  // width * height * 3 view normals (x, y, z)
    Image rebuiltNormals;           // owns the normals when they are rebuilt from depth
};
// References the G-buffer's depth and normals (or rebuilds normals into the input); the G-buffer must
// outlive the input.
AlchemyInput alchemyInput(const GBuffer& gbuffer, bool normalsFromDepth);

// Unit-radius spiral offsets for each pixel class and each sample count a pixel can get.
struct SpiralTable {
    int maxSamples = 0, minSamples = 0;
    // offsets(count, cls) -> 2 * count floats (x0, y0, x1, y1, ...): alpha_i (cos theta_i, sin theta_i).
    std::vector<std::vector<float>> offsets;  // index (count - minSamples) * kAlchemyPixelClasses + cls
    const float* at(int count, int cls) const {
        return offsets[std::size_t(count - minSamples) * kAlchemyPixelClasses + std::size_t(cls)].data();
    }
    // The maxSamples offsets of the four classes of each class row (y mod 4), interleaved for alchemyRow:
    // sample i of class (x mod 4) at [(y mod 4) * 4 * maxSamples + 4 i + x mod 4].
    std::vector<float> rowX, rowY;
};
SpiralTable alchemySpiral(const AlchemyConstants& k);

// Raw obscurance of pixel (x, y) of the buffers, before cropping. Hot path: no checks.
float alchemyPixel(const AlchemyConstants& k, const AlchemyInput& in, const SpiralTable& spiral, int x, int y);

// The same as alchemyPixel for the pixels [x0, x1) of row y (x1 - x0 <= 64), all at once: each sample index
// is evaluated for the whole segment before the next, so the loop over pixels vectorises (gathers). Needs the
// level of detail off (one sample count for every pixel). Hot path: checks only the centres it reads, with
// GBuffer::pixelsValid's test, and returns false (its output then undefined) if one has a bad depth or normal.
// On x86-64 CPUs with AVX2 and FMA it runs a version written with intrinsics, which fuses multiply-adds and
// so agrees with alchemyPixel to rounding (a sample at |v| = r may fall on either side of the radius; with bias
// 0 a flat neighbourhood's v.n is rounding noise that eq. 10 divides by v.v + eps: measured 1.9e-4 apart on the
// demo view, tested to 5e-4 by RowPathsWithoutBiasAgreeToTheAmplifiedRounding);
// elsewhere alchemyRowPortable, which performs alchemyPixel's operations in order and gives its bits. Tests
// call both. Either way the output does not depend on the thread count.
bool alchemyRow(const AlchemyConstants& k, const AlchemyInput& in, const SpiralTable& spiral, int y, int x0, int x1,
                float* out);
bool alchemyRowPortable(const AlchemyConstants& k, const AlchemyInput& in, const SpiralTable& spiral, int y, int x0,
                        int x1, float* out);

// Checks every pixel the estimator reads: depth and, unless settings.normalsFromDepth, normals (which may
// then be absent); throws obscura::Error naming the first bad pixel. alchemyAO checks as it goes instead
// where it can; the GPU pass calls this.
void validateAlchemyGBuffer(const GBuffer& gbuffer, const AlchemySettings& settings);

// Raw obscurance A in [0,1] for every pixel, guard band cropped: a 1-channel image of
// (width - 2 guardBand) x (height - 2 guardBand). Sky pixels are 1. Validates the G-buffer (size, NaN
// depths, normals) and settings; throws obscura::Error naming the problem. Deterministic: the same bits
// for any number of threads.
Image alchemyAO(const GBuffer& gbuffer, const AlchemySettings& settings);

// The ray-traced obscurance settings of the same integral (same falloff, same radius), for comparisons
// against trace::ambientObscurance. Valid for contrast 1 (the ray tracer has no contrast curve).
trace::ObscuranceSettings rayTracedEquivalent(const AlchemySettings& settings, int rays);

} // namespace obscura::ssao
