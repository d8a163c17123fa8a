// The separable cross-bilateral blur as two compute dispatches (src/gpu/shaders/bilateral_separable.comp):
// McGuire et al. 2011, "The Alchemy Screen-Space Ambient Obscurance Algorithm", Fig. 6. The host side of
// ssao::bilateralFilter's separable mode; the CPU reference is src/ssao/bilateral_separable.cpp. Contract
// in include/obscura/gpu.h.
#include "gpu/bilateral_2d_pass.h"
#include "gpu/bilateral_pass.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "gpu/spirv.h"
#include "shaders/layouts.h"
#include "ssao/bilateral_separable.h"

#include "obscura/error.h"
#include "obscura/gpu.h"

#include <cstdint>
#include <vector>

namespace obscura::gpu {

// validate() accepts radii up to ssao::kMaxBlurRadius; the shader's shared-memory lines must hold as many.
static_assert(kBilateralMaxRadius >= ssao::kMaxBlurRadius, "bilateral_separable.comp's tile holds every radius");
static_assert(kBilateralTiledMaxRadius == kTiledBlurMaxRadius, "bilateral_tiled.comp's apron is the public limit");

SeparableBilateral separableBilateral(const ssao::BilateralSettings& s, int width, int height) {
    s.validate();
    const ssao::detail::SeparableWeights weights = ssao::detail::separableWeights(s);
    SeparableBilateral f;
    f.logSpatial = weights.logSpatial;
    f.constants.width = width;
    f.constants.height = height;
    f.constants.radius = s.radius;
    f.constants.useNormal = s.usesNormals() ? 1 : 0;
    f.constants.depthScale = weights.depthScale;
    return f;
}

void recordSeparableBilateralAxis(Context::Impl& c, VkCommandBuffer cmd, const SeparableBilateralBuffers& b,
                                  const SeparableBilateral& f, int axis) {
    ComputePipeline& pipeline =
        c.pipeline("bilateral_separable", shaders::bilateral_separable,
                   std::vector<BindingKind>(kBilateralBindingCount, BindingKind::StorageBuffer),
                   kBilateralPushConstantBytes, kBilateralWorkgroupX, kBilateralWorkgroupY,
                   {f.constants.useNormal, b.packedNormals ? 1 : 0,
                    bilateralSpecUnrolled(f.constants.radius, f.constants.useNormal)});  // kBilateralSpec...
    BilateralConstants k = f.constants;
    k.axis = axis;
    // In binding order: kBilateralBindingDepth, Normal, LogSpatial, Input, Output.
    pipeline.dispatch(cmd, {&b.depth, &b.normal, &b.logSpatial, &b.input, &b.output}, &k, sizeof k,
                      std::uint32_t(bilateralGroupsX(axis, k.width)), std::uint32_t(bilateralGroupsY(axis, k.height)));
}

void recordSeparableBilateral(Context::Impl& c, VkCommandBuffer cmd, const SeparableBilateralBuffers& b,
                              const SeparableBilateral& f, BlurDispatch dispatch) {
    if (dispatch == BlurDispatch::Tiled) {
        if (f.constants.radius > kBilateralTiledMaxRadius)
            fail("the tiled blur", "holds radii up to " + std::to_string(kBilateralTiledMaxRadius) + ", not " +
                                       std::to_string(f.constants.radius));
        ComputePipeline& pipeline =
            c.pipeline("bilateral_tiled", shaders::bilateral_tiled,
                       std::vector<BindingKind>(kBilateralBindingCount, BindingKind::StorageBuffer),
                       kBilateralPushConstantBytes, kBilateralTiledWorkgroupX, kBilateralTiledWorkgroupY,
                       {f.constants.useNormal, b.packedNormals ? 1 : 0,
                        bilateralSpecUnrolled(f.constants.radius, f.constants.useNormal)});  // kBilateralSpec...
        const std::uint32_t tilesX = std::uint32_t((f.constants.width + kBilateralTiledTile - 1) / kBilateralTiledTile);
        const std::uint32_t tilesY = std::uint32_t((f.constants.height + kBilateralTiledTile - 1) / kBilateralTiledTile);
        pipeline.dispatch(cmd, {&b.depth, &b.normal, &b.logSpatial, &b.input, &b.output}, &f.constants,
                          sizeof f.constants, tilesX, tilesY);
        return;
    }
    recordSeparableBilateralAxis(
        c, cmd, {b.depth, b.normal, b.logSpatial, b.input, b.scratch, b.scratch, b.packedNormals}, f, 0);
    computeBarrier(cmd);  // the vertical pass reads what the horizontal one wrote
    recordSeparableBilateralAxis(
        c, cmd, {b.depth, b.normal, b.logSpatial, b.scratch, b.scratch, b.output, b.packedNormals}, f, 1);
}

namespace {

Image separableOnDevice(Context& context, const Image& ao, const GBuffer& g, const ssao::BilateralSettings& s,
                        BlurDispatch dispatch) {
    const SeparableBilateral f = separableBilateral(s, g.width(), g.height());
    Context::Impl& c = context.impl();
    const std::size_t pixels = g.depth.pixelCount();
    const Buffer depth = upload(c, g.depth.pixels.data(), pixels * sizeof(float));
    const Buffer normal = upload(c, g.normal.pixels.data(), 3 * pixels * sizeof(float));
    const Buffer spatial = upload(c, f.logSpatial.data(), f.logSpatial.size() * sizeof(float));
    const Buffer input = upload(c, ao.pixels.data(), pixels * sizeof(float));
    const Buffer horizontal(c, pixels * sizeof(float), MemoryUse::Device);
    const Buffer result(c, pixels * sizeof(float), MemoryUse::Device);
    c.submit([&](VkCommandBuffer cmd) {
        recordSeparableBilateral(c, cmd, {depth, normal, spatial, input, horizontal, result}, f, dispatch);
    },
             true);
    Image out(g.width(), g.height(), 1);
    download(c, result, out.pixels.data(), pixels * sizeof(float));
    return out;
}

} // namespace

Image bilateralFilter(Context& context, const Image& ao, const GBuffer& g, const ssao::BilateralSettings& s) {
    ssao::checkBilateralInputs(ao, g, s);  // ssao::bilateralFilter's checks and messages
    if (s.mode == ssao::BlurMode::None) return ao;
    if (s.mode == ssao::BlurMode::TwoD) return bilateral2D(context.impl(), ao, g, s);
    return separableOnDevice(context, ao, g, s, BlurDispatch::TwoPasses);
}

Image bilateralFilterTiled(Context& context, const Image& ao, const GBuffer& g, const ssao::BilateralSettings& s) {
    ssao::checkBilateralInputs(ao, g, s);
    if (s.mode != ssao::BlurMode::Separable) fail("the tiled blur", "is the separable blur's (--blur separable)");
    return separableOnDevice(context, ao, g, s, BlurDispatch::Tiled);
}

} // namespace obscura::gpu
