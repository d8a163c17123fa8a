// G-buffer consistency checks at the boundary (files and user buffers).
#include "obscura/gbuffer.h"

#include "obscura/error.h"
#include "obscura/parallel.h"

#include <atomic>
#include <cmath>
#include <string>

namespace obscura {

namespace {
void checkImage(const Image& image, const Camera& camera, int channels, const std::string& what,
                const char* name) {
    if (image.width != camera.width || image.height != camera.height)
        fail(what, std::string(name) + " is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                       " but the camera is " + std::to_string(camera.width) + "x" + std::to_string(camera.height));
    if (image.channels != channels)
        fail(what, std::string(name) + " has " + std::to_string(image.channels) + " channels, expected " +
                       std::to_string(channels));
}
} // namespace

void GBuffer::validateShape(const std::string& what) const {
    if (camera.width < 1 || camera.height < 1) fail(what, "G-buffer has zero size");
    validateDepthNormalShape(what);
    if (!albedo.empty()) checkImage(albedo, camera, 3, what, "albedo");
    if (!motion.empty()) checkImage(motion, camera, 2, what, "motion");
}

void GBuffer::validateDepthNormalShape(const std::string& what) const {
    checkImage(depth, camera, 1, what, "depth");
    checkImage(normal, camera, 3, what, "normal");
}

bool GBuffer::pixelsValid(int x0, int x1, int y0, int y1) const {
    const float* dp = depth.pixels.data();
    const float* n = normal.pixels.data();
    bool bad = false;
    for (int y = y0; y < y1; ++y) {
        const std::size_t row = std::size_t(y) * std::size_t(camera.width);
        for (std::size_t i = row + std::size_t(x0); i < row + std::size_t(x1); ++i) bad |= !pixelValid(dp[i], &n[3 * i]);
    }
    return !bad;
}

void GBuffer::validate(const std::string& what) const {
    validateShape(what);
    validatePixels(what);
}

void GBuffer::validatePixels(const std::string& what) const {
    // Every frame of a screen-space pass validates its G-buffer, so the scan is branch-free and rows run in
    // parallel; only a bad buffer takes the per-pixel loop below, which names the first bad pixel.
    std::atomic<bool> bad{false};
    parallelFor(std::size_t(camera.height), [&](std::size_t y0, std::size_t y1) {
        if (!pixelsValid(0, camera.width, int(y0), int(y1))) bad.store(true, std::memory_order_relaxed);
    }, 16);
    if (!bad.load()) return;
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            float d = depth.at(x, y);
            if (std::isnan(d) || d <= 0.0f || d == -INFINITY)
                fail(what, "depth at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                               ") is " + numberText(d) + " (must be positive or +inf)");
            if (!isFinite(viewNormal(x, y)))
                fail(what, "normal at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is not finite");
        }
}

} // namespace obscura
