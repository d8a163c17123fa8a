// obscura/math.h's vector functions as the shaders compute them: written out as the C++ ones compute them
// (no dot(), length() or normalize(), whose rounding GLSL leaves to the driver), so that the GPU reference
// passes agree with the CPU's to the bit where the device rounds +, * and / as the CPU does. Included by every
// shader that needs one of them, once (the guard).
#ifndef OBSCURA_GPU_VECTOR_MATH_GLSL
#define OBSCURA_GPU_VECTOR_MATH_GLSL

float dot3(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
vec3 cross3(vec3 a, vec3 b) { return vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x); }
float length3(vec3 a) { return sqrt(dot3(a, a)); }
// The zero vector for a zero input rather than NaNs.
vec3 normalize3(vec3 a) {
    const float l = length3(a);
    return l > 0.0 ? a / l : vec3(0.0);
}

#endif
