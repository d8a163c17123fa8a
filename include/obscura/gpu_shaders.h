// The compute shaders as SPIR-V, for an engine that runs them on its own Vulkan device (docs/INTEGRATION.md;
// examples/gpu_integration/ does it end to end). The library's own passes use the same modules.
//
// Each shader's resources are in the layout headers next to the shaders ("layouts.h", "prep_layouts.h",
// ... on obscura::obscura's include path): storage buffers of set 0 at the stated bindings (float
// arrays, std430), one push-constant block (the pass's constants struct), and the workgroup size. The
// constants come from the same functions the CPU references use: ssao::alchemyConstants,
// ssao::gtaoConstants, ssao::depthPrepConstants, gpu::separableBilateral below.
#pragma once

#include "obscura/bilateral.h"

#include "layouts.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace obscura::gpu {

struct ShaderCode {
    const std::uint32_t* words = nullptr;  // SPIR-V 1.5 (Vulkan 1.2), entry point "main"; lives as long as the process
    std::size_t wordCount = 0;
};

// The names of the embedded shaders ("alchemy", "gtao", "prepare_depth", ...), sorted.
std::vector<std::string> shaderNames();
// One shader's SPIR-V; throws obscura::Error naming the shader and listing the known ones if there is none.
ShaderCode shaderCode(const std::string& name);

// The separable bilateral blur's push constants (axis 0: set axis to 1 for the vertical pass) and its
// spatial weights (the buffer at kBilateralBindingLogSpatial), from the CPU filter's own settings.
struct SeparableBilateral {
    BilateralConstants constants{};
    std::vector<float> logSpatial;
};
// Throws obscura::Error for settings ssao::bilateralFilter rejects.
SeparableBilateral separableBilateral(const ssao::BilateralSettings& settings, int width, int height);

} // namespace obscura::gpu
