// The resources of alchemy.comp, shared by the shader and src/gpu/alchemy_pass.cpp (compiled as both C++
// and GLSL, like obscura/alchemy_constants.h). The host checks them against the compiled shader too
// (gpu::reflect), so a binding added on one side only fails at pipeline creation, not in a wrong image.
#ifndef OBSCURA_GPU_ALCHEMY_LAYOUT_H
#define OBSCURA_GPU_ALCHEMY_LAYOUT_H

#ifdef __cplusplus
namespace obscura::gpu {
#define OBSCURA_CONST inline constexpr
#else
#define OBSCURA_CONST const
#endif

// Storage buffers of set 0 (float arrays, std430).
OBSCURA_CONST int kAlchemyBindingDepth = 0;   // width * height linear depths, +inf for sky
OBSCURA_CONST int kAlchemyBindingNormal = 1;  // width * height * 3 view normals
OBSCURA_CONST int kAlchemyBindingSpiral = 2;  // SpiralTable::offsets, concatenated (see alchemySpiralAt)
OBSCURA_CONST int kAlchemyBindingOutput = 3;  // (width - 2 guardBand) * (height - 2 guardBand) obscurance
OBSCURA_CONST int kAlchemyBindingCount = 4;
// The push constants are one AlchemyConstants.
OBSCURA_CONST int kAlchemyPushConstantBytes = 96;

#ifdef __cplusplus
} // namespace obscura::gpu
#endif
#undef OBSCURA_CONST

#endif
