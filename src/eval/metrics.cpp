// Error metrics against a reference AO image and the signed-error colour map of the comparison pictures.
#include "obscura/metrics.h"

#include "obscura/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace obscura::eval {

namespace {
void checkSizes(const Image& estimate, const Image& reference, const GBuffer& g) {
    auto same = [&](const Image& img) { return img.width == g.width() && img.height == g.height() && img.channels == 1; };
    if (!same(estimate) || !same(reference) || !same(g.depth))
        fail("error metrics", "estimate " + std::to_string(estimate.width) + "x" + std::to_string(estimate.height) +
                                  ", reference " + std::to_string(reference.width) + "x" +
                                  std::to_string(reference.height) + " and G-buffer " + std::to_string(g.width()) +
                                  "x" + std::to_string(g.height()) + " must be 1-channel images of one size");
}
} // namespace

ErrorStats errorStats(const Image& estimate, const Image& reference, const GBuffer& g) {
    checkSizes(estimate, reference, g);
    ErrorStats s;
    double sum = 0, sumAbs = 0, sumSq = 0;
    for (std::size_t i = 0; i < estimate.pixels.size(); ++i) {
        if (!(g.depth.pixels[i] < 1e30f)) continue;
        // std::max would drop a NaN from maxError while mae went NaN: refuse it, naming the pixel.
        const bool badEstimate = !std::isfinite(estimate.pixels[i]);
        if (badEstimate || !std::isfinite(reference.pixels[i])) {
            const std::size_t w = std::size_t(g.width());
            fail("error metrics", std::string(badEstimate ? "estimate" : "reference") + " at pixel (" +
                                      std::to_string(i % w) + ", " + std::to_string(i / w) + ") is " +
                                      numberText(badEstimate ? estimate.pixels[i] : reference.pixels[i]) +
                                      ": must be finite");
        }
        const double e = double(estimate.pixels[i]) - double(reference.pixels[i]);
        sum += e;
        sumAbs += std::fabs(e);
        sumSq += e * e;
        s.maxError = std::max(s.maxError, std::fabs(e));
        ++s.pixels;
    }
    // Errors over no pixels are unknown, not 0: an all-sky view read as exact agreement.
    if (s.pixels == 0) {
        s.mae = s.rmse = s.bias = s.maxError = std::numeric_limits<double>::quiet_NaN();
        return s;
    }
    const double n = double(s.pixels);
    s.mae = sumAbs / n;
    s.rmse = std::sqrt(sumSq / n);
    s.bias = sum / n;
    return s;
}

Vec3 signedErrorColor(float error, float range) {
    const float t = std::clamp(error / range, -1.0f, 1.0f);
    const Vec3 white{1, 1, 1}, red{0.7f, 0.02f, 0.02f}, blue{0.02f, 0.1f, 0.7f};
    return t >= 0 ? white + (red - white) * t : white + (blue - white) * -t;
}

Image signedErrorImage(const Image& estimate, const Image& reference, const GBuffer& g, float range) {
    checkSizes(estimate, reference, g);
    // range <= 0 would swap red and blue (or give 0/0 = NaN colours at e = 0).
    if (!(range > 0.0f && std::isfinite(range)))
        fail("signed error range", "must be positive and finite, got " + numberText(range));
    Image out(g.width(), g.height(), 3);
    for (std::size_t i = 0; i < estimate.pixels.size(); ++i) {
        const Vec3 c = g.depth.pixels[i] < 1e30f ? signedErrorColor(estimate.pixels[i] - reference.pixels[i], range)
                                                 : Vec3{0.2f, 0.2f, 0.2f};
        for (int k = 0; k < 3; ++k) out.pixels[3 * i + std::size_t(k)] = c[k];
    }
    return out;
}

} // namespace obscura::eval
