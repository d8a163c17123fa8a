// `obscura gbuffer`: depth, view-space normal and albedo of a scene, as one multi-channel EXR or as files.
#include "cli_common.h"
#include "commands.h"

#include "obscura/camera_io.h"
#include "obscura/error.h"
#include "obscura/image_io.h"
#include "obscura/parallel.h"
#include "obscura/trace.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace obscura::cli {

namespace {

namespace fs = std::filesystem;

struct GBufferOptions {
    std::string scene = "demo";
    std::string output = "gbuffer.exr";
    int supersample = 1;
    int threads = 0;
    bool quiet = false;
    CameraOptions camera;
};

// One EXR with the channels Z, N.X, N.Y, N.Z, albedo.R, albedo.G, albedo.B.
Image combined(const GBuffer& g) {
    Image out(g.width(), g.height(), 7);
    out.channelNames = {"Z", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B"};
    for (std::size_t i = 0; i < out.pixelCount(); ++i) {
        out.pixels[i * 7] = g.depth.pixels[i];
        for (int c = 0; c < 3; ++c) {
            out.pixels[i * 7 + 1 + std::size_t(c)] = g.normal.pixels[i * 3 + std::size_t(c)];
            out.pixels[i * 7 + 4 + std::size_t(c)] = g.albedo.pixels[i * 3 + std::size_t(c)];
        }
    }
    return out;
}

void run(const GBufferOptions& o) {
    auto start = std::chrono::steady_clock::now();
    const bool toDirectory = fileExtension(o.output).empty();
    if (toDirectory)
        checkOutputDirectory("-o", o.output, true);
    else
        checkOutputPath("-o", o.output, {".exr"});
    ThreadLimit limit(o.threads, "--threads");
    LoadedScene loaded = loadSceneArgument(o.scene);
    Camera camera = o.camera.apply(loaded);
    trace::Tracer tracer(loaded.scene);
    Progress p("primary rays", progressWanted(o.quiet));
    trace::GBufferSettings gs;
    gs.supersample = o.supersample;
    GBuffer g = trace::renderGBuffer(tracer, camera, gs, [&](double f) { p(f); });

    if (toDirectory) {
        writeExr((fs::path(o.output) / "depth.exr").string(), g.depth);
        writeExr((fs::path(o.output) / "normal.exr").string(), g.normal);
        writeExr((fs::path(o.output) / "albedo.exr").string(), g.albedo);
        writeCameraJson((fs::path(o.output) / "camera.json").string(), camera);
    } else {
        writeExr(o.output, combined(g));
        writeCameraJson(fs::path(o.output).replace_extension(".camera.json").string(), camera);
    }
    std::printf("wrote %s: %dx%d G-buffer of %s, %.2f s\n", o.output.c_str(), camera.width, camera.height,
                loaded.name.c_str(), secondsSince(start));
}

} // namespace

void addGBufferCommand(CLI::App& app) {
    auto o = std::make_shared<GBufferOptions>();
    CLI::App* cmd = app.add_subcommand(
        "gbuffer", "Write a scene's G-buffer: linear view depth (m, +inf for sky), view-space normal, albedo");
    cmd->add_option("scene", o->scene, "Built-in scene name or a .gltf/.glb/.obj/.ply file")->capture_default_str();
    cmd->add_option("-o,--output", o->output,
                    "A .exr file (channels Z, N.X, N.Y, N.Z, albedo.R/G/B, plus NAME.camera.json beside it), or a "
                    "directory to get depth.exr, normal.exr, albedo.exr and camera.json")
        ->capture_default_str();
    cmd->add_option("--supersample", o->supersample, "N x N albedo samples per pixel, [1, 16]")->capture_default_str();
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->capture_default_str();
    cmd->add_flag("-q,--quiet", o->quiet, "No progress bar");
    o->camera.add(*cmd);
    cmd->callback([o] { run(*o); });
}

} // namespace obscura::cli
