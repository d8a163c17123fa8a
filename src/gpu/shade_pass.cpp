// The diffuse IBL composite as a compute pass (src/gpu/shaders/shade.comp): albedo x SH irradiance / pi x AO
// (Ramamoorthi and Hanrahan 2001), or x G(A, albedo) (Jimenez et al. 2016, eq. 10). The CPU references are
// render::shade (src/render/composite.cpp) and the CLI's multi-bounce composite (cli::shadeGtao in
// gtao_cli.cpp). Contract in include/obscura/gpu_lighting.h.
#include "gpu/shade_pass.h"
#include "gpu/compute_pipeline.h"
#include "gpu/image_planes.h"
#include "gpu/spirv.h"

#include "obscura/error.h"
#include "obscura/gpu_lighting.h"

#include <string>
#include <vector>

namespace obscura::gpu {

std::array<float, 36> irradianceTerms(const render::SH9& sh) {
    const std::array<double, 9> scales = render::irradianceScales();
    std::array<float, 36> terms{};
    for (std::size_t i = 0; i < 9; ++i)
        for (int c = 0; c < 3; ++c)
            terms[4 * i + std::size_t(c)] = float(scales[i] * double(sh.coefficients[i][c]));
    return terms;
}

ShadeConstants shadeConstants(const Camera& camera, int aoChannels, const Image& environment) {
    ShadeConstants k{};
    k.width = camera.width;
    k.height = camera.height;
    k.aoChannels = aoChannels;
    k.envWidth = environment.empty() ? 0 : environment.width;
    k.envHeight = environment.empty() ? 0 : environment.height;
    const Camera::PixelToView v = camera.viewFromPixelAffine();
    k.viewFromPixelMulX = v.mulX;
    k.viewFromPixelAddX = v.addX;
    k.viewFromPixelMulY = v.mulY;
    k.viewFromPixelAddY = v.addY;
    const Mat4 worldFromView = camera.worldFromView();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) k.worldFromView[4 * r + c] = worldFromView.m[r][c];
    return k;
}

Texture environmentTexture(Context::Impl& c, const Image& environment) {
    TextureShape shape;
    shape.channels = 4;
    if (environment.empty()) {
        const float black[4] = {0, 0, 0, 0};
        return uploadTexture(c, black, shape, TextureFilter::Nearest);
    }
    shape.width = environment.width;
    shape.height = environment.height;
    std::vector<float> rgba(4 * environment.pixelCount(), 0.0f);
    for (std::size_t i = 0; i < environment.pixelCount(); ++i)
        for (std::size_t ch = 0; ch < 3; ++ch)
            rgba[4 * i + ch] = environment.pixels[i * std::size_t(environment.channels) + ch];
    return uploadTexture(c, rgba.data(), shape, TextureFilter::Nearest);
}

void recordShade(Context::Impl& c, VkCommandBuffer cmd, const ShadeBuffers& b, const ShadeConstants& k) {
    using K = BindingKind;
    // In binding order: kShadeBindingDepth, Normal, Albedo, Occlusion, Irradiance, Environment, Color, Lighting.
    ComputePipeline& pipeline = c.pipeline(
        "shade", shaders::shade,
        {K::StorageBuffer, K::StorageBuffer, K::StorageBuffer, K::StorageBuffer, K::StorageBuffer, K::SampledImage,
         K::StorageBuffer, K::StorageBuffer},
        kShadePushConstantBytes, kLightingWorkgroupX, kLightingWorkgroupY,
        {b.packedNormals ? 1 : 0});  // kShadeSpecPackedNormals
    pipeline.dispatchGrid(cmd, {&b.depth, &b.normal, &b.albedo, &b.occlusion, &b.irradiance, &b.environment, &b.color,
                                &b.lighting},
                          &k, sizeof k, k.width, k.height);
}

namespace {

// Uploads, records and downloads; `occlusion` has 0 (none), 1 or 3 channels, checked by the caller.
render::Frame shadeOnGpu(Context& context, const GBuffer& g, const render::SH9& sh, const Image& occlusion,
                         const Image& environment) {
    render::Frame frame{Image(g.width(), g.height(), 3), Image(g.width(), g.height(), 3)};
    frame.color.channelNames = {"R", "G", "B"};
    frame.lighting.channelNames = {"R", "G", "B"};
    if (g.width() < 1 || g.height() < 1) return frame;  // as render::shade; Vulkan has no buffer of 0 bytes
    Context::Impl& c = context.impl();
    const int channels = occlusion.empty() ? 0 : occlusion.channels;
    const std::size_t pixels = g.depth.pixelCount();
    const Buffer depth = uploadChannels(c, g.depth, 1);
    const Buffer normal = uploadChannels(c, g.normal, 3);
    const Buffer albedo = uploadChannels(c, g.albedo, 3);
    const float none = 1.0f;
    const Buffer ao = channels ? uploadChannels(c, occlusion, channels) : upload(c, &none, sizeof none);
    const std::array<float, 36> terms = irradianceTerms(sh);
    const Buffer irradiance = upload(c, terms.data(), sizeof terms);
    const Texture env = environmentTexture(c, environment);
    const Buffer color(c, 3 * pixels * sizeof(float), MemoryUse::Device);
    const Buffer lighting(c, 3 * pixels * sizeof(float), MemoryUse::Device);
    const ShadeConstants k = shadeConstants(g.camera, channels, environment);
    c.submit([&](VkCommandBuffer cmd) { recordShade(c, cmd, {depth, normal, albedo, ao, irradiance, env, color, lighting}, k); },
             true);
    download(c, color, frame.color.pixels.data(), 3 * pixels * sizeof(float));
    download(c, lighting, frame.lighting.pixels.data(), 3 * pixels * sizeof(float));
    return frame;
}

} // namespace

render::Frame shade(Context& context, const GBuffer& g, const render::SH9& sh, const Image& ao, const Image& environment) {
    render::checkShadeInputs(g, ao, environment);  // render::shade's checks and messages
    return shadeOnGpu(context, g, sh, ao, environment);
}

render::Frame shadeMultiBounce(Context& context, const GBuffer& g, const render::SH9& sh, const Image& multibounce,
                               const Image& environment) {
    render::checkShadeInputs(g, Image(), environment);
    if (multibounce.width != g.width() || multibounce.height != g.height() || multibounce.channels != 3)
        fail("multi-bounce", "image must be 3 channels of the " + std::to_string(g.width()) + "x" +
                                 std::to_string(g.height()) + " G-buffer");
    return shadeOnGpu(context, g, sh, multibounce, environment);
}

} // namespace obscura::gpu
