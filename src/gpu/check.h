// VkResult -> obscura::Error, with the message every GPU error gives: the device, what was being done, and the
// problem in words a user can act on.
#pragma once

#include "gpu/vulkan.h"

#include <string>

namespace obscura::gpu {

// Throws obscura::Error("Vulkan device '<device>': <doing>: <problem> (<VK_ERROR_...>)") unless r is
// VK_SUCCESS; "Vulkan: ..." when there is no device yet (device empty).
void check(VkResult r, const std::string& device, const std::string& doing);

} // namespace obscura::gpu
