// Run-time loading of the Vulkan loader (see vulkan.h for why it is not linked).
#include "gpu/vulkan.h"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>

namespace obscura::gpu {

#define OBSCURA_VK_DEFINE(name) PFN_##name name = nullptr;
OBSCURA_VK_FUNCTIONS(OBSCURA_VK_DEFINE)
#undef OBSCURA_VK_DEFINE

bool loadVulkan(std::string* why) {
    static std::once_flag once;
    static std::string failure;
    std::call_once(once, [] {
        // Never closed: the function pointers live as long as the process.
        // OBSCURA_VULKAN_LIBRARY names another loader, e.g. one carried to a machine without it installed.
        const char* asked = std::getenv("OBSCURA_VULKAN_LIBRARY");
        const std::string path = asked && *asked ? asked : "libvulkan.so.1";
        void* lib = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!lib) {
            failure = asked && *asked ? "no Vulkan loader at OBSCURA_VULKAN_LIBRARY='" + path + "'"
                                      : "no Vulkan loader (libvulkan.so.1 not found; on Debian install libvulkan1 "
                                        "and a driver such as mesa-vulkan-drivers)";
            return;
        }
        // dlsym returns void*; the loader exports each core function under its own name and type.
#define OBSCURA_VK_LOAD(name)                                                                     \
    name = reinterpret_cast<PFN_##name>(dlsym(lib, #name));                                      \
    if (!name && failure.empty()) failure = "the Vulkan loader " + path + " lacks " #name " (Vulkan 1.2 needed)";
        OBSCURA_VK_FUNCTIONS(OBSCURA_VK_LOAD)
#undef OBSCURA_VK_LOAD
    });
    if (why) *why = failure;
    return failure.empty();
}

const char* resultName(VkResult r) {
    switch (r) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_INCOMPLETE: return "VK_INCOMPLETE";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_ERROR_OUT_OF_POOL_MEMORY: return "VK_ERROR_OUT_OF_POOL_MEMORY";
    default: return "VkResult error";
    }
}

} // namespace obscura::gpu
