// The subcommands of `obscura`; each registers itself on the app with its options and callback.
#pragma once

namespace CLI {
class App;
}

namespace obscura::cli {

void addRenderCommand(CLI::App& app);
void addGBufferCommand(CLI::App& app);
void addScenesCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addAoCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
void addAlchemyBench(CLI::App& bench);
void addGtaoBench(CLI::App& bench);  // `bench gtao`, registered by addBenchCommand
void addGpuBench(CLI::App& bench);   // `bench --gpu` and its options, on the bench command itself
void addBakeCommand(CLI::App& app);
void addBakeBenchCommands(CLI::App& bench);  // `bench bake-quality`, added by addBenchCommand

} // namespace obscura::cli
