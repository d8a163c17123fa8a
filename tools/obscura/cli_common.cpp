// Argument helpers shared by the subcommands.
#include "cli_common.h"

#include "obscura/bake.h"
#include "obscura/builtin_scenes.h"
#include "obscura/error.h"
#include "obscura/image_io.h"
#include "obscura/statistics.h"
#include "obscura/scene_io.h"
#include "obscura/trace.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <ctime>
#include <unistd.h>
#include <utility>

namespace obscura::cli {

namespace fs = std::filesystem;

LoadedScene loadSceneArgument(const std::string& argument) {
    LoadedScene out;
    // A file of that name wins over a built-in scene, a directory does not: `gbuffer plane -o plane` makes
    // one, and a second run then failed with "plane: unknown scene format ''".
    std::error_code ec;
    const bool file = fs::exists(argument, ec) && !fs::is_directory(argument, ec);
    // Nor does a file without a scene file's extension (no built-in name has one): it could not be loaded, and a
    // stray file `demo` in the working directory made a plain `obscura render` fail.
    if (isBuiltinScene(argument) && !(file && isSceneFileExtension(fileExtension(argument)))) {
        BuiltinScene b = makeBuiltinScene(argument);
        out.name = b.name;
        out.scene = std::move(b.scene);
        out.camera = b.camera;
        return out;
    }
    if (fileExtension(argument).empty() && !fs::exists(argument))
        fail(argument, "no such built-in scene or file (run `obscura scenes` for the list)");
    LoadInfo info;
    out.scene = loadScene(argument, &info);
    out.name = argument;
    out.colouredPrimitives = info.colouredPrimitives;
    if (info.droppedTriangles > 0)
        std::fprintf(stderr, "obscura: warning: %s: dropped %zu degenerate triangle%s\n", argument.c_str(),
                     info.droppedTriangles, info.droppedTriangles == 1 ? "" : "s");
    if (info.skippedPrimitives > 0)
        std::fprintf(stderr, "obscura: warning: %s: skipped %zu non-triangle primitive%s\n", argument.c_str(),
                     info.skippedPrimitives, info.skippedPrimitives == 1 ? "" : "s");
    // Frame the bounds from the front, a little above, the whole scene in view.
    Bounds b = out.scene.bounds();
    Vec3 c = b.center();
    float radius = 0.5f * length(b.size());
    float distance = radius / std::sin(0.5f * 60.0f * kPi / 180.0f);
    out.camera.position = c + normalize(Vec3{0.5f, 0.45f, 1.0f}) * distance;
    out.camera.target = c;
    // Relative only: an absolute floor of 0.1 mm put the near plane past a 40 um scene, which rendered as sky.
    out.camera.nearZ = distance * 1e-4f;
    out.camera.farZ = distance * 10.0f + radius * 10.0f;
    return out;
}

void checkRayReach(const LoadedScene& scene, float reach, const std::string& flag) {
    bool refuse = false;
    const std::string why = trace::rayReachProblem(scene.scene.bounds(), reach, scene.name, refuse);
    if (refuse) fail(flag, why);
    if (!why.empty())
        std::fprintf(stderr, "obscura: warning: %s: %s (the AO is lighter for it)\n", flag.c_str(), why.c_str());
}

long long parseLevelTriangles(const std::string& flag, const std::string& text) {
    std::istringstream in(text);
    double value = 0;
    // In double, exact for every whole number up to 2^53, far past the range; "2e8" and "200000000" alike.
    if (!(in >> value) || !(in >> std::ws).eof() || !std::isfinite(value) || value != std::floor(value))
        fail(flag, "expected a whole number of triangles, e.g. 1000000 or 1e6, got \"" + text + "\"");
    if (value < double(kMinLevelTriangles) || value > double(kMaxLevelTriangles))
        fail(flag, "must be in [" + std::to_string(kMinLevelTriangles) + ", " + std::to_string(kMaxLevelTriangles) +
                       "], got " + text);
    return static_cast<long long>(value);
}

Vec3 parseVec3(const std::string& flag, const std::string& text) {
    Vec3 v;
    char c1 = 0, c2 = 0;
    std::istringstream in(text);
    if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !(in >> std::ws).eof() || !isFinite(v))
        fail(flag, "expected three finite numbers \"x,y,z\", got \"" + text + "\"");
    return v;
}

void parseSize(const std::string& flag, const std::string& text, int& width, int& height) {
    long w = 0, h = 0;
    char x = 0;
    std::istringstream in(text);
    if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || !(in >> std::ws).eof())
        fail(flag, "expected WIDTHxHEIGHT, e.g. 1920x1080, got \"" + text + "\"");
    if (w < 1 || h < 1) fail(flag, "image size must be at least 1x1, got " + text);
    if (w > kMaxImageSide || h > kMaxImageSide)
        fail(flag, "image size " + text + " exceeds " + std::to_string(kMaxImageSide) + " on a side");
    width = int(w);
    height = int(h);
}

bool parseDecimal(const std::string& text, float& value) {
    // from_chars, not strtof: strtof also reads hex floats and skips leading spaces but not trailing ones.
    const auto space = [](char c) { return c == ' ' || c == '\t'; };
    const char* first = text.data();
    const char* last = first + text.size();
    while (first != last && space(*first)) ++first;
    while (last != first && space(last[-1])) --last;
    if (first != last && *first == '+' && last - first > 1 && first[1] != '-' && first[1] != '+') ++first;
    const auto [end, error] = std::from_chars(first, last, value, std::chars_format::general);
    return first != last && error == std::errc() && end == last;
}

float parseRadius(const std::string& flag, const std::string& text) {
    float r = 0.0f;
    if (!parseDecimal(text, r) || !(r > 0.0f))
        fail(flag, "expected a distance > 0 in meters or \"inf\", got \"" + text + "\"");
    return r;
}

// BakeSettings::validate's bound on a distance, checked here too so that the message names the flag the user
// gave (--distance or --distances) and does not offer "inf", which the bake refuses.
constexpr float kMaxBakeDistance = bake::BakeSettings::kMaxDistance;

float parseBakeDistance(const std::string& flag, const std::string& text) {
    float d = 0.0f;
    if (!parseDecimal(text, d) || !(d > 0.0f && d <= kMaxBakeDistance))
        fail(flag, "expected a distance in (0, 1e6] m, got \"" + text + "\"");
    return d;
}

// Split by hand: getline drops a trailing empty item, so "1," read as one distance while ",2" and "1,,2"
// failed. The order matters downstream: channel 0 is _AO_SHORT and takes --blend's weight.
std::vector<float> parseBakeDistances(const std::string& flag, const std::string& text) {
    std::vector<std::string> items;
    for (std::size_t start = 0;;) {
        const std::size_t comma = text.find(',', start);
        items.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    const bool blank = std::any_of(items.begin(), items.end(),
                                   [](const std::string& item) { return item.find_first_not_of(" \t") == std::string::npos; });
    if (items.size() > 2 || blank) fail(flag, "expected one or two distances \"short,long\", got \"" + text + "\"");
    std::vector<float> out;
    for (const std::string& item : items) out.push_back(parseBakeDistance(flag, item));
    if (out.size() == 2 && !(out[0] < out[1]))
        fail(flag, "the short distance must be less than the long one, got \"" + text + "\"");
    return out;
}

void CameraOptions::add(CLI::App& app) {
    app.add_option("--size", size, "Image size WIDTHxHEIGHT in pixels")->capture_default_str();
    app.add_option("--camera-from", from, "Camera position \"x,y,z\" in world meters (default: the scene's)");
    app.add_option("--camera-to", to, "Point the camera looks at, \"x,y,z\" (default: the scene's)");
    app.add_option("--camera-up", up, "Up direction \"x,y,z\" (default 0,1,0)");
    fovOption = app.add_option("--fov", fov, "Vertical field of view in degrees, [0.001, 180) (default: the scene's, usually 60)");
    nearOption = app.add_option("--near", nearZ, "Near plane distance in meters (default: the scene's)");
    farOption = app.add_option("--far", farZ, "Far plane distance in meters (default: the scene's)");
}

Camera CameraOptions::apply(const LoadedScene& scene) const {
    Camera c = scene.camera;
    parseSize("--size", size, c.width, c.height);
    if (!from.empty()) c.position = parseVec3("--camera-from", from);
    if (!to.empty()) c.target = parseVec3("--camera-to", to);
    if (!up.empty()) c.up = parseVec3("--camera-up", up);
    // Given or not is the option's count, not a value of 0: `--fov 0` was taken as "the scene's" (60 degrees),
    // and `--near 0` / `--far 0` likewise, where the help promises [0.001, 180) and 0 < near < far.
    const bool fovGiven = fovOption && fovOption->count() > 0;
    const bool nearGiven = nearOption && nearOption->count() > 0;
    const bool farGiven = farOption && farOption->count() > 0;
    if (fovGiven) {
        if (!(fov >= kMinFovDegrees && fov < 180.0f))
            fail("--fov", "must be in [" + numberText(kMinFovDegrees) + ", 180) degrees, got " + numberText(fov));
        c.fovY = fov;
    }
    if (nearGiven) c.nearZ = nearZ;
    if (farGiven) c.farZ = farZ;
    // A camera moved by --camera-from or --camera-to keeps the whole scene in reach: the default framing's far
    // plane, set for its own position, clipped a scene seen from farther away to sky.
    if ((!from.empty() || !to.empty()) && !farGiven && !scene.scene.instances.empty()) {
        const Bounds b = scene.scene.bounds();
        float reach = 0.0f;
        for (int k = 0; k < 8; ++k)
            reach = std::max(reach, length(Vec3{(k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y,
                                                (k & 4) ? b.hi.z : b.lo.z} - c.position));
        if (std::isfinite(reach)) c.farZ = std::max(c.farZ, 2.0f * reach);
    }
    try {
        c.validate();
    } catch (const Error& e) {
        const std::string problem = std::string(e.what()).substr(8);  // drop the "camera: " prefix
        if (from.empty() && to.empty() && up.empty() && !fovGiven && !nearGiven && !farGiven)
            fail(scene.name, "cannot be framed by the default camera (its bounds span " +
                                 numberText(length(scene.scene.bounds().size())) + " m; " + problem +
                                 "): give --camera-from, --camera-to, --near and --far");
        fail("camera flags", problem);
    }
    return c;
}

std::vector<const CLI::Option*> optionsAddedBy(CLI::App& app, const std::function<void()>& add) {
    const std::size_t before = app.get_options().size();
    add();
    const std::vector<const CLI::Option*> all = std::as_const(app).get_options();
    // get_options lists them in the order they were added.
    return {all.begin() + std::ptrdiff_t(before), all.end()};
}

void refuseEmptyValues(CLI::App& app) {
    // No description, so --help shows nothing of it; CLI11 prefixes the option's name to the message.
    const CLI::Validator nonEmpty([](const std::string& value) { return value.empty() ? "empty value" : ""; }, "");
    for (CLI::Option* option : app.get_options())
        if (option->get_type_size() != 0) option->check(nonEmpty);
    for (CLI::App* sub : app.get_subcommands({})) refuseEmptyValues(*sub);
}

void warnIgnored(const std::vector<const CLI::Option*>& options, const std::string& why) {
    for (const CLI::Option* option : options)
        if (option->count() > 0)
            std::fprintf(stderr, "obscura: warning: %s: %s; ignored\n", option->get_name().c_str(), why.c_str());
}

namespace {

// The extensions as a list for a message ("a, b, c", or with `last` before the last: "a or b"), and whether
// path has one of them.
std::string extensionList(const std::vector<std::string>& extensions, const std::string& last = ", ") {
    std::string list;
    for (std::size_t i = 0; i < extensions.size(); ++i)
        list += (i == 0 ? "" : i + 1 == extensions.size() ? last : ", ") + extensions[i];
    return list;
}

bool hasExtension(const std::string& path, const std::vector<std::string>& extensions) {
    return std::find(extensions.begin(), extensions.end(), fileExtension(path)) != extensions.end();
}

} // namespace

void checkOutputPath(const std::string& flag, const std::string& path, const std::vector<std::string>& extensions,
                     const std::vector<std::string>& inputs) {
    if (path.empty()) fail(flag, "output path is empty");
    if (!hasExtension(path, extensions))
        fail(path, fileExtension(path).empty()
                       ? "has no extension to tell the output format (expected " + extensionList(extensions) + ")"
                       : "unsupported output format '" + fileExtension(path) + "' (expected " +
                             extensionList(extensions) + ")");
    fs::path parent = fs::path(path).parent_path();
    if (!parent.empty() && !fs::is_directory(parent)) fail(path, "directory " + parent.string() + " does not exist");
    std::error_code ec;
    if (fs::is_directory(path, ec)) fail(path, "is a directory");
    for (const std::string& input : inputs)
        if (samePath(path, input))
            fail(path, "is the input file " + input + "; the input is never overwritten, choose another output");
    // A name the file system cannot hold failed only at the rename, after the work (the temporary's name is
    // cut to fit, so the check below passes).
    if (const std::size_t length = fs::path(path).filename().string().size(); length > 255)
        fail(path, "the file name is " + std::to_string(length) + " bytes, past the 255 a file system takes");
    // A directory that takes no new file (read-only, /proc) fails now, not after the work: compare traced its
    // references before -o /proc/x.png failed, and --json's figures were lost with it.
    checkWritable(path);
}

bool samePath(const std::string& a, const std::string& b) {
    if (a.empty() || b.empty()) return false;
    std::error_code ea, eb;
    if (fs::exists(a, ea) && fs::exists(b, eb)) return fs::equivalent(a, b, ea) && !ea;
    // Absolute first: weakly_canonical leaves a path relative when no part of it exists, so "ao.exr" and
    // "./ao.exr" compared unequal and --aov-dir . overwrote -o ao.exr.
    const fs::path aa = fs::absolute(a, ea), ab = fs::absolute(b, eb);
    if (ea || eb) return false;
    const fs::path ca = fs::weakly_canonical(aa, ea), cb = fs::weakly_canonical(ab, eb);
    return !ea && !eb && ca == cb;
}

void checkInputFormat(const std::string& flag, const std::string& path, const std::vector<std::string>& extensions,
                      const std::string& content) {
    if (path.empty() || hasExtension(path, extensions)) return;
    const std::string ext = fileExtension(path);
    fail(flag, path + ": " + content + " is read from " + extensionList(extensions, " or ") + " files, not " +
                   (ext.empty() ? std::string("a file without an extension") : ext));
}

void checkSupersample(int supersample) {
    if (supersample < 1 || supersample > 16)
        fail("--supersample", "must be in [1, 16], got " + std::to_string(supersample));
}

void checkOutputDirectory(const std::string& flag, const std::string& dir, bool create) {
    if (dir.empty()) fail(flag, "directory is empty");
    if (fs::exists(dir) && !fs::is_directory(dir)) fail(dir, "exists and is not a directory");
    // One that takes no new file (or whose nearest existing parent takes none) fails now, not after the work:
    // gbuffer -o /proc/gdir rendered first, render --aov-dir on a read-only directory traced the whole frame.
    if (!create) {
        fs::path probe = fs::absolute(dir);
        while (!fs::exists(probe) && probe.has_parent_path() && probe.parent_path() != probe) probe = probe.parent_path();
        try {
            checkWritable((probe / ".obscura").string());
        } catch (const Error&) {
            fail(dir, fs::exists(dir) ? "directory takes no new file (read-only?)"
                                      : "cannot be made: " + probe.string() + " takes no new file (read-only?)");
        }
    }
    if (!fs::exists(dir) && create) {
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec) fail(dir, "cannot create directory: " + ec.message());
    }
}

fs::path firstMissingDirectory(const std::string& dir) {
    std::error_code ec;
    fs::path created;
    for (fs::path p = fs::absolute(dir, ec); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) created = p;
    return created;
}

bool progressWanted(bool quiet) { return !quiet && isatty(STDERR_FILENO); }

Progress::Progress(std::string stage, bool enabled)
    : stage_(std::move(stage)), enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
    if (enabled_ && lastPercent_ >= 0)
        std::fprintf(stderr, "\r%-24s 100%%  %6.1f s\n", stage_.c_str(), secondsSince(start_));
}

void Progress::operator()(double fraction) {
    if (!enabled_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    int percent = int(fraction * 100.0);
    if (percent == lastPercent_) return;
    lastPercent_ = percent;
    int filled = percent / 5;
    std::fprintf(stderr, "\r%-24s %3d%% [%.*s%*s] %6.1f s", stage_.c_str(), percent, filled, "####################",
                 20 - filled, "", secondsSince(start_));
    std::fflush(stderr);
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

namespace {
double processCpuMs() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return 1000.0 * double(ts.tv_sec) + 1e-6 * double(ts.tv_nsec);
}
} // namespace


RunTimes timeRuns(int repeats, const std::function<void()>& body) {
    body();
    std::vector<double> wall, cpu;
    for (int i = 0; i < repeats; ++i) {
        const double cpu0 = processCpuMs();
        const auto start = std::chrono::steady_clock::now();
        body();
        wall.push_back(1000.0 * secondsSince(start));
        cpu.push_back(processCpuMs() - cpu0);
    }
    return {median(wall), *std::min_element(wall.begin(), wall.end()), median(cpu)};
}

} // namespace obscura::cli
