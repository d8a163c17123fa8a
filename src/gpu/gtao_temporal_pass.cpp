// Spatio-temporal GTAO as compute passes: Jimenez, Wu, Pesce and Jarabo 2016, "Practical Realtime Strategies
// for Accurate Indirect Occlusion", §4.1. The host side of ssao::GtaoTemporal (src/ssao/gtao_temporal.cpp):
// the same checks and messages, the same GTAO constants (ssao::gtaoConstants, interleaved), and the CPU
// frame's four steps as dispatches on resident buffers. Contract in include/obscura/gpu_temporal.h.
#include "gpu/gtao_temporal_pass.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gtao_pass.h"
#include "gpu/image_planes.h"
#include "gpu/spirv.h"
#include "shaders/layouts.h"

#include "obscura/error.h"
#include "obscura/gpu_temporal.h"
#include "obscura/history_packing.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstdint>
#include <string>
#include <vector>

namespace obscura::gpu {

namespace {

// Rows 0..2 of m into 12 floats, as the shader's transformPoint reads them.
void rows(const Mat4& m, float* out) {
    for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 4; ++col) out[4 * r + col] = m.m[r][col];
}

// The bytes between elements of GtaoTemporalPasses' ring of temporal constants: 256, the largest
// minStorageBufferOffsetAlignment Vulkan allows, so valid on every device. With elements 128 bytes apart
// (lavapipe's alignment is 16) the synchronization check of the validation layers (1.3.239) reports a
// write-after-read between a frame's update and the previous frame's dispatch in one submission, though their
// bound ranges do not overlap; 256 apart it reports none.
VkDeviceSize fusedConstantsStride(const Context::Impl& c) {
    static_assert(sizeof(GtaoTemporalConstants) <= 256);
    const VkDeviceSize align = c.properties.limits.minStorageBufferOffsetAlignment;
    return std::max<VkDeviceSize>(256, (sizeof(GtaoTemporalConstants) + align - 1) / align * align);
}

} // namespace

ReconstructConstants reconstructConstants(int width, int height, int guideWidth, int guideStep, float depthSigma) {
    return {width, height, guideWidth, guideStep, depthSigma, 0, 0, 0};
}

UpsampleConstants upsampleConstants(int width, int height, int lowWidth, int lowHeight, int guideWidth, int guideStep,
                                    float depthSigma) {
    return {width, height, lowWidth, lowHeight, guideWidth, guideStep, depthSigma, 0};
}

GtaoTemporalConstants gtaoTemporalConstants(const ssao::GtaoTemporalSettings& t, const Camera& current,
                                            const Camera& previous, bool useHistory) {
    assert(!useHistory || (previous.width == current.width && previous.height == current.height));
    GtaoTemporalConstants k{};
    k.width = current.width;
    k.height = current.height;
    k.maxHistory = useHistory ? float(t.maxHistory) : 0.0f;
    k.tanHalfFovY = current.tanHalfFovY();
    k.aspect = current.aspect();
    k.previousTanHalfFovY = previous.tanHalfFovY();
    k.rejectDepth = t.rejectDepth;
    k.rejectNormalCos = t.rejectNormalCos;
    rows(current.worldFromView(), k.worldFromView);
    rows(previous.viewFromWorld(), k.previousViewFromWorld);
    return k;
}

void recordReconstruct(Context::Impl& c, VkCommandBuffer cmd, const ReconstructBuffers& b,
                       const ReconstructConstants& k, int channels, int windowPhase, bool packedNormals) {
    assert(channels == 1 || channels == 3);
    assert(windowPhase >= -1 && windowPhase <= 7);
    ComputePipeline& pipeline =
        c.pipelineOfShadersSize("reconstruct_interleaved", shaders::reconstruct_interleaved,
                                storageBuffers(kReconstructBindingCount), kReconstructPushConstantBytes,
                                {channels, windowPhase, packedNormals ? 1 : 0});
    // (kReconstructSpecChannels, WindowPhase, PackedNormals)
    // In binding order: kReconstructBindingValues, Depth, Normal, Output.
    pipeline.dispatchGrid(cmd, {&b.values, &b.depth, &b.normal, &b.output}, &k, sizeof k, k.width, k.height);
}

void recordUpsample(Context::Impl& c, VkCommandBuffer cmd, const UpsampleBuffers& b, const UpsampleConstants& k,
                    int channels, bool packedLow, bool packedOut) {
    assert(channels == 1 || channels == 3);
    assert(!packedLow || channels == 1);
    assert(!packedOut || channels == 1);
    ComputePipeline& pipeline =
        c.pipelineOfShadersSize("upsample_depth_aware", shaders::upsample_depth_aware,
                                storageBuffers(kUpsampleBindingCount), kUpsamplePushConstantBytes,
                                // kUpsampleSpecChannels, PackedLow, PackedOut, PackedNormals
                                {channels, packedLow ? 1 : 0, packedOut ? 1 : 0, b.packedNormals ? 1 : 0});
    // In binding order: kUpsampleBindingLow, LowDepth, Depth, Output, Normal.
    // One invocation per 2x2 block of full-resolution pixels (the shader's main).
    pipeline.dispatchGrid(cmd, {&b.low, &b.lowDepth, &b.depth, &b.output, &b.normal}, &k, sizeof k,
                          (k.width + 1) / 2, (k.height + 1) / 2);
}

GtaoTemporalPasses::GtaoTemporalPasses(Context::Impl& c, const ssao::GtaoSettings& settings,
                                       const ssao::GtaoTemporalSettings& temporal, int width, int height,
                                       GtaoTemporalVariant variant)
    : context_(c), settings_(settings), temporal_(temporal), width_(width), height_(height),
      step_(temporal.halfResolution ? 2 : 1), gridWidth_((width + step_ - 1) / step_),
      gridHeight_((height + step_ - 1) / step_), gridHistory_(step_ == 2 && temporal.gridHistory), variant_(variant),
      unused_(deviceFloats(c, 4)) {
    const bool bentNormals = variant.bentNormals;
    assert(width >= 1 && height >= 1);
    temporal.validate();  // cheap, and a window size or mode the shaders do not know must not reach them
    checkGridVariants(temporal, variant);
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    const std::size_t grid = std::size_t(gridWidth_) * std::size_t(gridHeight_);
    const std::size_t lattice = gridHistory_ ? grid : pixels;  // the history's
    // Fused, the raw values stay in shared memory.
    for (int set = 0; set < (variant.fused ? 0 : rawSets()); ++set) {
        rawVisibility_[set] = deviceFloats(c, grid);
        if (bentNormals) rawBent_[set] = deviceFloats(c, 3 * grid);
    }
    if (step_ == 2 && !gridHistory_) {
        visibility_ = deviceFloats(c, grid);
        if (bentNormals) bent_ = deviceFloats(c, 3 * grid);
    }
    if (bentNormals) bentView_ = deviceFloats(c, 3 * pixels);
    if (gridHistory_) {
        upsampled_ = variant.packedOutput
                         ? Buffer(c, upsamplePackedWords(width, height) * sizeof(std::uint32_t), MemoryUse::Device)
                         : deviceFloats(c, pixels);
        if (bentNormals) bentGrid_ = deviceFloats(c, 3 * grid);
    }
    depthMips_ = gtaoDepthMipsBuffer(c, width, height, ssao::gtaoDepthMipLevels(settings));
    if (variant.fused)
        temporalConstants_ = Buffer(c, ComputePipeline::kSetsPerSubmit * fusedConstantsStride(c), MemoryUse::Device);
    // Packed: one word per normal, and the length in the visibility's word (obscura/history_packing.h).
    const std::size_t vector = temporal.packedHistory ? 1 : 3;
    for (History& h : history_) {
        if (!variant.callerKeepsDepth) h.depth = deviceFloats(c, lattice);
        h.normalWorld = deviceFloats(c, vector * lattice);
        h.visibility = deviceFloats(c, lattice);
        if (bentNormals) h.bentWorld = deviceFloats(c, vector * lattice);
        if (!temporal.packedHistory) h.length = deviceFloats(c, lattice);
    }
}

void GtaoTemporalPasses::record(VkCommandBuffer cmd, const GtaoTemporalFrameInputs& in,
                                const std::function<void(const char*)>& mark) {
    assert(in.camera.width == width_ && in.camera.height == height_);
    const bool useHistory = temporal_.temporal && recorded_ > 0;
    // Checked even in release builds: without it the shader would read the 4-float placeholder as a depth
    // plane, out of bounds on the device.
    if (useHistory && variant_.callerKeepsDepth && !in.previousDepth)
        fail("gtao temporal", "callerKeepsDepth needs the previous frame's depth buffer (previousDepth) from the "
                              "second frame on");
    Context::Impl& c = context_;
    const auto stage = [&](const char* name) {
        if (mark) mark(name);
    };
    // 1. One interleaved evaluation per grid pixel, into the raw set the previous frame did not read.
    // Without bent normals, unused_ stands for every bent-normal buffer (the shaders leave those bindings alone).
    const auto bent = [&](const Buffer& b) -> const Buffer& { return variant_.bentNormals ? b : unused_; };
    const ssao::GtaoConstants k = ssao::gtaoConstants(settings_, in.camera, in.frameIndex, true);
    // With mip sampling the chain is made first, from this frame's depth. The previous frame's GTAO pass,
    // its only reader, is ordered before this by that frame's later barriers.
    if (k.mipLevels > 0) {
        recordGtaoDepthMips(c, cmd, in.depth, depthMips_, k);
        stage("mips");
        computeBarrier(cmd);  // the GTAO pass reads the chain
    }
    const GtaoTemporalConstants tk = gtaoTemporalConstants(temporal_, in.camera, previousCamera_, useHistory);
    const History& previous = history_[current_];
    const History& next = history_[1 - current_];
    // The previous depth is the history's copy, or the caller's buffer of the last frame, which unused_ stands
    // for on a first frame.
    const Buffer& previousDepth = !variant_.callerKeepsDepth ? previous.depth
                                  : useHistory                     ? *in.previousDepth
                                                                   : unused_;
    const Buffer& depthOut = variant_.callerKeepsDepth ? unused_ : next.depth;
    // Packed, the length travels in the visibility's word: unused_ stands for the length planes.
    const auto length = [&](const Buffer& b) -> const Buffer& { return temporal_.packedHistory ? unused_ : b; };
    // The reconstruction's window: with temporal.alternatingWindow, one of 4 by the frame index.
    const int phase = ssao::reconstructWindowPhase(temporal_, in.frameIndex);
    if (variant_.fused) {
        // 1., 2. and 4. in one dispatch, on the grid (gtao_temporal_fused.comp).
        recordFused(cmd, k, tk, phase,
                    {in.depth, in.normal, depthMips_, previousDepth, previous.normalWorld, previous.visibility,
                     bent(previous.bentWorld), length(previous.length), depthOut, next.normalWorld, next.visibility,
                     bent(next.bentWorld), length(next.length), bent(bentGrid_)});
    } else {
        const int rawSet = rawSets() == 2 ? 1 - current_ : 0;
        const Buffer& rawVisibility = rawVisibility_[rawSet];
        const Buffer& rawBent = bent(rawBent_[rawSet]);
        recordGtao(c, cmd, {in.depth, in.normal, rawVisibility, rawBent, depthMips_}, k, step_, variant_.bentNormals,
                   variant_.packedNormals);
        stage("gtao");
        computeBarrier(cmd);  // the next stage reads the raw values

        // 2. At half resolution, the spatial gather of the 16 pattern directions on the grid, whose depth and
        // normals are the G-buffer's at every other pixel. At full resolution the accumulation gathers them for
        // its own pixel instead, and the upsampling (3.) is the accumulation's too.
        const Buffer* grid[2] = {&rawVisibility, &rawBent};
        if (step_ == 2 && !gridHistory_) {
            const ReconstructConstants rk =
                reconstructConstants(gridWidth_, gridHeight_, width_, step_, temporal_.depthSigma);
            const bool packed = variant_.packedNormals;
            recordReconstruct(c, cmd, {rawVisibility, in.depth, in.normal, visibility_}, rk, 1, phase, packed);
            if (variant_.bentNormals)
                recordReconstruct(c, cmd, {rawBent, in.depth, in.normal, bent_}, rk, 3, phase, packed);
            stage("denoise");
            computeBarrier(cmd);  // the accumulation reads the reconstructed values
            grid[0] = &visibility_;
            grid[1] = &bent(bent_);
        }

        // 4. Reprojection and exponential accumulation into the other history set. Without temporal filtering the
        // same pass runs with no history: it writes the view bent normals and the planes a later frame would read.
        ComputePipeline& pipeline =
            c.pipelineOfShadersSize("gtao_temporal", shaders::gtao_temporal, storageBuffers(kTemporalBindingCount),
                                    kTemporalPushConstantBytes,
                                    {step_, std::bit_cast<std::int32_t>(temporal_.depthSigma),
                                     variant_.bentNormals ? 1 : 0, temporal_.packedHistory ? 1 : 0,
                                     variant_.callerKeepsDepth ? 0 : 1, gridHistory_ ? 2 : 1,
                                     step_ == 2 && !gridHistory_ ? -1 : phase, variant_.packedNormals ? 1 : 0});
        // (kTemporalSpecGridStep, DepthSigma, BentNormal, PackedHistory, DepthCopy, HistoryStep, WindowPhase: the
        // window where this pass reconstructs, else -1, so that the upsampling variant is one pipeline;
        // PackedNormals.)
        // In binding order: kTemporalBindingDepth ... kTemporalBindingBentViewOut.
        pipeline.dispatchGrid(cmd,
                              {&in.depth, &in.normal, grid[0], grid[1], &previousDepth, &previous.normalWorld,
                               &previous.visibility, &bent(previous.bentWorld), &length(previous.length), &depthOut,
                               &next.normalWorld, &next.visibility, &bent(next.bentWorld), &length(next.length),
                               &bent(gridHistory_ ? bentGrid_ : bentView_)},
                              &tk, sizeof tk, historyWidth(), historyHeight());
    }
    stage(temporal_.temporal ? "temporal" : "resolve");

    // 3., after the accumulation with the grid's history: the accumulated grid to full resolution, guided by
    // the grid's depth, which is the G-buffer's at every other pixel.
    if (gridHistory_) {
        computeBarrier(cmd);  // the upsampling reads the accumulated grid
        const UpsampleConstants uk =
            upsampleConstants(width_, height_, gridWidth_, gridHeight_, width_, step_, temporal_.depthSigma);
        recordUpsample(c, cmd, {next.visibility, in.depth, in.depth, upsampled_, in.normal}, uk, 1,
                       temporal_.packedHistory, variant_.packedOutput);
        if (variant_.bentNormals)
            recordUpsample(c, cmd, {bentGrid_, in.depth, in.depth, bentView_, in.normal, variant_.packedNormals}, uk,
                           3);
        stage("upsample");
    }

    current_ = 1 - current_;
    previousCamera_ = in.camera;
    ++recorded_;
}

void GtaoTemporalPasses::recordFused(VkCommandBuffer cmd, const ssao::GtaoConstants& k, const GtaoTemporalConstants& tk,
                                     int phase, const FusedBuffers& b) {
    // This frame's element of the constants' ring (temporalConstants_), written in the command stream; the
    // dispatch binds that element alone, so the frames of one submission each read their own, and no earlier
    // frame's dispatch read what this writes.
    const VkDeviceSize stride = fusedConstantsStride(context_);
    const VkDeviceSize offset = VkDeviceSize(recorded_ % ComputePipeline::kSetsPerSubmit) * stride;
    vkCmdUpdateBuffer(cmd, temporalConstants_.handle(), offset, sizeof tk, &tk);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    checkGtaoLoopBudget(context_, k);
    ComputePipeline& pipeline =
        context_.pipelineOfShadersSize("gtao_temporal_fused", shaders::gtao_temporal_fused,
                                       storageBuffers(kFusedBindingCount), kGtaoPushConstantBytes,
                                       {k.sampling, k.weighting, k.thicknessMode, k.beyondRadius,
                                        variant_.packedNormals ? 1 : 0, variant_.bentNormals ? 1 : 0,
                                        std::bit_cast<std::int32_t>(temporal_.depthSigma),
                                        temporal_.packedHistory ? 1 : 0, variant_.callerKeepsDepth ? 0 : 1, phase});
    // (kFusedSpecSampling ... BeyondRadius: the constants' modes, as recordGtao sets gtao.comp's; PackedNormals,
    // BentNormal, DepthSigma, PackedHistory, DepthCopy, WindowPhase.) Workgroups of the compiled shader's size
    // (kFusedWorkgroupX x kFusedWorkgroupY as embedded), which overlap by the window's side less one: each
    // accumulates fusedOutputTile pixels of the grid along each axis.
    const int tileX = fusedOutputTile(phase, int(pipeline.layout().localSize[0]));
    const int tileY = fusedOutputTile(phase, int(pipeline.layout().localSize[1]));
    // A candidate shader no wider than the window accumulates nothing: a tile of 0 divided the dispatch by zero.
    if (tileX < 1 || tileY < 1) {
        const int side = ssao::reconstructWindowSide(phase);
        fail("shader gtao_temporal_fused", "has workgroups of " + std::to_string(pipeline.layout().localSize[0]) + "x" +
                                               std::to_string(pipeline.layout().localSize[1]) + ": the " +
                                               std::to_string(side) + "x" + std::to_string(side) +
                                               " reconstruction window needs at least " + std::to_string(side) +
                                               " invocations a side");
    }
    // In binding order: kTemporalBindingDepth, Normal, kFusedBindingDepthMips, TemporalConstants, then
    // kTemporalBindingPreviousDepth ... kTemporalBindingBentViewOut.
    pipeline.dispatch(cmd, {&b.depth, &b.normal, &b.depthMips, Resource(&temporalConstants_, offset, sizeof tk),
                            &b.previousDepth, &b.previousNormalWorld, &b.previousVisibility, &b.previousBentWorld,
                            &b.previousLength, &b.depthOut, &b.normalWorldOut, &b.visibilityOut, &b.bentWorldOut,
                            &b.lengthOut, &b.bentViewOut},
                      &k, sizeof k, std::uint32_t((gridWidth_ + tileX - 1) / tileX),
                      std::uint32_t((gridHeight_ + tileY - 1) / tileY));
}

void checkGridVariants(const ssao::GtaoTemporalSettings& temporal, const GtaoTemporalVariant& variant) {
    if (temporal.halfResolution && temporal.gridHistory) return;
    if (variant.packedOutput)
        fail("gtao temporal", "packedOutput needs the grid's history (half resolution, gridHistory): there the "
                              "upsampling writes the frame's visibility");
    if (variant.fused)
        fail("gtao temporal", "the fused pass needs the grid's history (half resolution, gridHistory): it fuses "
                              "the GTAO pass and the accumulation on the grid");
}

Image unpackVisibilityPairs(const std::vector<std::uint32_t>& words, int width, int height) {
    const std::size_t rowWords = std::size_t(upsamplePackedRowWords(width));
    assert(words.size() == upsamplePackedWords(width, height));
    Image visibility(width, height, 1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::uint32_t word = words[std::size_t(y) * rowWords + std::size_t(x / 2)];
            visibility.at(x, y) = ssao::unpackUnorm16(x % 2 == 0 ? word & 0xffffu : word >> 16);
        }
    return visibility;
}

std::size_t GtaoTemporalPasses::bytesPerFrame() const {
    const std::size_t f = sizeof(float);
    const std::size_t pixels = std::size_t(width_) * std::size_t(height_);
    const std::size_t grid = std::size_t(gridWidth_) * std::size_t(gridHeight_);
    const std::size_t b = variant_.bentNormals ? 3 : 0;  // floats of a bent normal
    const std::size_t n = variant_.packedNormals ? 1 : 3;  // words of an input normal
    // GTAO: the search reads the whole depth plane, the normals of the grid pixels; writes 1 + b per grid pixel,
    // which the fused pass keeps in shared memory.
    const std::size_t raw = variant_.fused ? 0 : 1 + b;
    std::size_t bytes = f * (pixels + n * grid + raw * grid);
    // Mip sampling: the chain's pass reads depth and writes the chain, which the GTAO pass reads.
    const std::size_t chain = gtaoDepthMipsFloats(width_, height_, ssao::gtaoDepthMipLevels(settings_));
    if (chain > 0) bytes += f * (pixels + 2 * chain);
    // Half resolution: the reconstruction, 1 and b channels: values, guide depth and normals in, values out.
    if (step_ == 2 && !gridHistory_) bytes += f * grid * ((1 + 1 + n + 1) + (b > 0 ? b + 1 + n + b : 0));
    // Accumulation: the grid's 1 + b values (its depth and normals are those of the full planes at full
    // resolution, and at half resolution the upsampling reads only the depth: 1 more per grid pixel), depth,
    // normals and the history planes in; the next history planes and the view bent normals out. The
    // history: depth, world normal, visibility, world bent normal and length; packed, one word for the
    // normal, one for the bent normal if any, and the length inside the visibility's word.
    // The depth is written only where the history keeps its own copy.
    const std::size_t history = temporal_.packedHistory ? 1 + 1 + 1 + (b > 0 ? 1 : 0) : 1 + 3 + 1 + b + 1;
    const std::size_t written = history - (variant_.callerKeepsDepth ? 1 : 0);
    // The spatial mode writes the history planes but reads none (temporal_pixel.glsl returns before its loads).
    const std::size_t read = temporal_.temporal ? history : 0;
    if (gridHistory_) {
        // The accumulation on the grid: the raw values, the grid's depth and normals, the history in; the next
        // history and the grid's view bent normals out. Then the upsampling, one dispatch per plane: the grid's
        // accumulated visibility (and b bent-normal channels) with its depth and the full depth in; 1 (and b)
        // per pixel out. Fused, the raw values and the grid's depth and normals are the GTAO evaluation's.
        bytes += f * grid * ((variant_.fused ? 0 : (1 + b) + (1 + n)) + read + written + b);
        const std::size_t out =
            variant_.packedOutput ? sizeof(std::uint32_t) * upsamplePackedWords(width_, height_) : f * pixels;
        bytes += f * (grid * (1 + 1) + pixels) + out;
        if (b > 0) bytes += f * (grid * (b + 1) + pixels * (1 + b));
        return bytes;
    }
    bytes += f * (grid * (1 + b + (step_ == 2 ? 1 : 0)) + pixels * ((1 + n) + read + written + b));
    return bytes;
}

// ---- the public API: uploads, one submission, downloads ----

Image reconstructInterleaved(Context& context, const Image& values, const Image& depth, const Image& normal,
                             float depthSigma, int windowPhase) {
    const int w = values.width, h = values.height;
    ssao::checkReconstructInterleavedInputs(values, depth, normal, windowPhase);  // the CPU's checks and messages
    if (values.empty()) return values;
    Context::Impl& c = context.impl();
    const Buffer in = uploadChannels(c, values, values.channels);
    const Buffer d = uploadChannels(c, depth, 1);
    const Buffer n = uploadChannels(c, normal, 3);
    const Buffer out = deviceFloats(c, values.pixels.size());
    const ReconstructConstants k = reconstructConstants(w, h, w, 1, depthSigma);
    c.submit([&](VkCommandBuffer cmd) { recordReconstruct(c, cmd, {in, d, n, out}, k, values.channels, windowPhase); },
             true);
    Image result(w, h, values.channels);
    download(c, out, result.pixels.data(), result.pixels.size() * sizeof(float));
    return result;
}

Image upsampleDepthAware(Context& context, const Image& low, const Image& lowDepth, const GBuffer& full,
                         float depthSigma) {
    const int w = full.width(), h = full.height();
    // The CPU's checks and messages: among them that `low` is the G-buffer's grid, which the shader (clamping its
    // taps to low's size) would otherwise stretch over the image without a word.
    ssao::checkUpsampleDepthAwareInputs(low, lowDepth, full);
    if (w < 1 || h < 1) return Image(w, h, low.channels, low.channels == 1 ? 1.0f : 0.0f);  // no 0-byte buffers
    Context::Impl& c = context.impl();
    const Buffer in = uploadChannels(c, low, low.channels);
    const Buffer ld = uploadChannels(c, lowDepth, 1);
    const Buffer d = uploadChannels(c, full.depth, 1);
    const Buffer n = uploadChannels(c, full.normal, 3);
    Image result(w, h, low.channels);
    const Buffer out = deviceFloats(c, result.pixels.size());
    const UpsampleConstants k = upsampleConstants(w, h, low.width, low.height, low.width, 1, depthSigma);
    c.submit([&](VkCommandBuffer cmd) { recordUpsample(c, cmd, {in, ld, d, out, n}, k, low.channels); }, true);
    download(c, out, result.pixels.data(), result.pixels.size() * sizeof(float));
    return result;
}

namespace {

// What gpu::GtaoTemporal asks of its passes. It keeps the previous frame's upload, so the history holds no
// copy of depth.
GtaoTemporalVariant variantOf(GtaoOutputs outputs, GtaoTemporalFormats formats, GtaoTemporalDispatch dispatch) {
    return {outputs == GtaoOutputs::VisibilityAndBentNormal, /*callerKeepsDepth=*/true, formats.packedNormals,
            formats.packedOutput, dispatch == GtaoTemporalDispatch::Fused};
}

} // namespace

GtaoTemporal::GtaoTemporal(Context& context, const ssao::GtaoSettings& settings,
                           const ssao::GtaoTemporalSettings& temporal, GtaoOutputs outputs,
                           GtaoTemporalFormats formats, GtaoTemporalDispatch dispatch)
    : context_(&context.impl()), settings_(settings), temporal_(temporal), outputs_(outputs), formats_(formats),
      dispatch_(dispatch) {
    settings_.validate();
    temporal_.validate();
    checkGridVariants(temporal_, variantOf(outputs, formats, dispatch));  // before the first frame makes the passes
}

GtaoTemporal::~GtaoTemporal() = default;
GtaoTemporal::GtaoTemporal(GtaoTemporal&&) noexcept = default;
GtaoTemporal& GtaoTemporal::operator=(GtaoTemporal&&) noexcept = default;

const ssao::GtaoResult& GtaoTemporal::frame(const GBuffer& g) {
    const int w = g.width(), h = g.height();
    // ssao::GtaoTemporal::frame's checks and messages.
    g.validateDepthNormalShape("gtao temporal");
    g.validatePixels("gtao temporal");  // the CPU's check of the depths and normals; the shaders check nothing
    if (g.depth.pixelCount() > 0) g.camera.validate();  // as computeGtao: the constants' projection comes from it
    if (frame_ > 0 && (w != width_ || h != height_))
        fail("gtao temporal", "frame size changed from " + std::to_string(width_) + "x" + std::to_string(height_) +
                                  " to " + std::to_string(w) + "x" + std::to_string(h));
    const bool bentNormals = outputs_ == GtaoOutputs::VisibilityAndBentNormal;
    if (w < 1 || h < 1) {  // the CPU's answer, empty images; nothing to upload
        result_.visibility = Image(w, h, 1);
        result_.bentNormal = bentNormals ? Image(w, h, 3) : Image();
        width_ = w, height_ = h;
        ++frame_;
        return result_;
    }

    Context::Impl& c = *context_;
    // Made for the first frame rendered: a first frame that failed (a buffer past the device's range) once
    // left passes of its size behind, which the next frame of another size ran into.
    if (!passes_ || passes_->width() != w || passes_->height() != h)
        passes_ = std::make_unique<GtaoTemporalPasses>(c, settings_, temporal_, w, h,
                                                       variantOf(outputs_, formats_, dispatch_));
    const std::size_t pixels = std::size_t(w) * std::size_t(h);
    auto depth = std::make_unique<Buffer>(uploadChannels(c, g.depth, 1));
    const Buffer normal = uploadNormals(c, g.normal, formats_.packedNormals);
    c.submit([&](VkCommandBuffer cmd) { passes_->record(cmd, {*depth, normal, g.camera, frame_, previousDepth_.get()}); },
             true);
    previousDepth_ = std::move(depth);  // the submission has completed: the next frame may read it
    result_.visibility = historyPlane(false);
    result_.bentNormal = Image();
    if (bentNormals) {
        result_.bentNormal = Image(w, h, 3);
        download(c, passes_->bentNormal(), result_.bentNormal.pixels.data(), 3 * pixels * sizeof(float));
    }
    width_ = w, height_ = h;
    ++frame_;
    return result_;
}

Image GtaoTemporal::historyLength() const {
    if (!passes_) return Image();
    return historyPlane(true);
}

Image GtaoTemporal::historyPlane(bool length) const {
    Context::Impl& c = *context_;
    // The visibility has the image's size; the length the history's (the grid's with gridHistory).
    Image image = length ? Image(passes_->historyWidth(), passes_->historyHeight(), 1)
                         : Image(passes_->width(), passes_->height(), 1);
    if (!length && formats_.packedOutput) {
        const int w = passes_->width(), h = passes_->height();
        return unpackVisibilityPairs(downloadWords(c, passes_->visibility(), upsamplePackedWords(w, h)), w, h);
    }
    const bool packed = length ? passes_->packedHistory() : passes_->visibilityPacked();
    if (!packed) {
        download(c, length ? passes_->historyLength() : passes_->visibility(), image.pixels.data(),
                 image.pixels.size() * sizeof(float));
        return image;
    }
    std::vector<std::uint32_t> words(image.pixels.size());
    download(c, passes_->historyVisibility(), words.data(), words.size() * sizeof(std::uint32_t));
    for (std::size_t i = 0; i < words.size(); ++i)
        image.pixels[i] = length ? ssao::unpackLength(words[i]) : ssao::unpackVisibility(words[i]);
    return image;
}

int GtaoTemporal::framesRendered() const { return frame_; }

} // namespace obscura::gpu
