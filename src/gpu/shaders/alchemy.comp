// Alchemy screen-space ambient obscurance as a compute pass: McGuire, Osman, Bukowski, Hennessy 2011, "The
// Alchemy Screen-Space Ambient Obscurance Algorithm" (HPG 2011), eq. 10, with the spiral and the formulation
// of "Where Corners Stay Dark". One invocation per output pixel.
//
// alchemyPixel (alchemy_pixel.glsl) is src/ssao/alchemy.cpp's alchemyPixel line for line, with the same
// names; read them side by side. The differences are GLSL's: the G-buffer planes are the buffers `depth` and
// `normalWords` (C++: in.depth, in.normal; read through loadNormal, 3 floats or, with the specialization
// constant kAlchemySpecPackedNormals, an octahedral word per pixel), spiral.at(count, cls) is the index
// alchemySpiralAt(count, cls) into `spiral`, and std::nextafter is nextUp. The constants are the push
// constants `k`, filled by ssao::alchemyConstants().
// On lavapipe the result has alchemyPixel's bits except where pow rounds differently (tests/gpu measure it);
// a driver that fuses multiply-adds or divides less exactly agrees to rounding instead.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "obscura/alchemy_constants.h"
#include "layouts.h"

layout(local_size_x = kAlchemyWorkgroupX, local_size_y = kAlchemyWorkgroupY, local_size_z = 1) in;

layout(push_constant, std430) uniform Constants { AlchemyConstants k; };
layout(std430, binding = kAlchemyBindingDepth) readonly buffer DepthPlane { float depth[]; };
layout(constant_id = kAlchemySpecPackedNormals) const int kPackedNormals = 0;
layout(std430, binding = kAlchemyBindingNormal) readonly buffer NormalPlane { uint normalWords[]; };
// The table as pairs: a sample's two offsets in one 8-byte load (every count's run starts at an even float).
layout(std430, binding = kAlchemyBindingSpiral) readonly buffer Spiral { vec2 spiral[]; };
layout(std430, binding = kAlchemyBindingOutput) writeonly buffer Obscurance { float ao[]; };

#include "alchemy_pixel.glsl"

void main() {
    const int outWidth = k.width - 2 * k.guardBand, outHeight = k.height - 2 * k.guardBand;
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= outWidth || p.y >= outHeight) return;
    ao[uint(p.y) * uint(outWidth) + uint(p.x)] = alchemyPixel(p.x + k.guardBand, p.y + k.guardBand);
}
