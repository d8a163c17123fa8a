// Multi-channel float image: row-major, top row first, channels interleaved per pixel.
#pragma once

#include <cassert>
#include <cstddef>
#include <string>
#include <vector>

namespace obscura {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels; // width * height * channels values
    // Optional channel names, e.g. {"R","G","B"} or {"Z"}; EXR writing uses them when present.
    std::vector<std::string> channelNames;

    Image() = default;
    Image(int w, int h, int c, float fill = 0.0f)
        : width(w), height(h), channels(c), pixels(std::size_t(w) * std::size_t(h) * std::size_t(c), fill) {}

    bool empty() const { return width <= 0 || height <= 0 || channels <= 0; }
    std::size_t pixelCount() const { return std::size_t(width) * std::size_t(height); }
    std::size_t index(int x, int y, int c = 0) const {
        assert(x >= 0 && x < width && y >= 0 && y < height && c >= 0 && c < channels);
        return (std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(channels) + std::size_t(c);
    }
    float& at(int x, int y, int c = 0) { return pixels[index(x, y, c)]; }
    float at(int x, int y, int c = 0) const { return pixels[index(x, y, c)]; }
};

} // namespace obscura
