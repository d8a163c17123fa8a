// The packed history words of spatio-temporal GTAO (obscura/history_packing.h): exact where the format is
// exact, within its step elsewhere, and the octahedral map over the whole sphere, folds and axes included.
#include "obscura/history_packing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace obscura::ssao {
namespace {

TEST(HistoryPacking, ScaleConstantsAreTheNearestFloats) {
    EXPECT_EQ(packInverse65535(), 1.0f / 65535.0f);
    EXPECT_EQ(packInverse32767(), 1.0f / 32767.0f);
}

TEST(HistoryPacking, VisibilityAndLength) {
    // Ends and whole frames are exact; the length keeps 1/32 frame.
    for (float v : {0.0f, 1.0f})
        for (float frames : {1.0f, 2.0f, 24.0f, 1024.0f}) {
            const std::uint32_t w = packVisibilityLength(v, frames);
            EXPECT_EQ(unpackVisibility(w), v);
            EXPECT_EQ(unpackLength(w), frames);
        }
    EXPECT_EQ(unpackLength(packVisibilityLength(0.5f, 3.75f)), 3.75f);
    EXPECT_NEAR(unpackLength(packVisibilityLength(0.5f, 3.7f)), 3.7f, 1.0 / 64 + 1e-6);
    // Visibility to the nearest 1/65535, clamped to [0, 1].
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double worst = 0;
    for (int i = 0; i < 100000; ++i) {
        const float v = u(rng);
        worst = std::max(worst, std::fabs(double(unpackVisibility(packVisibilityLength(v, 1.0f))) - double(v)));
    }
    EXPECT_LE(worst, 0.5 / 65535 + 1e-7);
    EXPECT_GT(worst, 0.4 / 65535);  // the step is really 1/65535, not finer
    EXPECT_EQ(unpackVisibility(packVisibilityLength(-0.5f, 1.0f)), 0.0f);
    EXPECT_EQ(unpackVisibility(packVisibilityLength(1.5f, 1.0f)), 1.0f);
}

TEST(HistoryPacking, Snorm16EndsAndZeroAreExact) {
    for (float x : {-1.0f, 0.0f, 1.0f}) EXPECT_EQ(unpackSnorm16(packSnorm16(x)), x);
    EXPECT_EQ(unpackSnorm16(packSnorm16(-3.0f)), -1.0f);
    EXPECT_EQ(unpackSnorm16(packSnorm16(3.0f)), 1.0f);
}

// A NaN (a corrupt normal or visibility that reached the packing) clamps to an end instead of going through
// a float-to-int conversion of NaN, which C++ leaves undefined; so do the infinities.
TEST(HistoryPacking, NanAndInfinitiesClampToAnEnd) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(packUnorm16(nan), 0u);
    EXPECT_EQ(packSnorm16(nan), packSnorm16(-1.0f));
    EXPECT_EQ(packUnorm16(inf), 65535u);
    EXPECT_EQ(packUnorm16(-inf), 0u);
    EXPECT_EQ(packSnorm16(inf), packSnorm16(1.0f));
    EXPECT_EQ(packSnorm16(-inf), packSnorm16(-1.0f));
    // A NaN normal packs to some direction of the unit sphere, never to an out-of-range code.
    const Vec3 n = unpackOctahedral(packOctahedral(Vec3(nan, 0.0f, 1.0f)));
    EXPECT_NEAR(length(n), 1.0f, 1e-4f);
}

TEST(HistoryPacking, OctahedralRoundTripOverTheSphere) {
    // The six axes (both folds' edges) come back exactly.
    for (const Vec3 axis : {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)}) {
        const Vec3 r = unpackOctahedral(packOctahedral(axis));
        EXPECT_EQ(r.x, axis.x);
        EXPECT_EQ(r.y, axis.y);
        EXPECT_EQ(r.z, axis.z);
    }
    // Uniform directions: unit length out, and within the grid's angular step (two snorm16 over a square
    // of side 2 that maps to the sphere with at most about 2.3 times stretch: 2.3 / 32767 rad at worst).
    std::mt19937 rng(11);
    std::normal_distribution<float> g;
    double worstAngle = 0, worstLength = 0;
    int lower = 0;
    for (int i = 0; i < 200000; ++i) {
        const Vec3 n = normalize(Vec3(g(rng), g(rng), g(rng)));
        lower += n.z < 0;
        const Vec3 r = unpackOctahedral(packOctahedral(n));
        worstLength = std::max(worstLength, std::fabs(double(length(r)) - 1.0));
        // The chord in double: acos of a float dot product cannot resolve angles this small.
        const double dx = double(n.x) - double(r.x), dy = double(n.y) - double(r.y), dz = double(n.z) - double(r.z);
        worstAngle = std::max(worstAngle, 2.0 * std::asin(0.5 * std::sqrt(dx * dx + dy * dy + dz * dz)));
    }
    std::printf("[ measured ] octahedral snorm16: worst angle %.3g rad, worst length error %.3g\n", worstAngle,
                worstLength);
    EXPECT_GT(lower, 90000);  // the fold is exercised
    EXPECT_LE(worstLength, 1e-6);
    EXPECT_LE(worstAngle, 2.3 / 32767);
    EXPECT_GT(worstAngle, 0.2 / 32767);  // really quantized
    // The zero vector (sky) packs as +z.
    const Vec3 sky = unpackOctahedral(packOctahedral(Vec3(0, 0, 0)));
    EXPECT_EQ(sky.z, 1.0f);
}

} // namespace
} // namespace obscura::ssao
