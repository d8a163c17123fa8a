// Headless Vulkan compute context: instance (with validation on request), device choice, one compute queue,
// a command buffer, a fence and timestamp queries. After SaschaWillems' computeheadless example.
#include "gpu/context.h"
#include "gpu/check.h"
#include "gpu/compute_pipeline.h"
#include "gpu/spirv.h"

#include "obscura/error.h"

#include <charconv>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string_view>

namespace obscura::gpu {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// Unset, empty or "0": off; "1": on. Anything else is refused: "true" once left the layers off without a word.
bool envFlag(const char* name) {
    const char* v = std::getenv(name);
    if (!v || *v == '\0' || std::strcmp(v, "0") == 0) return false;
    if (std::strcmp(v, "1") == 0) return true;
    fail(name, std::string("must be 0 or 1, got '") + v + "'");
}

VKAPI_ATTR VkBool32 VKAPI_CALL recordMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* impl = static_cast<Context::Impl*>(user);
    const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    std::string text = std::string(level) + ": " + (data->pMessageIdName ? data->pMessageIdName : "?") + ": " +
                       (data->pMessage ? data->pMessage : "");
    std::lock_guard lock(impl->messagesMutex);
    impl->messages.push_back(std::move(text));
    return VK_FALSE;  // never abort the call: the message is the finding
}

bool hasDeviceExtension(VkPhysicalDevice physical, const char* name) {
    std::uint32_t n = 0;
    if (vkEnumerateDeviceExtensionProperties(physical, nullptr, &n, nullptr) != VK_SUCCESS) return false;
    std::vector<VkExtensionProperties> extensions(n);
    if (vkEnumerateDeviceExtensionProperties(physical, nullptr, &n, extensions.data()) < VK_SUCCESS) return false;
    for (std::uint32_t i = 0; i < n; ++i)
        if (std::strcmp(extensions[i].extensionName, name) == 0) return true;
    return false;
}

bool hasLayer(const char* name) {
    std::uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
    std::uint32_t n = 0;
    if (vkEnumeratePhysicalDevices(instance, &n, nullptr) != VK_SUCCESS) return {};
    std::vector<VkPhysicalDevice> devices(n);
    if (vkEnumeratePhysicalDevices(instance, &n, devices.data()) < VK_SUCCESS) return {};
    devices.resize(n);
    return devices;
}

VkInstance createInstance(bool validation, const VkDebugUtilsMessengerCreateInfoEXT* messenger) {
    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "obscura";
    app.pEngineName = "obscura";
    app.apiVersion = VK_API_VERSION_1_2;
    VkInstanceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    info.pApplicationInfo = &app;
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    // Synchronization validation catches a missing barrier, the bug the default checks miss in compute code.
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{};
    features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    if (validation) {
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = &kValidationLayer;
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &extension;
        // Chained messenger: also reports on vkCreateInstance and vkDestroyInstance themselves.
        features.pNext = messenger;
        info.pNext = &features;
    }
    VkInstance instance = VK_NULL_HANDLE;
    const VkResult r = vkCreateInstance(&info, nullptr, &instance);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
        fail("Vulkan", "no Vulkan 1.2 driver (on Debian install mesa-vulkan-drivers for the CPU driver lavapipe)");
    if (r == VK_ERROR_LAYER_NOT_PRESENT || r == VK_ERROR_EXTENSION_NOT_PRESENT)
        fail("Vulkan", "validation asked for but VK_LAYER_KHRONOS_validation is not installed "
                       "(on Debian: vulkan-validationlayers)");
    check(r, "", "creating the Vulkan instance");
    return instance;
}

int chooseDevice(const std::vector<VkPhysicalDevice>& devices, int asked, const std::string& askedName) {
    const int count = int(devices.size());
    std::string from = askedName;
    if (asked < -1) fail(from, "must be a device index >= 0, or -1 for the default device, not " + std::to_string(asked));
    if (asked < 0)
        if (const char* env = std::getenv("OBSCURA_GPU_DEVICE"); env && *env) {
            // The whole value, digits only, as --gpu-device takes it: strtol let " 0" and "+0" through but not "0 ".
            // -1 asks for the default device, as it does on the command line.
            const std::string_view text(env);
            int v = -2;
            const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), v);
            from = "OBSCURA_GPU_DEVICE";
            // Not `count` as the marker of a bad value: an index equal to the count is a valid number, out of range.
            if (error != std::errc() || end != text.data() + text.size() || v < -1 || v >= 1 << 20)
                fail(from, std::string("'") + env + "' is not a device index (0, 1, ...; -1 for the default device)");
            asked = v;
        }
    if (asked >= 0) {
        if (asked >= count)
            fail(from, "device " + std::to_string(asked) + " asked for, but there are " + std::to_string(count) +
                           " Vulkan device(s)");
        return asked;
    }
    for (int i = 0; i < count; ++i) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[std::size_t(i)], &p);
        if (p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU) return i;
    }
    return 0;
}

} // namespace

int deviceCount() {
    if (!loadVulkan(nullptr)) return 0;
    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.apiVersion = VK_API_VERSION_1_2;
    VkInstanceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    info.pApplicationInfo = &app;
    VkInstance instance = VK_NULL_HANDLE;
    if (vkCreateInstance(&info, nullptr, &instance) != VK_SUCCESS) return 0;
    const int n = int(physicalDevices(instance).size());
    vkDestroyInstance(instance, nullptr);
    return n;
}

Context::Context(const ContextSettings& settings) : impl_(std::make_unique<Impl>()) {
    Impl& c = *impl_;
    std::string why;
    if (!loadVulkan(&why)) fail("Vulkan", why);
    c.validation = settings.validation || envFlag("OBSCURA_VALIDATION");
    if (const char* dir = std::getenv("OBSCURA_SHADER_DIR"); dir && *dir) {
        if (!std::filesystem::is_directory(dir)) fail(std::string("OBSCURA_SHADER_DIR ") + dir, "is not a folder");
        c.shaderDir = dir;
    }
    if (c.validation && !hasLayer(kValidationLayer))
        fail("Vulkan", "validation asked for but VK_LAYER_KHRONOS_validation is not installed "
                       "(on Debian: vulkan-validationlayers)");

    VkDebugUtilsMessengerCreateInfoEXT messenger{};
    messenger.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    messenger.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger.pfnUserCallback = recordMessage;
    messenger.pUserData = &c;
    c.instance = createInstance(c.validation, &messenger);
    if (c.validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(c.instance, "vkCreateDebugUtilsMessengerEXT"));
        c.destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(c.instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (!create || !c.destroyMessenger) fail("Vulkan", "the validation layer lacks VK_EXT_debug_utils");
        check(create(c.instance, &messenger, nullptr, &c.messenger), "", "creating the debug messenger");
    }

    const std::vector<VkPhysicalDevice> devices = physicalDevices(c.instance);
    if (devices.empty()) fail("Vulkan", "no Vulkan device (on Debian install mesa-vulkan-drivers for lavapipe)");
    const int index = chooseDevice(devices, settings.deviceIndex, settings.deviceIndexName);
    c.physical = devices[std::size_t(index)];
    vkGetPhysicalDeviceProperties(c.physical, &c.properties);
    c.info.name = c.properties.deviceName;
    c.info.index = index;
    c.info.discrete = c.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
    c.info.maxImageDimension2D = c.properties.limits.maxImageDimension2D;
    c.info.apiVersion = c.properties.apiVersion;
    if (c.properties.apiVersion < VK_API_VERSION_1_2)
        fail("Vulkan device '" + c.info.name + "'",
             "supports Vulkan " + std::to_string(VK_API_VERSION_MAJOR(c.properties.apiVersion)) + "." +
                 std::to_string(VK_API_VERSION_MINOR(c.properties.apiVersion)) + ", 1.2 needed");
    // The driver's own name and version, for benchmark records (core in Vulkan 1.2).
    VkPhysicalDeviceDriverProperties driver{};
    driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
    VkPhysicalDeviceProperties2 properties2{};
    properties2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    properties2.pNext = &driver;
    vkGetPhysicalDeviceProperties2(c.physical, &properties2);
    c.info.driver = std::string(driver.driverName) + (driver.driverInfo[0] ? std::string(" ") + driver.driverInfo : "");
    c.lavapipe = driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE;

    // A compute queue; a family with compute and no graphics is the dedicated one, so it is preferred.
    std::uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(c.physical, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(c.physical, &n, families.data());
    int family = -1;
    for (std::uint32_t i = 0; i < n; ++i) {
        if (!(families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) continue;
        if (family < 0 || !(families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT)) family = int(i);
        if (!(families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT)) break;
    }
    if (family < 0) fail("Vulkan device '" + c.info.name + "'", "has no compute queue");
    c.queueFamily = std::uint32_t(family);

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{};
    queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queue.queueFamilyIndex = c.queueFamily;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkDeviceCreateInfo deviceInfo{};
    deviceInfo.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queue;
    // Pipeline statistics only where asked: the extension and its feature must both be there.
    const char* executableProperties = VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME;
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executableFeature{};
    executableFeature.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR;
    if ((settings.pipelineStatistics || settings.pipelineInternals) &&
        hasDeviceExtension(c.physical, executableProperties)) {
        VkPhysicalDeviceFeatures2 features2{};
        features2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
        features2.pNext = &executableFeature;
        vkGetPhysicalDeviceFeatures2(c.physical, &features2);
        if (executableFeature.pipelineExecutableInfo) {
            executableFeature.pNext = nullptr;
            deviceInfo.pNext = &executableFeature;
            deviceInfo.enabledExtensionCount = 1;
            deviceInfo.ppEnabledExtensionNames = &executableProperties;
        }
    }
    c.check(vkCreateDevice(c.physical, &deviceInfo, nullptr, &c.device), "creating the device");
    vkGetDeviceQueue(c.device, c.queueFamily, 0, &c.queue);
    if (deviceInfo.enabledExtensionCount == 1) {
        ExecutableQueries& q = c.executableQueries;
        q.properties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
            vkGetDeviceProcAddr(c.device, "vkGetPipelineExecutablePropertiesKHR"));
        q.statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
            vkGetDeviceProcAddr(c.device, "vkGetPipelineExecutableStatisticsKHR"));
        q.internals = reinterpret_cast<PFN_vkGetPipelineExecutableInternalRepresentationsKHR>(
            vkGetDeviceProcAddr(c.device, "vkGetPipelineExecutableInternalRepresentationsKHR"));
        c.info.pipelineStatistics = q.properties && q.statistics && q.internals;
        c.captureInternals = c.info.pipelineStatistics && settings.pipelineInternals;
    }

    VkCommandPoolCreateInfo pool{};
    pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = c.queueFamily;
    c.check(vkCreateCommandPool(c.device, &pool, nullptr, &c.commandPool), "creating a command pool");
    VkCommandBufferAllocateInfo cmd{};
    cmd.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    cmd.commandPool = c.commandPool;
    cmd.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cmd.commandBufferCount = 1;
    c.check(vkAllocateCommandBuffers(c.device, &cmd, &c.commandBuffer), "allocating a command buffer");
    VkFenceCreateInfo fence{};
    fence.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    c.check(vkCreateFence(c.device, &fence, nullptr, &c.fence), "creating a fence");

    if (families[c.queueFamily].timestampValidBits > 0 && c.properties.limits.timestampPeriod > 0.0f) {
        VkQueryPoolCreateInfo query{};
        query.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
        query.queryType = VK_QUERY_TYPE_TIMESTAMP;
        query.queryCount = Context::Impl::kMaxTimestamps;
        c.check(vkCreateQueryPool(c.device, &query, nullptr, &c.timestamps), "creating timestamp queries");
        c.info.timestampPeriodNs = double(c.properties.limits.timestampPeriod);
        const std::uint32_t bits = families[c.queueFamily].timestampValidBits;
        c.timestampMask = timestampMask(bits);
    }
    c.allocator = std::make_unique<Allocator>(c.physical, c.device, c.info.name);
}

Context::Impl::~Impl() {
    if (device != VK_NULL_HANDLE) {
        vkDeviceWaitIdle(device);  // nothing may be in flight when its objects go
        pipelines.clear();
        allocator.reset();
        if (timestamps != VK_NULL_HANDLE) vkDestroyQueryPool(device, timestamps, nullptr);
        if (fence != VK_NULL_HANDLE) vkDestroyFence(device, fence, nullptr);
        if (commandPool != VK_NULL_HANDLE) vkDestroyCommandPool(device, commandPool, nullptr);
        vkDestroyDevice(device, nullptr);
    }
    if (messenger != VK_NULL_HANDLE) destroyMessenger(instance, messenger, nullptr);
    if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
}

void Context::Impl::check(VkResult r, const std::string& doing) const { gpu::check(r, info.name, doing); }

void Context::Impl::submit(const std::function<void(VkCommandBuffer)>& record, bool timed) {
    timing = timed && timestamps != VK_NULL_HANDLE;
    markNames.clear();
    for (auto& [name, p] : pipelines) p->beginCommands();
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(commandBuffer, &begin), "recording commands");
    if (timing) {
        vkCmdResetQueryPool(commandBuffer, timestamps, 0, kMaxTimestamps);
        vkCmdWriteTimestamp(commandBuffer, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps, 0);
    }
    try {
        record(commandBuffer);
    } catch (...) {
        timing = false;
        vkEndCommandBuffer(commandBuffer);  // out of the recording state, so the next submit can begin again
        throw;
    }
    const std::uint32_t last = std::uint32_t(markNames.size()) + 1;
    if (timing) vkCmdWriteTimestamp(commandBuffer, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, last);
    const bool timedHere = timing;
    timing = false;
    check(vkEndCommandBuffer(commandBuffer), "recording commands");
    VkSubmitInfo work{};
    work.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    work.commandBufferCount = 1;
    work.pCommandBuffers = &commandBuffer;
    check(vkResetFences(device, 1, &fence), "resetting a fence");
    check(vkQueueSubmit(queue, 1, &work, fence), "submitting commands");
    check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "waiting for the GPU");
    if (timedHere) {
        std::uint64_t ticks[kMaxTimestamps] = {};
        check(vkGetQueryPoolResults(device, timestamps, 0, last + 1, sizeof ticks, ticks, sizeof ticks[0],
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              "reading timestamps");
        const auto ms = [&](std::uint32_t from, std::uint32_t to) {
            return timestampDeltaMs(ticks[from], ticks[to], timestampMask, info.timestampPeriodNs);
        };
        lastPassMs = ms(0, last);
        lastMarks.clear();
        for (std::uint32_t i = 0; i < markNames.size(); ++i) lastMarks.emplace_back(markNames[i], ms(i, i + 1));
    }
}

void Context::Impl::mark(VkCommandBuffer cmd, const std::string& name) {
    if (!timing || markNames.size() + 2 >= kMaxTimestamps) return;
    markNames.push_back(name);
    // BOTTOM_OF_PIPE: the timestamp is written once every earlier command has completed.
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, std::uint32_t(markNames.size()));
}

Spirv Context::Impl::shaderCode(const std::string& name, const Spirv& embedded) {
    if (shaderDir.empty()) return embedded;
    const std::filesystem::path file = std::filesystem::path(shaderDir) / (name + ".spv");
    auto known = shaderFiles.find(name);
    if (known == shaderFiles.end()) {
        if (!std::filesystem::exists(file)) return embedded;
        std::ifstream in(file, std::ios::binary);
        const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        if (!in.good() && !in.eof()) fail(file.string(), "cannot be read");
        if (bytes.size() < 20 || bytes.size() % 4 != 0)
            fail(file.string(), "is not SPIR-V (" + std::to_string(bytes.size()) + " bytes, not a whole number of words)");
        std::vector<std::uint32_t> words(bytes.size() / 4);
        std::memcpy(words.data(), bytes.data(), bytes.size());
        if (words[0] != 0x07230203u) fail(file.string(), "is not SPIR-V (no magic number)");
        // Read once here, so a malformed module is named by its file, not only as "SPIR-V".
        try {
            reflect({words.data(), words.size()});
        } catch (const Error& e) {
            fail(file.string(), std::string("is not a module the host can read (") + e.what() + ")");
        }
        known = shaderFiles.emplace(name, std::move(words)).first;
    }
    return Spirv{known->second.data(), known->second.size()};
}

ComputePipeline& Context::Impl::pipeline(const std::string& name, const Spirv& code, int bindings,
                                         std::uint32_t pushConstantBytes, int workgroupX, int workgroupY) {
    // Inserted only once built: a constructor that throws (a layout check, a device's workgroup limit) once left a
    // null entry that the next submit() dereferenced.
    if (auto known = pipelines.find(name); known != pipelines.end()) return *known->second;
    auto built = std::make_unique<ComputePipeline>(*this, shaderCode(name, code), name, bindings, pushConstantBytes,
                                                   workgroupX, workgroupY);
    return *pipelines.emplace(name, std::move(built)).first->second;
}

ComputePipeline& Context::Impl::pipeline(const std::string& name, const Spirv& code,
                                         const std::vector<BindingKind>& bindings, std::uint32_t pushConstantBytes,
                                         int workgroupX, int workgroupY, const std::vector<std::int32_t>& specialization) {
    std::string key = name;  // name<v0,v1,...>
    for (std::size_t i = 0; i < specialization.size(); ++i) {
        key.push_back(i == 0 ? '<' : ',');
        key.append(std::to_string(specialization[i]));
    }
    if (!specialization.empty()) key.push_back('>');
    if (auto known = pipelines.find(key); known != pipelines.end()) return *known->second;  // inserted once built
    auto built = std::make_unique<ComputePipeline>(*this, shaderCode(name, code), key, bindings, pushConstantBytes,
                                                   workgroupX, workgroupY, specialization);
    return *pipelines.emplace(key, std::move(built)).first->second;
}

ComputePipeline& Context::Impl::pipelineOfShadersSize(const std::string& name, const Spirv& code,
                                                      const std::vector<BindingKind>& bindings,
                                                      std::uint32_t pushConstantBytes,
                                                      const std::vector<std::int32_t>& specialization) {
    return pipeline(name, code, bindings, pushConstantBytes, ComputePipeline::kShadersOwnSize,
                    ComputePipeline::kShadersOwnSize, specialization);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags src, VkPipelineStageFlags dstStage,
                   VkAccessFlags dst) {
    VkMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    b.srcAccessMask = src;
    b.dstAccessMask = dst;
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

void computeBarrier(VkCommandBuffer cmd) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

Context::~Context() = default;
Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;

const DeviceInfo& Context::device() const { return impl_->info; }
bool Context::validation() const { return impl_->validation; }
std::vector<std::string> Context::validationMessages() const {
    std::lock_guard lock(impl_->messagesMutex);
    return impl_->messages;
}
double Context::lastPassMs() const { return impl_->lastPassMs; }
std::vector<PipelineReport> Context::pipelineReports() const {
    std::vector<PipelineReport> reports;
    if (!impl_->info.pipelineStatistics) return reports;
    for (const auto& [name, p] : impl_->pipelines) reports.push_back({name, p->executables(), p->describeError()});
    return reports;
}

} // namespace obscura::gpu
