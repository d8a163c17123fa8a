// Alchemy AO as a compute pass (src/gpu/shaders/alchemy.comp): McGuire et al. 2011, "The Alchemy
// Screen-Space Ambient Obscurance Algorithm", eq. 10. The host side of ssao::alchemyAO: the same
// validation, the same constants (ssao::alchemyConstants) and the same spiral table, so CPU and GPU differ
// only in the kernel. Contract in include/obscura/gpu.h.
#include "gpu/alchemy_pass.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "gpu/depth_prep_pass.h"
#include "gpu/spirv.h"
#include "shaders/layouts.h"

#include "obscura/error.h"
#include "obscura/gpu.h"

#include <vector>

namespace obscura::gpu {

static_assert(sizeof(ssao::AlchemyConstants) == kAlchemyPushConstantBytes,
              "the push constants of alchemy.comp are one AlchemyConstants");

std::vector<float> alchemySpiralOffsets(const ssao::AlchemyConstants& k) {
    std::vector<float> offsets;
    for (const std::vector<float>& o : ssao::alchemySpiral(k).offsets) offsets.insert(offsets.end(), o.begin(), o.end());
    return offsets;
}

void recordAlchemy(Context::Impl& c, VkCommandBuffer cmd, const AlchemyBuffers& b, const ssao::AlchemyConstants& k) {
    ComputePipeline& pipeline = c.pipeline("alchemy", shaders::alchemy, kAlchemyBindingCount, kAlchemyPushConstantBytes,
                                           ssao::kAlchemyWorkgroupX, ssao::kAlchemyWorkgroupY);
    // In binding order: kAlchemyBindingDepth, Normal, Spiral, Output.
    pipeline.dispatchGrid(cmd, {&b.depth, &b.normal, &b.spiral, &b.output}, &k, sizeof k, k.width - 2 * k.guardBand,
                          k.height - 2 * k.guardBand);
}

Image alchemyAO(Context& context, const GBuffer& g, const ssao::AlchemySettings& s) {
    const ssao::AlchemyConstants k = ssao::alchemyConstants(s, g.camera);
    // ssao::alchemyAO's checks and messages (the shader checks nothing, and a NaN depth would reach a
    // float-to-int conversion).
    ssao::validateAlchemyGBuffer(g, s);
    const std::vector<float> offsets = alchemySpiralOffsets(k);

    Context::Impl& c = context.impl();
    const std::size_t pixels = std::size_t(k.width) * std::size_t(k.height);
    const Buffer depth = upload(c, g.depth.pixels.data(), pixels * sizeof(float));
    // Normals rebuilt from depth: normals_from_depth.comp, ssao::normalsFromDepth's mirror, before the pass.
    const Buffer normal = s.normalsFromDepth ? Buffer(c, 3 * pixels * sizeof(float), MemoryUse::Device)
                                             : upload(c, g.normal.pixels.data(), 3 * pixels * sizeof(float));
    const Buffer table = upload(c, offsets.data(), offsets.size() * sizeof(float));
    Image out(k.width - 2 * k.guardBand, k.height - 2 * k.guardBand, 1);
    const Buffer ao(c, out.pixels.size() * sizeof(float), MemoryUse::Device);
    c.submit(
        [&](VkCommandBuffer cmd) {
            if (s.normalsFromDepth) {
                recordNormalsFromDepth(c, cmd, depth, normal, ssao::depthPrepConstants({}, g.camera));
                computeBarrier(cmd);
            }
            recordAlchemy(c, cmd, {depth, normal, table, ao}, k);
        },
        true);
    download(c, ao, out.pixels.data(), out.pixels.size() * sizeof(float));
    return out;
}

} // namespace obscura::gpu
