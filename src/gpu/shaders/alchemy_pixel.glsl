// alchemyPixel, src/ssao/alchemy.cpp's kernel for one pixel, for the shaders that evaluate it (alchemy.comp
// and alchemy_blur_row.comp). The includer declares what it reads: the push constants `k` (an
// AlchemyConstants), the storage buffers `depth`, `normalWords` and `spiral` of alchemy.comp's layout, and
// kPackedNormals (normal_plane.glsl reads the normals); with ALCHEMY_SPIRAL_SHARED defined, it also calls
// loadSpiralShared (below).

bool isSkyDepth(float d) { return !(d < 1e30); }

#include "normal_plane.glsl"

int floorToInt(float v) { return int(floor(v)); }

// The next float above a positive finite v (std::nextafter(v, INFINITY)).
float nextUp(float v) { return uintBitsToFloat(floatBitsToUint(v) + 1u); }

// SpiralTable::at: the table holds, for each count in [minSamples, samples] and each of the 16 classes,
// 2 count floats; sum over c in [minSamples, count) of 16 * 2c = 16 (count - minSamples)(count + minSamples - 1).
int alchemySpiralAt(int count, int cls) {
    return kAlchemyPixelClasses * (count - k.minSamples) * (count + k.minSamples - 1) + 2 * cls * count;
}

// One sample of alchemyPixel at spiral offset `offset`, added to sum; none for a sample outside the image.
// `centre` is the pixel's own index in `depth`: a sample outside the image reads the centre's depth instead of
// branching around its load, and adds nothing, so that no branch stands between the samples' loads (the unrolled
// run's loads can then be issued ahead of the tests too). On an H100 (2026-11-27, third call, 3 rounds in one
// run) the estimator went to 0.945 / 0.984 of its time at 1920x1080 / 3840x2160 and the fused rows to 0.984 /
// 0.988 (alchemy-fused's frame 0.989 / 0.991), for 28 -> 32 registers in alchemy.comp; the same bits.
void alchemySample(vec2 offset, float fx, float fy, float radiusPixels, float cx, float cy, float cz, float nx,
                   float ny, float nz, float shift, float radius2, bool paper, uint centre, inout float sum) {
    const int sx = floorToInt(fx + offset.x * radiusPixels);
    const int sy = floorToInt(fy + offset.y * radiusPixels);
    const bool seen = uint(sx) < uint(k.width) && uint(sy) < uint(k.height);  // unseen: empty
    // A sky sample (+inf) becomes a point 1e18 m away: finite arithmetic, and far outside the radius.
    const float ds = min(depth[seen ? uint(sy) * uint(k.width) + uint(sx) : centre], 1e18);
    const float vx = ((float(sx) + 0.5) * k.viewScaleX + k.viewOffsetX) * ds - cx;
    const float vy = ((float(sy) + 0.5) * k.viewScaleY + k.viewOffsetY) * ds - cy;
    const float vz = -ds - cz;
    const float vv = vx * vx + vy * vy + vz * vz;
    const float vn = max(0.0, vx * nx + vy * ny + vz * nz + shift);
    const float term = vn / (paper ? vv + k.denominator : max(k.denominator, vv));
    // Heaviside term as a 0/1 factor, as on the CPU.
    if (seen) sum += term * float(vv < radius2);
}

// A pixel's samples are a run of kAlchemyUnrolledSamples, unrolled (alchemyUnrolledSamples), or a loop for any
// other count. The run is split so that each change tried on it (bench/gpu-candidates) edits one place: the
// sample (alchemySample), its spiral offset (alchemyUnrolledOffset) or the run's call (alchemyPixel); their
// patches then apply together, and a combination of them is their patches, not a copy of their hunks.
const int kAlchemyUnrolledSamples = 12;

#ifdef ALCHEMY_SPIRAL_SHARED
// The spiral table's run for kAlchemyUnrolledSamples samples, every class, in shared memory, for an includer
// that defines ALCHEMY_SPIRAL_SHARED (and enables GL_KHR_shader_subgroup_basic): the unrolled samples read
// their offsets there instead of from the storage buffer, 12 loads per pixel that no longer take the global
// load path beside the depth gathers. The includer calls loadSpiralShared from every invocation of the
// workgroup, in uniform control flow, before its first alchemyPixel. The first subgroup loads the run: the
// workgroup's size is not known here (the host may run a module whose size was changed, and gl_WorkGroupSize
// would be the compiled one).
// On an H100 (2026-11-27, two calls, 3 rounds in one run each) the fused rows (alchemy_blur_row.comp) went to
// 0.980 / 0.985 and 0.987 / 0.986 of their time at 1920x1080 / 3840x2160, alchemy-fused's frame to 0.986 /
// 0.989 and 0.992 / 0.990 (0.0805 -> 0.0799 ms at 1920x1080 in the second); but the estimator in its own pass
// (alchemy.comp) to 1.021 / 1.011 and 1.026 / 1.017, so alchemy.comp reads the buffer. The same bits.
shared vec2 spiralShared[kAlchemyPixelClasses * kAlchemyUnrolledSamples];
void loadSpiralShared() {
    // The run exists in the table when its count lies in [minSamples, samples] (the push constants, uniform).
    if (gl_SubgroupID == 0 && k.minSamples <= kAlchemyUnrolledSamples && kAlchemyUnrolledSamples <= k.samples) {
        const uint base = uint(alchemySpiralAt(kAlchemyUnrolledSamples, 0) / 2);
        for (uint i = gl_SubgroupInvocationID; i < uint(kAlchemyPixelClasses * kAlchemyUnrolledSamples);
             i += gl_SubgroupSize)
            spiralShared[i] = spiral[base + i];
    }
    barrier();
}
#endif

// The spiral offset of the unrolled run's sample i, for the pixel of class cls whose run starts at float
// `offsets` of the table.
vec2 alchemyUnrolledOffset(int offsets, int cls, int i) {
#ifdef ALCHEMY_SPIRAL_SHARED
    return spiralShared[cls * kAlchemyUnrolledSamples + i];
#else
    return spiral[offsets / 2 + i];
#endif
}

// The paper's 12 samples (every pixel's count with the level of detail off, the default) unrolled: the count is
// a push constant, so the loop was a loop, each sample's spiral and depth loads issued after the sample before
// had been summed unless the compiler reordered them; unrolled, the 12 pairs of loads can be issued ahead. On an
// H100 (2026-11-27, 3 rounds in one run) the estimator went to 0.972 / 0.982 of its time at 1920x1080 /
// 3840x2160 and the fused rows (alchemy_blur_row.comp) to 0.952 / 0.942: the Alchemy target's frame from 0.0876
// to 0.0846 ms, for one more register (28; 32 with the branchless samples above). The same operations in
// the same order.
void alchemyUnrolledSamples(int offsets, int cls, float fx, float fy, float radiusPixels, float cx, float cy,
                            float cz, float nx, float ny, float nz, float shift, float radius2, bool paper,
                            uint centre, inout float sum) {
    [[unroll]] for (int i = 0; i < kAlchemyUnrolledSamples; ++i)
        alchemySample(alchemyUnrolledOffset(offsets, cls, i), fx, fy, radiusPixels, cx, cy, cz, nx, ny, nz, shift,
                      radius2, paper, centre, sum);
}

float alchemyPixel(int x, int y) {
    const uint c = uint(y) * uint(k.width) + uint(x);
    const float d = depth[c];
    if (isSkyDepth(d)) return 1.0;
    const float fx = float(x) + 0.5, fy = float(y) + 0.5;
    const float cx = (fx * k.viewScaleX + k.viewOffsetX) * d, cy = (fy * k.viewScaleY + k.viewOffsetY) * d, cz = -d;
    const vec3 n = loadNormal(c);
    const float nx = n.x, ny = n.y, nz = n.z;
    const float radiusPixels = min(k.radius * k.focalPixels / d, k.maxRadiusPixels);
    int count = k.samples;
    if (k.lodRadiusPixels > 0.0 && radiusPixels < k.lodRadiusPixels)
        count = clamp(int(ceil(float(k.samples) * radiusPixels / k.lodRadiusPixels)), k.minSamples, k.samples);
    const int cls = (y % kAlchemyClassTile) * kAlchemyClassTile + x % kAlchemyClassTile;
    const int offsets = alchemySpiralAt(count, cls);
    // Paper: + z_C beta with z_C < 0; chapter: - bias. Both are one constant per pixel.
    const float shift = k.formulation == kAlchemyPaper ? cz * k.bias : -k.bias;
    // The paper drops samples at |v| >= r, the chapter's step() keeps |v| = r: one ulp of r^2 apart.
    const float radius2 = k.formulation == kAlchemyPaper ? k.radius2 : nextUp(k.radius2);
    const bool paper = k.formulation == kAlchemyPaper;
    float sum = 0.0;
    // The formulation is a push constant: chosen once per pixel here, each unrolled copy has its own
    // denominator as a constant instead of both and a select per sample. On an H100 (2026-11-27, fourth call,
    // 3 rounds in one run), with the branchless samples above, the fused rows went to 0.964 / 0.967 of their time
    // at 1920x1080 / 3840x2160 and alchemy-fused's frame to 0.974 / 0.976 (0.0830 -> 0.0809 ms at 1080p); the
    // estimator's own pass (alchemy.comp) moved within the noise (0.993 / 0.997), the registers not at all.
    // Alone, before the branchless samples, it gave 0.996 / 0.994. alchemy.comp's SPIR-V grows from 26.4 to
    // 39.7 kB (glslc -O, 2026-11-27). The same bits.
    if (count == kAlchemyUnrolledSamples && paper) {
        alchemyUnrolledSamples(offsets, cls, fx, fy, radiusPixels, cx, cy, cz, nx, ny, nz, shift, radius2, true, c,
                               sum);
    } else if (count == kAlchemyUnrolledSamples) {
        alchemyUnrolledSamples(offsets, cls, fx, fy, radiusPixels, cx, cy, cz, nx, ny, nz, shift, radius2, false, c,
                               sum);
    } else {
        for (int i = 0; i < count; ++i)
            alchemySample(spiral[offsets / 2 + i], fx, fy, radiusPixels, cx, cy, cz, nx, ny, nz, shift, radius2,
                          paper, c, sum);
    }
    const float a = max(0.0, 1.0 - k.intensity / float(count) * sum);
    return k.contrast == 1.0 ? a : pow(a, k.contrast);
}
