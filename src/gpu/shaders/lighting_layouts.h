// The constants and resources of the post-processing compute shaders (multibounce.comp,
// specular_occlusion.comp, shade.comp; bilateral_2d.comp shares layouts.h's), shared by each shader and its host side in
// src/gpu, compiled as both C++ and GLSL like layouts.h. Plain 32-bit ints and floats only (vec4 where
// noted), so std430 and C++ lay the push constants out alike; the static_asserts below hold C++ to it, and
// ComputePipeline checks binding kinds, counts and push-constant sizes against the compiled shader.
#ifndef OBSCURA_GPU_LIGHTING_LAYOUTS_H
#define OBSCURA_GPU_LIGHTING_LAYOUTS_H

#ifdef __cplusplus
#include <cstddef>
namespace obscura::gpu {
#define OBSCURA_CONST inline constexpr
#else
#define OBSCURA_CONST const
#endif

OBSCURA_CONST int kLightingWorkgroupX = 8;
OBSCURA_CONST int kLightingWorkgroupY = 8;

// ---- multibounce.comp (src/gpu/multibounce_pass.cpp): ssao::multiBounce per pixel and channel ----
struct MultiBounceConstants {
    int width;   // px
    int height;  // px
    int pad0;
    int pad1;
};
// Storage buffers (float arrays, std430).
OBSCURA_CONST int kMultiBounceBindingDepth = 0;       // width * height linear depths, +inf for sky (G = 1)
OBSCURA_CONST int kMultiBounceBindingVisibility = 1;  // width * height visibility A in [0, 1]
OBSCURA_CONST int kMultiBounceBindingAlbedo = 2;      // width * height * 3 albedo
OBSCURA_CONST int kMultiBounceBindingOutput = 3;      // width * height * 3 G(A, albedo)
OBSCURA_CONST int kMultiBounceBindingCount = 4;
OBSCURA_CONST int kMultiBouncePushConstantBytes = 16;

// ---- specular_occlusion.comp (src/gpu/specular_occlusion_pass.cpp): ssao::specularOcclusion ----
// Specialization constants: the mode and how the table is interpolated.
OBSCURA_CONST int kSpecularModeLut4 = 0;  // ssao::SpecularOcclusionMode::Lut4
OBSCURA_CONST int kSpecularModeLut3 = 1;  // ... Lut3
OBSCURA_CONST int kSpecularModeCone = 2;  // ... Cone (no table; a 1-texel one is bound)
OBSCURA_CONST int kSpecularLookupFetch = 0;     // texelFetch of the 2^d nodes, weighted in float as the CPU does
OBSCURA_CONST int kSpecularLookupHardware = 1;  // the sampler's trilinear filter (the 4-D table: two, lerped)
OBSCURA_CONST int kSpecularSpecMode = 0;        // constant_id of the mode
OBSCURA_CONST int kSpecularSpecLookup = 1;      // constant_id of the lookup
// constant_id of the normals' layout, as gtao.comp's kGtaoSpecPackedNormals (layouts.h): 0 3 floats per pixel,
// 1 one octahedral word (normal_plane.glsl).
OBSCURA_CONST int kSpecularSpecPackedNormals = 2;
// Table textures, R32_SFLOAT, node (i alpha_v, j beta, k roughness, l theta_o) of
// ssao::SpecularOcclusionTable at texel:
//   4-D: (i, j, l * 32 + k) of a 32 x 32 x 1024 3-D image (theta_o and roughness share the z axis),
//   3-D: (i, k, l) of a 32 x 32 x 32 3-D image.
struct SpecularConstants {
    int width;        // px
    int height;       // px
    float roughness;  // GGX roughness of every pixel, [0, 1]
    int tableSize;    // ssao::kSpecularTableSize
    float viewFromPixelMulX;  // view x / depth = px * mulX + addX (Camera::viewFromPixelAffine)
    float viewFromPixelAddX;
    float viewFromPixelMulY;
    float viewFromPixelAddY;
};
OBSCURA_CONST int kSpecularBindingDepth = 0;       // width * height linear depths, +inf for sky (S = 1)
OBSCURA_CONST int kSpecularBindingNormal = 1;      // width * height * 3 view normals
OBSCURA_CONST int kSpecularBindingAo = 2;          // width * height visibility
OBSCURA_CONST int kSpecularBindingBentNormal = 3;  // width * height * 3 view bent normals
OBSCURA_CONST int kSpecularBindingTable = 4;       // sampler3D, the table above
OBSCURA_CONST int kSpecularBindingOutput = 5;      // width * height S
OBSCURA_CONST int kSpecularBindingCount = 6;
OBSCURA_CONST int kSpecularPushConstantBytes = 32;

// ---- shade.comp (src/gpu/shade_pass.cpp): render::shade and the multi-bounce composite ----
// color = albedo * E(n) / pi * occlusion (1, 1 or 3 channels), lighting = E(n) / pi; sky pixels: color is
// the environment (bilinear, as render::sampleEquirect), lighting 0.
struct ShadeConstants {
    int width;          // px
    int height;         // px
    int aoChannels;     // 0: no occlusion, 1: AO, 3: G(A, albedo) per channel
    int envWidth;       // texels; 0: no environment (black sky)

    int envHeight;      // texels
    int pad0;
    int pad1;
    int pad2;

    float viewFromPixelMulX;  // view x / depth = px * mulX + addX (Camera::viewFromPixelAffine)
    float viewFromPixelAddX;
    float viewFromPixelMulY;
    float viewFromPixelAddY;

    float worldFromView[12];  // rows 0..2 of Camera::worldFromView, 4 floats each (the 4th unused)
};
OBSCURA_CONST int kShadeBindingDepth = 0;        // width * height linear depths, +inf for sky
OBSCURA_CONST int kShadeBindingNormal = 1;       // width * height * 3 view normals (or words, kShadeSpecPackedNormals)
// constant_id of the normals' layout, as kSpecularSpecPackedNormals.
OBSCURA_CONST int kShadeSpecPackedNormals = 0;
OBSCURA_CONST int kShadeBindingAlbedo = 2;       // width * height * 3 albedo
OBSCURA_CONST int kShadeBindingOcclusion = 3;    // width * height * aoChannels (one float when 0)
OBSCURA_CONST int kShadeBindingIrradiance = 4;   // 9 x 4 floats: A_l N_lm L_lm RGB per basis term (shade_pass.h)
OBSCURA_CONST int kShadeBindingEnvironment = 5;  // sampler2D, RGBA32F equirect (1 texel when envWidth is 0)
OBSCURA_CONST int kShadeBindingColor = 6;        // width * height * 3, output
OBSCURA_CONST int kShadeBindingLighting = 7;     // width * height * 3, output
OBSCURA_CONST int kShadeBindingCount = 8;
OBSCURA_CONST int kShadePushConstantBytes = 96;

// ---- bilateral_2d.comp (src/gpu/bilateral_2d_pass.cpp): ssao::bilateral2D ----
// The separable pass's BilateralConstants and bindings (layouts.h; axis unused), except that binding
// kBilateralBindingLogSpatial holds the radius + 1 floats of ssao::gaussianHalfKernel(radius): a tap (tx, ty)
// weighs kernel[|tx|] kernel[|ty|] 2^(-dd^2 depthScale / d^2), times max(0, N . N_t) when useNormal is 1.
OBSCURA_CONST int kBilateral2DBindingKernel = 2;  // kBilateralBindingLogSpatial

#ifdef __cplusplus
static_assert(sizeof(MultiBounceConstants) == kMultiBouncePushConstantBytes, "MultiBounceConstants is std430");
static_assert(sizeof(SpecularConstants) == kSpecularPushConstantBytes &&
                  offsetof(SpecularConstants, viewFromPixelMulX) == 16,
              "SpecularConstants is std430");
static_assert(sizeof(ShadeConstants) == kShadePushConstantBytes && offsetof(ShadeConstants, viewFromPixelMulX) == 32 &&
                  offsetof(ShadeConstants, worldFromView) == 48,
              "ShadeConstants is std430");
} // namespace obscura::gpu
#endif
#undef OBSCURA_CONST

#endif
