// The separable cross-bilateral blur on GPU-resident buffers, for callers that chain passes in one submission
// (the public gpu::bilateralFilter uploads, records this and downloads).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "shaders/layouts.h"

#include "obscura/bilateral.h"
#include "obscura/gpu_shaders.h"  // SeparableBilateral

#include <vector>

namespace obscura::gpu {

// Storage buffers of bilateral_separable.comp (shaders/layouts.h states their contents).
struct SeparableBilateralBuffers {
    const Buffer& depth;       // width * height linear depths
    const Buffer& normal;      // width * height * 3 view normals
    const Buffer& logSpatial;  // SeparableBilateral::logSpatial
    const Buffer& input;       // width * height AO
    const Buffer& scratch;     // width * height floats: the horizontal pass's result
    const Buffer& output;      // width * height AO
    bool packedNormals = false;  // `normal` holds one octahedral word per pixel (kBilateralSpecPackedNormals 1)
};

// How the two passes are dispatched: bilateral_separable.comp twice with a barrier between them, or
// bilateral_tiled.comp once (both passes per tile from shared memory; radius <= kBilateralTiledMaxRadius).
// The same bits either way.
enum class BlurDispatch { TwoPasses, Tiled };
// Its dispatches, each reading the guide and the values and writing values: what a byte count multiplies.
inline int blurDispatchCount(BlurDispatch d) { return d == BlurDispatch::Tiled ? 1 : 2; }

// Records the blur. The inputs must be visible to compute shaders (the caller's barrier); the settings were
// checked by ssao::checkBilateralInputs. BlurDispatch::Tiled with a larger radius throws obscura::Error;
// buffers.scratch is then unused.
void recordSeparableBilateral(Context::Impl& context, VkCommandBuffer cmd, const SeparableBilateralBuffers& buffers,
                              const SeparableBilateral& filter, BlurDispatch dispatch = BlurDispatch::TwoPasses);
// One of them: axis 0 (horizontal) or 1 (vertical), from `input` to `output` (buffers.scratch unused).
void recordSeparableBilateralAxis(Context::Impl& context, VkCommandBuffer cmd, const SeparableBilateralBuffers& buffers,
                                  const SeparableBilateral& filter, int axis);

} // namespace obscura::gpu
