// The separable blur's tap loop for one centre, shared by its passes (bilateral_separable.comp) and by the
// Alchemy pass that blurs its own rows (alchemy_blur_row.comp). The includer declares the shared arrays
// tile (depth and input of each slot) and tileLogSpatial, tileIndex(line, i), the specialization constant
// kUseNormal and loadNormal (normal_plane.glsl), which only a kUseNormal of 1 calls.

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
    // A centre on sky or with no weight (impossible for a surface: its own tap counts) keeps its input.
    const bool keep = d < 1e30 && wsum > 0.0;
    return keep ? sum / wsum : tile[tileIndex(line, centre)].y;
}
