// The diffuse IBL composite on GPU-resident buffers, for callers that chain passes in one submission (the
// public gpu::shade and gpu::shadeMultiBounce upload, record this and download).
#pragma once

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/texture.h"
#include "shaders/lighting_layouts.h"

#include "obscura/camera.h"
#include "obscura/image.h"
#include "obscura/render.h"

#include <array>

namespace obscura::gpu {

// Resources of shade.comp (shaders/lighting_layouts.h states their contents).
struct ShadeBuffers {
    const Buffer& depth;        // width * height linear depths
    const Buffer& normal;       // width * height * 3 view normals
    const Buffer& albedo;       // width * height * 3 albedo
    const Buffer& occlusion;    // width * height * aoChannels (one float when 0)
    const Buffer& irradiance;   // irradianceTerms(sh)
    const Texture& environment; // environmentTexture(environment)
    const Buffer& color;        // width * height * 3, output
    const Buffer& lighting;     // width * height * 3, output
    bool packedNormals = false;  // `normal` holds one octahedral word per pixel (kShadeSpecPackedNormals 1)
};

// The SH9 as the shader evaluates it: term i (SH9's order) is A_l N_lm L_lm RGB (and a 0), formed in double
// as render::irradiance forms them, times the bare monomial of Y_lm in the shader.
std::array<float, 36> irradianceTerms(const render::SH9& sh);
// The camera's transforms and the occlusion's and environment's sizes.
ShadeConstants shadeConstants(const Camera& camera, int aoChannels, const Image& environment);
// The equirect as an RGBA32F 2-D texture (the first three channels; one black texel when empty), read by
// texelFetch.
Texture environmentTexture(Context::Impl& context, const Image& environment);

// Records the dispatch; the inputs must be visible to compute shaders (the caller's barrier).
void recordShade(Context::Impl& context, VkCommandBuffer cmd, const ShadeBuffers& buffers,
                 const ShadeConstants& constants);

} // namespace obscura::gpu
