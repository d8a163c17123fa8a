// `obscura scenes`: the built-in scenes, one line each.
#include "commands.h"

#include "obscura/builtin_scenes.h"

#include <CLI/CLI.hpp>

#include <cstdio>

namespace obscura::cli {

void addScenesCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("scenes", "List the built-in scenes (use a name wherever a scene file goes)");
    cmd->callback([] {
        for (const std::string& name : builtinSceneNames()) {
            BuiltinScene s = makeBuiltinScene(name);
            std::printf("%-9s %s (%zu triangles)\n", name.c_str(), s.description.c_str(), s.scene.triangleCount());
        }
    });
}

} // namespace obscura::cli
