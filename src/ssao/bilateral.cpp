// Cross-bilateral AO filter: McGuire et al. 2011, "The Alchemy Screen-Space Ambient Obscurance
// Algorithm" (two 1-D passes, Fig. 6) and the 2-D filter of "Where Corners Stay Dark" (Alchemy SSAO in an
// IBL renderer). See include/obscura/bilateral.h for the contract.
#include "obscura/bilateral.h"
#include "bilateral_separable.h"

#include "obscura/error.h"
#include "obscura/parallel.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cassert>
#include <cmath>
#include <string>

namespace obscura::ssao {

void BilateralSettings::validate() const {
    if (radius < 1 || radius > kMaxBlurRadius)
        fail("blur-radius", "must be in [1, " + std::to_string(kMaxBlurRadius) + "] taps, is " + std::to_string(radius));
    // From 1e-6 up: a depth is a float, good to 6e-8 of itself, so a smaller tolerance admits no tap a sigma of
    // 1e-6 would not; and from about 1e-19 down 1 / (2 sigma^2) overflows a float, which made the CPU's weights
    // NaN (a fully occluded pixel came out 0.95) while the GPU's stayed finite.
    if (!(depthSigma >= 1e-6f && depthSigma <= 10.0f))
        fail("blur-depth-sigma", "must be in [1e-6, 10] (relative to depth), is " + numberText(depthSigma));
}

std::vector<float> gaussianHalfKernel(int radius) {
    assert(radius >= 1 && radius <= kMaxBlurRadius);
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

// exp(x) for x <= 0 without a libm call or a branch, so the tap loops vectorise: 2^(x log2 e) as 2^i times
// a degree-6 Taylor polynomial of 2^f, f in [0, 1) (relative error < 2e-5, far below what a blur weight
// needs). exp(0) is exactly 1. x is clamped at -87 (and NaN taken as -87), so a sky tap, whose depth
// difference is infinite, weighs 2^-125.5 ~ 1e-38 of a centre tap: nothing a float sum can show.
inline float fastExpNegative(float x) {
    // Offsetting by 128 makes t positive, so truncation is floor.
    const float t = std::max(-87.0f, x) * 1.44269504f + 128.0f;
    const int i = int(t);
    const float f = t - float(i);
    const float p =
        1.0f + f * (0.693147181f + f * (0.240226507f + f * (0.0555041087f + f * (0.00961812911f + f * (0.00133335581f + f * 0.000154035304f)))));
    return p * std::bit_cast<float>((i - 1) << 23);  // 2^(i - 128) has the biased exponent i - 1
}

// One row segment of taps: for x in [0, n), the tap at dT[x] etc. weighs against the centre at dC[x].
// The same loop serves the horizontal pass (tap pointers shifted by t), the vertical pass (tap pointers on
// another row) and each offset of the 2-D filter; every output accumulates its taps in the same order on
// any thread count.
// Built for AVX2 as well where the compiler can (the library targets baseline x86-64 otherwise) and
// chosen at load time; fp-contract is off in ISO C++ mode, so both versions give the same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define OBSCURA_TARGET_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define OBSCURA_TARGET_CLONES
#endif

template <bool UseNormal>
OBSCURA_TARGET_CLONES void accumulateTaps(int n, float spatial, const float* __restrict dC, const float* __restrict invC,
                    const float* __restrict nxC, const float* __restrict nyC, const float* __restrict nzC,
                    const float* __restrict dT, const float* __restrict nxT, const float* __restrict nyT,
                    const float* __restrict nzT, const float* __restrict aoT, float* __restrict sum,
                    float* __restrict wsum) {
    for (int x = 0; x < n; ++x) {
        const float dd = dT[x] - dC[x];
        float w = spatial * fastExpNegative(-dd * dd * invC[x]);
        if constexpr (UseNormal) w *= std::max(0.0f, nxC[x] * nxT[x] + nyC[x] * nyT[x] + nzC[x] * nzT[x]);
        sum[x] += w * aoT[x];
        wsum[x] += w;
    }
}

void accumulateTaps(int n, float spatial, bool useNormal, const float* dC, const float* invC, const float* nxC,
                    const float* nyC, const float* nzC, const float* dT, const float* nxT, const float* nyT,
                    const float* nzT, const float* aoT, float* sum, float* wsum) {
    if (useNormal)
        accumulateTaps<true>(n, spatial, dC, invC, nxC, nyC, nzC, dT, nxT, nyT, nzT, aoT, sum, wsum);
    else
        accumulateTaps<false>(n, spatial, dC, invC, nxC, nyC, nzC, dT, nxT, nyT, nzT, aoT, sum, wsum);
}

float invTwoSigma2(float depthSigma, float d) {
    const float sd = depthSigma * d;
    return 1.0f / (2.0f * sd * sd);
}

// Per row scratch: 1 / (2 sigma_d^2) of each centre, and the running sums.
struct RowScratch {
    std::vector<float> inv, sum, wsum;
    explicit RowScratch(int w) : inv(std::size_t(w)), sum(std::size_t(w)), wsum(std::size_t(w)) {}
    void begin(const float* d, int w, float depthSigma) {
        for (int x = 0; x < w; ++x) inv[std::size_t(x)] = invTwoSigma2(depthSigma, d[x]);
        std::fill(sum.begin(), sum.end(), 0.0f);
        std::fill(wsum.begin(), wsum.end(), 0.0f);
    }
    // A centre with no weight (impossible for a surface: its own tap weighs kernel[0]) or on sky keeps its input.
    void finish(const float* d, const float* ao, float* out, int w) const {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(x);
            out[x] = (isSkyDepth(d[x]) || !(wsum[i] > 0.0f)) ? ao[x] : sum[i] / wsum[i];
        }
    }
};

// Rows are processed in chunks of this many pixels, so a chunk's centre data, sums and taps stay in L1.
constexpr int kChunk = 256;

Image pass2D(const Image& ao, const Planes& p, const BilateralSettings& s) {
    const std::vector<float> kernel = gaussianHalfKernel(s.radius);
    Image out(ao.width, ao.height, 1);
    const int w = p.width, h = p.height, r = s.radius;
    parallelFor(
        std::size_t(h),
        [&](std::size_t y0, std::size_t y1) {
            RowScratch row(w);
            for (int y = int(y0); y < int(y1); ++y) {
                const std::size_t c = std::size_t(y) * std::size_t(w);
                row.begin(&p.depth[c], w, s.depthSigma);
                for (int cx0 = 0; cx0 < w; cx0 += kChunk) {
                    const int cx1 = std::min(w, cx0 + kChunk);
                    for (int ty = std::max(-r, -y); ty <= std::min(r, h - 1 - y); ++ty) {
                        const std::size_t rowT = std::size_t(y + ty) * std::size_t(w);
                        for (int tx = -r; tx <= r; ++tx) {
                            const int x0 = std::max(cx0, -tx), x1 = std::min(cx1, w - tx);
                            if (x1 <= x0) continue;
                            const float k = kernel[std::size_t(std::abs(tx))] * kernel[std::size_t(std::abs(ty))];
                            const std::size_t i = c + std::size_t(x0);
                            const std::size_t j = std::size_t(std::ptrdiff_t(rowT + std::size_t(x0)) + tx);
                            accumulateTaps(x1 - x0, k, s.usesNormals(), &p.depth[i], &row.inv[std::size_t(x0)],
                                           &p.nx[i], &p.ny[i], &p.nz[i], &p.depth[j], &p.nx[j], &p.ny[j], &p.nz[j],
                                           &ao.pixels[j], &row.sum[std::size_t(x0)], &row.wsum[std::size_t(x0)]);
                        }
                    }
                }
                row.finish(&p.depth[c], &ao.pixels[c], &out.pixels[c], w);
            }
        },
        2);
    return out;
}

} // namespace

void checkBilateralInputs(const Image& ao, const GBuffer& g, const BilateralSettings& settings) {
    settings.validate();
    if (g.width() < 1 || g.height() < 1) fail("bilateral filter", "G-buffer has zero size");
    if (g.depth.width != g.width() || g.depth.height != g.height() || g.depth.channels != 1)
        fail("bilateral filter", "depth buffer does not match the camera's size or is not 1 channel");
    if (g.normal.width != g.width() || g.normal.height != g.height() || g.normal.channels != 3)
        fail("bilateral filter", "normal buffer does not match the camera's size or is not 3 channels");
    if (ao.width != g.width() || ao.height != g.height() || ao.channels != 1)
        fail("bilateral filter", "AO image is " + std::to_string(ao.width) + "x" + std::to_string(ao.height) + "x" +
                                     std::to_string(ao.channels) + ", G-buffer is " + std::to_string(g.width()) +
                                     "x" + std::to_string(g.height()) + " (needs 1 channel of the same size)");
    // A NaN depth made a NaN weight, which the CPU's exp2 clamps to about 2^-125 (the centre still blurred) and
    // the GPU's exp2 passes on (the centre kept raw): 0.79 against 0.51 beside it. A NaN AO spread over a window.
    // Every blur of every frame makes this check, so it reads what the blur reads and no more (the normals only
    // with the normal weight; the whole G-buffer's validatePixels and a separate AO scan took 2.7 ms, a fifth of a
    // separable blur at 1920x1080 on 2 cores), in one branch-free pass over rows in parallel; the loop that
    // names the first bad pixel runs only for a bad image.
    const bool normals = settings.usesNormals();
    const int w = ao.width;
    std::atomic<bool> bad{false};
    parallelFor(std::size_t(ao.height), [&](std::size_t y0, std::size_t y1) {
        bool ok = normals ? g.pixelsValid(0, w, int(y0), int(y1)) : true;
        for (std::size_t i = y0 * std::size_t(w); i < y1 * std::size_t(w); ++i)
            ok &= (g.depth.pixels[i] > 0.0f) & ((ao.pixels[i] - ao.pixels[i]) == 0.0f);
        if (!ok) bad.store(true, std::memory_order_relaxed);
    }, 16);
    if (!bad.load()) return;
    if (normals) g.validatePixels("bilateral filter");
    for (int y = 0; y < ao.height; ++y)
        for (int x = 0; x < w; ++x) {
            const float d = g.depth.at(x, y), v = ao.at(x, y);
            if (d > 0.0f && std::isfinite(v)) continue;
            const std::string at = "at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is ";
            if (!(d > 0.0f)) fail("bilateral filter", "depth " + at + numberText(d) + " (must be positive or +inf)");
            fail("bilateral filter", "AO " + at + numberText(v));
        }
}

Image bilateralPass(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings, int axis) {
    checkBilateralInputs(ao, gbuffer, settings);
    assert(axis == 0 || axis == 1);
    return detail::separableBlur(ao, gbuffer, settings, axis == 0, axis == 1);
}

Image bilateral2D(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings) {
    checkBilateralInputs(ao, gbuffer, settings);
    return pass2D(ao, Planes(gbuffer), settings);
}

Image bilateralFilter(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings) {
    checkBilateralInputs(ao, gbuffer, settings);
    switch (settings.mode) {
    case BlurMode::None:
        return ao;
    case BlurMode::Separable:
        return detail::separableBlur(ao, gbuffer, settings, true, true);
    case BlurMode::TwoD:
        return pass2D(ao, Planes(gbuffer), settings);
    }
    return ao;
}

} // namespace obscura::ssao
