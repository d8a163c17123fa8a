// The AVX2 + FMA version of alchemyRow (src/ssao/alchemy_avx2.cpp); library-internal.
#pragma once

#include "obscura/alchemy.h"

namespace obscura::ssao::detail {

#if defined(__GNUC__) && defined(__x86_64__)
#define OBSCURA_HAVE_ALCHEMY_AVX2 1
bool haveAvx2Fma();  // this CPU runs AVX2 and FMA
// alchemyRow with AVX2 + FMA intrinsics: the same estimator, rounded differently. Call only where haveAvx2Fma().
bool alchemyRowAvx2(const AlchemyConstants& k, const AlchemyInput& in, const SpiralTable& spiral, int y, int x0, int x1,
                    float* out);
#endif

} // namespace obscura::ssao::detail
