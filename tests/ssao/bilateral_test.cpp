// Cross-bilateral filter (include/obscura/bilateral.h): kernel normalisation, invariance on constant input,
// edge stopping across depth steps, creases and sky, agreement with a plain Gaussian where nothing stops
// it, and the same bits on any thread count.
#include "obscura/bilateral.h"
#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace obscura::ssao {
namespace {

// A w x h G-buffer whose depth(x, y) and view normal(x, y) come from functions.
template <class Depth, class Normal>
GBuffer makeGBuffer(int w, int h, Depth depth, Normal normal) {
    GBuffer g;
    g.camera.width = w;
    g.camera.height = h;
    g.depth = Image(w, h, 1);
    g.normal = Image(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            g.depth.at(x, y) = depth(x, y);
            Vec3 n = normal(x, y);
            for (int c = 0; c < 3; ++c) g.normal.at(x, y, c) = n[c];
        }
    return g;
}

const Vec3 kFacing{0, 0, 1};

BilateralSettings settings(BlurMode mode, int radius) {
    BilateralSettings s;
    s.mode = mode;
    s.radius = radius;
    return s;
}

Image noise(int w, int h, std::uint32_t seed) {
    Image img(w, h, 1);
    for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = toUnitFloat(hashCombine(seed, std::uint32_t(i)));
    return img;
}

} // namespace

// The chapter's warning: the centre tap counts once, the others twice. In double the full kernel sums to 1
// up to rounding (1e-12); summed in float as a shader would, 2r + 1 additions of values <= 1 stay within
// 65 * 2^-24 ~ 4e-6 of it, so 1e-6 (observed sums are within a few ulps) is a real check of the normalisation.
TEST(Bilateral, KernelWeightsSumToOneForEveryRadius) {
    for (int r = 1; r <= 32; ++r) {
        std::vector<float> k = gaussianHalfKernel(r);
        ASSERT_EQ(k.size(), std::size_t(r) + 1);
        double sumD = k[0];
        float sumF = k[0];
        for (int i = 1; i <= r; ++i) {
            sumD += 2.0 * double(k[std::size_t(i)]);
            sumF += 2.0f * k[std::size_t(i)];
        }
        EXPECT_NEAR(sumD, 1.0, 1e-6) << "radius " << r;
        EXPECT_NEAR(sumF, 1.0f, 1e-6f) << "radius " << r;
        // sigma = r / 2 puts the edge tap at exp(-2) of the centre.
        EXPECT_NEAR(k[std::size_t(r)] / k[0], std::exp(-2.0f), 1e-5f) << "radius " << r;
        for (int i = 1; i <= r; ++i) EXPECT_LT(k[std::size_t(i)], k[std::size_t(i - 1)]);
    }
}

// Any weights, normalised by their sum, map a constant to itself: checked on a G-buffer with depth ramps,
// steps, tilted normals and sky, for all modes and radii 1, 6, 32. Float rounding of a normalised sum of
// up to 65^2 terms stays below 1e-5 relative.
TEST(Bilateral, ConstantImageIsUnchanged) {
    const int w = 48, h = 40;
    GBuffer g = makeGBuffer(
        w, h,
        [](int x, int y) {
            if (x > 40 && y < 6) return INFINITY;
            return 1.0f + 0.05f * float(x) + (y > 20 ? 2.0f : 0.0f);
        },
        [](int x, int) { return x < 24 ? kFacing : normalize(Vec3{0.6f, 0.0f, 0.8f}); });
    const float value = 0.37f;
    Image ao(w, h, 1, value);
    for (BlurMode mode : {BlurMode::None, BlurMode::Separable, BlurMode::TwoD})
        for (int r : {1, 6, 32}) {
            Image out = bilateralFilter(ao, g, settings(mode, r));
            float worst = 0;
            for (float v : out.pixels) worst = std::max(worst, std::fabs(v - value));
            EXPECT_LE(worst, 1e-5f * value) << "mode " << int(mode) << " radius " << r;
        }
}

// A depth step of 20% (d = 2 | 2.4) between AO 0 and AO 1. With depthSigma 0.05, sigma_d = 0.1 m at the
// near side and a cross tap weighs exp(-0.4^2 / (2 * 0.1^2)) = exp(-8) = 3.4e-4 of a same-side tap at the
// same spatial weight, so at most ~3.4e-4 of the result can leak: the acceptance bound is 1%.
TEST(Bilateral, DepthStepLeaksLessThanOnePercent) {
    const int w = 64, h = 32;
    GBuffer g = makeGBuffer(w, h, [](int x, int) { return x < 32 ? 2.0f : 2.4f; }, [](int, int) { return kFacing; });
    Image ao(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) ao.at(x, y) = x < 32 ? 0.0f : 1.0f;
    for (BlurMode mode : {BlurMode::Separable, BlurMode::TwoD})
        for (int r : {2, 6, 16}) {
            Image out = bilateralFilter(ao, g, settings(mode, r));
            float leakNear = 0, leakFar = 0;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    if (x < 32) leakNear = std::max(leakNear, out.at(x, y));
                    else leakFar = std::max(leakFar, 1.0f - out.at(x, y));
                }
            EXPECT_LT(leakNear, 0.01f) << "mode " << int(mode) << " radius " << r;
            EXPECT_LT(leakFar, 0.01f) << "mode " << int(mode) << " radius " << r;
        }
    // Without the depth test (a huge sigma) the same edge does blur: the check above is not vacuous.
    BilateralSettings loose = settings(BlurMode::Separable, 6);
    loose.depthSigma = 10.0f;
    EXPECT_GT(bilateralFilter(ao, g, loose).at(31, 16), 0.2f);
}

// A crease at equal depth (a wall meeting a floor): normals 90 degrees apart give max(0, N . Ni) = 0, so
// nothing crosses it when the normal weight is on (the 2-D filter's default). The separable filter weighs
// by depth alone by default, as the paper does, and then blurs across it.
TEST(Bilateral, NormalCreaseStopsTheBlur) {
    const int w = 40, h = 24;
    GBuffer g = makeGBuffer(w, h, [](int, int) { return 3.0f; },
                            [](int x, int) { return x < 20 ? kFacing : Vec3{1, 0, 0}; });
    Image ao(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) ao.at(x, y) = x < 20 ? 0.0f : 1.0f;
    for (BlurMode mode : {BlurMode::Separable, BlurMode::TwoD})
        for (NormalWeight nw : {NormalWeight::Auto, NormalWeight::On}) {
            BilateralSettings s = settings(mode, 6);
            s.normalWeight = nw;
            if (!s.usesNormals()) continue;
            Image out = bilateralFilter(ao, g, s);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) ASSERT_EQ(out.at(x, y), ao.at(x, y)) << x << "," << y;
        }
    BilateralSettings depthOnly = settings(BlurMode::Separable, 6);
    ASSERT_FALSE(depthOnly.usesNormals());
    // Beside the crease a depth-only 13-tap Gaussian (sigma 3) mixes both sides: about 0.4 and 0.6.
    const Image out = bilateralFilter(ao, g, depthOnly);
    EXPECT_NEAR(out.at(19, 12), 0.43, 0.05);
    EXPECT_NEAR(out.at(20, 12), 0.57, 0.05);
    depthOnly.mode = BlurMode::TwoD;
    depthOnly.normalWeight = NormalWeight::Off;
    EXPECT_NEAR(bilateralFilter(ao, g, depthOnly).at(19, 12), 0.43, 0.05);
}

// Sky pixels keep their value and never feed a surface pixel.
TEST(Bilateral, SkyIsIgnored) {
    const int w = 32, h = 32;
    GBuffer g = makeGBuffer(w, h, [](int x, int y) { return (x + y) % 3 == 0 ? INFINITY : 5.0f; },
                            [](int x, int y) { return (x + y) % 3 == 0 ? Vec3{} : kFacing; });
    Image ao(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) ao.at(x, y) = (x + y) % 3 == 0 ? 0.0f : 0.75f;
    for (BlurMode mode : {BlurMode::Separable, BlurMode::TwoD}) {
        Image out = bilateralFilter(ao, g, settings(mode, 4));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) ASSERT_NEAR(out.at(x, y), ao.at(x, y), 1e-6f) << x << "," << y;
    }
}

// On one plane facing the camera every range weight is 1, so the filters reduce to a Gaussian
// convolution, computed here independently in double (away from the borders): 2-D directly, separable as
// the same 2-D kernel's product form, which is exact for a constant-depth plane.
TEST(Bilateral, FlatPlaneIsAPlainGaussian) {
    const int w = 40, h = 40, r = 5;
    GBuffer g = makeGBuffer(w, h, [](int, int) { return 1.5f; }, [](int, int) { return kFacing; });
    Image ao = noise(w, h, 11);
    const double s = r / 2.0;
    std::vector<double> k(r + 1);
    double sum = 0;
    for (int i = -r; i <= r; ++i) sum += std::exp(-0.5 * (i / s) * (i / s));
    for (int i = 0; i <= r; ++i) k[std::size_t(i)] = std::exp(-0.5 * (i / s) * (i / s)) / sum;
    Image sep = bilateralFilter(ao, g, settings(BlurMode::Separable, r));
    Image two = bilateralFilter(ao, g, settings(BlurMode::TwoD, r));
    for (int y = r; y < h - r; ++y)
        for (int x = r; x < w - r; ++x) {
            double expected = 0;
            for (int ty = -r; ty <= r; ++ty)
                for (int tx = -r; tx <= r; ++tx)
                    expected += k[std::size_t(std::abs(tx))] * k[std::size_t(std::abs(ty))] * double(ao.at(x + tx, y + ty));
            // Inside [r, size - r) neither pass reaches the border, so the separable product is exact.
            EXPECT_NEAR(two.at(x, y), expected, 1e-5) << x << "," << y;
            EXPECT_NEAR(sep.at(x, y), expected, 1e-5) << x << "," << y;
        }
}

// The row-vectorised filter against a direct per-pixel evaluation with tapWeight (std::exp) in double, on a
// G-buffer with depth ramps, 10% steps, varied normals and sky. The fast exp has relative error < 2e-5 and
// the sums are normalised, so outputs agree to ~1e-5; 1e-4 is the bound. Where a whole window reads 1 the
// output must be exactly 1.
TEST(Bilateral, MatchesADirectEvaluation) {
    const int w = 41, h = 29;
    GBuffer g = makeGBuffer(
        w, h, [](int x, int y) { return (x * 7 + y * 3) % 23 == 0 ? INFINITY : 2.0f + 0.03f * float(x) + (y > 14 ? 0.2f : 0.0f); },
        [](int x, int y) { return normalize(Vec3{0.05f * float(x % 5), 0.1f * float(y % 3), 1.0f}); });
    // Noise, with blocks of exactly 1 (what the estimator writes on open surfaces and sky), where the separable
    // filter skips its arithmetic.
    Image ao = noise(w, h, 5);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if ((x / 16 + y / 15) % 2 == 0) ao.at(x, y) = 1.0f;
    for (BlurMode mode : {BlurMode::Separable, BlurMode::TwoD})
        for (NormalWeight nw : {NormalWeight::On, NormalWeight::Off})
        for (int r : {1, 3, 7}) {
            BilateralSettings st = settings(mode, r);
            st.normalWeight = nw;
            std::vector<float> k = gaussianHalfKernel(r);
            auto direct = [&](const Image& in, int x, int y, int axis) {  // axis 0, 1, or 2 for the square
                const float d = g.depth.at(x, y);
                if (!(d < 1e30f)) return double(in.at(x, y));
                const float inv = 1.0f / (2.0f * (st.depthSigma * d) * (st.depthSigma * d));
                double sum = 0, wsum = 0;
                for (int ty = (axis == 0 ? 0 : -r); ty <= (axis == 0 ? 0 : r); ++ty)
                    for (int tx = (axis == 1 ? 0 : -r); tx <= (axis == 1 ? 0 : r); ++tx) {
                        const int sx = x + tx, sy = y + ty;
                        if (sx < 0 || sy < 0 || sx >= w || sy >= h) continue;
                        const double wt = tapWeight(k[std::size_t(std::abs(tx))] * k[std::size_t(std::abs(ty))], d,
                                                    g.viewNormal(x, y), g.depth.at(sx, sy), g.viewNormal(sx, sy), inv, st.usesNormals());
                        sum += wt * double(in.at(sx, sy));
                        wsum += wt;
                    }
                return sum / wsum;
            };
            Image expected(w, h, 1);
            if (mode == BlurMode::TwoD) {
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) expected.at(x, y) = float(direct(ao, x, y, 2));
            } else {
                Image horizontal(w, h, 1);
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) horizontal.at(x, y) = float(direct(ao, x, y, 0));
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) expected.at(x, y) = float(direct(horizontal, x, y, 1));
            }
            Image out = bilateralFilter(ao, g, st);
            for (std::size_t i = 0; i < out.pixels.size(); ++i)
                ASSERT_NEAR(out.pixels[i], expected.pixels[i], 1e-4f) << "mode " << int(mode) << " radius " << r << " pixel " << i;
            int ones = 0;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    bool all = true;
                    for (int ty = std::max(0, y - r); ty <= std::min(h - 1, y + r); ++ty)
                        for (int tx = std::max(0, x - r); tx <= std::min(w - 1, x + r); ++tx) all = all && ao.at(tx, ty) == 1.0f;
                    if (!all) continue;
                    ++ones;
                    ASSERT_EQ(out.at(x, y), 1.0f) << x << "," << y;
                }
            EXPECT_GT(ones, 0);
        }
}

TEST(Bilateral, SameBitsOnAnyThreadCount) {
    const int w = 97, h = 61;
    GBuffer g = makeGBuffer(w, h, [](int x, int y) { return 1.0f + 0.01f * float(x * y % 17); },
                            [](int x, int) { return normalize(Vec3{0.01f * float(x), 0.2f, 1.0f}); });
    Image ao = noise(w, h, 3);
    for (BlurMode mode : {BlurMode::Separable, BlurMode::TwoD}) {
        Image one, many;
        {
            ThreadLimit limit(1);
            one = bilateralFilter(ao, g, settings(mode, 6));
        }
        many = bilateralFilter(ao, g, settings(mode, 6));
        EXPECT_EQ(one.pixels, many.pixels);
    }
}

// The separable filter fuses its two passes over tiles (with apron rows and sky padding at the borders);
// the single passes run the same arithmetic, so chaining them gives the same bits, at sizes that leave
// partial tiles and with and without the normal weight.
TEST(Bilateral, FusedSeparableEqualsTwoPasses) {
    for (auto [w, h] : {std::pair{301, 277}, std::pair{9, 530}}) {
        GBuffer g = makeGBuffer(
            w, h, [](int x, int y) { return (x * 5 + y * 11) % 37 == 0 ? INFINITY : 1.0f + 0.01f * float((x * y) % 23); },
            [](int x, int y) { return normalize(Vec3{0.02f * float(x % 7), 0.1f * float(y % 5) - 0.2f, 1.0f}); });
        Image ao = noise(w, h, 17);
        for (bool normals : {true, false})
            for (int r : {1, 6, 32}) {
                BilateralSettings s = settings(BlurMode::Separable, r);
                s.normalWeight = normals ? NormalWeight::On : NormalWeight::Off;
                Image fused = bilateralFilter(ao, g, s);
                Image chained = bilateralPass(bilateralPass(ao, g, s, 0), g, s, 1);
                ASSERT_EQ(fused.pixels, chained.pixels) << w << "x" << h << " radius " << r << " normals " << normals;
            }
    }
}

TEST(Bilateral, RejectsBadSettingsAndBuffers) {
    GBuffer g = makeGBuffer(8, 8, [](int, int) { return 1.0f; }, [](int, int) { return kFacing; });
    Image ao(8, 8, 1, 0.5f);
    EXPECT_THROW(bilateralFilter(ao, g, settings(BlurMode::Separable, 0)), Error);
    EXPECT_THROW(bilateralFilter(ao, g, settings(BlurMode::Separable, 33)), Error);
    BilateralSettings s;
    s.depthSigma = 0.0f;
    EXPECT_THROW(bilateralFilter(ao, g, s), Error);
    s.depthSigma = NAN;
    EXPECT_THROW(bilateralFilter(ao, g, s), Error);
    // Below float's resolution of a depth: 1e-30 once overflowed 1 / (2 sigma^2) into NaN weights.
    for (float tiny : {1e-30f, 1e-20f, 9e-7f}) {
        s.depthSigma = tiny;
        EXPECT_THROW(bilateralFilter(ao, g, s), Error) << tiny;
    }
    s.depthSigma = 1e-6f;
    const Image smallest = bilateralFilter(ao, g, s);
    for (float v : smallest.pixels) EXPECT_FLOAT_EQ(v, 0.5f);  // a constant stays constant
    EXPECT_THROW(bilateralFilter(Image(8, 7, 1), g, BilateralSettings{}), Error);
    EXPECT_THROW(bilateralFilter(Image(8, 8, 3), g, BilateralSettings{}), Error);
    try {
        bilateralFilter(Image(4, 4, 1), g, BilateralSettings{});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("4x4x1"), std::string::npos) << e.what();
    }
    // Non-finite inputs: a NaN depth was blurred on the CPU and kept raw on the GPU; a NaN AO spread.
    const auto errorOf = [](const auto& run) -> std::string {
        try {
            run();
        } catch (const Error& e) {
            return e.what();
        }
        return "no error";
    };
    GBuffer nanDepth = g;
    nanDepth.depth.at(3, 2) = NAN;
    EXPECT_EQ(errorOf([&] { bilateralFilter(ao, nanDepth, BilateralSettings{}); }),
              "bilateral filter: depth at pixel (3, 2) is nan (must be positive or +inf)");
    Image nanAo = ao;
    nanAo.at(5, 6) = NAN;
    EXPECT_EQ(errorOf([&] { bilateral2D(nanAo, g, BilateralSettings{}); }), "bilateral filter: AO at pixel (5, 6) is nan");
    // Normals are checked where the blur reads them: with the normal weight (the 2-D blur's by default), not
    // without it (the separable one's default), where the check reads depth and AO alone.
    GBuffer nanNormal = g;
    nanNormal.normal.at(4, 1, 2) = NAN;
    BilateralSettings twoD = settings(BlurMode::TwoD, 3);
    EXPECT_EQ(errorOf([&] { bilateralFilter(ao, nanNormal, twoD); }),
              "bilateral filter: normal at pixel (4, 1) is not finite");
    EXPECT_EQ(errorOf([&] { bilateralFilter(ao, nanNormal, settings(BlurMode::Separable, 3)); }), "no error");
}

} // namespace obscura::ssao
