// `obscura bench trace`: ray-tracing throughput of the ground-truth estimator against bare Embree calls.
#include "cli_common.h"
#include "commands.h"

#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/trace.h"
#include "obscura/trace_bench.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <sys/utsname.h>

namespace obscura::cli {

namespace {

struct BenchOptions {
    std::string scene = "demo";
    std::string triangles;  // empty: --scene; else a level's budget as written (parseLevelTriangles)
    const CLI::Option* sceneOption = nullptr;
    std::string size = "640x360";
    int rays = 64;
    int threads = 0;
    bool json = false;
};

std::string cpuName() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    utsname u{};
    uname(&u);
    return u.machine;
}

void runTrace(const BenchOptions& o) {
    // The flags first: a level of 5e7 triangles took 19 s and 1.5 GB before --rays 0 was refused.
    int width = 0, height = 0;
    parseSize("--size", o.size, width, height);
    if (o.rays < 1 || o.rays > 4096) fail("--rays", "must be in [1, 4096]");
    ThreadLimit limit(o.threads, "--threads");
    const int threads = o.threads > 0 ? o.threads : hardwareThreads();
    LoadedScene loaded;
    if (!o.triangles.empty()) {
        // A budget under the generator's floor once timed a 4742-triangle level labelled "level-100"; a budget of 0
        // once meant "no level", and --scene beside a budget was ignored.
        const long long triangles = parseLevelTriangles("--triangles", o.triangles);
        if (o.sceneOption && o.sceneOption->count() > 0)
            fail("--scene", "and --triangles both name the scene: give one");
        loaded.scene = generateLevel(std::size_t(triangles));
        loaded.name = "level-" + std::to_string(triangles);
        loaded.camera.position = {-40, 25, 60};
        loaded.camera.target = {0, 0, 0};
    } else {
        loaded = loadSceneArgument(o.scene);
    }
    Camera camera = loaded.camera;
    camera.width = width;
    camera.height = height;

    auto buildStart = std::chrono::steady_clock::now();
    trace::Tracer tracer(loaded.scene);
    double buildSeconds = secondsSince(buildStart);
    GBuffer g = trace::renderGBuffer(tracer, camera);
    // Rays leave surface pixels only: a view of sky timed nothing, and printed 0 Mrays/s and -nan as figures.
    if (std::none_of(g.depth.pixels.begin(), g.depth.pixels.end(), [](float d) { return d < 1e30f; }))
        fail(loaded.name, "the view sees no surface, every pixel is sky: no ray to time (the scene's own camera "
                          "frames it; --size changes only the pixel count)");

    struct Case {
        const char* label;
        trace::Falloff falloff;
        float radius;
    };
    const Case cases[] = {{"occlusion r=2m", trace::Falloff::Binary, 2.0f},
                          {"occlusion r=inf", trace::Falloff::Binary, trace::kInfinity},
                          {"obscurance exp d=2m", trace::Falloff::Exponential, trace::kInfinity}};
    nlohmann::json report;
    char date[32];
    std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    report["scene"] = loaded.name;
    report["triangles"] = loaded.scene.triangleCount();
    report["size"] = o.size;
    report["rays_per_pixel"] = o.rays;
    report["threads"] = threads;
    report["cpu"] = cpuName();
    report["date"] = date;
    report["bvh_build_s"] = buildSeconds;
    if (!o.json) {
        std::printf("obscura bench trace: %s, %zu triangles, %dx%d px, %d rays/px, %d threads\n", loaded.name.c_str(),
                    loaded.scene.triangleCount(), camera.width, camera.height, o.rays, threads);
        std::printf("cpu: %s, %s; BVH build %.3f s\n\n", cpuName().c_str(), date, buildSeconds);
        std::printf("%-22s %12s %14s %14s %12s %14s\n", "rays", "count", "estimator", "raw embree", "raw/est.",
                    "est./thread");
        std::printf("%-22s %12s %14s %14s %12s %14s\n", "", "", "Mrays/s", "Mrays/s", "", "Mrays/s");
    }
    for (const Case& c : cases) {
        trace::ObscuranceSettings s;
        s.falloff = c.falloff;
        s.radius = c.radius;
        s.rays = o.rays;
        trace::TraceBenchResult r = trace::benchObscurance(tracer, g, s);
        if (!o.json)
            std::printf("%-22s %12llu %14.2f %14.2f %12.3f %14.2f\n", c.label, static_cast<unsigned long long>(r.rays),
                        r.estimatorMrays(), r.rawMrays(), r.rawMrays() / r.estimatorMrays(), r.estimatorMrays() / threads);
        report["cases"].push_back({{"label", c.label},
                                   {"rays", r.rays},
                                   {"estimator_mrays_per_s", r.estimatorMrays()},
                                   {"raw_embree_mrays_per_s", r.rawMrays()},
                                   {"estimator_s", r.estimatorSeconds},
                                   {"raw_s", r.rawSeconds}});
    }
    if (o.json) std::printf("%s\n", report.dump(2).c_str());
}

} // namespace

void addBenchCommand(CLI::App& app) {
    CLI::App* bench = app.add_subcommand(
        "bench", "Benchmarks that print tables (and JSON with --json): a subcommand, or --gpu for the Vulkan passes");
    bench->require_subcommand(0, 1);
    auto o = std::make_shared<BenchOptions>();
    CLI::App* trace = bench->add_subcommand(
        "trace", "Ray-tracing throughput (Mrays/s) of the AO estimator and of bare Embree calls on the same rays");
    o->sceneOption = trace->add_option("--scene", o->scene, "Built-in scene or scene file")->capture_default_str();
    trace->add_option("--triangles", o->triangles, "Use a generated level of about this many triangles instead of --scene, [4000, 2e8]");
    trace->add_option("--size", o->size, "G-buffer size whose pixels shoot the rays")->capture_default_str();
    trace->add_option("--rays", o->rays, "Rays per pixel, [1, 4096]")->capture_default_str();
    trace->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->capture_default_str();
    trace->add_flag("--json", o->json, "Print JSON instead of a table");
    trace->callback([o] { runTrace(*o); });
    addAlchemyBench(*bench);
    addGtaoBench(*bench);
    addGpuBench(*bench);
    addBakeBenchCommands(*bench);
}

} // namespace obscura::cli
