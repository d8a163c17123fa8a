// Views shared by the GTAO tests: built-in scenes seen from above, where the depth buffer is a height
// field that holds every occluder within the radius.
#pragma once

#include "obscura/builtin_scenes.h"
#include "obscura/gbuffer.h"
#include "obscura/metrics.h"

#include <cmath>
#include <string>

namespace obscura::test {

struct TopDownView {
    Scene scene;
    Camera camera;
    float radius;  // AO radius used with this view, m
};

inline TopDownView topDownView(const std::string& name, int width, int height) {
    TopDownView v{makeBuiltinScene(name).scene, {}, 1.0f};
    v.camera.up = {0.0f, 0.0f, -1.0f};
    if (name == "well") {
        // Straight down the axis: every point of the wall faces the camera.
        v.camera.position = {0.0f, 3.0f, 0.0f};
        v.camera.target = {0.0f, -2.0f, 0.0f};
    } else if (name == "stairs") {
        v.camera.position = {0.0f, 5.0f, -0.2f};
        v.camera.target = {0.0f, 0.0f, -0.2f};
    } else {
        // Inside the corner, above the floor and below the walls' top: both walls' faces are seen.
        v.camera.position = {2.5f, 6.0f, 2.5f};
        v.camera.target = {0.8f, 0.0f, 0.8f};
    }
    v.camera.width = width;
    v.camera.height = height;
    return v;
}

// Mean of |a - b| over the G-buffer's surface pixels: the MAE that `obscura compare` reports.
inline double meanAbsoluteError(const GBuffer& g, const Image& a, const Image& b) {
    return eval::errorStats(a, b, g).mae;
}

} // namespace obscura::test
