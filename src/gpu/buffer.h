// Storage and staging buffers in the context's suballocated memory, and staged copies to and from them.
#pragma once

#include "gpu/allocator.h"
#include "gpu/context.h"

#include <cstddef>

namespace obscura::gpu {

// A VkBuffer bound to its range of a memory block: move-only, both released together.
class Buffer {
public:
    Buffer() = default;
    // Usage: storage, transfer source and destination (any buffer can be a copy's end). Throws
    // obscura::Error for out of memory.
    Buffer(Context::Impl& context, VkDeviceSize bytes, MemoryUse use);
    ~Buffer() { reset(); }
    Buffer(Buffer&& o) noexcept { *this = std::move(o); }
    Buffer& operator=(Buffer&& o) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return bytes_; }
    void* mapped() const { return allocation_.mapped; }  // null for MemoryUse::Device
    void reset();

private:
    Context::Impl* context_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceSize bytes_ = 0;
    Allocation allocation_;
};

// A device buffer holding `bytes` from `data`, copied through a staging buffer; waits for the copy and
// makes it visible to compute shaders.
Buffer upload(Context::Impl& context, const void* data, std::size_t bytes);
// Copies `bytes` of a device buffer written by compute shaders into `data` through a staging buffer.
void download(Context::Impl& context, const Buffer& buffer, void* data, std::size_t bytes);

} // namespace obscura::gpu
