// Alchemy AO as a compute pass (src/gpu/shaders/alchemy.comp): McGuire et al. 2011, "The Alchemy
// Screen-Space Ambient Obscurance Algorithm", eq. 10. The host side of ssao::alchemyAO: the same
// validation, the same constants (ssao::alchemyConstants) and the same spiral table, so CPU and GPU differ
// only in the kernel. Contract in include/obscura/gpu.h.
#include "gpu/alchemy_pass.h"
#include "gpu/bilateral_pass.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "gpu/depth_prep_pass.h"
#include "gpu/image_planes.h"
#include "gpu/spirv.h"
#include "shaders/layouts.h"

#include "obscura/error.h"
#include "obscura/gpu.h"

#include <cassert>
#include <cstdint>
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
    // Workgroups of the compiled shader's size (ssao::kAlchemyWorkgroupX x Y as embedded): each invocation
    // evaluates its own pixel, so any size gives the same image, and a candidate shader may try another.
    ComputePipeline& pipeline =
        c.pipelineOfShadersSize("alchemy", shaders::alchemy, storageBuffers(kAlchemyBindingCount),
                                kAlchemyPushConstantBytes, {b.packedNormals ? 1 : 0});  // kAlchemySpecPackedNormals
    // In binding order: kAlchemyBindingDepth, Normal, Spiral, Output.
    pipeline.dispatchGrid(cmd, {&b.depth, &b.normal, &b.spiral, &b.output}, &k, sizeof k, k.width - 2 * k.guardBand,
                          k.height - 2 * k.guardBand);
}

void recordAlchemyBlurred(Context::Impl& c, VkCommandBuffer cmd, const AlchemyBlurredBuffers& b,
                          const ssao::AlchemyConstants& k, const SeparableBilateral& f,
                          const std::function<void(const char*)>& mark, std::uint32_t rowGroupsX) {
    assert(f.constants.useNormal == 0 && f.constants.width == k.width - 2 * k.guardBand &&
           f.constants.height == k.height - 2 * k.guardBand);
    // Workgroups of the compiled shader's width (kBilateralHorizontalTileX as embedded), each blurring that
    // width less the radius at each end: a candidate shader may try another width.
    ComputePipeline& pipeline =
        c.pipelineOfShadersSize("alchemy_blur_row", shaders::alchemy_blur_row, storageBuffers(kAlchemyBlurBindingCount),
                                kAlchemyBlurPushConstantBytes, {b.packedNormals ? 1 : 0});  // kAlchemySpecPackedNormals
    const std::uint32_t* size = pipeline.layout().localSize;
    if (size[1] != 1 || int(size[0]) <= 2 * f.constants.radius)
        fail("shader alchemy_blur_row", "has workgroups of " + std::to_string(size[0]) + "x" + std::to_string(size[1]) +
                                            ": a row of more than 2 radius (" + std::to_string(2 * f.constants.radius) +
                                            ") invocations is what it blurs");
    struct {
        ssao::AlchemyConstants alchemy;
        BilateralConstants blur;
    } constants{k, f.constants};
    static_assert(sizeof constants == kAlchemyBlurPushConstantBytes, "the two blocks back to back, as the shader has them");
    constants.blur.axis = 0;
    if (rowGroupsX == 0)
        rowGroupsX = std::uint32_t(alchemyBlurRowGroupsX(f.constants.width, f.constants.radius, int(size[0])));
    // In binding order: kAlchemyBindingDepth, Normal, Spiral, kAlchemyBlurBindingLogSpatial, Output.
    pipeline.dispatch(cmd, {&b.depth, &b.normal, &b.spiral, &b.logSpatial, &b.scratch}, &constants, sizeof constants,
                      rowGroupsX, std::uint32_t(f.constants.height));
    if (mark) mark("alchemy-rows");
    computeBarrier(cmd);  // the vertical pass reads the rows
    // Its normal binding is unread without the normal weight; the depth buffer stands in for it.
    recordSeparableBilateralAxis(c, cmd, {b.blurDepth, b.blurDepth, b.logSpatial, b.scratch, b.scratch, b.output}, f, 1);
    if (mark) mark("blur-columns");
}

namespace {

void checkFormats(const ssao::AlchemySettings& s, AlchemyFormats formats) {
    if (formats.packedNormals && s.normalsFromDepth)
        fail("alchemy", "packed normals are the G-buffer's; with normalsFromDepth the GPU rebuilds them as floats");
}

// The G-buffer's normals as the pass reads them (3 floats, or with packedNormals a word each), or with
// normalsFromDepth a device plane for normals_from_depth.comp to fill.
Buffer normalPlane(Context::Impl& c, const GBuffer& g, const ssao::AlchemySettings& s, AlchemyFormats formats) {
    if (s.normalsFromDepth) return deviceFloats(c, 3 * g.depth.pixelCount());
    return uploadNormals(c, g.normal, formats.packedNormals);
}

} // namespace

Image alchemyAOBlurred(Context& context, const GBuffer& g, const ssao::AlchemySettings& s,
                       const ssao::BilateralSettings& blur, AlchemyFormats formats) {
    return alchemyAOBlurredInRowGroups(context, g, s, blur, formats, 0);
}

Image alchemyAOBlurredInRowGroups(Context& context, const GBuffer& g, const ssao::AlchemySettings& s,
                                  const ssao::BilateralSettings& blur, AlchemyFormats formats,
                                  std::uint32_t rowGroupsX) {
    const ssao::AlchemyConstants k = ssao::alchemyConstants(s, g.camera);
    ssao::validateAlchemyGBuffer(g, s);
    checkFormats(s, formats);
    if (blur.mode != ssao::BlurMode::Separable || blur.usesNormals())
        fail("alchemy blur", "the fused pass blurs separably by depth alone (BlurMode::Separable, no normal weight)");
    const GBuffer cropped = ssao::cropGuardBand(g, ssao::guardBandCamera(g.camera, -k.guardBand), k.guardBand);
    const SeparableBilateral f = separableBilateral(blur, cropped.width(), cropped.height());
    const std::vector<float> offsets = alchemySpiralOffsets(k);

    Context::Impl& c = context.impl();
    const std::size_t pixels = std::size_t(k.width) * std::size_t(k.height), out = cropped.depth.pixelCount();
    const Buffer depth = upload(c, g.depth.pixels.data(), pixels * sizeof(float));
    const Buffer normal = normalPlane(c, g, s, formats);
    const Buffer table = upload(c, offsets.data(), offsets.size() * sizeof(float));
    const Buffer blurDepth = upload(c, cropped.depth.pixels.data(), out * sizeof(float));
    const Buffer spatial = upload(c, f.logSpatial.data(), f.logSpatial.size() * sizeof(float));
    const Buffer rows(c, out * sizeof(float), MemoryUse::Device);
    const Buffer result(c, out * sizeof(float), MemoryUse::Device);
    c.submit(
        [&](VkCommandBuffer cmd) {
            if (s.normalsFromDepth) {
                recordNormalsFromDepth(c, cmd, depth, normal, ssao::depthPrepConstants({}, g.camera));
                computeBarrier(cmd);
            }
            recordAlchemyBlurred(c, cmd,
                                 {depth, normal, table, blurDepth, spatial, rows, result, formats.packedNormals}, k, f,
                                 {}, rowGroupsX);
        },
        true);
    Image image(cropped.width(), cropped.height(), 1);
    download(c, result, image.pixels.data(), out * sizeof(float));
    return image;
}

Image alchemyAO(Context& context, const GBuffer& g, const ssao::AlchemySettings& s, AlchemyFormats formats) {
    const ssao::AlchemyConstants k = ssao::alchemyConstants(s, g.camera);
    // ssao::alchemyAO's checks and messages (the shader checks nothing, and a NaN depth would reach a
    // float-to-int conversion).
    ssao::validateAlchemyGBuffer(g, s);
    checkFormats(s, formats);
    const std::vector<float> offsets = alchemySpiralOffsets(k);

    Context::Impl& c = context.impl();
    const std::size_t pixels = std::size_t(k.width) * std::size_t(k.height);
    const Buffer depth = upload(c, g.depth.pixels.data(), pixels * sizeof(float));
    // Normals rebuilt from depth: normals_from_depth.comp, ssao::normalsFromDepth's mirror, before the pass.
    const Buffer normal = normalPlane(c, g, s, formats);
    const Buffer table = upload(c, offsets.data(), offsets.size() * sizeof(float));
    Image out(k.width - 2 * k.guardBand, k.height - 2 * k.guardBand, 1);
    const Buffer ao(c, out.pixels.size() * sizeof(float), MemoryUse::Device);
    c.submit(
        [&](VkCommandBuffer cmd) {
            if (s.normalsFromDepth) {
                recordNormalsFromDepth(c, cmd, depth, normal, ssao::depthPrepConstants({}, g.camera));
                computeBarrier(cmd);
            }
            recordAlchemy(c, cmd, {depth, normal, table, ao, formats.packedNormals}, k);
        },
        true);
    download(c, ao, out.pixels.data(), out.pixels.size() * sizeof(float));
    return out;
}

} // namespace obscura::gpu
