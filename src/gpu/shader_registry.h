// The embedded shaders by name (the generated shaders/registry.cpp lists every src/gpu/shaders/*.comp).
#pragma once

#include "gpu/spirv.h"

#include <string>
#include <utility>
#include <vector>

namespace obscura::gpu {

const std::vector<std::pair<std::string, const Spirv*>>& shaderRegistry();

} // namespace obscura::gpu
