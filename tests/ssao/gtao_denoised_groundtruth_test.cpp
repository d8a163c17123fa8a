// GTAO followed by its separable bilateral blur (as `obscura bench --gpu`'s gtao case runs it) against
// ray-traced AO of the same radius, with fewer slices than the high preset: where the slices are rotated
// per pixel (GtaoSettings::jitter), the blur averages neighbours' directions, so fewer slices per pixel can
// reach the error of the high preset's 3 regular slices. The question is how few: the GPU pass's time
// grows with the samples per pixel (2 x slices x steps).
//
// Scenes and reference as in gtao_groundtruth_test.cpp (seen from above, every occluder in view but on
// stairs' sides), at 256x256, where the 13-tap blur spans 5% of the width (2% at 640x360, where the own
// views of docs/QUALITY.md agree with these; less at a game's resolution, where it averages fewer
// features); 1024 stratified rays (two such references are expected to differ by about 0.0007 MAE, and
// both sides of each comparison below are measured against the same one).
//
// Measured 2026-11-25, MAE well / stairs / corner, nearest-pixel samples (planar ones 0 to 0.0015 lower):
//   high 3x3 regular + blur (18 samples):  0.0114 / 0.0166 / 0.0136  (without the blur 0.0113 / 0.0142 / 0.0145)
//   2x4 jittered + blur (16 samples):       0.0091 / 0.0164 / 0.0126  (5-tap blur: 0.0090 / 0.0139 / 0.0132)
//   6x1 jittered + blur (12 samples):       0.0343 / 0.0239 / 0.0438
//   3x2 jittered + blur (12 samples):       0.0182 / 0.0194 / 0.0232
//   2x3 jittered + blur (12 samples):       0.0120 / 0.0177 / 0.0159
//   1x6 jittered + blur (12 samples):       0.0160 / 0.0189 / 0.0138
//   1x4 jittered + blur (8 samples):        0.0158 / 0.0191 / 0.0164
// Regular slices gain nothing from the blur (every pixel has the same directions), and 1 jittered slice
// stays at 0.0156 or above on well with 4, 6 (or 8, nearest: 0.0161) steps: the 13 x 13 neighbourhood's
// directions do not make up for each pixel's single one there.
#include "ssao/gtao_scenes.h"

#include "obscura/bilateral.h"
#include "obscura/gtao.h"
#include "obscura/trace.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <string>

using namespace obscura;
using namespace obscura::ssao;

namespace {

struct Config {
    const char* name;
    GtaoSliceOverride counts;  // over the high preset
};

} // namespace

TEST(GtaoGroundTruth, TwoJitteredSlicesOfFourStepsMatchTheHighPresetOnceBlurred) {
    const Config high{"high 3x3", {}};
    const Config two4{"2x4 jittered", {2, 4, true}};
    // Every split of 12 samples, and 8.
    const Config fewer[] = {{"6x1 jittered", {6, 1, true}}, {"3x2 jittered", {3, 2, true}},
                            {"2x3 jittered", {2, 3, true}}, {"1x6 jittered", {1, 6, true}},
                            {"1x4 jittered", {1, 4, true}}};
    constexpr int kFewer = int(std::size(fewer));
    for (GtaoSampling sampling : {GtaoSampling::Nearest, GtaoSampling::Planar}) {
        const char* samplingName = gtaoSamplingName(sampling);
        double worstFewerMargin[kFewer];  // per config, its largest excess over high's error
        std::fill(std::begin(worstFewerMargin), std::end(worstFewerMargin), -1.0);
        for (const char* scene : {"well", "stairs", "corner"}) {
            const test::TopDownReference top(scene, 256, 1024);
            const GBuffer& g = top.g;
            const Image& reference = top.reference;
            // radius: the blur's taps on each side (6, its default: 13 taps; 0: no blur).
            auto blurredError = [&](const Config& c, int radius = 6) {
                GtaoSettings s;
                applyQuality(s, GtaoQuality::High);
                s.radius = top.view.radius;
                s.sampling = sampling;
                c.counts.apply(s);
                const Image visibility = computeGtao(g, s).visibility;
                BilateralSettings blur;
                blur.radius = std::max(radius, 1);
                return test::meanAbsoluteError(g, radius == 0 ? visibility : bilateralFilter(visibility, g, blur),
                                               reference);
            };
            const double highError = blurredError(high), two4Error = blurredError(two4);
            const double highRaw = blurredError(high, 0), two4Short = blurredError(two4, 2);
            std::printf("%s, %s samples: %s %.4f (unblurred %.4f), %s %.4f (5-tap blur %.4f)", scene, samplingName,
                        high.name, highError, highRaw, two4.name, two4Error, two4Short);
            // Fewer samples (16 against 18) and no worse: within the references' own spread of 0.001. With a
            // 5-tap blur too, against the high preset blurred or not.
            EXPECT_LE(two4Error, highError + 0.001) << scene << ", " << samplingName;
            EXPECT_LE(two4Short, std::min(highError, highRaw) + 0.001) << scene << ", " << samplingName;
            for (int i = 0; i < kFewer; ++i) {
                const double e = blurredError(fewer[i]);
                std::printf(", %s %.4f", fewer[i].name, e);
                worstFewerMargin[i] = std::max(worstFewerMargin[i], e - highError);
            }
            std::printf("\n");
        }
        // 12 samples or fewer lose to the high preset by more than the references' spread on some scene.
        for (int i = 0; i < kFewer; ++i)
            EXPECT_GT(worstFewerMargin[i], 0.0015) << fewer[i].name << ", " << samplingName;
    }
}
