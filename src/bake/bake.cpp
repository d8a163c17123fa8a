// The bake pipeline: weld -> samples -> BVH -> rays -> least squares, timed per stage like Table 1 of
// Sloan et al. 2013, with the welded values handed back in the file's vertex order per instance.
#include "obscura/bake.h"

#include "obscura/bake_bench.h"

#include "obscura/error.h"
#include "obscura/trace.h"

#include <algorithm>
#include <chrono>

namespace obscura::bake {

namespace {

double now() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

} // namespace

BakeResult bakeScene(const Scene& scene, const BakeSettings& settings, const StageProgress& progress,
                     std::size_t rawEmbreeStride) {
    settings.validate();
    checkScene(scene, "bake");
    auto report = [&](const char* stage, double f) {
        if (progress) progress(stage, f);
    };
    BakeResult r;
    r.channels = settings.channels();

    double t0 = now();
    report("process geometry", 0.0);
    const WeldedMesh mesh = weldScene(scene, settings.weldDistance(scene.bounds()), settings.creaseAngle);
    if (mesh.triangleCount() == 0)
        fail("bake", "no triangles left after welding (every face has no area where its instances place it)");
    report("process geometry", 1.0);
    double t1 = now();
    r.times.processGeometry = t1 - t0;

    report("sample", 0.0);
    const SampleSet samples = generateSamples(mesh, settings);
    report("sample", 1.0);
    double t2 = now();
    r.times.sample = t2 - t1;

    report("BVH build", 0.0);
    const trace::Tracer tracer(scene);
    report("BVH build", 1.0);
    double t3 = now();
    r.times.bvhBuild = t3 - t2;

    const RayResults rays = traceSamples(tracer, samples, settings, [&](double f) { report("trace", f); });
    double t4 = now();
    r.times.trace = t4 - t3;
    if (rawEmbreeStride > 0) {
        report("raw Embree check", 0.0);
        r.raw = benchRawEmbree(tracer, samples, settings, rawEmbreeStride);
        report("raw Embree check", 1.0);
        t4 = now();  // not part of any stage
    }

    report("least-squares solve", 0.0);
    const std::vector<float> welded = solveVertexValues(mesh, samples, rays, settings.alpha, &r.solve, settings.linearSolver);
    report("least-squares solve", 1.0);
    r.times.solve = now() - t4;

    const auto channels = std::size_t(r.channels);
    r.instanceFirst = mesh.instanceFirst;
    r.values.resize(mesh.vertexMap.size() * channels);
    for (std::size_t i = 0; i < mesh.vertexMap.size(); ++i)
        for (std::size_t c = 0; c < channels; ++c)
            r.values[i * channels + c] = std::clamp(welded[std::size_t(mesh.vertexMap[i]) * channels + c], 0.0f, 1.0f);
    // A file vertex on both sides of a crease: the mean of its copies by face area (WeldedMesh::blends).
    for (std::size_t i = 0; i < mesh.blends.size();) {
        std::size_t end = i;
        double sum[2] = {0, 0}, weight = 0;
        for (; end < mesh.blends.size() && mesh.blends[end].file == mesh.blends[i].file; ++end) {
            const WeldedMesh::Blend& b = mesh.blends[end];
            weight += double(b.weight);
            for (std::size_t c = 0; c < channels; ++c) sum[c] += double(b.weight) * double(welded[std::size_t(b.copy) * channels + c]);
        }
        if (weight > 0)
            for (std::size_t c = 0; c < channels; ++c)
                r.values[std::size_t(mesh.blends[i].file) * channels + c] = std::clamp(float(sum[c] / weight), 0.0f, 1.0f);
        i = end;
    }
    r.inputTriangles = mesh.inputTriangles;
    r.droppedTriangles = mesh.droppedTriangles;
    r.weldedVertices = r.solve.unknowns;
    r.inputVertices = mesh.vertexMap.size();
    r.samples = samples.size();
    r.invalidSamples = rays.invalidSamples;
    r.rays = rays.rays;
    return r;
}

} // namespace obscura::bake
