// GTSO on GPU-resident buffers and a table texture, for callers that chain passes in one submission (the
// public gpu::specularOcclusion uploads, records this and downloads).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/texture.h"
#include "shaders/lighting_layouts.h"

#include "obscura/gbuffer.h"
#include "obscura/specular_occlusion.h"

namespace obscura::gpu {

// Resources of specular_occlusion.comp (shaders/lighting_layouts.h states their contents).
struct SpecularOcclusionBuffers {
    const Buffer& depth;       // width * height linear depths
    const Buffer& normal;      // width * height * 3 view normals
    const Buffer& ao;          // width * height visibility
    const Buffer& bentNormal;  // width * height * 3 view bent normals
    const Texture& table;      // specularTable(mode)
    const Buffer& output;      // width * height S
    bool packedNormals = false;  // `normal` holds one octahedral word per pixel (kSpecularSpecPackedNormals 1)
};

// The pass's constants for this G-buffer's camera and size; roughness checked by the caller.
SpecularConstants specularConstants(const GBuffer& gbuffer, float roughness);
// The mode's table (SpecularOcclusionTable::fourD / threeD, built on first use) as the 3-D texture the
// shader reads; Cone reads none and gets one texel. `filter` Linear only for kSpecularLookupHardware.
Texture specularTable(Context::Impl& context, ssao::SpecularOcclusionMode mode, TextureFilter filter);

// Records the dispatch of the mode's variant with `lookup` (kSpecularLookupFetch or Hardware); the inputs
// must be visible to compute shaders (the caller's barrier).
void recordSpecularOcclusion(Context::Impl& context, VkCommandBuffer cmd, const SpecularOcclusionBuffers& buffers,
                             const SpecularConstants& constants, ssao::SpecularOcclusionMode mode,
                             int lookup = kSpecularLookupFetch);

// gpu::specularOcclusion with the table read by `lookup` (the tests compare both interpolations).
Image specularOcclusionWith(Context& context, const GBuffer& gbuffer, const Image& ao, const Image& bentNormal,
                            ssao::SpecularOcclusionMode mode, float roughness, int lookup);

} // namespace obscura::gpu
