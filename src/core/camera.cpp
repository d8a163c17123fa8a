// Perspective camera: the pixel <-> view-space mapping (conventions in camera.h).
#include "obscura/camera.h"

#include "obscura/error.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace obscura {

namespace {
// The view axes in world space: x right, y up, z backwards (the camera looks down -z).
// up over its largest component: a hint of (0, 1e20, 0) or (0, 1e-25, 0) is a direction, but its squared length
// overflows or underflows float and normalize() made it (0, 0, 0).
Vec3 upDirection(Vec3 up) {
    const float m = maxAbsComponent(up);
    return m > 0.0f ? normalize(up / m) : Vec3{};
}

std::array<Vec3, 3> viewAxes(const Camera& c) {
    Vec3 back = normalize(c.position - c.target);
    Vec3 right = normalize(cross(upDirection(c.up), back));
    return {right, cross(back, right), back};
}
} // namespace

void Camera::validate() const {
    if (!isFinite(position)) fail("camera", "position is not finite");
    if (!isFinite(target)) fail("camera", "target is not finite");
    for (const auto& [name, p] : {std::pair<const char*, Vec3>{"position", position}, {"target", target}})
        if (maxAbsComponent(p) > kMaxCameraCoordinate)
            fail("camera", std::string(name) + " lies beyond " + numberText(kMaxCameraCoordinate) + " m of the origin");
    if (!(length(target - position) > 0)) fail("camera", "position and target coincide");
    if (!isFinite(up) || !(length(cross(normalize(target - position), upDirection(up))) > 1e-6f))
        fail("camera", "up is zero or parallel to the view direction");
    if (!(fovY >= kMinFovDegrees && fovY < 180.0f))
        fail("camera", "fov must be in [" + numberText(kMinFovDegrees) + ", 180) degrees, got " + numberText(fovY));
    if (!(nearZ > 0.0f) || !(farZ > nearZ) || !std::isfinite(nearZ))
        fail("camera", "near/far must satisfy 0 < near < far");
    // An infinite far plane has no clipFromView (inf / -inf is NaN) and no JSON number ("far": null).
    if (!std::isfinite(farZ)) fail("camera", "far must be finite, got " + numberText(farZ));
    if (width < 1 || height < 1)
        fail("camera", "image size must be at least 1x1, got " + std::to_string(width) + "x" + std::to_string(height));
    if (width > kMaxImageSide || height > kMaxImageSide)
        fail("camera", "image size " + std::to_string(width) + "x" + std::to_string(height) + " exceeds " +
                           std::to_string(kMaxImageSide));
}

float Camera::tanHalfFovY() const { return std::tan(0.5f * fovY * kPi / 180.0f); }

Mat4 Camera::viewFromWorld() const {
    // Rows are the camera's axes in world space.
    const std::array<Vec3, 3> axes = viewAxes(*this);
    Mat4 r;
    for (int i = 0; i < 3; ++i) {
        r.m[i][0] = axes[i].x;
        r.m[i][1] = axes[i].y;
        r.m[i][2] = axes[i].z;
        r.m[i][3] = -dot(axes[i], position);
    }
    return r;
}

Mat4 Camera::worldFromView() const {
    const std::array<Vec3, 3> axes = viewAxes(*this);
    Mat4 r;
    for (int j = 0; j < 3; ++j) {
        r.m[0][j] = axes[j].x;
        r.m[1][j] = axes[j].y;
        r.m[2][j] = axes[j].z;
    }
    r.m[0][3] = position.x;
    r.m[1][3] = position.y;
    r.m[2][3] = position.z;
    return r;
}

Mat4 Camera::clipFromView() const {
    float f = 1.0f / tanHalfFovY();
    Mat4 r;
    r.m[0][0] = f / aspect();
    r.m[1][1] = f;
    // In double: 2 * far * near overflows float for far beyond 1.7e38 / near, and the terms are far smaller.
    const double n = nearZ, fz = farZ;
    r.m[2][2] = float((fz + n) / (n - fz));
    r.m[2][3] = float(2.0 * fz * n / (n - fz));
    r.m[3][2] = -1.0f;
    r.m[3][3] = 0.0f;
    return r;
}

Vec3 Camera::viewFromPixel(float px, float py, float depth) const {
    float t = tanHalfFovY();
    float ndcX = 2.0f * px / float(width) - 1.0f;
    float ndcY = 1.0f - 2.0f * py / float(height);
    return {ndcX * t * aspect() * depth, ndcY * t * depth, -depth};
}

Camera::PixelToView Camera::viewFromPixelAffine() const {
    const float tanY = tanHalfFovY(), tanX = tanHalfFovX();
    return {2.0f * tanX / float(width), -tanX, -2.0f * tanY / float(height), tanY};
}

Vec3 Camera::viewRayDirection(float px, float py) const { return normalize(viewFromPixel(px, py, 1.0f)); }

Vec2 Camera::pixelFromView(Vec3 p, float* depth) const {
    float d = -p.z;
    if (depth) *depth = d;
    float t = tanHalfFovY();
    float ndcX = p.x / (d * t * aspect());
    float ndcY = p.y / (d * t);
    return {(ndcX + 1.0f) * 0.5f * float(width), (1.0f - ndcY) * 0.5f * float(height)};
}

Camera turnedAboutTarget(const Camera& base, float radians) {
    // In double, rounded once: in float, a turn of 0 moved the camera (x 0.4 -> 0.40000004, so frame 0 of
    // render --ao gtao was not the view asked for), and about a target 1e6 m away by 1.25 cm.
    Camera c = base;
    const double cosine = std::cos(double(radians)), sine = std::sin(double(radians));
    const double x = double(base.position.x) - double(base.target.x), z = double(base.position.z) - double(base.target.z);
    c.position.x = float(double(base.target.x) + (cosine * x + sine * z));
    c.position.z = float(double(base.target.z) + (cosine * z - sine * x));
    // The up vector turns with the camera, so the path is a rigid turn: a fixed up that was not vertical became
    // parallel to the view a quarter turn on (render --frames 181 with --camera-up 1,0,0 failed at frame 180,
    // after rendering the others). A vertical up is left as it is, to the bit.
    const double ux = double(base.up.x), uz = double(base.up.z);
    if (ux != 0.0 || uz != 0.0) {
        c.up.x = float(cosine * ux + sine * uz);
        c.up.z = float(cosine * uz - sine * ux);
    }
    return c;
}

} // namespace obscura
