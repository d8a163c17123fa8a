// The 2-D cross-bilateral blur of "Where Corners Stay Dark" (Alchemy SSAO in an IBL renderer) as one compute
// dispatch (src/gpu/shaders/bilateral_2d.comp). The host side of ssao::bilateralFilter's TwoD mode; the CPU
// reference is ssao::bilateral2D (src/ssao/bilateral.cpp). Contract in include/obscura/gpu.h.
#include "gpu/bilateral_2d_pass.h"
#include "gpu/bilateral_pass.h"
#include "gpu/compute_pipeline.h"
#include "gpu/image_planes.h"
#include "gpu/spirv.h"

#include <vector>

namespace obscura::gpu {

void recordBilateral2D(Context::Impl& c, VkCommandBuffer cmd, const Bilateral2DBuffers& b,
                       const BilateralConstants& k) {
    ComputePipeline& pipeline =
        c.pipeline("bilateral_2d", shaders::bilateral_2d,
                   std::vector<BindingKind>(kBilateralBindingCount, BindingKind::StorageBuffer),
                   kBilateralPushConstantBytes, kBilateral2DWorkgroupX, kBilateral2DWorkgroupY,
                   {k.useNormal, b.packedNormals ? 1 : 0});  // kBilateralSpecUseNormal, PackedNormals
    // In binding order: kBilateralBindingDepth, Normal, kBilateral2DBindingKernel, Input, Output.
    pipeline.dispatchGrid(cmd, {&b.depth, &b.normal, &b.kernel, &b.input, &b.output}, &k, sizeof k, k.width,
                          k.height);
}

Image bilateral2D(Context::Impl& c, const Image& ao, const GBuffer& g, const ssao::BilateralSettings& s) {
    const std::vector<float> kernel = ssao::gaussianHalfKernel(s.radius);
    const std::size_t pixels = g.depth.pixelCount();
    const Buffer depth = uploadChannels(c, g.depth, 1);
    const Buffer normal = uploadChannels(c, g.normal, 3);
    const Buffer weights = upload(c, kernel.data(), kernel.size() * sizeof(float));
    const Buffer input = uploadChannels(c, ao, 1);
    const Buffer result(c, pixels * sizeof(float), MemoryUse::Device);
    // The separable filter's constants function: the same depthScale (axis and logSpatial unused here).
    const BilateralConstants k = separableBilateral(s, g.width(), g.height()).constants;
    c.submit([&](VkCommandBuffer cmd) { recordBilateral2D(c, cmd, {depth, normal, weights, input, result}, k); }, true);
    Image out(g.width(), g.height(), 1);
    download(c, result, out.pixels.data(), pixels * sizeof(float));
    return out;
}

} // namespace obscura::gpu
