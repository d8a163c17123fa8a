// Compute pipelines with checked layouts; see compute_pipeline.h.
#include "gpu/compute_pipeline.h"
#include "gpu/pipeline_executables.h"

#include "obscura/error.h"

#include <algorithm>
#include <cassert>
#include <string>
#include <vector>

namespace obscura::gpu {

namespace {

const char* kindName(BindingKind k) { return k == BindingKind::SampledImage ? "a sampled image" : "a storage buffer"; }

VkDescriptorType descriptorType(BindingKind k) {
    return k == BindingKind::SampledImage ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                                          : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

} // namespace

ComputePipeline::ComputePipeline(Context::Impl& context, const Spirv& code, const std::string& name, int bindings,
                                 std::uint32_t pushConstantBytes, int workgroupX, int workgroupY)
    : ComputePipeline(context, code, name, std::vector<BindingKind>(std::size_t(bindings), BindingKind::StorageBuffer),
                      pushConstantBytes, workgroupX, workgroupY) {}

ComputePipeline::ComputePipeline(Context::Impl& context, const Spirv& code, const std::string& name,
                                 const std::vector<BindingKind>& kinds, std::uint32_t pushConstantBytes, int workgroupX,
                                 int workgroupY, const std::vector<std::int32_t>& specialization)
    : context_(context), name_(name), layout_(reflect(code)), kinds_(kinds) {
    const int bindings = int(kinds.size());
    const std::string what = "shader " + name;
    // dispatchGrid divides the image by the size the shader declares; a size the host names must be that one.
    const std::uint32_t* size = layout_.localSize;
    const std::string workgroups = "has workgroups of " + std::to_string(size[0]) + "x" + std::to_string(size[1]) +
                                   "x" + std::to_string(size[2]);
    if (size[0] == 0 || size[1] == 0 || size[2] == 0) fail(what, "declares no workgroup size");
    if (size[2] != 1) fail(what, workgroups + ", the host dispatches 2-D ones");
    const bool shadersOwn = workgroupX == kShadersOwnSize && workgroupY == kShadersOwnSize;
    if (!shadersOwn && (size[0] != std::uint32_t(workgroupX) || size[1] != std::uint32_t(workgroupY)))
        fail(what, workgroups + ", the host dispatches " + std::to_string(workgroupX) + "x" +
                       std::to_string(workgroupY));
    if (!layout_.unsupported.empty()) fail(what, layout_.unsupported);
    if (layout_.bindings != bindings || layout_.pushConstantBytes != pushConstantBytes)
        fail(what, "declares " + std::to_string(layout_.bindings) + " bindings and " +
                       std::to_string(layout_.pushConstantBytes) + " bytes of push constants, the host binds " +
                       std::to_string(bindings) + " and " + std::to_string(pushConstantBytes));
    for (int b = 0; b < bindings; ++b)
        if (std::size_t(b) >= layout_.kinds.size() || layout_.kinds[std::size_t(b)] != kinds[std::size_t(b)])
            fail(what, "binding " + std::to_string(b) + " is not " + kindName(kinds[std::size_t(b)]) +
                           " as the host binds it");
    // A size given by specialization constants is dispatched by their defaults (reflect): a variant of the
    // host's (constant_id i is specialization[i]) must not be one of them.
    for (const std::uint32_t id : layout_.sizeSpecIds)
        if (id < specialization.size())
            fail(what, "takes its workgroup size from constant_id " + std::to_string(id) +
                           ", which the host sets as one of its " + std::to_string(specialization.size()) +
                           " variant constants");
    if (layout_.specConstants != int(specialization.size()))
        fail(what, "declares " + std::to_string(layout_.specConstants) + " specialization constants, the host sets " +
                       std::to_string(specialization.size()));
    // As many is not enough: the host sets constant_ids 0 to n - 1, and one numbered past them kept its default.
    for (std::size_t i = 0; i < layout_.specIds.size(); ++i)
        if (layout_.specIds[i] != i) {
            std::string ids;
            for (const std::uint32_t id : layout_.specIds) ids += (ids.empty() ? "" : ", ") + std::to_string(id);
            fail(what, "declares specialization constant_ids " + ids + "; the host sets constant_ids 0 to " +
                           std::to_string(specialization.size() - 1));
        }
    const VkPhysicalDeviceLimits& limits = context.properties.limits;
    if (pushConstantBytes > limits.maxPushConstantsSize)
        fail("Vulkan device '" + context.info.name + "'", what + " needs " + std::to_string(pushConstantBytes) +
                                                              " bytes of push constants");
    // The size a pass takes from its shader (kShadersOwnSize) is not one the headers vouch for: a candidate may
    // ask for more than a device has, which Vulkan leaves undefined rather than refused.
    if (size[0] > limits.maxComputeWorkGroupSize[0] || size[1] > limits.maxComputeWorkGroupSize[1] ||
        std::uint64_t(size[0]) * size[1] > limits.maxComputeWorkGroupInvocations)
        fail("Vulkan device '" + context.info.name + "'",
             what + " " + workgroups + ", beyond the device's limits (" +
                 std::to_string(limits.maxComputeWorkGroupSize[0]) + "x" +
                 std::to_string(limits.maxComputeWorkGroupSize[1]) + ", " +
                 std::to_string(limits.maxComputeWorkGroupInvocations) + " invocations)");
    VkDevice device = context.device;

    std::vector<VkDescriptorSetLayoutBinding> slots(static_cast<std::size_t>(bindings));
    for (int i = 0; i < bindings; ++i) {
        slots[std::size_t(i)].binding = std::uint32_t(i);
        slots[std::size_t(i)].descriptorType = descriptorType(kinds[std::size_t(i)]);
        slots[std::size_t(i)].descriptorCount = 1;
        slots[std::size_t(i)].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    VkDescriptorSetLayoutCreateInfo setInfo{};
    setInfo.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    setInfo.bindingCount = std::uint32_t(bindings);
    setInfo.pBindings = slots.data();
    setLayout_ = create(context, vkCreateDescriptorSetLayout, setInfo, vkDestroyDescriptorSetLayout,
                        "creating " + what + "'s layout");
    const VkDescriptorSetLayout setLayout = setLayout_.get();

    const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo layoutInfo{};
    layoutInfo.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &setLayout;
    layoutInfo.pushConstantRangeCount = pushConstantBytes > 0 ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    pipelineLayout_ =
        create(context, vkCreatePipelineLayout, layoutInfo, vkDestroyPipelineLayout, "creating " + what + "'s layout");

    VkShaderModuleCreateInfo moduleInfo{};
    moduleInfo.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    moduleInfo.codeSize = code.count * sizeof(std::uint32_t);
    moduleInfo.pCode = code.words;
    // Needed only until the pipeline exists.
    const Unique<VkShaderModule> module =
        create(context, vkCreateShaderModule, moduleInfo, vkDestroyShaderModule, "loading " + what);

    VkComputePipelineCreateInfo pipelineInfo{};
    pipelineInfo.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    pipelineInfo.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipelineInfo.stage.module = module.get();
    pipelineInfo.stage.pName = "main";
    // constant_id i is the i-th int of `specialization`.
    std::vector<VkSpecializationMapEntry> entries;
    for (std::size_t i = 0; i < specialization.size(); ++i)
        entries.push_back({std::uint32_t(i), std::uint32_t(i * sizeof(std::int32_t)), sizeof(std::int32_t)});
    VkSpecializationInfo specInfo{};
    specInfo.mapEntryCount = std::uint32_t(entries.size());
    specInfo.pMapEntries = entries.data();
    specInfo.dataSize = specialization.size() * sizeof(std::int32_t);
    specInfo.pData = specialization.data();
    if (!specialization.empty()) pipelineInfo.stage.pSpecializationInfo = &specInfo;
    pipelineInfo.layout = pipelineLayout_.get();
    if (context.info.pipelineStatistics) pipelineInfo.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
    if (context.captureInternals) pipelineInfo.flags |= VK_PIPELINE_CREATE_CAPTURE_INTERNAL_REPRESENTATIONS_BIT_KHR;
    VkPipeline pipeline = VK_NULL_HANDLE;
    context.check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &pipeline),
                  "compiling " + what);
    pipeline_ = Unique<VkPipeline>(device, pipeline, vkDestroyPipeline);
    if (context.info.pipelineStatistics)
        executables_ = describeExecutables(context.device, pipeline, context.executableQueries,
                                           context.captureInternals, &describeError_);

    std::vector<VkDescriptorPoolSize> poolSizes;
    for (const BindingKind k : {BindingKind::StorageBuffer, BindingKind::SampledImage}) {
        const auto n = std::count(kinds.begin(), kinds.end(), k);
        if (n > 0) poolSizes.push_back({descriptorType(k), std::uint32_t(n * kSetsPerSubmit)});
    }
    VkDescriptorPoolCreateInfo poolInfo{};
    poolInfo.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    poolInfo.maxSets = kSetsPerSubmit;
    poolInfo.poolSizeCount = std::uint32_t(poolSizes.size());
    poolInfo.pPoolSizes = poolSizes.data();
    pool_ = create(context, vkCreateDescriptorPool, poolInfo, vkDestroyDescriptorPool,
                   "creating " + what + "'s descriptors");
    VkDescriptorSetAllocateInfo allocInfo{};
    allocInfo.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    allocInfo.descriptorPool = pool_.get();
    const std::vector<VkDescriptorSetLayout> setLayouts(kSetsPerSubmit, setLayout);
    allocInfo.descriptorSetCount = kSetsPerSubmit;
    allocInfo.pSetLayouts = setLayouts.data();
    context.check(vkAllocateDescriptorSets(device, &allocInfo, sets_), "allocating " + what + "'s descriptors");
}

void ComputePipeline::dispatch(VkCommandBuffer cmd, std::initializer_list<Resource> resources,
                               const void* pushConstants, std::uint32_t pushBytes, std::uint32_t groupsX,
                               std::uint32_t groupsY) {
    // The shader's declared layout, checked at creation, is what is bound here.
    assert(resources.size() == kinds_.size() && pushBytes == layout_.pushConstantBytes);
    if (used_ == kSetsPerSubmit)
        fail("shader " + name_, "more than " + std::to_string(kSetsPerSubmit) + " dispatches in one submission");
    // A storage buffer binding larger than the device's limit is invalid usage (VUID-VkWriteDescriptorSet-
    // descriptorType-00333): the shader may see a truncated buffer. Fail cleanly instead (lavapipe: 128 MiB, a
    // 4096x2736 plane of 3-float normals).
    const VkDeviceSize maxRange = context_.properties.limits.maxStorageBufferRange;
    for (const Resource& r : resources)
        if (r.buffer && r.bytes > maxRange)
            fail("Vulkan device '" + context_.info.name + "'",
                 "binds at most " + std::to_string(maxRange) + " bytes as one storage buffer (maxStorageBufferRange), "
                 "and shader " + name_ + " needs " + std::to_string(r.bytes) + ": the image is too large for it");
    // So is a group count past maxComputeWorkGroupCount (VUID-vkCmdDispatch-groupCountY-00387): the row blur's
    // one group per row, for an image 70000 rows tall, which the public functions took.
    const std::uint32_t* maxGroups = context_.properties.limits.maxComputeWorkGroupCount;
    if (groupsX > maxGroups[0] || groupsY > maxGroups[1])
        fail("Vulkan device '" + context_.info.name + "'",
             "dispatches at most " + std::to_string(maxGroups[0]) + " x " + std::to_string(maxGroups[1]) +
                 " workgroups (maxComputeWorkGroupCount), and shader " + name_ + " needs " + std::to_string(groupsX) +
                 " x " + std::to_string(groupsY) + ": the image is too large for it");
    const VkDescriptorSet set = sets_[used_++];
    std::vector<VkDescriptorBufferInfo> buffers(resources.size());
    std::vector<VkDescriptorImageInfo> images(resources.size());
    std::vector<VkWriteDescriptorSet> writes;
    std::size_t i = 0;
    for (const Resource& r : resources) {
        VkWriteDescriptorSet w{};
        w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        w.dstSet = set;
        w.dstBinding = std::uint32_t(i);
        w.descriptorCount = 1;
        w.descriptorType = descriptorType(kinds_[i]);
        if (kinds_[i] == BindingKind::SampledImage) {
            assert(r.texture);
            images[i] = {r.texture->sampler(), r.texture->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            w.pImageInfo = &images[i];
        } else {
            assert(r.buffer);
            buffers[i] = {r.buffer->handle(), r.offset, r.bytes};
            w.pBufferInfo = &buffers[i];
        }
        writes.push_back(w);
        ++i;
    }
    vkUpdateDescriptorSets(context_.device, std::uint32_t(writes.size()), writes.data(), 0, nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_.get(), 0, 1, &set, 0, nullptr);
    if (pushBytes > 0)
        vkCmdPushConstants(cmd, pipelineLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes, pushConstants);
    vkCmdDispatch(cmd, groupsX, groupsY, 1);
    ++dispatches_;
}

void ComputePipeline::dispatchGrid(VkCommandBuffer cmd, std::initializer_list<Resource> resources,
                                   const void* pushConstants, std::uint32_t pushBytes, int width, int height) {
    dispatch(cmd, resources, pushConstants, pushBytes, (std::uint32_t(width) + layout_.localSize[0] - 1) / layout_.localSize[0],
             (std::uint32_t(height) + layout_.localSize[1] - 1) / layout_.localSize[1]);
}

} // namespace obscura::gpu
