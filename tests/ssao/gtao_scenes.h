// Views shared by the GTAO tests: built-in scenes seen from above, where the depth buffer is a height
// field that holds every occluder within the radius.
#pragma once

#include "obscura/builtin_scenes.h"
#include "obscura/error.h"
#include "obscura/gbuffer.h"
#include "obscura/metrics.h"
#include "obscura/trace.h"
#include "trace/primary_ray.h"

#include <cmath>
#include <functional>
#include <string>

namespace obscura::test {

// The G-buffer with a rectangle of sky cut into it, [x0, x1) x [y0, y1), its depth `skyDepth` (+inf, or 1e30
// and more, which FORMATS.md also calls sky) and its normals zero; the rest of its sky takes `skyDepth` too.
inline GBuffer withSkyHole(GBuffer g, int x0, int y0, int x1, int y1, float skyDepth) {
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            g.depth.at(x, y) = INFINITY;
            for (int c = 0; c < 3; ++c) g.normal.at(x, y, c) = 0.0f;
        }
    for (float& d : g.depth.pixels)
        if (!(d < 1e30f)) d = skyDepth;
    return g;
}

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
        // Above and in front of the bottom step, so every riser faces the camera. The flight's sides and
        // the back of the top step are vertical faces no camera above sees; occludersSeen() measures how
        // much of the picture they reach (8%, the floor along the sides).
        v.camera.position = {0.0f, 6.0f, 3.5f};
        v.camera.target = {0.0f, 0.5f, 0.2f};
    } else {
        // Inside the corner, above the floor and below the walls' top: both walls' faces are seen.
        v.camera.position = {2.5f, 6.0f, 2.5f};
        v.camera.target = {0.8f, 0.0f, 0.8f};
    }
    v.camera.width = width;
    v.camera.height = height;
    return v;
}

// The integral GTAO estimates for the view: binary visibility within `radius`, cosine-weighted, by ray
// tracing with `rays` stratified rays per pixel.
inline Image rayTracedReference(const trace::Tracer& tracer, const GBuffer& g, float radius, int rays) {
    trace::ObscuranceSettings settings;
    settings.radius = radius;
    settings.rays = rays;
    return trace::ambientObscurance(tracer, g, settings);
}

// A top-down view rendered, with its ray-traced reference (`rays` rays per pixel) and the tracer for more.
// Neither copied nor moved: the tracer refers to the view's scene.
struct TopDownReference {
    TopDownReference(const std::string& name, int size, int rays)
        : view(topDownView(name, size, size)), tracer(view.scene), g(trace::renderGBuffer(tracer, view.camera)),
          reference(rayTracedReference(tracer, g, view.radius, rays)) {}
    TopDownReference(const TopDownReference&) = delete;
    TopDownReference& operator=(const TopDownReference&) = delete;

    TopDownView view;
    trace::Tracer tracer;
    GBuffer g;
    Image reference;
};

// Mean of |a - b| over the G-buffer's surface pixels: the MAE that `obscura compare` reports.
inline double meanAbsoluteError(const GBuffer& g, const Image& a, const Image& b) {
    return eval::errorStats(a, b, g).mae;
}

// 1 where every surface that a pixel's ray-traced AO rays hit within `radius` is seen by the camera (the
// premise under which screen-space AO can match it), 0 where some occluder is hidden, sky 0. 256 rays
// per pixel, a hit counting as seen if the camera's ray to it meets nothing 0.1% short of it.
inline Image occludersSeen(const trace::Tracer& tracer, const GBuffer& g, float radius) {
    trace::ObscuranceSettings settings;
    settings.radius = radius;
    settings.rays = 256;
    const trace::ObscuranceEstimator estimator(tracer, settings);
    const Mat4 worldFromView = g.camera.worldFromView();
    Image seen(g.width(), g.height(), 1, 0.0f);
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            Vec3 p, n, ng;
            float offset;
            if (!trace::pixelSurface(tracer, g, worldFromView, x, y, p, n, ng, offset)) continue;
            const auto frame = estimator.frame(p, n, ng, 0, offset);
            bool hidden = false;
            for (int i = 0; i < settings.rays && !hidden; ++i) {
                const Vec3 d = estimator.direction(frame, i);
                trace::Hit hit;
                if (!tracer.intersect(frame.origin, d, 0.0f, radius, hit)) continue;
                const Vec3 toHit = frame.origin + d * hit.t - g.camera.position;
                const float distance = length(toHit);
                hidden = tracer.closestDistance(g.camera.position, toHit / distance, 0.0f, distance) <
                         distance * (1.0f - 1e-3f);
            }
            seen.at(x, y) = hidden ? 0.0f : 1.0f;
        }
    return seen;
}

// Fraction of the surface pixels where `mask` is 1.
inline double maskFraction(const GBuffer& g, const Image& mask) {
    double in = 0, all = 0;
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x)
            if (!g.isSky(x, y)) {
                all += 1;
                in += mask.at(x, y) > 0.5f ? 1 : 0;
            }
    return all > 0 ? in / all : 0.0;
}

// A 6x6 view of the sky with a surface pixel in each row of column 3, 2 m away facing the camera (normal
// `normal`): a pole one pixel wide that the half-resolution grid (columns 0, 2, 4) never sees.
inline GBuffer poleAgainstTheSky(Vec3 normal = {0, 0, 1}) {
    Camera cam;
    cam.position = {0, 0, 0};
    cam.target = {0, 0, -1};
    cam.width = cam.height = 6;
    GBuffer g;
    g.camera = cam;
    g.depth = Image(6, 6, 1, INFINITY);
    g.normal = Image(6, 6, 3, 0.0f);
    for (int y = 0; y < 6; ++y) {
        g.depth.at(3, y) = 2.0f;
        g.normal.at(3, y, 0) = normal.x;
        g.normal.at(3, y, 1) = normal.y;
        g.normal.at(3, y, 2) = normal.z;
    }
    return g;
}

// The message of the obscura::Error that `run` throws, or "no error".
inline std::string errorOf(const std::function<void()>& run) {
    try {
        run();
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

} // namespace obscura::test
