// `obscura bench gtao`: CPU time of the GTAO reference per preset and per mode on one G-buffer.
#include "cli_common.h"
#include "commands.h"

#include "obscura/error.h"
#include "obscura/gtao.h"
#include "obscura/gtao_temporal.h"
#include "obscura/parallel.h"
#include "obscura/specular_occlusion.h"
#include "obscura/trace.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>
#include <vector>

namespace obscura::cli {

namespace {

struct GtaoBenchOptions {
    std::string scene = "demo";
    std::string size = "1920x1080";
    float radius = 1.0f;
    int repeat = 3;
    int threads = 0;
    bool json = false;
};

void runGtaoBench(const GtaoBenchOptions& o) {
    if (o.repeat < 1 || o.repeat > 100) fail("--repeats", "must be in [1, 100]");
    if (!(o.radius > 0.0f && o.radius <= 1e4f)) fail("--radius", "must be in (0, 1e4] m");
    int width = 0, height = 0;
    parseSize("--size", o.size, width, height);
    ThreadLimit limit(o.threads, "--threads");
    const int threads = o.threads > 0 ? o.threads : hardwareThreads();
    LoadedScene loaded = loadSceneArgument(o.scene);
    Camera camera = loaded.camera;
    camera.width = width;
    camera.height = height;
    trace::Tracer tracer(loaded.scene);
    const GBuffer g = trace::renderGBuffer(tracer, camera);
    const double megapixels = double(camera.width) * double(camera.height) * 1e-6;

    nlohmann::json report;
    report["scene"] = loaded.name;
    report["size"] = o.size;
    report["threads"] = threads;
    report["radius_m"] = o.radius;
    if (!o.json) {
        std::printf("obscura bench gtao: %s, %dx%d px, r = %.2f m, %d threads, median (min) of %d runs\n\n",
                    loaded.name.c_str(), camera.width, camera.height, double(o.radius), threads, o.repeat);
        std::printf("%-34s %12s %12s %12s\n", "case", "ms/frame", "min ms", "Mpixel/s");
    }
    auto record = [&](const std::string& label, const RunTimes& t) {
        if (!o.json) std::printf("%-34s %12.1f %12.1f %12.2f\n", label.c_str(), t.medianMs, t.minMs, megapixels / (t.medianMs * 1e-3));
        report["cases"].push_back({{"label", label}, {"median_ms", t.medianMs}, {"min_ms", t.minMs}});
    };
    for (ssao::GtaoQuality q : {ssao::GtaoQuality::Low, ssao::GtaoQuality::Medium, ssao::GtaoQuality::High,
                                ssao::GtaoQuality::Ultra}) {
        ssao::GtaoSettings s;
        ssao::applyQuality(s, q);
        s.radius = o.radius;
        const ssao::GtaoConstants c = ssao::gtaoConstants(s, camera);
        record(std::string("full ") + ssao::qualityName(q) + " (" + std::to_string(s.sliceCount) + "x" +
                   std::to_string(s.stepsPerSide) + ")",
               timeRuns(o.repeat, [&] { ssao::computeGtao(g, c); }));
    }
    // High with one depth read per horizon sample instead of the planar quad's five, and with far samples from
    // the depth MIP chain, which computeGtao builds first (GtaoSampling).
    for (auto [label, sampling] : {std::pair{"high (3x3), nearest samples", ssao::GtaoSampling::Nearest},
                                   std::pair{"high (3x3), depth MIP samples", ssao::GtaoSampling::Mip}}) {
        ssao::GtaoSettings s;
        s.radius = o.radius;
        s.sampling = sampling;
        const ssao::GtaoConstants c = ssao::gtaoConstants(s, camera);
        record(label, timeRuns(o.repeat, [&] { ssao::computeGtao(g, c); }));
    }
    // The paper's real-time configuration: one slice per pixel, high's 3 steps, reconstruction + history.
    ssao::GtaoSettings one;
    one.radius = o.radius;
    one.sliceCount = 1;
    one.stepsPerSide = 3;
    // Full resolution, half, and half with the history on the grid (the accumulation on a quarter of the pixels).
    for (int variant = 0; variant < 3; ++variant) {
        ssao::GtaoTemporalSettings t;
        t.halfResolution = variant > 0;
        t.gridHistory = variant == 2;
        ssao::GtaoTemporal temporal(one, t);
        record(std::string("temporal 1x3") + (variant == 2 ? " half-res, grid history" : variant == 1 ? " half-res" : ""),
               timeRuns(o.repeat, [&] { temporal.frame(g); }));
    }
    ssao::GtaoSettings high;
    high.radius = o.radius;
    const ssao::GtaoResult r = ssao::computeGtao(g, high);
    // Built once per process, on first use: timed here, before the per-frame GTSO cases.
    auto tables = std::chrono::steady_clock::now();
    ssao::SpecularOcclusionTable::fourD();
    const double fourDSeconds = secondsSince(tables);
    tables = std::chrono::steady_clock::now();
    ssao::SpecularOcclusionTable::threeD();
    const double threeDSeconds = secondsSince(tables);
    report["gtso_table_4d_build_s"] = fourDSeconds;
    report["gtso_table_3d_build_s"] = threeDSeconds;
    if (!o.json) std::printf("%-34s %12.1f\n%-34s %12.1f\n", "GTSO 4-D table build (once)", 1000.0 * fourDSeconds,
                             "GTSO 3-D table build (once)", 1000.0 * threeDSeconds);
    for (auto [label, mode] : {std::pair{"GTSO lut4 (after AO)", ssao::SpecularOcclusionMode::Lut4},
                               std::pair{"GTSO lut3 (after AO)", ssao::SpecularOcclusionMode::Lut3},
                               std::pair{"GTSO cone (after AO)", ssao::SpecularOcclusionMode::Cone}})
        record(label, timeRuns(o.repeat, [&] { ssao::computeSpecularOcclusion(g, r.visibility, r.bentNormal, mode, 0.5f); }));
    if (o.json) std::printf("%s\n", report.dump(2).c_str());
}

} // namespace

void addGtaoBench(CLI::App& bench) {
    auto o = std::make_shared<GtaoBenchOptions>();
    CLI::App* cmd = bench.add_subcommand("gtao", "CPU time of the GTAO reference per preset and mode (ms per frame)");
    cmd->add_option("--scene", o->scene, "Built-in scene or scene file")->capture_default_str();
    cmd->add_option("--size", o->size, "Image size WIDTHxHEIGHT")->capture_default_str();
    cmd->add_option("--radius", o->radius, "AO radius r, m, (0, 1e4]")->capture_default_str();
    cmd->add_option("--repeat,--repeats", o->repeat, "Timed runs per case after one warm-up, [1, 100]")->capture_default_str();
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->capture_default_str();
    cmd->add_flag("--json", o->json, "Print JSON instead of a table");
    cmd->callback([o] { runGtaoBench(*o); });
}

} // namespace obscura::cli
