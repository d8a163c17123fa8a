// The Alchemy compute pass on GPU-resident buffers, for callers that chain passes in one submission (the
// public gpu::alchemyAO uploads, records this and downloads).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"

#include "obscura/alchemy.h"
#include "obscura/gpu_shaders.h"  // SeparableBilateral

#include <functional>
#include <vector>

namespace obscura::gpu {

// Storage buffers of alchemy.comp (shaders/layouts.h states their contents).
struct AlchemyBuffers {
    const Buffer& depth;   // width * height linear depths of the guard-banded G-buffer
    const Buffer& normal;  // width * height * 3 view normals
    const Buffer& spiral;  // alchemySpiralOffsets(k)
    const Buffer& output;  // (width - 2 guardBand) * (height - 2 guardBand) obscurance
    bool packedNormals = false;  // `normal` holds one octahedral word per pixel (kAlchemySpecPackedNormals 1)
};

// ssao::alchemySpiral(k)'s offsets concatenated; the shader finds (count, class) by alchemySpiralAt.
std::vector<float> alchemySpiralOffsets(const ssao::AlchemyConstants& k);

// Records one dispatch. The inputs must be visible to compute shaders (the caller's barrier); k comes from
// ssao::alchemyConstants and the G-buffer was checked by ssao::validateAlchemyGBuffer.
void recordAlchemy(Context::Impl& context, VkCommandBuffer cmd, const AlchemyBuffers& buffers,
                   const ssao::AlchemyConstants& k);

// Storage buffers of alchemy_blur_row.comp and of the vertical blur pass after it.
struct AlchemyBlurredBuffers {
    const Buffer& depth;       // as AlchemyBuffers: the guard-banded G-buffer's
    const Buffer& normal;
    const Buffer& spiral;
    const Buffer& blurDepth;   // out width * out height linear depths: the output grid's (depth itself when
                               // there is no guard band)
    const Buffer& logSpatial;  // SeparableBilateral::logSpatial
    const Buffer& scratch;     // out width * out height floats: the rows' result
    const Buffer& output;      // out width * out height AO, blurred both ways
    bool packedNormals = false;  // as AlchemyBuffers'
};

// Records the estimator fused with the blur's horizontal pass, a barrier, and the vertical pass: what
// recordAlchemy and recordSeparableBilateral record, in two dispatches instead of three. The filter is
// separableBilateral(settings, out width, out height) without the normal weight (asserted). After each
// dispatch it calls mark(stage) if set, so that a caller can write a timestamp: "alchemy-rows", then
// "blur-columns". rowGroupsX 0 dispatches one workgroup per segment of a row (alchemyBlurRowGroupsX); fewer
// also cover the row, each workgroup taking every segment from its index on (docs/INTEGRATION.md offers that
// to an engine), with the same result.
void recordAlchemyBlurred(Context::Impl& context, VkCommandBuffer cmd, const AlchemyBlurredBuffers& buffers,
                          const ssao::AlchemyConstants& k, const SeparableBilateral& filter,
                          const std::function<void(const char*)>& mark = {}, std::uint32_t rowGroupsX = 0);

// gpu::alchemyAOBlurred with recordAlchemyBlurred's rowGroupsX (0: one workgroup per segment, as the public
// call dispatches).
Image alchemyAOBlurredInRowGroups(Context& context, const GBuffer& gbuffer, const ssao::AlchemySettings& settings,
                                  const ssao::BilateralSettings& blur, AlchemyFormats formats,
                                  std::uint32_t rowGroupsX);

} // namespace obscura::gpu
