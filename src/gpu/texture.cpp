// Sampled images and their staged upload; see texture.h.
#include "gpu/texture.h"

#include "gpu/buffer.h"

#include "obscura/error.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>

namespace obscura::gpu {

namespace {

std::string shapeText(const TextureShape& s) {
    std::string text = std::to_string(s.width) + "x" + std::to_string(s.height);
    if (s.threeD) text.append("x").append(std::to_string(s.depth));  // not "x" + ...: GCC 12 warns (-Wrestrict)
    return text;
}

} // namespace

Texture::Texture(Context::Impl& context, const TextureShape& shape, TextureFilter filter)
    : context_(&context), shape_(shape) {
    const std::string what = "a " + shapeText(shape) + " texture";
    const std::uint32_t limit = shape.threeD ? context.properties.limits.maxImageDimension3D
                                             : context.properties.limits.maxImageDimension2D;
    if (shape.width < 1 || shape.height < 1 || shape.depth < 1 || (!shape.threeD && shape.depth != 1) ||
        (shape.channels != 1 && shape.channels != 4))
        fail(what, "needs a positive size (depth 1 in 2-D) and 1 or 4 channels");
    if (std::uint32_t(std::max({shape.width, shape.height, shape.depth})) > limit)
        fail("Vulkan device '" + context.info.name + "'", "cannot hold " + what + " (its limit is " +
                                                              std::to_string(limit) + " texels per axis)");
    const VkFormat format = shape.channels == 1 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT;
    VkFormatProperties features{};
    vkGetPhysicalDeviceFormatProperties(context.physical, format, &features);
    const VkFormatFeatureFlags needed =
        VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT |
        (filter == TextureFilter::Linear ? VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT : 0);
    if ((features.optimalTilingFeatures & needed) != needed)
        fail("Vulkan device '" + context.info.name + "'", "cannot sample " + what +
                                                              (filter == TextureFilter::Linear ? " with linear filtering" : ""));

    VkImageCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    info.imageType = shape.threeD ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {std::uint32_t(shape.width), std::uint32_t(shape.height), std::uint32_t(shape.depth)};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    context.check(vkCreateImage(context.device, &info, nullptr, &image_), "creating " + what);
    try {
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(context.device, image_, &req);
        // Optimal-tiling images share blocks with buffers: bufferImageGranularity apart (Vulkan spec 11.6),
        // so the image starts and ends on a granularity boundary.
        const VkDeviceSize granularity = std::max<VkDeviceSize>(context.properties.limits.bufferImageGranularity, 1);
        req.alignment = std::max(req.alignment, granularity);
        req.size = (req.size + granularity - 1) / granularity * granularity;
        allocation_ = context.allocator->allocate(req, MemoryUse::Device);
        context.check(vkBindImageMemory(context.device, image_, allocation_.memory, allocation_.offset),
                      "binding " + what + "'s memory");

        VkImageViewCreateInfo viewInfo{};
        viewInfo.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
        viewInfo.image = image_;
        viewInfo.viewType = shape.threeD ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
        viewInfo.format = format;
        viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        context.check(vkCreateImageView(context.device, &viewInfo, nullptr, &view_), "creating " + what + "'s view");

        VkSamplerCreateInfo samplerInfo{};
        samplerInfo.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
        const VkFilter f = filter == TextureFilter::Linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
        samplerInfo.magFilter = f;
        samplerInfo.minFilter = f;
        samplerInfo.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
        samplerInfo.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        samplerInfo.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        samplerInfo.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        samplerInfo.maxLod = 0.0f;
        context.check(vkCreateSampler(context.device, &samplerInfo, nullptr, &sampler_),
                      "creating " + what + "'s sampler");
    } catch (...) {
        reset();
        throw;
    }
}

Texture& Texture::operator=(Texture&& o) noexcept {
    if (this != &o) {
        reset();
        context_ = std::exchange(o.context_, nullptr);
        shape_ = o.shape_;
        image_ = std::exchange(o.image_, VK_NULL_HANDLE);
        view_ = std::exchange(o.view_, VK_NULL_HANDLE);
        sampler_ = std::exchange(o.sampler_, VK_NULL_HANDLE);
        allocation_ = std::exchange(o.allocation_, Allocation{});
    }
    return *this;
}

void Texture::reset() {
    if (!context_) return;
    if (sampler_ != VK_NULL_HANDLE) vkDestroySampler(context_->device, sampler_, nullptr);
    if (view_ != VK_NULL_HANDLE) vkDestroyImageView(context_->device, view_, nullptr);
    if (image_ != VK_NULL_HANDLE) vkDestroyImage(context_->device, image_, nullptr);
    if (allocation_.memory != VK_NULL_HANDLE) context_->allocator->release(allocation_);
    context_ = nullptr;
    sampler_ = VK_NULL_HANDLE;
    view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    allocation_ = Allocation{};
}

Texture uploadTexture(Context::Impl& context, const float* data, const TextureShape& shape, TextureFilter filter) {
    Texture texture(context, shape, filter);
    const std::size_t bytes = shape.texels() * std::size_t(shape.channels) * sizeof(float);
    Buffer staging(context, bytes, MemoryUse::Upload);
    std::memcpy(staging.mapped(), data, bytes);  // coherent memory: no flush needed
    context.submit([&](VkCommandBuffer cmd) {
        VkImageMemoryBarrier toCopy{};
        toCopy.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
        toCopy.srcAccessMask = 0;
        toCopy.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        toCopy.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        toCopy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        toCopy.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        toCopy.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        toCopy.image = texture.image();
        toCopy.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &toCopy);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {std::uint32_t(shape.width), std::uint32_t(shape.height), std::uint32_t(shape.depth)};
        vkCmdCopyBufferToImage(cmd, staging.handle(), texture.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        // The copy's writes land before any later compute shader samples the image, in the layout it reads.
        VkImageMemoryBarrier toRead = toCopy;
        toRead.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        toRead.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
        toRead.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        toRead.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr,
                             0, nullptr, 1, &toRead);
    });
    return texture;
}

} // namespace obscura::gpu
