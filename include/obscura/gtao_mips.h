// The depth MIP chain of GtaoSampling::Mip and PlanarMip, shared by the C++ reference (src/ssao/gtao_mips.cpp, the
// sampling in src/ssao/gtao.cpp) and the compute passes (src/gpu/shaders/gtao_mips.comp, gtao.comp); the
// same file is #included by GLSL, so both sides size, filter and place texels with one arithmetic.
//
// XeGTAO (Intel, 2021) prefilters depth into 5 MIPs and reads farther samples from coarser ones, so that a
// sample's footprint in memory shrinks with its distance. Its filter keeps a weighted depth at the pixel's
// centre; this chain keeps the mean of inverse depth w and places it at the mean of the children's centres.
// Inverse depth is affine in the image over a plane, so on a plane that mean is the plane's own value there:
// a texel's point lies on the surface at every level, and open ground stays open. Across an edge the point
// lies between the surfaces. A texel over any sky is sky (w = 0): filling it from its other children would
// extend a surface's far edge into the sky, and from below that edge the extension is a false horizon.
// Measured against ray tracing (docs/QUALITY.md), the mean was the best of three rules: keeping the farthest
// child erases thin occluders at coarse levels (cabinet's slats: MAE 0.0435 -> 0.0587 at 1280x720), and
// the nearest child dilates every silhouette (demo 0.0386 -> 0.0399); the mean stays within 0.002 of
// nearest-pixel samples on every built-in scene.
//
// Level 0 is the depth buffer itself; levels 1..mipLevels (at most GTAO_MAX_MIP_LEVELS) are stored one
// after the other in one float array, level l of size gtaoMipSize(width, l) x gtaoMipSize(height, l) at
// gtaoMipOffset(width, height, l), rows top to bottom. Texel t of level l averages children 2t and 2t + 1 of
// level l - 1 in each axis, the last one clamped to the level's last texel at an odd size.
#ifndef OBSCURA_GTAO_MIPS_H
#define OBSCURA_GTAO_MIPS_H

#ifdef __cplusplus
namespace obscura::ssao {
#define OBSCURA_FN inline
#else
#define OBSCURA_FN
#endif

#define GTAO_MAX_MIP_LEVELS 4           // coarse levels above the depth buffer: 5 MIPs in all, as XeGTAO's
#define GTAO_MIP_WORKGROUP 8            // gtao_mips.comp: 8x8 level-1 texels (16x16 pixels) per workgroup

// Texels of level `level` along an axis of `size` >= 1 pixels: ceil(size / 2^level).
OBSCURA_FN int gtaoMipSize(int size, int level) { return ((size - 1) >> level) + 1; }

// Where coarse level `level` (1..GTAO_MAX_MIP_LEVELS + 1) starts in the chain's array, in floats; with
// level = mipLevels + 1, the chain's length.
OBSCURA_FN int gtaoMipOffset(int width, int height, int level) {
    int offset = 0;
    for (int l = 1; l < level; ++l) offset += gtaoMipSize(width, l) * gtaoMipSize(height, l);
    return offset;
}

// Image coordinate (pixels, centres at +0.5) of the point that texel `texel` of level `level` stands for
// along an axis of `size` pixels: the mean of its children's, which for a full texel is its centre. Only the
// last texel of an odd-sized level differs: its second child is its first, so the mean leans towards it.
OBSCURA_FN float gtaoMipCentre(int texel, int level, int size) {
    if (((texel + 1) << level) <= size) return (float(texel) + 0.5f) * float(1 << level);
    float centre = float(size) - 0.5f;  // the last pixel
    int n = size;                       // texels of level l - 1
    for (int l = 1; l <= level; ++l) {
        // An even count gives the last parent two children: a full texel and the previous last one.
        if ((n & 1) == 0) centre = 0.5f * ((float(n - 2) + 0.5f) * float(1 << (l - 1)) + centre);
        n = (n + 1) >> 1;
    }
    return centre;
}

// One texel from its four children's inverse depths (0: sky): sky if any child is sky, else their mean.
OBSCURA_FN float gtaoMipFilter(float w00, float w10, float w01, float w11) {
    if (!(w00 > 0.0f && w10 > 0.0f && w01 > 0.0f && w11 > 0.0f)) return 0.0f;
    return ((w00 + w10) + (w01 + w11)) * 0.25f;
}

// The level a sample `offsetPixels` from the centre reads: the coarsest of 0..mipLevels whose texels are at
// most offsetPixels * texelScale pixels wide (texelScale = 1 / GtaoSettings::mipDistanceRatio).
OBSCURA_FN int gtaoMipLevel(float offsetPixels, float texelScale, int mipLevels) {
    const float texel = offsetPixels * texelScale;
    int level = 0;
    while (level < mipLevels && float(2 << level) <= texel) ++level;
    return level;
}

#ifdef __cplusplus
} // namespace obscura::ssao
#endif
#undef OBSCURA_FN

#endif
