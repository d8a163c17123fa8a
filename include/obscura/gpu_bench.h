// GPU timing of the screen-space passes: per-pass milliseconds from timestamp queries, frame after frame on
// buffers that stay on the device, so what is timed is the dispatches alone (no uploads, no host work).
// `obscura bench --gpu` prints these; docs/PERFORMANCE.md records them per device.
//
// The frames go to the GPU in submissions of GpuBenchSettings::framesPerSubmit, back to back with a full
// barrier between them, as an engine's frames follow each other: a GPU left idle between frames lowers its
// clocks. Each submission has a timestamp at its start and one after each pass (the GPU has finished every
// earlier command when it is written); a pass's time runs from the previous timestamp to its own. The
// frames rotate through the input G-buffers, so a frame's inputs are not the ones the previous frame left
// in the caches.
//
// Errors: GpuBenchSettings::validate() and benchGpuCase() throw obscura::Error naming the bad setting, case
// or buffer; Vulkan errors as in obscura/gpu.h. A device without timestamp queries fails with a message.
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/gpu.h"
#include "obscura/gtao.h"

#include <functional>
#include <string>
#include <vector>

namespace obscura::gpu {

struct GpuBenchSettings {
    int frames = 200;       // timed frames per case and size, [1, 100000]; medians over them are reported
    int warmup = 20;        // untimed frames before them (pipelines, clocks, caches), [0, 10000]
    int framesPerSubmit = 1;  // frames recorded into one submission, back to back, [1, 64]; 1 waits for each
                              // frame before recording the next, and leaves the GPU idle in between
    int alchemySamples = 12;                          // the `alchemy` case's samples per pixel, [1, 1024]
    int blurRadius = 6;  // taps on each side of the alchemy and gtao cases' separable blur, [1, 32] (6: the
                         // paper's 13 taps, what the Alchemy target names)
    int halfBlurRadius = 2;  // taps on each side of the gtao-half case's blur, on the half-resolution grid,
                             // [1, 32] (2: 5 taps, the configuration docs/QUALITY.md measured)
    bool halfBlur2D = false;  // the gtao-half case's blur as one 2-D dispatch instead of two separable ones
                              // (both by depth alone; the same error on the built-in views)
    bool blurTiled = false;   // the separable blurs of the alchemy, gtao and gtao-half cases as one dispatch
                              // (bilateral_tiled.comp: both passes per tile from shared memory, the same bits);
                              // their radii must then be <= kTiledBlurMaxRadius (obscura/gpu.h)
    ssao::GtaoQuality quality = ssao::GtaoQuality::High;  // the GTAO cases' preset (slices x steps)
    // Counts over the preset's: slices of the gtao and gtao-spatial cases (the temporal ones take
    // temporalSlices), steps of every GTAO case; jitter rotates the gtao case's slices per pixel, noise its
    // blur averages (the interleaved cases rotate by their 4x4 pattern instead). The gtao-half case takes 2
    // slices, 4 steps and the 4x4 interleave where this gives no count and no jitter.
    ssao::GtaoSliceOverride gtao;
    int temporalSlices = 1;  // slices of the `gtao-temporal` cases, [1, 64]: the paper's 1, times the 16
                             // interleave directions and 6 rotations of the history
    bool packedHistory = false;  // the temporal cases keep their history in packed words (obscura/history_packing.h)
    bool alternatingWindow = false;  // the temporal cases reconstruct with 4x4 windows alternating over 4 frames
                                     // (GtaoTemporalSettings::alternatingWindow)
    int alternatingWindowSize = 4;  // ... of 4x4 or 2x2 taps (GtaoTemporalSettings::alternatingWindowSize)
    bool callerKeepsDepth = false;  // the temporal cases read the previous frame's input depth instead of a
                                    // copy in the history (GtaoTemporalVariant::callerKeepsDepth)
    bool packedNormals = false;  // every case reads the G-buffer's normals as one octahedral word per pixel, as
                                 // an engine keeps them, instead of 3 floats (GtaoTemporalVariant::packedNormals
                                 // and its likes)
    bool packedOutput = false;  // the gtao-temporal-grid case writes its visibility as unorm16 pairs (an R16
                                // image) instead of floats (GtaoTemporalVariant::packedOutput)
    bool fusedTemporal = false;  // the gtao-temporal-grid case runs GTAO and the accumulation in one dispatch
                                 // (GtaoTemporalVariant::fused; its "temporal" pass is both, and no "gtao")
    bool bentNormals = true;  // the GTAO cases compute, filter and accumulate bent normals; false: visibility
                              // only (kGtaoSpecBentNormal 0), as an engine without bent-normal lighting runs them
    ssao::GtaoSampling sampling = ssao::GtaoSampling::Planar;  // the GTAO cases' horizon samples (GtaoSettings)
    float mipDistanceRatio = 7.0f;  // with GtaoSampling::Mip (GtaoSettings::mipDistanceRatio), [2, 64]
    float gtaoRadius = 1.0f;  // the GTAO cases' radius r, m, (0, 1e4]: with the camera it sets how far on screen
                              // the horizon samples reach (GtaoSettings::radius)
    void validate() const;   // throws obscura::Error("gpu-bench-<field>: ...")
};

struct GpuPassTime {
    std::string name;       // "alchemy", "blur", "alchemy-rows" (the estimator with the horizontal blur),
                            // "blur-columns" (the vertical blur), "gtao", "mips", "denoise", "temporal",
                            // "resolve" (gpu::GtaoTemporalPasses::record says which dispatches those time),
                            // "upsample" (gtao-half: gpu::GtaoHalfResolutionPasses::record)
    double medianMs = 0;    // median over the timed frames of this pass's GPU time
    double minMs = 0;       // its fastest frame (the passes of one frame add up to its time)
};

struct GpuBenchCase {
    std::string name;         // the case, as gpuBenchCases() lists it
    std::string description;  // one line: what the frame runs
    int width = 0, height = 0;
    int frames = 0;           // timed frames
    std::vector<GpuPassTime> passes;  // in dispatch order
    std::vector<std::string> shaders;  // the shaders its frames dispatched (src/gpu/shaders/NAME.comp), sorted:
                                       // the cases a changed shader reaches (OBSCURA_SHADER_DIR)
    double medianMs = 0;      // median over the frames of the frame's GPU time: its passes' times added up,
                              // from the timestamp before its first pass to the one after its last
    double minMs = 0;         // fastest frame
    double bytes = 0;         // compulsory memory traffic per frame: every buffer element each dispatch
                              // reads or writes, counted once per dispatch (cache reuse between neighbours
                              // is free, so the real traffic is at least this)
    double mpixelsPerSecond() const { return medianMs > 0 ? double(width) * double(height) / (medianMs * 1e3) : 0; }
    double gigabytesPerSecond() const { return medianMs > 0 ? bytes / (medianMs * 1e6) : 0; }
};

struct GpuBenchCaseInfo {
    std::string name;
    std::string description;
};
// The cases: alchemy (estimator + separable 13-tap blur), gtao (full GTAO + separable blur), gtao-spatial
// (4x4 interleaved GTAO + its reconstruction), gtao-temporal (interleaved + reconstruction + reprojected
// history), gtao-temporal-half (the same at half resolution, with the depth-aware upsample),
// gtao-temporal-grid (gtao-temporal-half with the history on the half-resolution grid, upsampled last).
std::vector<GpuBenchCaseInfo> gpuBenchCases();

// Times one case on `inputs`: G-buffers (depth and view normals; albedo unused) of one size whose cameras
// are the frames' (the temporal cases reproject between them). Frame i uses inputs[i % inputs.size()].
// Throws obscura::Error for an unknown case, no inputs, inputs of different sizes, bad settings, or a device
// without timestamps.
// progress, if set, is called after each frame with the fraction of the case's frames done.
GpuBenchCase benchGpuCase(Context& context, const std::string& name, const std::vector<GBuffer>& inputs,
                          const GpuBenchSettings& settings, const std::function<void(double)>& progress = {});

} // namespace obscura::gpu
