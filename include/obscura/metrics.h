// Error metrics of an AO image against a reference (usually the ray-traced integral of the same falloff),
// and the signed-error colours of the comparison pictures.
//
// Errors: errorStats() throws obscura::Error when the images and the G-buffer differ in size or are not
// 1 channel.
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/image.h"

#include <cstddef>

namespace obscura::eval {

// Over the G-buffer's surface pixels (sky excluded), e = estimate - reference; with no surface pixel, every
// figure is NaN (pixels 0), not the 0 of exact agreement:
struct ErrorStats {
    double mae = 0;       // mean |e|
    double rmse = 0;      // sqrt(mean e^2)
    double bias = 0;      // mean e: > 0 means the estimate is too light (too little occlusion)
    double maxError = 0;  // max |e|
    std::size_t pixels = 0;
};
ErrorStats errorStats(const Image& estimate, const Image& reference, const GBuffer& gbuffer);

// Diverging colour for a signed error e in [-range, range]: blue (estimate too dark) through white (0) to
// red (too light), clamped outside; linear-light values ready for the sRGB transfer of toDisplay.
Vec3 signedErrorColor(float error, float range);
// 3-channel picture of estimate - reference; sky pixels are mid grey.
Image signedErrorImage(const Image& estimate, const Image& reference, const GBuffer& gbuffer, float range);

} // namespace obscura::eval
