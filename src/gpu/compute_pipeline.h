// A compute pipeline whose layout is checked against its shader: storage buffers and combined image
// samplers at bindings 0..n-1 of set 0, one push-constant block and the specialization constants that pick
// the shader's variant. After niagara's dispatch(), which asserts that what it binds matches the
// compiled shader.
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/spirv.h"
#include "gpu/texture.h"

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace obscura::gpu {

// What a dispatch binds at one binding: a storage buffer or a sampled texture. Implicit from either, so a
// pass lists its resources as {&depth, &table, ...}.
struct Resource {
    Resource(const Buffer* b) : buffer(b), bytes(b ? b->size() : 0) {}
    // `count` bytes of the buffer from `from` (a multiple of minStorageBufferOffsetAlignment): the shader's
    // block starts there, and what the dispatch reads or writes is that range alone.
    Resource(const Buffer* b, VkDeviceSize from, VkDeviceSize count) : buffer(b), offset(from), bytes(count) {}
    Resource(const Texture* t) : texture(t) {}
    const Buffer* buffer = nullptr;
    const Texture* texture = nullptr;
    VkDeviceSize offset = 0, bytes = 0;
};

class ComputePipeline {
public:
    // As workgroupX and workgroupY: whatever 2-D size the shader declares, for a pass whose dispatch reads it
    // back from layout().localSize (dispatchGrid does), so that a shader swapped in through OBSCURA_SHADER_DIR
    // may try another size without a rebuilt host (bench/gpu-candidates).
    static constexpr int kShadersOwnSize = 0;

    // `bindings` storage buffers, `pushConstantBytes` of push constants and workgroups of workgroupX x
    // workgroupY, as the pass's shared header states them (or kShadersOwnSize for both); throws obscura::Error
    // if the shader declares something else or the device's limits are too small.
    ComputePipeline(Context::Impl& context, const Spirv& code, const std::string& name, int bindings,
                    std::uint32_t pushConstantBytes, int workgroupX, int workgroupY);
    // The same with binding b of kind bindings[b], and constant_id i specialized to specialization[i] (32-bit
    // int constants; the shader must declare exactly as many).
    ComputePipeline(Context::Impl& context, const Spirv& code, const std::string& name,
                    const std::vector<BindingKind>& bindings, std::uint32_t pushConstantBytes, int workgroupX,
                    int workgroupY, const std::vector<std::int32_t>& specialization = {});

    // Records a dispatch of `groupsX` x `groupsY` workgroups with these resources at bindings 0, 1, ... and
    // these push constants. Each dispatch of one submission takes its own descriptor set (kSetsPerSubmit at
    // most); sets are rewritten in the next submission, after Context::Impl::submit has waited for this one.
    void dispatch(VkCommandBuffer cmd, std::initializer_list<Resource> resources, const void* pushConstants,
                  std::uint32_t pushBytes, std::uint32_t groupsX, std::uint32_t groupsY);
    // The same over a width x height grid of invocations: enough workgroups to cover it.
    void dispatchGrid(VkCommandBuffer cmd, std::initializer_list<Resource> resources, const void* pushConstants,
                      std::uint32_t pushBytes, int width, int height);

    const SpirvLayout& layout() const { return layout_; }
    // What the driver said of the compiled pipeline, when the context captures it (Context::pipelineReports).
    const std::vector<PipelineExecutable>& executables() const { return executables_; }
    const std::string& describeError() const { return describeError_; }  // why they are missing, if they are
    // Dispatches recorded since the pipeline was made: `obscura bench --gpu` names the shaders a case ran by
    // the pipelines whose count its frames raised.
    std::uint64_t dispatches() const { return dispatches_; }
    // Called by Context::Impl::submit before recording: the descriptor sets are free again.
    void beginCommands() { used_ = 0; }

    // A frame dispatches one shader at most 4 times, and `obscura bench --gpu` records up to 64 frames in
    // one submission (GpuBenchSettings::framesPerSubmit).
    static constexpr int kSetsPerSubmit = 256;

private:
    Context::Impl& context_;
    std::string name_;  // the cache's key: the shader's name, then its specialization constants in <>
    SpirvLayout layout_;
    std::vector<BindingKind> kinds_;
    Unique<VkDescriptorSetLayout> setLayout_;
    Unique<VkPipelineLayout> pipelineLayout_;
    Unique<VkPipeline> pipeline_;
    Unique<VkDescriptorPool> pool_;
    VkDescriptorSet sets_[kSetsPerSubmit] = {};  // freed with the pool
    int used_ = 0;
    std::uint64_t dispatches_ = 0;
    std::vector<PipelineExecutable> executables_;
    std::string describeError_;
};

} // namespace obscura::gpu
