// Uploads of obscura::Image planes for the passes in src/gpu: the first `channels` channels of every pixel,
// interleaved, as the shaders' float arrays expect (an image with more channels is repacked on the host).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"

#include "obscura/image.h"

#include <cassert>
#include <vector>

namespace obscura::gpu {

inline Buffer uploadChannels(Context::Impl& context, const Image& image, int channels) {
    assert(image.channels >= channels && channels > 0 && !image.empty());
    if (image.channels == channels) return upload(context, image.pixels.data(), image.pixels.size() * sizeof(float));
    const std::size_t pixels = image.pixelCount();
    std::vector<float> packed(pixels * std::size_t(channels));
    for (std::size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < channels; ++c)
            packed[i * std::size_t(channels) + std::size_t(c)] =
                image.pixels[i * std::size_t(image.channels) + std::size_t(c)];
    return upload(context, packed.data(), packed.size() * sizeof(float));
}

} // namespace obscura::gpu
