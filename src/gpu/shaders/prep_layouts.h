// Resources of the depth and normal preparation passes (prepare_depth.comp, normals_from_depth.comp; host
// side src/gpu/depth_prep_pass.cpp), shared by the shaders and the host like layouts.h. The push constants
// of both are one DepthPrepConstants (obscura/depth_prep_constants.h).
#ifndef OBSCURA_GPU_PREP_LAYOUTS_H
#define OBSCURA_GPU_PREP_LAYOUTS_H

#ifdef __cplusplus
namespace obscura::gpu {
#define OBSCURA_CONST inline constexpr
#else
#define OBSCURA_CONST const
#endif

// prepare_depth.comp: storage buffers of set 0 (float arrays, std430).
OBSCURA_CONST int kPrepBindingDeviceDepth = 0;  // width * height device depths in [0, 1]
OBSCURA_CONST int kPrepBindingNormalIn = 1;     // width * height * normalChannels normals (FromDepth: any buffer)
OBSCURA_CONST int kPrepBindingDepth = 2;        // width * height linear depths, +inf for sky: output
OBSCURA_CONST int kPrepBindingNormal = 3;       // width * height * 3 view normals, 0 for sky: output
OBSCURA_CONST int kPrepBindingCount = 4;

// normals_from_depth.comp: storage buffers of set 0.
OBSCURA_CONST int kRebuildBindingDepth = 0;   // width * height linear depths
OBSCURA_CONST int kRebuildBindingNormal = 1;  // width * height * 3 view normals: output
OBSCURA_CONST int kRebuildBindingCount = 2;

OBSCURA_CONST int kPrepPushConstantBytes = 112;  // one DepthPrepConstants

#ifdef __cplusplus
} // namespace obscura::gpu
#endif
#undef OBSCURA_CONST

#endif
