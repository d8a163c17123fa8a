// Perspective pinhole camera and the pixel <-> view-space mapping every screen-space pass relies on.
//
// Conventions (docs/FORMATS.md, "Spaces and units"): meters; view space is right-handed, camera at the origin
// looking down -Z, +Y up, +X right. "Depth" is linear view depth, the positive distance along -Z
// (depth = -z_view). Pixel (px, py) has its centre at (px + 0.5, py + 0.5); py = 0 is the top row.
#pragma once

#include "obscura/math.h"

namespace obscura {

// The widest and tallest image Obscura makes or reads, pixels: Camera::validate, the size flags, camera files
// and the image readers all hold to it.
inline constexpr int kMaxImageSide = 32768;
// The narrowest vertical field of view, degrees. Far below any lens (a 2400 mm telephoto sees about 0.6 degrees),
// it keeps tan(fovY / 2) and its reciprocal well inside float's range: at 1e-45 degrees the tangent was 0 and
// every projection divided by it.
inline constexpr float kMinFovDegrees = 1e-3f;
// The farthest a camera's position or target may lie from the origin, m: ten times kMaxSceneCoordinate
// (scene.h), so that a default camera framing the largest scene fits, and its rays stay far inside the origins
// Embree takes.
inline constexpr float kMaxCameraCoordinate = 1e13f;

struct Camera {
    Vec3 position{0, 1, 5};   // world, m
    Vec3 target{0, 0, 0};     // world point the camera looks at, m
    Vec3 up{0, 1, 0};         // world up hint, need not be orthogonal to the view direction
    float fovY = 60.0f;       // vertical field of view, degrees, [kMinFovDegrees, 180)
    float nearZ = 0.01f;      // near plane distance, m, > 0 (primary rays start here)
    float farZ = 1.0e4f;      // far plane distance, m, > nearZ (primary rays end here)
    int width = 1280;         // image size, pixels, >= 1
    int height = 720;

    // Throws obscura::Error naming the bad field.
    void validate() const;

    float aspect() const { return float(width) / float(height); }
    float tanHalfFovY() const;
    float tanHalfFovX() const { return tanHalfFovY() * aspect(); }
    // Focal length in pixels along y: a view-space length L at depth d spans L * focalPixels() / d pixels.
    float focalPixels() const { return 0.5f * float(height) / tanHalfFovY(); }

    Mat4 viewFromWorld() const;
    Mat4 worldFromView() const;
    // OpenGL-style projection (right-handed view, clip z in [-w, w]), for interop and documentation.
    Mat4 clipFromView() const;

    // View-space position of the point at linear depth `depth` seen through image position (px, py),
    // in continuous pixel coordinates (a pixel centre is x + 0.5). Hot-path: no checks.
    Vec3 viewFromPixel(float px, float py, float depth) const;
    // viewFromPixel as the per-axis affine map that screen-space kernels keep in their constants:
    // x = (px * mulX + addX) * depth, y = (py * mulY + addY) * depth, z = -depth.
    struct PixelToView {
        float mulX, addX, mulY, addY;
    };
    PixelToView viewFromPixelAffine() const;
    // Unit view-space direction through image position (px, py).
    Vec3 viewRayDirection(float px, float py) const;
    // Continuous pixel coordinates of a view-space point, and its depth (-z).
    Vec2 pixelFromView(Vec3 p, float* depth = nullptr) const;
};

// `base` with its position turned by `radians` about the world's vertical (+Y) through its target, looking
// at the same target, its up vector turned with it (a rigid turn: a vertical up stays as it is): the camera
// path the temporal passes are shown and tested on.
Camera turnedAboutTarget(const Camera& base, float radians);

} // namespace obscura
