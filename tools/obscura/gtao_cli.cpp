// `obscura render --ao gtao`: options, the camera path for --frames, and shading with multi-bounce.
#include "gtao_cli.h"

#include "cli_common.h"

#include "obscura/error.h"
#include "obscura/gpu_lighting.h"
#include "obscura/gpu_temporal.h"
#include "obscura/gtao_half_res.h"
#include "obscura/image_io.h"
#include "obscura/multibounce.h"
#include "obscura/specular_occlusion.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace obscura::cli {

namespace {

const std::map<std::string, ssao::SpecularOcclusionMode> kSpecularModes = {
    {"lut4", ssao::SpecularOcclusionMode::Lut4},
    {"lut3", ssao::SpecularOcclusionMode::Lut3},
    {"cone", ssao::SpecularOcclusionMode::Cone}};

std::string numbered(const std::string& dir, const char* name, int frame) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "_%04d.exr", frame);
    return (std::filesystem::path(dir) / (std::string(name) + buffer)).string();
}

} // namespace

std::vector<std::string> GtaoOptions::aovFiles(const std::string& aovDir) const {
    std::vector<const char*> names = {"ao"};
    if (output != "visibility") names.push_back("bent_normal");
    if (output == "all" && multibounce) names.push_back("ao_multibounce");
    if (output == "all" && specular != "none") names.push_back("specular_occlusion");
    std::vector<std::string> files;
    for (const char* name : names) {
        files.push_back((std::filesystem::path(aovDir) / (std::string(name) + ".exr")).string());
        for (int k = 0; frames > 1 && k < frames; ++k) files.push_back(numbered(aovDir, name, k));
    }
    return files;
}

namespace {

std::vector<std::string> gtaoSamplingNames() {
    std::vector<std::string> names;
    for (int i = 0; i < ssao::kGtaoSamplingCount; ++i) names.push_back(ssao::gtaoSamplingName(ssao::GtaoSampling(i)));
    return names;
}

// What --gtao-mip-ratio does, wherever it is offered.
const char* const kMipRatioHelp =
    "a sample d pixels away reads the coarsest MIP level whose texels are at most d / ratio pixels wide, [2, 64]; "
    "smaller reads coarser levels sooner (fewer cache lines, a lower horizon behind thin rims). With "
    "planar-nearest: samples from 2 ratio pixels out are nearest-pixel ones";

// "0 for the methods' default (7)", from GtaoSettings' own default.
std::string defaultMipRatioText() {
    char text[64];
    std::snprintf(text, sizeof text, "0 for the methods' default (%g)", double(ssao::GtaoSettings{}.mipDistanceRatio));
    return text;
}

} // namespace

void addGtaoMipRatioOverride(CLI::App& app, float& mipRatio) {
    app.add_option("--gtao-mip-ratio", mipRatio,
                   "GTAO methods with a depth MIP chain (gtao-mip, gtao-planar-mip) or planar-nearest samples "
                   "(gtao-planar-nearest, gtao-half-planar-nearest), " + defaultMipRatioText() + ": " + kMipRatioHelp)
        ->capture_default_str();
}

void warnGtaoMipRatioUnread(float mipRatio, bool read, const std::string& what) {
    if (mipRatio > 0.0f && !read)
        std::fprintf(stderr, "obscura: warning: --gtao-mip-ratio: %s (gtao-mip, gtao-planar-mip and the "
                             "planar-nearest ones do); ignored\n", what.c_str());
}

void validateGtaoMipRatioOverride(float mipRatio) {
    if (mipRatio != 0.0f && !(mipRatio >= 2.0f && mipRatio <= 64.0f))
        fail("--gtao-mip-ratio", "must be in [2, 64], or " + defaultMipRatioText());
}

const CLI::Option* addGtaoSamplingOption(CLI::App& app, std::string& sampling, float& mipRatio, const std::string& lead) {
    app.add_option("--gtao-sampling", sampling,
                   lead + ": planar (inverse depth interpolated over a planar 2x2 quad, on the slice line; 5 reads), "
                          "nearest (the nearest pixel, 1 read, as XeGTAO; far open ground at grazing angles darkens) or "
                          "mip (samples farther than 14 pixels read a coarser level of a 5-level depth MIP chain, "
                          "nearer ones are nearest, as XeGTAO), planar-mip (the same, nearer ones planar: far open "
                          "ground stays open) or planar-nearest (planar within 14 pixels, nearest beyond, no chain: "
                          "nearest's false horizons come from near samples of rotated slices)")
        ->check(CLI::IsMember(gtaoSamplingNames()))
        ->capture_default_str();
    return app.add_option("--gtao-mip-ratio", mipRatio, std::string("With --gtao-sampling mip, planar-mip or planar-nearest: ") + kMipRatioHelp)
        ->capture_default_str();
}

void GtaoSliceFlags::add(CLI::App& app, const std::string& lead, const std::string& slicesNote,
                         const std::string& jitterNote) {
    app.add_option("--gtao-slices", value.slices, lead + ": slice directions per pixel, [1, 64] (0: the preset's)" + slicesNote)
        ->capture_default_str();
    app.add_option("--gtao-steps", value.steps, lead + ": horizon samples on each side of a slice, [1, 256] (0: the preset's)")
        ->capture_default_str();
    app.add_flag("--gtao-jitter", value.jitter,
                 lead + ": rotate each pixel's slices and offset its steps by a hash of the pixel (and frame), noise "
                        "that a blur averages; without it every pixel has the same regular slices" + jitterNote);
    app.add_flag("--gtao-interleave", value.interleave,
                 lead + ": rotate each pixel's slices by its place in the 4x4 pattern of the spatio-temporal mode "
                        "(16 direction classes per 4x4 block), stratified where --gtao-jitter is noise; a blur "
                        "averages them" + jitterNote);
}

void GtaoSliceFlags::validate() const {
    ssao::GtaoSettings s;
    value.apply(s);
    try {
        s.validate();  // the defaults are valid, so a failure names one of these flags
    } catch (const Error& e) {
        throw Error("--" + std::string(e.what()));
    }
}

ssao::GtaoSampling gtaoSampling(const std::string& sampling) {
    for (int i = 0; i < ssao::kGtaoSamplingCount; ++i)
        if (sampling == ssao::gtaoSamplingName(ssao::GtaoSampling(i))) return ssao::GtaoSampling(i);
    return ssao::GtaoSampling::Planar;  // the option's check has refused any other word
}

// Slow enough for the history to follow and fast enough to disocclude something over a few frames.
Camera gtaoPathCamera(const Camera& base, int k) { return turnedAboutTarget(base, 0.5f * kPi / 180.0f * float(k)); }

void GtaoOptions::add(CLI::App& app) {
    app.add_option("--ao-quality", quality, "GTAO preset (slices x steps per side): low 1x2, medium 2x2, high 3x3, ultra 9x3")
        ->check(CLI::IsMember({"low", "medium", "high", "ultra"}))
        ->capture_default_str();
    app.add_option("--ao-output", output,
                   "GTAO images written to --aov-dir: visibility (ao.exr), bent-normal (also bent_normal.exr), all "
                   "(also ao_multibounce.exr and specular_occlusion.exr when enabled)")
        ->check(CLI::IsMember({"visibility", "bent-normal", "all"}))
        ->capture_default_str();
    app.add_flag("--multibounce", multibounce, "GTAO: near-field interreflection G(A, albedo) per colour channel");
    specularOption = app.add_option("--specular-occlusion", specular,
                   "GTAO: specular occlusion from the bent-normal cone: none, lut4 (4-D GGX table), lut3 (3-D, "
                   "the normal taken as the bent normal), cone (cone-cone intersection)")
        ->check(CLI::IsMember({"none", "lut4", "lut3", "cone"}))
        ->capture_default_str();
    roughnessOption = app.add_option("--roughness", roughness,
                                     "GTAO specular occlusion: GGX roughness of every surface, [0, 1]")
        ->capture_default_str();
    app.add_option("--frames", frames, "GTAO: frames rendered along the built-in camera path (the last is written), [1, 1000]")
        ->capture_default_str();
    app.add_option("--gtao-mode", mode,
                   "GTAO: full (every slice each frame), spatial (4x4 interleave, no history), temporal (interleave + "
                   "history), auto (full for one frame, temporal for more)")
        ->check(CLI::IsMember({"auto", "full", "spatial", "temporal"}))
        ->capture_default_str();
    app.add_flag("--gtao-half-res", halfResolution,
                 "GTAO: evaluate at half resolution (every other pixel in x and y) and upsample by depth; in the full "
                 "mode the grid is blurred first (--gtao-half-blur-radius). At half resolution 2 slices x 4 steps "
                 "with --gtao-interleave beat the full-resolution high preset against ray tracing (docs/QUALITY.md)");
    app.add_option("--gtao-half-blur-radius", halfBlurRadius,
                   "GTAO full mode with --gtao-half-res: taps on each side of the separable blur on the half-resolution "
                   "grid, [0, 32] (0: no blur; 2: 5 taps)")
        ->capture_default_str();
    app.add_flag("--gtao-packed-history", packedHistory,
                 "GTAO temporal: keep the history in packed words (visibility to 1/65535, octahedral normals), "
                 "4 words per pixel instead of 9 floats, as a GPU would");
    app.add_flag("--gtao-grid-history", gridHistory,
                 "GTAO spatial and temporal modes with --gtao-half-res: reproject and accumulate on the half-resolution "
                 "grid and upsample afterwards, so the history is a quarter of the full-resolution one (the same "
                 "error against ray tracing to 4 digits on the static views of docs/QUALITY.md)");
    app.add_flag("--gtao-alternating-window", alternatingWindow,
                 "GTAO temporal mode: reconstruct with a 4x4 window (16 taps instead of 25) whose place alternates "
                 "over 4 frames, so that the history averages it to the 5x5 window's weights");
    app.add_option("--gtao-alternating-window-size", alternatingWindowSize,
                   "GTAO temporal mode with --gtao-alternating-window: the windows' side, 4 (16 taps) or 2 (2x2 "
                   "windows that each hold the pixel, 4 taps, which the history averages to a 3x3 tent)")
        ->capture_default_str();
    app.add_flag("--gpu-packed-output", gpuPackedOutput,
                 "GTAO with --gpu, --gtao-half-res and --gtao-grid-history: the passes write the visibility as "
                 "unorm16 (an R16 image), each value rounded to 1/65535");
    app.add_flag("--gpu-fused-temporal", gpuFusedTemporal,
                 "GTAO with --gpu, --gtao-half-res and --gtao-grid-history: one dispatch evaluates GTAO over the grid "
                 "and reconstructs and accumulates it, instead of two; the same values");
    app.add_option("--gtao-thickness", thickness, "GTAO thin occluders: none, heuristic (eq. 9), bitmask")
        ->check(CLI::IsMember({"none", "heuristic", "bitmask"}))
        ->capture_default_str();
    falloffStartOption = app.add_option("--gtao-falloff-start", falloffStart,
                                        "GTAO: fraction of the radius where the linear fade starts, [0, 1] (not with "
                                        "--gtao-thickness bitmask, which counts an occluder within the radius whole)")
                             ->capture_default_str();
    app.add_option("--gtao-beyond-radius", beyondRadius,
                   "GTAO: a horizon sample farther than the radius counts through the solid column behind it where "
                   "that comes within the radius (column), or not at all (drop)")
        ->check(CLI::IsMember({"column", "drop"}))
        ->capture_default_str();
    mipRatioOption = addGtaoSamplingOption(app, sampling, mipRatio, "GTAO: how a horizon sample reads depth");
    app.add_option("--gtao-step-power", stepPower,
                   "GTAO: horizon step distribution, distance ~ (k / steps)^power, [1, 4]; > 1 packs steps near the centre")
        ->capture_default_str();
    sliceFlags.add(app, "GTAO");
}

ssao::GtaoSettings GtaoOptions::settings(float radius) const {
    ssao::GtaoSettings s;
    ssao::applyQuality(s, ssao::parseQuality(quality));
    if (!(radius > 0.0f && radius <= 1e4f)) fail("--ao-radius", "GTAO needs a finite radius in (0, 1e4] m");
    s.radius = radius;
    s.falloffStart = falloffStart;
    s.beyondRadius = beyondRadius == "drop" ? ssao::GtaoBeyondRadius::Drop : ssao::GtaoBeyondRadius::Column;
    s.stepPower = stepPower;
    sliceFlags.value.apply(s);  // checked with the rest below
    s.sampling = gtaoSampling(sampling);
    s.mipDistanceRatio = mipRatio;
    s.thickness = thickness == "heuristic" ? ssao::GtaoThickness::Heuristic
                  : thickness == "bitmask" ? ssao::GtaoThickness::Bitmask
                                           : ssao::GtaoThickness::None;
    try {
        s.validate();
    } catch (const Error& e) {
        throw Error("--" + std::string(e.what()));
    }
    return s;
}

void GtaoOptions::validate(const std::string& aovDir) const {
    if (frames < 1 || frames > 1000) fail("--frames", "must be in [1, 1000]");
    if (!(roughness >= 0.0f && roughness <= 1.0f)) fail("--roughness", "must be in [0, 1]");
    if (!(falloffStart >= 0.0f && falloffStart <= 1.0f)) fail("--gtao-falloff-start", "must be in [0, 1]");
    if (output != "visibility" && aovDir.empty()) fail("--ao-output", "'" + output + "' needs --aov-dir");
    const bool temporal = mode == "temporal" || (mode == "auto" && frames > 1);
    if (halfBlurRadius < 0 || halfBlurRadius > ssao::kMaxBlurRadius) fail("--gtao-half-blur-radius", "must be in [0, 32]");
    if (halfBlurRadius != 2 && !(halfResolution && (mode == "full" || (mode == "auto" && !temporal))))
        fail("--gtao-half-blur-radius", "needs --gtao-half-res in the full mode (--gtao-mode full, or auto with one frame)");
    if (packedHistory && !temporal)
        fail("--gtao-packed-history", "needs a history: --gtao-mode temporal, or auto with --frames > 1");
    if (alternatingWindow && !temporal)
        fail("--gtao-alternating-window", "needs a history to average its windows: --gtao-mode temporal, or auto with "
                                          "--frames > 1");
    if (alternatingWindowSize != 4 && alternatingWindowSize != 2)
        fail("--gtao-alternating-window-size", "must be 4 or 2, not " + std::to_string(alternatingWindowSize));
    if (alternatingWindowSize != 4 && !alternatingWindow)
        fail("--gtao-alternating-window-size", "needs --gtao-alternating-window");
    if (gridHistory && (!halfResolution || !(mode == "spatial" || temporal)))
        fail("--gtao-grid-history", "needs --gtao-half-res in the spatial or temporal mode (--gtao-mode spatial or "
                                    "temporal, or auto with --frames > 1)");
    if (gpuPackedNormals && !(mode == "spatial" || temporal))
        fail("--gpu-packed-normals", "needs the spatial or temporal mode (--gtao-mode spatial or temporal, or auto with "
                                     "--frames > 1)");
    if (gpuPackedOutput && !gridHistory)
        fail("--gpu-packed-output", "needs --gtao-grid-history: there the upsampling writes the frame's visibility");
    if (gpuFusedTemporal && !gridHistory)
        fail("--gpu-fused-temporal", "needs --gtao-grid-history: it fuses GTAO with the accumulation on the grid");
    if (sliceFlags.value.jitter && (mode == "spatial" || temporal))
        fail("--gtao-jitter", "needs --gtao-mode full (or auto with one frame): the interleave rotates the slices of the "
                              "spatial and temporal modes");
}

void GtaoOptions::warnUnread() const {
    // Computed on every frame and written nowhere, it took a 64x36 render from 0.05 s to 1.55 s for nothing.
    if (specular != "none" && !writesSpecular() && specularOption)
        warnIgnored({specularOption}, "is written only as specular_occlusion.exr (--ao-output all); the frame's "
                                      "composite is diffuse");
    if (specular == "none" && roughnessOption) warnIgnored({roughnessOption}, "applies to --specular-occlusion");
    // The sector mask has no partial occluder: a sample within the radius sets its sectors whole.
    if (thickness == "bitmask" && falloffStartOption && falloffStart < 1.0f)
        warnIgnored({falloffStartOption}, "the bitmask thickness counts every occluder within the radius whole, "
                                          "without the fade");
    // Given, not merely defaulted (render's ratio defaults to 7, not to ao's and compare's 0 for "none").
    if (mipRatioOption && mipRatioOption->count() > 0)
        warnGtaoMipRatioUnread(mipRatio, ssao::gtaoSamplingReadsMipRatio(gtaoSampling(sampling)),
                               "--gtao-sampling " + sampling + " does not read it");
}

GtaoFrame renderGtaoFrames(const GtaoOptions& o, float radius, const trace::Tracer& tracer, const Camera& camera,
                           const trace::GBufferSettings& gbufferSettings, const std::string& aovDir, bool progress,
                           gpu::Context* context) {
    const ssao::GtaoSettings settings = o.settings(radius);
    const std::string mode = o.mode == "auto" ? (o.frames > 1 ? "temporal" : "full") : o.mode;
    ssao::GtaoTemporalSettings temporalSettings;
    temporalSettings.temporal = mode == "temporal";
    temporalSettings.halfResolution = o.halfResolution;
    temporalSettings.packedHistory = o.packedHistory;
    temporalSettings.gridHistory = o.gridHistory;
    temporalSettings.alternatingWindow = o.alternatingWindow;
    temporalSettings.alternatingWindowSize = o.alternatingWindowSize;
    ssao::GtaoHalfResolutionSettings half;  // the full mode's, with --gtao-half-res
    half.blur.mode = o.halfBlurRadius > 0 ? ssao::BlurMode::Separable : ssao::BlurMode::None;
    half.blur.radius = std::max(o.halfBlurRadius, 1);
    const bool bent = o.output != "visibility";
    const bool all = o.output == "all";
    // The GPU skips the bent normal where nothing reads it: no bent-normal image, no specular occlusion (the
    // shading uses visibility alone). Its visibility is the same bits either way.
    const gpu::GtaoOutputs outputs = bent || o.writesSpecular() ? gpu::GtaoOutputs::VisibilityAndBentNormal
                                                                : gpu::GtaoOutputs::Visibility;
    std::optional<ssao::GtaoTemporal> temporal;
    std::optional<gpu::GtaoTemporal> gpuTemporal;
    if (mode != "full" && context)
        gpuTemporal.emplace(*context, settings, temporalSettings, outputs,
                            gpu::GtaoTemporalFormats{o.gpuPackedNormals, o.gpuPackedOutput},
                            o.gpuFusedTemporal ? gpu::GtaoTemporalDispatch::Fused : gpu::GtaoTemporalDispatch::Separate);
    else if (mode != "full")
        temporal.emplace(settings, temporalSettings);

    GtaoFrame f;
    Progress p("GTAO frames", progress && o.frames > 1);
    for (int k = 0; k < o.frames; ++k) {
        f.gbuffer = trace::renderGBuffer(tracer, gtaoPathCamera(camera, k), gbufferSettings);
        ssao::GtaoResult r;
        const ssao::GtaoConstants constants = ssao::gtaoConstants(settings, f.gbuffer.camera, k);
        if (mode == "full" && o.halfResolution)
            r = context ? gpu::computeGtaoHalfResolution(*context, f.gbuffer, settings, half, k, outputs)
                        : ssao::computeGtaoHalfResolution(f.gbuffer, settings, half, k);
        else if (mode == "full")
            r = context ? gpu::computeGtao(*context, f.gbuffer, constants, outputs)
                        : ssao::computeGtao(f.gbuffer, constants);
        else
            r = context ? gpuTemporal->frame(f.gbuffer) : temporal->frame(f.gbuffer);
        f.visibility = std::move(r.visibility);
        f.bentNormal = std::move(r.bentNormal);
        if (o.multibounce && context) {
            f.multibounce = gpu::multiBounce(*context, f.gbuffer, f.visibility);
        } else if (o.multibounce) {
            f.multibounce = Image(f.gbuffer.width(), f.gbuffer.height(), 3, 1.0f);
            for (int y = 0; y < f.gbuffer.height(); ++y)
                for (int x = 0; x < f.gbuffer.width(); ++x) {
                    if (f.gbuffer.isSky(x, y)) continue;
                    Vec3 albedo{f.gbuffer.albedo.at(x, y, 0), f.gbuffer.albedo.at(x, y, 1), f.gbuffer.albedo.at(x, y, 2)};
                    Vec3 g = ssao::multiBounce(f.visibility.at(x, y), albedo);
                    for (int c = 0; c < 3; ++c) f.multibounce.at(x, y, c) = g[c];
                }
        }
        if (o.writesSpecular())
            f.specular = context ? gpu::specularOcclusion(*context, f.gbuffer, f.visibility, f.bentNormal,
                                                          kSpecularModes.at(o.specular), o.roughness)
                                 : ssao::computeSpecularOcclusion(f.gbuffer, f.visibility, f.bentNormal,
                                                                  kSpecularModes.at(o.specular), o.roughness);
        if (!aovDir.empty()) {
            // What is written here, aovFiles lists.
            const bool last = k + 1 == o.frames;
            auto write = [&](const char* name, const Image& image) {
                if (image.empty()) return;
                if (o.frames > 1) writeExr(numbered(aovDir, name, k), image);
                // The last frame's ao.exr is written by `render` with the other AOVs.
                if (last && std::string(name) != "ao")
                    writeExr((std::filesystem::path(aovDir) / (std::string(name) + ".exr")).string(), image);
            };
            write("ao", f.visibility);
            if (bent) write("bent_normal", f.bentNormal);
            if (all) {
                write("ao_multibounce", f.multibounce);
                write("specular_occlusion", f.specular);
            }
        }
        p(double(k + 1) / double(o.frames));
    }
    return f;
}

render::Frame shadeGtao(const GtaoFrame& f, const render::SH9& sh, const Image& environment, gpu::Context* context) {
    if (context && f.multibounce.empty()) return gpu::shade(*context, f.gbuffer, sh, f.visibility, environment);
    if (context) return gpu::shadeMultiBounce(*context, f.gbuffer, sh, f.multibounce, environment);
    if (f.multibounce.empty()) return render::shade(f.gbuffer, sh, f.visibility, environment);
    render::Frame frame = render::shade(f.gbuffer, sh, Image(), environment);
    for (int y = 0; y < f.gbuffer.height(); ++y)
        for (int x = 0; x < f.gbuffer.width(); ++x) {
            if (f.gbuffer.isSky(x, y)) continue;
            for (int c = 0; c < 3; ++c) frame.color.at(x, y, c) *= f.multibounce.at(x, y, c);
        }
    return frame;
}

} // namespace obscura::cli
