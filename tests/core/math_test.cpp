// Matrix helpers: inverse, normal matrix under non-uniform scale and mirroring.
#include "obscura/math.h"
#include "obscura/statistics.h"

#include <gtest/gtest.h>

using namespace obscura;

TEST(Math, InverseOfComposedTransform) {
    Mat4 m = Mat4::translation({1, -2, 3}) * Mat4::rotation({1, 1, 0}, 0.7f) * Mat4::scale({2, 0.5f, 3});
    Mat4 inv;
    ASSERT_TRUE(invert(m, inv));
    Mat4 id = m * inv;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_NEAR(id.m[i][j], i == j ? 1.0f : 0.0f, 1e-5);
    Mat4 zero = Mat4::scale({0, 1, 1});
    EXPECT_FALSE(invert(zero, inv));
}

TEST(Math, NormalMatrixKeepsNormalsPerpendicular) {
    Mat4 m = Mat4::rotation({0, 0, 1}, 0.3f) * Mat4::scale({4, 1, 0.25f});
    Vec3 t1{1, 1, 0}, t2{0, 1, 1};
    Vec3 n = cross(t1, t2);
    Vec3 nw = transformVector(normalMatrix(m), n);
    EXPECT_NEAR(dot(nw, transformVector(m, t1)), 0.0f, 1e-5);
    EXPECT_NEAR(dot(nw, transformVector(m, t2)), 0.0f, 1e-5);
    EXPECT_LT(determinant3(Mat4::scale({-1, 1, 1})), 0.0f);
}

TEST(Math, ColumnMajorMatchesGltf) {
    // glTF stores a translation in elements 12..14.
    float v[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
    Vec3 p = transformPoint(Mat4::fromColumnMajor(v), {1, 1, 1});
    EXPECT_EQ(p, (Vec3{6, 7, 8}));
}

// The benches' median: an even count takes the mean of the two middle values (the CPU benches took the upper
// one, so 2 repeats of 10 and 40 ms gave 40).
TEST(Statistics, OddAndEvenCounts) {
    EXPECT_EQ(median({}), 0.0);
    EXPECT_EQ(median({3.0}), 3.0);
    EXPECT_EQ(median({40.0, 10.0}), 25.0);
    EXPECT_EQ(median({40.0, 10.0, 40.0, 10.0}), 25.0);
    EXPECT_EQ(median({5.0, 1.0, 9.0}), 5.0);
}
