// The state behind obscura::gpu::Context, for the passes in src/gpu.
#pragma once

#include "gpu/allocator.h"
#include "gpu/pipeline_executables.h"
#include "gpu/vulkan.h"

#include "obscura/gpu.h"

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <string>
#include <vector>

namespace obscura::gpu {

class ComputePipeline;
struct Spirv;
enum class BindingKind : int;  // gpu/spirv.h

struct Context::Impl {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    PFN_vkDestroyDebugUtilsMessengerEXT destroyMessenger = nullptr;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::uint32_t queueFamily = 0;
    VkQueue queue = VK_NULL_HANDLE;
    VkCommandPool commandPool = VK_NULL_HANDLE;
    VkCommandBuffer commandBuffer = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    VkQueryPool timestamps = VK_NULL_HANDLE;  // null when the queue has no timestamps
    // The queue family's timestampValidBits as a mask: a counter of fewer than 64 bits wraps at 2^bits.
    std::uint64_t timestampMask = ~std::uint64_t(0);
    VkPhysicalDeviceProperties properties{};
    DeviceInfo info;
    // Mesa's lavapipe (llvmpipe): it ends a shader invocation's loops after 65535 iterations in all, with no
    // error (checkGtaoLoopBudget).
    bool lavapipe = false;
    bool validation = false;
    // VK_KHR_pipeline_executable_properties, when ContextSettings asked for it and the device offers it
    // (info.pipelineStatistics): pipelines are made with the capture flags and report what the driver says.
    bool captureInternals = false;
    ExecutableQueries executableQueries;
    std::unique_ptr<Allocator> allocator;
    double lastPassMs = -1.0;
    // Timestamps of the submission being recorded: slot 0 at its start, one per mark(), one at its end.
    static constexpr std::uint32_t kMaxTimestamps = 512;
    bool timing = false;                  // the submission being recorded is timed
    std::vector<std::string> markNames;   // mark() names of that submission, in order
    // The last timed submission's marks: each name with the GPU ms since the previous mark (or the start).
    std::vector<std::pair<std::string, double>> lastMarks;

    // Made once per context: creating a pipeline compiles its shader to the device's machine code.
    std::map<std::string, std::unique_ptr<ComputePipeline>> pipelines;
    // OBSCURA_SHADER_DIR: a folder whose NAME.spv replaces the embedded shader NAME (for timing a changed
    // shader without a rebuild); the words of the files read from it, by shader name.
    std::string shaderDir;
    std::map<std::string, std::vector<std::uint32_t>> shaderFiles;

    mutable std::mutex messagesMutex;  // the layer may call back from any thread
    std::vector<std::string> messages;

    Impl() = default;
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    ~Impl();

    // Throws obscura::Error naming this device unless r is VK_SUCCESS.
    void check(VkResult r, const std::string& doing) const;
    // Records commands with `record` into the context's command buffer, submits them and waits for them.
    // With `timed`, the commands are bracketed by timestamps and lastPassMs is set from them.
    void submit(const std::function<void(VkCommandBuffer)>& record, bool timed = false);
    // In a timed submission, a timestamp after every command recorded so far has finished, named `name`;
    // submit() then sets lastMarks. Ignored in an untimed one, and past kMaxTimestamps - 2 marks.
    void mark(VkCommandBuffer cmd, const std::string& name);
    // The code of shader `name`: `embedded`, unless shaderDir holds NAME.spv (read once; a file that is not
    // SPIR-V fails naming it).
    Spirv shaderCode(const std::string& name, const Spirv& embedded);
    // The pipeline of shader `name`, made on first use (see ComputePipeline for the checks).
    ComputePipeline& pipeline(const std::string& name, const Spirv& code, int bindings,
                              std::uint32_t pushConstantBytes, int workgroupX, int workgroupY);
    // The variant of shader `name` with these binding kinds and specialization constants, made on first use
    // and cached per variant (the key holds the constants).
    ComputePipeline& pipeline(const std::string& name, const Spirv& code, const std::vector<BindingKind>& bindings,
                              std::uint32_t pushConstantBytes, int workgroupX, int workgroupY,
                              const std::vector<std::int32_t>& specialization = {});
    // The same, in the workgroup size the compiled shader declares (ComputePipeline::kShadersOwnSize): for a
    // pass whose invocations each evaluate their own pixels, so that a shader swapped in through
    // OBSCURA_SHADER_DIR may try another size.
    ComputePipeline& pipelineOfShadersSize(const std::string& name, const Spirv& code,
                                           const std::vector<BindingKind>& bindings, std::uint32_t pushConstantBytes,
                                           const std::vector<std::int32_t>& specialization);
};

// A Vulkan object owned by a device, destroyed with it: move-only.
template <class T>
class Unique {
public:
    using Destroy = void (*)(VkDevice, T, const VkAllocationCallbacks*);
    Unique() = default;
    Unique(VkDevice device, T handle, Destroy destroy) : device_(device), handle_(handle), destroy_(destroy) {}
    ~Unique() { reset(); }
    Unique(Unique&& o) noexcept : device_(o.device_), handle_(o.handle_), destroy_(o.destroy_) {
        o.handle_ = VK_NULL_HANDLE;
    }
    Unique& operator=(Unique&& o) noexcept {
        if (this != &o) {
            reset();
            device_ = o.device_;
            handle_ = o.handle_;
            destroy_ = o.destroy_;
            o.handle_ = VK_NULL_HANDLE;
        }
        return *this;
    }
    Unique(const Unique&) = delete;
    Unique& operator=(const Unique&) = delete;
    T get() const { return handle_; }
    void reset() {
        if (handle_ != VK_NULL_HANDLE) destroy_(device_, handle_, nullptr);
        handle_ = VK_NULL_HANDLE;
    }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    T handle_ = VK_NULL_HANDLE;
    Destroy destroy_ = nullptr;
};

// A global memory barrier: the `src` accesses of `srcStage` (and commands before it in submission order) are
// complete and visible to the `dst` accesses of `dstStage` (in commands after it, in any later submission).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags src, VkPipelineStageFlags dstStage,
                   VkAccessFlags dst);
// The barrier between two compute passes of one submission: the earlier one's writes are visible to the
// later one's reads and writes.
void computeBarrier(VkCommandBuffer cmd);

// The mask of a timestamp counter with `validBits` bits (VkQueueFamilyProperties::timestampValidBits, 1..64).
inline std::uint64_t timestampMask(std::uint32_t validBits) {
    return validBits >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << validBits) - 1;
}
// Milliseconds from timestamp `from` to `to` of a counter with `mask` (timestampMask) ticking every `periodNs`:
// taken modulo the counter's width, a wrap between the two reads as the ticks between them (a plain 64-bit
// difference of a 36-bit counter's wrap read 52 us as 9.6e14 ms).
inline double timestampDeltaMs(std::uint64_t from, std::uint64_t to, std::uint64_t mask, double periodNs) {
    return double((to - from) & mask) * periodNs * 1e-6;
}

// vkCreate<T>(device, &info) wrapped in a Unique; throws obscura::Error saying what was `doing`.
template <class T, class Info>
Unique<T> create(Context::Impl& context, VkResult (*createFn)(VkDevice, const Info*, const VkAllocationCallbacks*, T*),
                 const Info& info, typename Unique<T>::Destroy destroy, const std::string& doing) {
    T handle = VK_NULL_HANDLE;
    context.check(createFn(context.device, &info, nullptr, &handle), doing);
    return Unique<T>(context.device, handle, destroy);
}

} // namespace obscura::gpu
