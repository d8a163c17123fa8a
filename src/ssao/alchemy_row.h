// The AVX2 version of alchemyRow (src/ssao/alchemy_avx2.cpp); library-internal.
#pragma once

#include "obscura/alchemy.h"

namespace obscura::ssao::detail {

#if defined(__GNUC__) && defined(__x86_64__)
#define OBSCURA_HAVE_ALCHEMY_AVX2 1
bool haveAvx2();  // this CPU runs AVX2
// alchemyRow with AVX2 intrinsics: the same bits. Call only where haveAvx2().
void alchemyRowAvx2(const AlchemyConstants& k, const AlchemyInput& in, const SpiralTable& spiral, int y, int x0, int x1,
                    float* out);
#endif

} // namespace obscura::ssao::detail
