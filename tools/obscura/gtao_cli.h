// The GTAO options of `obscura render --ao gtao` and the frame loop behind them (kept out of
// cmd_render.cpp, which only forwards to it).
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/gpu.h"
#include "obscura/gtao.h"
#include "obscura/gtao_temporal.h"
#include "obscura/image.h"
#include "obscura/render.h"
#include "obscura/trace.h"

#include <string>

namespace CLI {
class App;
class Option;
}

namespace obscura::cli {

// --gtao-slices, --gtao-steps, --gtao-jitter and --gtao-interleave (ssao::GtaoSliceOverride), for the commands that run GTAO.
struct GtaoSliceFlags {
    ssao::GtaoSliceOverride value;

    // `lead` starts each flag's help: what it applies to, for this command; a note ends the help of
    // --gtao-slices or --gtao-jitter where they apply to less than that.
    void add(CLI::App& app, const std::string& lead, const std::string& slicesNote = "",
             const std::string& jitterNote = "");
    // Throws obscura::Error naming the flag for a count out of range.
    void validate() const;
};

struct GtaoOptions {
    std::string quality = "high";
    std::string output = "visibility";  // visibility, bent-normal, all: which AOVs go to --aov-dir
    bool multibounce = false;
    std::string specular = "none";      // none, lut4, lut3, cone
    float roughness = 0.5f;
    int frames = 1;
    std::string mode = "auto";          // auto, full, spatial, temporal
    bool halfResolution = false;
    int halfBlurRadius = 2;  // full mode at half resolution: taps on each side of the grid's blur; 0: none
    bool packedHistory = false;
    bool gridHistory = false;  // spatial/temporal modes at half resolution: accumulate on the grid
    bool alternatingWindow = false;  // temporal mode: 4x4 reconstruction windows alternating over 4 frames
    int alternatingWindowSize = 4;   // ... or 2x2 ones (GtaoTemporalSettings::alternatingWindowSize)
    bool gpuPackedNormals = false;   // --gpu: gpu::GtaoTemporalFormats::packedNormals (render registers the flag,
                                     // which --ao alchemy takes too)
    bool gpuPackedOutput = false;    // --gpu: gpu::GtaoTemporalFormats::packedOutput
    bool gpuFusedTemporal = false;   // --gpu: gpu::GtaoTemporalDispatch::Fused
    std::string thickness = "none";
    float falloffStart = 1.0f;
    std::string beyondRadius = "column";
    std::string sampling = "planar";
    float mipRatio = 7.0f;  // GtaoSettings::mipDistanceRatio
    float stepPower = 1.0f;
    GtaoSliceFlags sliceFlags;

    void add(CLI::App& app);
    // The settings for radius r; throws obscura::Error naming the flag for a bad value.
    ssao::GtaoSettings settings(float radius) const;
    // Checks that need no scene; throws obscura::Error naming the flag.
    void validate(const std::string& aovDir) const;
    // Every file renderGtaoFrames writes to `aovDir` with these flags (the numbered frames' too), and ao.exr.
    std::vector<std::string> aovFiles(const std::string& aovDir) const;
    // Warns of the given flags these ones leave unread: the composite is diffuse, so specular occlusion shows only
    // as its AOV (--ao-output all), and --roughness only with it (renderGtaoFrames then skips that pass); the
    // bitmask thickness counts a sample within r whole, without --gtao-falloff-start's fade; --gtao-mip-ratio
    // applies to the mip and planar-nearest samplings.
    void warnUnread() const;
    bool writesSpecular() const { return specular != "none" && output == "all"; }

    const CLI::Option* specularOption = nullptr;  // set by add()
    const CLI::Option* roughnessOption = nullptr;
    const CLI::Option* falloffStartOption = nullptr;
    const CLI::Option* mipRatioOption = nullptr;
};

// --gtao-sampling (ssao::gtaoSamplingName's words) and --gtao-mip-ratio on `app`, the first's help starting with `lead`
// (what the flag sets, for this command), and the sampling's value as the setting.
// Returns the --gtao-mip-ratio option, for a warning where the sampling does not read it.
const CLI::Option* addGtaoSamplingOption(CLI::App& app, std::string& sampling, float& mipRatio, const std::string& lead);
ssao::GtaoSampling gtaoSampling(const std::string& sampling);

// --gtao-mip-ratio for the commands that run the registry's GTAO methods (compare, ao), whose sampling the
// method fixes: eval::MethodOptions::gtaoMipRatio, 0 meaning the method's default.
void addGtaoMipRatioOverride(CLI::App& app, float& mipRatio);
// Throws obscura::Error naming --gtao-mip-ratio unless it is 0 or in [2, 64].
void validateGtaoMipRatioOverride(float mipRatio);
// Warns that --gtao-mip-ratio is ignored when it is given and `read` is false (no method run reads it).
void warnGtaoMipRatioUnread(float mipRatio, bool read, const std::string& what);

// Frame k of the built-in camera path: `base` turned k * 0.5 degrees about the vertical through its target.
Camera gtaoPathCamera(const Camera& base, int k);

struct GtaoFrame {
    GBuffer gbuffer;        // the last frame's
    Image visibility;       // 1 channel
    Image bentNormal;       // 3 channels, view space; empty on the GPU when nothing reads it
    Image multibounce;      // 3 channels G(A, albedo), empty unless --multibounce
    Image specular;         // 1 channel, empty unless --specular-occlusion
};

// Renders the frames along the built-in camera path (frame k: the camera turned k * 0.5 degrees about the
// vertical through its target) and returns the last. With an AOV directory and several frames, each
// frame's AOVs are written as NAME_0000.exr ...; the last frame's also without the number. With a context,
// every GTAO pass (main, reconstruction, upsample, history, multi-bounce, specular occlusion) runs on it;
// the G-buffers are ray traced on the CPU either way.
GtaoFrame renderGtaoFrames(const GtaoOptions& options, float radius, const trace::Tracer& tracer, const Camera& camera,
                           const trace::GBufferSettings& gbufferSettings, const std::string& aovDir, bool progress,
                           gpu::Context* context = nullptr);

// Shaded frame with the GTAO result: albedo x lighting x AO, or x G(A, albedo) per channel with
// multi-bounce; on the context's device when there is one.
render::Frame shadeGtao(const GtaoFrame& frame, const render::SH9& sh, const Image& environment,
                        gpu::Context* context = nullptr);

} // namespace obscura::cli
