// Buffers and staged transfers; see buffer.h.
#include "gpu/buffer.h"

#include <cassert>
#include <cstring>
#include <utility>

namespace obscura::gpu {


Buffer::Buffer(Context::Impl& context, VkDeviceSize bytes, MemoryUse use) : context_(&context), bytes_(bytes) {
    assert(bytes > 0);  // Vulkan has no empty buffers
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = bytes;
    info.usage =
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    context.check(vkCreateBuffer(context.device, &info, nullptr, &buffer_),
                  "creating a buffer of " + std::to_string(bytes) + " bytes");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(context.device, buffer_, &req);
    try {
        allocation_ = context.allocator->allocate(req, use);
        context.check(vkBindBufferMemory(context.device, buffer_, allocation_.memory, allocation_.offset),
                      "binding buffer memory");
    } catch (...) {
        reset();
        throw;
    }
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
    if (this != &o) {
        reset();
        context_ = std::exchange(o.context_, nullptr);
        buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
        bytes_ = std::exchange(o.bytes_, 0);
        allocation_ = std::exchange(o.allocation_, Allocation{});
    }
    return *this;
}

void Buffer::reset() {
    if (!context_) return;
    if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(context_->device, buffer_, nullptr);
    context_->allocator->release(allocation_);
    context_ = nullptr;
    buffer_ = VK_NULL_HANDLE;
    allocation_ = Allocation{};
}

Buffer upload(Context::Impl& context, const void* data, std::size_t bytes) {
    Buffer staging(context, bytes, MemoryUse::Upload);
    std::memcpy(staging.mapped(), data, bytes);  // coherent memory: no flush needed
    Buffer device(context, bytes, MemoryUse::Device);
    context.submit([&](VkCommandBuffer cmd) {
        const VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, staging.handle(), device.handle(), 1, &region);
        // The copy's writes must land before any later compute shader reads the buffer.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    });
    return device;
}

void download(Context::Impl& context, const Buffer& buffer, void* data, std::size_t bytes) {
    assert(bytes <= buffer.size());
    Buffer staging(context, bytes, MemoryUse::Download);
    context.submit([&](VkCommandBuffer cmd) {
        // Earlier compute shader writes must be complete and visible to the copy.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        const VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, buffer.handle(), staging.handle(), 1, &region);
        // The copy's writes must be visible to the host once the fence signals.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_HOST_READ_BIT);
    });
    std::memcpy(data, staging.mapped(), bytes);
}

} // namespace obscura::gpu
