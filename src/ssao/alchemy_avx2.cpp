// Alchemy AO row kernel with AVX2 intrinsics: McGuire et al. 2011, "The Alchemy Screen-Space Ambient
// Obscurance Algorithm", eq. 10 (see include/obscura/alchemy.h). The same operations in the same order as
// alchemyPixel (src/ssao/alchemy.cpp), 8 pixels per instruction, two groups of 8 side by side, the pixel
// state in registers across all samples (the portable kernel keeps it in arrays). One hardware gather reads
// the 8 sample depths; building it from 8 scalar loads measured the same on the 2-core EPYC VM
// (2026-11-23). No FMA: each product is rounded as in the scalar reference, so the bits match it. Only
// these functions are built for AVX2; alchemyRow calls them on CPUs that have it.
#include "alchemy_row.h"

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>

#include <cmath>

namespace obscura::ssao::detail {

bool haveAvx2() { return __builtin_cpu_supports("avx2"); }

namespace {

#define OBSCURA_AVX2 __attribute__((target("avx2"), always_inline)) inline

// The constants of one row segment, splatted.
struct Row {
    __m256 fy, half, zero, one, scaleX, offsetX, scaleY, offsetY, signBit, skyDepth, denominator, radius2, bias, negBias;
    __m256 maxRadius, radiusFocal, scale;
    __m256i widthM1, heightM1, width, lane;
    const float* depth;
    const float* normal;
    int y, width1, x1;
    bool paper;
};

// 8 pixels' state across the samples.
struct Pixels {
    __m256i centre;
    __m256 d, fx, cx, cy, nx, ny, nz, rpx, shift, sum;
};

OBSCURA_AVX2 void begin(const Row& r, Pixels& p, int g) {
    // Lanes past x1 repeat pixel x1 - 1 (inside the buffer) and are not stored.
    const __m256i xs = _mm256_min_epi32(_mm256_add_epi32(r.lane, _mm256_set1_epi32(g)), _mm256_set1_epi32(r.x1 - 1));
    p.centre = _mm256_add_epi32(_mm256_set1_epi32(r.y * r.width1), xs);
    p.d = _mm256_i32gather_ps(r.depth, p.centre, 4);
    p.fx = _mm256_add_ps(_mm256_cvtepi32_ps(xs), r.half);
    p.cx = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(p.fx, r.scaleX), r.offsetX), p.d);
    p.cy = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(r.fy, r.scaleY), r.offsetY), p.d);
    const __m256i centre3 = _mm256_mullo_epi32(p.centre, _mm256_set1_epi32(3));
    p.nx = _mm256_i32gather_ps(r.normal, centre3, 4);
    p.ny = _mm256_i32gather_ps(r.normal + 1, centre3, 4);
    p.nz = _mm256_i32gather_ps(r.normal + 2, centre3, 4);
    // std::min(a, b) is b < a ? b : a, which is _mm256_min_ps(b, a); likewise std::max(a, b) = max_ps(b, a).
    p.rpx = _mm256_min_ps(r.maxRadius, _mm256_div_ps(r.radiusFocal, p.d));
    p.shift = r.paper ? _mm256_mul_ps(_mm256_xor_ps(p.d, r.signBit), r.bias) : r.negBias;  // z_C beta or -bias
    p.sum = r.zero;
}

OBSCURA_AVX2 void sample(const Row& r, Pixels& p, __m256 ox, __m256 oy) {
    // Exact floor (the scalar floorToInt); the float of the floored value is float(sx).
    const __m256 fsx = _mm256_floor_ps(_mm256_add_ps(p.fx, _mm256_mul_ps(ox, p.rpx)));
    const __m256 fsy = _mm256_floor_ps(_mm256_add_ps(r.fy, _mm256_mul_ps(oy, p.rpx)));
    const __m256i sx = _mm256_cvttps_epi32(fsx), sy = _mm256_cvttps_epi32(fsy);
    // unsigned(sx) < width: min_epu32(sx, width - 1) == sx.
    const __m256i inside = _mm256_and_si256(_mm256_cmpeq_epi32(_mm256_min_epu32(sx, r.widthM1), sx),
                                            _mm256_cmpeq_epi32(_mm256_min_epu32(sy, r.heightM1), sy));
    // An off-screen sample reads the centre instead and is then multiplied by 0.
    const __m256i index = _mm256_blendv_epi8(p.centre, _mm256_add_epi32(_mm256_mullo_epi32(sy, r.width), sx), inside);
    const __m256 gathered = _mm256_i32gather_ps(r.depth, index, 4);
    const __m256 ds = _mm256_min_ps(r.skyDepth, gathered);
    const __m256 vx = _mm256_sub_ps(
        _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_add_ps(fsx, r.half), r.scaleX), r.offsetX), ds), p.cx);
    const __m256 vy = _mm256_sub_ps(
        _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_add_ps(fsy, r.half), r.scaleY), r.offsetY), ds), p.cy);
    const __m256 vz = _mm256_sub_ps(p.d, ds);  // -ds - z_C with z_C = -d: the same sum, so the same bits
    const __m256 vv = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(vx, vx), _mm256_mul_ps(vy, vy)), _mm256_mul_ps(vz, vz));
    const __m256 dot = _mm256_add_ps(
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(vx, p.nx), _mm256_mul_ps(vy, p.ny)), _mm256_mul_ps(vz, p.nz)), p.shift);
    const __m256 vn = _mm256_max_ps(dot, r.zero);
    const __m256 den = r.paper ? _mm256_add_ps(vv, r.denominator) : _mm256_max_ps(vv, r.denominator);
    const __m256 term = _mm256_div_ps(vn, den);
    // float((vv < radius2) & inside): 1 or 0, multiplied as the scalar code does.
    const __m256 keep = _mm256_and_ps(_mm256_cmp_ps(vv, r.radius2, _CMP_LT_OQ), _mm256_castsi256_ps(inside));
    p.sum = _mm256_add_ps(p.sum, _mm256_mul_ps(term, _mm256_and_ps(keep, r.one)));
}

__attribute__((target("avx2"))) void finish(const Row& r, const Pixels& p, float contrast, int g, int x0, float* out) {
    const __m256 a = _mm256_max_ps(_mm256_sub_ps(r.one, _mm256_mul_ps(r.scale, p.sum)), r.zero);
    alignas(32) float av[8], dv[8];
    _mm256_store_ps(av, a);
    _mm256_store_ps(dv, p.d);
    for (int j = 0; j < 8 && g + j < r.x1; ++j) {
        const float v = contrast == 1.0f ? av[j] : std::pow(av[j], contrast);
        out[g + j - x0] = !(dv[j] < 1e30f) ? 1.0f : v;
    }
}

} // namespace

__attribute__((target("avx2"))) void alchemyRowAvx2(const AlchemyConstants& k, const AlchemyInput& in,
                                                   const SpiralTable& spiral, int y, int x0, int x1, float* out) {
    Row r;
    r.paper = k.formulation == kAlchemyPaper;
    r.fy = _mm256_set1_ps(float(y) + 0.5f);
    r.half = _mm256_set1_ps(0.5f);
    r.zero = _mm256_setzero_ps();
    r.one = _mm256_set1_ps(1.0f);
    r.scaleX = _mm256_set1_ps(k.viewScaleX);
    r.offsetX = _mm256_set1_ps(k.viewOffsetX);
    r.scaleY = _mm256_set1_ps(k.viewScaleY);
    r.offsetY = _mm256_set1_ps(k.viewOffsetY);
    r.signBit = _mm256_set1_ps(-0.0f);
    r.skyDepth = _mm256_set1_ps(1e18f);
    r.denominator = _mm256_set1_ps(k.denominator);
    r.radius2 = _mm256_set1_ps(r.paper ? k.radius2 : std::nextafter(k.radius2, INFINITY));
    r.bias = _mm256_set1_ps(k.bias);
    r.negBias = _mm256_set1_ps(-k.bias);
    r.maxRadius = _mm256_set1_ps(k.maxRadiusPixels);
    r.radiusFocal = _mm256_set1_ps(k.radius * k.focalPixels);
    r.scale = _mm256_set1_ps(k.intensity / float(k.samples));
    r.widthM1 = _mm256_set1_epi32(k.width - 1);
    r.heightM1 = _mm256_set1_epi32(k.height - 1);
    r.width = _mm256_set1_epi32(k.width);
    r.lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    r.depth = in.depth;
    r.normal = in.normal;
    r.y = y;
    r.width1 = k.width;
    r.x1 = x1;
    // Sample i of the four pixel classes of this row sits at [4 i, 4 i + 4) of rowX / rowY; lane l takes
    // class (x0 + l) mod 4, and so does lane l of every later group of 8.
    const std::size_t classRow = std::size_t(y % kAlchemyClassTile) * kAlchemyClassTile * std::size_t(k.samples);
    const float* ox = spiral.rowX.data() + classRow;
    const float* oy = spiral.rowY.data() + classRow;
    const __m256i classOf = _mm256_and_si256(_mm256_add_epi32(r.lane, _mm256_set1_epi32(x0)), _mm256_set1_epi32(3));
    // Two groups of 8 pixels side by side: each sample is a long chain (gather, division), and the second
    // group's independent chain fills the pipeline. A lone last group runs with a duplicate that is not stored.
    for (int g = x0; g < x1; g += 16) {
        Pixels a, b;
        begin(r, a, g);
        begin(r, b, g + 8);
        for (int i = 0; i < k.samples; ++i) {
            const __m256 oxv = _mm256_permutevar8x32_ps(_mm256_broadcast_ps(reinterpret_cast<const __m128*>(ox + 4 * i)), classOf);
            const __m256 oyv = _mm256_permutevar8x32_ps(_mm256_broadcast_ps(reinterpret_cast<const __m128*>(oy + 4 * i)), classOf);
            sample(r, a, oxv, oyv);
            sample(r, b, oxv, oyv);
        }
        finish(r, a, k.contrast, g, x0, out);
        finish(r, b, k.contrast, g + 8, x0, out);
    }
}

} // namespace obscura::ssao::detail
#endif
