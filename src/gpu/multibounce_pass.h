// Multi-bounce AO on GPU-resident buffers, for callers that chain passes in one submission (the public
// gpu::multiBounce uploads, records this and downloads).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "shaders/lighting_layouts.h"

namespace obscura::gpu {

// Storage buffers of multibounce.comp (shaders/lighting_layouts.h states their contents).
struct MultiBounceBuffers {
    const Buffer& depth;       // width * height linear depths
    const Buffer& visibility;  // width * height visibility
    const Buffer& albedo;      // width * height * 3 albedo
    const Buffer& output;      // width * height * 3 G(A, albedo)
};

// Records the dispatch; the inputs must be visible to compute shaders (the caller's barrier).
void recordMultiBounce(Context::Impl& context, VkCommandBuffer cmd, const MultiBounceBuffers& buffers,
                       const MultiBounceConstants& constants);

} // namespace obscura::gpu
