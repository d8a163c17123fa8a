// The GTAO main pass on GPU-resident buffers, for callers that chain passes in one submission (the public
// gpu::computeGtao uploads, records this and downloads).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"

#include "obscura/gtao.h"

namespace obscura::gpu {

// Storage buffers of gtao.comp (shaders/layouts.h states their contents).
struct GtaoBuffers {
    const Buffer& depth;       // width * height linear depths
    const Buffer& normal;      // width * height * 3 view normals
    const Buffer& visibility;  // width * height visibility
    const Buffer& bentNormal;  // width * height * 3 view-space bent normals
};

// Records one dispatch. The inputs must be visible to compute shaders (the caller's barrier); the buffers
// were checked by ssao::checkGtaoBuffers.
void recordGtao(Context::Impl& context, VkCommandBuffer cmd, const GtaoBuffers& buffers, const ssao::GtaoConstants& k);

} // namespace obscura::gpu
