// Sampled float images (2-D and 3-D VkImage) in the context's suballocated memory, uploaded through a
// staging buffer: lookup tables and environment maps that shaders read as combined image samplers.
#pragma once

#include "gpu/allocator.h"
#include "gpu/context.h"

#include <cstddef>
#include <utility>

namespace obscura::gpu {

enum class TextureFilter {
    Nearest,  // texelFetch or nearest sampling
    Linear,   // hardware (bi/tri)linear filtering; checked against the format's features
};

struct TextureShape {
    int width = 1;     // texels, >= 1
    int height = 1;    // texels, >= 1
    int depth = 1;     // texels, >= 1; a 3-D image when `threeD`, else 1
    int channels = 1;  // floats per texel: 1 (R32_SFLOAT) or 4 (R32G32B32A32_SFLOAT)
    bool threeD = false;
    std::size_t texels() const { return std::size_t(width) * std::size_t(height) * std::size_t(depth); }
};

// A VkImage with its view and sampler, bound to its range of a memory block: move-only, released together.
// Addressing clamps to the edge on every axis (a shader wraps by hand where it needs to).
class Texture {
public:
    Texture() = default;
    // An image in VK_IMAGE_LAYOUT_UNDEFINED; upload() fills it. Throws obscura::Error for a shape the device
    // cannot hold (maxImageDimension2D/3D), a filter its format lacks, or out of memory.
    Texture(Context::Impl& context, const TextureShape& shape, TextureFilter filter);
    ~Texture() { reset(); }
    Texture(Texture&& o) noexcept { *this = std::move(o); }
    Texture& operator=(Texture&& o) noexcept;
    Texture(const Texture&) = delete;
    Texture& operator=(const Texture&) = delete;

    VkImage image() const { return image_; }
    VkImageView view() const { return view_; }
    VkSampler sampler() const { return sampler_; }
    const TextureShape& shape() const { return shape_; }
    void reset();

private:
    Context::Impl* context_ = nullptr;
    TextureShape shape_;
    VkImage image_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkSampler sampler_ = VK_NULL_HANDLE;
    Allocation allocation_;
};

// A texture holding shape.texels() * shape.channels floats from `data` (x fastest, then y, then z), copied
// through a staging buffer; waits for the copy and leaves the image in SHADER_READ_ONLY_OPTIMAL, visible to
// compute shaders.
Texture uploadTexture(Context::Impl& context, const float* data, const TextureShape& shape, TextureFilter filter);

} // namespace obscura::gpu
