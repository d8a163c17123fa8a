// The per-pixel bounds for GTAO on the GPU against the CPU reference, and the differences the GTAO
// tests measure against them (gtao_gpu_test.cpp, gtao_temporal_gpu_test.cpp).
#pragma once

#include "obscura/gtao.h"
#include "obscura/image.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace obscura::gpu::testing {

inline constexpr double kVisibilityBound = 2e-3;  // max |GPU - CPU| of a pixel's visibility
inline constexpr double kBentBound = 1e-2;        // max |GPU - CPU| of a bent-normal component

struct GtaoDifference {
    double visibility = 0;      // max |GPU - CPU| over all pixels
    double bent = 0;            // max over all pixels and bent-normal components
    double visibilityRest = 0;  // the same over the pixels within both bounds
    double bentRest = 0;
    int beyond = 0;             // pixels beyond either bound
    int occluded = 0;           // CPU pixels below 0.99: the comparison is not vacuous
};

// Max |a - b| over the channels of pixel i.
inline double pixelDifference(const Image& a, const Image& b, std::size_t i) {
    double d = 0;
    for (std::size_t c = 0; c < std::size_t(a.channels); ++c) {
        const std::size_t j = i * std::size_t(a.channels) + c;
        d = std::max(d, std::fabs(double(a.pixels[j]) - double(b.pixels[j])));
    }
    return d;
}

// The results must have the same sizes (the callers assert it first).
inline GtaoDifference compareGtao(const ssao::GtaoResult& gpu, const ssao::GtaoResult& cpu) {
    GtaoDifference d;
    for (std::size_t i = 0; i < cpu.visibility.pixelCount(); ++i) {
        const double dv = pixelDifference(gpu.visibility, cpu.visibility, i);
        const double db = pixelDifference(gpu.bentNormal, cpu.bentNormal, i);
        d.visibility = std::max(d.visibility, dv);
        d.bent = std::max(d.bent, db);
        if (dv > kVisibilityBound || db > kBentBound) {
            ++d.beyond;
        } else {
            d.visibilityRest = std::max(d.visibilityRest, dv);
            d.bentRest = std::max(d.bentRest, db);
        }
        d.occluded += cpu.visibility.pixels[i] < 0.99f;
    }
    return d;
}

} // namespace obscura::gpu::testing
