// `obscura bench alchemy`: milliseconds per pass of the Alchemy AO CPU reference (estimator, separable and
// 2-D bilateral blur) at 1280x720 and 1920x1080, on one thread and on all of them.
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
#include <functional>
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
};

// Median wall time of `repeats` runs, ms.
double medianMs(int repeats, const std::function<void()>& body) {
    std::vector<double> t;
    for (int i = 0; i < repeats; ++i) {
        auto start = std::chrono::steady_clock::now();
        body();
        t.push_back(1000.0 * secondsSince(start));
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

void runAlchemy(const AlchemyBenchOptions& o) {
    if (o.samples < 1 || o.samples > 1024) fail("--samples", "must be in [1, 1024]");
    if (o.repeats < 1 || o.repeats > 100) fail("--repeats", "must be in [1, 100]");
    const int all = o.threads > 0 ? o.threads : hardwareThreads();
    LoadedScene loaded = loadSceneArgument(o.scene);
    trace::Tracer tracer(loaded.scene);
    ssao::AlchemySettings settings;
    settings.samples = o.samples;
    ssao::BilateralSettings separable, twoD;
    twoD.mode = ssao::BlurMode::TwoD;
    nlohmann::json report;
    report["scene"] = loaded.name;
    report["samples"] = o.samples;
    report["repeats"] = o.repeats;
    if (!o.json) {
        std::printf("obscura bench alchemy: scene %s, %d samples/px, paper defaults (r 0.5 m), blur radius 6 (13 taps),\n"
                    "median of %d runs, ms per pass\n\n",
                    loaded.name.c_str(), o.samples, o.repeats);
        std::printf("%-11s %8s %12s %14s %10s %16s\n", "size", "threads", "alchemy", "blur separable", "blur 2d",
                    "alchemy+separable");
    }
    const std::pair<int, int> sizes[] = {{1280, 720}, {1920, 1080}};
    for (auto [w, h] : sizes) {
        Camera camera = loaded.camera;
        camera.width = w;
        camera.height = h;
        GBuffer g = trace::renderGBuffer(tracer, camera);
        for (int threads : {1, all}) {
            ThreadLimit limit(threads);
            Image ao;
            const double tAo = medianMs(o.repeats, [&] { ao = ssao::alchemyAO(g, settings); });
            const double tSep = medianMs(o.repeats, [&] { (void)ssao::bilateralFilter(ao, g, separable); });
            const double t2d = medianMs(o.repeats, [&] { (void)ssao::bilateralFilter(ao, g, twoD); });
            if (!o.json)
                std::printf("%4dx%-6d %8d %12.1f %14.1f %10.1f %16.1f\n", w, h, threads, tAo, tSep, t2d, tAo + tSep);
            report["rows"].push_back({{"width", w},
                                      {"height", h},
                                      {"threads", threads},
                                      {"alchemy_ms", tAo},
                                      {"blur_separable_ms", tSep},
                                      {"blur_2d_ms", t2d}});
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
    cmd->add_flag("--json", o->json, "Print JSON instead of a table");
    cmd->callback([o] { runAlchemy(*o); });
}

} // namespace obscura::cli
