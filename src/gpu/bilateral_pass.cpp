// The separable cross-bilateral blur as two compute dispatches (src/gpu/shaders/bilateral_separable.comp):
// McGuire et al. 2011, "The Alchemy Screen-Space Ambient Obscurance Algorithm", Fig. 6. The host side of
// ssao::bilateralFilter's separable mode; the CPU reference is src/ssao/bilateral_separable.cpp. Contract
// in include/obscura/gpu.h.
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "gpu/spirv.h"
#include "shaders/layouts.h"

#include "obscura/error.h"
#include "obscura/gpu.h"

#include <cmath>
#include <cstdlib>
#include <vector>

namespace obscura::gpu {

Image bilateralFilter(Context& context, const Image& ao, const GBuffer& g, const ssao::BilateralSettings& s) {
    // ssao::bilateralFilter's checks and messages, without filtering: its BlurMode::None returns a copy.
    ssao::BilateralSettings checkOnly = s;
    checkOnly.mode = ssao::BlurMode::None;
    Image out = ssao::bilateralFilter(ao, g, checkOnly);
    if (s.mode == ssao::BlurMode::None) return out;
    if (s.mode == ssao::BlurMode::TwoD) fail("blur", "the 2-D filter has no GPU pass yet (use separable)");

    // The constants separableBlur computes: log2 of the Gaussian half kernel per tap, and the depth term's
    // scale, so that a tap weighs 2^(logSpatial - dd^2 depthScale / d^2).
    const std::vector<float> kernel = ssao::gaussianHalfKernel(s.radius);
    std::vector<float> logSpatial(2 * std::size_t(s.radius) + 1);
    for (int t = -s.radius; t <= s.radius; ++t)
        logSpatial[std::size_t(t + s.radius)] = std::log2(kernel[std::size_t(std::abs(t))]);
    BilateralConstants k{};
    k.width = g.width();
    k.height = g.height();
    k.radius = s.radius;
    k.useNormal = s.usesNormals() ? 1 : 0;
    k.depthScale = 1.44269504f / (2.0f * s.depthSigma * s.depthSigma);

    Context::Impl& c = context.impl();
    ComputePipeline& pipeline = c.pipeline("bilateral_separable", shaders::bilateral_separable, kBilateralBindingCount,
                                           kBilateralPushConstantBytes);
    if (pipeline.layout().localSize[0] != std::uint32_t(kBilateralWorkgroupX) ||
        pipeline.layout().localSize[1] != std::uint32_t(kBilateralWorkgroupY))
        fail("shader bilateral_separable", "workgroup size differs from kBilateralWorkgroupX x kBilateralWorkgroupY");
    const std::size_t pixels = g.depth.pixelCount();
    const Buffer depth = upload(c, g.depth.pixels.data(), pixels * sizeof(float));
    const Buffer normal = upload(c, g.normal.pixels.data(), 3 * pixels * sizeof(float));
    const Buffer spatial = upload(c, logSpatial.data(), logSpatial.size() * sizeof(float));
    const Buffer input = upload(c, ao.pixels.data(), pixels * sizeof(float));
    const Buffer horizontal(c, pixels * sizeof(float), MemoryUse::Device);
    const Buffer result(c, pixels * sizeof(float), MemoryUse::Device);
    const auto groups = [](int n, int size) { return std::uint32_t((n + size - 1) / size); };
    c.submit(
        [&](VkCommandBuffer cmd) {
            // In binding order: kBilateralBindingDepth, Normal, LogSpatial, Input, Output.
            k.axis = 0;
            pipeline.dispatch(cmd, {&depth, &normal, &spatial, &input, &horizontal}, &k, sizeof k,
                              groups(k.width, kBilateralWorkgroupX), groups(k.height, kBilateralWorkgroupY));
            // The vertical pass reads what the horizontal one wrote.
            memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
            k.axis = 1;
            pipeline.dispatch(cmd, {&depth, &normal, &spatial, &horizontal, &result}, &k, sizeof k,
                              groups(k.width, kBilateralWorkgroupX), groups(k.height, kBilateralWorkgroupY));
        },
        true);
    download(c, result, out.pixels.data(), pixels * sizeof(float));
    return out;
}

} // namespace obscura::gpu
