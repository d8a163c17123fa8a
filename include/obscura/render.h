// Diffuse image-based lighting and compositing: 9-coefficient spherical-harmonic irradiance from an
// equirectangular environment (Ramamoorthi and Hanrahan 2001), a procedural sky, tonemapping.
//
// Pixel = albedo * E(n) / pi * AO, with AO multiplying all of the lighting as the Alchemy IBL chapter does.
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/image.h"
#include "obscura/math.h"

#include <array>

namespace obscura::render {

// Equirectangular convention: world +Y is up; column u in [0,1) is the azimuth phi = 2 pi (u - 0.5)
// measured from -Z towards +X; row v in [0,1) (top first) is the polar angle theta = pi v from +Y.
Vec3 directionFromEquirect(float u, float v);
Vec2 equirectFromDirection(Vec3 dir);
// Bilinear lookup of an RGB equirect image (first three channels) in world direction dir.
Vec3 sampleEquirect(const Image& env, Vec3 dir);

// Radiance SH coefficients L_lm (l <= 2), RGB each, in the order (0,0) (1,-1) (1,0) (1,1) (2,-2) (2,-1)
// (2,0) (2,1) (2,2) of the real basis.
struct SH9 {
    std::array<Vec3, 9> coefficients{};
};

// Projects an equirect radiance map onto SH, integrating each texel's exact solid angle.
// Throws obscura::Error for an image with fewer than 3 channels, a non-finite or negative value, or radiance so
// large that an SH coefficient reaches FLT_MAX/8 (the irradiance could overflow; a constant map above ~1.2e37).
SH9 projectEnvironment(const Image& equirect);
// Irradiance E(n) = sum_l A_l sum_m L_lm Y_lm(n), A_0 = pi, A_1 = 2pi/3, A_2 = pi/4. For a constant
// radiance L it is pi L for every n.
Vec3 irradiance(const SH9& sh, Vec3 n);
// irradiance() as a polynomial: term i (SH9's order) is A_l times the normalisation of Y_lm, so that
// E(n) = max(0, sum_i scale_i L_i m_i(n)) with the bare monomials m = (1, y, z, x, xy, yz, 3z^2 - 1, xz,
// x^2 - y^2) of the unit n. For passes that evaluate it elsewhere (gpu::shade).
std::array<double, 9> irradianceScales();

struct SkySettings {
    Vec3 zenith{0.25f, 0.45f, 0.95f};    // radiance straight up, linear RGB
    Vec3 horizon{1.0f, 0.95f, 0.9f};     // radiance at the horizon
    Vec3 ground{0.3f, 0.27f, 0.24f};     // radiance below the horizon
    Vec3 sunDirection{0.4f, 0.75f, 0.3f};  // towards the sun, world (normalised on use)
    float sunIntensity = 6.0f;           // extra radiance in a soft lobe around the sun
};
// The built-in sky as an equirect radiance image.
Image proceduralSky(int width = 256, int height = 128, const SkySettings& settings = {});

enum class Tonemap { Aces, Reinhard, None };

struct ShadeSettings {
    float exposure = 0.0f;                // EV stops added before tonemapping, [-20, 20]
    Tonemap tonemap = Tonemap::Aces;      // ACES filmic fit (Narkowicz 2016), Reinhard, or clamp
};

struct Frame {
    Image color;      // 3 channels, linear radiance = albedo * lighting * AO; sky pixels show the environment
    Image lighting;   // 3 channels, unoccluded diffuse lighting E(n)/pi for a white surface; sky 0
};

// Shades a G-buffer. `ao` is a 1-channel image of the G-buffer's size, or empty for no occlusion.
// `environment` is the equirect map shown behind geometry (may be empty: black). Throws obscura::Error on
// a size mismatch.
Frame shade(const GBuffer& gbuffer, const SH9& sh, const Image& ao, const Image& environment);
// shade()'s checks and messages, for the passes that composite the same inputs elsewhere (gpu::shade).
void checkShadeInputs(const GBuffer& gbuffer, const Image& ao, const Image& environment);

// Exposure, tonemap and the sRGB transfer function: a 3-channel image in [0,1] ready for writePng.
Image toDisplay(const Image& linear, const ShadeSettings& settings);

} // namespace obscura::render
