// Depth and normal preparation on the GPU: ssao::prepareGBuffer (obscura/depth_prep.h) as compute passes,
// the first passes an engine runs on its own depth and normal buffers (docs/INTEGRATION.md).
#pragma once

#include "obscura/depth_prep.h"
#include "obscura/gpu.h"

#include <string>

namespace obscura::gpu {

// ssao::prepareGBuffer on the GPU: the same settings, checks, messages and output (depth and normal; no
// albedo), equal to the CPU's to within GPU rounding (tests/gpu bound it).
GBuffer prepareGBuffer(Context& context, const Image& deviceDepth, const Image& normals, const Camera& camera,
                       const ssao::DepthPrepSettings& settings, const std::string& what = "depth buffer");

} // namespace obscura::gpu
