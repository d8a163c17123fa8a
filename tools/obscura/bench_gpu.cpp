// `obscura bench --gpu`: per-pass GPU milliseconds of the screen-space passes from timestamp queries
// (gpu::benchGpuCase), at 1280x720, 1920x1080 and 3840x2160, with Mpixel/s, the compulsory memory traffic
// per frame and its fraction of a bandwidth ceiling, as a table and as JSON.
#include "cli_common.h"
#include "commands.h"
#include "gpu_flags.h"
#include "gtao_cli.h"

#include "obscura/error.h"
#include "obscura/gpu.h"
#include "obscura/gpu_bench.h"
#include "obscura/image_io.h"
#include "obscura/trace.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

namespace obscura::cli {

namespace {

std::vector<std::string> splitList(const std::string& list) {
    std::vector<std::string> out;
    std::stringstream in(list);
    std::string item;
    while (std::getline(in, item, ',')) out.push_back(item);
    return out;
}

// VK_MAKE_API_VERSION's fields (the CLI does not include Vulkan's headers).
std::string apiText(std::uint32_t v) {
    return std::to_string((v >> 22) & 0x7fu) + "." + std::to_string((v >> 12) & 0x3ffu) + "." + std::to_string(v & 0xfffu);
}

struct GpuBenchOptions {
    bool gpu = false;
    std::string sizes = "1280x720,1920x1080,3840x2160";
    std::string cases =
        "alchemy,alchemy-fused,gtao,gtao-half,gtao-spatial,gtao-temporal,gtao-temporal-half,gtao-temporal-grid";
    int frames = 200;
    int warmup = 20;
    int framesPerSubmit = 1;
    int inputs = 4;
    std::string scene = "demo";
    std::string quality = "high";
    int temporalSlices = 1;
    bool visibilityOnly = false;
    bool packedHistory = false;
    bool keepPreviousDepth = false;
    bool alternatingWindow = false;
    int alternatingWindowSize = 4;
    bool packedNormals = false;
    bool packedOutput = false;
    bool fusedTemporal = false;
    std::string sampling = "planar";
    float mipRatio = 7.0f;
    const CLI::Option* mipRatioOption = nullptr;  // --gtao-mip-ratio, warned of where the sampling does not read it
    float radius = 1.0f;
    GtaoSliceFlags gtao;
    int blurRadius = 6;
    int halfBlurRadius = 2;
    std::string halfBlur = "separable";
    bool blurTiled = false;
    double peakGbps = 3000.0;
    int device = -1;
    bool json = false;
    bool pipelineStats = false;
    std::string pipelineInternals;

    void add(CLI::App& bench);
};

void GpuBenchOptions::add(CLI::App& bench) {
    bench.add_flag("--gpu", gpu,
                   "Time the Vulkan compute passes: per-pass GPU ms from timestamp queries (median of --frames after "
                   "--warmup), Mpixel/s, bytes per frame and their share of --peak-gbps");
    bench.add_option("--sizes", sizes, "--gpu: comma-separated WxH sizes")->capture_default_str();
    bench.add_option("--cases", cases,
                     "--gpu: comma-separated cases: alchemy, alchemy-fused, gtao, gtao-half, gtao-spatial, gtao-temporal, "
                     "gtao-temporal-half, gtao-temporal-grid")
        ->capture_default_str();
    bench.add_option("--frames", frames, "--gpu: timed frames per case and size, [1, 100000]")->capture_default_str();
    bench.add_option("--warmup", warmup, "--gpu: untimed frames before them, [0, 10000]")->capture_default_str();
    bench.add_option("--frames-per-submit", framesPerSubmit,
                     "--gpu: frames recorded into one submission, back to back with a barrier between them, as an "
                     "engine's frames follow each other, [1, 64]; with 1 the GPU idles between frames (an H100 "
                     "gave the same times either way, its clocks unchanged)")
        ->capture_default_str();
    bench.add_option("--inputs", inputs,
                     "--gpu: G-buffers the frames rotate through (the camera path's first frames), so no frame reads "
                     "its inputs from the caches the last one left, [1, 16]")
        ->capture_default_str();
    bench.add_option("--scene", scene, "--gpu: built-in scene or scene file")->capture_default_str();
    bench.add_option("--ao-quality", quality, "--gpu: GTAO preset of the gtao cases: low, medium, high, ultra")
        ->check(CLI::IsMember({"low", "medium", "high", "ultra"}))
        ->capture_default_str();
    bench.add_option("--temporal-slices", temporalSlices, "--gpu: slices per pixel of the temporal cases, [1, 64]")
        ->capture_default_str();
    bench.add_flag("--visibility-only", visibilityOnly,
                   "--gpu: the GTAO cases compute and accumulate visibility alone, no bent normal (the AO-only variant "
                   "an engine without bent-normal lighting runs, and what XeGTAO computes by default)");
    bench.add_flag("--packed-history", packedHistory,
                   "--gpu: the temporal cases keep their history in packed words (visibility + length, octahedral "
                   "normals: 4 words per pixel instead of 9 floats, 3 instead of 6 with --visibility-only)");
    bench.add_flag("--keep-previous-depth", keepPreviousDepth,
                   "--gpu: the temporal cases read the previous frame's depth buffer instead of a copy in the history, "
                   "as an engine that keeps last frame's depth (for TAA, say) can");
    bench.add_flag("--packed-normals", packedNormals,
                   "--gpu: every case reads the G-buffer's normals as one octahedral word per pixel (two snorm16, as "
                   "engines keep them) instead of 3 floats");
    bench.add_flag("--packed-output", packedOutput,
                   "--gpu: the gtao-temporal-grid case writes its visibility as unorm16, two pixels to a word (what an "
                   "R16_UNORM image holds) instead of a float per pixel; the other cases write floats");
    bench.add_flag("--fused-temporal", fusedTemporal,
                   "--gpu: the gtao-temporal-grid case evaluates GTAO, reconstructs and accumulates the grid in one "
                   "dispatch (its 'temporal' pass, with no 'gtao' pass) instead of two; the same values");
    bench.add_flag("--alternating-window", alternatingWindow,
                   "--gpu: the temporal cases reconstruct with a 4x4 window (16 taps instead of 25) whose place "
                   "alternates over 4 frames, which the history averages to the 5x5 window's weights");
    bench.add_option("--alternating-window-size", alternatingWindowSize,
                     "--gpu with --alternating-window: the windows' side, 4 (16 taps) or 2 (4 taps, each window "
                     "holding the pixel, which the history averages to a 3x3 tent)")
        ->capture_default_str();
    mipRatioOption = addGtaoSamplingOption(bench, sampling, mipRatio, "--gpu: how the GTAO cases' horizon samples read depth");
    gtao.add(bench, "--gpu, the GTAO cases", "; the temporal cases take --temporal-slices",
             "; the gtao and gtao-half cases only: the others rotate by their 4x4 interleave");
    bench.add_option("--blur-radius", blurRadius,
                     "--gpu: taps on each side of the alchemy and gtao cases' separable blur, [1, 32] (6: 13 taps, the "
                     "paper's)")
        ->capture_default_str();
    bench.add_option("--half-blur-radius", halfBlurRadius,
                     "--gpu: taps on each side of the gtao-half case's blur, on the half-resolution grid, [1, 32] (2: 5 "
                     "taps)")
        ->capture_default_str();
    bench.add_option("--half-blur", halfBlur,
                     "--gpu: the gtao-half case's blur, separable (two dispatches from shared memory) or 2d (one "
                     "dispatch, (2r+1)^2 taps); both by depth alone")
        ->check(CLI::IsMember({"separable", "2d"}))
        ->capture_default_str();
    bench.add_flag("--blur-tiled", blurTiled,
                   "--gpu: the separable blurs of the alchemy, gtao and gtao-half cases in one dispatch instead of two: "
                   "each workgroup blurs the rows of a 32x32 tile and its apron, then the tile's columns, from shared "
                   "memory (12 bytes per pixel instead of 24, one barrier fewer; the same bits); radii up to " +
                       std::to_string(gpu::kTiledBlurMaxRadius));
    bench.add_option("--ao-radius", radius,
                     "--gpu: the GTAO cases' radius, m, (0, 1e4]; a smaller one keeps the horizon samples nearer the "
                     "pixel on screen (fewer cache lines per frame, nearly the same arithmetic)")
        ->capture_default_str();
    bench.add_option("--peak-gbps", peakGbps,
                     "--gpu: bandwidth ceiling the traffic is compared with, GB/s (default: a compute-shader copy on "
                     "an H100, 3.0 TB/s)")
        ->capture_default_str();
    bench.add_option("--gpu-device", device, "--gpu: Vulkan device index (-1: OBSCURA_GPU_DEVICE, else the first discrete GPU)")
        ->capture_default_str();
    bench.add_flag("--json", json,
                   "--gpu: print JSON instead of a table (each case also names the shaders its frames dispatched, "
                   "\"shaders\")");
    bench.add_flag("--pipeline-stats", pipelineStats,
                   "--gpu: after the timings, what the driver says of each compute pipeline it compiled "
                   "(VK_KHR_pipeline_executable_properties: registers per invocation, code size, spills, ... as the "
                   "driver names them), so occupancy can be read beside the times; a driver without the extension "
                   "is named and the run goes on");
    bench.add_option("--pipeline-internals", pipelineInternals,
                     "--gpu: also write each pipeline's internal representations (the driver's intermediate or "
                     "machine code, where it gives them) into this folder, one file each: PIPELINE.N.NAME.txt "
                     "(.bin where not text); implies --pipeline-stats");
}

// A pipeline's or representation's name as a file name: letters, digits, '-' and '_'; others become '_'.
std::string fileWord(const std::string& name) {
    std::string w;
    for (const char ch : name) w.push_back(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' ? ch : '_');
    return w.empty() ? "_" : w;
}

// --pipeline-stats and --pipeline-internals: the driver's statistics of every pipeline the cases made, into
// the report (and printed unless --json), and its internal representations into the folder.
void reportPipelines(const gpu::Context& context, const GpuBenchOptions& o, nlohmann::json& report) {
    const gpu::DeviceInfo& info = context.device();
    report["pipeline_statistics"] = info.pipelineStatistics;
    if (!info.pipelineStatistics) {
        const std::string note = info.name + " (" + info.driver +
                                 ") does not offer VK_KHR_pipeline_executable_properties: no pipeline statistics";
        report["pipeline_statistics_note"] = note;
        if (!o.json) std::printf("\npipelines: %s\n", note.c_str());
        return;
    }
    nlohmann::json pipelines = nlohmann::json::array();
    int written = 0;
    if (!o.json) std::printf("\npipelines (the driver's statistics of each executable):\n");
    for (const gpu::PipelineReport& p : context.pipelineReports()) {
        nlohmann::json executables = nlohmann::json::array();
        for (std::size_t e = 0; e < p.executables.size(); ++e) {
            const gpu::PipelineExecutable& x = p.executables[e];
            nlohmann::json statistics = nlohmann::json::array();
            std::string line;
            for (const gpu::PipelineStatistic& s : x.statistics) {
                statistics.push_back({{"name", s.name}, {"description", s.description}, {"value", s.value}});
                char v[48];
                std::snprintf(v, sizeof v, "%g", s.value);
                line += (line.empty() ? "" : ", ") + s.name + " " + v;
            }
            nlohmann::json files = nlohmann::json::array();
            for (const gpu::PipelineInternal& r : x.internals) {
                const std::filesystem::path file = std::filesystem::path(o.pipelineInternals) /
                    (fileWord(p.pipeline) + "." + std::to_string(e) + "." + fileWord(r.name) + (r.text ? ".txt" : ".bin"));
                writeAtomically(file.string(), [&](const std::string& temp) {
                    std::ofstream out(temp, std::ios::binary);
                    out << r.data;
                    out.flush();
                    if (!out) fail(file.string(), "write failed");
                });
                files.push_back(file.string());
                ++written;
            }
            executables.push_back({{"name", x.name},
                                   {"description", x.description},
                                   {"subgroup_size", x.subgroupSize},
                                   {"statistics", statistics},
                                   {"internal_files", files}});
            if (!o.json)
                std::printf("  %-40s %s (subgroup %u): %s\n", p.pipeline.c_str(), x.name.c_str(), x.subgroupSize,
                            line.empty() ? "(no statistics)" : line.c_str());
        }
        if (!p.error.empty() && !o.json) std::printf("  %-40s (the driver refused: %s)\n", p.pipeline.c_str(), p.error.c_str());
        pipelines.push_back({{"pipeline", p.pipeline}, {"executables", executables}, {"error", p.error}});
    }
    report["pipelines"] = pipelines;
    if (!o.json && !o.pipelineInternals.empty())
        std::printf("%d internal representation(s) written to %s\n", written, o.pipelineInternals.c_str());
}

void runGpuBench(const GpuBenchOptions& o) {
    gpu::GpuBenchSettings settings;
    settings.frames = o.frames;
    settings.warmup = o.warmup;
    settings.framesPerSubmit = o.framesPerSubmit;
    settings.quality = ssao::parseQuality(o.quality);
    settings.temporalSlices = o.temporalSlices;
    settings.gtao = o.gtao.value;
    settings.blurRadius = o.blurRadius;
    settings.halfBlurRadius = o.halfBlurRadius;
    settings.halfBlur2D = o.halfBlur == "2d";
    settings.blurTiled = o.blurTiled;
    settings.bentNormals = !o.visibilityOnly;
    settings.packedHistory = o.packedHistory;
    settings.callerKeepsDepth = o.keepPreviousDepth;
    settings.packedNormals = o.packedNormals;
    settings.packedOutput = o.packedOutput;
    settings.fusedTemporal = o.fusedTemporal;
    settings.alternatingWindow = o.alternatingWindow;
    settings.alternatingWindowSize = o.alternatingWindowSize;
    settings.sampling = gtaoSampling(o.sampling);
    settings.mipDistanceRatio = o.mipRatio;
    settings.gtaoRadius = o.radius;
    try {
        settings.validate();
    } catch (const Error& e) {
        // "gpu-bench-frames: ..." -> "--frames: ..."
        const std::string what = e.what();
        throw Error("--" + what.substr(std::string("gpu-bench-").size()));
    }
    if (o.inputs < 1 || o.inputs > 16) fail("--inputs", "must be in [1, 16]");
    if (!(o.peakGbps > 0.0 && o.peakGbps < 1e6)) fail("--peak-gbps", "must be in (0, 1e6) GB/s");
    if (o.alternatingWindowSize != 4 && !o.alternatingWindow)
        fail("--alternating-window-size", "needs --alternating-window");
    GpuFlags device{true, o.device};
    device.pipelineStatistics = o.pipelineStats || !o.pipelineInternals.empty();
    device.pipelineInternals = !o.pipelineInternals.empty();
    device.validate();
    if (!o.pipelineInternals.empty() && std::filesystem::exists(o.pipelineInternals) &&
        !std::filesystem::is_directory(o.pipelineInternals))
        fail("--pipeline-internals " + o.pipelineInternals, "is not a folder");
    if (o.mipRatioOption && o.mipRatioOption->count() > 0)
        warnGtaoMipRatioUnread(o.mipRatio, ssao::gtaoSamplingReadsMipRatio(gtaoSampling(o.sampling)),
                               "--gtao-sampling " + o.sampling + " does not read it");
    std::vector<std::pair<int, int>> sizes;
    for (const std::string& s : splitList(o.sizes)) {
        int w = 0, h = 0;
        parseSize("--sizes", s, w, h);
        // A size or case twice printed two rows, of which scripts/gpu-ab kept the second (warmer) one alone.
        if (std::find(sizes.begin(), sizes.end(), std::pair{w, h}) != sizes.end())
            fail("--sizes", s + " is given twice");
        sizes.push_back({w, h});
    }
    if (sizes.empty()) fail("--sizes", "no size given");
    const std::vector<std::string> cases = splitList(o.cases);
    if (cases.empty()) fail("--cases", "no case given");
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const std::string& c = cases[i];
        if (std::find(cases.begin(), cases.begin() + std::ptrdiff_t(i), c) != cases.begin() + std::ptrdiff_t(i))
            fail("--cases", c + " is given twice");
        bool known = false;
        std::string names;
        for (const gpu::GpuBenchCaseInfo& info : gpu::gpuBenchCases()) {
            known = known || info.name == c;
            names += (names.empty() ? "" : ", ") + info.name;
        }
        if (!known) fail("--cases", "unknown case '" + c + "' (known: " + names + ")");
    }

    const std::unique_ptr<gpu::Context> opened = device.open();
    gpu::Context& context = *opened;
    const gpu::DeviceInfo& info = context.device();
    LoadedScene loaded = loadSceneArgument(o.scene);
    trace::Tracer tracer(loaded.scene);
    // Made once the device has opened and the scene loaded, so that a run failing on them leaves no folder.
    if (!o.pipelineInternals.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(o.pipelineInternals, ec);
        if (!std::filesystem::is_directory(o.pipelineInternals))
            fail("--pipeline-internals " + o.pipelineInternals, "is not a folder and cannot be made one");
    }

    char date[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    nlohmann::json report;
    report["device"] = info.name;
    report["driver"] = info.driver;
    report["vulkan"] = apiText(info.apiVersion);
    report["date"] = date;
    report["scene"] = loaded.name;
    report["frames"] = o.frames;
    report["warmup"] = o.warmup;
    report["frames_per_submit"] = o.framesPerSubmit;
    report["inputs"] = o.inputs;
    report["peak_gbps"] = o.peakGbps;
    report["bent_normals"] = settings.bentNormals;
    report["packed_history"] = settings.packedHistory;
    report["keep_previous_depth"] = settings.callerKeepsDepth;
    report["packed_normals"] = settings.packedNormals;
    report["packed_output"] = settings.packedOutput;
    report["fused_temporal"] = settings.fusedTemporal;
    report["alternating_window"] = settings.alternatingWindow;
    report["alternating_window_size"] = settings.alternatingWindow ? settings.alternatingWindowSize : 0;
    report["gtao_sampling"] = o.sampling;
    report["gtao_mip_ratio"] = o.mipRatio;
    report["gtao_radius_m"] = o.radius;
    report["gtao_slices"] = o.gtao.value.slices;  // 0: the preset's (the descriptions give each case's counts)
    report["gtao_steps"] = o.gtao.value.steps;
    report["gtao_jitter"] = o.gtao.value.jitter;
    report["gtao_interleave"] = o.gtao.value.interleave;
    report["blur_radius"] = o.blurRadius;
    report["half_blur_radius"] = o.halfBlurRadius;
    report["half_blur"] = o.halfBlur;
    report["blur_tiled"] = o.blurTiled;
    report["validation"] = context.validation();
    if (!o.json) {
        std::string variants;  // the flags that change what the GTAO cases run
        if (o.visibilityOnly) variants += ", GTAO visibility only";
        if (o.packedHistory) variants += ", packed history";
        if (o.keepPreviousDepth) variants += ", previous depth kept";
        if (o.packedNormals) variants += ", octahedral normals";
        if (o.packedOutput) variants += ", unorm16 output (gtao-temporal-grid)";
        if (o.fusedTemporal) variants += ", GTAO and accumulation fused (gtao-temporal-grid)";
        if (o.alternatingWindow)
            variants += o.alternatingWindowSize == 2 ? ", alternating 2x2 windows" : ", alternating 4x4 windows";
        ssao::GtaoSettings sampling;
        sampling.sampling = settings.sampling;
        sampling.mipDistanceRatio = settings.mipDistanceRatio;
        if (settings.sampling != ssao::GtaoSampling::Planar) variants += ", GTAO " + ssao::gtaoSamplingText(sampling);
        if (o.gtao.value.slices != 0) variants += ", GTAO " + std::to_string(o.gtao.value.slices) + " slices";
        if (o.gtao.value.steps != 0) variants += ", GTAO " + std::to_string(o.gtao.value.steps) + " steps per side";
        if (o.gtao.value.jitter) variants += ", GTAO jittered";
        if (o.gtao.value.interleave) variants += ", GTAO slices by the 4x4 interleave";
        if (o.blurRadius != gpu::GpuBenchSettings{}.blurRadius)
            variants += ", blur " + std::to_string(2 * o.blurRadius + 1) + " taps per axis";
        if (o.halfBlurRadius != gpu::GpuBenchSettings{}.halfBlurRadius)
            variants += ", half-resolution blur " + std::to_string(2 * o.halfBlurRadius + 1) + " taps per axis";
        if (o.halfBlur == "2d") variants += ", half-resolution blur in 2-D";
        if (o.blurTiled) variants += ", separable blurs in one tiled dispatch";
        if (settings.gtaoRadius != gpu::GpuBenchSettings{}.gtaoRadius) {
            char text[48];
            std::snprintf(text, sizeof text, ", GTAO r %g m", double(o.radius));
            variants += text;
        }
        std::printf("obscura bench --gpu: %s (%s, Vulkan %s), %s\n", info.name.c_str(), info.driver.c_str(),
                    apiText(info.apiVersion).c_str(), date);
        std::printf("scene %s%s; GPU ms from timestamps, median of %d frames after %d warm-up, %d per submission, "
                    "rotating %d inputs;\n"
                    "MB = compulsory traffic per frame (each buffer a dispatch reads or writes, once); %% = its rate "
                    "over %.0f GB/s%s\n",
                    loaded.name.c_str(), variants.c_str(), o.frames, o.warmup, o.framesPerSubmit,
                    o.inputs, o.peakGbps,
                    context.validation() ? "; VALIDATION ON (timings are not representative)" : "");
    }
    bool headerPrinted = false;
    for (auto [w, h] : sizes) {
        std::vector<GBuffer> inputs;
        for (int k = 0; k < o.inputs; ++k) {
            Camera camera = gtaoPathCamera(loaded.camera, k);
            camera.width = w;
            camera.height = h;
            inputs.push_back(trace::renderGBuffer(tracer, camera));
        }
        char size[24];
        std::snprintf(size, sizeof size, "%dx%d", w, h);
        for (const std::string& name : cases) {
            Progress progress(name + " " + size, progressWanted(false));
            const gpu::GpuBenchCase r =
                gpu::benchGpuCase(context, name, inputs, settings, [&](double f) { progress(f); });
            const double fraction = r.gigabytesPerSecond() / o.peakGbps;
            nlohmann::json passes = nlohmann::json::array();
            std::string passText;
            for (const gpu::GpuPassTime& p : r.passes) {
                passes.push_back({{"name", p.name}, {"median_ms", p.medianMs}, {"min_ms", p.minMs}});
                char b[64];
                std::snprintf(b, sizeof b, "%s%s %.4f", passText.empty() ? "" : ", ", p.name.c_str(), p.medianMs);
                passText += b;
            }
            report["cases"].push_back({{"case", r.name},
                                       {"description", r.description},
                                       {"width", r.width},
                                       {"height", r.height},
                                       {"median_ms", r.medianMs},
                                       {"min_ms", r.minMs},
                                       {"mpixels_per_s", r.mpixelsPerSecond()},
                                       {"bytes_per_frame", r.bytes},
                                       {"gbytes_per_s", r.gigabytesPerSecond()},
                                       {"fraction_of_peak", fraction},
                                       {"passes", passes},
                                       {"shaders", r.shaders}});
            if (o.json) continue;
            if (!headerPrinted) {
                std::printf("\n%-19s %-10s %9s %9s %10s %8s %6s  %s\n", "case", "size", "ms", "min ms", "Mpixel/s", "MB",
                            "%peak", "passes (median ms)");
                headerPrinted = true;
            }
            std::printf("%-19s %-10s %9.4f %9.4f %10.0f %8.1f %5.1f%%  %s\n", r.name.c_str(), size, r.medianMs, r.minMs,
                        r.mpixelsPerSecond(), r.bytes * 1e-6, 100.0 * fraction, passText.c_str());
            std::fflush(stdout);  // a row as soon as it is measured, also into a pipe or a file
        }
    }
    if (!o.json) {
        std::printf("\ncases:\n");
        for (const std::string& name : cases)
            for (const auto& c : report["cases"])
                if (c["case"] == name) {
                    std::printf("  %-19s %s\n", name.c_str(), c["description"].get<std::string>().c_str());
                    break;
                }
    }
    if (device.pipelineStatistics) reportPipelines(context, o, report);
    reportValidation(&context);
    if (o.json) std::printf("%s\n", report.dump(2).c_str());
}

} // namespace

void addGpuBench(CLI::App& bench) {
    auto o = std::make_shared<GpuBenchOptions>();
    o->add(bench);
    // Before any callback runs (a subcommand's ran first, and `bench --gpu trace` printed its whole table, then
    // failed): bench's own options belong to --gpu, and `bench --scene cabinet trace` timed demo with exit 0.
    bench.parse_complete_callback([&bench] {
        if (bench.get_subcommands().empty()) return;
        const std::string sub = bench.get_subcommands().front()->get_name();
        for (const CLI::Option* option : bench.get_options())
            if (option->count() > 0 && option->get_name() != "--help")
                fail(option->get_name(), option->get_name() == "--gpu"
                                             ? "times the GPU passes by itself; give it without a subcommand"
                                             : "is an option of bench --gpu, not of bench " + sub +
                                                   " (a subcommand's options follow its name: bench " + sub +
                                                   " --help lists them)");
    });
    // `bench --gpu` runs after option parsing; `bench SUBCOMMAND` runs the subcommand's callback instead.
    bench.callback([o, &bench] {
        if (!bench.get_subcommands().empty()) return;
        // A command line that asks for nothing: exit 2 with the others of its kind (main), not 1.
        if (!o->gpu) throw CLI::ValidationError("bench", "needs a subcommand (trace, alchemy, gtao, bake-quality) or --gpu");
        runGpuBench(*o);
    });
}

} // namespace obscura::cli
