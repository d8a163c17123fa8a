// obscura: the command-line tool over libobscura. Errors print one line and exit non-zero:
// 1 for a bad input or failed operation, 2 for a bad command line.
#include "cli_common.h"
#include "commands.h"

#include "obscura/error.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <new>
#include <string>

int main(int argc, char** argv) {
    CLI::App app{"Obscura: ambient occlusion and obscurance, screen-space, baked and ray-traced ground truth.\n"
                 "Run `obscura COMMAND --help` for a command's options."};
    app.name("obscura");
    app.require_subcommand(1);
    app.set_version_flag("--version", "obscura 0.1.0");
    obscura::cli::addRenderCommand(app);
    obscura::cli::addGBufferCommand(app);
    obscura::cli::addScenesCommand(app);
    obscura::cli::addBenchCommand(app);
    obscura::cli::addAoCommand(app);
    obscura::cli::addCompareCommand(app);
    obscura::cli::addBakeCommand(app);
    obscura::cli::refuseEmptyValues(app);
    // A first word that is no command: CLI11 reports only that a subcommand is required, without naming it.
    if (argc > 1 && argv[1][0] != '-') {
        std::string known;
        bool found = false;
        for (const CLI::App* sub : app.get_subcommands({})) {
            found = found || sub->get_name() == argv[1];
            known += (known.empty() ? "" : ", ") + sub->get_name();
        }
        if (!found) {
            std::fprintf(stderr, "obscura: error: unknown command '%s' (commands: %s) (see --help)\n", argv[1],
                         known.c_str());
            return 2;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::fprintf(stderr, "obscura: error: %s (see --help)\n", e.what());
        return 2;
    } catch (const obscura::Error& e) {
        std::fprintf(stderr, "obscura: error: %s\n", e.what());
        return 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "obscura: error: out of memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "obscura: error: internal: %s\n", e.what());
        return 3;
    }
    return 0;
}
