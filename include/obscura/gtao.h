// Ground-Truth Ambient Occlusion, CPU reference (Jimenez, Wu, Pesce and Jarabo 2016, "Practical
// Realtime Strategies for Accurate Indirect Occlusion", §4 and App. A).
//
// Per pixel and per slice direction phi, the maximum horizon on each side is searched in the depth buffer
// (eq. 6, horizon angles measured from the view vector), and the visible arc between the two horizons is
// integrated in closed form against the normal projected into the slice (eq. 7-8; App. A for the uniformly
// weighted variant). Visibility is binary within the radius r, so on scenes that are height fields seen
// from the camera it converges to ray-traced ambient occlusion with the same r.
//
// Errors: GtaoSettings::validate() and computeGtao() throw obscura::Error naming the bad setting or buffer.
// gtaoPixel() is the kernel: a hot path that checks nothing.
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/gtao_constants.h"
#include "obscura/gtao_mips.h"
#include "obscura/image.h"

#include <string>
#include <vector>

namespace obscura::ssao {

enum class GtaoWeighting { Cosine, Uniform };
enum class GtaoThickness { None, Heuristic, Bitmask };
enum class GtaoQuality { Low, Medium, High, Ultra };
// What a horizon sample farther than r stands for. Below the horizon GTAO assumes solid ground (the depth
// buffer read as a height field: each sample the front of a column that runs away from the camera), and
// that column can come within r even when its front does not: from a well's floor the rim is beyond r
// while the wall under it is not. Column keeps the assumption consistent and counts the column's part
// within r; Drop ignores the sample, as most implementations do, and loses that occlusion.
enum class GtaoBeyondRadius { Column, Drop };
// How a horizon sample at a continuous image position reads the depth buffer. Planar interpolates inverse
// depth over the 2x2 quad around it where those pixels lie on one plane, so the point stays on the slice
// line (five reads and four reciprocals). Nearest takes the nearest pixel's own point (one read), as XeGTAO
// does: at grazing angles that point can sit off the slice line by metres of depth and make a false
// horizon, so far open ground darkens (by up to 0.17 at a plane's far edge against the sky; elsewhere both
// are within 0.001 of each other against ray tracing: docs/QUALITY.md). Mip reads samples beyond
// 2 mipDistanceRatio pixels from a coarser level of a depth MIP chain (XeGTAO's depth MIPs; obscura/gtao_mips.h
// says how it is filtered), so that far samples of neighbouring pixels share texels and cache lines, and
// nearer ones as Nearest, as XeGTAO does. PlanarMip reads the nearer ones as Planar: that is where a pixel
// centre's point is farthest off the slice line (by an angle of up to 0.7 / d at d pixels), so it keeps far
// open ground open (1 - A below 0.008 where Nearest and Mip leave 0.17); on lavapipe it costs what Planar
// does (docs/PERFORMANCE.md). PlanarNearest reads the nearer samples (within 2 mipDistanceRatio pixels) as
// Planar and the farther ones as Nearest, without a chain: the far samples' point is off the slice line by
// a small angle, and a near one's is what makes Nearest's false horizons (docs/QUALITY.md). With rotated
// slices it keeps Planar's error against ray tracing (within 0.0002 MAE on the built-in views) for 0.64x its
// GTAO pass's time on an H100 (half resolution, 1920x1080; docs/PERFORMANCE.md).
enum class GtaoSampling { Planar, Nearest, Mip, PlanarMip, PlanarNearest };

struct GtaoSettings {
    float radius = 1.0f;            // r: m, (0, 1e4]; occluders farther than r from the point do not count
    float falloffStart = 1.0f;      // fraction of r where the conservative linear fade to 0 at r starts,
                                    // [0, 1]; 1 = hard cut at r, which is what binary AO of radius r means
                                    // (the paper always fades, from "a large enough distance" to r).
                                    // The bitmask thickness does not fade: a sample within r sets its sectors whole
    int sliceCount = 3;             // slice directions per pixel, [1, 64] (the `high` preset)
    int stepsPerSide = 3;           // horizon samples on each side of a slice, [1, 256]
    float maxRadiusPixels = 512.0f; // screen-space search radius clamp, pixels, [1, 8192]; bounds the cost
                                    // of points close to the camera (§4: "clamped to a maximum radius")
    float stepPower = 1.0f;         // sample distance s_k = ((k + jitter) / steps)^power, [1, 4]; > 1 puts
                                    // more samples near the centre. 1 measured closest to ray-traced AO on
                                    // every preset but low (docs/QUALITY.md)
    GtaoBeyondRadius beyondRadius = GtaoBeyondRadius::Column;
    GtaoSampling sampling = GtaoSampling::Planar;  // horizon samples' depth reads: Planar (5 reads, on the
                                                   // slice line), Nearest (1 read, as XeGTAO), Mip, PlanarMip
                                                   // or PlanarNearest
    int depthMipLevels = 4;         // with (Planar)Mip: coarse levels of the chain, [0, 4] (4: 5 MIPs, as XeGTAO's)
    float mipDistanceRatio = 7.0f;  // with (Planar)Mip: a sample d pixels away reads the coarsest level whose texels
                                    // are at most d / ratio pixels wide, [2, 64] (7: XeGTAO's MIP offset 3.3);
                                    // with PlanarNearest, samples from 2 ratio pixels out are nearest-pixel ones
    GtaoWeighting weighting = GtaoWeighting::Cosine;  // App. A's uniform weighting is an option
    GtaoThickness thickness = GtaoThickness::None;
    float thicknessBlend = 0.3f;    // eq. 9 blend towards a lower sample horizon, [0, 1): 0 = plain maximum
    float bitmaskThickness = 0.5f;  // assumed thickness of every occluder for the bitmask, m, (0, 1e4]
    bool jitter = false;            // per-pixel hashed slice rotation and step offsets (noise for a filter
                                    // to remove); false: the same regular slices everywhere
    bool interleave = false;        // slices rotated by the pixel's place in the 4x4 pattern of §4.1
                                    // (interleaveIndex), 16 direction classes per 4x4 block for a filter to
                                    // gather: stratified where jitter is white noise; not with jitter

    void validate() const;          // throws obscura::Error("gtao-<field>: ...")
};

// Slices x steps per side of each preset: low 1x2, medium 2x2, high 3x3, ultra 9x3 (as XeGTAO's).
void applyQuality(GtaoSettings& settings, GtaoQuality quality);

// Slice and step counts that replace a preset's, and per-pixel jitter: what `--gtao-slices`, `--gtao-steps`
// and `--gtao-jitter` set. Fewer slices, jittered, can match a preset's error once blurred (docs/QUALITY.md).
struct GtaoSliceOverride {
    int slices = 0;       // replaces sliceCount unless 0; GtaoSettings::validate checks what results
    int steps = 0;        // replaces stepsPerSide unless 0; the same
    bool jitter = false;  // sets GtaoSettings::jitter
    bool interleave = false;  // sets GtaoSettings::interleave
    bool empty() const { return slices == 0 && steps == 0 && !jitter && !interleave; }
    void apply(GtaoSettings& settings) const;
};

// "low", "medium", "high", "ultra"; throws obscura::Error for another name.
GtaoQuality parseQuality(const std::string& name);
const char* qualityName(GtaoQuality quality);
// The --gtao-sampling words, in GtaoSampling's order: "planar", "nearest", "mip", "planar-mip", "planar-nearest".
inline constexpr int kGtaoSamplingCount = 5;
const char* gtaoSamplingName(GtaoSampling sampling);
// Whether the sampling reads GtaoSettings::mipDistanceRatio: the depth MIP samplings, and planar-nearest for where
// its nearest-pixel samples start. The CLI's warnings and the methods' registry ask the same question.
inline constexpr bool gtaoSamplingReadsMipRatio(GtaoSampling s) {
    return s == GtaoSampling::Mip || s == GtaoSampling::PlanarMip || s == GtaoSampling::PlanarNearest;
}

// The pure function between settings and kernel: camera projection, radius and falloff, slice and step
// counts. `interleaved` rotates each pixel's slices by its place in the 4x4 pattern and by frameIndex
// (§4.1): with 1 slice (the paper's setting) a 4x4 block and 6 frames cover 96 directions, with k slices
// 96 k. settings.interleave does the same for any caller.
// Assumes validated settings and camera.
GtaoConstants gtaoConstants(const GtaoSettings& settings, const Camera& camera, int frameIndex = 0,
                            bool interleaved = false);

struct GtaoPixel {
    float visibility = 1.0f;  // A in [0, 1]: 1 = unoccluded
    Vec3 bentNormal;          // view space, unit: mean unoccluded direction (cosine-weighted); 0 for sky
};

// The kernel for one pixel of a G-buffer of the constants' size. Sky pixels give visibility 1 and a zero
// bent normal. Hot path: no checks.
GtaoPixel gtaoPixel(const GtaoConstants& constants, const GBuffer& gbuffer, int x, int y);
// The same with the interleave index (0..15) given, for grids that are not the G-buffer's own (half
// resolution evaluates full-resolution pixel (2x, 2y) with the pattern of low-resolution pixel (x, y)).
GtaoPixel gtaoPixel(const GtaoConstants& constants, const GBuffer& gbuffer, int x, int y, int interleave);

// The coarse levels of GtaoSampling::Mip's depth MIP chain (layout and filter in obscura/gtao_mips.h).
struct GtaoDepthMips {
    int width = 0, height = 0;  // of the depth buffer, level 0
    int levels = 0;             // coarse levels, [0, GTAO_MAX_MIP_LEVELS]
    std::vector<float> texels;  // inverse depths (0: sky), level 1 first, gtaoMipOffset(width, height, levels + 1)
    float at(int level, int x, int y) const;  // level in 1..levels, no checks
    // gtaoMipOffset and gtaoMipSize(width, .) of each level, so that at() does not loop over the levels.
    int offset[GTAO_MAX_MIP_LEVELS + 1] = {}, levelWidth[GTAO_MAX_MIP_LEVELS + 1] = {};
};
// The coarse levels the settings' sampling reads: depthMipLevels with GtaoSampling::Mip or PlanarMip, else 0.
int gtaoDepthMipLevels(const GtaoSettings& settings);
// The sampling as reports name it: "nearest-pixel samples", "depth MIP samples (5 levels, ratio 7)",
// "planar + depth MIP samples (...)", or "" for the default planar samples.
std::string gtaoSamplingText(const GtaoSettings& settings);
// Builds `levels` coarse levels from linear depths (+inf or >= 1e30 for sky). Assumes a depth image of at
// least 1x1 and levels in [0, GTAO_MAX_MIP_LEVELS].
GtaoDepthMips buildGtaoDepthMips(const Image& depth, int levels);

// The kernel with its depth MIP chain, which the constants' GTAO_SAMPLING_(PLANAR_)MIP needs (built from the same
// depth with constants.mipLevels levels); the overloads without it throw obscura::Error for that mode.
GtaoPixel gtaoPixel(const GtaoConstants& constants, const GBuffer& gbuffer, const GtaoDepthMips* mips, int x, int y,
                    int interleave);

// How far (pixels) one side of a slice marches from pixel centre (px, py) in screen direction (dx, dy), unit:
// the screen radius or the distance to the image's border less the first step's offset (minStepPixels),
// whichever is shorter, and at least 0. Steps are spread over it, so none lands off the image.
float gtaoSideReach(float px, float py, float dx, float dy, const GtaoConstants& constants, float screenRadius);

struct GtaoResult {
    Image visibility;  // 1 channel, [0, 1]; sky 1
    Image bentNormal;  // 3 channels, view-space unit vectors; sky (0, 0, 0)
};

// Throws obscura::Error if the G-buffer does not match the constants' size (or its depth is not 1 channel
// or its normals not 3), or if a depth is NaN, zero or negative or a normal not finite (naming the first such pixel):
// computeGtao's check, and its GPU pass's.
void checkGtaoBuffers(const GBuffer& gbuffer, const GtaoConstants& constants);

// Every pixel. Throws obscura::Error if the G-buffer does not match the constants' size.
GtaoResult computeGtao(const GBuffer& gbuffer, const GtaoConstants& constants);
// Validates the settings, then computeGtao(gbuffer, gtaoConstants(settings, gbuffer.camera)).
GtaoResult computeGtao(const GBuffer& gbuffer, const GtaoSettings& settings);

// The 4x4 interleave of §4.1: which of the 16 slice directions pixel (x, y) takes, a permutation of
// 0..15 that puts far-apart directions next to each other.
int interleaveIndex(int x, int y);
constexpr int kGtaoRotations = 6;  // temporal rotations: 16 x 6 = 96 directions per pixel

} // namespace obscura::ssao
