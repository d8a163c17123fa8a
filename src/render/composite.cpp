// Compositing and display: albedo x SH irradiance / pi x AO per pixel, then exposure, the ACES filmic fit
// of Narkowicz ("ACES Filmic Tone Mapping Curve", 2016) or Reinhard et al. 2002's L/(1+L), and the sRGB
// OETF (IEC 61966-2-1).
#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/render.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace obscura::render {

namespace {

std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

void requireSize(const Image& image, const char* what, int w, int h) {
    if (image.width != w || image.height != h)
        fail(what, "size " + sizeText(image.width, image.height) + " does not match the G-buffer's " + sizeText(w, h));
}

void setRgb(Image& image, int x, int y, Vec3 c) {
    image.at(x, y, 0) = c.x;
    image.at(x, y, 1) = c.y;
    image.at(x, y, 2) = c.z;
}

// Clamps through fmin/fmax so a NaN becomes 0 instead of travelling on to the PNG.
float saturate(float v) { return std::fmin(std::fmax(v, 0.0f), 1.0f); }

float aces(float x) {
    // Narkowicz's fit is pre-exposed so that 1 maps to about 0.8; its asymptote 2.51/2.43 is above 1,
    // so it reaches 1 (and saturates) at x ~ 7.2.
    return saturate((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f));
}

float srgbOetf(float v) {
    // In double so that 1 maps to exactly 1 (in float 1.055f - 0.055f is one ulp short of white).
    return v <= 0.0031308f ? 12.92f * v : float(1.055 * std::pow(double(v), 1.0 / 2.4) - 0.055);
}

} // namespace

void checkShadeInputs(const GBuffer& gbuffer, const Image& ao, const Image& environment) {
    const int w = gbuffer.width(), h = gbuffer.height();
    requireSize(gbuffer.depth, "G-buffer depth", w, h);
    requireSize(gbuffer.normal, "G-buffer normal", w, h);
    requireSize(gbuffer.albedo, "G-buffer albedo", w, h);
    if (gbuffer.depth.channels < 1 || gbuffer.normal.channels < 3 || gbuffer.albedo.channels < 3)
        fail("G-buffer", "needs 1 depth, 3 normal and 3 albedo channels");
    if (!ao.empty()) {
        requireSize(ao, "ao", w, h);
        if (ao.channels != 1) fail("ao", "needs 1 channel, got " + std::to_string(ao.channels));
    }
    if (!environment.empty() && environment.channels < 3)
        fail("environment", "needs at least 3 channels (RGB), got " + std::to_string(environment.channels));
}

Frame shade(const GBuffer& gbuffer, const SH9& sh, const Image& ao, const Image& environment) {
    checkShadeInputs(gbuffer, ao, environment);
    const int w = gbuffer.width(), h = gbuffer.height();

    Frame frame{Image(w, h, 3), Image(w, h, 3)};
    frame.color.channelNames = {"R", "G", "B"};
    frame.lighting.channelNames = {"R", "G", "B"};
    const Mat4 worldFromView = gbuffer.camera.worldFromView();
    const float invPi = 1.0f / kPi;

    parallelFor(std::size_t(h), [&](std::size_t begin, std::size_t end) {
        for (int y = int(begin); y < int(end); ++y) {
            for (int x = 0; x < w; ++x) {
                if (gbuffer.isSky(x, y)) {
                    Vec3 view = gbuffer.camera.viewRayDirection(float(x) + 0.5f, float(y) + 0.5f);
                    setRgb(frame.color, x, y, sampleEquirect(environment, normalize(transformVector(worldFromView, view))));
                    continue; // lighting stays 0: there is no surface to light
                }
                Vec3 n = normalize(transformVector(worldFromView, gbuffer.viewNormal(x, y)));
                Vec3 lighting = irradiance(sh, n) * invPi;
                Vec3 albedo{gbuffer.albedo.at(x, y, 0), gbuffer.albedo.at(x, y, 1), gbuffer.albedo.at(x, y, 2)};
                float occlusion = ao.empty() ? 1.0f : ao.at(x, y);
                setRgb(frame.lighting, x, y, lighting);
                setRgb(frame.color, x, y, albedo * lighting * occlusion);
            }
        }
    });
    return frame;
}

Image toDisplay(const Image& linear, const ShadeSettings& settings) {
    if (!std::isfinite(settings.exposure) || settings.exposure < -20.0f || settings.exposure > 20.0f)
        fail("exposure", "must be in [-20, 20] EV, got " + numberText(settings.exposure));
    if (!linear.empty() && linear.channels != 1 && linear.channels < 3)
        fail("image", "needs 1 (grey) or at least 3 (RGB) channels to display, got " + std::to_string(linear.channels));

    Image out(std::max(linear.width, 0), std::max(linear.height, 0), 3);
    out.channelNames = {"R", "G", "B"};
    if (linear.empty()) return out;
    const float scale = std::exp2(settings.exposure);
    const bool grey = linear.channels == 1;
    parallelFor(std::size_t(linear.height), [&](std::size_t begin, std::size_t end) {
        for (int y = int(begin); y < int(end); ++y) {
            for (int x = 0; x < linear.width; ++x) {
                for (int c = 0; c < 3; ++c) {
                    // Negative radiance would send ACES below zero; the upper bound keeps ACES's x^2 finite
                    // so +inf shows white rather than inf/inf = NaN (black).
                    float v = std::fmin(std::fmax(linear.at(x, y, grey ? 0 : c) * scale, 0.0f), 1e18f);
                    switch (settings.tonemap) {
                    case Tonemap::Aces: v = aces(v); break;
                    case Tonemap::Reinhard: v = v / (1.0f + v); break;
                    case Tonemap::None: break;
                    }
                    out.at(x, y, c) = saturate(srgbOetf(saturate(v)));
                }
            }
        }
    });
    return out;
}

} // namespace obscura::render
