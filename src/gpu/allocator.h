// Device memory for storage and staging buffers, suballocated from a few large blocks: Vulkan limits the
// number of live vkAllocateMemory calls (4096 is common) and each one is slow, so a pass's buffers share
// blocks. First fit over a sorted free list per block; neighbouring free ranges merge on release.
#pragma once

#include "gpu/vulkan.h"

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace obscura::gpu {

// The free-list of one block, in bytes; no Vulkan (tests/gpu/allocator_test.cpp checks it alone).
class RangeAllocator {
public:
    explicit RangeAllocator(std::uint64_t size);
    // Offset of `size` bytes aligned to `alignment` (a power of two), or nothing if no free range fits.
    std::optional<std::uint64_t> allocate(std::uint64_t size, std::uint64_t alignment);
    // Returns a range from allocate() (same offset and size).
    void release(std::uint64_t offset, std::uint64_t size);
    bool empty() const { return free_.size() == 1 && free_.begin()->second == size_; }
    std::uint64_t freeBytes() const;
    std::size_t freeRanges() const { return free_.size(); }

private:
    std::uint64_t size_;
    std::map<std::uint64_t, std::uint64_t> free_;  // offset -> size, disjoint and never adjacent
};

enum class MemoryUse {
    Device,    // read and written by shaders: device-local
    Upload,    // host writes, the GPU copies from it: host-visible, coherent
    Download,  // the GPU copies into it, host reads: host-visible, coherent, cached where available
};

struct Allocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0, size = 0;
    void* mapped = nullptr;  // host pointer at `offset` for Upload and Download
    std::uint32_t block = 0;
};

class Allocator {
public:
    static constexpr VkDeviceSize kBlockBytes = VkDeviceSize(64) << 20;  // larger requests get a block of their own

    Allocator(VkPhysicalDevice physical, VkDevice device, std::string deviceName);
    ~Allocator();
    Allocator(const Allocator&) = delete;
    Allocator& operator=(const Allocator&) = delete;

    // Throws obscura::Error for out of device or host memory.
    Allocation allocate(const VkMemoryRequirements& requirements, MemoryUse use);
    void release(const Allocation& allocation);
    std::size_t blockCount() const;

private:
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;
        std::uint32_t type = 0;
        RangeAllocator ranges{0};
        void* mapped = nullptr;
        bool shared = true;  // a kBlockBytes block other allocations may use; false: one allocation's own
    };
    std::uint32_t memoryType(std::uint32_t allowed, MemoryUse use) const;

    VkDevice device_;
    std::string deviceName_;
    VkPhysicalDeviceMemoryProperties properties_{};
    std::vector<Block> blocks_;  // a released own block leaves a null slot, reused later
};

} // namespace obscura::gpu
