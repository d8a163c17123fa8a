// A compute pipeline whose layout is checked against its shader: storage buffers at bindings 0..n-1 of set
// 0 and one push-constant block. After niagara's dispatch(), which asserts that what it binds matches the
// compiled shader.
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/spirv.h"

#include <cstdint>
#include <initializer_list>
#include <string>

namespace obscura::gpu {

class ComputePipeline {
public:
    // `bindings` storage buffers, `pushConstantBytes` of push constants and workgroups of workgroupX x
    // workgroupY, as the pass's shared header states them; throws obscura::Error if the shader declares
    // something else or the device's limits are too small.
    ComputePipeline(Context::Impl& context, const Spirv& code, const std::string& name, int bindings,
                    std::uint32_t pushConstantBytes, int workgroupX, int workgroupY);

    // Records a dispatch of `groupsX` x `groupsY` workgroups with these buffers at bindings 0, 1, ... and
    // these push constants. Each dispatch of one submission takes its own descriptor set (kSetsPerSubmit at
    // most); sets are rewritten in the next submission, after Context::Impl::submit has waited for this one.
    void dispatch(VkCommandBuffer cmd, std::initializer_list<const Buffer*> buffers, const void* pushConstants,
                  std::uint32_t pushBytes, std::uint32_t groupsX, std::uint32_t groupsY);
    // The same over a width x height grid of invocations: enough workgroups to cover it.
    void dispatchGrid(VkCommandBuffer cmd, std::initializer_list<const Buffer*> buffers, const void* pushConstants,
                      std::uint32_t pushBytes, int width, int height);

    const SpirvLayout& layout() const { return layout_; }
    // Called by Context::Impl::submit before recording: the descriptor sets are free again.
    void beginCommands() { used_ = 0; }

    static constexpr int kSetsPerSubmit = 4;

private:
    Context::Impl& context_;
    std::string name_;
    SpirvLayout layout_;
    Unique<VkDescriptorSetLayout> setLayout_;
    Unique<VkPipelineLayout> pipelineLayout_;
    Unique<VkPipeline> pipeline_;
    Unique<VkDescriptorPool> pool_;
    VkDescriptorSet sets_[kSetsPerSubmit] = {};  // freed with the pool
    int used_ = 0;
};

} // namespace obscura::gpu
