#include "gpu/check.h"

#include "obscura/error.h"

namespace obscura::gpu {

void check(VkResult r, const std::string& device, const std::string& doing) {
    if (r == VK_SUCCESS) return;
    std::string problem;
    switch (r) {
    case VK_ERROR_DEVICE_LOST:
        problem = "device lost (the driver reset the GPU or a shader faulted); make a new Context";
        break;
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: problem = "out of device memory"; break;
    case VK_ERROR_OUT_OF_HOST_MEMORY: problem = "out of host memory"; break;
    case VK_ERROR_INCOMPATIBLE_DRIVER: problem = "no compatible Vulkan driver"; break;
    default: problem = "failed"; break;
    }
    const std::string what = device.empty() ? std::string("Vulkan") : "Vulkan device '" + device + "'";
    throw Error(what + ": " + doing + ": " + problem + " (" + resultName(r) + ")");
}

} // namespace obscura::gpu
