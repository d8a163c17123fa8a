// An engine's view of Obscura's compute shaders: its own Vulkan instance, device and buffers, Obscura's
// SPIR-V (gpu::shaderCode), layouts (layouts.h, prep_layouts.h) and constants functions, and nothing of
// gpu::Context. One frame: device depth + world normals -> prepare_depth -> gtao -> the separable blur's
// two passes, recorded in one command buffer with a barrier between passes, then checked against the CPU
// references. docs/INTEGRATION.md walks through it.
//
// The "engine" buffers are made from a built-in scene here, to have something to render; an engine copies
// its depth attachment and normal target into such buffers (or writes them so in its G-buffer pass).
// Exit code 0 when the GPU result matches the CPU within 2e-3.
#include <obscura/bilateral.h>
#include <obscura/builtin_scenes.h>
#include <obscura/depth_prep.h>
#include <obscura/gpu_shaders.h>
#include <obscura/gtao.h>
#include <obscura/trace.h>

#include "layouts.h"
#include "prep_layouts.h"

#include <vulkan/vulkan.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

void check(VkResult r, const char* what) {
    if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(r) + ")");
}

// The engine's side: an instance, the first device with a compute queue, host-visible buffers (simple for an
// example; a renderer keeps them device-local and copies).
struct Engine {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkPhysicalDeviceMemoryProperties memory{};

    Engine() {
        VkApplicationInfo app{};
        app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
        app.apiVersion = VK_API_VERSION_1_2;
        VkInstanceCreateInfo ici{};
        ici.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
        ici.pApplicationInfo = &app;
        const char* validation = "VK_LAYER_KHRONOS_validation";
        const char* env = std::getenv("OBSCURA_VALIDATION");
        if (env && std::strcmp(env, "1") == 0) {  // any message then prints to stderr
            ici.enabledLayerCount = 1;
            ici.ppEnabledLayerNames = &validation;
        }
        check(vkCreateInstance(&ici, nullptr, &instance), "vkCreateInstance");
        uint32_t count = 0;
        vkEnumeratePhysicalDevices(instance, &count, nullptr);
        if (count == 0) throw std::runtime_error("no Vulkan device");
        std::vector<VkPhysicalDevice> devices(count);
        vkEnumeratePhysicalDevices(instance, &count, devices.data());
        physical = devices[0];
        uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, nullptr);
        std::vector<VkQueueFamilyProperties> props(families);
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, props.data());
        while (family < families && !(props[family].queueFlags & VK_QUEUE_COMPUTE_BIT)) ++family;
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo qci{};
        qci.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
        qci.queueFamilyIndex = family;
        qci.queueCount = 1;
        qci.pQueuePriorities = &priority;
        VkDeviceCreateInfo dci{};
        dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
        dci.queueCreateInfoCount = 1;
        dci.pQueueCreateInfos = &qci;
        check(vkCreateDevice(physical, &dci, nullptr, &device), "vkCreateDevice");
        vkGetDeviceQueue(device, family, 0, &queue);
        vkGetPhysicalDeviceMemoryProperties(physical, &memory);
    }
    ~Engine() {
        vkDestroyDevice(device, nullptr);
        vkDestroyInstance(instance, nullptr);
    }
};

struct HostBuffer {
    VkDevice device = VK_NULL_HANDLE;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    float* data = nullptr;
    VkDeviceSize bytes = 0;

    HostBuffer(const Engine& e, std::size_t floats) : device(e.device), bytes(floats * sizeof(float)) {
        VkBufferCreateInfo bci{};
        bci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
        bci.size = bytes;
        bci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        check(vkCreateBuffer(device, &bci, nullptr, &buffer), "vkCreateBuffer");
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(device, buffer, &req);
        const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        uint32_t type = 0;
        while (type < e.memory.memoryTypeCount &&
               !((req.memoryTypeBits >> type & 1) && (e.memory.memoryTypes[type].propertyFlags & want) == want))
            ++type;
        VkMemoryAllocateInfo mai{};
        mai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
        mai.allocationSize = req.size;
        mai.memoryTypeIndex = type;
        check(vkAllocateMemory(device, &mai, nullptr, &memory), "vkAllocateMemory");
        check(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory");
        void* mapped = nullptr;
        check(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
        data = static_cast<float*>(mapped);
    }
    ~HostBuffer() {
        vkDestroyBuffer(device, buffer, nullptr);
        vkFreeMemory(device, memory, nullptr);  // unmaps
    }
    HostBuffer(const HostBuffer&) = delete;
    HostBuffer& operator=(const HostBuffer&) = delete;
};

// One of Obscura's shaders as a pipeline: `bindings` storage buffers at set 0, bindings 0..n-1, and a
// push-constant block of `pushBytes` (the numbers in the layout headers).
struct Pass {
    VkDevice device;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    std::vector<VkDescriptorSet> sets;
    int bindings;
    uint32_t pushBytes;

    Pass(const Engine& e, const char* shader, int bindingCount, uint32_t pushConstantBytes, int dispatches)
        : device(e.device), bindings(bindingCount), pushBytes(pushConstantBytes) {
        std::vector<VkDescriptorSetLayoutBinding> b(static_cast<std::size_t>(bindingCount));
        for (int i = 0; i < bindings; ++i)
            b[std::size_t(i)] = {uint32_t(i), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
        VkDescriptorSetLayoutCreateInfo dsl{};
        dsl.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
        dsl.bindingCount = uint32_t(bindings);
        dsl.pBindings = b.data();
        check(vkCreateDescriptorSetLayout(device, &dsl, nullptr, &setLayout), "vkCreateDescriptorSetLayout");
        const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes};
        VkPipelineLayoutCreateInfo pli{};
        pli.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
        pli.setLayoutCount = 1;
        pli.pSetLayouts = &setLayout;
        pli.pushConstantRangeCount = 1;
        pli.pPushConstantRanges = &range;
        check(vkCreatePipelineLayout(device, &pli, nullptr, &layout), "vkCreatePipelineLayout");
        const obscura::gpu::ShaderCode code = obscura::gpu::shaderCode(shader);
        VkShaderModuleCreateInfo smi{};
        smi.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
        smi.codeSize = code.wordCount * 4;
        smi.pCode = code.words;
        VkShaderModule module = VK_NULL_HANDLE;
        check(vkCreateShaderModule(device, &smi, nullptr, &module), "vkCreateShaderModule");
        VkComputePipelineCreateInfo cpi{};
        cpi.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
        cpi.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
        cpi.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        cpi.stage.module = module;
        cpi.stage.pName = "main";
        cpi.layout = layout;
        check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &cpi, nullptr, &pipeline), "vkCreateComputePipelines");
        vkDestroyShaderModule(device, module, nullptr);
        const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, uint32_t(bindings * dispatches)};
        VkDescriptorPoolCreateInfo dpi{};
        dpi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
        dpi.maxSets = uint32_t(dispatches);
        dpi.poolSizeCount = 1;
        dpi.pPoolSizes = &size;
        check(vkCreateDescriptorPool(device, &dpi, nullptr, &pool), "vkCreateDescriptorPool");
        sets.resize(std::size_t(dispatches));
        const std::vector<VkDescriptorSetLayout> layouts(std::size_t(dispatches), setLayout);
        VkDescriptorSetAllocateInfo dsa{};
        dsa.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
        dsa.descriptorPool = pool;
        dsa.descriptorSetCount = uint32_t(dispatches);
        dsa.pSetLayouts = layouts.data();
        check(vkAllocateDescriptorSets(device, &dsa, sets.data()), "vkAllocateDescriptorSets");
    }
    ~Pass() {
        vkDestroyDescriptorPool(device, pool, nullptr);
        vkDestroyPipeline(device, pipeline, nullptr);
        vkDestroyPipelineLayout(device, layout, nullptr);
        vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
    }
    Pass(const Pass&) = delete;
    Pass& operator=(const Pass&) = delete;

    // Dispatch number `index` of this pass in the frame: its buffers in binding order, its constants, and
    // enough workgroups of wx x wy to cover width x height.
    void record(VkCommandBuffer cmd, int index, const std::vector<const HostBuffer*>& buffers, const void* constants,
                int width, int height, int wx, int wy) const {
        VkDescriptorSet set = sets[std::size_t(index)];
        std::vector<VkDescriptorBufferInfo> info;
        for (const HostBuffer* b : buffers) info.push_back({b->buffer, 0, VK_WHOLE_SIZE});
        std::vector<VkWriteDescriptorSet> writes(info.size(), VkWriteDescriptorSet{});
        for (std::size_t i = 0; i < info.size(); ++i) {
            writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
            writes[i].dstSet = set;
            writes[i].dstBinding = uint32_t(i);
            writes[i].descriptorCount = 1;
            writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            writes[i].pBufferInfo = &info[i];
        }
        vkUpdateDescriptorSets(device, uint32_t(writes.size()), writes.data(), 0, nullptr);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
        vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes, constants);
        vkCmdDispatch(cmd, uint32_t((width + wx - 1) / wx), uint32_t((height + wy - 1) / wy), 1);
    }
};

// Between passes: the earlier pass's writes become visible to the later pass's reads.
void barrier(VkCommandBuffer cmd, VkPipelineStageFlags dstStage = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
             VkAccessFlags dst = VK_ACCESS_SHADER_READ_BIT) {
    VkMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    b.dstAccessMask = dst;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, dstStage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

} // namespace

int main(int argc, char** argv) try {
    using namespace obscura;
    const int width = argc > 1 ? std::atoi(argv[1]) : 160, height = argc > 2 ? std::atoi(argv[2]) : 90;

    // ---- what the engine has: a camera, reversed-Z device depth and world-space normals ----
    BuiltinScene scene = makeBuiltinScene("demo");
    Camera camera = scene.camera;
    camera.width = width;
    camera.height = height;
    const GBuffer truth = trace::renderGBuffer(trace::Tracer(scene.scene), camera);
    ssao::DepthPrepSettings prep;  // reversed Z, world normals, signed
    ssao::DepthPrepConstants prepK = ssao::depthPrepConstants(prep, camera);
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    Image deviceDepth(width, height, 1), worldNormal(width, height, 3);
    const Mat4 worldFromView = camera.worldFromView();
    for (std::size_t i = 0; i < pixels; ++i) {
        deviceDepth.pixels[i] = ssao::deviceDepthFromLinear(truth.depth.pixels[i], prepK);
        const float* n = &truth.normal.pixels[3 * i];
        for (int r = 0; r < 3; ++r)
            worldNormal.pixels[3 * i + std::size_t(r)] =
                worldFromView.m[r][0] * n[0] + worldFromView.m[r][1] * n[1] + worldFromView.m[r][2] * n[2];
    }

    // ---- the constants: the functions the CPU references use ----
    prepK.normalChannels = 3;
    ssao::GtaoSettings gtaoSettings;  // the `high` preset
    gtaoSettings.radius = 0.5f;
    const ssao::GtaoConstants gtaoK = ssao::gtaoConstants(gtaoSettings, camera);
    ssao::BilateralSettings blurSettings;  // separable, radius 6
    const gpu::SeparableBilateral blur = gpu::separableBilateral(blurSettings, width, height);

    // ---- GPU objects ----
    Engine e;
    HostBuffer zBuffer(e, pixels), normalIn(e, 3 * pixels), depth(e, pixels), normal(e, 3 * pixels);
    HostBuffer visibility(e, pixels), bent(e, 3 * pixels), spatial(e, blur.logSpatial.size()), scratch(e, pixels),
        ao(e, pixels);
    // Planar samples read no depth MIP chain, but its binding needs a buffer. With GtaoSampling::Mip or PlanarMip it holds
    // gtaoMipOffset(width, height, mipLevels + 1) floats that gtao_mips.comp writes from `depth` first.
    HostBuffer noChain(e, 4);
    std::memcpy(zBuffer.data, deviceDepth.pixels.data(), zBuffer.bytes);
    std::memcpy(normalIn.data, worldNormal.pixels.data(), normalIn.bytes);
    std::memcpy(spatial.data, blur.logSpatial.data(), spatial.bytes);
    using namespace obscura::gpu;
    const Pass prepare(e, "prepare_depth", kPrepBindingCount, kPrepPushConstantBytes, 1);
    // No specialization: gtao.comp's defaults are the default settings' modes (planar samples, cosine weighting,
    // no thickness, column rule) and bent normals on. Other settings set kGtaoSpecSampling ... BeyondRadius
    // from gtaoK's fields (layouts.h).
    const Pass gtao(e, "gtao", kGtaoBindingCount, kGtaoPushConstantBytes, 1);
    // bilateral_separable's kBilateralSpecUnrolled keeps its default 0 here, the tap loop; an engine sets it to
    // bilateralSpecUnrolled(radius, useNormal), 1 at this radius 6, for the unrolled taps (the same bits, the
    // blur 7-9% faster on an H100, docs/PERFORMANCE.md).
    const Pass bilateral(e, "bilateral_separable", kBilateralBindingCount, kBilateralPushConstantBytes, 2);

    VkCommandPoolCreateInfo cpi{};

    cpi.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    cpi.queueFamilyIndex = e.family;
    VkCommandPool commandPool;
    check(vkCreateCommandPool(e.device, &cpi, nullptr, &commandPool), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo cba{};
    cba.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    cba.commandPool = commandPool;
    cba.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cba.commandBufferCount = 1;
    VkCommandBuffer cmd;
    check(vkAllocateCommandBuffers(e.device, &cba, &cmd), "vkAllocateCommandBuffers");
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");

    // ---- one frame: the bindings in each layout header's order ----
    prepare.record(cmd, 0, {&zBuffer, &normalIn, &depth, &normal}, &prepK, width, height, ssao::kDepthPrepWorkgroupX,
                   ssao::kDepthPrepWorkgroupY);
    barrier(cmd);
    gtao.record(cmd, 0, {&depth, &normal, &visibility, &bent, &noChain}, &gtaoK, width, height, kGtaoWorkgroupX, kGtaoWorkgroupY);
    barrier(cmd);
    BilateralConstants k = blur.constants;
    k.axis = 0;
    // Each pass covers its own tile per workgroup (layouts.h): a row of pixels, then columns.
    bilateral.record(cmd, 0, {&depth, &normal, &spatial, &visibility, &scratch}, &k, width, height,
                     kBilateralHorizontalTileX, kBilateralHorizontalTileY);
    barrier(cmd);
    k.axis = 1;
    bilateral.record(cmd, 1, {&depth, &normal, &spatial, &scratch, &ao}, &k, width, height, kBilateralVerticalTileX,
                     kBilateralVerticalTileY);
    barrier(cmd, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);  // the host reads the result
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    check(vkQueueSubmit(e.queue, 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit");
    check(vkQueueWaitIdle(e.queue), "vkQueueWaitIdle");
    vkDestroyCommandPool(e.device, commandPool, nullptr);

    // ---- the same frame on the CPU ----
    const GBuffer prepared = ssao::prepareGBuffer(deviceDepth, worldNormal, camera, prep);
    const Image cpu = ssao::bilateralFilter(ssao::computeGtao(prepared, gtaoK).visibility, prepared, blurSettings);
    float worst = 0.0f;
    double mean = 0.0;
    for (std::size_t i = 0; i < pixels; ++i) {
        worst = std::max(worst, std::fabs(cpu.pixels[i] - ao.data[i]));
        mean += double(ao.data[i]);
    }
    std::printf("%dx%d: mean AO %.4f, max |GPU - CPU| %.2g\n", width, height, mean / double(pixels), double(worst));
    return worst <= 2e-3f ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "gpu_integration: %s\n", e.what());
    return 1;
}
