// GTAO at half resolution, blurred there and upsampled by depth (ssao::computeGtaoHalfResolution), on
// GPU-resident buffers, for callers that record frames themselves (a benchmark, or the public
// gpu::computeGtaoHalfResolution, which uploads, records one frame and downloads).
#pragma once

#include "gpu/bilateral_pass.h"
#include "gpu/buffer.h"
#include "gpu/context.h"

#include "obscura/camera.h"
#include "obscura/gpu_shaders.h"
#include "obscura/gtao.h"
#include "obscura/gtao_half_res.h"

#include <cstddef>
#include <functional>
#include <vector>

namespace obscura::gpu {

// The resident intermediates and outputs for one size. Made once; no allocation per frame.
class GtaoHalfResolutionPasses {
public:
    // Assumes validated settings and width, height >= 1. Without bentNormals only the visibility is computed
    // (kGtaoSpecBentNormal 0) and bentNormal() is not to be read.
    GtaoHalfResolutionPasses(Context::Impl& context, const ssao::GtaoSettings& settings,
                             const ssao::GtaoHalfResolutionSettings& half, int width, int height, bool bentNormals,
                             BlurDispatch blurDispatch = BlurDispatch::TwoPasses, bool packedNormals = false);

    // Records the frame for `camera` (of the passes' size) and frameIndex (ssao::gtaoConstants') from depth
    // (width * height) and view normals (3 floats each, or with packedNormals one octahedral word, as
    // GtaoTemporalVariant::packedNormals), visible to compute shaders, with a barrier between
    // dependent dispatches. After each stage it calls mark(stage) if set: "mips" (mip sampling only),
    // "gtao" (the grid), "blur" (both axes; none without a blur) and "upsample" (visibility, and bent
    // normals with them). A caller that reads the result, or records another frame, records a barrier first.
    void record(VkCommandBuffer cmd, const Buffer& depth, const Buffer& normal, const Camera& camera, int frameIndex,
                const std::function<void(const char*)>& mark = {});

    const Buffer& visibility() const { return visibility_; }  // width * height
    const Buffer& bentNormal() const { return bentView_; }    // width * height * 3, with bentNormals
    int gridWidth() const { return gridWidth_; }
    int gridHeight() const { return gridHeight_; }

    // Compulsory traffic of a frame, counted as GtaoTemporalPasses::bytesPerFrame counts it.
    std::size_t bytesPerFrame() const;

private:
    Context::Impl& context_;
    ssao::GtaoSettings settings_;
    ssao::GtaoHalfResolutionSettings half_;
    int width_, height_, gridWidth_, gridHeight_;
    bool bentNormals_;
    bool packedNormals_;
    SeparableBilateral blur_;          // the grid's constants, guide at a stride of 2 in the full planes
    BlurDispatch blurDispatch_;        // of the separable blur
    std::vector<float> kernel2D_;      // the 2-D blur's half kernel
    Buffer blurWeights_;               // logSpatial (separable) or the half kernel (2-D)
    Buffer rawVisibility_, rawBent_;   // grid: the GTAO pass's output
    Buffer scratch_, filtered_;        // grid: the blur's horizontal pass and its result
    Buffer depthMips_;
    Buffer visibility_, bentView_;     // full resolution
};

} // namespace obscura::gpu
