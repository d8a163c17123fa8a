// The planes the passes in src/gpu read and write, to and from the host: obscura::Image uploads (the first
// `channels` channels of every pixel, interleaved, as the shaders' float arrays expect; an image with more
// channels is repacked on the host), device-only float planes, downloads as 32-bit words, and the G-buffer's
// normals as the octahedral words the passes take instead of 3 floats (normal_plane.glsl).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"

#include "obscura/history_packing.h"
#include "obscura/image.h"

#include <cassert>
#include <cstdint>
#include <vector>

namespace obscura::gpu {

inline Buffer deviceFloats(Context::Impl& context, std::size_t count) {
    return Buffer(context, count * sizeof(float), MemoryUse::Device);
}

inline std::vector<std::uint32_t> downloadWords(Context::Impl& context, const Buffer& buffer, std::size_t count) {
    std::vector<std::uint32_t> words(count);
    download(context, buffer, words.data(), count * sizeof(std::uint32_t));
    return words;
}

// The view normals of `normal` (3 channels) as one octahedral word per pixel (ssao::packOctahedral), for the
// passes' packedNormals; and the normals a pass reading those words sees, for a CPU reference of that frame.
inline std::vector<std::uint32_t> packNormals(const Image& normal) {
    assert(normal.channels == 3);
    std::vector<std::uint32_t> words(normal.pixelCount());
    for (std::size_t i = 0; i < words.size(); ++i)
        words[i] = ssao::packOctahedral({normal.pixels[3 * i], normal.pixels[3 * i + 1], normal.pixels[3 * i + 2]});
    return words;
}
// The normals uploaded in the layout a pass with packedNormals (or without) reads: words, or 3 floats.
inline Buffer uploadNormals(Context::Impl& context, const Image& normal, bool packed) {
    assert(normal.channels == 3);
    if (!packed) return upload(context, normal.pixels.data(), normal.pixels.size() * sizeof(float));
    const std::vector<std::uint32_t> words = packNormals(normal);
    return upload(context, words.data(), words.size() * sizeof(std::uint32_t));
}
inline Image unpackNormals(const std::vector<std::uint32_t>& words, int width, int height) {
    assert(words.size() == std::size_t(width) * std::size_t(height));
    Image normal(width, height, 3);
    for (std::size_t i = 0; i < words.size(); ++i) {
        const Vec3 n = ssao::unpackOctahedral(words[i]);
        normal.pixels[3 * i] = n.x;
        normal.pixels[3 * i + 1] = n.y;
        normal.pixels[3 * i + 2] = n.z;
    }
    return normal;
}

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
