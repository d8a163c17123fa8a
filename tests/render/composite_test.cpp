// Tests for shade (albedo x E/pi x AO, sky behind) and toDisplay (exposure, ACES fit of Narkowicz 2016,
// Reinhard, sRGB OETF) on hand-made G-buffers and single values with closed-form answers.
#include "obscura/error.h"
#include "obscura/render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace obscura::render {
namespace {

const Vec3 kRho{0.2f, 0.5f, 0.9f};

// A w x h G-buffer of one surface at depth 2 with the given view normal and albedo rho.
GBuffer surfaceGBuffer(int w, int h, Vec3 viewNormal = {0, 0, 1}) {
    GBuffer g;
    g.camera.width = w;
    g.camera.height = h;
    g.depth = Image(w, h, 1, 2.0f);
    g.normal = Image(w, h, 3);
    g.albedo = Image(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                g.normal.at(x, y, c) = viewNormal[c];
                g.albedo.at(x, y, c) = kRho[c];
            }
    return g;
}

void makeSky(GBuffer& g, int x, int y) {
    g.depth.at(x, y) = INFINITY;
    for (int c = 0; c < 3; ++c) g.normal.at(x, y, c) = g.albedo.at(x, y, c) = 0.0f;
}

Vec3 rgb(const Image& img, int x, int y) { return {img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)}; }

void expectRgb(Vec3 actual, Vec3 expected, float tolerance, const std::string& what) {
    EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
    EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
    EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

// Radiance top above the horizon (world +Y), bottom below; 64 x 32 puts the horizon on a row edge.
Image twoToneSky(float top, float bottom) {
    Image env(64, 32, 3);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) env.at(x, y, c) = y < 16 ? top : bottom;
    return env;
}

// ---- shade -----------------------------------------------------------------------------------------

// Acceptance: a white sky of radiance L and a plane of albedo rho with no AO render to rho * L before
// tonemapping, whatever the normal: E = pi L, lighting = E / pi = L. Normals are arbitrary on purpose.
TEST(CompositeShade, WhiteSkyRendersAlbedoTimesRadiance) {
    for (float L : {1.0f, 3.0f}) {
        Image env(64, 32, 3, L);
        SH9 sh = projectEnvironment(env);
        for (Vec3 n : {Vec3{0, 0, 1}, normalize(Vec3{0.3f, -0.8f, 0.5f}), Vec3{0, -1, 0}}) {
            Frame f = shade(surfaceGBuffer(4, 3, n), sh, Image(), env);
            ASSERT_EQ(f.color.width, 4);
            ASSERT_EQ(f.color.height, 3);
            ASSERT_EQ(f.color.channels, 3);
            for (int y = 0; y < 3; ++y)
                for (int x = 0; x < 4; ++x) {
                    expectRgb(rgb(f.color, x, y), kRho * L, 1e-4f * L, "color = rho L");
                    expectRgb(rgb(f.lighting, x, y), Vec3(L), 1e-4f * L, "lighting = L");
                }
        }
    }
}

TEST(CompositeShade, AoMultipliesAllLighting) {
    Image env(64, 32, 3, 1.0f);
    SH9 sh = projectEnvironment(env);
    Frame f = shade(surfaceGBuffer(4, 3), sh, Image(4, 3, 1, 0.25f), env);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            expectRgb(rgb(f.color, x, y), kRho * 0.25f, 1e-4f, "color = 0.25 rho");
            expectRgb(rgb(f.lighting, x, y), Vec3(1.0f), 1e-4f, "lighting is unoccluded");
        }
}

TEST(CompositeShade, SkyPixelsShowTheEnvironment) {
    GBuffer g = surfaceGBuffer(4, 3);
    makeSky(g, 1, 1);
    Image white(64, 32, 3, 1.0f);
    Frame f = shade(g, projectEnvironment(white), Image(4, 3, 1, 0.5f), white);
    expectRgb(rgb(f.color, 1, 1), Vec3(1.0f), 1e-6f, "sky = environment, AO does not apply");
    expectRgb(rgb(f.lighting, 1, 1), Vec3(0.0f), 0.0f, "sky lighting = 0");
    expectRgb(rgb(f.color, 0, 0), kRho * 0.5f, 1e-4f, "surface next to it");

    // Empty environment: black behind geometry.
    f = shade(g, projectEnvironment(white), Image(), Image());
    expectRgb(rgb(f.color, 1, 1), Vec3(0.0f), 0.0f, "no environment = black");
}

// The view ray goes to world space: a level camera (60 degree fov, 4x3) sees 21 degrees above the horizon
// through its top row's centres and 21 below through its bottom row's, far from the 5.6 degree texels
// at the horizon, so each samples one tone of the two-tone sky only.
TEST(CompositeShade, SkyDirectionIsInWorldSpace) {
    GBuffer g = surfaceGBuffer(4, 3);
    g.camera.position = {0, 0, 0};
    g.camera.target = {0, 0, -1};
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) makeSky(g, x, y);
    Image env = twoToneSky(5.0f, 1.0f);
    Frame f = shade(g, SH9{}, Image(), env);
    for (int x = 0; x < 4; ++x) {
        expectRgb(rgb(f.color, x, 0), Vec3(5.0f), 1e-5f, "top row sees the sky");
        expectRgb(rgb(f.color, x, 2), Vec3(1.0f), 1e-5f, "bottom row sees the ground");
    }
    // Tilt the camera to look straight down: every pixel is within 37 degrees of -Y, all ground.
    g.camera.position = {0, 5, 0};
    g.camera.target = {0, 0, 0};
    g.camera.up = {0, 0, -1};
    f = shade(g, SH9{}, Image(), env);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) expectRgb(rgb(f.color, x, y), Vec3(1.0f), 1e-5f, "looking down");
}

// Normals go to world space: under a sky of L above the horizon and 0 below, E(n) = pi L (1 + n.y) / 2
// (derived in sh_test.cpp), so lighting = L (1 + n_world.y) / 2.
TEST(CompositeShade, NormalsAreLitInWorldSpace) {
    const float L = 2.0f;
    SH9 sh = projectEnvironment(twoToneSky(L, 0.0f));
    // Camera looking straight down: the view normal facing it, +Z, is world +Y: fully lit.
    GBuffer g = surfaceGBuffer(4, 3, {0, 0, 1});
    g.camera.position = {0, 5, 0};
    g.camera.target = {0, 0, 0};
    g.camera.up = {0, 0, -1};
    Frame f = shade(g, sh, Image(), Image());
    expectRgb(rgb(f.lighting, 2, 1), Vec3(L), 1e-3f * L, "floor seen from above");
    // Same camera, view normal +Y (world -Z, horizontal): half lit.
    g = surfaceGBuffer(4, 3, {0, 1, 0});
    g.camera.position = {0, 5, 0};
    g.camera.target = {0, 0, 0};
    g.camera.up = {0, 0, -1};
    f = shade(g, sh, Image(), Image());
    expectRgb(rgb(f.lighting, 2, 1), Vec3(0.5f * L), 1e-3f * L, "wall");
    // A level camera: view normal -Y is world -Y, a ceiling: unlit. A non-unit normal is normalised.
    g = surfaceGBuffer(4, 3, {0, -3, 0});
    g.camera.position = {0, 0, 0};
    g.camera.target = {0, 0, -1};
    f = shade(g, sh, Image(), Image());
    expectRgb(rgb(f.lighting, 0, 0), Vec3(0.0f), 1e-3f * L, "ceiling");
    expectRgb(rgb(f.color, 0, 0), Vec3(0.0f), 1e-3f * L, "ceiling colour");
}

TEST(CompositeShade, MismatchedAoSizeThrows) {
    Image env(64, 32, 3, 1.0f);
    SH9 sh = projectEnvironment(env);
    try {
        shade(surfaceGBuffer(4, 3), sh, Image(5, 3, 1, 1.0f), env);
        FAIL() << "a 5x3 AO was accepted for a 4x3 G-buffer";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "ao: size 5x3 does not match the G-buffer's 4x3");
    }
    EXPECT_THROW(shade(surfaceGBuffer(4, 3), sh, Image(4, 2, 1, 1.0f), env), Error);
    EXPECT_THROW(shade(surfaceGBuffer(4, 3), sh, Image(4, 3, 3, 1.0f), env), Error); // AO is 1 channel
    EXPECT_THROW(shade(surfaceGBuffer(4, 3), sh, Image(), Image(8, 4, 1, 1.0f)), Error); // env needs RGB
}

// ---- toDisplay -------------------------------------------------------------------------------------

// The sRGB OETF written out independently, in double.
double srgb(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }
double srgbInverse(double e) { return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4); }

// Displays one grey value and returns the red channel (checking the others agree).
float display(float linear, Tonemap tonemap, float exposure = 0.0f) {
    Image img(1, 1, 3, linear);
    Image out = toDisplay(img, {exposure, tonemap});
    EXPECT_EQ(out.channels, 3);
    EXPECT_EQ(out.at(0, 0, 0), out.at(0, 0, 1));
    EXPECT_EQ(out.at(0, 0, 0), out.at(0, 0, 2));
    return out.at(0, 0, 0);
}

TEST(CompositeDisplay, NoneIsClampThenSrgb) {
    EXPECT_NEAR(display(0.5f, Tonemap::None), 0.735357, 1e-5);
    EXPECT_NEAR(display(0.002f, Tonemap::None), 12.92 * 0.002, 1e-6); // linear toe
    EXPECT_EQ(display(0.0f, Tonemap::None), 0.0f);
    EXPECT_NEAR(display(1.0f, Tonemap::None), 1.0, 1e-6);
    EXPECT_NEAR(display(7.0f, Tonemap::None), 1.0, 1e-6);
    EXPECT_EQ(display(-1.0f, Tonemap::None), 0.0f);
    EXPECT_EQ(display(std::nanf(""), Tonemap::None), 0.0f);
}

TEST(CompositeDisplay, ExposureScalesByPowerOfTwo) {
    const float v = 0.05f; // small enough that 2^2 v stays below the clamp
    for (float ev : {1.0f, 2.0f, -1.0f}) {
        double base = srgbInverse(display(v, Tonemap::None, 0.0f));
        double exposed = srgbInverse(display(v, Tonemap::None, ev));
        EXPECT_NEAR(exposed / base, std::exp2(double(ev)), 1e-4) << "EV " << ev;
        EXPECT_NEAR(display(v, Tonemap::None, ev), srgb(double(v) * std::exp2(double(ev))), 1e-5) << "EV " << ev;
    }
    EXPECT_THROW(toDisplay(Image(1, 1, 3), {21.0f, Tonemap::None}), Error);
    EXPECT_THROW(toDisplay(Image(1, 1, 3), {NAN, Tonemap::None}), Error);
}

// Narkowicz's fit x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14), saturated. Its asymptote 2.51/2.43 is above
// 1: it crosses 1 at x = (0.56 + sqrt(0.56^2 + 4 * 0.08 * 0.14)) / 0.16 = 7.24 and saturates from there.
TEST(CompositeDisplay, AcesShape) {
    EXPECT_EQ(display(0.0f, Tonemap::Aces), 0.0f);
    EXPECT_NEAR(display(1.0f, Tonemap::Aces), srgb(2.54 / 3.16), 1e-5); // 1 maps to ~0.8 before the OETF
    float previous = 0.0f;
    for (float x = 0.01f; x < 7.0f; x *= 1.1f) {
        float d = display(x, Tonemap::Aces);
        EXPECT_GT(d, previous) << "strictly increasing below the saturation point, x = " << x;
        EXPECT_LT(d, 1.0f) << x;
        previous = d;
    }
    for (float x : {8.0f, 100.0f, 1e6f, INFINITY}) EXPECT_EQ(display(x, Tonemap::Aces), 1.0f) << x;
}

TEST(CompositeDisplay, ReinhardPerChannel) {
    EXPECT_NEAR(display(1.0f, Tonemap::Reinhard), srgb(0.5), 1e-5);
    EXPECT_NEAR(display(3.0f, Tonemap::Reinhard), srgb(0.75), 1e-5);
    EXPECT_LT(display(1000.0f, Tonemap::Reinhard), 1.0f);
    Image img(1, 1, 3);
    img.at(0, 0, 0) = 1.0f;
    img.at(0, 0, 1) = 3.0f;
    Image out = toDisplay(img, {0.0f, Tonemap::Reinhard});
    EXPECT_NEAR(out.at(0, 0, 0), srgb(0.5), 1e-5);
    EXPECT_NEAR(out.at(0, 0, 1), srgb(0.75), 1e-5);
    EXPECT_EQ(out.at(0, 0, 2), 0.0f);
}

TEST(CompositeDisplay, OutputIsRgbInUnitRange) {
    Image grey(3, 2, 1, 0.5f); // a 1-channel image (an AO buffer) displays as grey
    Image out = toDisplay(grey, {});
    ASSERT_EQ(out.channels, 3);
    ASSERT_EQ(out.width, 3);
    for (float v : out.pixels) EXPECT_NEAR(v, out.pixels[0], 0.0f);
    Image wild(2, 2, 4);
    const float values[] = {-5.0f, 0.0f, 0.3f, 1e30f, INFINITY, NAN, 2.0f, 1e-8f};
    for (std::size_t i = 0; i < wild.pixels.size(); ++i) wild.pixels[i] = values[i % 8];
    for (Tonemap t : {Tonemap::Aces, Tonemap::Reinhard, Tonemap::None}) {
        out = toDisplay(wild, {3.0f, t});
        ASSERT_EQ(out.channels, 3);
        for (float v : out.pixels) {
            EXPECT_GE(v, 0.0f);
            EXPECT_LE(v, 1.0f);
        }
    }
    EXPECT_THROW(toDisplay(Image(1, 1, 2), {}), Error);
}

} // namespace
} // namespace obscura::render
