// The comparison the GPU blur tests share: one filter setting on one G-buffer, GPU against CPU.
#pragma once

#include "gpu_test_util.h"

#include "obscura/alchemy.h"
#include "obscura/bilateral.h"
#include "obscura/gpu.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace obscura::gpu::testing {

// A noisy AO to blur: the Alchemy estimator at 8 samples.
inline Image noisyAo(const GBuffer& g) {
    ssao::AlchemySettings estimator;
    estimator.samples = 8;
    return ssao::alchemyAO(g, estimator);
}

// Filters `raw` with gpu::bilateralFilter and ssao::bilateralFilter, prints the largest difference and the GPU
// time under `label`, and expects it within `bound`, at least 5% of the pixels changed (the blur did
// something) and every sky pixel keeping its input exactly.
inline void expectBlurMatchesCpu(Context& context, const GBuffer& g, const Image& raw, const ssao::BilateralSettings& s,
                                 const std::string& label, double bound) {
    const Image gpu = bilateralFilter(context, raw, g, s);
    const double ms = context.lastPassMs();
    const Image cpu = ssao::bilateralFilter(raw, g, s);
    ASSERT_EQ(gpu.pixels.size(), cpu.pixels.size());
    double worst = 0;
    int changed = 0;
    for (std::size_t i = 0; i < cpu.pixels.size(); ++i) {
        worst = std::max(worst, std::fabs(double(gpu.pixels[i]) - double(cpu.pixels[i])));
        changed += cpu.pixels[i] != raw.pixels[i];
        if (!(g.depth.pixels[i] < 1e30f)) {
            ASSERT_EQ(gpu.pixels[i], raw.pixels[i]) << label << ": sky keeps its input";
        }
    }
    std::printf("[ measured ] %s: max %.3g, %.3f ms on the GPU\n", label.c_str(), worst, ms);
    EXPECT_LE(worst, bound) << label;
    EXPECT_GT(changed, g.width() * g.height() / 20) << label;
}

// expectBlurMatchesCpu for every setting on the blur tests' three scenes (one at an odd size), labelled
// `prefix` scene size name.
inline void expectBlursMatchCpu(Context& context,
                                const std::vector<std::pair<std::string, ssao::BilateralSettings>>& settings,
                                const std::string& prefix, double bound) {
    struct Case {
        const char* scene;
        int w, h;
    };
    for (const Case& c : {Case{"demo", 333, 197}, Case{"corner", 160, 96}, Case{"cabinet", 256, 144}}) {
        const GBuffer g = render(c.scene, c.w, c.h);
        const Image raw = noisyAo(g);
        for (const auto& [name, s] : settings)
            expectBlurMatchesCpu(context, g, raw, s,
                                 prefix + c.scene + " " + std::to_string(c.w) + "x" + std::to_string(c.h) + " " + name,
                                 bound);
    }
}

} // namespace obscura::gpu::testing
