// Spatio-temporal GTAO (Jimenez et al. 2016, §4.1) on GPU-resident buffers, for callers that record frames
// themselves (a benchmark, or gpu::GtaoTemporal, which uploads, records one frame and downloads).
#pragma once

#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "shaders/temporal_layouts.h"

#include "obscura/camera.h"
#include "obscura/gtao.h"
#include "obscura/gtao_temporal.h"

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace obscura::gpu {

// The push constants of the two filters (fields in shaders/temporal_layouts.h); gtaoTemporalConstants, the
// accumulation's, is public (obscura/gpu_temporal.h).
ReconstructConstants reconstructConstants(int width, int height, int guideWidth, int guideStep, float depthSigma);
UpsampleConstants upsampleConstants(int width, int height, int lowWidth, int lowHeight, int guideWidth, int guideStep,
                                    float depthSigma);

// Storage buffers of reconstruct_interleaved.comp (shaders/temporal_layouts.h states their contents).
struct ReconstructBuffers {
    const Buffer& values;
    const Buffer& depth;   // guide
    const Buffer& normal;  // guide
    const Buffer& output;
};
// Records one dispatch for `channels` 1 or 3 and the window of ssao::reconstructInterleaved's windowPhase
// (-1: 5x5); the inputs must be visible to compute shaders. packedNormals: the guide normals are octahedral
// words (kReconstructSpecPackedNormals).
void recordReconstruct(Context::Impl& context, VkCommandBuffer cmd, const ReconstructBuffers& buffers,
                       const ReconstructConstants& k, int channels, int windowPhase = -1, bool packedNormals = false);

// Storage buffers of upsample_depth_aware.comp.
struct UpsampleBuffers {
    const Buffer& low;
    const Buffer& lowDepth;  // guide
    const Buffer& depth;
    const Buffer& output;
    const Buffer& normal;    // full-resolution view normals; read with 3 channels only
    bool packedNormals = false;  // `normal` holds octahedral words (kUpsampleSpecPackedNormals)
};
// packedLow: `low` holds packed visibility-and-length words (1 channel; kUpsampleSpecPackedLow). packedOut:
// `output` receives unorm16 pairs (1 channel; kUpsampleSpecPackedOut, height rows of
// upsamplePackedRowWords(width) words; unpackVisibilityPairs decodes them).
void recordUpsample(Context::Impl& context, VkCommandBuffer cmd, const UpsampleBuffers& buffers,
                    const UpsampleConstants& k, int channels, bool packedLow = false, bool packedOut = false);

// The words packedOut writes for a width x height visibility, and those words as the image.
inline std::size_t upsamplePackedWords(int width, int height) {
    return std::size_t(upsamplePackedRowWords(width)) * std::size_t(height);
}
Image unpackVisibilityPairs(const std::vector<std::uint32_t>& words, int width, int height);

// One frame's inputs, resident on the device and visible to compute shaders (the caller's barrier).
struct GtaoTemporalFrameInputs {
    const Buffer& depth;   // width * height linear depths, +inf for sky
    const Buffer& normal;  // width * height * 3 view normals (GtaoTemporalVariant::packedNormals: width * height words)
    Camera camera;         // of the passes' size
    int frameIndex;        // selects the rotation (ssao::gtaoConstants' frameIndex) and, with alternatingWindow,
                           // the reconstruction's window (ssao::reconstructWindowPhase): keep it counting
    // With GtaoTemporalVariant::callerKeepsDepth: the previous recorded frame's `depth` buffer, unchanged
    // since that frame (an engine that keeps last frame's depth, as TAA does); record() throws
    // obscura::Error without it on a frame that uses the history. Ignored otherwise.
    const Buffer* previousDepth = nullptr;
};

// Variants of the frame that move fewer bytes, each the same visibility and history length.
struct GtaoTemporalVariant {
    // false: visibility alone (kGtaoSpecBentNormal and kTemporalSpecBentNormal 0); no bent-normal buffer.
    bool bentNormals = true;
    // true: the history keeps no copy of depth (kTemporalSpecDepthCopy 0); each frame after the first reads
    // the previous frame's depth buffer from GtaoTemporalFrameInputs::previousDepth.
    bool callerKeepsDepth = false;
    // true: GtaoTemporalFrameInputs::normal holds one octahedral word per pixel (ssao::packOctahedral, as
    // gpu::packNormals of gpu/image_planes.h makes them) instead of 3 floats (kGtaoSpecPackedNormals,
    // kReconstructSpecPackedNormals and kTemporalSpecPackedNormals 1): the frame of those normals decoded
    // (ssao::unpackOctahedral).
    bool packedNormals = false;
    // true, with the grid's history (temporal.gridHistory): the upsampling writes the frame's visibility as
    // unorm16 pairs (kUpsampleSpecPackedOut; unpackVisibilityPairs decodes visibility()), half the bytes of
    // the largest plane the frame writes. The constructor throws obscura::Error without the grid's history.
    bool packedOutput = false;
    // true, with the grid's history: GTAO, the reconstruction and the accumulation in one dispatch
    // (gtao_temporal_fused.comp; temporal_layouts.h's kFused*), the same values as the two dispatches. The
    // frame then marks no "gtao" stage: "temporal" (or "resolve") is both. The constructor throws
    // obscura::Error without the grid's history.
    bool fused = false;
};

// Throws obscura::Error if the variant asks for what only the grid's history has (packedOutput, fused) without
// it: GtaoTemporalPasses' check, which gpu::GtaoTemporal makes before its first frame makes them.
void checkGridVariants(const ssao::GtaoTemporalSettings& temporal, const GtaoTemporalVariant& variant);

// The resident buffers of ssao::GtaoTemporal for one size: the frame's intermediates and two sets of history
// (depth, world normals, visibility, world bent normals, history length), written in turn: a frame reads the
// set the previous one wrote and writes the other. Made once; no allocation per frame.
class GtaoTemporalPasses {
public:
    // Assumes validated GTAO settings and width, height >= 1; validates `temporal` (throws obscura::Error).
    GtaoTemporalPasses(Context::Impl& context, const ssao::GtaoSettings& settings,
                       const ssao::GtaoTemporalSettings& temporal, int width, int height,
                       GtaoTemporalVariant variant = {});

    // Records the whole frame into cmd, with a barrier between dependent dispatches. Frames recorded back to
    // back in one command buffer need none between them: a frame's first stage touches nothing its
    // predecessor's last stage does (at half resolution it overwrites the raw values its predecessor's
    // reconstruction, or with the grid's history its accumulation, read, which that frame's barrier before its
    // accumulation, or its upsampling, already orders), and its later
    // barriers order the rest (the history it reads, the intermediates it overwrites). A caller that reads the result records its own barrier. After each stage
    // it calls mark(stage) if set, so that a caller can write a timestamp: "mips" (the depth MIP chain, with
    // mip sampling only), "gtao", "denoise" (both
    // reconstructions, half resolution only: at full resolution the accumulation reconstructs its own pixel),
    // "temporal" (the upsampling at half resolution, the reconstruction at full, and the accumulation with
    // temporal.temporal; else "resolve", the same pass without history). With temporal.gridHistory there is
    // no "denoise": "temporal" (or "resolve") reconstructs and accumulates each grid pixel, and "upsample"
    // brings the result to full resolution. The history is used from the second
    // recorded frame on (with temporal.temporal), reprojected from the previous record's camera. At most
    // ComputePipeline::kSetsPerSubmit frames per submission (each pipeline is dispatched once per frame).
    void record(VkCommandBuffer cmd, const GtaoTemporalFrameInputs& inputs,
                const std::function<void(const char*)>& mark = {});

    // The last recorded frame's result, valid once its submission completes: width * height visibility and
    // width * height * 3 view-space bent normals; and its history length (frames per element of the
    // history's lattice, historyWidth() x historyHeight()). With temporal.packedHistory the history's
    // visibility plane holds packed words of visibility and length (ssao::unpackVisibility,
    // ssao::unpackLength), historyLength() is not to be read, and visibility() is that plane unless the
    // history is the grid's (visibilityPacked()); with GtaoTemporalVariant::packedOutput it holds unorm16
    // pairs (unpackVisibilityPairs).
    const Buffer& visibility() const { return gridHistory_ ? upsampled_ : history_[current_].visibility; }
    bool visibilityPacked() const { return temporal_.packedHistory && !gridHistory_; }
    const Buffer& historyVisibility() const { return history_[current_].visibility; }
    const Buffer& bentNormal() const {
        assert(variant_.bentNormals);
        return bentView_;
    }
    const Buffer& historyLength() const {
        assert(!temporal_.packedHistory);
        return history_[current_].length;
    }
    bool packedHistory() const { return temporal_.packedHistory; }
    int framesRecorded() const { return recorded_; }
    int width() const { return width_; }
    int height() const { return height_; }
    int historyWidth() const { return gridHistory_ ? gridWidth_ : width_; }
    int historyHeight() const { return gridHistory_ ? gridHeight_ : height_; }

    // Bytes a frame's dispatches read and write: each dispatch reads each element of its input planes once
    // and writes each element of its outputs once (neighbourhood taps, the GTAO search and the bilinear
    // footprint are taken to hit in cache), with the history read as in every frame after the first. The
    // compulsory traffic, a lower bound on what reaches memory; divided by a frame's time, a bandwidth.
    std::size_t bytesPerFrame() const;

private:
    struct History {
        Buffer depth, normalWorld, visibility, bentWorld, length;
    };
    // The buffers of gtao_temporal_fused.comp but its constants: gtao_temporal.comp's of the same names
    // (kTemporalBinding*), and the MIP chain at kFusedBindingDepthMips.
    struct FusedBuffers {
        const Buffer &depth, &normal, &depthMips;
        const Buffer &previousDepth, &previousNormalWorld, &previousVisibility, &previousBentWorld, &previousLength;
        const Buffer &depthOut, &normalWorldOut, &visibilityOut, &bentWorldOut, &lengthOut, &bentViewOut;
    };
    // GtaoTemporalVariant::fused: this frame's temporal constants into the ring, then the fused dispatch.
    void recordFused(VkCommandBuffer cmd, const ssao::GtaoConstants& k, const GtaoTemporalConstants& tk, int phase,
                     const FusedBuffers& b);

    Context::Impl& context_;
    ssao::GtaoSettings settings_;
    ssao::GtaoTemporalSettings temporal_;
    int width_, height_, step_, gridWidth_, gridHeight_;
    bool gridHistory_;  // the history is the grid's (temporal.gridHistory at half resolution)
    // Grid: the GTAO pass's output. At full resolution two sets, written in turn like the history, because the
    // last stage reads them and a frame recorded right after another must not overwrite what that one reads.
    // At half resolution one: the reconstruction (or, with the grid's history, the accumulation) reads it, and
    // the barrier after that stage orders the read before the next frame's GTAO pass.
    int rawSets() const { return step_ == 2 ? 1 : 2; }
    Buffer rawVisibility_[2], rawBent_[2];
    Buffer visibility_, bent_;        // grid: reconstructed (half resolution only)
    Buffer bentView_;
    Buffer upsampled_, bentGrid_;  // with the grid's history: full-resolution visibility, grid view bent normals
    Buffer depthMips_;  // GtaoSampling::(Planar)Mip's chain of the frame's depth (a placeholder otherwise)
    History history_[2];
    GtaoTemporalVariant variant_;
    // GtaoTemporalVariant::fused: one GtaoTemporalConstants per frame of a submission, frame n in element
    // n % kSetsPerSubmit (push constants hold only the GTAO pass's). Context::Impl::submit waits for each
    // submission, and a submission holds at most kSetsPerSubmit frames, so an element is rewritten only after
    // the frame that read it has run.
    Buffer temporalConstants_;
    // Bound at the bindings a variant leaves untouched (bent normals, length planes, depth copy); never read
    // or written.
    Buffer unused_;
    int current_ = 0;  // the set the last recorded frame wrote
    int recorded_ = 0;
    Camera previousCamera_;
};

} // namespace obscura::gpu
