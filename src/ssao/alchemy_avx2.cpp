// Alchemy AO row kernel with AVX2 and FMA intrinsics: McGuire et al. 2011, "The Alchemy Screen-Space Ambient
// Obscurance Algorithm", eq. 10 (see include/obscura/alchemy.h). alchemyPixel's estimator (src/ssao/alchemy.cpp)
// for 8 pixels per instruction, two groups of 8 side by side, with fused multiply-adds: the same sums rounded
// differently, so it agrees with alchemyPixel to float rounding, not bit for bit (tests/ssao/alchemy_test.cpp
// bounds the difference). Only these functions are built for AVX2 + FMA; alchemyRow calls them on CPUs with both.
//
// Cost, measured on the 2-core EPYC VM (2026-11-23): an 8-wide hardware gather takes about 5 ns even from L1
// (8 scalar loads measured the same), one per sample, and that is most of the time. So:
//  - No other gathers: the centres' depths and normals come from plain loads, the normals deinterleaved by
//    shuffles. The kernel checks the centres it loads, which replaces a separate scan of the G-buffer.
//  - Two phases per group: first every sample's position and gather, then the arithmetic. The gathers of
//    all 12 samples are in flight together instead of each waiting behind the previous sample's division
//    (1.2x on the kernel).
//  - A group whose samples all land on screen (its largest R_px away from every edge, 3/4 of the groups on
//    the demo view) skips the per-sample bounds test; a group of 16 sky pixels is not sampled at all.
#include "alchemy_row.h"

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace obscura::ssao::detail {

bool haveAvx2Fma() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }

namespace {

#define OBSCURA_AVX2 __attribute__((target("avx2,fma"), always_inline)) inline

// The constants of one row segment, splatted.
struct Row {
    __m256 fy, half, zero, one, scaleX, viewX0, scaleY, viewY0, skyDepth, sky, denominator, radius2, bias, negBias;
    __m256 maxRadius, radiusFocal, widthF;
    __m256i widthM1, heightM1, width, lane;
    const float* depth;
    const float* normal;
    int y, width1, x1;
    bool paper;
};

// 8 pixels' state across the samples.
struct Pixels {
    __m256i centre;
    __m256 d, fx, fxs, cx, cy, nx, ny, nz, rpx, shift, sum;  // fxs: the centre's column x as a float
};

// Loads 8 centres at x = g.. (lanes past x1 repeat pixel x1 - 1 and are not stored). Returns false where a
// centre's depth is not > 0 (NaN, zero, negative) or its normal is not finite: GBuffer::pixelsValid's test.
OBSCURA_AVX2 bool begin(const Row& r, Pixels& p, int g) {
    const __m256i xs = _mm256_min_epi32(_mm256_add_epi32(r.lane, _mm256_set1_epi32(g)), _mm256_set1_epi32(r.x1 - 1));
    p.centre = _mm256_add_epi32(_mm256_set1_epi32(r.y * r.width1), xs);
    if (g + 8 <= r.x1) {
        const std::size_t c = std::size_t(r.y) * std::size_t(r.width1) + std::size_t(g);
        p.d = _mm256_loadu_ps(r.depth + c);
        // v0..v2 hold x0 y0 z0 x1 ... z7: each component takes its lanes from the three, then is reordered.
        const float* n = r.normal + 3 * c;
        const __m256 v0 = _mm256_loadu_ps(n), v1 = _mm256_loadu_ps(n + 8), v2 = _mm256_loadu_ps(n + 16);
        p.nx = _mm256_permutevar8x32_ps(_mm256_blend_ps(_mm256_blend_ps(v0, v1, 0x92), v2, 0x24),
                                        _mm256_setr_epi32(0, 3, 6, 1, 4, 7, 2, 5));
        p.ny = _mm256_permutevar8x32_ps(_mm256_blend_ps(_mm256_blend_ps(v0, v1, 0x24), v2, 0x49),
                                        _mm256_setr_epi32(1, 4, 7, 2, 5, 0, 3, 6));
        p.nz = _mm256_permutevar8x32_ps(_mm256_blend_ps(_mm256_blend_ps(v0, v1, 0x49), v2, 0x92),
                                        _mm256_setr_epi32(2, 5, 0, 3, 6, 1, 4, 7));
    } else {  // the segment's last pixels: plain loads would run past them
        p.d = _mm256_i32gather_ps(r.depth, p.centre, 4);
        const __m256i centre3 = _mm256_mullo_epi32(p.centre, _mm256_set1_epi32(3));
        p.nx = _mm256_i32gather_ps(r.normal, centre3, 4);
        p.ny = _mm256_i32gather_ps(r.normal + 1, centre3, 4);
        p.nz = _mm256_i32gather_ps(r.normal + 2, centre3, 4);
    }
    const __m256 fxs = _mm256_cvtepi32_ps(xs);
    p.fx = _mm256_add_ps(fxs, r.half);
    p.fxs = fxs;
    p.cx = _mm256_mul_ps(_mm256_fmadd_ps(fxs, r.scaleX, r.viewX0), p.d);
    p.cy = _mm256_mul_ps(_mm256_fmadd_ps(_mm256_sub_ps(r.fy, r.half), r.scaleY, r.viewY0), p.d);
    p.rpx = _mm256_min_ps(r.maxRadius, _mm256_div_ps(r.radiusFocal, p.d));
    p.shift = r.paper ? _mm256_mul_ps(_mm256_sub_ps(r.zero, p.d), r.bias) : r.negBias;  // z_C beta or -bias
    p.sum = r.zero;
    // x - x is 0 for finite x and NaN otherwise; ordered compares are false on NaN.
    const __m256 nn = _mm256_add_ps(_mm256_add_ps(_mm256_sub_ps(p.nx, p.nx), _mm256_sub_ps(p.ny, p.ny)),
                                    _mm256_sub_ps(p.nz, p.nz));
    const __m256 ok = _mm256_and_ps(_mm256_cmp_ps(p.d, r.zero, _CMP_GT_OQ), _mm256_cmp_ps(nn, r.zero, _CMP_EQ_OQ));
    return _mm256_movemask_ps(ok) == 0xff;
}

// Phase 1 of one sample: its pixel (floored position) and depth. Checked: the sample may fall off screen,
// where it reads as a point 1e18 m away, which the radius test drops as eq. 9's Heaviside term does.
template <bool Checked>
OBSCURA_AVX2 void fetch(const Row& r, const Pixels& p, __m256 ox, __m256 oy, __m256& fsx, __m256& fsy, __m256& ds) {
    fsx = _mm256_floor_ps(_mm256_fmadd_ps(ox, p.rpx, p.fx));
    fsy = _mm256_floor_ps(_mm256_fmadd_ps(oy, p.rpx, r.fy));
    __m256 depth;
    if constexpr (Checked) {
        const __m256i sx = _mm256_cvttps_epi32(fsx), sy = _mm256_cvttps_epi32(fsy);
        // unsigned(sx) < width: min_epu32(sx, width - 1) == sx.
        const __m256i inside = _mm256_and_si256(_mm256_cmpeq_epi32(_mm256_min_epu32(sx, r.widthM1), sx),
                                                _mm256_cmpeq_epi32(_mm256_min_epu32(sy, r.heightM1), sy));
        const __m256i index = _mm256_blendv_epi8(p.centre, _mm256_add_epi32(_mm256_mullo_epi32(sy, r.width), sx), inside);
        depth = _mm256_blendv_ps(r.skyDepth, _mm256_i32gather_ps(r.depth, index, 4), _mm256_castsi256_ps(inside));
    } else {
        // sy width + sx in float is exact: the caller takes this path only up to 2^24 pixels.
        depth = _mm256_i32gather_ps(r.depth, _mm256_cvttps_epi32(_mm256_fmadd_ps(fsy, r.widthF, fsx)), 4);
    }
    ds = _mm256_min_ps(r.skyDepth, depth);  // a sky sample (+inf) becomes a point 1e18 m away
}

// Phase 2: eq. 10's term of one sample.
OBSCURA_AVX2 void accumulate(const Row& r, Pixels& p, __m256 fsx, __m256 fsy, __m256 ds) {
    const __m256 vx = _mm256_fmsub_ps(_mm256_fmadd_ps(fsx, r.scaleX, r.viewX0), ds, p.cx);
    const __m256 vy = _mm256_fmsub_ps(_mm256_fmadd_ps(fsy, r.scaleY, r.viewY0), ds, p.cy);
    const __m256 vz = _mm256_sub_ps(p.d, ds);  // -ds - z_C with z_C = -d
    const __m256 vv = _mm256_fmadd_ps(vx, vx, _mm256_fmadd_ps(vy, vy, _mm256_mul_ps(vz, vz)));
    const __m256 dot = _mm256_fmadd_ps(vx, p.nx, _mm256_fmadd_ps(vy, p.ny, _mm256_fmadd_ps(vz, p.nz, p.shift)));
    const __m256 vn = _mm256_max_ps(dot, r.zero);
    const __m256 den = r.paper ? _mm256_add_ps(vv, r.denominator) : _mm256_max_ps(vv, r.denominator);
    // A sample on the centre's own pixel is v = 0 and adds 0 in alchemyPixel; fused (and a compiler contracts
    // even a separate multiply and subtract), a ds - c_x is the rounding error of c_x instead, which over the
    // paper's epsilon-sized denominator darkened far open ground (0.74 at 1230 m). Its term is masked.
    const __m256 self = _mm256_and_ps(_mm256_cmp_ps(fsx, p.fxs, _CMP_EQ_OQ),
                                      _mm256_cmp_ps(fsy, _mm256_sub_ps(r.fy, r.half), _CMP_EQ_OQ));
    // A dropped sample's term is masked, not multiplied by 0, so an overflow there cannot leak a NaN.
    p.sum = _mm256_add_ps(p.sum, _mm256_andnot_ps(self, _mm256_and_ps(_mm256_div_ps(vn, den),
                                                                      _mm256_cmp_ps(vv, r.radius2, _CMP_LT_OQ))));
}

template <bool Checked>
__attribute__((target("avx2,fma"))) inline void samples(const Row& r, Pixels& a, Pixels& b, const float* ox,
                                                        const float* oy, __m256i classOf, int count) {
    constexpr int kChunk = 12;  // the default sample count: one chunk
    __m256 xa[kChunk], ya[kChunk], da[kChunk], xb[kChunk], yb[kChunk], db[kChunk];
    for (int i0 = 0; i0 < count; i0 += kChunk) {
        const int n = std::min(kChunk, count - i0);
        for (int i = 0; i < n; ++i) {
            const float* cx = ox + 4 * (i0 + i);
            const float* cy = oy + 4 * (i0 + i);
            const __m256 oxv = _mm256_permutevar8x32_ps(_mm256_broadcast_ps(reinterpret_cast<const __m128*>(cx)), classOf);
            const __m256 oyv = _mm256_permutevar8x32_ps(_mm256_broadcast_ps(reinterpret_cast<const __m128*>(cy)), classOf);
            fetch<Checked>(r, a, oxv, oyv, xa[i], ya[i], da[i]);
            fetch<Checked>(r, b, oxv, oyv, xb[i], yb[i], db[i]);
        }
        for (int i = 0; i < n; ++i) {
            accumulate(r, a, xa[i], ya[i], da[i]);
            accumulate(r, b, xb[i], yb[i], db[i]);
        }
    }
}

__attribute__((target("avx2,fma"))) void finish(const Row& r, const Pixels& p, float scale, float contrast, int g,
                                               int x0, float* out) {
    const __m256 a = _mm256_max_ps(_mm256_fnmadd_ps(_mm256_set1_ps(scale), p.sum, r.one), r.zero);
    const __m256 sky = _mm256_cmp_ps(p.d, r.sky, _CMP_NLT_UQ);
    if (contrast == 1.0f && g + 8 <= r.x1) {
        _mm256_storeu_ps(out + (g - x0), _mm256_blendv_ps(a, r.one, sky));
        return;
    }
    alignas(32) float av[8], skyv[8];
    _mm256_store_ps(av, a);
    _mm256_store_ps(skyv, sky);
    for (int j = 0; j < 8 && g + j < r.x1; ++j)
        out[g + j - x0] = skyv[j] != 0.0f ? 1.0f : (contrast == 1.0f ? av[j] : std::pow(av[j], contrast));
}

__attribute__((target("avx2,fma"))) inline float largest(__m256 a, __m256 b) {
    const __m256 m = _mm256_max_ps(a, b);
    __m128 h = _mm_max_ps(_mm256_castps256_ps128(m), _mm256_extractf128_ps(m, 1));
    h = _mm_max_ps(h, _mm_movehl_ps(h, h));
    return _mm_cvtss_f32(_mm_max_ss(h, _mm_shuffle_ps(h, h, 1)));
}

} // namespace

__attribute__((target("avx2,fma"))) bool alchemyRowAvx2(const AlchemyConstants& k, const AlchemyInput& in,
                                                       const SpiralTable& spiral, int y, int x0, int x1, float* out) {
    Row r;
    r.paper = k.formulation == kAlchemyPaper;
    r.fy = _mm256_set1_ps(float(y) + 0.5f);
    r.half = _mm256_set1_ps(0.5f);
    r.zero = _mm256_setzero_ps();
    r.one = _mm256_set1_ps(1.0f);
    // A pixel's view coordinate (sx + 0.5) scale + offset as one FMA: sx scale + viewX0.
    r.scaleX = _mm256_set1_ps(k.viewScaleX);
    r.viewX0 = _mm256_set1_ps(0.5f * k.viewScaleX + k.viewOffsetX);
    r.scaleY = _mm256_set1_ps(k.viewScaleY);
    r.viewY0 = _mm256_set1_ps(0.5f * k.viewScaleY + k.viewOffsetY);
    r.skyDepth = _mm256_set1_ps(1e18f);
    r.sky = _mm256_set1_ps(1e30f);
    r.denominator = _mm256_set1_ps(k.denominator);
    // The paper drops samples at |v| >= r, the chapter's step() keeps |v| = r: one ulp of r^2 apart.
    r.radius2 = _mm256_set1_ps(r.paper ? k.radius2 : std::nextafter(k.radius2, INFINITY));
    r.bias = _mm256_set1_ps(k.bias);
    r.negBias = _mm256_set1_ps(-k.bias);
    r.maxRadius = _mm256_set1_ps(k.maxRadiusPixels);
    r.radiusFocal = _mm256_set1_ps(k.radius * k.focalPixels);
    r.widthF = _mm256_set1_ps(float(k.width));
    r.widthM1 = _mm256_set1_epi32(k.width - 1);
    r.heightM1 = _mm256_set1_epi32(k.height - 1);
    r.width = _mm256_set1_epi32(k.width);
    r.lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    r.depth = in.depth;
    r.normal = in.normal;
    r.y = y;
    r.width1 = k.width;
    r.x1 = x1;
    const float scale = k.intensity / float(k.samples);
    // Sample i of the four pixel classes of this row sits at [4 i, 4 i + 4) of rowX / rowY; lane l takes
    // class (x0 + l) mod 4, and so does lane l of every later group of 8.
    const std::size_t classRow = std::size_t(y % kAlchemyClassTile) * kAlchemyClassTile * std::size_t(k.samples);
    const float* ox = spiral.rowX.data() + classRow;
    const float* oy = spiral.rowY.data() + classRow;
    const __m256i classOf = _mm256_and_si256(_mm256_add_epi32(r.lane, _mm256_set1_epi32(x0)), _mm256_set1_epi32(3));
    const bool exactIndex = double(k.width) * double(k.height) <= 16777216.0;
    const float fy = float(y) + 0.5f;
    bool valid = true;
    // Two groups of 8 pixels side by side, so that each phase has two independent chains. A lone last group
    // runs with a duplicate that is not stored.
    for (int g = x0; g < x1; g += 16) {
        Pixels a, b;
        const bool okA = begin(r, a, g), okB = begin(r, b, g + 8);
        if (!(okA & okB)) {  // a NaN centre would turn into wild indices; the caller names the pixel
            valid = false;
            continue;
        }
        const __m256 skyA = _mm256_cmp_ps(a.d, r.sky, _CMP_NLT_UQ), skyB = _mm256_cmp_ps(b.d, r.sky, _CMP_NLT_UQ);
        if (_mm256_movemask_ps(_mm256_and_ps(skyA, skyB)) == 0xff) {
            std::fill(out + (g - x0), out + (std::min(g + 16, x1) - x0), 1.0f);
            continue;
        }
        // Every sample lies within R_px of its pixel (|offset| < 1); one more pixel covers rounding.
        const float reach = largest(a.rpx, b.rpx) + 1.0f;
        const bool onScreen = exactIndex && float(g) + 0.5f - reach >= 0.0f &&
                              float(g + 15) + 0.5f + reach < float(k.width) && fy - reach >= 0.0f &&
                              fy + reach < float(k.height);
        if (onScreen)
            samples<false>(r, a, b, ox, oy, classOf, k.samples);
        else
            samples<true>(r, a, b, ox, oy, classOf, k.samples);
        finish(r, a, scale, k.contrast, g, x0, out);
        finish(r, b, scale, k.contrast, g + 8, x0, out);
    }
    return valid;
}

} // namespace obscura::ssao::detail
#endif
