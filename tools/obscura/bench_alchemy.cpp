// `obscura bench alchemy`: milliseconds per pass of the Alchemy AO CPU reference (estimator, separable and
// 2-D bilateral blur) at 1280x720 and 1920x1080, on one thread and on all of them.
#include "ao_options.h"
#include "cli_common.h"
#include "commands.h"

#include "obscura/alchemy.h"
#include "obscura/bilateral.h"
#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/trace.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

namespace obscura::cli {

namespace {

struct AlchemyBenchOptions {
    std::string scene = "demo";
    int samples = 12;
    int repeats = 5;
    int threads = 0;  // the "all threads" column; 0 = all cores
    bool json = false;
    std::string size;         // "WxH" for one size; empty = 1280x720 and 1920x1080
    bool skip2d = false;      // the 2-D blur takes longest and is not part of the 40 ms aim
    float maxRadiusPixels = ssao::AlchemySettings{}.maxRadiusPixels;
    std::string normalWeight = "auto";
    bool dense = false;  // blur an AO with no pixel exactly 1, so the separable blur skips nothing
};

void runAlchemy(const AlchemyBenchOptions& o) {
    if (o.samples < 1 || o.samples > 1024) fail("--samples", "must be in [1, 1024]");
    if (o.repeats < 1 || o.repeats > 100) fail("--repeats", "must be in [1, 100]");
    // Checked before the scene loads (-1 once meant all cores without a word); it also bounds the set-up.
    ThreadLimit limitAll(o.threads, "--threads");
    const int all = o.threads > 0 ? o.threads : hardwareThreads();
    std::vector<std::pair<int, int>> sizes = {{1280, 720}, {1920, 1080}};
    if (!o.size.empty()) {
        sizes.resize(1);
        parseSize("--size", o.size, sizes[0].first, sizes[0].second);
    }
    ssao::AlchemySettings settings;
    settings.samples = o.samples;
    settings.maxRadiusPixels = o.maxRadiusPixels;
    // Before the scene loads and the table's header prints: --max-radius-px 0 failed after both.
    try {
        settings.validate();
    } catch (const Error& e) {
        throw Error("--" + std::string(e.what()));
    }
    LoadedScene loaded = loadSceneArgument(o.scene);
    trace::Tracer tracer(loaded.scene);
    ssao::BilateralSettings separable, twoD;
    twoD.mode = ssao::BlurMode::TwoD;
    separable.normalWeight = twoD.normalWeight = normalWeightFromFlag(o.normalWeight);
    nlohmann::json report;
    report["scene"] = loaded.name;
    report["samples"] = o.samples;
    report["repeats"] = o.repeats;
    report["separable_normal_weight"] = separable.usesNormals();
    report["dense"] = o.dense;
    report["2d_normal_weight"] = twoD.usesNormals();
    if (!o.json) {
        std::printf("obscura bench alchemy: scene %s, %d samples/px, paper defaults (r 0.5 m), blur radius 6 (13 taps),\n"
                    "separable blur weighs %s, 2-D %s%s; median of %d runs after a warm-up;\n"
                    "wall ms per pass (process CPU ms in brackets)\n\n",
                    loaded.name.c_str(), o.samples, separable.usesNormals() ? "depth and normals" : "depth only",
                    twoD.usesNormals() ? "depth and normals" : "depth only",
                    o.dense ? ", both on the AO with every 1 lowered by an ulp (dense)" : "", o.repeats);
        std::printf("%-10s %7s %17s %17s %17s %17s\n", "size", "threads", "alchemy", "blur separable", "blur 2d",
                    "alchemy+separable");
    }
    for (auto [w, h] : sizes) {
        Camera camera = loaded.camera;
        camera.width = w;
        camera.height = h;
        GBuffer g = trace::renderGBuffer(tracer, camera);
        for (int threads : {1, all}) {
            ThreadLimit limit(threads);
            Image ao;
            const RunTimes tAo = timeRuns(o.repeats, [&] { ao = ssao::alchemyAO(g, settings); });
            Image dense;
            if (o.dense) {
                dense = ao;
                for (float& v : dense.pixels) v = std::min(v, 0.99999994f);  // the float below 1
            }
            const Image& blurInput = o.dense ? dense : ao;
            const RunTimes tSep = timeRuns(o.repeats, [&] { (void)ssao::bilateralFilter(blurInput, g, separable); });
            const RunTimes t2d =
                o.skip2d ? RunTimes{} : timeRuns(o.repeats, [&] { (void)ssao::bilateralFilter(blurInput, g, twoD); });
            auto cell = [](double wall, double cpu) {
                char b[32];
                std::snprintf(b, sizeof b, "%.1f (%.1f)", wall, cpu);
                return std::string(b);
            };
            if (!o.json)
                std::printf("%4dx%-5d %7d %17s %17s %17s %17s\n", w, h, threads, cell(tAo.medianMs, tAo.medianCpuMs).c_str(),
                            cell(tSep.medianMs, tSep.medianCpuMs).c_str(), (o.skip2d ? std::string("-") : cell(t2d.medianMs, t2d.medianCpuMs)).c_str(),
                            cell(tAo.medianMs + tSep.medianMs, tAo.medianCpuMs + tSep.medianCpuMs).c_str());
            report["rows"].push_back({{"width", w},
                                      {"height", h},
                                      {"threads", threads},
                                      {"alchemy_ms", tAo.medianMs},
                                      {"blur_separable_ms", tSep.medianMs},
                                      {"blur_2d_ms", o.skip2d ? nlohmann::json() : nlohmann::json(t2d.medianMs)},
                                      {"alchemy_cpu_ms", tAo.medianCpuMs},
                                      {"blur_separable_cpu_ms", tSep.medianCpuMs},
                                      {"blur_2d_cpu_ms", o.skip2d ? nlohmann::json() : nlohmann::json(t2d.medianCpuMs)}});
            if (threads == all || all == 1) {
                // The separable blur skips windows that read exactly 1 (open surfaces and sky), so its time
                // depends on how much of the view that is.
                std::size_t ones = 0;
                for (float v : ao.pixels) ones += v == 1.0f;
                const double fraction = double(ones) / double(ao.pixels.size());
                report["rows"].back()["ao_one_fraction"] = fraction;
                if (!o.json) std::printf("%29s(%.0f%% of the %dx%d AO is exactly 1)\n", "", 100.0 * fraction, w, h);
            }
            if (threads == all) break;  // a one-core machine has one row
        }
    }
    if (o.json) std::printf("%s\n", report.dump(2).c_str());
}

} // namespace

void addAlchemyBench(CLI::App& bench) {
    auto o = std::make_shared<AlchemyBenchOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "alchemy", "Alchemy AO CPU passes (estimator, separable and 2-D blur) at 1280x720 and 1920x1080, ms");
    cmd->add_option("--scene", o->scene, "Built-in scene or scene file")->capture_default_str();
    cmd->add_option("--samples", o->samples, "Samples per pixel, [1, 1024]")->capture_default_str();
    cmd->add_option("--repeats", o->repeats, "Runs per pass; the median is printed, [1, 100]")->capture_default_str();
    cmd->add_option("--threads", o->threads, "Threads of the multithreaded rows (0 = all cores)")->capture_default_str();
    cmd->add_option("--size", o->size, "One size WxH instead of 1280x720 and 1920x1080");
    cmd->add_option("--max-radius-px", o->maxRadiusPixels, "Clamp of the estimator's screen radius, px, [1, 4096]")
        ->capture_default_str();
    cmd->add_option("--blur-normal-weight", o->normalWeight, kNormalWeightHelp)
        ->check(CLI::IsMember({"auto", "on", "off"}))
        ->capture_default_str();
    cmd->add_flag("--skip-2d", o->skip2d, "Do not time the 2-D blur (printed as -)");
    cmd->add_flag("--dense", o->dense,
                  "Blur the AO with every value 1 lowered by an ulp: the separable blur skips windows that read "
                  "exactly 1 (open surfaces, sky), so this times it on a view with occlusion everywhere");
    cmd->add_flag("--json", o->json, "Print JSON instead of a table");
    cmd->callback([o] { runAlchemy(*o); });
}

} // namespace obscura::cli
