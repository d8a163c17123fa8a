// `--gpu` and `--gpu-device` (gpu_flags.h).
#include "gpu_flags.h"

#include "obscura/error.h"

#include <CLI/CLI.hpp>

#include <cstdio>

namespace obscura::cli {

void GpuFlags::add(CLI::App& app, const std::string& what, const std::string& note) {
    app.add_flag("--gpu", gpu,
                 "Run " + what + " as Vulkan compute passes (the first discrete GPU, else e.g. lavapipe). " +
                     (note.empty() ? "" : note + " ") + "OBSCURA_VALIDATION=1 turns on the validation layers");
    deviceOption = app.add_option("--gpu-device", device,
                   "Vulkan device index with --gpu (-1: OBSCURA_GPU_DEVICE, else the first discrete GPU)")
        ->capture_default_str();
}

void GpuFlags::validate() const {
    if (device < -1) fail("--gpu-device", "must be a device index >= 0 (or -1: the default device)");
    if (!gpu && deviceOption && deviceOption->count() > 0)
        fail("--gpu-device", "needs --gpu: without it everything runs on the CPU");
}

std::unique_ptr<gpu::Context> GpuFlags::open() const {
    if (!gpu) return nullptr;
    gpu::ContextSettings cs;  // it names a missing driver or device, and a bad index by the flag
    cs.deviceIndex = device;
    cs.deviceIndexName = "--gpu-device";
    cs.pipelineStatistics = pipelineStatistics;
    cs.pipelineInternals = pipelineInternals;
    return std::make_unique<gpu::Context>(cs);
}

void reportValidation(const gpu::Context* context) {
    if (!context) return;
    for (const std::string& m : context->validationMessages())
        std::fprintf(stderr, "obscura: warning: Vulkan validation: %s\n", m.c_str());
}

} // namespace obscura::cli
