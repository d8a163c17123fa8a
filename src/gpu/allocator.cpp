// Block suballocator for device memory; see allocator.h.
#include "gpu/allocator.h"
#include "gpu/check.h"

#include "obscura/error.h"

#include <cassert>
#include <iterator>

namespace obscura::gpu {

RangeAllocator::RangeAllocator(std::uint64_t size) : size_(size) {
    if (size > 0) free_[0] = size;
}

std::optional<std::uint64_t> RangeAllocator::allocate(std::uint64_t size, std::uint64_t alignment) {
    assert(size > 0 && alignment > 0 && (alignment & (alignment - 1)) == 0);
    for (auto it = free_.begin(); it != free_.end(); ++it) {
        const std::uint64_t start = it->first, end = it->first + it->second;
        const std::uint64_t offset = (start + alignment - 1) & ~(alignment - 1);
        if (offset + size > end) continue;
        free_.erase(it);
        if (offset > start) free_[start] = offset - start;  // the alignment gap stays free
        if (offset + size < end) free_[offset + size] = end - offset - size;
        return offset;
    }
    return std::nullopt;
}

void RangeAllocator::release(std::uint64_t offset, std::uint64_t size) {
    auto next = free_.lower_bound(offset);
    assert(next == free_.end() || next->first >= offset + size);
    if (next != free_.end() && next->first == offset + size) {  // merge with the range after
        size += next->second;
        next = free_.erase(next);
    }
    if (next != free_.begin()) {
        auto prev = std::prev(next);
        assert(prev->first + prev->second <= offset);
        if (prev->first + prev->second == offset) {  // merge with the range before
            prev->second += size;
            return;
        }
    }
    free_[offset] = size;
}

std::uint64_t RangeAllocator::freeBytes() const {
    std::uint64_t sum = 0;
    for (const auto& [offset, size] : free_) sum += size;
    return sum;
}

Allocator::Allocator(VkPhysicalDevice physical, VkDevice device, std::string deviceName)
    : device_(device), deviceName_(std::move(deviceName)) {
    vkGetPhysicalDeviceMemoryProperties(physical, &properties_);
}

Allocator::~Allocator() {
    for (Block& b : blocks_)
        if (b.memory != VK_NULL_HANDLE) vkFreeMemory(device_, b.memory, nullptr);  // unmaps too
}

std::uint32_t Allocator::memoryType(std::uint32_t allowed, MemoryUse use) const {
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    const VkMemoryPropertyFlags required = use == MemoryUse::Device ? 0 : host;
    const VkMemoryPropertyFlags preferred = use == MemoryUse::Device    ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT
                                            : use == MemoryUse::Download ? VK_MEMORY_PROPERTY_HOST_CACHED_BIT
                                                                         : 0;
    int fallback = -1;
    for (std::uint32_t i = 0; i < properties_.memoryTypeCount; ++i) {
        if (!(allowed & (1u << i))) continue;
        const VkMemoryPropertyFlags f = properties_.memoryTypes[i].propertyFlags;
        if ((f & required) != required) continue;
        if ((f & preferred) == preferred) return i;
        if (fallback < 0) fallback = int(i);
    }
    if (fallback < 0) fail("Vulkan device '" + deviceName_ + "'", "no memory type for a buffer");
    return std::uint32_t(fallback);
}

Allocation Allocator::allocate(const VkMemoryRequirements& req, MemoryUse use) {
    const std::uint32_t type = memoryType(req.memoryTypeBits, use);
    const bool host = use != MemoryUse::Device;
    const auto found = [&](std::uint32_t index, std::uint64_t offset) {
        Block& b = blocks_[index];
        void* mapped = b.mapped ? static_cast<char*>(b.mapped) + offset : nullptr;
        return Allocation{b.memory, offset, req.size, mapped, index};
    };
    if (req.size <= kBlockBytes)
        for (std::uint32_t i = 0; i < blocks_.size(); ++i) {
            Block& b = blocks_[i];
            if (b.memory == VK_NULL_HANDLE || !b.shared || b.type != type || (host && !b.mapped)) continue;
            if (auto offset = b.ranges.allocate(req.size, req.alignment)) return found(i, *offset);
        }
    Block b;
    b.type = type;
    b.shared = req.size <= kBlockBytes;
    const VkDeviceSize bytes = b.shared ? kBlockBytes : req.size;
    // Asked of the driver, a request beyond the heap is undefined enough that some drivers crash or the
    // validation layer objects; named here in the words of a failed allocation instead.
    const VkDeviceSize heap = properties_.memoryHeaps[properties_.memoryTypes[type].heapIndex].size;
    if (bytes > heap)
        fail("Vulkan device '" + deviceName_ + "'", "allocating " + std::to_string(bytes >> 20) +
                                                       " MiB of device memory: out of device memory (the heap has " +
                                                       std::to_string(heap >> 20) + " MiB)");
    VkMemoryAllocateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    info.allocationSize = bytes;
    info.memoryTypeIndex = type;
    check(vkAllocateMemory(device_, &info, nullptr, &b.memory), deviceName_,
          "allocating " + std::to_string(bytes >> 20) + " MiB of device memory");
    if (properties_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
        const VkResult r = vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped);
        if (r != VK_SUCCESS) {
            vkFreeMemory(device_, b.memory, nullptr);
            check(r, deviceName_, "mapping device memory");
        }
    }
    b.ranges = RangeAllocator(bytes);
    const std::uint64_t offset = *b.ranges.allocate(req.size, req.alignment);
    std::uint32_t index = 0;
    while (index < blocks_.size() && blocks_[index].memory != VK_NULL_HANDLE) ++index;
    if (index == blocks_.size()) blocks_.emplace_back();
    blocks_[index] = std::move(b);
    return found(index, offset);
}

void Allocator::release(const Allocation& a) {
    if (a.memory == VK_NULL_HANDLE) return;
    Block& b = blocks_[a.block];
    assert(b.memory == a.memory);
    b.ranges.release(a.offset, a.size);
    // An own block goes back at once; shared blocks stay for the next pass.
    if (!b.shared && b.ranges.empty()) {
        vkFreeMemory(device_, b.memory, nullptr);
        b = Block{};
    }
}

std::size_t Allocator::blockCount() const {
    std::size_t n = 0;
    for (const Block& b : blocks_) n += b.memory != VK_NULL_HANDLE;
    return n;
}

} // namespace obscura::gpu
