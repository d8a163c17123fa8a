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
// G-buffer's normal in world space. False for sky or a miss.
inline bool pixelSurface(const Tracer& tracer, const GBuffer& g, const Mat4& worldFromView, int x, int y, Vec3& p,
                         Vec3& n, Vec3& ng, float& offset) {
    if (g.isSky(x, y)) return false;
    PrimaryRay ray = primaryRay(g.camera, worldFromView, float(x) + 0.5f, float(y) + 0.5f);
    Hit hit;
    if (!tracer.intersect(ray.origin, ray.direction, ray.tnear, ray.tfar, hit)) return false;
    p = ray.origin + ray.direction * hit.t;
    ng = dot(hit.geometricNormal, ray.direction) > 0.0f ? -hit.geometricNormal : hit.geometricNormal;
    offset = tracer.selfHitOffset(hit, ray.origin, p);
    n = normalize(transformVector(worldFromView, g.viewNormal(x, y)));
    return true;
}

} // namespace obscura::trace
