// One 1-D pass of the separable cross-bilateral blur: McGuire et al. 2011, "The Alchemy Screen-Space Ambient
// Obscurance Algorithm", Fig. 6 (horizontal, then vertical), as a compute pass; one invocation per pixel.
//
// The CPU reference is src/ssao/bilateral_separable.cpp; the tap loop (bilateral_taps.glsl) is its
// beginCentres, addTap and finishCentres for one centre instead of eight. The differences: exp2 is the GPU's instead of a degree-3
// polynomial (relative error 7.5e-5), and taps outside the image are skipped instead of read as sky padding
// that weighs 2^-125.
//
// Each workgroup first copies the depths and inputs of its lines along the axis, radius longer on each side,
// into shared memory, and the spatial weights beside them; the taps then read shared memory instead of 13
// global loads each. The horizontal pass's workgroup is one line of 256 pixels, the vertical pass's 8
// columns of 32 (a warp reads 8 columns x 4 rows: whole 32-byte sectors), so that the lines are long and the
// radius around them is a small part of what is read. On an H100 (2026-11-25, 13 taps) the two passes took
// 0.075 ms at 1920x1080 reading global memory per tap, 0.057 ms with 8x8 workgroups of 8-pixel lines and
// 0.050 ms with these; at 3840x2160, 0.277, 0.230 and 0.183 ms.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "layouts.h"

layout(local_size_x = kBilateralWorkgroupX, local_size_y = kBilateralWorkgroupY, local_size_z = 1) in;

layout(constant_id = kBilateralSpecUseNormal) const int kUseNormal = 0;  // = k.useNormal (layouts.h)

layout(push_constant, std430) uniform Constants { BilateralConstants k; };
layout(std430, binding = kBilateralBindingDepth) readonly buffer DepthPlane { float depth[]; };
layout(constant_id = kBilateralSpecPackedNormals) const int kPackedNormals = 0;
layout(constant_id = kBilateralSpecUnrolled) const int kUnrolled = 0;  // bilateralSpecUnrolled (layouts.h)
layout(std430, binding = kBilateralBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };
layout(std430, binding = kBilateralBindingLogSpatial) readonly buffer Spatial { float logSpatial[]; };
layout(std430, binding = kBilateralBindingInput) readonly buffer Input { float aoIn[]; };
layout(std430, binding = kBilateralBindingOutput) writeonly buffer Output { float aoOut[]; };

// A workgroup's tile (layouts.h): axis 0, 1 line of kBilateralHorizontalTileX pixels; axis 1,
// kBilateralVerticalTileX lines (columns) of kBilateralVerticalTileY pixels. Each line is stored with the
// taps beyond both of its ends at the largest radius.
const int kHorizontalSlots = kBilateralHorizontalTileX + 2 * kBilateralMaxRadius;
const int kVerticalSlots = kBilateralVerticalTileX * (kBilateralVerticalTileY + 2 * kBilateralMaxRadius);
const int kSlots = kHorizontalSlots > kVerticalSlots ? kHorizontalSlots : kVerticalSlots;
// Each slot holds a tap's depth and input side by side: one 8-byte shared load per tap instead of two.
shared vec2 tile[kSlots];
shared float tileLogSpatial[2 * kBilateralMaxRadius + 1];

// Position i along line `line`: the horizontal line as it lies; the columns interleaved, so that a warp's
// 8 columns x 4 rows read 32 consecutive slots.
int tileIndex(int line, int i) { return k.axis == 0 ? i : i * kBilateralVerticalTileX + line; }

#include "bilateral_guide.glsl"
#include "normal_plane.glsl"
#include "bilateral_taps.glsl"

void main() {
    const int invocation = int(gl_LocalInvocationID.x);
    const ivec2 group = ivec2(gl_WorkGroupID.xy);
    // This invocation's pixel, its line and its place along the line, and the line's length in the tile.
    ivec2 p;
    int line, localAlong, tileLength;
    if (k.axis == 0) {
        p = ivec2(group.x * kBilateralHorizontalTileX + invocation, group.y);
        line = 0;
        localAlong = invocation;
        tileLength = kBilateralHorizontalTileX;
    } else {
        line = invocation % kBilateralVerticalTileX;
        localAlong = invocation / kBilateralVerticalTileX;
        p = ivec2(group.x * kBilateralVerticalTileX + line, group.y * kBilateralVerticalTileY + localAlong);
        tileLength = kBilateralVerticalTileY;
    }
    // Along the axis and across it: this pixel's place and the image's extent.
    const int along = k.axis == 0 ? p.x : p.y, length = k.axis == 0 ? k.width : k.height;
    const int across = min(k.axis == 0 ? p.y : p.x, (k.axis == 0 ? k.height : k.width) - 1);
    // The tile starts radius taps before the line's first pixel; taps outside the image repeat the edge pixel
    // in the tile but are never read (the loop below skips them, as the CPU pass does).
    const int start = along - localAlong - k.radius;
    for (int i = localAlong; i < tileLength + 2 * k.radius; i += tileLength) {
        const int a = clamp(start + i, 0, length - 1);
        const uint o = k.axis == 0 ? uint(across) * uint(k.width) + uint(a) : uint(a) * uint(k.width) + uint(across);
        tile[tileIndex(line, i)] =
            vec2(depth[k.axis == 0 ? bilateralGuideIndex(a, across) : bilateralGuideIndex(across, a)], aoIn[o]);
    }
    for (int i = invocation; i <= 2 * k.radius; i += kBilateralWorkgroupX) tileLogSpatial[i] = logSpatial[i];
    barrier();
    if (p.x >= k.width || p.y >= k.height) return;

    const uint x = uint(p.y) * uint(k.width) + uint(p.x);
    const int centre = localAlong + k.radius;  // this pixel in the tile
    const float d = tile[tileIndex(line, centre)].x;
    const float c = k.depthScale / (d * d);  // 0 on sky: its output is its input anyway
    // The normals are read from the guide: the centre's index there, and the taps' spacing.
    const uint g = bilateralGuideIndex(p.x, p.y);
    const vec3 n = kUseNormal != 0 ? loadNormal(g) : vec3(0.0);
    const int guideStride = k.axis == 0 ? bilateralGuideStep() : int(bilateralGuideIndex(0, 1));
    // Taps inside the image along the axis: t in [tFirst, tLast].
    const int tFirst = max(-k.radius, -along), tLast = min(k.radius, length - 1 - along);
    aoOut[x] = bilateralTaps(line, centre, k.radius, tFirst, tLast, d, c, n, g, guideStride);
}
