// The camera ray through a pixel position, shared by the G-buffer and the per-pixel estimators so both
// find the same surface point.
#pragma once

#include "obscura/camera.h"
#include "obscura/gbuffer.h"
#include "obscura/trace.h"

namespace obscura::trace {

struct PrimaryRay {
    Vec3 origin, direction;  // world
    float tnear, tfar;       // the camera's near and far planes along this ray
    float depthPerT;         // linear view depth = t * depthPerT
};

inline PrimaryRay primaryRay(const Camera& camera, const Mat4& worldFromView, float px, float py) {
    Vec3 viewDir = camera.viewRayDirection(px, py);
    float cosZ = -viewDir.z;
    return {camera.position, normalize(transformVector(worldFromView, viewDir)), camera.nearZ / cosZ,
            camera.farZ / cosZ, cosZ};
}

// The surface behind G-buffer pixel (x, y), traced again for the exact point and geometric normal (facing
// the camera) that the G-buffer does not store, and the self-hit offset of rays leaving that point; n is the
// G-buffer's normal in world space. False for sky or a miss. The point is the hit's barycentric one: the
// ray's origin + t d is off the surface by the rounding of the camera's coordinates, and an offset that
// covered it (scaled by the camera's distance and the triangle's aspect ratio) lifted the rays 1 m at a
// camera 100 km out, which read a well's floor as 0.51 for 0.2.
inline bool pixelSurface(const Tracer& tracer, const GBuffer& g, const Mat4& worldFromView, int x, int y, Vec3& p,
                         Vec3& n, Vec3& ng, float& offset) {
    if (g.isSky(x, y)) return false;
    PrimaryRay ray = primaryRay(g.camera, worldFromView, float(x) + 0.5f, float(y) + 0.5f);
    Hit hit;
    if (!tracer.intersect(ray.origin, ray.direction, ray.tnear, ray.tfar, hit)) return false;
    p = tracer.surfacePoint(hit, &offset);
    ng = dot(hit.geometricNormal, ray.direction) > 0.0f ? -hit.geometricNormal : hit.geometricNormal;
    n = normalize(transformVector(worldFromView, g.viewNormal(x, y)));
    return true;
}

} // namespace obscura::trace
