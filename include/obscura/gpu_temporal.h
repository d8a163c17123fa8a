// Spatio-temporal GTAO (Jimenez et al. 2016, "Practical Realtime Strategies for Accurate Indirect
// Occlusion", §4.1) as Vulkan compute passes on a gpu::Context: the mirror of obscura/gtao_temporal.h. Each
// function and GtaoTemporal take their CPU reference's inputs and settings, run its checks with the same
// messages, and return the same images to within GPU rounding (tests/gpu/gtao_temporal_gpu_test.cpp states
// and measures the bounds). The CPU's frame is four steps: the interleaved GTAO pass, the 4x4 reconstruction,
// the depth-aware upsampling at half resolution, and the reprojected accumulation. On the GPU it is two
// passes at full resolution: gtao.comp, then gtao_temporal.comp, which reconstructs its own pixel before
// accumulating; and three at half: gtao.comp on every other pixel, reconstruct_interleaved.comp on that
// grid, then gtao_temporal.comp, which upsamples its own pixel. With GtaoTemporalSettings::gridHistory
// (half resolution, the history on the grid) also three: gtao.comp on every other pixel, gtao_temporal.comp on
// the grid, which reconstructs its own grid pixel before accumulating, then upsample_depth_aware.comp. The
// filtered planes never reach memory. The
// history stays on the GPU between frames. reconstructInterleaved and upsampleDepthAware below run a filter
// as a pass of its own (reconstruct_interleaved.comp, upsample_depth_aware.comp).
//
// Errors: as in obscura/gpu.h; the CPU's errors for bad settings and buffers. reconstructInterleaved and
// upsampleDepthAware make the CPU's checks (ssao::checkReconstructInterleavedInputs,
// ssao::checkUpsampleDepthAwareInputs), with the same messages.
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/gpu.h"
#include "obscura/gtao.h"
#include "obscura/gtao_temporal.h"
#include "obscura/image.h"

#include "temporal_layouts.h"

#include <memory>

namespace obscura::gpu {

class GtaoTemporalPasses;  // src/gpu/gtao_temporal_pass.h
class Buffer;              // src/gpu/buffer.h

// ssao::reconstructInterleaved: the same checks and messages (ssao::checkReconstructInterleavedInputs):
// `values` 1 or 3 channels, `depth` 1 and `normal` 3 channels of the same size. Sky pixels keep their value.
// windowPhase as the CPU's (-1: the 5x5 window; 0..3: a 4x4 window; 4..7: a 2x2 window; other values throw
// obscura::Error).
Image reconstructInterleaved(Context& context, const Image& values, const Image& depth, const Image& normal,
                             float depthSigma, int windowPhase = -1);
// ssao::upsampleDepthAware: the same checks and messages (ssao::checkUpsampleDepthAwareInputs): `low` 1 or 3
// channels of the G-buffer's grid size and `lowDepth` of the same size; the G-buffer's depth (1 channel) and
// normal (3) of its camera's size. The output has the G-buffer's size; sky 1 (1 channel)
// or 0; a surface pixel none of whose taps is a surface gets 1, or its own normal, as on the CPU.
Image upsampleDepthAware(Context& context, const Image& low, const Image& lowDepth, const GBuffer& full,
                         float depthSigma);

// How GtaoTemporal lays out what it exchanges with its passes, as an engine may keep them (docs/INTEGRATION.md):
// each changes the result by its rounding alone.
struct GtaoTemporalFormats {
    // The G-buffer's normals uploaded as one octahedral word per pixel (two snorm16, ssao::packOctahedral)
    // instead of 3 floats: the frame of the words' decoded normals (within 1e-4 of the floats).
    bool packedNormals = false;
    // With half resolution and the grid's history (GtaoTemporalSettings::gridHistory): the frame's visibility
    // written as unorm16 (an R16 image's bytes), each value the float's rounded to 1/65535. The constructor
    // throws obscura::Error without the grid's history.
    bool packedOutput = false;
};

// How GtaoTemporal records the half-resolution frame with the grid's history: GTAO over the grid, then the
// reconstruction and accumulation of each grid pixel, as two dispatches (Separate), or as one
// (Fused: gtao_temporal_fused.comp, each workgroup evaluating GTAO for a block of the grid and accumulating its
// inner pixels; the same values). Fused needs the grid's history: the constructor throws obscura::Error
// without it.
enum class GtaoTemporalDispatch { Separate, Fused };

// ssao::GtaoTemporal on the GPU. The context must outlive it. Results differ from the CPU's by the GPU's
// trigonometry in the GTAO pass and its exp in the filters, and by what they feed through the rejection
// tests over frames. It keeps the previous frame's uploaded depth for the reprojection, as an engine with TAA
// does, so the history holds no copy of depth (the same results as with the copy).
class GtaoTemporal {
public:
    // Validates both settings (throws obscura::Error with the CPU's messages). With GtaoOutputs::Visibility
    // the passes compute, filter and accumulate visibility alone: the same visibility and history length bit
    // for bit, and frame()'s bentNormal is empty.
    GtaoTemporal(Context& context, const ssao::GtaoSettings& settings, const ssao::GtaoTemporalSettings& temporal,
                 GtaoOutputs outputs = GtaoOutputs::VisibilityAndBentNormal, GtaoTemporalFormats formats = {},
                 GtaoTemporalDispatch dispatch = GtaoTemporalDispatch::Separate);
    ~GtaoTemporal();
    GtaoTemporal(GtaoTemporal&&) noexcept;
    GtaoTemporal& operator=(GtaoTemporal&&) noexcept;

    // Uploads the G-buffer's depth and normals, runs one frame in one submission and downloads its result
    // (visibility and, unless GtaoOutputs::Visibility, view-space bent normal). The camera may move; the size
    // must stay.
    const ssao::GtaoResult& frame(const GBuffer& gbuffer);
    // Frames accumulated per pixel in the last result (downloaded on each call); empty before the first.
    // With gridHistory, per grid pixel, as ssao::GtaoTemporal::historyLength.
    Image historyLength() const;
    int framesRendered() const;

private:
    Image historyPlane(bool length) const;  // the last frame's visibility or history length, decoded if packed

    // The context's state, not the Context: that is a movable shell, and moving it (a struct holding both, moved)
    // once left this pointing at an empty one.
    Context::Impl* context_;
    ssao::GtaoSettings settings_;
    ssao::GtaoTemporalSettings temporal_;
    GtaoOutputs outputs_;
    GtaoTemporalFormats formats_;
    GtaoTemporalDispatch dispatch_;
    int frame_ = 0;
    int width_ = 0, height_ = 0;  // the frames' size, from the first frame rendered
    ssao::GtaoResult result_;
    std::unique_ptr<GtaoTemporalPasses> passes_;  // made for the first frame's size
    std::unique_ptr<Buffer> previousDepth_;       // the last frame's upload, read by the next frame
};

// The push constants of gtao_temporal.comp (temporal_layouts.h), for an engine that records the shaders
// itself: what GtaoTemporal pushes. `previous` is the last frame's camera (ignored when useHistory is false,
// as on the first frame or with temporal.temporal off), of `current`'s size. Assumes validated settings.
GtaoTemporalConstants gtaoTemporalConstants(const ssao::GtaoTemporalSettings& temporal, const Camera& current,
                                            const Camera& previous, bool useHistory);

} // namespace obscura::gpu
