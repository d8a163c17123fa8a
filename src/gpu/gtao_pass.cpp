// Ground-Truth Ambient Occlusion as a compute pass (src/gpu/shaders/gtao.comp): Jimenez, Wu, Pesce and
// Jarabo 2016, "Practical Realtime Strategies for Accurate Indirect Occlusion", §4 and App. A. The host
// side of ssao::computeGtao: the same checks and messages, the same constants (ssao::gtaoConstants) as
// push constants, so CPU and GPU differ only in the kernel. Contract in include/obscura/gpu.h.
#include "gpu/buffer.h"
#include "gpu/gtao_pass.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "gpu/spirv.h"
#include "shaders/layouts.h"
#include "shaders/temporal_layouts.h"

#include "obscura/error.h"
#include "obscura/gpu.h"

#include <cassert>
#include <string>
#include <vector>

namespace obscura::gpu {

static_assert(sizeof(ssao::GtaoConstants) == kGtaoPushConstantBytes,
              "the push constants of gtao.comp are one GtaoConstants");
static_assert(ssao::kGtaoRotations == kGtaoRotations, "gtao.comp rotates the interleave as the CPU kernel does");
static_assert((GTAO_MIP_WORKGROUP >> (GTAO_MAX_MIP_LEVELS - 1)) >= 1,
              "gtao_mips.comp makes every level in one workgroup's tile: the top level needs a texel of it");

// gallivm (llvmpipe's shader compiler) counts the iterations of every loop of an invocation against one budget of
// 65535 (LP_MAX_TGSI_LOOP_ITERATIONS, "shared between every loop") and breaks out of each loop once it is spent.
// What one horizon step costs of it depends on how the driver compiled the sampling's code; measured on lavapipe
// (Mesa 22.3.6, the demo scene at 64x48, GPU against CPU, 2026-11-27): with planar samples the result went wrong
// from 4864 slices x steps (right at 4608), with planar-MIP ones from 4096 (right at 3072), with MIP ones from
// 8192 (right at 6144), and nearest ones were right at 64 x 256, the most there is. The iterations a step is
// counted for below lie above what those thresholds imply (65535 / 4864 = 13.5 for planar). The bitmask adds at
// most 32 sector iterations a sample, two samples a step, and 32 a slice: an upper bound from the loops'
// structure, not measured. The budget keeps a tenth in reserve for the loops outside the march.
void checkGtaoLoopBudget(const Context::Impl& c, const ssao::GtaoConstants& k) {
    if (!c.lavapipe) return;
    const bool bitmask = k.thicknessMode == GTAO_THICKNESS_BITMASK;
    const double perStep = (k.sampling == GTAO_SAMPLING_NEAREST       ? 3.0
                            : k.sampling == GTAO_SAMPLING_MIP         ? 10.0
                            : k.sampling == GTAO_SAMPLING_PLANAR_MIP  ? 21.0
                                                                      : 14.0) +
                           (bitmask ? 2.0 * GTAO_BITMASK_SECTORS : 0.0);
    const double perSlice = 1.0 + (bitmask ? GTAO_BITMASK_SECTORS : 0.0);
    const double budget = 0.9 * 65535.0;
    const double iterations = double(k.sliceCount) * (double(k.stepsPerSide) * perStep + perSlice);
    if (iterations <= budget) return;
    const long most = long((budget / double(k.sliceCount) - perSlice) / perStep) * long(k.sliceCount);
    fail(c.info.name, "ends a shader's loops after 65535 iterations in all, without an error, and GTAO with " +
                          std::to_string(k.sliceCount) + " slices x " + std::to_string(k.stepsPerSide) +
                          " steps would need about " + std::to_string(long(iterations)) + " there, past the " +
                          std::to_string(long(budget)) + " it is held to (a tenth kept for the loops outside the "
                          "march), so its result would be wrong: use at most " + std::to_string(std::max(most, 0L)) +
                          " slices x steps with these samples on lavapipe, or another device");
}

void recordGtao(Context::Impl& c, VkCommandBuffer cmd, const GtaoBuffers& b, const ssao::GtaoConstants& k,
                int gridStep, bool bentNormal, bool packedNormals) {
    assert(gridStep == 1 || gridStep == 2);
    checkGtaoLoopBudget(c, k);
    ComputePipeline& pipeline =
        c.pipelineOfShadersSize("gtao", shaders::gtao,
                                std::vector<BindingKind>(kGtaoBindingCount, BindingKind::StorageBuffer),
                                kGtaoPushConstantBytes,
                                // kGtaoSpecGridStep, BentNormal, the constants' modes (Sampling ... BeyondRadius),
                                // PackedNormals.
                                {gridStep, bentNormal ? 1 : 0, k.sampling, k.weighting, k.thicknessMode,
                                 k.beyondRadius, packedNormals ? 1 : 0});
    // In binding order: kGtaoBindingDepth, Normal, Visibility, BentNormal, DepthMips.
    pipeline.dispatchGrid(cmd, {&b.depth, &b.normal, &b.visibility, &b.bentNormal, &b.depthMips}, &k, sizeof k,
                          (k.width + gridStep - 1) / gridStep, (k.height + gridStep - 1) / gridStep);
}

std::size_t gtaoDepthMipsFloats(int width, int height, int mipLevels) {
    return mipLevels > 0 ? std::size_t(ssao::gtaoMipOffset(width, height, mipLevels + 1)) : 0;
}

Buffer gtaoDepthMipsBuffer(Context::Impl& c, int width, int height, int mipLevels) {
    const std::size_t floats = gtaoDepthMipsFloats(width, height, mipLevels);
    return Buffer(c, (floats > 0 ? floats : 4) * sizeof(float), MemoryUse::Device);
}

void recordGtaoDepthMips(Context::Impl& c, VkCommandBuffer cmd, const Buffer& depth, const Buffer& chain,
                         const ssao::GtaoConstants& k) {
    if (k.mipLevels <= 0) return;
    assert(k.mipLevels <= GTAO_MAX_MIP_LEVELS &&
           chain.size() >= gtaoDepthMipsFloats(k.width, k.height, k.mipLevels) * sizeof(float));
    ComputePipeline& pipeline = c.pipeline("gtao_mips", shaders::gtao_mips, kGtaoMipsBindingCount,
                                           kGtaoMipsPushConstantBytes, GTAO_MIP_WORKGROUP, GTAO_MIP_WORKGROUP);
    const GtaoMipConstants m{k.width, k.height, k.mipLevels, 0};
    // One invocation per texel of level 1.
    pipeline.dispatchGrid(cmd, {&depth, &chain}, &m, sizeof m, ssao::gtaoMipSize(k.width, 1),
                          ssao::gtaoMipSize(k.height, 1));
}

Buffer gtaoBentNormalBuffer(Context::Impl& c, std::size_t pixels, bool bentNormal) {
    return Buffer(c, (bentNormal ? 3 * pixels : 4) * sizeof(float), MemoryUse::Device);
}

ssao::GtaoResult computeGtao(Context& context, const GBuffer& g, const ssao::GtaoConstants& k, GtaoOutputs outputs) {
    ssao::checkGtaoBuffers(g, k);  // ssao::computeGtao's check and message; the shader checks nothing

    const bool bentNormal = outputs == GtaoOutputs::VisibilityAndBentNormal;
    ssao::GtaoResult r;
    r.visibility = Image(k.width, k.height, 1, 1.0f);
    if (bentNormal) r.bentNormal = Image(k.width, k.height, 3, 0.0f);
    const std::size_t pixels = std::size_t(k.width) * std::size_t(k.height);
    if (pixels == 0) return r;  // no buffer of 0 bytes

    Context::Impl& c = context.impl();
    const Buffer depth = upload(c, g.depth.pixels.data(), pixels * sizeof(float));
    const Buffer normal = upload(c, g.normal.pixels.data(), 3 * pixels * sizeof(float));
    const Buffer visibility(c, pixels * sizeof(float), MemoryUse::Device);
    const Buffer bent = gtaoBentNormalBuffer(c, pixels, bentNormal);
    const Buffer mips = gtaoDepthMipsBuffer(c, k.width, k.height, k.mipLevels);
    c.submit(
        [&](VkCommandBuffer cmd) {
            if (k.mipLevels > 0) {
                recordGtaoDepthMips(c, cmd, depth, mips, k);
                computeBarrier(cmd);  // the GTAO pass reads the chain
            }
            recordGtao(c, cmd, {depth, normal, visibility, bent, mips}, k, 1, bentNormal);
        },
        true);
    download(c, visibility, r.visibility.pixels.data(), pixels * sizeof(float));
    if (bentNormal) download(c, bent, r.bentNormal.pixels.data(), 3 * pixels * sizeof(float));
    return r;
}

ssao::GtaoResult computeGtao(Context& context, const GBuffer& gbuffer, const ssao::GtaoSettings& settings,
                             GtaoOutputs outputs) {
    settings.validate();
    return computeGtao(context, gbuffer, ssao::gtaoConstants(settings, gbuffer.camera), outputs);
}

} // namespace obscura::gpu
