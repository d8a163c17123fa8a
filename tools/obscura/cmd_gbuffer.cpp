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
#include <string>
#include <system_error>
#include <vector>

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
    // A directory that is there is one, whatever its name: -o out.d was refused as "unsupported output format".
    std::error_code isDir;
    const bool toDirectory = fileExtension(o.output).empty() || fs::is_directory(o.output, isDir);
    checkSupersample(o.supersample);
    // Every file this run writes, checked before any work; the directory is made only once there is something
    // to put in it, so that a failure (bad flag, missing scene, an output that is a directory) leaves nothing.
    const fs::path dir(o.output);
    const std::vector<std::string> outputs =
        toDirectory ? std::vector<std::string>{(dir / "depth.exr").string(), (dir / "normal.exr").string(),
                                               (dir / "albedo.exr").string(), (dir / "camera.json").string()}
                    : std::vector<std::string>{o.output, fs::path(o.output).replace_extension(".camera.json").string()};
    std::error_code ec;
    if (toDirectory) {
        checkOutputDirectory("-o", o.output, false);
        for (const std::string& path : outputs)
            if (fs::is_directory(path, ec)) fail(path, "is a directory");
    } else {
        checkOutputPath("-o", outputs[0], {".exr"});
        checkOutputPath("-o", outputs[1], {".json"});
    }
    ThreadLimit limit(o.threads, "--threads");
    LoadedScene loaded = loadSceneArgument(o.scene);
    Camera camera = o.camera.apply(loaded);
    trace::Tracer tracer(loaded.scene);
    Progress progress("primary rays", progressWanted(o.quiet));
    trace::GBufferSettings gs;
    gs.supersample = o.supersample;
    GBuffer g = trace::renderGBuffer(tracer, camera, gs, [&](double f) { progress(f); });

    // The first directory of the output's path that is not there yet: removed again if a write fails.
    const fs::path created = toDirectory ? firstMissingDirectory(dir) : fs::path();
    // All or none: half a G-buffer (an EXR without its camera) is worse than none, and so is a new depth beside
    // an old camera. The files were once written one by one and the written ones removed on a failure: a failed
    // camera.json took the new EXR with it and the previous one, which the new had replaced.
    const auto exr = [](const Image& image) { return [&image](const std::string& path) { writeExr(path, image); }; };
    const auto json = [&camera](const std::string& path) { writeCameraJson(path, camera); };
    const Image all = toDirectory ? Image() : combined(g);
    try {
        if (toDirectory) {
            checkOutputDirectory("-o", o.output, true);
            writeFilesTogether({{outputs[0], exr(g.depth)}, {outputs[1], exr(g.normal)}, {outputs[2], exr(g.albedo)},
                                {outputs[3], json}});
        } else {
            writeFilesTogether({{outputs[0], exr(all)}, {outputs[1], json}});
        }
    } catch (...) {
        if (!created.empty()) fs::remove_all(created, ec);
        throw;
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
