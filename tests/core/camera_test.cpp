// Camera: pixel <-> view-space round trips and agreement with the projection matrix.
#include "obscura/camera.h"
#include "obscura/error.h"

#include <gtest/gtest.h>

using namespace obscura;

namespace {
Camera testCamera() {
    Camera c;
    c.position = {1, 2, 3};
    c.target = {-0.5f, 0.2f, -1};
    c.fovY = 50;
    c.width = 333;
    c.height = 197;
    return c;
}
} // namespace

TEST(Camera, PixelViewRoundTrip) {
    Camera c = testCamera();
    for (float py : {0.5f, 10.25f, 98.5f, 196.5f})
        for (float px : {0.5f, 100.75f, 332.5f})
            for (float d : {0.1f, 2.0f, 500.0f}) {
                Vec3 p = c.viewFromPixel(px, py, d);
                EXPECT_FLOAT_EQ(-p.z, d);
                float depth = 0;
                Vec2 back = c.pixelFromView(p, &depth);
                EXPECT_NEAR(back.x, px, 1e-3);
                EXPECT_NEAR(back.y, py, 1e-3);
                EXPECT_NEAR(depth, d, 1e-5f * d);
            }
}

// The affine form the screen-space kernels read is the same mapping as viewFromPixel (float rounding apart).
TEST(Camera, AffinePixelMappingMatchesViewFromPixel) {
    Camera c = testCamera();
    const Camera::PixelToView a = c.viewFromPixelAffine();
    for (float py : {0.5f, 98.5f, 196.5f})
        for (float px : {0.5f, 166.5f, 332.5f})
            for (float d : {0.1f, 2.0f, 500.0f}) {
                const Vec3 p = c.viewFromPixel(px, py, d);
                EXPECT_NEAR((px * a.mulX + a.addX) * d, p.x, 1e-5f * d);
                EXPECT_NEAR((py * a.mulY + a.addY) * d, p.y, 1e-5f * d);
            }
}

TEST(Camera, MatricesAreInverse) {
    Camera c = testCamera();
    Mat4 m = c.viewFromWorld() * c.worldFromView();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_NEAR(m.m[i][j], i == j ? 1.0f : 0.0f, 1e-5);
    // The camera sits at the view origin and looks down -Z at its target.
    Vec3 o = transformPoint(c.viewFromWorld(), c.position);
    EXPECT_NEAR(length(o), 0.0f, 1e-5);
    Vec3 t = transformPoint(c.viewFromWorld(), c.target);
    EXPECT_NEAR(t.x, 0.0f, 1e-5);
    EXPECT_NEAR(t.y, 0.0f, 1e-5);
    EXPECT_NEAR(t.z, -length(c.target - c.position), 1e-5);
}

TEST(Camera, ProjectionMatrixAgreesWithPixelMapping) {
    Camera c = testCamera();
    Vec3 p = c.viewFromPixel(40.5f, 150.5f, 3.0f);
    Mat4 clip = c.clipFromView();
    float x = clip.m[0][0] * p.x + clip.m[0][2] * p.z, y = clip.m[1][1] * p.y + clip.m[1][2] * p.z;
    float w = -p.z;
    EXPECT_NEAR((x / w + 1) * 0.5f * float(c.width), 40.5f, 1e-3);
    EXPECT_NEAR((1 - y / w) * 0.5f * float(c.height), 150.5f, 1e-3);
}

TEST(Camera, ValidateNamesTheProblem) {
    Camera c = testCamera();
    c.width = 0;
    try {
        c.validate();
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("image size"), std::string::npos) << e.what();
    }
    c = testCamera();
    c.fovY = 180;
    EXPECT_THROW(c.validate(), Error);
    // The narrowest field of view is taken, and projects a pixel there and back; one below it is refused by name.
    c = testCamera();
    c.fovY = kMinFovDegrees;
    c.validate();
    const Vec3 view = c.viewFromPixel(3.5f, 2.5f, 2.0f);
    float depth = 0.0f;
    const Vec2 pixel = c.pixelFromView(view, &depth);
    EXPECT_NEAR(pixel.x, 3.5f, 1e-2f);
    EXPECT_NEAR(pixel.y, 2.5f, 1e-2f);
    EXPECT_NEAR(depth, 2.0f, 1e-6f);
    for (const float tooNarrow : {0.5f * kMinFovDegrees, 1e-45f}) {
        c.fovY = tooNarrow;
        try {
            c.validate();
            ADD_FAILURE() << "fov " << tooNarrow << " taken";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("fov must be in [0.001, 180)"), std::string::npos) << e.what();
        }
    }
    c = testCamera();
    c.target = c.position;
    EXPECT_THROW(c.validate(), Error);
    // Position and target within kMaxCameraCoordinate of the origin, where Embree's rays stay valid.
    c = testCamera();
    c.position = {0, 0, kMaxCameraCoordinate};
    c.validate();
    c.position = {0, 0, 2 * kMaxCameraCoordinate};
    try {
        c.validate();
        ADD_FAILURE() << "a camera 2e13 m out taken";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "camera: position lies beyond 1e+13 m of the origin");
    }
    c = testCamera();
    c.target = {-3e13f, 0, 0};
    EXPECT_THROW(c.validate(), Error);
}

// A quarter turn about the vertical through the target, worked by hand: the offset from the target
// (1.5, 1.8, 4) goes to (z, y, -x) = (4, 1.8, -1.5) for a right-handed turn of +90 degrees about +Y.
TEST(Camera, TurnedAboutTargetRotatesThePositionAboutTheVertical) {
    const Camera c = testCamera();
    const Camera q = turnedAboutTarget(c, 0.5f * kPi);
    EXPECT_NEAR(q.position.x, -0.5f + 4.0f, 1e-5f);
    EXPECT_NEAR(q.position.y, 2.0f, 1e-5f);
    EXPECT_NEAR(q.position.z, -1.0f - 1.5f, 1e-5f);
    EXPECT_EQ(q.target.x, c.target.x);
    EXPECT_EQ(q.target.z, c.target.z);
    EXPECT_EQ(q.width, c.width);
    const Camera full = turnedAboutTarget(c, 2.0f * kPi);
    EXPECT_NEAR(full.position.x, c.position.x, 1e-5f);
    EXPECT_NEAR(full.position.z, c.position.z, 1e-5f);
    // No turn is the camera itself (frame 0 of render --ao gtao): in float, x 0.4 became 0.40000004, and a
    // camera at x 0.3 turned by 0 about a target 1e6 m away landed at 0.3125.
    Camera demo = c;
    demo.position = {0.4f, 2.0f, 5.5f};
    demo.target = {-0.2f, 0.7f, -1.0f};
    EXPECT_EQ(turnedAboutTarget(demo, 0.0f).position, demo.position);
    demo.position = {0.3f, 1.7f, 5.0f};
    demo.target = {1e6f, 0.0f, 0.0f};
    EXPECT_EQ(turnedAboutTarget(demo, 0.0f).position, demo.position);
    // A small turn about that far target: the offset's length is kept to float rounding of the result.
    const Camera turned = turnedAboutTarget(demo, 0.5f * kPi / 180.0f);
    const double before = std::hypot(double(demo.position.x) - 1e6, double(demo.position.z));
    const double after = std::hypot(double(turned.position.x) - 1e6, double(turned.position.z));
    EXPECT_NEAR(after, before, 0.07);  // half an ulp of 1e6 in float is 0.03
    // The up vector turns with the camera. Held fixed, an up of +X became parallel to the view a quarter turn
    // on, and the frame's camera was refused after the frames before it were rendered.
    Camera sideways = c;
    sideways.position = {0.0f, 1.0f, 1.5f};
    sideways.target = {0.0f, 1.0f, 0.0f};
    sideways.up = {1.0f, 0.0f, 0.0f};
    for (float turn : {0.25f, 0.5f, 1.0f, 1.5f}) {
        const Camera turnedSideways = turnedAboutTarget(sideways, turn * kPi);
        EXPECT_NEAR(dot(normalize(turnedSideways.target - turnedSideways.position), turnedSideways.up), 0.0f, 1e-6f) << turn;
        EXPECT_NEAR(length(turnedSideways.up), 1.0f, 1e-6f) << turn;
        EXPECT_NO_THROW(turnedSideways.validate()) << turn;
    }
    EXPECT_EQ(turnedAboutTarget(c, 1.0f).up, c.up);  // a vertical up, to the bit
}

// An infinite far plane passed validate; clipFromView then held NaN (inf / -inf) and the camera file
// written for it said "far": null, which readCameraJson refuses.
TEST(Camera, InfiniteFarIsRefused) {
    Camera c;
    c.farZ = INFINITY;
    EXPECT_THROW(c.validate(), Error);
}

// 2.0f * far * near overflowed float for a finite far of 3e38: clipFromView[2][3] was -inf.
TEST(Camera, ClipFromViewIsFiniteForAValidCamera) {
    Camera c;
    c.farZ = 3e38f;
    ASSERT_NO_THROW(c.validate());
    const Mat4 p = c.clipFromView();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_TRUE(std::isfinite(p.m[i][j])) << i << "," << j;
    EXPECT_NEAR(p.m[2][3], -2.0f * c.nearZ, 1e-6f);
}

// An up hint is a direction; its length overflowing or underflowing float made it (0, 0, 0).
TEST(Camera, UpHintOfAnyMagnitudeIsADirection) {
    for (float s : {1e20f, 1e-25f}) {
        Camera c;
        c.up = {0, s, 0};
        EXPECT_NO_THROW(c.validate()) << s;
        Camera unit;
        const Mat4 a = c.viewFromWorld(), b = unit.viewFromWorld();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) EXPECT_NEAR(a.m[i][j], b.m[i][j], 1e-6f) << s;
    }
}
