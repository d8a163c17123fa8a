// What a driver says of a compiled pipeline, through VK_KHR_pipeline_executable_properties: its executables,
// their statistics (registers, code size, spills: whatever the driver reports, under its own names) and,
// when captured, their internal representations. The queries are function pointers so that the reading can
// be tested without a driver that offers the extension.
#pragma once

#include "gpu/vulkan.h"

#include "obscura/gpu.h"

#include <string>
#include <vector>

namespace obscura::gpu {

struct ExecutableQueries {
    PFN_vkGetPipelineExecutablePropertiesKHR properties = nullptr;
    PFN_vkGetPipelineExecutableStatisticsKHR statistics = nullptr;
    PFN_vkGetPipelineExecutableInternalRepresentationsKHR internals = nullptr;
};

// The executables of `pipeline`, made with VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR (and
// ..._INTERNAL_REPRESENTATIONS_BIT_KHR when `withInternals`). Never throws: a query the driver refuses leaves
// what was read before it, and *error says which query failed and with what result (empty when none did),
// because statistics are a report beside the work, not a reason to stop it.
std::vector<PipelineExecutable> describeExecutables(VkDevice device, VkPipeline pipeline, const ExecutableQueries& q,
                                                    bool withInternals, std::string* error);

} // namespace obscura::gpu
