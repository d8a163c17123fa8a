// The separable cross-bilateral blur (McGuire et al. 2011, Fig. 6) as one fused pass over tiles; the
// library-internal half of include/obscura/bilateral.h.
#pragma once

#include "obscura/bilateral.h"

#include <vector>

namespace obscura::ssao::detail {

// The separable filter's constants: logSpatial[t + r] = log2 of the spatial weight of tap t in [-r, r], and
// depthScale = log2(e) / (2 depthSigma^2), so that a tap weighs 2^(logSpatial - dd^2 depthScale / d^2)
// = spatial exp(-dd^2 / (2 (depthSigma d)^2)). The CPU filter and the GPU pass both take them from here.
struct SeparableWeights {
    std::vector<float> logSpatial;
    float depthScale = 0;
};
SeparableWeights separableWeights(const BilateralSettings& settings);

// The horizontal pass, the vertical pass, or both (horizontal first) of the separable filter, on inputs
// already checked. Deterministic: each output depends only on its own taps, summed in a fixed order.
Image separableBlur(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings, bool horizontal,
                    bool vertical);

} // namespace obscura::ssao::detail
