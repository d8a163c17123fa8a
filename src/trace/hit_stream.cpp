// Closest hits with their facing, for the baker: 8-wide Embree packets of rays from one origin, the facing
// read from Embree's geometric normal, so no vertex data is fetched per hit.
#include "obscura/trace_stream.h"

#include "trace/embree_ray.h"

#include <algorithm>

namespace obscura::trace {

HitStream::HitStream(const Tracer& tracer) : scene_(tracer.embreeScene()) {
    // Embree reports Ng in the object space of an instanced mesh; dot(Ng_world, d) = dot(Ng_obj, L^-1 d)
    // for a linear part L, so the direction goes to object space instead of the normal to world space.
    // Flattened meshes are already in world space, where the identity is right too.
    const Scene& scene = tracer.scene();
    objectFromWorld_.resize(scene.instances.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i)
        if (!invert(scene.instances[i].worldFromObject, objectFromWorld_[i])) objectFromWorld_[i] = Mat4::identity();
    // A flattened mesh under a mirroring transform has its world-space winding reversed.
    mirrored_.resize(scene.instances.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i)
        mirrored_[i] = determinant3(scene.instances[i].worldFromObject) < 0.0f;
}

void HitStream::closestHits(Vec3 origin, const Vec3* directions, int count, float tfar, float* t,
                            std::uint8_t* backFacing) const {
    auto scene = static_cast<RTCScene>(scene_);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // Rays of one bake sample share their origin, and callers order them so that neighbours point alike:
    // 8-wide packets then traverse the BVH together.
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    RTCRayHit8 rh;
    int valid[8];
    for (int first = 0; first < count; first += 8) {
        const int n = std::min(8, count - first);
        for (int k = 0; k < 8; ++k) {
            const Vec3 d = directions[first + std::min(k, n - 1)];
            valid[k] = k < n ? -1 : 0;
            rh.ray.org_x[k] = origin.x;
            rh.ray.org_y[k] = origin.y;
            rh.ray.org_z[k] = origin.z;
            rh.ray.dir_x[k] = d.x;
            rh.ray.dir_y[k] = d.y;
            rh.ray.dir_z[k] = d.z;
            rh.ray.tnear[k] = 0.0f;
            rh.ray.tfar[k] = tfar;
            rh.ray.time[k] = 0.0f;
            rh.ray.mask[k] = ~0u;
            rh.ray.id[k] = 0;
            rh.ray.flags[k] = 0;
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect8(valid, scene, &context, &rh);
        for (int k = 0; k < n; ++k) {
            const int i = first + k;
            if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
                t[i] = kInfinity;
                backFacing[i] = 0;
                continue;
            }
            t[i] = rh.ray.tfar[k];
            Vec3 local = directions[i];
            if (rh.hit.instID[0][k] != RTC_INVALID_GEOMETRY_ID)
                local = transformVector(objectFromWorld_[rh.hit.instID[0][k]], local);
            else if (mirrored_[rh.hit.geomID[k]])
                local = -local;
            // Embree's Ng points to the counter-clockwise (front) side (checked in tests/bake): a ray
            // travelling along it arrives from behind.
            const float facing = rh.hit.Ng_x[k] * local.x + rh.hit.Ng_y[k] * local.y + rh.hit.Ng_z[k] * local.z;
            backFacing[i] = facing > 0.0f;
        }
    }
}

} // namespace obscura::trace
