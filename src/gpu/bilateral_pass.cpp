// The separable cross-bilateral blur as two compute dispatches (src/gpu/shaders/bilateral_separable.comp):
// McGuire et al. 2011, "The Alchemy Screen-Space Ambient Obscurance Algorithm", Fig. 6. The host side of
// ssao::bilateralFilter's separable mode; the CPU reference is src/ssao/bilateral_separable.cpp. Contract
// in include/obscura/gpu.h.
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "gpu/spirv.h"
#include "shaders/layouts.h"
#include "ssao/bilateral_separable.h"

#include "obscura/error.h"
#include "obscura/gpu.h"

#include <vector>

namespace obscura::gpu {

Image bilateralFilter(Context& context, const Image& ao, const GBuffer& g, const ssao::BilateralSettings& s) {
    ssao::checkBilateralInputs(ao, g, s);  // ssao::bilateralFilter's checks and messages
    if (s.mode == ssao::BlurMode::None) return ao;
    if (s.mode == ssao::BlurMode::TwoD) fail("blur", "the 2-D filter has no GPU pass yet (use separable)");

    // The CPU filter's own constants (src/ssao/bilateral_separable.h).
    const ssao::detail::SeparableWeights weights = ssao::detail::separableWeights(s);
    const std::vector<float>& logSpatial = weights.logSpatial;
    BilateralConstants k{};
    k.width = g.width();
    k.height = g.height();
    k.radius = s.radius;
    k.useNormal = s.usesNormals() ? 1 : 0;
    k.depthScale = weights.depthScale;

    Context::Impl& c = context.impl();
    ComputePipeline& pipeline = c.pipeline("bilateral_separable", shaders::bilateral_separable, kBilateralBindingCount,
                                           kBilateralPushConstantBytes, kBilateralWorkgroupX, kBilateralWorkgroupY);
    const std::size_t pixels = g.depth.pixelCount();
    const Buffer depth = upload(c, g.depth.pixels.data(), pixels * sizeof(float));
    const Buffer normal = upload(c, g.normal.pixels.data(), 3 * pixels * sizeof(float));
    const Buffer spatial = upload(c, logSpatial.data(), logSpatial.size() * sizeof(float));
    const Buffer input = upload(c, ao.pixels.data(), pixels * sizeof(float));
    const Buffer horizontal(c, pixels * sizeof(float), MemoryUse::Device);
    const Buffer result(c, pixels * sizeof(float), MemoryUse::Device);
    c.submit(
        [&](VkCommandBuffer cmd) {
            // In binding order: kBilateralBindingDepth, Normal, LogSpatial, Input, Output.
            k.axis = 0;
            pipeline.dispatchGrid(cmd, {&depth, &normal, &spatial, &input, &horizontal}, &k, sizeof k, k.width, k.height);
            // The vertical pass reads what the horizontal one wrote.
            memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
            k.axis = 1;
            pipeline.dispatchGrid(cmd, {&depth, &normal, &spatial, &horizontal, &result}, &k, sizeof k, k.width, k.height);
        },
        true);
    Image out(k.width, k.height, 1);
    download(c, result, out.pixels.data(), pixels * sizeof(float));
    return out;
}

} // namespace obscura::gpu
