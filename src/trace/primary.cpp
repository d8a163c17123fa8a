// Primary rays: one ray through each pixel centre gives exact depth and normal; albedo is averaged over
// N x N sub-pixel samples for antialiased pictures.
#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/trace.h"
#include "trace/primary_ray.h"

#include <atomic>
#include <string>

namespace obscura::trace {

GBuffer renderGBuffer(const Tracer& tracer, const Camera& camera, const GBufferSettings& settings,
                      const Progress& progress) {
    camera.validate();
    if (settings.supersample < 1 || settings.supersample > 16)
        fail("supersample", "must be in [1, 16], got " + std::to_string(settings.supersample));
    GBuffer g;
    g.camera = camera;
    g.depth = Image(camera.width, camera.height, 1, kInfinity);
    g.depth.channelNames = {"Z"};
    g.normal = Image(camera.width, camera.height, 3, 0.0f);
    g.normal.channelNames = {"X", "Y", "Z"};
    g.albedo = Image(camera.width, camera.height, 3, 0.0f);
    g.albedo.channelNames = {"R", "G", "B"};

    const Mat4 worldFromView = camera.worldFromView();
    const Mat4 viewFromWorld = camera.viewFromWorld();
    const int n = settings.supersample;
    std::atomic<int> rowsDone{0};

    parallelFor(std::size_t(camera.height), [&](std::size_t y0, std::size_t y1) {
        for (auto y = int(y0); y < int(y1); ++y) {
            for (int x = 0; x < camera.width; ++x) {
                // The centre ray: depth and normal.
                PrimaryRay ray = primaryRay(camera, worldFromView, float(x) + 0.5f, float(y) + 0.5f);
                const Vec3 dir = ray.direction;
                Hit hit;
                Vec3 albedoSum{};
                int covered = 0;
                const bool surface = tracer.intersect(ray.origin, dir, ray.tnear, ray.tfar, hit);
                if (surface) {
                    // Surfaces are two-sided: both normals face the camera, the shading one following the
                    // geometric one so a file whose winding disagrees with its normals still shades right.
                    bool flip = dot(hit.geometricNormal, dir) > 0.0f;
                    Vec3 ns = tracer.shadingNormal(hit);
                    Vec3 ng = flip ? -hit.geometricNormal : hit.geometricNormal;
                    if (dot(ns, ng) < 0.0f) ns = -ns;
                    Vec3 nv = normalize(transformVector(viewFromWorld, ns));
                    g.depth.at(x, y) = hit.t * ray.depthPerT;
                    g.normal.at(x, y, 0) = nv.x;
                    g.normal.at(x, y, 1) = nv.y;
                    g.normal.at(x, y, 2) = nv.z;
                    if (n == 1) {
                        albedoSum = tracer.albedo(hit);
                        covered = 1;
                    }
                }
                // A sky pixel keeps albedo (0, 0, 0), as GBuffer says, though sub-samples near an edge hit.
                for (int sy = 0; n > 1 && surface && sy < n; ++sy)
                    for (int sx = 0; sx < n; ++sx) {
                        PrimaryRay sr = primaryRay(camera, worldFromView, float(x) + (float(sx) + 0.5f) / float(n),
                                                   float(y) + (float(sy) + 0.5f) / float(n));
                        Hit sub;
                        if (tracer.intersect(sr.origin, sr.direction, sr.tnear, sr.tfar, sub)) {
                            albedoSum += tracer.albedo(sub);
                            ++covered;
                        }
                    }
                if (covered > 0) {
                    Vec3 a = albedoSum / float(covered);
                    g.albedo.at(x, y, 0) = a.x;
                    g.albedo.at(x, y, 1) = a.y;
                    g.albedo.at(x, y, 2) = a.z;
                }
            }
            int done = ++rowsDone;
            if (progress) progress(double(done) / double(camera.height));
        }
    });
    return g;
}

} // namespace obscura::trace
