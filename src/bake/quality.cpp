// The baked vertices against dense ray tracing (the Foundation's estimator at every vertex), and against
// the naive alternative, point sampling at each vertex with the bake's ray budget: the least-squares fit
// over samples on the faces should match the reference and be smoother (Kavan et al. 2011 §5).
#include "obscura/bake_quality.h"

#include "obscura/error.h"
#include "obscura/parallel.h"
#include "obscura/trace.h"
#include "obscura/trace_stream.h"
#include "obscura/sampling.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace obscura::bake {

Scene refineScene(const Scene& scene, float maxEdge, int maxSplits) {
    Scene out;
    out.instances = scene.instances;
    for (const Mesh& mesh : scene.meshes) {
        Mesh m;
        m.name = mesh.name;
        m.baseColor = mesh.baseColor;
        const bool normals = mesh.normals.size() == mesh.positions.size();
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const std::uint32_t* v = &mesh.indices[3 * t];
            const Vec3 p[3] = {mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]};
            const float longest = std::max({length(p[1] - p[0]), length(p[2] - p[1]), length(p[0] - p[2])});
            const int k = std::clamp(int(std::ceil(longest / maxEdge)), 1, maxSplits);
            const auto base = std::uint32_t(m.positions.size());
            auto at = [&](int i, int j) { return base + std::uint32_t(j * (k + 1) - j * (j - 1) / 2 + i); };
            for (int j = 0; j <= k; ++j)
                for (int i = 0; i + j <= k; ++i) {
                    const float b1 = float(i) / float(k), b2 = float(j) / float(k), b0 = 1.0f - b1 - b2;
                    m.positions.push_back(p[0] * b0 + p[1] * b1 + p[2] * b2);
                    if (normals)
                        m.normals.push_back(normalize(mesh.normals[v[0]] * b0 + mesh.normals[v[1]] * b1 + mesh.normals[v[2]] * b2));
                }
            for (int j = 0; j < k; ++j)
                for (int i = 0; i + j < k; ++i) {
                    m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
                    if (i + j + 1 < k) m.indices.insert(m.indices.end(), {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
                }
        }
        computeSmoothNormals(m);
        out.meshes.push_back(std::move(m));
    }
    return out;
}

QualityResult compareWithDense(const Scene& scene, const BakeSettings& settings, int referenceRays) {
    settings.validate();
    if (settings.mode != Mode::Obscurance) fail("compare", "the dense comparison is for obscurance mode");
    const auto start = std::chrono::steady_clock::now();
    QualityResult q;
    q.referenceRays = referenceRays;
    const WeldedMesh mesh = weldScene(scene, settings.weldTolerance * length(scene.bounds().size()));
    const SampleSet samples = generateSamples(mesh, settings);
    const trace::Tracer tracer(scene);
    const RayResults rays = traceSamples(tracer, samples, settings);
    const std::vector<float> baked = solveVertexValues(mesh, samples, rays, settings.alpha);
    q.vertices = mesh.positions.size();
    q.triangles = mesh.triangleCount();
    q.samples = samples.size();

    // Vertex normals of the welded vertices; used ones only.
    std::vector<Vec3> normal(mesh.positions.size(), Vec3{});
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        const Mesh& m = scene.meshes[inst.mesh];
        const Mat4 nm = normalMatrix(inst.worldFromObject);
        for (std::size_t v = 0; v < m.positions.size(); ++v)
            normal[mesh.vertexMap[mesh.instanceFirst[i] + v]] += normalize(transformVector(nm, m.normals[v]));
    }
    std::vector<char> used(mesh.positions.size(), 0);
    for (std::uint32_t v : mesh.indices) used[v] = 1;
    // Vertices hidden inside closed geometry or under a floor (more than the bake's back-face limit of their
    // rays hit back faces) have no meaningful reference and are never seen: they are left out, as the bake
    // leaves out such samples. 256 rays per vertex decide.
    {
        const trace::HitStream stream(tracer);
        const CosineHemisphereSet set(256);
        const auto limit = int(std::floor(double(settings.backFaceLimit) * 256));
        parallelFor(mesh.positions.size(), [&](std::size_t b, std::size_t e) {
            std::vector<Vec3> dirs(256);
            std::vector<float> t(256);
            std::vector<std::uint8_t> back(256);
            for (std::size_t v = b; v < e; ++v) {
                const Vec3 n = normalize(normal[v]);
                if (!used[v] || n == Vec3{}) {
                    used[v] = 0;
                    continue;
                }
                Vec3 tx, bx;
                orthonormalBasis(n, tx, bx);
                const auto shift = CosineHemisphereSet::shift(std::uint32_t(v) ^ 0x0bacu);
                for (int i = 0; i < 256; ++i) {
                    const Vec3 l = set.direction(i, shift);
                    dirs[std::size_t(i)] = tx * l.x + bx * l.y + n * l.z;
                }
                const Vec3 p = mesh.positions[v];
                stream.closestHits(p + n * tracer.selfHitOffset(p), dirs.data(), 256, trace::kInfinity, t.data(), back.data());
                int backs = 0;
                for (std::uint8_t x : back) backs += x;
                if (backs > limit) used[v] = 0;
            }
        }, 64);
        for (char u : used) q.hiddenVertices += u ? 0 : 1;
    }

    // Crease vertices: an adjacent face turns more than 30 degrees from the vertex normal. There one value
    // must serve faces that see different hemispheres, and a reference at the vertex is ambiguous.
    std::vector<char> crease(mesh.positions.size(), 0);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* v = &mesh.indices[3 * t];
        const Vec3 nf = normalize(cross(mesh.positions[v[1]] - mesh.positions[v[0]], mesh.positions[v[2]] - mesh.positions[v[0]]));
        for (int k = 0; k < 3; ++k)
            if (dot(nf, normalize(normal[v[k]])) < 0.866f) crease[v[k]] = 1;
    }
    const int channels = settings.channels();
    const auto nc = std::size_t(channels);
    std::vector<float> reference(baked.size(), 1.0f), point(baked.size(), 1.0f);
    for (int c = 0; c < channels; ++c) {
        trace::ObscuranceSettings os;
        os.falloff = trace::Falloff::Exponential;
        os.halfDistance = settings.distances[std::size_t(c)];
        os.rays = referenceRays;
        os.seed = settings.seed ^ 0x5eed0001u;
        const trace::ObscuranceEstimator dense(tracer, os);
        os.rays = settings.rays;
        os.seed = settings.seed ^ 0x5eed0002u;
        const trace::ObscuranceEstimator sparse(tracer, os);
        parallelFor(mesh.positions.size(), [&](std::size_t b, std::size_t e) {
            for (std::size_t v = b; v < e; ++v) {
                const Vec3 n = normalize(normal[v]);
                if (!used[v]) continue;
                reference[v * nc + std::size_t(c)] = dense(mesh.positions[v], n, n, std::uint32_t(v));
                point[v * nc + std::size_t(c)] = sparse(mesh.positions[v], n, n, std::uint32_t(v));
            }
        }, 64);
    }
    for (int c = 0; c < channels; ++c) {
        QualityChannel r;
        r.distance = double(settings.distances[std::size_t(c)]);
        std::size_t count = 0, smooth = 0;
        q.comparedVertices = 0;
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            if (!used[v]) continue;
            const std::size_t k = v * nc + std::size_t(c);
            const double ref = reference[k];
            const double eb = std::fabs(std::clamp(double(baked[k]), 0.0, 1.0) - ref), ep = std::fabs(double(point[k]) - ref);
            r.bakedMae += eb;
            r.pointMae += ep;
            if (!crease[v]) {
                r.bakedSmoothMae += eb;
                r.pointSmoothMae += ep;
                ++smooth;
            }
            r.bakedMax = std::max(r.bakedMax, eb);
            r.pointMax = std::max(r.pointMax, ep);
            ++count;
        }
        q.comparedVertices = count;
        q.smoothVertices = smooth;
        r.bakedSmoothMae /= double(std::max<std::size_t>(smooth, 1));
        r.pointSmoothMae /= double(std::max<std::size_t>(smooth, 1));
        r.bakedMae /= double(std::max<std::size_t>(count, 1));
        r.pointMae /= double(std::max<std::size_t>(count, 1));
        r.bakedJump = gradientJump(mesh, baked, channels, c);
        r.pointJump = gradientJump(mesh, point, channels, c);
        r.referenceJump = gradientJump(mesh, reference, channels, c);
        q.channels.push_back(r);
    }
    q.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return q;
}

} // namespace obscura::bake
