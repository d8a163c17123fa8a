// The 2-D cross-bilateral blur on GPU-resident buffers, for callers that chain passes in one submission
// (gpu::bilateralFilter with BlurMode::TwoD uploads, records this and downloads).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "shaders/layouts.h"
#include "shaders/lighting_layouts.h"

#include "obscura/bilateral.h"
#include "obscura/gbuffer.h"
#include "obscura/image.h"

namespace obscura::gpu {

// Storage buffers of bilateral_2d.comp (shaders/layouts.h and lighting_layouts.h state their contents).
struct Bilateral2DBuffers {
    const Buffer& depth;   // width * height linear depths
    const Buffer& normal;  // width * height * 3 view normals
    const Buffer& kernel;  // ssao::gaussianHalfKernel(radius)
    const Buffer& input;   // width * height AO
    const Buffer& output;  // width * height AO
    bool packedNormals = false;  // `normal` holds one octahedral word per pixel (kBilateralSpecPackedNormals 1)
};

// Records the dispatch; the inputs must be visible to compute shaders (the caller's barrier); the settings
// were checked by ssao::checkBilateralInputs.
void recordBilateral2D(Context::Impl& context, VkCommandBuffer cmd, const Bilateral2DBuffers& buffers,
                       const BilateralConstants& constants);

// ssao::bilateral2D on the GPU, inputs checked by the caller (gpu::bilateralFilter).
Image bilateral2D(Context::Impl& context, const Image& ao, const GBuffer& gbuffer,
                  const ssao::BilateralSettings& settings);

} // namespace obscura::gpu
