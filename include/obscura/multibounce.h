// Near-field interreflection from ambient occlusion and albedo (Jimenez et al. 2016, §5, eq. 10): a cubic
// in A whose coefficients are linear fits in the albedo rho, fitted to three-bounce path tracing.
//
// Pure functions, no checks: A and rho are expected in [0, 1].
#pragma once

#include "obscura/math.h"

namespace obscura::ssao {

// G(A, rho) = a(rho) A^3 - b(rho) A^2 + c(rho) A with the paper's fits, and never below A: interreflection can
// only add light. Where c(rho) < 1 (rho < 0.112) the fitted cubic starts under A and stays there over most of
// [0, 1]: by up to 0.044 at rho = 0 (A = 0.32), 0.022 at rho = 0.05, 0.009 at rho = 0.08, 3e-4 from rho = 0.11;
// near A = 1, 4e-4 (G(1, rho) = 0.9996 + 0.0005 rho). So G(1, rho) = 1 within 1e-3 and G >= A everywhere, and
// for dark albedos G is A wherever the cubic is lower.
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
