// Depth-aware upsampling of half-resolution GTAO: Jimenez, Wu, Pesce and Jarabo 2016, "Practical Realtime
// Strategies for Accurate Indirect Occlusion", §4.1 (evaluation at half resolution), as a pass of its own:
// one invocation per 2x2 block of full-resolution pixels; 1 or 3 channels by specialization constant. The
// filter is temporal_filters.glsl's upsampleDepthAware; here the low-resolution depth is a guide plane read
// at a stride (temporal_layouts.h), and `low` and `outWords` are the buffers below.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "temporal_layouts.h"

layout(local_size_x = kUpsampleWorkgroupX, local_size_y = kUpsampleWorkgroupY, local_size_z = 1) in;

layout(constant_id = kUpsampleSpecChannels) const int kGridChannels = 1;
layout(constant_id = kUpsampleSpecPackedLow) const int kPackedLow = 0;
layout(constant_id = kUpsampleSpecPackedOut) const int kPackedOut = 0;
layout(constant_id = kUpsampleSpecPackedNormals) const int kPackedNormals = 0;

layout(push_constant, std430) uniform Constants { UpsampleConstants k; };
// Words: floats' bits, or with kPackedLow the packed visibility of obscura/history_packing.h.
layout(std430, binding = kUpsampleBindingLow) readonly buffer Low { uint low[]; };
layout(std430, binding = kUpsampleBindingLowDepth) readonly buffer LowDepth { float lowDepthPlane[]; };
layout(std430, binding = kUpsampleBindingDepth) readonly buffer DepthPlane { float depthPlane[]; };
// Words: floats' bits, or with kPackedOut two unorm16 visibilities (temporal_layouts.h).
layout(std430, binding = kUpsampleBindingOutput) writeonly buffer Output { uint outWords[]; };
// Words: normal_plane.glsl's, 3 floats' bits or with kPackedNormals an octahedral code.
layout(std430, binding = kUpsampleBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };

// One invocation per 2x2 block of full-resolution pixels (2bx..2bx+1, 2by..2by+1): all four read the grid
// pixels bx..bx+1 x by..by+1 (clamped at the grid's edge), so the invocation loads those once and the filter
// reads them from registers: 3 loads per pixel instead of 9, and the index arithmetic once per block.
// Scalars and selects rather than arrays, which a dynamic index would send to local memory.
ivec2 block;                     // (bx, by)
float depth00, depth10, depth01, depth11;  // grid pixel (bx + i, by + j) as depth<i><j>
vec3 value00, value10, value01, value11;   // its kGridChannels values

float gridDepth(int x, int y) {
    const bool right = x != block.x, down = y != block.y;
    return down ? (right ? depth11 : depth01) : (right ? depth10 : depth00);
}
vec3 gridNormal(int x, int y) { return vec3(0.0); }  // the upsampling weighs by depth alone
float gridValue(int x, int y, int c) {
    const bool right = x != block.x, down = y != block.y;
    return (down ? (right ? value11 : value01) : (right ? value10 : value00))[c];
}
float lowDepth(int x, int y) { return lowDepthPlane[uint(y * k.guideStep) * uint(k.guideWidth) + uint(x * k.guideStep)]; }

#include "temporal_filters.glsl"
#include "normal_plane.glsl"
#include "obscura/history_packing.h"

vec3 lowValues(int x, int y) {
    const uint base = (uint(y) * uint(k.lowWidth) + uint(x)) * uint(kGridChannels);
    if (kPackedLow != 0) return vec3(unpackVisibility(low[base]), 0.0, 0.0);
    vec3 v = vec3(0.0);
    for (int c = 0; c < kGridChannels; ++c) v[c] = uintBitsToFloat(low[base + uint(c)]);
    return v;
}

void main() {
    block = ivec2(gl_GlobalInvocationID.xy);
    if (2 * block.x >= k.width || 2 * block.y >= k.height) return;
    // The filter's taps, clamped as upsampleDepthAware clamps them.
    const int x1 = min(block.x + 1, k.lowWidth - 1), y1 = min(block.y + 1, k.lowHeight - 1);
    depth00 = lowDepth(block.x, block.y);
    depth10 = lowDepth(x1, block.y);
    depth01 = lowDepth(block.x, y1);
    depth11 = lowDepth(x1, y1);
    value00 = lowValues(block.x, block.y);
    value10 = lowValues(x1, block.y);
    value01 = lowValues(block.x, y1);
    value11 = lowValues(x1, y1);
    // The taps' positions as upsampleDepthAware computes them from pixel (2 bx + i, 2 by + j): x0 = min(bx,
    // lowWidth - 1) and fx = bx - x0 + i / 2 (exact, as its gx - float(x0) is), without its 6 conversions
    // between floats and ints per pixel, on the unit that also runs the filter's exp and divisions. On an
    // H100 (2026-11-27) this took the pass to 0.933 / 0.927 of its time at 1920x1080 / 3840x2160 (gtao-half),
    // 0.933 in the spatio-temporal target's frame, whose 3840x2160 frame went to 0.982. The same bits.
    const int gx0 = min(block.x, k.lowWidth - 1), gy0 = min(block.y, k.lowHeight - 1);
    const float fx0 = float(block.x - gx0), fy0 = float(block.y - gy0);
    // The block's four depths, loaded before any pixel's filter: in the loop below each load stood after the
    // bound test that may end it, so the next pixel's load waited for the filter before it. A pixel past the
    // image's edge reads its clamped neighbour's depth and is skipped as before. On an H100 (2026-11-27,
    // fourth call, 3 rounds in one run) the pass went to 0.981 / 0.938 of its time at 1920x1080 / 3840x2160 in
    // gtao-half and 0.969 at 3840x2160 in the spatio-temporal target's frame (that frame 0.993, 0.1656 ->
    // 0.1644 ms), for 37 -> 40-42 registers. The same bits.
    const int xr = min(2 * block.x + 1, k.width - 1), yb = min(2 * block.y + 1, k.height - 1);
    const uint row0 = uint(2 * block.y) * uint(k.width), row1 = uint(yb) * uint(k.width);
    const float blockDepth[4] = float[4](depthPlane[row0 + uint(2 * block.x)], depthPlane[row0 + uint(xr)],
                                         depthPlane[row1 + uint(2 * block.x)], depthPlane[row1 + uint(xr)]);
    [[unroll]] for (int j = 0; j < 2; ++j) {
        const int y = 2 * block.y + j;
        if (y >= k.height) break;
        uint word = 0u;  // kPackedOut: the block's two pixels of row y
        [[unroll]] for (int i = 0; i < 2; ++i) {
            const int x = 2 * block.x + i;
            if (x >= k.width) break;
            float result[4];
            const float d = blockDepth[2 * j + i];
            const float fx = fx0 + 0.5 * float(i), fy = fy0 + 0.5 * float(j);
            // A surface pixel with only sky among its taps (rare: a feature thinner than the grid's spacing)
            // reads its own normal, which no other pixel does.
            if (!upsampleDepthAwareAt(gx0, gy0, x1, y1, fx, fy, d, k.depthSigma, result))
                setGridVector(result, normalize3(loadNormal(uint(y) * uint(k.width) + uint(x))));
            if (kPackedOut != 0) {
                word |= packUnorm16(result[0]) << (16 * i);
                continue;
            }
            const uint o = (uint(y) * uint(k.width) + uint(x)) * uint(kGridChannels);
            for (int c = 0; c < kGridChannels; ++c) outWords[o + uint(c)] = floatBitsToUint(result[c]);
        }
        if (kPackedOut != 0) outWords[uint(y) * uint((k.width + 1) / 2) + uint(block.x)] = word;
    }
}
