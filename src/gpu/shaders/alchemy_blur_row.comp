// Alchemy ambient obscurance (McGuire et al. 2011, eq. 10) and the horizontal pass of its separable
// cross-bilateral blur (Fig. 6) in one dispatch: each workgroup evaluates a row of output pixels, radius
// more on each side, into shared memory, and blurs them there. The raw AO never goes through memory, and
// the frame has one dispatch and one barrier fewer than alchemy.comp followed by both passes of
// bilateral_separable.comp; its vertical pass follows this one. The apron is evaluated twice, by this
// workgroup and its neighbour: 2 radius / (256 - 2 radius) more estimator work (5% at radius 6).
// Each invocation evaluates one pixel and the workgroup blurs the middle 256 - 2 radius of them. Before,
// 2 radius invocations evaluated a second pixel (the apron) while the other 244 waited at the barrier: on an
// H100 (2026-11-27, docs/PERFORMANCE.md) this took the rows from 0.0747 to 0.0637 ms at 1920x1080 (0.853)
// and the fused frame from 0.1003 to 0.0894 ms (0.891); at 3840x2160 0.904 and 0.927. The same bits.
//
// The estimator is alchemy.comp's (alchemy_pixel.glsl) and the taps are bilateral_separable.comp's
// (bilateral_taps.glsl), on the same values in the same order, so the result has the same bits as the two
// dispatches it replaces wherever the compiler rounds both alike (lavapipe: tests/gpu).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_basic : require

#include "obscura/alchemy_constants.h"
#include "layouts.h"

// A row of kRowTile invocations (the host reads the size back from the module: alchemy_pass.cpp).
const int kRowTile = kBilateralHorizontalTileX;
layout(local_size_x = kRowTile, local_size_y = 1, local_size_z = 1) in;

// The estimator's constants `k` (alchemy_pixel.glsl reads them by that name), then the blur's `b` on the
// output grid: width and height are the output's, axis 0, no normal weight.
layout(push_constant, std430) uniform Constants {
    AlchemyConstants k;
    BilateralConstants b;
};
layout(std430, binding = kAlchemyBindingDepth) readonly buffer DepthPlane { float depth[]; };
layout(constant_id = kAlchemySpecPackedNormals) const int kPackedNormals = 0;
layout(std430, binding = kAlchemyBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };
layout(std430, binding = kAlchemyBindingSpiral) readonly buffer Spiral { vec2 spiral[]; };  // as alchemy.comp's
layout(std430, binding = kAlchemyBlurBindingLogSpatial) readonly buffer LogSpatial { float logSpatial[]; };
layout(std430, binding = kAlchemyBlurBindingOutput) writeonly buffer Output { float aoOut[]; };

// The unrolled samples read their spiral offsets from shared memory in this shader only (alchemy_pixel.glsl).
#define ALCHEMY_SPIRAL_SHARED
#include "alchemy_pixel.glsl"

const int kUseNormal = 0;  // the separable blur's default (bilateral_taps.glsl)
// The unrolled taps (bilateral_taps.glsl) at the default radius: once every invocation evaluates one pixel and
// the whole workgroup reaches the taps together, they took the rows to 0.986 / 0.975 of their time at
// 1920x1080 / 3840x2160 on an H100 (2026-11-27, third call; the frame 0.990 / 0.982), the same registers.
const int kUnrolled = 1;
const int kSlots = kRowTile;
shared vec2 tile[kSlots];  // depth, input
shared float tileLogSpatial[2 * kBilateralMaxRadius + 1];

int tileIndex(int line, int i) { return i; }

#include "bilateral_taps.glsl"

void main() {
    const int invocation = int(gl_LocalInvocationID.x);
    const int y = int(gl_WorkGroupID.y);  // the output row; the host dispatches b.height rows
    // Each invocation evaluates one pixel, and the workgroup blurs the middle tile - 2 radius pixels of its
    // tile, a segment: no invocation evaluates a second pixel of the apron while the rest of its workgroup
    // waits at the barrier. The host dispatches one workgroup per segment (alchemyBlurRowGroupsX, layouts.h);
    // a workgroup still takes every segment from its index on, in steps of the workgroups' count, so that a
    // host dispatching fewer gets the whole row.
    const int outputs = kRowTile - 2 * b.radius;
    const int segments = (b.width + outputs - 1) / outputs;
    for (int i = invocation; i <= 2 * b.radius; i += kRowTile)
        tileLogSpatial[i] = logSpatial[i];
    loadSpiralShared();
    for (int s = int(gl_WorkGroupID.x); s < segments; s += int(gl_NumWorkGroups.x)) {
        // Slot i holds pixel s outputs - radius + i. Those outside the image stay unwritten: the tap loop
        // never reads them (tFirst, tLast below), as the blur skips taps outside the image.
        // Output pixel (a, y) is pixel (a + guardBand, y + guardBand) of the guard-banded buffers.
        const int a = s * outputs - b.radius + invocation, ga = a + k.guardBand, gy = y + k.guardBand;
        if (a >= 0 && a < b.width)
            tile[invocation] = vec2(depth[uint(gy) * uint(k.width) + uint(ga)], alchemyPixel(ga, gy));
        barrier();
        const int x = s * outputs + invocation;
        if (invocation < outputs && x < b.width) {
            const int centre = invocation + b.radius;
            const float d = tile[centre].x;
            const float c = b.depthScale / (d * d);  // 0 on sky: its output is its input anyway
            const int tFirst = max(-b.radius, -x), tLast = min(b.radius, b.width - 1 - x);
            const uint o = uint(y) * uint(b.width) + uint(x);
            aoOut[o] = bilateralTaps(0, centre, b.radius, tFirst, tLast, d, c, vec3(0.0), o, 1);
        }
        // The taps have read the tile before the next segment writes it.
        if (s + int(gl_NumWorkGroups.x) < segments) barrier();
    }
}
