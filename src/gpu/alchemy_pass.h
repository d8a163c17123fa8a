// The Alchemy compute pass on GPU-resident buffers, for callers that chain passes in one submission (the
// public gpu::alchemyAO uploads, records this and downloads).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"

#include "obscura/alchemy.h"

#include <vector>

namespace obscura::gpu {

// Storage buffers of alchemy.comp (shaders/layouts.h states their contents).
struct AlchemyBuffers {
    const Buffer& depth;   // width * height linear depths of the guard-banded G-buffer
    const Buffer& normal;  // width * height * 3 view normals
    const Buffer& spiral;  // alchemySpiralOffsets(k)
    const Buffer& output;  // (width - 2 guardBand) * (height - 2 guardBand) obscurance
};

// ssao::alchemySpiral(k)'s offsets concatenated; the shader finds (count, class) by alchemySpiralAt.
std::vector<float> alchemySpiralOffsets(const ssao::AlchemyConstants& k);

// Records one dispatch. The inputs must be visible to compute shaders (the caller's barrier); k comes from
// ssao::alchemyConstants and the G-buffer was checked by ssao::validateAlchemyGBuffer.
void recordAlchemy(Context::Impl& context, VkCommandBuffer cmd, const AlchemyBuffers& buffers,
                   const ssao::AlchemyConstants& k);

} // namespace obscura::gpu
