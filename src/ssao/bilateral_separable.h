// The separable cross-bilateral blur (McGuire et al. 2011, Fig. 6) as one fused pass over tiles; the
// library-internal half of include/obscura/bilateral.h.
#pragma once

#include "obscura/bilateral.h"

namespace obscura::ssao::detail {

// The horizontal pass, the vertical pass, or both (horizontal first) of the separable filter, on inputs
// already checked. Deterministic: each output depends only on its own taps, summed in a fixed order.
Image separableBlur(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings, bool horizontal,
                    bool vertical);

} // namespace obscura::ssao::detail
