// Helpers shared by the obscura subcommands: scene and camera arguments, value parsing, progress.
#pragma once

#include "obscura/builtin_scenes.h"
#include "obscura/camera.h"
#include "obscura/scene.h"

#include <chrono>
#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
}

namespace obscura::cli {

// A scene argument: a built-in scene name, or a .gltf/.glb/.obj/.ply file.
struct LoadedScene {
    std::string name;
    Scene scene;
    Camera camera;  // the built-in default, or one framing a file's bounds
    std::size_t colouredPrimitives = 0;  // glTF triangle primitives with a COLOR_0 (LoadInfo)
};
LoadedScene loadSceneArgument(const std::string& argument);
// Ray-traced AO of reach `reach` (m: a radius r, or an exponential falloff's d) over `scene`: fails naming `flag`
// where the float precision left at the scene's distance from the origin starts every ray a quarter of the reach
// or more off its surface (trace::selfHitOffsetFloor), and warns from 1% of it. Such a scene's AO came out 1.
void checkRayReach(const LoadedScene& scene, float reach, const std::string& flag);

// "x,y,z" -> Vec3; throws obscura::Error naming the flag.
Vec3 parseVec3(const std::string& flag, const std::string& text);
// "WxH" -> width, height (each in [1, 32768]); throws obscura::Error naming the flag.
void parseSize(const std::string& flag, const std::string& text, int& width, int& height);
// A decimal number ("2", "0.5", "-1e3", "+4"; spaces around it allowed, as parseVec3 allows them), stored in
// `value`; false for anything else, hex floats ("0x1p1") and numbers outside float's range included. "inf"
// and "nan" read as themselves: callers that take neither check the value.
bool parseDecimal(const std::string& text, float& value);
// A float that may be "inf".
float parseRadius(const std::string& flag, const std::string& text);
// A generated level's triangle budget as written: a whole number, in exponent notation too ("2e8", "1.5e6", as
// --help writes the range), held to [kMinLevelTriangles, kMaxLevelTriangles]. The error quotes the text.
long long parseLevelTriangles(const std::string& flag, const std::string& text);
// A bake distance in (0, 1e6] m, and --distances' "short,long" (short < long) or one value.
float parseBakeDistance(const std::string& flag, const std::string& text);
std::vector<float> parseBakeDistances(const std::string& flag, const std::string& text);

// Camera flags common to render and gbuffer.
struct CameraOptions {
    std::string from, to, up, size = "1280x720";
    float fov = 0.0f, nearZ = 0.0f, farZ = 0.0f;  // the scene's unless the flag was given (0 included)
    CLI::Option *fovOption = nullptr, *nearOption = nullptr, *farOption = nullptr;
    void add(CLI::App& app);
    // The scene's camera with the flags given on top. A camera that fails Camera::validate is blamed on the flags
    // when one was given, else on the scene (a file too large or too small for float to frame by default).
    Camera apply(const LoadedScene& scene) const;
};

// The options that add() put on app: those app has after it that it did not have before, so that a command can
// tell later which of a group of flags the command line gave.
std::vector<const CLI::Option*> optionsAddedBy(CLI::App& app, const std::function<void()>& add);
// A warning on stderr for each of `options` that the command line gave, with `why` (e.g. "applies to --ao
// alchemy, not --ao gtao"): a flag that the chosen method ignores is otherwise dropped without a word, its
// value unchecked. A warning, not an error, so that a script passing one set of flags to every method runs on.
void warnIgnored(const std::vector<const CLI::Option*>& options, const std::string& why);

// Makes every option of app and its subcommands that takes a value refuse an empty one ("--threads ''" from an
// unset shell variable), which CLI11 would read as 0 for a number and as "not given" for a path or a camera
// vector: the command would run on a setting the user never chose.
void refuseEmptyValues(CLI::App& app);

// Fails early, before any work, if the output cannot be written: wrong extension, missing directory or a
// directory of that name, it is one of the command's input files (empty names are skipped), which the
// output would replace, or its directory takes no new file (checkWritable).
void checkOutputPath(const std::string& flag, const std::string& path, const std::vector<std::string>& extensions,
                     const std::vector<std::string>& inputs = {});
// True if `a` and `b` name the same file: one existing file (a link or another spelling), or two paths that do
// not exist yet but resolve alike ("d/./ao.exr" and "d/ao.exr"). False for an empty name.
bool samePath(const std::string& a, const std::string& b);
// `dir` names a directory or none yet (not a file); with `create`, one that is not there is made. A command
// checks without `create` first and creates once its inputs have loaded, so a failure leaves no directory.
void checkOutputDirectory(const std::string& flag, const std::string& dir, bool create);
// The outermost directory of `dir`'s path that is not there yet (empty if `dir` exists): what creating `dir`
// makes, and what a failed command removes again.
std::filesystem::path firstMissingDirectory(const std::string& dir);


// --supersample's range, checked before any input is read (GBufferSettings' own check comes after the scene
// and the environment, and names no flag).
void checkSupersample(int supersample);

// Fails early if an input (skipped when empty) is not one of `extensions`, where readImage would read other
// formats as something they cannot hold: "<flag>: <path>: <content> is read from .hdr or .exr files, not .png".
void checkInputFormat(const std::string& flag, const std::string& path, const std::vector<std::string>& extensions,
                      const std::string& content);

// A one-line progress bar on stderr when it is a terminal; silent otherwise. Thread-safe.
class Progress {
public:
    Progress(std::string stage, bool enabled);
    ~Progress();
    void operator()(double fraction);

private:
    std::string stage_;
    bool enabled_;
    int lastPercent_ = -1;
    std::mutex mutex_;
    std::chrono::steady_clock::time_point start_;
};
bool progressWanted(bool quiet);

double secondsSince(std::chrono::steady_clock::time_point start);

// `repeats` timed runs of `body` after one untimed warm-up (first-touch allocations, lazily built tables).
struct RunTimes {
    double medianMs = 0;     // wall
    double minMs = 0;        // wall
    double medianCpuMs = 0;  // process CPU time, all threads: on a shared machine, what the work itself cost
};
RunTimes timeRuns(int repeats, const std::function<void()>& body);  // medians as obscura::median

} // namespace obscura::cli
