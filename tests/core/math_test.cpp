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

// The cofactor form holds where the inverse-transpose does not exist: a transform of rank 2 keeps the area of
// faces in the plane it does not squash, and their normals must follow (glTF allows scale [1, 1, 0]). A mirror
// still turns a normal the way the inverse-transpose does.
TEST(Math, NormalMatrixOfASquashAndOfAMirror) {
    const Mat4 rotate = Mat4::rotation(normalize(Vec3{1, 2, 3}), 0.7f);
    const Vec3 t1{1, 0.5f, 0}, t2{-0.25f, 1, 0};  // a face in z = 0
    for (const Mat4& m : {rotate * Mat4::scale({2, 0.5f, 0}), rotate * Mat4::scale({1, 1, 1e-30f}),
                          rotate * Mat4::scale({-1, 1, 1}), rotate * Mat4::scale({3, 3, 3})}) {
        const Vec3 placed = cross(transformVector(m, t1), transformVector(m, t2));
        const Vec3 nw = transformVector(normalMatrix(m), cross(t1, t2));
        ASSERT_GT(length(nw), 0.0f);
        EXPECT_NEAR(dot(normalize(nw), normalize(placed)), determinant3(m) < 0 ? -1.0f : 1.0f, 1e-5f);
    }
    // Rank 1 keeps no face's area: there is no normal to give, and the identity stands in.
    const Mat4 line = normalMatrix(Mat4::scale({1, 0, 0}));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_EQ(line.m[i][j], i == j ? 1.0f : 0.0f);
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
