// GPU timing of the screen-space passes (include/obscura/gpu_bench.h): the record functions the public
// passes use, on resident buffers, timed submissions of one or more frames with a timestamp after each pass.
#include "obscura/gpu_bench.h"

#include "gpu/alchemy_pass.h"
#include "gpu/bilateral_pass.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/gtao_half_res_pass.h"
#include "gpu/gtao_pass.h"
#include "gpu/gtao_temporal_pass.h"
#include "gpu/image_planes.h"

#include "obscura/alchemy.h"
#include "obscura/error.h"
#include "obscura/gpu_shaders.h"
#include "obscura/gtao_temporal.h"
#include "obscura/statistics.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace obscura::gpu {

namespace {

// One input G-buffer on the device: its normals as 3 floats, or as octahedral words with
// GpuBenchSettings::packedNormals (every case then tells its passes so).
struct ResidentInput {
    Buffer depth, normal;
    Camera camera;
};

// Bytes of a normal in the inputs: one octahedral word with GpuBenchSettings::packedNormals, else 3 floats.
double normalBytes(const GpuBenchSettings& s) { return s.packedNormals ? 4.0 : 12.0; }

std::string normalsText(const GpuBenchSettings& s) { return s.packedNormals ? ", octahedral normals" : ""; }


// Records frame `index` (on input `in`); calls mark(pass) after each pass.
using RecordFrame = std::function<void(VkCommandBuffer, const ResidentInput& in, int index,
                                       const std::function<void(const char*)>& mark)>;

struct CaseSetup {
    RecordFrame record;
    double bytes = 0;
    std::string description;
    std::vector<std::shared_ptr<void>> keepAlive;  // buffers and pass objects the recording uses
};

ssao::GtaoSettings gtaoSettings(const GpuBenchSettings& s) {
    ssao::GtaoSettings g;
    ssao::applyQuality(g, s.quality);
    s.gtao.apply(g);
    g.sampling = s.sampling;
    g.mipDistanceRatio = s.mipDistanceRatio;
    g.radius = s.gtaoRadius;
    return g;
}

BlurDispatch blurDispatch(const GpuBenchSettings& s) {
    return s.blurTiled ? BlurDispatch::Tiled : BlurDispatch::TwoPasses;
}
// What the descriptions add for GpuBenchSettings::blurTiled.
std::string tiledText(const GpuBenchSettings& s) { return s.blurTiled ? " (both passes in one tiled dispatch)" : ""; }

// ", r 1 m": the radius as the descriptions give it.
std::string radiusText(const ssao::GtaoSettings& g) {
    char text[32];
    std::snprintf(text, sizeof text, ", r %g m", double(g.radius));
    return text;
}

// "GTAO high" for the preset's counts, "GTAO" where --gtao-slices or --gtao-steps changed them.
std::string presetText(const GpuBenchSettings& s) {
    return s.gtao.slices != 0 || s.gtao.steps != 0 ? "GTAO" : "GTAO " + std::string(ssao::qualityName(s.quality));
}

// The cases' separable blur: the library's defaults at the settings' radius.
ssao::BilateralSettings blurSettings(const GpuBenchSettings& s) {
    ssao::BilateralSettings b;
    b.radius = s.blurRadius;
    return b;
}

// ", + separable bilateral, 13 taps per axis"
std::string blurText(const GpuBenchSettings& s) {
    return " + separable bilateral, " + std::to_string(2 * s.blurRadius + 1) + " taps per axis";
}

std::string slicesText(const ssao::GtaoSettings& g) {
    return std::to_string(g.sliceCount) + " slice" + (g.sliceCount > 1 ? "s" : "") + " x " +
           std::to_string(g.stepsPerSide) + " steps per side" + (g.jitter ? ", jittered" : "") +
           (g.interleave ? ", 4x4 interleave" : "") +
           (g.sampling == ssao::GtaoSampling::Planar ? "" : ", " + ssao::gtaoSamplingText(g));
}

// The constants hold the projection only, which the rotated inputs share (their cameras differ in position).
// fused: the estimator and the blur's horizontal pass in one dispatch (alchemy_blur_row.comp), then the
// vertical pass; otherwise three dispatches.
CaseSetup alchemyCase(Context::Impl& c, int w, int h, const GpuBenchSettings& s, const Camera& camera, bool fused) {
    ssao::AlchemySettings settings;
    settings.samples = s.alchemySamples;
    const ssao::AlchemyConstants k = ssao::alchemyConstants(settings, camera);
    const std::vector<float> offsets = alchemySpiralOffsets(k);
    const SeparableBilateral blur = separableBilateral(blurSettings(s), w, h);
    const std::size_t px = std::size_t(w) * std::size_t(h);
    auto spiral = std::make_shared<Buffer>(upload(c, offsets.data(), offsets.size() * sizeof(float)));
    auto logSpatial = std::make_shared<Buffer>(upload(c, blur.logSpatial.data(), blur.logSpatial.size() * sizeof(float)));
    auto raw = std::make_shared<Buffer>(c, px * sizeof(float), MemoryUse::Device);
    auto scratch = std::make_shared<Buffer>(c, px * sizeof(float), MemoryUse::Device);
    auto out = std::make_shared<Buffer>(c, px * sizeof(float), MemoryUse::Device);
    CaseSetup setup;
    setup.description = "Alchemy AO, " + std::to_string(s.alchemySamples) +
                        " samples/px (paper defaults, r 0.5 m)" + blurText(s) + (fused ? "" : tiledText(s)) +
                        ", depth only" +
                        (fused ? ", its horizontal pass fused into the estimator's dispatch" : "") + normalsText(s);
    setup.keepAlive = {spiral, logSpatial, raw, scratch, out};
    const bool packed = s.packedNormals;
    if (fused) {
        // Estimator + rows: depth + normal in, rows out; columns: depth + rows in, AO out.
        setup.bytes = double(px) * (4 + normalBytes(s) + 4) + double(px) * (4 + 4 + 4);
        setup.record = [&c, k, blur, spiral, logSpatial, scratch, out, packed](
                           VkCommandBuffer cmd, const ResidentInput& in, int, const std::function<void(const char*)>& mark) {
            recordAlchemyBlurred(
                c, cmd, {in.depth, in.normal, *spiral, in.depth, *logSpatial, *scratch, *out, packed}, k,
                blur, mark);
        };
        return setup;
    }
    // Estimator: depth + normal in, AO out; each blur dispatch: depth + AO in, AO out (normals unused).
    const BlurDispatch dispatch = blurDispatch(s);
    setup.bytes = double(px) * (4 + normalBytes(s) + 4) + blurDispatchCount(dispatch) * double(px) * (4 + 4 + 4);
    setup.record = [&c, k, blur, spiral, logSpatial, raw, scratch, out, dispatch, packed](
                       VkCommandBuffer cmd, const ResidentInput& in, int, const std::function<void(const char*)>& mark) {
        recordAlchemy(c, cmd, {in.depth, in.normal, *spiral, *raw, packed}, k);
        mark("alchemy");
        computeBarrier(cmd);  // the blur reads the estimator's output
        recordSeparableBilateral(c, cmd, {in.depth, in.normal, *logSpatial, *raw, *scratch, *out, packed}, blur,
                                 dispatch);
        mark("blur");
    };
    return setup;
}

CaseSetup gtaoCase(Context::Impl& c, int w, int h, const GpuBenchSettings& s, const Camera& camera) {
    const ssao::GtaoSettings settings = gtaoSettings(s);
    const ssao::GtaoConstants k = ssao::gtaoConstants(settings, camera);
    const SeparableBilateral blur = separableBilateral(blurSettings(s), w, h);
    const std::size_t px = std::size_t(w) * std::size_t(h);
    auto logSpatial = std::make_shared<Buffer>(upload(c, blur.logSpatial.data(), blur.logSpatial.size() * sizeof(float)));
    auto visibility = std::make_shared<Buffer>(c, px * sizeof(float), MemoryUse::Device);
    auto bent = std::make_shared<Buffer>(gtaoBentNormalBuffer(c, px, s.bentNormals));
    auto mips = std::make_shared<Buffer>(gtaoDepthMipsBuffer(c, w, h, k.mipLevels));
    auto scratch = std::make_shared<Buffer>(c, px * sizeof(float), MemoryUse::Device);
    auto out = std::make_shared<Buffer>(c, px * sizeof(float), MemoryUse::Device);
    CaseSetup setup;
    setup.description = presetText(s) + " (" + slicesText(settings) +
                        radiusText(settings) + "), visibility" + (s.bentNormals ? " + bent normal" : " only") +
                        "," + blurText(s) + tiledText(s) + normalsText(s);
    // GTAO: depth + normal in, visibility (+ bent normal) out; blur dispatches as in the alchemy case.
    const BlurDispatch dispatch = blurDispatch(s);
    setup.bytes = double(px) * (4 + normalBytes(s) + 4 + (s.bentNormals ? 12 : 0)) +
                  blurDispatchCount(dispatch) * double(px) * (4 + 4 + 4);
    // Mip sampling: the chain's pass reads depth and writes the chain, which the GTAO pass reads.
    if (k.mipLevels > 0) setup.bytes += 4.0 * (double(px) + 2.0 * double(gtaoDepthMipsFloats(w, h, k.mipLevels)));
    setup.keepAlive = {logSpatial, visibility, bent, mips, scratch, out};
    setup.record = [&c, k, blur, logSpatial, visibility, bent, mips, scratch, out, bentNormals = s.bentNormals,
                    dispatch, packed = s.packedNormals](VkCommandBuffer cmd, const ResidentInput& in, int,
                                                        const std::function<void(const char*)>& mark) {
        if (k.mipLevels > 0) {
            recordGtaoDepthMips(c, cmd, in.depth, *mips, k);
            mark("mips");
            computeBarrier(cmd);  // the GTAO pass reads the chain
        }
        recordGtao(c, cmd, {in.depth, in.normal, *visibility, *bent, *mips}, k, 1, bentNormals, packed);
        mark("gtao");
        computeBarrier(cmd);  // the blur reads the visibility
        recordSeparableBilateral(
            c, cmd, {in.depth, in.normal, *logSpatial, *visibility, *scratch, *out, packed}, blur, dispatch);
        mark("blur");
    };
    return setup;
}

CaseSetup gtaoHalfCase(Context::Impl& c, int w, int h, const GpuBenchSettings& s) {
    ssao::GtaoSettings settings = gtaoSettings(s);
    ssao::applyHalfResolutionCounts(settings, s.gtao);
    ssao::GtaoHalfResolutionSettings half;
    half.blur.radius = s.halfBlurRadius;
    // Both blurs by depth alone: the 2-D one measured as accurate as the separable one there (docs/QUALITY.md).
    half.blur.mode = s.halfBlur2D ? ssao::BlurMode::TwoD : ssao::BlurMode::Separable;
    half.blur.normalWeight = ssao::NormalWeight::Off;
    auto passes = std::make_shared<GtaoHalfResolutionPasses>(c, settings, half, w, h, s.bentNormals, blurDispatch(s),
                                                             s.packedNormals);
    CaseSetup setup;
    const std::string taps = std::to_string(2 * s.halfBlurRadius + 1);
    setup.description = "GTAO at half resolution (" + slicesText(settings) + radiusText(settings) + "), visibility" +
                        (s.bentNormals ? " + bent normal" : " only") +
                        (s.halfBlur2D ? " + 2-D bilateral there, " + taps + "x" + taps + " taps"
                                      : " + separable bilateral there, " + taps + " taps per axis" + tiledText(s)) +
                        ", depth only + depth-aware upsample" + normalsText(s);
    setup.bytes = double(passes->bytesPerFrame());
    setup.keepAlive = {passes};
    setup.record = [passes](VkCommandBuffer cmd, const ResidentInput& in, int index,
                            const std::function<void(const char*)>& mark) {
        passes->record(cmd, in.depth, in.normal, in.camera, index, mark);
    };
    return setup;
}

CaseSetup temporalCase(Context::Impl& c, int w, int h, const GpuBenchSettings& s, bool temporal, bool half,
                       bool gridHistory) {
    ssao::GtaoSettings settings = gtaoSettings(s);
    if (temporal) settings.sliceCount = s.temporalSlices;
    settings.jitter = false;  // the interleave rotates the slices instead
    ssao::GtaoTemporalSettings t;
    t.temporal = temporal;
    t.halfResolution = half;
    t.packedHistory = s.packedHistory;
    t.gridHistory = gridHistory;
    t.alternatingWindow = temporal && s.alternatingWindow;  // the spatial case has no history to average
    t.alternatingWindowSize = s.alternatingWindowSize;
    auto passes = std::make_shared<GtaoTemporalPasses>(
        c, settings, t, w, h,
        GtaoTemporalVariant{s.bentNormals, s.callerKeepsDepth, s.packedNormals, gridHistory && s.packedOutput,
                            gridHistory && s.fusedTemporal});
    CaseSetup setup;
    setup.description = std::string(temporal ? "spatio-temporal" : "spatial") + " GTAO" +
                        (half ? " at half resolution" : "") + " (" + slicesText(settings) +
                        ", 4x4 interleave" + radiusText(settings) + ") + " +
                        (t.alternatingWindow ? std::string(t.alternatingWindowSize == 2 ? "2x2" : "4x4") +
                                                   " reconstruction, its window alternating over 4 frames"
                                             : std::string("5x5 reconstruction")) +
                        (half && !gridHistory ? " + depth-aware upsample" : "") +
                        (temporal ? (s.packedHistory ? " + reprojected packed history" : " + reprojected history") : "") +
                        (gridHistory ? " on the grid + depth-aware upsample" : "") +
                        (s.bentNormals ? "" : ", visibility only") +
                        (temporal && s.callerKeepsDepth ? ", previous depth kept by the caller" : "") +
                        normalsText(s) + (gridHistory && s.packedOutput ? ", unorm16 output" : "") +
                        (gridHistory && s.fusedTemporal ? ", GTAO and accumulation in one dispatch" : "");
    setup.bytes = double(passes->bytesPerFrame());
    setup.keepAlive = {passes};
    // The previous frame's depth: the rotating inputs stay resident, so it is still there (callerKeepsDepth).
    auto previousDepth = std::make_shared<const Buffer*>(nullptr);
    setup.record = [passes, previousDepth](VkCommandBuffer cmd, const ResidentInput& in, int index,
                                           const std::function<void(const char*)>& mark) {
        passes->record(cmd, {in.depth, in.normal, in.camera, index, *previousDepth}, mark);
        *previousDepth = &in.depth;
    };
    return setup;
}

} // namespace

void GpuBenchSettings::validate() const {
    auto check = [](bool ok, const char* field, const char* range) {
        if (!ok) fail(std::string("gpu-bench-") + field, std::string("must be in ") + range);
    };
    check(frames >= 1 && frames <= 100000, "frames", "[1, 100000]");
    check(warmup >= 0 && warmup <= 10000, "warmup", "[0, 10000]");
    check(framesPerSubmit >= 1 && framesPerSubmit <= 64, "frames-per-submit", "[1, 64]");
    check(alchemySamples >= 1 && alchemySamples <= 1024, "alchemy-samples", "[1, 1024]");
    check(blurRadius >= 1 && blurRadius <= ssao::kMaxBlurRadius, "blur-radius", "[1, 32] taps on each side");
    check(halfBlurRadius >= 1 && halfBlurRadius <= ssao::kMaxBlurRadius, "half-blur-radius", "[1, 32] taps on each side");
    check(alternatingWindowSize == 4 || alternatingWindowSize == 2, "alternating-window-size", "{4, 2}");
    if (blurTiled) {
        const std::string most = std::to_string(kTiledBlurMaxRadius);
        if (blurRadius > kTiledBlurMaxRadius)
            fail("gpu-bench-blur-tiled", "holds radii up to " + most + ", and --blur-radius is " + std::to_string(blurRadius));
        if (!halfBlur2D && halfBlurRadius > kTiledBlurMaxRadius)
            fail("gpu-bench-blur-tiled",
                 "holds radii up to " + most + ", and --half-blur-radius is " + std::to_string(halfBlurRadius));
    }
    check(temporalSlices >= 1 && temporalSlices <= 64, "temporal-slices", "[1, 64]");
    check(gtaoRadius > 0.0f && gtaoRadius <= 1e4f, "ao-radius", "(0, 1e4] m");
    check(mipDistanceRatio >= 2.0f && mipDistanceRatio <= 64.0f, "gtao-mip-ratio", "[2, 64]");
    // What is left to check is the counts the override sets.
    try {
        gtaoSettings(*this).validate();
    } catch (const Error& e) {
        throw Error("gpu-bench-" + std::string(e.what()));  // "gpu-bench-gtao-slices: ..."
    }
}

std::vector<GpuBenchCaseInfo> gpuBenchCases() {
    return {{"alchemy", "Alchemy AO + separable bilateral blur"},
            {"alchemy-fused", "the same, the blur's horizontal pass in the estimator's dispatch"},
            {"gtao", "GTAO (every slice each frame) + separable bilateral blur"},
            {"gtao-spatial", "GTAO with the 4x4 interleave + its depth- and normal-aware reconstruction"},
            {"gtao-temporal", "interleaved GTAO + reconstruction + reprojected exponential history"},
            {"gtao-temporal-half", "gtao-temporal at half resolution + depth-aware upsample"},
            {"gtao-temporal-grid", "gtao-temporal-half with the history on the half-resolution grid, upsampled after "
                                   "the accumulation"},
            {"gtao-half", "GTAO at half resolution (2 interleaved slices x 4 steps) + 5-tap blur there + depth-aware "
                          "upsample"}};
}

GpuBenchCase benchGpuCase(Context& context, const std::string& name, const std::vector<GBuffer>& inputs,
                          const GpuBenchSettings& settings, const std::function<void(double)>& progress) {
    settings.validate();
    std::string known;
    bool found = false;
    for (const GpuBenchCaseInfo& info : gpuBenchCases()) {
        known += (known.empty() ? "" : ", ") + info.name;
        found = found || info.name == name;
    }
    if (!found) fail("gpu bench", "unknown case '" + name + "' (known: " + known + ")");
    if (inputs.empty()) fail("gpu bench", "no input G-buffers");
    const int w = inputs[0].width(), h = inputs[0].height();
    for (const GBuffer& g : inputs) {
        g.validateShape("gpu bench");
        if (g.width() != w || g.height() != h)
            fail("gpu bench", "input G-buffers must all be " + std::to_string(w) + "x" + std::to_string(h) + ", not " +
                                  std::to_string(g.width()) + "x" + std::to_string(g.height()));
    }
    Context::Impl& c = context.impl();
    if (c.timestamps == VK_NULL_HANDLE) fail(c.info.name, "the compute queue has no timestamp queries to time passes with");

    std::vector<ResidentInput> resident;
    for (const GBuffer& g : inputs) {
        resident.push_back({upload(c, g.depth.pixels.data(), g.depth.pixelCount() * sizeof(float)),
                            uploadNormals(c, g.normal, settings.packedNormals), g.camera});
    }
    const CaseSetup setup = name == "alchemy" || name == "alchemy-fused"
                                ? alchemyCase(c, w, h, settings, inputs[0].camera, name == "alchemy-fused")
                            : name == "gtao"      ? gtaoCase(c, w, h, settings, inputs[0].camera)
                            : name == "gtao-half" ? gtaoHalfCase(c, w, h, settings)
                                              : temporalCase(c, w, h, settings, name != "gtao-spatial",
                                                             name == "gtao-temporal-half" ||
                                                                 name == "gtao-temporal-grid",
                                                             name == "gtao-temporal-grid");

    GpuBenchCase result;
    result.name = name;
    result.description = setup.description;
    result.width = w;
    result.height = h;
    result.frames = settings.frames;
    result.bytes = setup.bytes;
    std::vector<double> frameMs;
    std::map<std::string, std::vector<double>> passMs;
    std::vector<std::string> order;
    const int total = settings.warmup + settings.frames;
    // Each pipeline's dispatches before the frames (the setup's clears and first history are not the frame's).
    std::map<std::string, std::uint64_t> dispatchesBefore;
    for (const auto& [key, pipeline] : c.pipelines) dispatchesBefore[key] = pipeline->dispatches();
    for (int first = 0; first < total; first += settings.framesPerSubmit) {
        const int count = std::min(settings.framesPerSubmit, total - first);
        std::vector<int> marksAfterFrame;  // marks recorded once frame first + k is recorded
        c.submit(
            [&](VkCommandBuffer cmd) {
                int marks = 0;
                for (int k = 0; k < count; ++k) {
                    // The frames follow each other as an engine's do: nothing of one overlaps the next.
                    if (k > 0) computeBarrier(cmd);
                    const int i = first + k;
                    setup.record(cmd, resident[std::size_t(i) % resident.size()], i, [&](const char* pass) {
                        c.mark(cmd, pass);
                        ++marks;
                    });
                    marksAfterFrame.push_back(marks);
                }
                if (std::uint32_t(marks) + 2 > Context::Impl::kMaxTimestamps)
                    fail("gpu bench", std::to_string(count) + " frames of case '" + name + "' need " +
                                          std::to_string(marks + 2) + " timestamps, more than the " +
                                          std::to_string(Context::Impl::kMaxTimestamps) +
                                          " a submission has: lower --frames-per-submit");
            },
            true);
        if (progress) progress(double(first + count) / double(total));
        for (int k = 0; k < count; ++k) {
            if (first + k < settings.warmup) continue;
            const std::size_t from = k == 0 ? 0 : std::size_t(marksAfterFrame[std::size_t(k) - 1]);
            const std::size_t to = std::size_t(marksAfterFrame[std::size_t(k)]);
            // Every frame runs the same passes: a frame whose marks are not the first frame's would mean they
            // were split between frames wrongly, and its times would be another frame's.
            std::vector<std::string> passes;
            double frame = 0;
            for (std::size_t m = from; m < to; ++m) {
                const auto& [pass, ms] = c.lastMarks[m];
                if (frameMs.empty()) order.push_back(pass);
                passes.push_back(pass);
                passMs[pass].push_back(ms);
                frame += ms;
            }
            if (passes != order)
                fail("gpu bench", "frame " + std::to_string(first + k) + " of case '" + name + "' timed " +
                                      std::to_string(passes.size()) + " passes, the first timed frame " +
                                      std::to_string(order.size()));
            frameMs.push_back(frame);
        }
    }
    for (const std::string& pass : order) {
        const std::vector<double>& ms = passMs[pass];
        result.passes.push_back({pass, median(ms), *std::min_element(ms.begin(), ms.end())});
    }
    // The shaders of the pipelines the frames dispatched: a cache key is the shader's name, then <constants>.
    std::set<std::string> shaders;
    for (const auto& [key, pipeline] : c.pipelines)
        if (pipeline->dispatches() > dispatchesBefore[key]) shaders.insert(key.substr(0, key.find('<')));
    result.shaders.assign(shaders.begin(), shaders.end());
    result.medianMs = median(frameMs);
    result.minMs = *std::min_element(frameMs.begin(), frameMs.end());
    return result;
}

} // namespace obscura::gpu
