// Tests for the equirect mapping, SH projection and irradiance (Ramamoorthi and Hanrahan 2001) and the
// procedural sky, against closed forms derived in the comments.
#include "obscura/error.h"
#include "obscura/image_io.h"
#include "obscura/render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace obscura::render {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Evenly spread unit vectors (the Fibonacci sphere): no clustering, deterministic.
std::vector<Vec3> fibonacciSphere(int count) {
    std::vector<Vec3> dirs;
    const double golden = kPiD * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        double y = 1.0 - 2.0 * (i + 0.5) / count;
        double r = std::sqrt(1.0 - y * y);
        double phi = golden * i;
        dirs.push_back({float(r * std::cos(phi)), float(y), float(r * std::sin(phi))});
    }
    return dirs;
}

Image constantImage(int w, int h, Vec3 c) {
    Image img(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[k];
    return img;
}

void expectRelative(double actual, double expected, double tolerance, const char* what) {
    EXPECT_NEAR(actual, expected, tolerance * std::fabs(expected)) << what;
}

// ---- equirect mapping ------------------------------------------------------------------------------

TEST(ShEquirect, DocumentedConvention) {
    auto expectDir = [](Vec3 d, Vec3 e) {
        EXPECT_NEAR(d.x, e.x, 1e-6f);
        EXPECT_NEAR(d.y, e.y, 1e-6f);
        EXPECT_NEAR(d.z, e.z, 1e-6f);
    };
    expectDir(directionFromEquirect(0.5f, 0.5f), {0, 0, -1});  // centre looks down -Z
    expectDir(directionFromEquirect(0.3f, 0.0f), {0, 1, 0});   // top row is +Y whatever u
    expectDir(directionFromEquirect(0.3f, 1.0f), {0, -1, 0});  // bottom row is -Y
    expectDir(directionFromEquirect(0.75f, 0.5f), {1, 0, 0});  // azimuth turns from -Z towards +X
    expectDir(directionFromEquirect(0.25f, 0.5f), {-1, 0, 0});
    expectDir(directionFromEquirect(0.0f, 0.5f), {0, 0, 1});   // the seam is behind, at +Z
    Vec2 uv = equirectFromDirection({0, 0, -1});
    EXPECT_NEAR(uv.x, 0.5f, 1e-6f);
    EXPECT_NEAR(uv.y, 0.5f, 1e-6f);
    uv = equirectFromDirection({0, 0, 1});
    EXPECT_GE(uv.x, 0.0f); // u stays in [0, 1) on the seam
    EXPECT_LT(uv.x, 1.0f);
    // Straight up or down, whatever the zeros' signs (atan2(0, -0) is pi, atan2(0, 0) is 0): u = 0.5.
    for (float x : {0.0f, -0.0f})
        for (float z : {0.0f, -0.0f})
            for (float y : {1.0f, -1.0f}) {
                uv = equirectFromDirection({x, y, z});
                EXPECT_EQ(uv.x, 0.5f) << x << " " << y << " " << z;
                EXPECT_EQ(uv.y, y > 0.0f ? 0.0f : 1.0f);
            }
}

TEST(ShEquirect, RoundTripWithin1e5) {
    std::vector<Vec3> dirs = fibonacciSphere(2000);
    // The poles and the seam are where an atan2 mapping goes wrong if it does.
    dirs.insert(dirs.end(), {{0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0},
                             {1e-4f, 0, 1}, {-1e-4f, 0, 1}});
    for (Vec3 d : dirs) {
        d = normalize(d);
        Vec2 uv = equirectFromDirection(d);
        ASSERT_GE(uv.x, 0.0f);
        ASSERT_LT(uv.x, 1.0f);
        ASSERT_GE(uv.y, 0.0f);
        ASSERT_LE(uv.y, 1.0f);
        Vec3 back = directionFromEquirect(uv.x, uv.y);
        EXPECT_NEAR(back.x, d.x, 1e-5f);
        EXPECT_NEAR(back.y, d.y, 1e-5f);
        EXPECT_NEAR(back.z, d.z, 1e-5f);
    }
}

TEST(ShEquirect, BilinearLookupHitsTexelCentresAndWraps) {
    Image env(4, 2, 3);
    for (int x = 0; x < 4; ++x)
        for (int y = 0; y < 2; ++y)
            for (int c = 0; c < 3; ++c) env.at(x, y, c) = float(10 * y + x + c);
    // Centre of texel (2, 0): exactly that texel.
    Vec3 v = sampleEquirect(env, directionFromEquirect(2.5f / 4.0f, 0.25f));
    EXPECT_NEAR(v.x, 2.0f, 1e-5f);
    EXPECT_NEAR(v.z, 4.0f, 1e-5f);
    // Half-way between the centres of columns 3 and 0 across the seam (u = 0): their mean.
    v = sampleEquirect(env, directionFromEquirect(0.0f, 0.25f));
    EXPECT_NEAR(v.x, 1.5f, 1e-5f);
    // On the equator, half-way between the rows: the mean of rows 0 and 1.
    v = sampleEquirect(env, directionFromEquirect(1.5f / 4.0f, 0.5f));
    EXPECT_NEAR(v.x, 6.0f, 1e-5f);
    // Above the top row's centres the pole clamps to the top row (values x + c, no 10s from row 1).
    v = sampleEquirect(env, {0, 1, 0});
    EXPECT_NEAR(v.y, v.x + 1.0f, 1e-5f);
    EXPECT_GE(v.x, 0.0f);
    EXPECT_LE(v.x, 3.0f);
    EXPECT_EQ(sampleEquirect(Image(), {0, 1, 0}), Vec3(0.0f));
}

// ---- projection and irradiance ---------------------------------------------------------------------

// A constant radiance L projects onto Y00 only: L00 = L * Y00 * 4 pi = L * sqrt(4 pi) (Y00 = 1/sqrt(4 pi)),
// and E(n) = A0 * L00 * Y00 = pi * L for every n.
void checkConstantEnvironment(int w, int h) {
    const Vec3 L{0.7f, 1.3f, 2.0f};
    SH9 sh = projectEnvironment(constantImage(w, h, L));
    const double sqrt4Pi = std::sqrt(4.0 * kPiD);
    for (int c = 0; c < 3; ++c) {
        const double Lc = L[c];
        expectRelative(sh.coefficients[0][c], Lc * sqrt4Pi, 1e-5, "L00");
        for (int k = 1; k < 9; ++k) EXPECT_NEAR(sh.coefficients[std::size_t(k)][c], 0.0, 1e-5 * Lc) << "L_" << k;
    }
    for (Vec3 n : fibonacciSphere(200)) {
        Vec3 e = irradiance(sh, n);
        for (int c = 0; c < 3; ++c) expectRelative(e[c], kPiD * double(L[c]), 1e-4, "E = pi L");
    }
}

TEST(ShProjection, ConstantEnvironment64x32) { checkConstantEnvironment(64, 32); }
TEST(ShProjection, ConstantEnvironment256x128) { checkConstantEnvironment(256, 128); }

// Radiance L on the half-sphere dot(d, axis) > 0, 0 on the other half; the grid's row/column boundaries
// fall exactly on the dividing great circle for the sizes used, so the texel image is the exact step.
Image stepImage(int w, int h, Vec3 axis, float L) {
    Image img(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Vec3 d = directionFromEquirect((float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h));
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = dot(d, axis) > 0 ? L : 0.0f;
        }
    return img;
}

// Closed form for the +Y step (mu = d.y):
//   L00    = L * Y00 * 2 pi                           = L sqrt(pi)
//   L1,-1  = L * sqrt(3/4pi) * int_{y>0} y dOmega     = L sqrt(3/4pi) * pi = L sqrt(3 pi) / 2
//   every other l <= 2 coefficient is 0: x, z, xy, yz, xz are odd under x -> -x or z -> -z, which keeps
//   the half-sphere; 3z^2 - 1 and x^2 - y^2 integrate to 0 because x^2, y^2 and z^2 each give 2pi/3.
// So E(n) = pi L00 Y00 + (2pi/3) L1,-1 sqrt(3/4pi) n.y = (pi L / 2)(1 + n.y). This is also the exact
// irradiance under a uniform half-sky: the step's l >= 2 even bands vanish (int_0^1 P_l = 0) and its odd
// bands l >= 3 meet A_l = 0, so nine coefficients lose nothing here.
TEST(ShProjection, UpperHemisphereStepMatchesClosedForm) {
    const double L = 1.7;
    for (auto [w, h] : {std::pair{64, 32}, std::pair{256, 128}}) {
        SH9 sh = projectEnvironment(stepImage(w, h, {0, 1, 0}, float(L)));
        const double expected[9] = {L * std::sqrt(kPiD), L * std::sqrt(3.0 * kPiD) / 2.0, 0, 0, 0, 0, 0, 0, 0};
        for (int k = 0; k < 9; ++k) {
            double tolerance = expected[k] != 0 ? 1e-3 * std::fabs(expected[k]) : 1e-5 * L;
            EXPECT_NEAR(sh.coefficients[std::size_t(k)].x, expected[k], tolerance) << "k=" << k << " at " << w;
        }
        Vec3 up = irradiance(sh, {0, 1, 0});
        expectRelative(up.x, kPiD * L, 1e-3, "E(+Y) = pi L");
        Vec3 down = irradiance(sh, {0, -1, 0});
        EXPECT_GE(down.x, 0.0f);
        EXPECT_NEAR(down.x, 0.0, 1e-5 * L);
        for (Vec3 n : fibonacciSphere(200))
            EXPECT_NEAR(irradiance(sh, n).x, 0.5 * kPiD * L * (1.0 + double(n.y)), 1e-3 * kPiD * L);
    }
}

// The same step about each axis and its opposite: exercises the azimuthal integrals and shows the basis's
// axis choice (z polar) does not matter. The seam (u = 0) and u = 0.25, 0.5, 0.75 are column edges for
// widths divisible by 4, so the x and z steps are exact too.
TEST(ShProjection, StepAboutEveryAxisGivesHalfCosineIrradiance) {
    const double L = 2.0;
    for (Vec3 axis : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, -1, 0}, Vec3{0, 0, 1}, Vec3{0, 0, -1}}) {
        SH9 sh = projectEnvironment(stepImage(64, 32, axis, float(L)));
        for (Vec3 n : fibonacciSphere(200))
            EXPECT_NEAR(irradiance(sh, n).x, 0.5 * kPiD * L * (1.0 + double(dot(n, axis))), 1e-4 * kPiD * L)
                << "axis " << axis.x << "," << axis.y << "," << axis.z;
    }
}

TEST(ShProjection, RejectsFewChannelsAndNonFiniteValues) {
    EXPECT_THROW(projectEnvironment(Image(8, 4, 1, 1.0f)), Error);
    EXPECT_THROW(projectEnvironment(Image(8, 4, 2, 1.0f)), Error);
    EXPECT_THROW(projectEnvironment(Image()), Error);
    Image bad = constantImage(8, 4, Vec3(1.0f));
    bad.at(3, 2, 1) = std::nanf("");
    try {
        projectEnvironment(bad);
        FAIL() << "NaN accepted";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("environment: ", 0), 0u) << e.what();
    }
    bad.at(3, 2, 1) = INFINITY;
    EXPECT_THROW(projectEnvironment(bad), Error);
    // Negative radiance is refused too, naming the first such texel in row order.
    bad.at(3, 2, 1) = 1.0f;
    bad.at(5, 3, 2) = -0.5f;
    bad.at(6, 3, 0) = -1.0f;
    try {
        projectEnvironment(bad);
        FAIL() << "negative radiance accepted";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "environment: radiance at pixel (5, 3) is (1, 1, -0.5): must be finite and non-negative");
    }
    bad.at(5, 3, 2) = 0.0f;
    bad.at(6, 3, 0) = 0.0f;
    EXPECT_NO_THROW(projectEnvironment(bad));  // zero is a radiance
    // A fourth channel (alpha) is ignored, not rejected.
    Image rgba(8, 4, 4, 1.0f);
    rgba.at(0, 0, 3) = std::nanf("");
    EXPECT_NO_THROW(projectEnvironment(rgba));
}

// An EXR keeps its channels as B, G, R; a red sky read from one once lit the scene blue.
TEST(ShProjection, RedExrEnvironmentLightsRed) {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("obscura_red_sky_" + std::to_string(getpid()) + ".exr")).string();
    Image red = constantImage(16, 8, Vec3{1.0f, 0.0f, 0.0f});
    red.channelNames = {"R", "G", "B"};
    writeExr(path, red);
    const SH9 sh = projectEnvironment(readImage(path));
    std::filesystem::remove(path);
    // A constant radiance L projects to L * sqrt(4 pi) on the first coefficient.
    EXPECT_NEAR(sh.coefficients[0][0], std::sqrt(4.0f * kPi), 1e-4f);
    EXPECT_EQ(sh.coefficients[0][1], 0.0f);
    EXPECT_EQ(sh.coefficients[0][2], 0.0f);
}

// Negative lobes: a single bright texel rings to negative values opposite; the result is clamped to 0.
TEST(ShProjection, IrradianceClampsNegativeToZero) {
    Image img(64, 32, 3);
    for (int c = 0; c < 3; ++c) img.at(16, 1, c) = 1000.0f;
    SH9 sh = projectEnvironment(img);
    for (Vec3 n : fibonacciSphere(200)) {
        Vec3 e = irradiance(sh, n);
        EXPECT_GE(e.x, 0.0f);
        EXPECT_GE(e.y, 0.0f);
        EXPECT_GE(e.z, 0.0f);
    }
}

// ---- procedural sky --------------------------------------------------------------------------------

TEST(ShSky, ProceduralSkyIsFinitePositiveAndShaped) {
    SkySettings s;
    Image sky = proceduralSky(256, 128, s);
    ASSERT_EQ(sky.width, 256);
    ASSERT_EQ(sky.height, 128);
    ASSERT_EQ(sky.channels, 3);
    for (float v : sky.pixels) {
        ASSERT_TRUE(std::isfinite(v));
        ASSERT_GT(v, 0.0f);
    }
    // Top row: the zenith colour (the sun, 34 degrees off, adds 6 * 0.83^64 < 1e-4).
    Vec3 top{sky.at(10, 0, 0), sky.at(10, 0, 1), sky.at(10, 0, 2)};
    EXPECT_NEAR(top.x, s.zenith.x, 2e-2f);
    EXPECT_NEAR(top.z, s.zenith.z, 2e-2f);
    // Bottom row: the ground colour exactly (the sun lobe is hidden below the horizon).
    Vec3 bottom{sky.at(10, 127, 0), sky.at(10, 127, 1), sky.at(10, 127, 2)};
    EXPECT_NEAR(bottom.x, s.ground.x, 1e-6f);
    EXPECT_NEAR(bottom.z, s.ground.z, 1e-6f);
    // Towards the sun: the sky there plus about sunIntensity.
    Vec3 atSun = sampleEquirect(sky, normalize(s.sunDirection));
    EXPECT_GT(atSun.x, s.sunIntensity);
    // Lit from above: a floor gets more light than a ceiling.
    SH9 sh = projectEnvironment(sky);
    EXPECT_GT(irradiance(sh, {0, 1, 0}).x, irradiance(sh, {0, -1, 0}).x);
}

TEST(ShSky, RejectsBadSettings) {
    EXPECT_THROW(proceduralSky(0, 8), Error);
    SkySettings s;
    s.zenith = {-1, 0, 0};
    EXPECT_THROW(proceduralSky(16, 8, s), Error);
    s = {};
    s.sunIntensity = NAN;
    EXPECT_THROW(proceduralSky(16, 8, s), Error);
}

// Finite radiance whose projection sums past a float (a constant 3e38, below the 1.7e38 a Radiance file holds
// times the map's solid angle) is refused: it gave L00 = inf and an inf frame with exit status 0. 1e36 still
// projects, to E = pi * 1e36 toward +Y (relative 1e-5).
TEST(ShProjection, RefusesRadianceWhoseIrradianceOverflows) {
    EXPECT_THROW(projectEnvironment(Image(16, 8, 3, 3e38f)), Error);
    const Vec3 e = irradiance(projectEnvironment(Image(16, 8, 3, 1e36f)), {0, 1, 0});
    EXPECT_NEAR(double(e.x) / 1e36, kPiD, 1e-5 * kPiD);
}

} // namespace
} // namespace obscura::render
