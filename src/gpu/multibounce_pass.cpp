// Multi-bounce AO as a compute pass (src/gpu/shaders/multibounce.comp): Jimenez et al. 2016, "Practical
// Realtime Strategies for Accurate Indirect Occlusion", §5, eq. 10. The CPU reference is ssao::multiBounce
// (include/obscura/multibounce.h) applied per pixel as the CLI's GTAO frame does. Contract in
// include/obscura/gpu_lighting.h.
#include "gpu/multibounce_pass.h"
#include "gpu/compute_pipeline.h"
#include "gpu/image_planes.h"
#include "gpu/spirv.h"

#include "obscura/error.h"
#include "obscura/gpu_lighting.h"

#include <string>

namespace obscura::gpu {

void recordMultiBounce(Context::Impl& c, VkCommandBuffer cmd, const MultiBounceBuffers& b,
                       const MultiBounceConstants& k) {
    ComputePipeline& pipeline = c.pipeline("multibounce", shaders::multibounce, kMultiBounceBindingCount,
                                           kMultiBouncePushConstantBytes, kLightingWorkgroupX, kLightingWorkgroupY);
    // In binding order: kMultiBounceBindingDepth, Visibility, Albedo, Output.
    pipeline.dispatchGrid(cmd, {&b.depth, &b.visibility, &b.albedo, &b.output}, &k, sizeof k, k.width, k.height);
}

Image multiBounce(Context& context, const GBuffer& g, const Image& visibility) {
    const int w = g.width(), h = g.height();
    const auto matches = [&](const Image& image, int channels) {
        return image.width == w && image.height == h && image.channels >= channels;
    };
    if (!matches(g.depth, 1) || !matches(g.albedo, 3) || !matches(visibility, 1) || visibility.channels != 1)
        fail("multi-bounce", "visibility (1 channel), depth and albedo (3 channels) must match the " +
                                 std::to_string(w) + "x" + std::to_string(h) + " G-buffer");
    if (w < 1 || h < 1) return Image(w, h, 3);  // as the other passes answer an empty G-buffer: no 0-byte buffers
    Context::Impl& c = context.impl();
    const std::size_t pixels = g.depth.pixelCount();
    const Buffer depth = uploadChannels(c, g.depth, 1);
    const Buffer ao = uploadChannels(c, visibility, 1);
    const Buffer albedo = uploadChannels(c, g.albedo, 3);
    const Buffer result(c, 3 * pixels * sizeof(float), MemoryUse::Device);
    const MultiBounceConstants k{w, h, 0, 0};
    c.submit([&](VkCommandBuffer cmd) { recordMultiBounce(c, cmd, {depth, ao, albedo, result}, k); }, true);
    Image out(w, h, 3);
    download(c, result, out.pixels.data(), 3 * pixels * sizeof(float));
    return out;
}

} // namespace obscura::gpu
