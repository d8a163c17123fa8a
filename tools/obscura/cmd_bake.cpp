// `obscura bake`: per-vertex ambient obscurance (or occlusion) baked by least squares and written back as
// vertex attributes (Sloan et al. 2013 §2-4), with a progress bar per stage and a closing stage table.
#include "cli_common.h"
#include "commands.h"

#include "obscura/bake.h"
#include "obscura/bake_io.h"
#include "obscura/error.h"
#include "obscura/image_io.h"
#include "obscura/parallel.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

namespace obscura::cli {

namespace {

// --raw-embree-check's largest stride: every billionth sample, which checks the first sample of any bake.
constexpr long long kMaxRawCheckStride = 1000000000;

struct BakeOptions {
    std::string input, output, report, mode = "obscurance", distances = "2,300", solver = "auto";
    std::string distance;  // --distance as given, parsed and checked where it was given
    CLI::Option* distanceOption = nullptr;
    CLI::Option* distancesOption = nullptr;
    bake::BakeSettings settings;
    bake::ArtistControls controls;
    int threads = 0;
    long long rawCheck = 0;  // signed, so that -1 is refused as -1, not taken as 2^64 - 1
    bool quiet = false;
};

// Removes a written output unless kept, when a later step of the command fails.
struct OutputGuard {
    std::string path;
    bool keep = false;
    explicit OutputGuard(std::string written) : path(std::move(written)) {}
    OutputGuard(const OutputGuard&) = delete;
    OutputGuard& operator=(const OutputGuard&) = delete;
    ~OutputGuard() {
        if (!keep) std::remove(path.c_str());
    }
};

std::string loadAverage() {
    std::ifstream in("/proc/loadavg");
    std::string a, b, c;
    in >> a >> b >> c;
    return a + " " + b + " " + c;
}

std::string human(std::size_t n) {
    char buf[32];
    if (n >= 1000000) std::snprintf(buf, sizeof buf, "%.2fM", double(n) * 1e-6);
    else if (n >= 1000) std::snprintf(buf, sizeof buf, "%.1fk", double(n) * 1e-3);
    else std::snprintf(buf, sizeof buf, "%zu", n);
    return buf;
}

void runBake(BakeOptions& o) {
    namespace fs = std::filesystem;
    bake::BakeSettings& s = o.settings;
    if (o.mode == "occlusion") s.mode = bake::Mode::Occlusion;
    else if (o.mode == "obscurance") s.mode = bake::Mode::Obscurance;
    else fail("--mode", "expected obscurance or occlusion, got \"" + o.mode + "\"");
    if (o.solver == "auto") s.linearSolver = bake::LinearSolver::Auto;
    else if (o.solver == "cholmod") s.linearSolver = bake::LinearSolver::Cholmod;
    else if (o.solver == "ldlt") s.linearSolver = bake::LinearSolver::SimplicialLDLT;
    else fail("--linear-solver", "expected auto, cholmod or ldlt, got \"" + o.solver + "\"");
    // --distance was once a float whose non-positive (and NaN) values fell back to --distances' default unsaid;
    // given with --distances, one of the two was once dropped without a word.
    if (o.distanceOption->count() > 0 && o.distancesOption->count() > 0)
        fail("--distance", "cannot be given with --distances (--distance d is --distances d); give one of them");
    s.distances = o.distanceOption->count() > 0 ? std::vector<float>{parseBakeDistance("--distance", o.distance)}
                                                : parseBakeDistances("--distances", o.distances);
    s.validate();
    o.controls.validate();
    if (o.rawCheck < 0 || o.rawCheck > kMaxRawCheckStride)
        fail("--raw-embree-check", "must be in [0, " + std::to_string(kMaxRawCheckStride) + "], got " +
                                       std::to_string(o.rawCheck));
    // Before the bake, which can take hours: a directory that takes no new files (read-only, /proc) fails now.
    checkOutputPath("--output", o.output, {".glb", ".gltf", ".ply", ".csv"}, {o.input});
    if (!o.report.empty()) checkOutputPath("--report", o.report, {".json"}, {o.input});

    ThreadLimit limit(o.threads, "--threads");
    const int threads = o.threads > 0 ? o.threads : hardwareThreads();
    const std::string loadBefore = loadAverage();
    auto t0 = std::chrono::steady_clock::now();
    LoadedScene loaded = loadSceneArgument(o.input);
    const double loadSeconds = secondsSince(t0);
    checkRayReach(loaded, *std::min_element(s.distances.begin(), s.distances.end()),
                  o.distanceOption->count() > 0 ? "--distance" : "--distances");
    // A glTF's own vertex colours (a tint, an alpha) are replaced by the baked grey: said, not done quietly.
    if (loaded.colouredPrimitives > 0 && (fileExtension(o.output) == ".glb" || fileExtension(o.output) == ".gltf"))
        std::fprintf(stderr, "obscura: warning: %s: the COLOR_0 of %zu primitive%s is replaced by the baked grey\n",
                     o.input.c_str(), loaded.colouredPrimitives, loaded.colouredPrimitives == 1 ? "" : "s");

    const bool show = progressWanted(o.quiet);
    std::mutex mutex;
    std::string current;
    std::unique_ptr<Progress> bar;
    auto progress = [&](const std::string& stage, double f) {
        if (!show) return;
        std::lock_guard<std::mutex> lock(mutex);
        if (stage != current) {
            bar.reset();
            current = stage;
            bar = std::make_unique<Progress>(stage, true);
        }
        (*bar)(f);
    };
    // The settings were checked above, so what the bake refuses is the scene: its errors name the input (a
    // glTF whose instances scale every face to nothing said only "bake: no triangles left after welding").
    bake::BakeResult r;
    try {
        r = bake::bakeScene(loaded.scene, s, progress, std::size_t(o.rawCheck));
    } catch (const Error& e) {
        bar.reset();
        fail(o.input, e.what());
    }
    progress("write", 0.0);
    auto tw = std::chrono::steady_clock::now();
    bake::writeBakeOutput(o.input, loaded.scene, r, o.controls, o.output);
    // From here a failure removes the output again: a command that fails leaves neither file (checkWritable
    // made that rare: it takes a full disk or a directory changed during the bake).
    OutputGuard written{o.output};
    r.times.write = secondsSince(tw);
    progress("write", 1.0);
    {
        std::lock_guard<std::mutex> lock(mutex);
        bar.reset();
    }
    const std::string loadAfter = loadAverage();

    nlohmann::json j;
    j["input"] = o.input;
    j["output"] = o.output;
    j["mode"] = o.mode;
    j["distances_m"] = s.distances;
    j["rays_per_sample"] = s.rays;
    j["alpha"] = s.alpha;
    j["crease_angle_deg"] = s.creaseAngle;
    j["linear_solver"] = o.solver;
    j["samples_per_face"] = {s.minSamplesPerFace, s.maxSamplesPerFace};
    j["sample_density_per_m2"] = s.sampleDensity;
    j["blend"] = o.controls.blend;
    j["threads"] = threads;
    j["load_average_before"] = loadBefore;
    j["load_average_after"] = loadAfter;
    j["input_triangles"] = r.inputTriangles;
    j["dropped_triangles"] = r.droppedTriangles;
    j["input_vertices"] = r.inputVertices;
    j["welded_vertices"] = r.weldedVertices;
    j["samples"] = r.samples;
    j["invalid_samples"] = r.invalidSamples;
    j["rays"] = r.rays;
    j["mrays_per_s"] = r.mraysPerSecond();
    j["solve"] = {{"unknowns", r.solve.unknowns}, {"interior_edges", r.solve.edges}, {"nonzeros", r.solve.nonZeros}};
    j["stage_seconds"] = {{"load", loadSeconds},
                          {"process_geometry", r.times.processGeometry},
                          {"sample", r.times.sample},
                          {"bvh_build", r.times.bvhBuild},
                          {"trace", r.times.trace},
                          {"least_squares_solve", r.times.solve},
                          {"write", r.times.write},
                          {"total", r.times.total()}};
    if (r.raw.stride > 0)
        j["raw_embree"] = {{"sample_stride", r.raw.stride},
                           {"rays", r.raw.rays},
                           {"seconds", r.raw.seconds},
                           {"mrays_per_s", r.raw.mrays()},
                           {"bake_path_seconds", r.raw.bakeSeconds},
                           {"bake_path_mrays_per_s", r.raw.bakeMrays()},
                           {"bake_path_fraction_of_raw", r.raw.bakeMrays() / r.raw.mrays()},
                           {"trace_stage_fraction_of_raw", r.mraysPerSecond() / r.raw.mrays()}};
    if (!o.report.empty()) {
        const std::string text = j.dump(2) + "\n";
        writeAtomically(o.report, [&](const std::string& temp) {
            std::ofstream out(temp, std::ios::binary);
            out << text;
            out.flush();
            if (!out) fail(o.report, "write failed");
        });
    }
    written.keep = true;
    if (o.quiet) return;
    std::string distances;  // what the bake used, --distance or --distances
    for (float d : s.distances) distances += (distances.empty() ? "" : ",") + numberText(d);
    std::printf("obscura bake: %s -> %s (%s, d = %s m, %d rays/sample, alpha %g, %d threads)\n", o.input.c_str(),
                o.output.c_str(), o.mode.c_str(), distances.c_str(), s.rays, double(s.alpha), threads);
    if (r.droppedTriangles)
        std::printf("dropped %zu triangle%s made degenerate by welding\n", r.droppedTriangles, r.droppedTriangles == 1 ? "" : "s");
    std::printf("\n%-58s %10s\n", "Description", "Time (s)");
    char line[128];
    std::snprintf(line, sizeof line, "Load %s", fs::path(o.input).filename().c_str());
    std::printf("%-58s %10.2f\n", line, loadSeconds);
    std::snprintf(line, sizeof line, "Process geometry, %s V %s F (%s V welded)", human(r.inputVertices).c_str(),
                  human(r.inputTriangles).c_str(), human(r.weldedVertices).c_str());
    std::printf("%-58s %10.2f\n", line, r.times.processGeometry);
    std::snprintf(line, sizeof line, "Samples mesh, %s samples", human(r.samples).c_str());
    std::printf("%-58s %10.2f\n", line, r.times.sample);
    std::printf("%-58s %10.2f\n", "Embree BVH build", r.times.bvhBuild);
    std::snprintf(line, sizeof line, "Ray trace samples, %s rays, %.2f Mrays/s, %s invalid", human(std::size_t(r.rays)).c_str(),
                  r.mraysPerSecond(), human(r.invalidSamples).c_str());
    std::printf("%-58s %10.2f\n", line, r.times.trace);
    std::snprintf(line, sizeof line, "Least squares solve, %s unknowns", human(r.solve.unknowns).c_str());
    std::printf("%-58s %10.2f\n", line, r.times.solve);
    std::snprintf(line, sizeof line, "Write %s", fs::path(o.output).filename().c_str());
    std::printf("%-58s %10.2f\n", line, r.times.write);
    std::printf("%-58s %10.2f\n", "Total (without load)", r.times.total());
    if (r.raw.stride > 0)
        std::printf("\nevery %zu-th sample's rays, alternating batches: bare Embree rtcIntersect1 %.2f Mrays/s, the bake's "
                    "path %.2f Mrays/s = %.2f of raw\n(the whole trace stage above: %.2f of that raw figure)\n",
                    r.raw.stride, r.raw.mrays(), r.raw.bakeMrays(), r.raw.bakeMrays() / r.raw.mrays(),
                    r.mraysPerSecond() / r.raw.mrays());
    std::printf("load average before %s, after %s\n", loadBefore.c_str(), loadAfter.c_str());
}

} // namespace

void addBakeCommand(CLI::App& app) {
    auto o = std::make_shared<BakeOptions>();
    CLI::App* cmd = app.add_subcommand(
        "bake", "Bake per-vertex ambient obscurance by least squares into glTF (COLOR_0, _AO_SHORT, _AO_LONG), PLY or CSV");
    cmd->add_option("input", o->input, "Scene file (.gltf .glb .obj .ply) or built-in scene name")->required();
    cmd->add_option("-o,--output", o->output, "Output .glb, .gltf, .ply (quality) or .csv")->required();
    cmd->add_option("--mode", o->mode, "obscurance (exponential kernel) or occlusion (binary within d)")->capture_default_str();
    o->distancesOption = cmd->add_option("--distances", o->distances, "Half distances d in m, \"short,long\" (short < long) or one value")
                             ->capture_default_str();
    o->distanceOption = cmd->add_option("--distance", o->distance, "One distance d in m (same as --distances d)");
    cmd->add_option("--rays", o->settings.rays, "Rays per sample, [1, 65536]")->capture_default_str();
    cmd->add_option("--alpha", o->settings.alpha, "Regulariser weight, unitless, [0, 1e6]")->capture_default_str();
    cmd->add_option("--max-samples-per-face", o->settings.maxSamplesPerFace, "Sample cap per face, [1, 4096], at least --min-samples-per-face")->capture_default_str();
    cmd->add_option("--min-samples-per-face", o->settings.minSamplesPerFace, "Samples at least per face, [1, 4096], at most --max-samples-per-face")->capture_default_str();
    cmd->add_option("--sample-density", o->settings.sampleDensity, "Samples per m^2 between the two caps")->capture_default_str();
    cmd->add_option("--back-face-limit", o->settings.backFaceLimit, "Invalidate samples with more back-facing hits, [0, 1]")
        ->capture_default_str();
    cmd->add_option("--weld-tolerance", o->settings.weldTolerance, "Weld distance relative to the scene diagonal, [0, 0.01]")
        ->capture_default_str();
    cmd->add_option("--crease-angle", o->settings.creaseAngle,
                    "Faces meeting at a larger angle, degrees, keep separate vertex values, [0, 180]; 180 never splits")
        ->capture_default_str();
    cmd->add_option("--linear-solver", o->solver,
                    "Least-squares factorisation: auto (CHOLMOD if built with it), cholmod, ldlt (Eigen SimplicialLDLT)")
        ->capture_default_str();
    cmd->add_option("--seed", o->settings.seed, "Random seed")->capture_default_str();
    cmd->add_option("--blend", o->controls.blend, "Weight of the short distance in the blend, [0, 1]")->capture_default_str();
    cmd->add_option("--gamma", o->controls.gamma, "Remap exponent of the blend, (0, 16]")->capture_default_str();
    cmd->add_option("--remap-min", o->controls.low, "Remapped value of full obscurance, [0, 1]")->capture_default_str();
    cmd->add_option("--remap-max", o->controls.high, "Remapped value of no obscurance, [0, 1]")->capture_default_str();
    cmd->add_option("--report", o->report, "Write a JSON report (counts, Mrays/s, stage times)");
    cmd->add_option("--raw-embree-check", o->rawCheck,
                    "Also trace every N-th sample's rays with bare Embree and report the bake's fraction of that, [0, 1e9] (0 = off)");
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->capture_default_str();
    cmd->add_flag("-q,--quiet", o->quiet, "No progress and no table");
    cmd->callback([o] { runBake(*o); });
}

} // namespace obscura::cli
