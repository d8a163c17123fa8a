// GTSO as a compute pass (src/gpu/shaders/specular_occlusion.comp): Jimenez et al. 2016, "Practical Realtime
// Strategies for Accurate Indirect Occlusion", §6 and App. B. The CPU reference is
// ssao::computeSpecularOcclusion (src/ssao/specular_occlusion.cpp). Contract in include/obscura/gpu_lighting.h.
#include "gpu/specular_occlusion_pass.h"
#include "gpu/compute_pipeline.h"
#include "gpu/image_planes.h"
#include "gpu/spirv.h"

#include "obscura/error.h"
#include "obscura/gpu_lighting.h"

#include <string>
#include <vector>

namespace obscura::gpu {

namespace {

int modeCode(ssao::SpecularOcclusionMode mode) {
    switch (mode) {
    case ssao::SpecularOcclusionMode::Lut4: return kSpecularModeLut4;
    case ssao::SpecularOcclusionMode::Lut3: return kSpecularModeLut3;
    case ssao::SpecularOcclusionMode::Cone: return kSpecularModeCone;
    }
    return kSpecularModeCone;
}

} // namespace

SpecularConstants specularConstants(const GBuffer& g, float roughness) {
    const Camera::PixelToView v = g.camera.viewFromPixelAffine();
    return {g.width(), g.height(), roughness, ssao::kSpecularTableSize, v.mulX, v.addX, v.mulY, v.addY};
}

Texture specularTable(Context::Impl& c, ssao::SpecularOcclusionMode mode, TextureFilter filter) {
    constexpr int n = ssao::kSpecularTableSize;
    using Table = ssao::SpecularOcclusionTable;
    TextureShape shape;
    shape.threeD = true;
    std::vector<float> texels;
    if (mode == ssao::SpecularOcclusionMode::Lut4) {
        // x alpha_v, y beta, z theta_o * n + roughness: the CPU's own node order.
        const Table& table = Table::fourD();
        shape.width = n;
        shape.height = n;
        shape.depth = n * n;
        for (int l = 0; l < n; ++l)
            for (int k = 0; k < n; ++k)
                for (int j = 0; j < n; ++j)
                    for (int i = 0; i < n; ++i) texels.push_back(table.node(i, j, k, l));
    } else if (mode == ssao::SpecularOcclusionMode::Lut3) {
        const Table& table = Table::threeD();
        shape.width = n;
        shape.height = n;
        shape.depth = n;
        for (int l = 0; l < n; ++l)
            for (int k = 0; k < n; ++k)
                for (int i = 0; i < n; ++i) texels.push_back(table.node(i, 0, k, l));
    } else {
        texels.push_back(1.0f);  // the cone variant binds a table it never reads
    }
    return uploadTexture(c, texels.data(), shape, filter);
}

void recordSpecularOcclusion(Context::Impl& c, VkCommandBuffer cmd, const SpecularOcclusionBuffers& b,
                             const SpecularConstants& k, ssao::SpecularOcclusionMode mode, int lookup) {
    using K = BindingKind;
    // In binding order: kSpecularBindingDepth, Normal, Ao, BentNormal, Table, Output.
    ComputePipeline& pipeline =
        c.pipeline("specular_occlusion", shaders::specular_occlusion,
                   {K::StorageBuffer, K::StorageBuffer, K::StorageBuffer, K::StorageBuffer, K::SampledImage,
                    K::StorageBuffer},
                   kSpecularPushConstantBytes, kLightingWorkgroupX, kLightingWorkgroupY,
                   {modeCode(mode), lookup, b.packedNormals ? 1 : 0});  // kSpecularSpecMode, Lookup, PackedNormals
    pipeline.dispatchGrid(cmd, {&b.depth, &b.normal, &b.ao, &b.bentNormal, &b.table, &b.output}, &k, sizeof k,
                          k.width, k.height);
}

Image specularOcclusionWith(Context& context, const GBuffer& g, const Image& ao, const Image& bentNormal,
                            ssao::SpecularOcclusionMode mode, float roughness, int lookup) {
    // ssao::computeSpecularOcclusion's checks and messages (tests/gpu compare them); they also keep the uploads
    // whole and NaN out of the table coordinates.
    ssao::checkSpecularOcclusionInputs(g, ao, bentNormal, roughness);
    if (g.width() < 1 || g.height() < 1) return Image(g.width(), g.height(), 1, 1.0f);  // as the CPU; no 0-byte buffers
    Context::Impl& c = context.impl();
    const Texture table = specularTable(
        c, mode, lookup == kSpecularLookupHardware ? TextureFilter::Linear : TextureFilter::Nearest);
    const std::size_t pixels = g.depth.pixelCount();
    const Buffer depth = uploadChannels(c, g.depth, 1);
    const Buffer normal = uploadChannels(c, g.normal, 3);
    const Buffer visibility = uploadChannels(c, ao, 1);
    const Buffer bent = uploadChannels(c, bentNormal, 3);
    const Buffer result(c, pixels * sizeof(float), MemoryUse::Device);
    const SpecularConstants k = specularConstants(g, roughness);
    c.submit([&](VkCommandBuffer cmd) {
        recordSpecularOcclusion(c, cmd, {depth, normal, visibility, bent, table, result}, k, mode, lookup);
    },
             true);
    Image out(g.width(), g.height(), 1);
    download(c, result, out.pixels.data(), pixels * sizeof(float));
    return out;
}

Image specularOcclusion(Context& context, const GBuffer& g, const Image& ao, const Image& bentNormal,
                        ssao::SpecularOcclusionMode mode, float roughness) {
    return specularOcclusionWith(context, g, ao, bentNormal, mode, roughness, kSpecularLookupFetch);
}

} // namespace obscura::gpu
