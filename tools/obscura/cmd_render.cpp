// `obscura render`: a scene lit by an environment, modulated by ambient occlusion, tonemapped to PNG.
#include "ao_options.h"
#include "cli_common.h"
#include "commands.h"
#include "gpu_flags.h"
#include "gtao_cli.h"

#include "obscura/alchemy.h"
#include "obscura/camera_io.h"
#include "obscura/error.h"
#include "obscura/gpu_lighting.h"
#include "obscura/image_io.h"
#include "obscura/parallel.h"
#include "obscura/render.h"
#include "obscura/trace.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

namespace obscura::cli {

namespace {

struct RenderOptions {
    std::string scene = "demo";
    std::string output = "frame.png";
    std::string ao = "raytraced";
    std::string radius = "1";
    int rays = 64;
    std::string falloff = "binary";
    float distance = 2.0f;
    float alchemyU = 0.05f;
    std::string env;
    float exposure = 0.0f;
    std::string tonemap = "aces";
    int supersample = 1;
    std::string aovDir;
    unsigned seed = 0;
    int threads = 0;
    bool quiet = false;
    CameraOptions camera;
    AlchemyFlags alchemy;  // --ao alchemy
    BlurFlags blur;
    CLI::Option* radiusOption = nullptr;
    CLI::Option *distanceOption = nullptr, *uOption = nullptr;
    GtaoOptions gtao;
    GpuFlags gpu;
    bool fusedBlur = false;  // --gpu-fused-blur
    bool tiledBlur = false;  // --gpu-tiled-blur
    // The flags of one --ao method each: the others ignore them, and say so when one is given.
    std::vector<const CLI::Option*> raytracedFlags, alchemyFlags, gtaoFlags;
    std::vector<const CLI::Option*> screenSpaceFlags;  // --gpu-packed-normals: alchemy's and gtao's
    std::vector<const CLI::Option*> displayFlags;      // --exposure, --tonemap: a PNG's
};

const std::map<std::string, trace::Falloff> kFalloffs = {
    {"binary", trace::Falloff::Binary}, {"alchemy", trace::Falloff::Alchemy}, {"exponential", trace::Falloff::Exponential}};
const std::map<std::string, render::Tonemap> kTonemaps = {
    {"aces", render::Tonemap::Aces}, {"reinhard", render::Tonemap::Reinhard}, {"none", render::Tonemap::None}};

void run(const RenderOptions& o) {
    auto start = std::chrono::steady_clock::now();
    // Everything that can be checked before the work is checked first.
    checkOutputPath("-o", o.output, {".png", ".exr"}, {o.env, o.scene});
    // A PNG holds display values (sRGB, clipped at 1), not radiance: read as one it lit scenes dim and flat.
    checkInputFormat("--env", o.env, {".hdr", ".exr"}, "an environment's linear radiance");
    const std::string notThis = ", not --ao " + o.ao;
    if (o.ao != "raytraced") warnIgnored(o.raytracedFlags, "applies to --ao raytraced" + notThis);
    if (o.ao != "alchemy") warnIgnored(o.alchemyFlags, "applies to --ao alchemy" + notThis);
    if (o.ao != "gtao") warnIgnored(o.gtaoFlags, "applies to --ao gtao" + notThis);
    if (o.ao != "alchemy" && o.ao != "gtao") warnIgnored(o.screenSpaceFlags, "applies to --ao alchemy or gtao" + notThis);
    if (fileExtension(o.output) == ".exr") warnIgnored(o.displayFlags, "applies to a PNG; an .exr output is linear radiance");
    // Each falloff reads its own parameters: the exponential one d alone (its rays reach 24 d), the others r, and
    // alchemy u. A value for another falloff changed nothing and was echoed in the summary as if it had.
    if (o.ao == "raytraced") {
        const std::string notThisFalloff = ", not --ao-falloff " + o.falloff;
        if (o.falloff == "exponential")
            warnIgnored({o.radiusOption}, "applies to the binary and alchemy falloffs" + notThisFalloff +
                                              " (its reach is --ao-distance)");
        if (o.falloff != "exponential") warnIgnored({o.distanceOption}, "applies to --ao-falloff exponential" + notThisFalloff);
        if (o.falloff != "alchemy") warnIgnored({o.uOption}, "applies to --ao-falloff alchemy" + notThisFalloff);
    }
    if (o.ao == "none") warnIgnored({o.radiusOption}, "applies to --ao raytraced, alchemy or gtao" + notThis);
    checkSupersample(o.supersample);
    // A flag said to be ignored is not validated either: "ignored" and then an error about its value was a
    // contradiction. What a setting does not read keeps its default.
    trace::ObscuranceSettings aoSettings;
    const bool readsRadius = o.ao == "alchemy" || o.ao == "gtao" || (o.ao == "raytraced" && o.falloff != "exponential");
    if (readsRadius) aoSettings.radius = parseRadius("--ao-radius", o.radius);
    if (o.ao == "raytraced") {
        aoSettings.falloff = kFalloffs.at(o.falloff);
        aoSettings.rays = o.rays;
        if (o.falloff == "exponential") aoSettings.halfDistance = o.distance;
        if (o.falloff == "alchemy") aoSettings.alchemyU = o.alchemyU;
        aoSettings.seed = o.seed;
        try {
            aoSettings.validate();
        } catch (const Error& e) {
            throw Error("--" + std::string(e.what()));
        }
    }
    if (fileExtension(o.output) != ".exr" && !(o.exposure >= -20.0f && o.exposure <= 20.0f))
        fail("--exposure", "must be in [-20, 20] EV, got " + numberText(o.exposure));
    ssao::AlchemySettings alchemy;
    ssao::BilateralSettings blur;
    if (o.ao == "alchemy") {
        alchemy = o.alchemy.settings(o.radiusOption->count() > 0 ? o.radius : std::string());
        alchemy.seed = o.seed;
        o.blur.warnUnread();
        blur = o.blur.settings();
    }
    if (o.ao == "gtao") {
        o.gtao.validate(o.aovDir);
        o.gtao.warnUnread();
        o.gtao.settings(aoSettings.radius);  // throws on a bad value before any work
    }

    o.gpu.validate();
    if (o.gtao.gpuPackedNormals && (o.ao == "alchemy" || o.ao == "gtao")) {
        if (!o.gpu.gpu) fail("--gpu-packed-normals", "needs --gpu: the CPU reads the normals as floats");
        if (o.ao == "alchemy" && alchemy.normalsFromDepth)
            fail("--gpu-packed-normals", "packs the G-buffer's normals, and --ao-normals-from-depth rebuilds them");
    }
    if (o.ao == "gtao" && o.gtao.gpuPackedOutput && !o.gpu.gpu)
        fail("--gpu-packed-output", "needs --gpu: the CPU writes the visibility as floats");
    if (o.ao == "gtao" && o.gtao.gpuFusedTemporal && !o.gpu.gpu)
        fail("--gpu-fused-temporal", "needs --gpu: it fuses two of the GPU's dispatches");
    if (o.fusedBlur && !(o.gpu.gpu && o.ao == "alchemy" && blur.mode == ssao::BlurMode::Separable && !blur.usesNormals()))
        fail("--gpu-fused-blur", "needs --gpu, --ao alchemy and the separable blur by depth alone (--blur separable, "
                                 "no normal weight)");
    if (o.tiledBlur && !(o.gpu.gpu && o.ao == "alchemy" && blur.mode == ssao::BlurMode::Separable &&
                         blur.radius <= gpu::kTiledBlurMaxRadius))
        fail("--gpu-tiled-blur", "needs --gpu, --ao alchemy and the separable blur (--blur separable) with "
                                 "--blur-radius up to " + std::to_string(gpu::kTiledBlurMaxRadius));
    if (o.tiledBlur && o.fusedBlur) fail("--gpu-tiled-blur", "and --gpu-fused-blur are two ways to run the blur: give one");

    // Every file --aov-dir gets, GTAO's (and their numbered frames) included: none may replace an input (the
    // environment read above) or the -o output, as -o itself may not, nor be a directory. (The GTAO images
    // were once missing here, and -o d/bent_normal.exr was overwritten by the bent normal, with exit 0.)
    std::vector<std::string> aovFiles;
    if (!o.aovDir.empty()) {
        if (samePath(o.aovDir, o.output)) fail("--aov-dir", o.aovDir + " is the -o output; give the AOVs a directory of their own");
        for (const char* name : {"ao.exr", "depth.exr", "normal.exr", "albedo.exr", "lighting.exr", "camera.json"})
            aovFiles.push_back((std::filesystem::path(o.aovDir) / name).string());
        if (o.ao == "gtao")
            for (const std::string& file : o.gtao.aovFiles(o.aovDir))
                if (std::find(aovFiles.begin(), aovFiles.end(), file) == aovFiles.end()) aovFiles.push_back(file);
    }
    for (const std::string& aov : aovFiles) {
        for (const auto& [what, other] : {std::pair<const char*, std::string>{"the input file", o.env},
                                          {"the input file", o.scene}, {"the output", o.output}})
            if (samePath(aov, other))
                fail(aov, std::string("is ") + what + " " + other + "; --aov-dir never overwrites it, choose another");
        if (std::filesystem::is_directory(aov)) fail(aov, "is a directory; --aov-dir writes a file there");
    }
    // Made once the scene and the environment have loaded (below), so that a bad one leaves no directory.
    if (!o.aovDir.empty()) checkOutputDirectory("--aov-dir", o.aovDir, false);

    ThreadLimit limit(o.threads, "--threads");
    const std::unique_ptr<gpu::Context> context = o.gpu.open();
    LoadedScene loaded = loadSceneArgument(o.scene);
    Camera camera = o.camera.apply(loaded);
    if (o.ao == "raytraced")
        checkRayReach(loaded, aoSettings.reach(),
                      aoSettings.falloff == trace::Falloff::Exponential ? "--ao-distance" : "--ao-radius");

    Image environment = o.env.empty() ? render::proceduralSky() : readEnvironmentImage(o.env);
    if (environment.channels < 3) fail(o.env, "environment needs 3 colour channels, has " + std::to_string(environment.channels));
    // Before the scene is traced: the GPU holds the environment as one texture, which has a size limit.
    if (const std::uint32_t side = context ? context->device().maxImageDimension2D : 0;
        side > 0 && (std::uint32_t(environment.width) > side || std::uint32_t(environment.height) > side))
        fail(o.env, std::to_string(environment.width) + "x" + std::to_string(environment.height) + " exceeds the " +
                        std::to_string(side) + " texels a side that device '" + context->device().name +
                        "' can hold (--gpu); resample it, or render without --gpu");
    render::SH9 sh;
    try {
        sh = render::projectEnvironment(environment);
    } catch (const Error& e) {
        fail(o.env.empty() ? "sky" : o.env, std::string(e.what()));
    }
    // The work once the inputs have loaded: the G-buffer, the AO, the frame and its files.
    auto renderAndWrite = [&] {
        const bool showProgress = progressWanted(o.quiet);
        std::unique_ptr<trace::Tracer> tracer;
        {
            Progress p("building BVH", showProgress);
            tracer = std::make_unique<trace::Tracer>(loaded.scene);
            p(1.0);
        }
        GBuffer gbuffer;
        {
            Progress p("primary rays", showProgress);
            trace::GBufferSettings gs;
            gs.supersample = o.supersample;
            // Alchemy's guard band renders a larger G-buffer and crops it after the AO pass.
            const Camera gbufferCamera = o.ao == "alchemy" ? ssao::guardBandCamera(camera, alchemy.guardBand) : camera;
            gbuffer = trace::renderGBuffer(*tracer, gbufferCamera, gs, [&](double f) { p(f); });
        }
        Image ao;
        const gpu::AlchemyFormats alchemyFormats{o.gtao.gpuPackedNormals};
        if (o.ao == "raytraced") {
            Progress p("ambient occlusion", showProgress);
            ao = trace::ambientObscurance(*tracer, gbuffer, aoSettings, [&](double f) { p(f); });
        } else if (o.ao == "alchemy" && o.fusedBlur) {
            ao = gpu::alchemyAOBlurred(*context, gbuffer, alchemy, blur, alchemyFormats);
            gbuffer = ssao::cropGuardBand(gbuffer, camera, alchemy.guardBand);
        } else if (o.ao == "alchemy") {
            Image raw = context ? gpu::alchemyAO(*context, gbuffer, alchemy, alchemyFormats) : ssao::alchemyAO(gbuffer, alchemy);
            gbuffer = ssao::cropGuardBand(gbuffer, camera, alchemy.guardBand);
            ao = o.tiledBlur ? gpu::bilateralFilterTiled(*context, raw, gbuffer, blur)
                 : context   ? gpu::bilateralFilter(*context, raw, gbuffer, blur)
                             : ssao::bilateralFilter(raw, gbuffer, blur);
        }
        GtaoFrame gtao;
        if (o.ao == "gtao") {
            trace::GBufferSettings gs;
            gs.supersample = o.supersample;
            gtao = renderGtaoFrames(o.gtao, aoSettings.radius, *tracer, camera, gs, o.aovDir, showProgress, context.get());
            gbuffer = gtao.gbuffer;
            camera = gbuffer.camera;
            ao = gtao.visibility;
        }

        render::Frame frame = o.ao == "gtao" ? shadeGtao(gtao, sh, environment, context.get())
                              : context      ? gpu::shade(*context, gbuffer, sh, ao, environment)
                                             : render::shade(gbuffer, sh, ao, environment);
        reportValidation(context.get());
        render::ShadeSettings shading;
        shading.exposure = o.exposure;
        shading.tonemap = kTonemaps.at(o.tonemap);

        if (!o.aovDir.empty()) {
            namespace fs = std::filesystem;
            auto path = [&](const char* name) { return (fs::path(o.aovDir) / name).string(); };
            writeExr(path("ao.exr"), ao.empty() ? Image(camera.width, camera.height, 1, 1.0f) : ao);
            writeExr(path("depth.exr"), gbuffer.depth);
            writeExr(path("normal.exr"), gbuffer.normal);
            writeExr(path("albedo.exr"), gbuffer.albedo);
            writeExr(path("lighting.exr"), frame.lighting);
            writeCameraJson(path("camera.json"), camera);
        }
        if (fileExtension(o.output) == ".exr")
            writeExr(o.output, frame.color);
        else
            writePng(o.output, render::toDisplay(frame.color, shading));

        std::printf("wrote %s: %dx%d, scene %s, AO %s", o.output.c_str(), camera.width, camera.height, loaded.name.c_str(),
                    o.ao.c_str());
        if (o.ao == "raytraced") {  // the parameters the falloff reads
            if (o.falloff == "exponential")
                std::printf(" (exponential, d = %g m, %d rays)", double(o.distance), o.rays);
            else if (o.falloff == "alchemy")
                std::printf(" (alchemy, r = %s m, u = %g m, %d rays)", o.radius.c_str(), double(o.alchemyU), o.rays);
            else
                std::printf(" (binary, r = %s m, %d rays)", o.radius.c_str(), o.rays);
        }
        if (o.ao == "alchemy")
            std::printf(" (%s, r = %g m, intensity %g, contrast %g, %d samples, blur %s%s%s)",
                        alchemy.formulation == ssao::AlchemyFormulation::Paper ? "paper" : "chapter", double(alchemy.radius),
                        double(alchemy.intensity), double(alchemy.contrast), alchemy.samples, o.blur.mode.c_str(),
                        o.fusedBlur   ? ", rows fused into the estimator"
                        : o.tiledBlur ? ", both passes in one tiled dispatch"
                                      : "",
                        alchemyFormats.packedNormals ? ", octahedral normals" : "");
        if (o.ao == "gtao") {
            const ssao::GtaoSettings g = o.gtao.settings(aoSettings.radius);
            std::string variants = o.gtao.halfResolution ? ", half resolution" : "";
            if (o.gtao.gridHistory) variants += ", history on the grid";
            if (o.gtao.alternatingWindow)
                variants += o.gtao.alternatingWindowSize == 2 ? ", alternating 2x2 windows" : ", alternating 4x4 windows";
            if (o.gtao.gpuPackedNormals) variants += ", octahedral normals";
            if (o.gtao.gpuPackedOutput) variants += ", 16-bit visibility";
            if (o.gtao.gpuFusedTemporal) variants += ", GTAO and accumulation in one dispatch";
            std::printf(" (%s: %d slice(s) x %d steps%s, r = %s m, %d frame(s)%s)", o.gtao.quality.c_str(), g.sliceCount,
                        g.stepsPerSide, g.interleave ? ", 4x4 interleave" : g.jitter ? ", jittered" : "", o.radius.c_str(),
                        o.gtao.frames, variants.c_str());
        }
        if (context) std::printf(", on %s", context->device().name.c_str());
        std::printf(", %.2f s\n", secondsSince(start));
    };
    // From here a failure removes what this run wrote to --aov-dir (the files that were not there before, and
    // the directories it made): once, a failed -o left six AOVs behind.
    std::vector<std::string> newAovFiles;
    for (const std::string& file : aovFiles)
        if (!std::filesystem::exists(file)) newAovFiles.push_back(file);
    const std::filesystem::path newAovDir = o.aovDir.empty() ? std::filesystem::path() : firstMissingDirectory(o.aovDir);
    if (!o.aovDir.empty()) checkOutputDirectory("--aov-dir", o.aovDir, true);
    try {
        renderAndWrite();
    } catch (...) {
        std::error_code ec;
        for (const std::string& file : newAovFiles) std::filesystem::remove(file, ec);
        if (!newAovDir.empty()) std::filesystem::remove_all(newAovDir, ec);
        throw;
    }
}

} // namespace

void addRenderCommand(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene lit by an environment and modulated by ambient occlusion");
    cmd->add_option("scene", o->scene, "Built-in scene name (see `obscura scenes`) or a .gltf/.glb/.obj/.ply file")
        ->capture_default_str();
    cmd->add_option("-o,--output", o->output, "Output image: .png (tonemapped sRGB) or .exr (linear radiance)")
        ->capture_default_str();
    cmd->add_option("--ao", o->ao,
                    "Ambient occlusion: none, raytraced (Monte Carlo ground truth), alchemy or gtao (screen space)")
        ->check(CLI::IsMember({"none", "raytraced", "alchemy", "gtao"}))
        ->capture_default_str();
    o->radiusOption = cmd->add_option("--ao-radius", o->radius,
                                      "Occlusion radius r in meters, or inf (alchemy: finite, default 0.5 or the preset's)")
                          ->capture_default_str();
    o->raytracedFlags = optionsAddedBy(*cmd, [&] {
        cmd->add_option("--ao-rays", o->rays, "Rays per pixel, [1, 1048576]")->capture_default_str();
        cmd->add_option("--ao-falloff", o->falloff,
                        "binary (occlusion within r), alchemy (g = u t / max(u,t)^2 within r), "
                        "exponential (rho = 1 - exp(ln(0.5) t / d))")
            ->check(CLI::IsMember({"binary", "alchemy", "exponential"}))
            ->capture_default_str();
        o->distanceOption =
            cmd->add_option("--ao-distance", o->distance, "Half-visibility distance d of the exponential falloff, meters")
                ->capture_default_str();
        o->uOption =
            cmd->add_option("--ao-u", o->alchemyU, "Falloff constant u of the alchemy falloff, meters")->capture_default_str();
    });
    cmd->add_option("--env", o->env, "Equirectangular environment (.hdr or .exr); default: a built-in procedural sky");
    o->displayFlags = optionsAddedBy(*cmd, [&] {
        cmd->add_option("--exposure", o->exposure, "Exposure in EV stops, [-20, 20] (PNG output)")->capture_default_str();
        cmd->add_option("--tonemap", o->tonemap, "aces, reinhard or none (PNG output)")
            ->check(CLI::IsMember({"aces", "reinhard", "none"}))
            ->capture_default_str();
    });
    cmd->add_option("--supersample", o->supersample, "N x N albedo samples per pixel for antialiasing, [1, 16]")
        ->capture_default_str();
    cmd->add_option("--aov-dir", o->aovDir,
                    "Also write ao.exr, depth.exr, normal.exr, albedo.exr, lighting.exr and camera.json here");
    cmd->add_option("--seed", o->seed, "Seed of the ray directions")->capture_default_str();
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->capture_default_str();
    cmd->add_flag("-q,--quiet", o->quiet, "No progress bars");
    o->camera.add(*cmd);
    o->alchemyFlags = optionsAddedBy(*cmd, [&] {
        o->alchemy.add(*cmd, false);
        o->blur.add(*cmd);
    });
    o->gtaoFlags = optionsAddedBy(*cmd, [&] { o->gtao.add(*cmd); });
    o->screenSpaceFlags = {cmd->add_flag("--gpu-packed-normals", o->gtao.gpuPackedNormals,
                  "With --gpu and --ao alchemy (its estimator), or gtao in its spatial and temporal modes: upload the "
                  "normals as one octahedral word per pixel (two snorm16, as engines keep them) instead of 3 floats; "
                  "the AO of those normals decoded")};
    o->gpu.add(*cmd, "the screen-space AO (alchemy, gtao: every pass) and the composite", "Ray-traced AO stays on the CPU.");
    cmd->add_flag("--gpu-fused-blur", o->fusedBlur,
                  "With --gpu --ao alchemy and the separable blur by depth alone: evaluate the estimator and the "
                  "blur's horizontal pass in one dispatch, so the raw AO never goes through memory (the same "
                  "result; `bench --gpu --cases alchemy,alchemy-fused` times both)");
    cmd->add_flag("--gpu-tiled-blur", o->tiledBlur,
                  "With --gpu --ao alchemy and the separable blur (radius up to " +
                      std::to_string(gpu::kTiledBlurMaxRadius) +
                      "): run the blur's two passes in one dispatch, rows then columns of each 32x32 tile from shared "
                      "memory (the same result; `bench --gpu --blur-tiled` times it)");
    cmd->callback([o] { run(*o); });
}

} // namespace obscura::cli
