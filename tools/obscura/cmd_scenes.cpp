// `obscura scenes`: the built-in scenes, one line each; with --generate, writes a generated scene to glTF.
#include "cli_common.h"
#include "commands.h"

#include "obscura/builtin_scenes.h"
#include "obscura/error.h"
#include "obscura/gltf_writer.h"
#include "obscura/image_io.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>

namespace obscura::cli {

namespace {

struct GenerateOptions {
    std::string kind, output;
    std::string triangles = "1000000";  // as written: "2e8" is a budget too (parseLevelTriangles)
    std::uint32_t seed = 1;
};

void generate(const GenerateOptions& o) {
    if (o.kind != "level") fail("--generate", "unknown generator \"" + o.kind + "\" (available: level)");
    if (o.output.empty()) fail("--output", "--generate needs -o FILE.glb (or .gltf)");
    const long long triangles = parseLevelTriangles("--triangles", o.triangles);
    checkOutputPath("--output", o.output, {".glb", ".gltf"});
    // Said before the minutes and gigabytes of generating it (kMaxGlbLevelTriangles), not after.
    if (fileExtension(o.output) == ".glb" && triangles > kMaxGlbLevelTriangles)
        fail("--triangles", std::to_string(triangles) + " would make a .glb past the 4 GiB its header can state (about " +
                                std::to_string(kMaxGlbLevelTriangles) + " triangles at most); write .gltf");
    Scene scene = generateLevel(std::size_t(triangles), o.seed);
    writeGltf(scene, o.output);
    std::printf("%s: level with %zu triangles (%zu meshes, %zu instances), seed %u\n", o.output.c_str(),
                scene.triangleCount(), scene.meshes.size(), scene.instances.size(), o.seed);
}

} // namespace

void addScenesCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("scenes", "List the built-in scenes (use a name wherever a scene file goes), or "
                                                 "write a generated one with --generate");
    auto o = std::make_shared<GenerateOptions>();
    cmd->add_option("--generate", o->kind, "Write a generated scene instead of listing: level (terrain, buildings, props)");
    CLI::Option* triangles =
        cmd->add_option("--triangles", o->triangles, "Triangle budget of the generated scene, [4000, 2e8] (1.5e8 at most for .glb); 2e8 and 200000000 alike")->capture_default_str();
    CLI::Option* seed = cmd->add_option("--seed", o->seed, "Seed of the generated scene (same seed, same file)")->capture_default_str();
    CLI::Option* output = cmd->add_option("-o,--output", o->output, "Output .glb or .gltf for --generate");
    cmd->callback([o, output, triangles, seed] {
        if (!o->kind.empty()) {
            generate(*o);
            return;
        }
        // Listing writes nothing: an output path without --generate was once ignored without a word.
        for (const CLI::Option* option : {output, triangles, seed})
            if (option->count() > 0) fail(option->get_name(), "is for a generated scene: give --generate level");
        for (const std::string& name : builtinSceneNames()) {
            BuiltinScene s = makeBuiltinScene(name);
            std::printf("%-9s %s (%zu triangles)\n", name.c_str(), s.description.c_str(), s.scene.triangleCount());
        }
    });
}

} // namespace obscura::cli
