// One validated Vulkan context shared by the GPU tests of a process (so the pipelines compile once), and the
// skip rule of the GPU tests: a GPU test skips, with a message, only when no Vulkan device exists at all.
#pragma once

#include "obscura/builtin_scenes.h"
#include "obscura/error.h"
#include "obscura/gpu.h"
#include "obscura/trace.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace obscura::gpu::testing {

// The shared context with validation on, or null when there is no Vulkan device (the caller skips).
inline Context* sharedContext() {
    static std::unique_ptr<Context> context = [] {
        if (deviceCount() == 0) return std::unique_ptr<Context>();
        ContextSettings settings;
        settings.validation = true;
        return std::make_unique<Context>(settings);
    }();
    return context.get();
}

// Every validation message so far, one per line; empty when there were none.
inline std::string validationReport(const Context& context) {
    std::string all;
    for (const std::string& m : context.validationMessages()) all += m + "\n";
    return all;
}

// The G-buffer of a built-in scene from its default camera at w x h pixels.
inline GBuffer render(const std::string& scene, int w, int h) {
    BuiltinScene s = makeBuiltinScene(scene);
    Camera cam = s.camera;
    cam.width = w;
    cam.height = h;
    trace::Tracer tracer(s.scene);
    return trace::renderGBuffer(tracer, cam);
}

// The message of the obscura::Error that run() throws, or "no error".
template <class Run>
std::string errorMessage(Run&& run) {
    try {
        run();
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

// Expects `cpu` to throw obscura::Error and `gpu` to throw one with the same message.
template <class Cpu, class Gpu>
void expectSameError(Cpu&& cpu, Gpu&& gpu) {
    const std::string expected = errorMessage(cpu);
    EXPECT_NE(expected, "no error");
    EXPECT_EQ(errorMessage(gpu), expected);
}

} // namespace obscura::gpu::testing

// Skips the test when there is no Vulkan device; `context` is then the validated shared context.
#define OBSCURA_GPU_CONTEXT(context)                                                                  \
    ::obscura::gpu::Context* context##Pointer = ::obscura::gpu::testing::sharedContext();            \
    if (!context##Pointer) GTEST_SKIP() << "no Vulkan device (install mesa-vulkan-drivers for lavapipe)"; \
    ::obscura::gpu::Context& context = *context##Pointer
