// Closest hits with their facing, for the baker: one rtcIntersect1 per ray, the facing read from Embree's
// geometric normal, so no vertex data is fetched per hit.
#include "obscura/trace_stream.h"

#include "trace/embree_ray.h"

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
    for (int i = 0; i < count; ++i) {
        const Vec3 d = directions[i];
        RTCRayHit rh = makeRayHit(origin, d, 0.0f, tfar);
        rtcIntersect1(scene, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
            t[i] = kInfinity;
            backFacing[i] = 0;
            continue;
        }
        t[i] = rh.ray.tfar;
        Vec3 local = d;
        if (rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID)
            local = transformVector(objectFromWorld_[rh.hit.instID[0]], d);
        else if (mirrored_[rh.hit.geomID])
            local = -d;
        // Embree's Ng points to the counter-clockwise (front) side (checked in tests/bake): a ray travelling
        // along it arrives from behind.
        const float facing = rh.hit.Ng_x * local.x + rh.hit.Ng_y * local.y + rh.hit.Ng_z * local.z;
        backFacing[i] = facing > 0.0f;
    }
}

} // namespace obscura::trace
