// The GTAO main pass on GPU-resident buffers, for callers that chain passes in one submission (the public
// gpu::computeGtao uploads, records this and downloads).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"

#include "obscura/gtao.h"

#include <cstddef>

namespace obscura::gpu {

// Storage buffers of gtao.comp (shaders/layouts.h states their contents).
struct GtaoBuffers {
    const Buffer& depth;       // width * height linear depths
    const Buffer& normal;      // width * height * 3 view normals
    const Buffer& visibility;  // gridWidth * gridHeight visibility
    const Buffer& bentNormal;  // gridWidth * gridHeight * 3 view-space bent normals
    const Buffer& depthMips;   // GTAO_SAMPLING_(PLANAR_)MIP: the chain recordGtaoDepthMips made from `depth`
};

// The depth MIP chain of constants with mipLevels coarse levels (0: any other sampling) for a width x height
// depth buffer: gtaoMipOffset(width, height, mipLevels + 1) floats, or with no level a 4-float buffer that
// only fills gtao.comp's binding.
Buffer gtaoDepthMipsBuffer(Context::Impl& context, int width, int height, int mipLevels);
std::size_t gtaoDepthMipsFloats(int width, int height, int mipLevels);  // 0 without levels
// Records gtao_mips.comp, which writes k.mipLevels coarse levels of `depth` (k.width x k.height) into
// `chain`; nothing when k.mipLevels is 0. The depth must be visible to compute shaders; the GTAO pass that
// reads the chain needs a barrier after this.
void recordGtaoDepthMips(Context::Impl& context, VkCommandBuffer cmd, const Buffer& depth, const Buffer& chain,
                         const ssao::GtaoConstants& k);

// Records one dispatch over the grid of ceil(width / gridStep) x ceil(height / gridStep) pixels (gridStep 1:
// the whole image; 2: the half-resolution grid of ssao::GtaoTemporal, see kGtaoSpecGridStep). The inputs
// must be visible to compute shaders (the caller's barrier); the buffers were checked by
// ssao::checkGtaoBuffers. Without bentNormal the pass writes visibility alone (kGtaoSpecBentNormal 0) and
// does not touch buffers.bentNormal, which may be any buffer. With packedNormals buffers.normal holds one
// octahedral word per pixel (kGtaoSpecPackedNormals 1, ssao::packOctahedral) instead of 3 floats.
// On lavapipe, throws obscura::Error where the GTAO pixel's loops (slices x steps, and the bitmask's sectors)
// could run past the 65535 iterations at which the driver ends every loop of an invocation without a word,
// so that the result would be silently wrong; elsewhere does nothing. recordGtao and the fused spatio-temporal
// pass call it.
void checkGtaoLoopBudget(const Context::Impl& context, const ssao::GtaoConstants& k);

void recordGtao(Context::Impl& context, VkCommandBuffer cmd, const GtaoBuffers& buffers, const ssao::GtaoConstants& k,
                int gridStep = 1, bool bentNormal = true, bool packedNormals = false);

// The bent-normal output of a pass over `pixels` pixels: 3 floats each, or without bentNormal a 4-float
// buffer that only fills the binding (the pass does not touch it; Vulkan has no empty buffers).
Buffer gtaoBentNormalBuffer(Context::Impl& context, std::size_t pixels, bool bentNormal);

} // namespace obscura::gpu
