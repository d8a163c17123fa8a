// Near-field interreflection from ambient occlusion and albedo (Jimenez et al. 2016, §5, eq. 10): a cubic
// in A whose coefficients are linear fits in the albedo rho, fitted to three-bounce path tracing.
//
// Pure functions, no checks: A and rho are expected in [0, 1].
#pragma once

#include "obscura/math.h"

namespace obscura::ssao {

// G(A, rho) = a(rho) A^3 - b(rho) A^2 + c(rho) A with the paper's fits, and never below A: the fitted
// cubic dips under A by up to 0.0013 for rho near 0 and A near 1 (G(1, rho) = 0.9996 + 0.0005 rho), and
// interreflection can only add light. So G(1, rho) = 1 within 1e-3 and G >= A everywhere.
constexpr float multiBounce(float ao, float albedo) {
    const float a = 2.0404f * albedo - 0.3324f;
    const float b = 4.7951f * albedo - 0.6417f;
    const float c = 2.7552f * albedo + 0.6903f;
    const float g = ((a * ao - b) * ao + c) * ao;
    return g > ao ? g : ao;
}

// Per colour channel of the albedo, as the paper applies it.
constexpr Vec3 multiBounce(float ao, Vec3 albedo) {
    return {multiBounce(ao, albedo.x), multiBounce(ao, albedo.y), multiBounce(ao, albedo.z)};
}

} // namespace obscura::ssao
