// The 4x4 interleave reconstruction of spatio-temporal GTAO: Jimenez, Wu, Pesce and Jarabo 2016, "Practical
// Realtime Strategies for Accurate Indirect Occlusion", §4.1 (the depth-aware spatial denoiser over the 4x4
// pattern), as a pass of its own: one invocation per grid pixel; 1 or 3 channels by specialization
// constant. The filter is temporal_filters.glsl's reconstructInterleaved; here the grid's depth and normals
// are guide planes read at a stride (temporal_layouts.h), and `values` and `outValues` are the buffers below.
// The filter reads them from a shared-memory tile (grid_tile.glsl); on an H100 (2026-11-25, visibility only)
// that took the half-resolution frame's pass from 0.041 to 0.024 ms at 1920x1080 (0.138 to 0.080 ms at
// 3840x2160).
#version 460
#extension GL_GOOGLE_include_directive : require

#include "temporal_layouts.h"

layout(local_size_x = kAccumulationWorkgroupX, local_size_y = kAccumulationWorkgroupY, local_size_z = 1) in;

layout(constant_id = kReconstructSpecChannels) const int kGridChannels = 1;
layout(constant_id = kReconstructSpecWindowPhase) const int kWindowPhase = -1;
layout(constant_id = kReconstructSpecPackedNormals) const int kPackedNormals = 0;

layout(push_constant, std430) uniform Constants { ReconstructConstants k; };
layout(std430, binding = kReconstructBindingValues) readonly buffer Values { float values[]; };
layout(std430, binding = kReconstructBindingDepth) readonly buffer DepthPlane { float depthPlane[]; };
layout(std430, binding = kReconstructBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };
layout(std430, binding = kReconstructBindingOutput) writeonly buffer Output { float outValues[]; };

uint guide(int x, int y) { return uint(y * k.guideStep) * uint(k.guideWidth) + uint(x * k.guideStep); }
float gridDepthAt(int x, int y) { return depthPlane[guide(x, y)]; }
#include "normal_plane.glsl"
vec3 gridNormalAt(int x, int y) { return loadNormal(guide(x, y)); }
float gridValueAt(int x, int y, int c) {
    return values[(uint(y) * uint(k.width) + uint(x)) * uint(kGridChannels) + uint(c)];
}

#define GRID_TILE_REACH (kWindowPhase >= 4 ? 1 : 2)  // the 2x2 windows reach 1 (obscura/reconstruct_window.h)
#include "grid_tile.glsl"
float gridDepth(int x, int y) { return gridTileDepth(x, y); }
vec3 gridNormal(int x, int y) { return gridTileNormal(x, y); }
float gridValue(int x, int y, int c) { return gridTileValue(x, y, c); }
#define GRID_OUTSIDE_IS_SKY true  // the tile's apron outside the grid is +inf (grid_tile.glsl)

#include "temporal_filters.glsl"

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    loadGridTile(k.width, k.height);
    if (p.x >= k.width || p.y >= k.height) return;
    float result[4];
    reconstructInterleaved(p.x, p.y, k.width, k.height, k.depthSigma, kWindowPhase, result);
    const uint i = (uint(p.y) * uint(k.width) + uint(p.x)) * uint(kGridChannels);
    for (int c = 0; c < kGridChannels; ++c) outValues[i + uint(c)] = result[c];
}
