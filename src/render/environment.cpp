// Equirectangular environment maps: direction <-> (u, v), bilinear lookup, and the built-in procedural
// sky (an artistic gradient, no paper; physical skies such as Preetham et al. 1999 are out of scope).
#include "obscura/error.h"
#include "obscura/render.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

namespace obscura::render {

Vec3 directionFromEquirect(float u, float v) {
    float phi = 2.0f * kPi * (u - 0.5f);
    float theta = kPi * v;
    float s = std::sin(theta);
    // phi = 0 is -Z and phi = pi/2 is +X, so z = -cos(phi), x = +sin(phi).
    return {s * std::sin(phi), std::cos(theta), -s * std::cos(phi)};
}

Vec2 equirectFromDirection(Vec3 dir) {
    // atan2 of the horizontal length rather than acos(y) keeps precision near the poles and accepts
    // directions that are not quite unit.
    float horizontal = std::sqrt(dir.x * dir.x + dir.z * dir.z);
    float theta = std::atan2(horizontal, dir.y);
    // Straight up or down every azimuth is the pole: u = 0.5, rather than atan2(0, +-0), whose answer follows the
    // zeros' signs here and is undefined in GLSL (the GPU pass read another texel of the top row).
    float phi = horizontal > 0.0f ? std::atan2(dir.x, -dir.z) : 0.0f;
    float u = phi / (2.0f * kPi) + 0.5f;
    if (u >= 1.0f) u -= 1.0f; // atan2 returns (-pi, pi]; keep u in [0, 1)
    return {u, theta / kPi};
}

Vec3 sampleEquirect(const Image& env, Vec3 dir) {
    if (env.empty()) return {};
    assert(env.channels >= 3);
    Vec2 uv = equirectFromDirection(dir);
    // Texel centres sit at (i + 0.5) / width: shift by half a texel so weights are distances to centres.
    float fx = uv.x * float(env.width) - 0.5f;
    float fy = uv.y * float(env.height) - 0.5f;
    float x0f = std::floor(fx), y0f = std::floor(fy);
    float tx = fx - x0f, ty = fy - y0f;
    // Azimuth wraps around; the polar angle clamps at the poles (every texel of the top row is the pole).
    auto wrapX = [&](int x) { return ((x % env.width) + env.width) % env.width; };
    auto clampY = [&](int y) { return std::clamp(y, 0, env.height - 1); };
    int x0 = wrapX(int(x0f)), x1 = wrapX(int(x0f) + 1);
    int y0 = clampY(int(y0f)), y1 = clampY(int(y0f) + 1);
    auto texel = [&](int x, int y) { return Vec3{env.at(x, y, 0), env.at(x, y, 1), env.at(x, y, 2)}; };
    Vec3 top = texel(x0, y0) * (1.0f - tx) + texel(x1, y0) * tx;
    Vec3 bottom = texel(x0, y1) * (1.0f - tx) + texel(x1, y1) * tx;
    return top * (1.0f - ty) + bottom * ty;
}

namespace {

float smoothstep(float edge0, float edge1, float x) {
    float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

bool nonNegativeFinite(Vec3 c) { return isFinite(c) && c.x >= 0 && c.y >= 0 && c.z >= 0; }

} // namespace

Image proceduralSky(int width, int height, const SkySettings& settings) {
    if (width < 1 || height < 1)
        fail("sky", "size must be at least 1x1, got " + std::to_string(width) + "x" + std::to_string(height));
    if (!nonNegativeFinite(settings.zenith) || !nonNegativeFinite(settings.horizon) ||
        !nonNegativeFinite(settings.ground))
        fail("sky", "zenith, horizon and ground radiance must be finite and non-negative");
    if (!isFinite(settings.sunDirection) || !std::isfinite(settings.sunIntensity) || settings.sunIntensity < 0)
        fail("sky", "sun direction and intensity must be finite, intensity non-negative");

    const Vec3 sun = normalize(settings.sunDirection);
    // sin(4 degrees): the ground fades in over a few degrees so the horizon has no hard seam to alias.
    const float groundFade = 0.0697565f;
    Image sky(width, height, 3);
    sky.channelNames = {"R", "G", "B"};
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            Vec3 d = directionFromEquirect((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
            // A square root of the elevation sine keeps a bright band near the horizon, as real skies have.
            float up = std::sqrt(std::max(d.y, 0.0f));
            Vec3 c = settings.horizon * (1.0f - up) + settings.zenith * up;
            float g = smoothstep(0.0f, groundFade, -d.y);
            c = c * (1.0f - g) + settings.ground * g;
            // cos^64 lobe: a soft disc about 8 degrees across at half maximum; hidden by the ground.
            float lobe = std::pow(std::max(dot(d, sun), 0.0f), 64.0f);
            c += Vec3(settings.sunIntensity * lobe * (1.0f - g));
            sky.at(x, y, 0) = c.x;
            sky.at(x, y, 1) = c.y;
            sky.at(x, y, 2) = c.z;
        }
    }
    return sky;
}

} // namespace obscura::render
