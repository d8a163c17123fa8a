// The G-buffer's view normals as the passes read them: 3 floats per pixel, or, with the including shader's
// packed-normals specialization constant, one word per pixel, the octahedral code of obscura/history_packing.h
// (two snorm16, within 6.5e-5 rad of the vector), as an engine's G-buffer keeps its normals compactly. A
// pass that reads the normals at every other pixel (the half-resolution grid) touches every cache line of
// the rows it reads either way, so the packed plane moves a third of the float plane's bytes.
//
// The including shader declares, before the #include, `const int kPackedNormals` (0 or 1) and the plane as
// 32-bit words, `normalWords`, so that one binding serves both layouts; the float path reads the floats'
// bits back unchanged.
#ifndef OBSCURA_GPU_NORMAL_PLANE_GLSL
#define OBSCURA_GPU_NORMAL_PLANE_GLSL

#include "vector_math.glsl"  // normalize3, which the decoding ends with
#include "obscura/history_packing.h"

vec3 loadNormal(uint pixel) {
    if (kPackedNormals != 0) return unpackOctahedral(normalWords[pixel]);
    const uint i = 3 * pixel;
    return vec3(uintBitsToFloat(normalWords[i]), uintBitsToFloat(normalWords[i + 1]),
                uintBitsToFloat(normalWords[i + 2]));
}

#endif
