// The depth and normal preparation passes on GPU-resident buffers, for callers that chain passes in one
// submission (the public gpu::prepareGBuffer uploads, records this and downloads).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"

#include "obscura/depth_prep.h"

namespace obscura::gpu {

// Storage buffers of prepare_depth.comp and normals_from_depth.comp (shaders/prep_layouts.h).
struct DepthPrepBuffers {
    const Buffer& deviceDepth;  // width * height device depths in [0, 1]
    const Buffer& normalIn;     // width * height * k.normalChannels normals; with FromDepth, any buffer
    const Buffer& depth;        // width * height linear depths: output
    const Buffer& normal;       // width * height * 3 view normals: output
};

// Records the preparation (and, with kNormalsFromDepth, the rebuild after a barrier). The inputs must be
// visible to compute shaders (the caller's barrier); k comes from ssao::depthPrepConstants with
// normalChannels set to the input's.
void recordDepthPrep(Context::Impl& context, VkCommandBuffer cmd, const DepthPrepBuffers& buffers,
                     const ssao::DepthPrepConstants& k);
// normals_from_depth.comp alone: view normals from a linear depth buffer (what gpu::alchemyAO runs for
// AlchemySettings::normalsFromDepth).
void recordNormalsFromDepth(Context::Impl& context, VkCommandBuffer cmd, const Buffer& depth, const Buffer& normal,
                            const ssao::DepthPrepConstants& k);

} // namespace obscura::gpu
