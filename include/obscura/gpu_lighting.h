// The post-processing passes after the AO estimators, as Vulkan compute passes on a gpu::Context: multi-bounce
// AO and GTSO (Jimenez et al. 2016, §5 and §6), and the diffuse IBL composite (render::shade). Each takes
// its CPU reference's inputs, runs its checks with the same messages, and returns the same images to within
// GPU rounding (tests/gpu/lighting_gpu_test.cpp states and measures the bounds). Errors: as in obscura/gpu.h.
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/gpu.h"
#include "obscura/image.h"
#include "obscura/render.h"
#include "obscura/specular_occlusion.h"

namespace obscura::gpu {

// ssao::multiBounce per pixel and channel from the G-buffer's albedo and a 1-channel visibility of its size:
// 3 channels G(A, albedo); sky pixels 1 (the CLI's GTAO frame). Throws obscura::Error on a size mismatch
// (the CPU function is per pixel and checks nothing; the message is this pass's own).
Image multiBounce(Context& context, const GBuffer& gbuffer, const Image& visibility);

// ssao::computeSpecularOcclusion: the same modes, checks and messages, output (sky 1). The tables
// (SpecularOcclusionTable::fourD / threeD) are built on the CPU on first use, then uploaded as 3-D textures.
Image specularOcclusion(Context& context, const GBuffer& gbuffer, const Image& ao, const Image& bentNormal,
                        ssao::SpecularOcclusionMode mode, float roughness);

// render::shade: the same checks, messages and Frame (color and lighting).
render::Frame shade(Context& context, const GBuffer& gbuffer, const render::SH9& sh, const Image& ao,
                    const Image& environment);
// The multi-bounce composite (the CLI's shadeGtao): render::shade without AO, then the colour of every
// surface pixel times `multibounce` (3 channels of the G-buffer's size) per channel. Throws obscura::Error
// with render::shade's messages, and this pass's own for a multibounce image of the wrong size.
render::Frame shadeMultiBounce(Context& context, const GBuffer& gbuffer, const render::SH9& sh,
                               const Image& multibounce, const Image& environment);

} // namespace obscura::gpu
