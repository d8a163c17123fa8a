// `--gpu` and `--gpu-device`, shared by the commands that run screen-space passes as Vulkan compute.
#pragma once

#include "obscura/gpu.h"

#include <memory>
#include <string>

namespace CLI {
class App;
class Option;
}

namespace obscura::cli {

struct GpuFlags {
    bool gpu = false;
    int device = -1;
    // What the driver says of each pipeline (ContextSettings::pipelineStatistics, pipelineInternals); set by
    // the commands that report it, not flags of every command.
    bool pipelineStatistics = false;
    bool pipelineInternals = false;
    const CLI::Option* deviceOption = nullptr;  // set by add(): --gpu-device given without --gpu is refused

    // `what` completes the --gpu help: "Run <what> as Vulkan compute passes ..."; `note`, if any, follows it.
    void add(CLI::App& app, const std::string& what, const std::string& note = "");
    // Throws obscura::Error naming --gpu-device for a bad index (before any work).
    void validate() const;
    // The context, or null without --gpu. Errors (no loader, driver or device) name the device or the flag.
    std::unique_ptr<gpu::Context> open() const;
};

// Prints every validation message of the context as a warning on stderr (none unless OBSCURA_VALIDATION=1).
void reportValidation(const gpu::Context* context);

} // namespace obscura::cli
