// Alchemy AO row kernel with AVX2 intrinsics: McGuire et al. 2011, "The Alchemy Screen-Space Ambient
// Obscurance Algorithm", eq. 10 (see include/obscura/alchemy.h). The same operations in the same order as
// alchemyPixel (src/ssao/alchemy.cpp), 8 pixels per instruction: a hardware gather reads the 8 sample
// depths (GCC does not emit gathers itself for generic tuning and builds them from 16 scalar moves), and
// the pixel state stays in registers across all samples. No FMA: each product is rounded as in the
// scalar reference, so the bits match it. Only this function is built for AVX2; alchemyRow calls it on
// CPUs that have AVX2.
#include "alchemy_row.h"

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>

#include <cmath>

namespace obscura::ssao::detail {

bool haveAvx2() { return __builtin_cpu_supports("avx2"); }

__attribute__((target("avx2"))) void alchemyRowAvx2(const AlchemyConstants& k, const AlchemyInput& in,
                                                   const SpiralTable& spiral, int y, int x0, int x1, float* out) {
    const bool paper = k.formulation == kAlchemyPaper;
    const int width = k.width;
    const float* depth = in.depth;
    const float fyScalar = float(y) + 0.5f;
    const __m256 fy = _mm256_set1_ps(fyScalar);
    const __m256 half = _mm256_set1_ps(0.5f), zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
    const __m256 scaleX = _mm256_set1_ps(k.viewScaleX), offsetX = _mm256_set1_ps(k.viewOffsetX);
    const __m256 scaleY = _mm256_set1_ps(k.viewScaleY), offsetY = _mm256_set1_ps(k.viewOffsetY);
    const __m256 signBit = _mm256_set1_ps(-0.0f), skyDepth = _mm256_set1_ps(1e18f);
    const __m256 denominator = _mm256_set1_ps(k.denominator);
    const __m256 radius2 = _mm256_set1_ps(paper ? k.radius2 : std::nextafter(k.radius2, INFINITY));
    const __m256i widthV = _mm256_set1_epi32(width), heightV = _mm256_set1_epi32(k.height);
    const __m256i minusOne = _mm256_set1_epi32(-1);
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    // Sample i of the four pixel classes of this row sits at [4 i, 4 i + 4) of rowX / rowY; lane l takes class (x0 + l) mod 4.
    const std::size_t classRow = std::size_t(y % kAlchemyClassTile) * kAlchemyClassTile * std::size_t(k.samples);
    const float* ox = spiral.rowX.data() + classRow;
    const float* oy = spiral.rowY.data() + classRow;
    const __m256i classOf = _mm256_and_si256(_mm256_add_epi32(lane, _mm256_set1_epi32(x0)), _mm256_set1_epi32(3));
    const float radiusFocal = k.radius * k.focalPixels;
    const float scale = k.intensity / float(k.samples);
    for (int g = x0; g < x1; g += 8) {
        // Lanes past x1 repeat pixel x1 - 1 (inside the buffer) and are not stored.
        const __m256i xs = _mm256_min_epi32(_mm256_add_epi32(lane, _mm256_set1_epi32(g)), _mm256_set1_epi32(x1 - 1));
        const __m256i centre = _mm256_add_epi32(_mm256_set1_epi32(y * width), xs);
        const __m256 d = _mm256_i32gather_ps(depth, centre, 4);
        const __m256 fx = _mm256_add_ps(_mm256_cvtepi32_ps(xs), half);
        const __m256 cx = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(fx, scaleX), offsetX), d);
        const __m256 cy = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(fy, scaleY), offsetY), d);
        const __m256 cz = _mm256_xor_ps(d, signBit);
        const __m256i centre3 = _mm256_mullo_epi32(centre, _mm256_set1_epi32(3));
        const __m256 nx = _mm256_i32gather_ps(in.normal, centre3, 4);
        const __m256 ny = _mm256_i32gather_ps(in.normal + 1, centre3, 4);
        const __m256 nz = _mm256_i32gather_ps(in.normal + 2, centre3, 4);
        // std::min(a, b) is b < a ? b : a, which is _mm256_min_ps(b, a); likewise std::max(a, b) = max_ps(b, a).
        const __m256 rpx = _mm256_min_ps(_mm256_set1_ps(k.maxRadiusPixels), _mm256_div_ps(_mm256_set1_ps(radiusFocal), d));
        const __m256 shift = paper ? _mm256_mul_ps(cz, _mm256_set1_ps(k.bias)) : _mm256_set1_ps(-k.bias);
        __m256 sum = zero;
        for (int i = 0; i < k.samples; ++i) {
            const __m256 oxv = _mm256_permutevar8x32_ps(_mm256_broadcast_ps(reinterpret_cast<const __m128*>(ox + 4 * i)), classOf);
            const __m256 oyv = _mm256_permutevar8x32_ps(_mm256_broadcast_ps(reinterpret_cast<const __m128*>(oy + 4 * i)), classOf);
            // Exact floor (the scalar floorToInt); the float of the floored value is float(sx).
            const __m256 fsx = _mm256_floor_ps(_mm256_add_ps(fx, _mm256_mul_ps(oxv, rpx)));
            const __m256 fsy = _mm256_floor_ps(_mm256_add_ps(fy, _mm256_mul_ps(oyv, rpx)));
            const __m256i sx = _mm256_cvttps_epi32(fsx), sy = _mm256_cvttps_epi32(fsy);
            const __m256i inside =
                _mm256_and_si256(_mm256_and_si256(_mm256_cmpgt_epi32(sx, minusOne), _mm256_cmpgt_epi32(widthV, sx)),
                                 _mm256_and_si256(_mm256_cmpgt_epi32(sy, minusOne), _mm256_cmpgt_epi32(heightV, sy)));
            // An off-screen sample reads the centre instead and is then multiplied by 0.
            const __m256i index = _mm256_blendv_epi8(centre, _mm256_add_epi32(_mm256_mullo_epi32(sy, widthV), sx), inside);
            const __m256 ds = _mm256_min_ps(skyDepth, _mm256_i32gather_ps(depth, index, 4));
            const __m256 vx = _mm256_sub_ps(
                _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_add_ps(fsx, half), scaleX), offsetX), ds), cx);
            const __m256 vy = _mm256_sub_ps(
                _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_add_ps(fsy, half), scaleY), offsetY), ds), cy);
            const __m256 vz = _mm256_sub_ps(_mm256_xor_ps(ds, signBit), cz);
            const __m256 vv =
                _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(vx, vx), _mm256_mul_ps(vy, vy)), _mm256_mul_ps(vz, vz));
            const __m256 dot =
                _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(vx, nx), _mm256_mul_ps(vy, ny)), _mm256_mul_ps(vz, nz)), shift);
            const __m256 vn = _mm256_max_ps(dot, zero);
            const __m256 den = paper ? _mm256_add_ps(vv, denominator) : _mm256_max_ps(vv, denominator);
            const __m256 term = _mm256_div_ps(vn, den);
            // float((vv < radius2) & inside): 1 or 0, multiplied as the scalar code does.
            const __m256 keep = _mm256_and_ps(_mm256_cmp_ps(vv, radius2, _CMP_LT_OQ), _mm256_castsi256_ps(inside));
            sum = _mm256_add_ps(sum, _mm256_mul_ps(term, _mm256_and_ps(keep, one)));
        }
        const __m256 a = _mm256_max_ps(_mm256_sub_ps(one, _mm256_mul_ps(_mm256_set1_ps(scale), sum)), zero);
        alignas(32) float av[8], dv[8];
        _mm256_store_ps(av, a);
        _mm256_store_ps(dv, d);
        for (int j = 0; j < 8 && g + j < x1; ++j) {
            const float v = k.contrast == 1.0f ? av[j] : std::pow(av[j], k.contrast);
            out[g + j - x0] = !(dv[j] < 1e30f) ? 1.0f : v;
        }
    }
}

} // namespace obscura::ssao::detail
#endif
