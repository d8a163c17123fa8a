// Embree 3 acceleration structure for a Scene. A mesh placed once is flattened into the top-level scene in
// world space (one BVH level, the fastest to trace); a mesh placed several times becomes an Embree
// instance of a shared per-mesh scene, so memory stays proportional to unique geometry.
#include "obscura/trace.h"

#include "obscura/error.h"

#include "core/face_geometry.h"
#include "trace/embree_ray.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace obscura::trace {

struct Tracer::Impl {
    RTCDevice device = nullptr;
    RTCScene top = nullptr;
    std::vector<RTCScene> meshScenes;   // per mesh, only for meshes placed more than once
    std::vector<Mat4> normalFromObject;  // per instance
    std::vector<Mat4> worldFromObject;   // per instance

    ~Impl() {
        for (RTCScene s : meshScenes)
            if (s) rtcReleaseScene(s);
        if (top) rtcReleaseScene(top);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

void onEmbreeError(void*, RTCError code, const char* message) {
    // Errors during build surface through rtcGetDeviceError below; this keeps Embree from printing.
    (void)code;
    (void)message;
}

void checkDevice(RTCDevice device, const char* stage) {
    RTCError e = rtcGetDeviceError(device);
    if (e == RTC_ERROR_NONE) return;
    const char* what = e == RTC_ERROR_OUT_OF_MEMORY ? "out of memory" : "internal error";
    fail("embree", std::string(stage) + " failed: " + what + " (code " + std::to_string(int(e)) + ")");
}

RTCGeometry makeTriangles(RTCDevice device, const Mesh& mesh, const Mat4* worldFromObject) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), mesh.positions.size()));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), mesh.triangleCount()));
    if (!v || !idx) {
        rtcReleaseGeometry(g);
        checkDevice(device, "allocating geometry");
        fail("embree", "allocating geometry failed");
    }
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        Vec3 p = worldFromObject ? transformPoint(*worldFromObject, mesh.positions[i]) : mesh.positions[i];
        v[3 * i] = p.x;
        v[3 * i + 1] = p.y;
        v[3 * i + 2] = p.z;
    }
    std::memcpy(idx, mesh.indices.data(), mesh.indices.size() * sizeof(unsigned));
    rtcCommitGeometry(g);
    return g;
}

// Whether Embree can trace an instance with this transform: it carries each ray into object space through the
// inverse, and a singular or near-singular linear part makes that ray infinite or NaN, which Embree asserts on.
// Such an instance is flattened into world space instead, which costs memory, not correctness; it can still
// have area (a planar mesh squashed along its own normal), and its normals come from normalMatrix's cofactors.
bool invertibleForEmbree(const Mat4& m) {
    const auto a = [&](int r, int c) { return double(m.m[r][c]); };
    const double det = a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)) -
                       a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0)) +
                       a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
    double scale = 0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) scale = std::max(scale, std::abs(a(r, c)));
    // Relative to the transform's own scale, so a uniformly tiny or huge instance still counts as invertible;
    // 1e-9 keeps the inverse's float entries finite and its rays well-formed.
    return std::isfinite(det) && scale > 0 && std::abs(det) > 1e-9 * scale * scale * scale;
}

} // namespace

RTCRayHit makeRayHit(Vec3 o, Vec3 d, float tnear, float tfar) {
    RTCRayHit rh;
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tnear = tnear;
    rh.ray.tfar = tfar;
    rh.ray.time = 0;
    rh.ray.mask = ~0u;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

Tracer::Tracer(const Scene& scene)
    : impl_(std::make_unique<Impl>()), scene_(scene), bounds_((checkScene(scene, "scene"), scene.bounds())) {
    Impl& s = *impl_;
    s.device = rtcNewDevice(nullptr);
    if (!s.device) fail("embree", "cannot create a device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(s.device, onEmbreeError, nullptr);

    // Uses that become Embree instances: a singular transform is flattened instead (invertibleForEmbree), and
    // a mesh whose triangles were all dropped as degenerate places nothing (Embree refuses empty buffers).
    std::vector<char> instanceable(scene.instances.size());
    std::vector<int> uses(scene.meshes.size(), 0);
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        instanceable[i] = invertibleForEmbree(scene.instances[i].worldFromObject);
        if (instanceable[i]) ++uses[scene.instances[i].mesh];
    }

    s.meshScenes.assign(scene.meshes.size(), nullptr);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        if (uses[m] < 2 || scene.meshes[m].triangleCount() == 0) continue;
        RTCScene ms = rtcNewScene(s.device);
        rtcSetSceneBuildQuality(ms, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry g = makeTriangles(s.device, scene.meshes[m], nullptr);
        rtcAttachGeometry(ms, g);
        rtcReleaseGeometry(g);
        rtcCommitScene(ms);
        s.meshScenes[m] = ms;
    }
    checkDevice(s.device, "building mesh BVHs");

    s.top = rtcNewScene(s.device);
    rtcSetSceneBuildQuality(s.top, RTC_BUILD_QUALITY_HIGH);
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        s.worldFromObject.push_back(inst.worldFromObject);
        s.normalFromObject.push_back(normalMatrix(inst.worldFromObject));
        if (scene.meshes[inst.mesh].triangleCount() == 0) continue;
        RTCGeometry g;
        if (s.meshScenes[inst.mesh] && instanceable[i]) {
            g = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(g, s.meshScenes[inst.mesh]);
            float xfm[12];
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 4; ++c) xfm[r * 4 + c] = inst.worldFromObject.m[r][c];
            rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xfm);
            rtcCommitGeometry(g);
        } else {
            g = makeTriangles(s.device, scene.meshes[inst.mesh], &inst.worldFromObject);
        }
        // Geometry ID = instance index, so a hit names its instance in both cases.
        rtcAttachGeometryByID(s.top, g, unsigned(i));
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(s.top);
    checkDevice(s.device, "building the scene BVH");
}

Tracer::~Tracer() = default;

void* Tracer::embreeScene() const { return impl_->top; }

bool Tracer::intersect(Vec3 o, Vec3 d, float tnear, float tfar, Hit& hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh = makeRayHit(o, d, tnear, tfar);
    rtcIntersect1(impl_->top, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

    hit.t = rh.ray.tfar;
    hit.instance = rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? rh.hit.instID[0] : rh.hit.geomID;
    hit.primitive = rh.hit.primID;
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
    // From object-space vertices for both placements: Embree reports Ng of instanced hits in object space.
    const Mesh& mesh = scene_.meshes[scene_.instances[hit.instance].mesh];
    const std::uint32_t* tri = &mesh.indices[3 * std::size_t(hit.primitive)];
    Vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
    hit.geometricNormal = normalize(transformVector(impl_->normalFromObject[hit.instance], cross(p1 - p0, p2 - p0)));
    return true;
}

float Tracer::closestDistance(Vec3 o, Vec3 d, float tnear, float tfar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh = makeRayHit(o, d, tnear, tfar);
    rtcIntersect1(impl_->top, &context, &rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? kInfinity : rh.ray.tfar;
}

bool Tracer::occluded(Vec3 o, Vec3 d, float tnear, float tfar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh = makeRayHit(o, d, tnear, tfar);
    rtcOccluded1(impl_->top, &context, &rh.ray);
    return rh.ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

Vec3 Tracer::shadingNormal(const Hit& hit) const {
    const Mesh& mesh = scene_.meshes[scene_.instances[hit.instance].mesh];
    // Normals are optional in a Scene (empty until computed or loaded): a mesh without them once crashed here.
    if (mesh.normals.size() != mesh.positions.size()) return hit.geometricNormal;
    const std::uint32_t* tri = &mesh.indices[3 * std::size_t(hit.primitive)];
    Vec3 n = mesh.normals[tri[0]] * (1.0f - hit.u - hit.v) + mesh.normals[tri[1]] * hit.u + mesh.normals[tri[2]] * hit.v;
    return normalize(transformVector(impl_->normalFromObject[hit.instance], n));
}

std::array<Vec3, 3> Tracer::worldTriangle(const Hit& hit) const {
    const Instance& inst = scene_.instances[hit.instance];
    const Mesh& mesh = scene_.meshes[inst.mesh];
    const std::uint32_t* tri = &mesh.indices[3 * std::size_t(hit.primitive)];
    return {transformPoint(inst.worldFromObject, mesh.positions[tri[0]]),
            transformPoint(inst.worldFromObject, mesh.positions[tri[1]]),
            transformPoint(inst.worldFromObject, mesh.positions[tri[2]])};
}

Vec3 Tracer::surfacePoint(const Hit& hit, float* offset) const {
    const auto [a, b, c] = worldTriangle(hit);
    const Vec3 p = a * (1.0f - hit.u - hit.v) + b * hit.u + c * hit.v;
    if (offset) *offset = trace::selfHitOffset(a, b, c, p, 0.0f);
    return p;
}

Vec3 Tracer::albedo(const Hit& hit) const { return scene_.meshes[scene_.instances[hit.instance].mesh].baseColor; }

namespace {

constexpr double kSelfHitPerUlpScale = 2.5e-7;  // x the largest |coordinate| x the aspect ratio
constexpr double kMinAspect = 4.0;

} // namespace

float selfHitOffset(Vec3 a, Vec3 b, Vec3 c, Vec3 p, float scale) {
    const double m = std::max({double(maxAbsComponent(a)), double(maxAbsComponent(b)), double(maxAbsComponent(c)),
                               double(maxAbsComponent(p)), double(scale)});
    // In double: the cross product of a sliver's edges is what float gets wrong.
    const double twiceArea = geometry::twiceArea(a, b, c), longest2 = geometry::longestEdge2(a, b, c);
    // A triangle the scene kept has some area; the cap only keeps a pathological one finite.
    const double aspect = twiceArea > 0 ? std::clamp(longest2 / twiceArea, kMinAspect, 1e6) : 1e6;
    return float(kSelfHitPerUlpScale * m * aspect);
}

float selfHitOffsetFloor(const Bounds& bounds) {
    if (bounds.empty()) return 0.0f;
    // The box's point of least largest |coordinate|: each axis's own nearest value to 0.
    double m = 0;
    for (int a = 0; a < 3; ++a) {
        const double lo = double(bounds.lo[a]), hi = double(bounds.hi[a]);
        m = std::max(m, lo <= 0.0 && hi >= 0.0 ? 0.0 : std::min(std::abs(lo), std::abs(hi)));
    }
    return float(kSelfHitPerUlpScale * m * kMinAspect);
}

std::string rayReachProblem(const Bounds& bounds, float reach, const std::string& scene, bool& refuse) {
    refuse = false;
    const float offset = selfHitOffsetFloor(bounds);
    if (!(reach > 0.0f) || !std::isfinite(reach) || offset < 0.01f * reach) return "";
    refuse = offset >= 0.25f * reach;
    return scene + " is so far from the origin that float precision starts every ray at least " + numberText(offset) +
           " m off its surface, " + numberText(100.0f * offset / reach) + "% of " + numberText(reach) +
           " m; move the scene nearer the origin";
}

float Tracer::selfHitOffset(const Hit& hit, Vec3 origin, Vec3 p) const {
    const auto [a, b, c] = worldTriangle(hit);
    return trace::selfHitOffset(a, b, c, p, maxAbsComponent(origin));
}

float Tracer::selfHitOffset(Vec3 p, Vec3 ng) const {
    const double m = bounds_.empty() ? double(maxAbsComponent(p))
                                     : std::max({double(maxAbsComponent(p)), double(maxAbsComponent(bounds_.lo)),
                                                 double(maxAbsComponent(bounds_.hi))});
    const auto reach = float(kSelfHitPerUlpScale * m * 100.0);
    // From `reach` above p, which clears any triangle but a thinner sliver, back down through p.
    Hit hit;
    if (reach > 0.0f && intersect(p + ng * reach, -ng, 0.0f, 2.0f * reach, hit)) return selfHitOffset(hit, p, p);
    return reach;
}

} // namespace obscura::trace
