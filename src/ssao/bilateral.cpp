// Cross-bilateral AO filter: McGuire et al. 2011, "The Alchemy Screen-Space Ambient Obscurance
// Algorithm" (two 1-D passes, Fig. 6) and the 2-D filter of "Where Corners Stay Dark" (Alchemy SSAO in an
// IBL renderer). See include/obscura/bilateral.h for the contract.
#include "obscura/bilateral.h"

#include "obscura/error.h"
#include "obscura/parallel.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

namespace obscura::ssao {

void BilateralSettings::validate() const {
    if (radius < 1 || radius > 32) fail("blur-radius", "must be in [1, 32] taps, is " + std::to_string(radius));
    if (!(depthSigma > 0.0f && depthSigma <= 10.0f))
        fail("blur-depth-sigma", "must be in (0, 10] (relative to depth), is " + std::to_string(depthSigma));
}

std::vector<float> gaussianHalfKernel(int radius) {
    assert(radius >= 1 && radius <= 32);
    const double s = radius / 2.0;
    std::vector<double> w(std::size_t(radius) + 1);
    for (int i = 0; i <= radius; ++i) w[std::size_t(i)] = std::exp(-0.5 * (i / s) * (i / s));
    // The centre tap appears once in the full kernel and every other tap twice.
    double sum = w[0];
    for (int i = 1; i <= radius; ++i) sum += 2.0 * w[std::size_t(i)];
    std::vector<float> out(w.size());
    for (std::size_t i = 0; i < w.size(); ++i) out[i] = float(w[i] / sum);
    return out;
}

namespace {

// The G-buffer fields the filter reads, as planes (structure of arrays) so the inner loops are unit-stride.
struct Planes {
    int width = 0, height = 0;
    std::vector<float> depth, nx, ny, nz;
    explicit Planes(const GBuffer& g) : width(g.width()), height(g.height()) {
        const std::size_t n = g.depth.pixelCount();
        depth.assign(g.depth.pixels.begin(), g.depth.pixels.end());
        nx.resize(n);
        ny.resize(n);
        nz.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            nx[i] = g.normal.pixels[3 * i];
            ny[i] = g.normal.pixels[3 * i + 1];
            nz[i] = g.normal.pixels[3 * i + 2];
        }
    }
    Vec3 normal(std::size_t i) const { return {nx[i], ny[i], nz[i]}; }
};

bool isSkyDepth(float d) { return !(d < 1e30f); }

float invTwoSigma2(float depthSigma, float d) {
    float sd = depthSigma * d;
    return 1.0f / (2.0f * sd * sd);
}

// One 1-D pass; `stride` is 1 along x and width along y.
Image pass1D(const Image& ao, const Planes& p, const BilateralSettings& s, int axis) {
    const std::vector<float> kernel = gaussianHalfKernel(s.radius);
    Image out(ao.width, ao.height, 1);
    const int w = p.width, h = p.height, r = s.radius;
    parallelFor(std::size_t(h), [&](std::size_t y0, std::size_t y1) {
        for (int y = int(y0); y < int(y1); ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t c = std::size_t(y) * std::size_t(w) + std::size_t(x);
                const float d = p.depth[c];
                if (isSkyDepth(d)) {
                    out.pixels[c] = ao.pixels[c];
                    continue;
                }
                const Vec3 n = p.normal(c);
                const float k = invTwoSigma2(s.depthSigma, d);
                const int pos = axis == 0 ? x : y, size = axis == 0 ? w : h;
                const int lo = std::max(-r, -pos), hi = std::min(r, size - 1 - pos);
                const std::ptrdiff_t stride = axis == 0 ? 1 : std::ptrdiff_t(w);
                float sum = 0.0f, wsum = 0.0f;
                for (int t = lo; t <= hi; ++t) {
                    const std::size_t i = std::size_t(std::ptrdiff_t(c) + t * stride);
                    const float wt =
                        tapWeight(kernel[std::size_t(std::abs(t))], d, n, p.depth[i], p.normal(i), k, s.normalWeight);
                    sum += wt * ao.pixels[i];
                    wsum += wt;
                }
                // The centre tap always has weight kernel[0] > 0 (unit normal, zero depth difference).
                out.pixels[c] = wsum > 0.0f ? sum / wsum : ao.pixels[c];
            }
    });
    return out;
}

Image pass2D(const Image& ao, const Planes& p, const BilateralSettings& s) {
    const std::vector<float> kernel = gaussianHalfKernel(s.radius);
    Image out(ao.width, ao.height, 1);
    const int w = p.width, h = p.height, r = s.radius;
    parallelFor(std::size_t(h), [&](std::size_t y0, std::size_t y1) {
        for (int y = int(y0); y < int(y1); ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t c = std::size_t(y) * std::size_t(w) + std::size_t(x);
                const float d = p.depth[c];
                if (isSkyDepth(d)) {
                    out.pixels[c] = ao.pixels[c];
                    continue;
                }
                const Vec3 n = p.normal(c);
                const float k = invTwoSigma2(s.depthSigma, d);
                float sum = 0.0f, wsum = 0.0f;
                for (int ty = std::max(-r, -y); ty <= std::min(r, h - 1 - y); ++ty)
                    for (int tx = std::max(-r, -x); tx <= std::min(r, w - 1 - x); ++tx) {
                        const std::size_t i = std::size_t(y + ty) * std::size_t(w) + std::size_t(x + tx);
                        const float spatial = kernel[std::size_t(std::abs(tx))] * kernel[std::size_t(std::abs(ty))];
                        const float wt = tapWeight(spatial, d, n, p.depth[i], p.normal(i), k, s.normalWeight);
                        sum += wt * ao.pixels[i];
                        wsum += wt;
                    }
                out.pixels[c] = wsum > 0.0f ? sum / wsum : ao.pixels[c];
            }
    });
    return out;
}

void checkInputs(const Image& ao, const GBuffer& g) {
    if (g.width() < 1 || g.height() < 1) fail("bilateral filter", "G-buffer has zero size");
    if (g.depth.width != g.width() || g.depth.height != g.height() || g.depth.channels != 1)
        fail("bilateral filter", "depth buffer does not match the camera's size or is not 1 channel");
    if (g.normal.width != g.width() || g.normal.height != g.height() || g.normal.channels != 3)
        fail("bilateral filter", "normal buffer does not match the camera's size or is not 3 channels");
    if (ao.width != g.width() || ao.height != g.height() || ao.channels != 1)
        fail("bilateral filter", "AO image is " + std::to_string(ao.width) + "x" + std::to_string(ao.height) + "x" +
                                     std::to_string(ao.channels) + ", G-buffer is " + std::to_string(g.width()) +
                                     "x" + std::to_string(g.height()) + " (needs 1 channel of the same size)");
}

} // namespace

Image bilateralPass(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings, int axis) {
    settings.validate();
    checkInputs(ao, gbuffer);
    assert(axis == 0 || axis == 1);
    return pass1D(ao, Planes(gbuffer), settings, axis);
}

Image bilateral2D(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings) {
    settings.validate();
    checkInputs(ao, gbuffer);
    return pass2D(ao, Planes(gbuffer), settings);
}

Image bilateralFilter(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings) {
    settings.validate();
    checkInputs(ao, gbuffer);
    switch (settings.mode) {
    case BlurMode::None:
        return ao;
    case BlurMode::Separable: {
        Planes p(gbuffer);
        return pass1D(pass1D(ao, p, settings, 0), p, settings, 1);
    }
    case BlurMode::TwoD:
        return pass2D(ao, Planes(gbuffer), settings);
    }
    return ao;
}

} // namespace obscura::ssao
