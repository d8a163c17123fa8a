// The windows of the interleave's reconstruction (Jimenez et al. 2016, "Practical Realtime Strategies for
// Accurate Indirect Occlusion", §4.1: the depth-aware gather over the 4x4 pattern), shared by the C++
// reference (ssao::reconstructInterleaved, src/ssao/gtao_temporal.cpp) and the compute passes
// (temporal_filters.glsl), compiled as both C++ and GLSL, so both gather the same taps at the same weights.
//
// A window is named by its phase, an int that the passes take as a specialization constant:
//   -1    the 5x5 window, offsets -2..2, its outer ring at weight 1/2 and its corners at 1/4, so that each of
//         the pattern's 16 classes weighs the same;
//   0..3  a 4x4 window, every tap at weight 1 (one tap per class): offsets -2..1 in x where bit 0 of the
//         phase is 0, else -1..2, and likewise in y with bit 1. Averaged over the 4 phases, a tap's weight is
//         the 5x5 window's (GtaoTemporalSettings::alternatingWindow);
//   4..7  a 2x2 window, every tap at weight 1: offsets -1..0 in x where bit 0 of (phase - 4) is 0, else 0..1,
//         and likewise in y with bit 1. Each holds the pixel itself; averaged over the 4 phases, a tap's weight
//         is the 3x3 tent's (1 at the centre, 1/2 on the edges, 1/4 at the corners), and over the 6 rotations
//         of the history the taps meet every direction of the pattern (alternatingWindowSize 2).
#ifndef OBSCURA_RECONSTRUCT_WINDOW_H
#define OBSCURA_RECONSTRUCT_WINDOW_H

#ifdef __cplusplus
namespace obscura::ssao {
#define OBSCURA_FN inline constexpr
#else
#define OBSCURA_FN
#endif

// Taps along one side of the window of windowPhase (-1..7): 5, 4 or 2.
OBSCURA_FN int reconstructWindowSide(int windowPhase) { return windowPhase < 0 ? 5 : (windowPhase < 4 ? 4 : 2); }

// The first offset of the window along x (axisBit 0) or y (axisBit 1); the last is first + side - 1.
OBSCURA_FN int reconstructWindowFirst(int windowPhase, int axisBit) {
    if (windowPhase < 0) return -2;
    return -(reconstructWindowSide(windowPhase) / 2) + (((windowPhase & 3) >> axisBit) & 1);
}

// The spatial weight of the tap at offset (dx, dy) inside the window.
OBSCURA_FN float reconstructWindowWeight(int windowPhase, int dx, int dy) {
    if (windowPhase >= 0) return 1.0f;
    return (dx == -2 || dx == 2 ? 0.5f : 1.0f) * (dy == -2 || dy == 2 ? 0.5f : 1.0f);
}

#ifdef __cplusplus
static_assert(reconstructWindowFirst(-1, 0) == -2 && reconstructWindowSide(-1) == 5, "the 5x5 window");
static_assert(reconstructWindowFirst(3, 0) == -1 && reconstructWindowFirst(2, 1) == -1 &&
                  reconstructWindowFirst(0, 1) == -2 && reconstructWindowSide(3) == 4,
              "the 4x4 windows");
static_assert(reconstructWindowFirst(4, 0) == -1 && reconstructWindowFirst(5, 0) == 0 &&
                  reconstructWindowFirst(6, 1) == 0 && reconstructWindowFirst(5, 1) == -1 &&
                  reconstructWindowSide(7) == 2,
              "the 2x2 windows, each holding the pixel itself");
} // namespace obscura::ssao
#endif
#undef OBSCURA_FN
#endif
