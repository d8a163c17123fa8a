// The separable cross-bilateral blur's two passes in one dispatch: McGuire et al. 2011, "The Alchemy
// Screen-Space Ambient Obscurance Algorithm", Fig. 6 (horizontal, then vertical), with the horizontal
// result kept in shared memory instead of going through a buffer.
//
// bilateral_separable.comp runs the passes as two dispatches: each pixel's depth and input are read twice
// and the horizontal result written and read once, 24 compulsory bytes per pixel, with a barrier between the
// dispatches that drains the GPU. Here a workgroup loads a square of kBilateralTiledTile pixels with radius
// more on each side once, blurs the rows of that whole apron (the rows above and below the square are blurred
// again by the workgroups there: (Tile + 2 radius) / Tile of the horizontal work), then the square's
// columns, and writes the square: 12 bytes per pixel. Each pixel's arithmetic is bilateral_separable's, tap
// for tap (bilateral_taps.glsl), so the result has its bits.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "layouts.h"

layout(local_size_x = kBilateralTiledWorkgroupX, local_size_y = kBilateralTiledWorkgroupY, local_size_z = 1) in;

layout(constant_id = kBilateralSpecUseNormal) const int kUseNormal = 0;  // = k.useNormal (layouts.h)

layout(push_constant, std430) uniform Constants { BilateralConstants k; };
layout(std430, binding = kBilateralBindingDepth) readonly buffer DepthPlane { float depth[]; };
layout(constant_id = kBilateralSpecPackedNormals) const int kPackedNormals = 0;
layout(constant_id = kBilateralSpecUnrolled) const int kUnrolled = 0;  // bilateralSpecUnrolled (layouts.h)
layout(std430, binding = kBilateralBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };
layout(std430, binding = kBilateralBindingLogSpatial) readonly buffer Spatial { float logSpatial[]; };
layout(std430, binding = kBilateralBindingInput) readonly buffer Input { float aoIn[]; };
layout(std430, binding = kBilateralBindingOutput) writeonly buffer Output { float aoOut[]; };

// The square and its apron at the largest radius, rows kStride slots apart; slot (x, y) holds the depth and
// the input of pixel (x0 - radius + x, y0 - radius + y), its input replaced by the row pass's result once the
// rows are blurred.
const int kStride = kBilateralTiledTile + 2 * kBilateralTiledMaxRadius;
const int kInvocations = kBilateralTiledWorkgroupX * kBilateralTiledWorkgroupY;
shared vec2 tile[kStride * kStride];
shared float tileLogSpatial[2 * kBilateralTiledMaxRadius + 1];

// Which way bilateral_taps.glsl walks the tile: along a row (line = its row) or down a column (line = its
// column).
int gAxis;
int tileIndex(int line, int i) { return gAxis == 0 ? line * kStride + i : i * kStride + line; }

#include "bilateral_guide.glsl"
#include "normal_plane.glsl"
#include "bilateral_taps.glsl"

// Slots loaded per invocation, every load issued before any store, and row-pass results per invocation.
const int kLoads = (kStride * kStride + kInvocations - 1) / kInvocations;
const int kRowsPerInvocation = (kBilateralTiledTile + 2 * kBilateralTiledMaxRadius + kBilateralTiledWorkgroupY - 1) /
                               kBilateralTiledWorkgroupY;
const int kOutputsPerInvocation = kBilateralTiledTile / kBilateralTiledWorkgroupY;

void main() {
    const int r = k.radius, side = kBilateralTiledTile + 2 * r;  // the apron's side at this radius
    const ivec2 lid = ivec2(gl_LocalInvocationID.xy);
    const int invocation = lid.y * kBilateralTiledWorkgroupX + lid.x;
    const ivec2 origin = ivec2(gl_WorkGroupID.xy) * kBilateralTiledTile - r;  // the pixel at slot (0, 0)

    // Pixels outside the image repeat the edge in the tile but are never read: the taps stop at the edges.
    vec2 loaded[kLoads];
    for (int j = 0; j < kLoads; ++j) {
        const int s = invocation + j * kInvocations;
        const int x = clamp(origin.x + s % side, 0, k.width - 1), y = clamp(origin.y + s / side, 0, k.height - 1);
        loaded[j] = s < side * side ? vec2(depth[bilateralGuideIndex(x, y)], aoIn[uint(y) * uint(k.width) + uint(x)])
                                    : vec2(0.0);
    }
    for (int j = 0; j < kLoads; ++j) {
        const int s = invocation + j * kInvocations;
        if (s < side * side) tile[(s / side) * kStride + s % side] = loaded[j];
    }
    for (int i = invocation; i <= 2 * r; i += kInvocations) tileLogSpatial[i] = logSpatial[i];
    barrier();

    // Rows: the square's columns in every row of the apron that lies in the image (the column pass reads no
    // other), kept in registers until every invocation has read the inputs they replace.
    gAxis = 0;
    const int px = origin.x + r + lid.x;  // this invocation's column in the image
    float rowResult[kRowsPerInvocation];
    for (int j = 0; j < kRowsPerInvocation; ++j) {
        const int row = lid.y + j * kBilateralTiledWorkgroupY, py = origin.y + row;
        rowResult[j] = 0.0;
        if (row >= side || px >= k.width || py < 0 || py >= k.height) continue;
        const int centre = r + lid.x;
        const float d = tile[tileIndex(row, centre)].x;
        const float c = k.depthScale / (d * d);  // 0 on sky: its output is its input anyway
        const uint g = bilateralGuideIndex(px, py);
        const vec3 n = kUseNormal != 0 ? loadNormal(g) : vec3(0.0);
        const int tFirst = max(-r, -px), tLast = min(r, k.width - 1 - px);
        rowResult[j] = bilateralTaps(row, centre, r, tFirst, tLast, d, c, n, g, bilateralGuideStep());
    }
    barrier();
    for (int j = 0; j < kRowsPerInvocation; ++j) {
        const int row = lid.y + j * kBilateralTiledWorkgroupY;
        if (row < side) tile[row * kStride + r + lid.x].y = rowResult[j];
    }
    barrier();

    // Columns: the square itself.
    gAxis = 1;
    if (px >= k.width) return;
    const int guideRow = int(bilateralGuideIndex(0, 1));
    for (int j = 0; j < kOutputsPerInvocation; ++j) {
        const int row = r + lid.y + j * kBilateralTiledWorkgroupY, py = origin.y + row;
        if (py >= k.height) break;
        const int line = r + lid.x;
        const float d = tile[tileIndex(line, row)].x;
        const float c = k.depthScale / (d * d);
        const uint g = bilateralGuideIndex(px, py);
        const vec3 n = kUseNormal != 0 ? loadNormal(g) : vec3(0.0);
        const int tFirst = max(-r, -py), tLast = min(r, k.height - 1 - py);
        aoOut[uint(py) * uint(k.width) + uint(px)] = bilateralTaps(line, row, r, tFirst, tLast, d, c, n, g, guideRow);
    }
}
