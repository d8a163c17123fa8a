// gpu::shaderNames and gpu::shaderCode (obscura/gpu_shaders.h) over the generated registry.
#include "gpu/shader_registry.h"

#include "obscura/error.h"
#include "obscura/gpu_shaders.h"

#include <algorithm>

namespace obscura::gpu {

std::vector<std::string> shaderNames() {
    std::vector<std::string> names;
    for (const auto& entry : shaderRegistry()) names.push_back(entry.first);
    std::sort(names.begin(), names.end());
    return names;
}

ShaderCode shaderCode(const std::string& name) {
    for (const auto& [known, code] : shaderRegistry())
        if (known == name) return {code->words, code->count};
    std::string list;
    for (const std::string& n : shaderNames()) list += (list.empty() ? "" : ", ") + n;
    fail("shader '" + name + "'", "no such shader (there are: " + list + ")");
}

} // namespace obscura::gpu
