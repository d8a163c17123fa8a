// The depth MIP chain of GTAO's mip sampling, after XeGTAO's depth prefilter (Intel, 2021): coarse levels
// 1..k.levels of inverse depth in one dispatch. The filter, sizes and layout are obscura/gtao_mips.h's,
// shared with the C++ reference ssao::buildGtaoDepthMips (src/ssao/gtao_mips.cpp), which this is texel for
// texel: level 1 from the depth buffer, each level above from the one below, the second child clamped to the
// level's last texel. One invocation per level-1 texel; the levels above live in shared memory, each made by
// the invocations of the tile's top-left corner.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "obscura/gtao_mips.h"
#include "layouts.h"

layout(local_size_x = GTAO_MIP_WORKGROUP, local_size_y = GTAO_MIP_WORKGROUP, local_size_z = 1) in;

layout(push_constant, std430) uniform Constants { GtaoMipConstants k; };
layout(std430, binding = kGtaoMipsBindingDepth) readonly buffer DepthPlane { float depthPlane[]; };
layout(std430, binding = kGtaoMipsBindingChain) writeonly buffer Chain { float chain[]; };

shared float tile[GTAO_MIP_WORKGROUP][GTAO_MIP_WORKGROUP];

// Level 0 as inverse depth: 0 for sky (1e30 and beyond, as the GTAO kernel reads it).
float inverseDepth(int x, int y) {
    const float d = depthPlane[uint(y) * uint(k.width) + uint(x)];
    return d < 1e30 ? 1.0 / d : 0.0;
}

void main() {
    const ivec2 local = ivec2(gl_LocalInvocationID.xy);
    const ivec2 group = ivec2(gl_WorkGroupID.xy);
    // Level 1. An invocation past the level's edge takes the last texel's value: it only ever feeds texels
    // past the edge of the levels above, which are not written, but it must read inside the buffer.
    int levelWidth = gtaoMipSize(k.width, 1), levelHeight = gtaoMipSize(k.height, 1);
    const ivec2 texel = group * GTAO_MIP_WORKGROUP + local;
    const int tx = min(texel.x, levelWidth - 1), ty = min(texel.y, levelHeight - 1);
    const int x0 = 2 * tx, x1 = min(2 * tx + 1, k.width - 1), y0 = 2 * ty, y1 = min(2 * ty + 1, k.height - 1);
    float w = gtaoMipFilter(inverseDepth(x0, y0), inverseDepth(x1, y0), inverseDepth(x0, y1), inverseDepth(x1, y1));
    if (texel.x < levelWidth && texel.y < levelHeight)
        chain[uint(texel.y) * uint(levelWidth) + uint(texel.x)] = w;
    tile[local.y][local.x] = w;

    // Level l: a tile of GTAO_MIP_WORKGROUP >> (l - 1) texels a side, from the tile of level l - 1 held in
    // its top-left corner. k.levels is uniform, so every barrier is reached by the whole workgroup.
    for (int level = 2; level <= k.levels; ++level) {
        const int childWidth = levelWidth, childHeight = levelHeight;
        levelWidth = gtaoMipSize(k.width, level);
        levelHeight = gtaoMipSize(k.height, level);
        const int side = GTAO_MIP_WORKGROUP >> (level - 1);
        const bool inside = local.x < side && local.y < side;
        const ivec2 t = group * side + local;  // this invocation's texel of the level
        barrier();                               // the level below is in the tile
        if (inside) {
            // Children 2t and 2t + 1, the second clamped to the last texel of the level below (which is then
            // the first: 2t is inside that level for every t inside this one).
            const int cx0 = 2 * local.x, cy0 = 2 * local.y;
            const int cx1 = 2 * t.x + 1 < childWidth ? cx0 + 1 : cx0, cy1 = 2 * t.y + 1 < childHeight ? cy0 + 1 : cy0;
            w = gtaoMipFilter(tile[cy0][cx0], tile[cy0][cx1], tile[cy1][cx0], tile[cy1][cx1]);
        }
        barrier();  // every child is read before the tile is overwritten
        if (inside) {
            tile[local.y][local.x] = w;
            if (t.x < levelWidth && t.y < levelHeight)
                chain[uint(gtaoMipOffset(k.width, k.height, level)) + uint(t.y) * uint(levelWidth) + uint(t.x)] = w;
        }
    }
}
