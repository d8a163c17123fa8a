// The separable blur's tap loop for one centre, shared by its passes (bilateral_separable.comp) and by the
// Alchemy pass that blurs its own rows (alchemy_blur_row.comp). The includer declares the shared arrays
// tile (depth and input of each slot) and tileLogSpatial, tileIndex(line, i), the specialization constants
// kUseNormal and kUnrolled (layouts.h, kBilateralSpecUnrolled) and loadNormal (normal_plane.glsl), which only
// a kUseNormal of 1 calls.

// kBilateralUnrolledRadius's taps unrolled, for a centre whose taps all lie inside the image, `step` slots
// apart: called with the steps 1 and kBilateralVerticalTileX as constants, so that each tap's slot is the
// first's plus a constant and the spatial weight's slot a constant: no loop counter, compare, branch or index
// arithmetic per tap. The same operations in the same order as the loop below.
void bilateralTapsUnrolled(int first, const int step, float d, float c, inout float sum, inout float wsum) {
    [[unroll]] for (int i = 0; i <= 2 * kBilateralUnrolledRadius; ++i) {
        const vec2 tap = tile[first + i * step];
        const float dd = tap.x - d;
        const float w = exp2(tileLogSpatial[i] - dd * dd * c);
        sum += w * tap.y;
        wsum += w;
    }
}

// The centre at tile position `centre` of line `line`, with depth d, c = depthScale / d^2, normal n and
// index x in the normal plane; taps t in [tFirst, tLast] (those inside the image), `stride` pixels apart
// there. Returns the blurred value, or the centre's own input where nothing weighs.
float bilateralTaps(int line, int centre, int radius, int tFirst, int tLast, float d, float c, vec3 n, uint x,
                    int stride) {
    float sum = 0.0, wsum = 0.0;
    // tileIndex is linear in its position for every includer: each tap's slot is the last one's plus a step
    // that the loop does not recompute (the separable pass's tileIndex chooses between the axes per call).
    // On an H200 (2026-11-26, 3 rounds in one run) that took the separable blur's two 13-tap dispatches to
    // 0.960 of their time at 1920x1080 and 3840x2160 (0.0497 -> 0.0477 ms at 1920x1080), the 5-tap grid
    // blur of gtao-half to 0.985, alchemy-fused's column pass to 0.96; the same bits.
    const int step = tileIndex(line, centre + 1) - tileIndex(line, centre);
    int slot = tileIndex(line, centre + tFirst);
    // The unrolled taps: on an H100 (2026-11-27, 3 rounds in one run) the separable blur's two 13-tap
    // dispatches went to 0.93 / 0.91 of their time at 1920x1080 / 3840x2160 (0.0478 -> 0.0446 ms at
    // 1920x1080), alchemy-fused's column pass to 0.92; the same bits. Compiled into every variant, they took
    // the 5-tap blur of gtao-half to 1.05 / 1.07 through the loop it still ran: kUnrolled leaves them out of
    // it (the host sets it where the radius is kBilateralUnrolledRadius and the normal weight is off,
    // bilateralSpecUnrolled). The rows of alchemy_blur_row.comp, which set it themselves, gained nothing
    // (1.009) while 12 of their invocations evaluated a second pixel, and 0.986 / 0.975 once none did.
    const bool unrolled = kUnrolled != 0 && kUseNormal == 0 && radius == kBilateralUnrolledRadius &&
                          tFirst == -radius && tLast == radius;
    if (unrolled && step == 1)
        bilateralTapsUnrolled(slot, 1, d, c, sum, wsum);
    else if (unrolled && step == kBilateralVerticalTileX)
        bilateralTapsUnrolled(slot, kBilateralVerticalTileX, d, c, sum, wsum);
    else {
        for (int t = tFirst; t <= tLast; ++t, slot += step) {
            const vec2 tap = tile[slot];
            const float dd = tap.x - d;
            float w = exp2(tileLogSpatial[t + radius] - dd * dd * c);
            if (kUseNormal != 0) {
                const uint o = uint(int(x) + t * stride);
                w *= max(0.0, dot(n, loadNormal(o)));
            }
            sum += w * tap.y;
            wsum += w;
        }
    }
    // A centre on sky or with no weight (impossible for a surface: its own tap counts) keeps its input.
    const bool keep = d < 1e30 && wsum > 0.0;
    return keep ? sum / wsum : tile[tileIndex(line, centre)].y;
}
