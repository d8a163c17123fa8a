// The depth MIP chain of GtaoSampling::Mip (obscura/gtao_mips.h, src/ssao/gtao_mips.cpp): its layout, the
// claim its sampling rests on (a plane's texels lie on the plane at every level, at odd sizes too), its sky
// rule, the level choice, and that with no coarse level Mip is Nearest and PlanarMip is Planar bit for bit.
#include "obscura/builtin_scenes.h"
#include "obscura/error.h"
#include "obscura/gtao.h"
#include "obscura/trace.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace obscura;
using namespace obscura::ssao;

TEST(GtaoMips, LevelSizesAndOffsets) {
    EXPECT_EQ(gtaoMipSize(333, 0), 333);
    EXPECT_EQ(gtaoMipSize(333, 1), 167);
    EXPECT_EQ(gtaoMipSize(333, 2), 84);
    EXPECT_EQ(gtaoMipSize(333, 3), 42);
    EXPECT_EQ(gtaoMipSize(333, 4), 21);
    EXPECT_EQ(gtaoMipSize(1, 4), 1);
    EXPECT_EQ(gtaoMipSize(16, 4), 1);
    EXPECT_EQ(gtaoMipSize(17, 4), 2);
    EXPECT_EQ(gtaoMipOffset(333, 197, 1), 0);
    EXPECT_EQ(gtaoMipOffset(333, 197, 2), 167 * 99);
    EXPECT_EQ(gtaoMipOffset(333, 197, 5), 167 * 99 + 84 * 50 + 42 * 25 + 21 * 13);
    Image depth(333, 197, 1, 2.0f);
    EXPECT_EQ(buildGtaoDepthMips(depth, 4).texels.size(), std::size_t(gtaoMipOffset(333, 197, 5)));
    EXPECT_TRUE(buildGtaoDepthMips(depth, 0).texels.empty());
}

// Inverse depth affine in the image (a plane seen in perspective): every texel of every level holds the
// plane's inverse depth at gtaoMipCentre, the partial last texels of odd sizes included. Computed
// independently here from the affine function; float rounding of four means is the only difference.
TEST(GtaoMips, TexelsOfAPlaneLieOnThePlaneAtTheirCentres) {
    const auto w = [](float x, float y) { return 0.25f + 0.004f * x - 0.0015f * y; };  // in (0.01, 1.6) below
    for (auto [width, height] : {std::pair{37, 23}, std::pair{64, 32}, std::pair{1, 9}, std::pair{33, 1}}) {
        Image depth(width, height, 1);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) depth.at(x, y) = 1.0f / w(float(x) + 0.5f, float(y) + 0.5f);
        const GtaoDepthMips m = buildGtaoDepthMips(depth, GTAO_MAX_MIP_LEVELS);
        double worst = 0.0;
        for (int level = 1; level <= GTAO_MAX_MIP_LEVELS; ++level)
            for (int y = 0; y < gtaoMipSize(height, level); ++y)
                for (int x = 0; x < gtaoMipSize(width, level); ++x) {
                    const float expected =
                        w(gtaoMipCentre(x, level, width), gtaoMipCentre(y, level, height));
                    worst = std::max(worst, std::fabs(double(m.at(level, x, y)) / double(expected) - 1.0));
                }
        EXPECT_LT(worst, 2e-6) << width << "x" << height;
    }
    // The last texel of level 2 over 7 pixels: children at 5 (pixels 4-5) and 6.5 (pixel 6, duplicated).
    EXPECT_FLOAT_EQ(gtaoMipCentre(1, 2, 7), 5.75f);
    EXPECT_FLOAT_EQ(gtaoMipCentre(3, 1, 7), 6.5f);
    EXPECT_FLOAT_EQ(gtaoMipCentre(2, 3, 40), 20.0f);
}

TEST(GtaoMips, AnySkyMakesSkyAndTheRestIsTheMean) {
    const float inf = std::numeric_limits<float>::infinity();
    Image depth(4, 2, 1, 2.0f);
    depth.at(3, 1) = inf;  // one sky pixel in the right 2x2
    depth.at(0, 0) = 4.0f;
    const GtaoDepthMips m = buildGtaoDepthMips(depth, 2);
    EXPECT_FLOAT_EQ(m.at(1, 0, 0), (0.25f + 0.5f + 0.5f + 0.5f) / 4.0f);
    EXPECT_EQ(m.at(1, 1, 0), 0.0f);
    EXPECT_EQ(m.at(2, 0, 0), 0.0f);  // sky carries up
    EXPECT_EQ(gtaoMipFilter(1e-3f, 1.0f, 1.0f, 1.0f), (1e-3f + 1.0f + 1.0f + 1.0f) * 0.25f);
}

TEST(GtaoMips, LevelGrowsWithTheSampleDistance) {
    const float scale = 1.0f / 7.0f;
    EXPECT_EQ(gtaoMipLevel(13.9f, scale, 4), 0);
    EXPECT_EQ(gtaoMipLevel(14.0f, scale, 4), 1);
    EXPECT_EQ(gtaoMipLevel(28.0f, scale, 4), 2);
    EXPECT_EQ(gtaoMipLevel(56.0f, scale, 4), 3);
    EXPECT_EQ(gtaoMipLevel(112.0f, scale, 4), 4);
    EXPECT_EQ(gtaoMipLevel(5000.0f, scale, 4), 4);
    EXPECT_EQ(gtaoMipLevel(5000.0f, scale, 2), 2);
    EXPECT_EQ(gtaoMipLevel(5000.0f, scale, 0), 0);
}

TEST(GtaoMips, WithoutCoarseLevelsTheChainModesAreTheirNearSampling) {
    BuiltinScene s = makeBuiltinScene("demo");
    s.camera.width = 97;
    s.camera.height = 61;
    trace::Tracer tracer(s.scene);
    const GBuffer g = trace::renderGBuffer(tracer, s.camera);
    for (auto [near, chain] : {std::pair{GtaoSampling::Nearest, GtaoSampling::Mip},
                               std::pair{GtaoSampling::Planar, GtaoSampling::PlanarMip}}) {
        GtaoSettings a, b;
        a.sampling = near;
        b.sampling = chain;
        b.depthMipLevels = 0;
        const GtaoResult ra = computeGtao(g, a), rb = computeGtao(g, b);
        EXPECT_EQ(ra.visibility.pixels, rb.visibility.pixels);
        EXPECT_EQ(ra.bentNormal.pixels, rb.bentNormal.pixels);
    }
    GtaoSettings nearest;
    nearest.sampling = GtaoSampling::Nearest;
    const GtaoResult a = computeGtao(g, nearest);
    GtaoSettings mip;
    mip.sampling = GtaoSampling::Mip;
    // With the levels the result differs (the chain is read), and stays close on this view.
    mip.depthMipLevels = 4;
    mip.mipDistanceRatio = 2.0f;
    const GtaoResult c = computeGtao(g, mip);
    double mean = 0.0;
    for (std::size_t i = 0; i < a.visibility.pixels.size(); ++i)
        mean += std::fabs(double(a.visibility.pixels[i]) - double(c.visibility.pixels[i]));
    mean /= double(a.visibility.pixels.size());
    EXPECT_GT(mean, 1e-4);
    EXPECT_LT(mean, 0.02);
}

TEST(GtaoMips, SettingsAndConstantsAreChecked) {
    GtaoSettings s;
    s.sampling = GtaoSampling::Mip;
    s.depthMipLevels = 5;
    EXPECT_THROW(s.validate(), Error);
    s.depthMipLevels = 4;
    s.mipDistanceRatio = 1.0f;
    EXPECT_THROW(s.validate(), Error);
    s.mipDistanceRatio = 7.0f;
    EXPECT_NO_THROW(s.validate());

    Camera camera;
    camera.width = 8;
    camera.height = 6;
    GBuffer g;
    g.camera = camera;
    g.depth = Image(8, 6, 1, 2.0f);
    g.normal = Image(8, 6, 3, 0.0f);
    GtaoConstants k = gtaoConstants(s, camera);
    EXPECT_EQ(k.sampling, GTAO_SAMPLING_MIP);
    EXPECT_EQ(k.mipLevels, 4);
    EXPECT_FLOAT_EQ(k.mipTexelScale, 1.0f / 7.0f);
    EXPECT_THROW(gtaoPixel(k, g, 1, 1), Error);  // the kernel without its chain
    k.mipLevels = 9;
    EXPECT_THROW(computeGtao(g, k), Error);
    // Planar and nearest constants read no chain.
    s.sampling = GtaoSampling::Nearest;
    EXPECT_EQ(gtaoConstants(s, camera).mipLevels, 0);
    // How reports name each sampling.
    EXPECT_EQ(gtaoSamplingText(s), "nearest-pixel samples");
    s.sampling = GtaoSampling::PlanarMip;
    s.mipDistanceRatio = 3.5f;
    EXPECT_EQ(gtaoSamplingText(s), "planar + depth MIP samples (5 levels, ratio 3.5)");
    EXPECT_EQ(gtaoConstants(s, camera).sampling, GTAO_SAMPLING_PLANAR_MIP);
    s.sampling = GtaoSampling::Planar;
    EXPECT_EQ(gtaoSamplingText(s), "");
}
