// The Vulkan entry points libobscura calls, loaded at run time from the system loader (libvulkan.so.1)
// instead of linked: the library and the obscura CLI then start on machines without Vulkan, and a GPU pass
// reports a missing loader as an obscura::Error instead of the dynamic linker refusing to run the program.
// Internal to src/gpu; every source there includes this header instead of <vulkan/vulkan.h>.
#pragma once

#ifndef VK_NO_PROTOTYPES
#define VK_NO_PROTOTYPES
#endif
#include <vulkan/vulkan.h>

#include <string>

// Core functions, taken from the loader's exports (the loader's trampolines work for every instance and
// device). Extension functions come from vkGetInstanceProcAddr per instance (debug utils) or
// vkGetDeviceProcAddr per device (pipeline executable properties).
#define OBSCURA_VK_FUNCTIONS(X)                                                                                  \
    X(vkGetInstanceProcAddr) X(vkEnumerateInstanceVersion) X(vkEnumerateInstanceLayerProperties)              \
    X(vkEnumerateInstanceExtensionProperties) X(vkCreateInstance) X(vkDestroyInstance)                        \
    X(vkEnumeratePhysicalDevices) X(vkGetPhysicalDeviceProperties) X(vkGetPhysicalDeviceQueueFamilyProperties) \
    X(vkGetPhysicalDeviceMemoryProperties) X(vkCreateDevice) X(vkDestroyDevice) X(vkGetDeviceQueue)           \
    X(vkDeviceWaitIdle) X(vkCreateCommandPool) X(vkDestroyCommandPool) X(vkAllocateCommandBuffers)            \
    X(vkFreeCommandBuffers) X(vkBeginCommandBuffer) X(vkEndCommandBuffer) X(vkQueueSubmit) X(vkCreateFence)    \
    X(vkDestroyFence) X(vkWaitForFences) X(vkResetFences) X(vkCreateQueryPool) X(vkDestroyQueryPool)          \
    X(vkGetQueryPoolResults) X(vkCmdResetQueryPool) X(vkCmdWriteTimestamp) X(vkAllocateMemory) X(vkFreeMemory) \
    X(vkMapMemory) X(vkUnmapMemory) X(vkCreateBuffer) X(vkDestroyBuffer) X(vkGetBufferMemoryRequirements)     \
    X(vkBindBufferMemory) X(vkCmdCopyBuffer) X(vkCmdUpdateBuffer) X(vkCmdPipelineBarrier)                     \
    X(vkCreateShaderModule) X(vkDestroyShaderModule) X(vkCreateDescriptorSetLayout)                           \
    X(vkDestroyDescriptorSetLayout)                                                                           \
    X(vkCreatePipelineLayout) X(vkDestroyPipelineLayout) X(vkCreateComputePipelines) X(vkDestroyPipeline)      \
    X(vkCreateDescriptorPool) X(vkDestroyDescriptorPool) X(vkAllocateDescriptorSets) X(vkUpdateDescriptorSets) \
    X(vkCmdBindPipeline) X(vkCmdBindDescriptorSets) X(vkCmdPushConstants) X(vkCmdDispatch)                    \
    X(vkCreateImage) X(vkDestroyImage) X(vkGetImageMemoryRequirements) X(vkBindImageMemory)                   \
    X(vkCreateImageView) X(vkDestroyImageView) X(vkCreateSampler) X(vkDestroySampler)                         \
    X(vkCmdCopyBufferToImage) X(vkGetPhysicalDeviceFormatProperties) X(vkGetPhysicalDeviceProperties2)        \
    X(vkGetPhysicalDeviceFeatures2) X(vkEnumerateDeviceExtensionProperties) X(vkGetDeviceProcAddr)

namespace obscura::gpu {

#define OBSCURA_VK_DECLARE(name) extern PFN_##name name;
OBSCURA_VK_FUNCTIONS(OBSCURA_VK_DECLARE)
#undef OBSCURA_VK_DECLARE

// Opens the loader once per process and fills the pointers above. Returns false, with the reason in
// *why, when there is no loader or it lacks a core function; never throws.
bool loadVulkan(std::string* why);

// "VK_ERROR_DEVICE_LOST" etc., for messages.
const char* resultName(VkResult r);

} // namespace obscura::gpu
