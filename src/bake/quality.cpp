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

namespace {

float distanceToBounds(const Bounds& b, Vec3 p) {
    const Vec3 d = max(max(b.lo - p, p - b.hi), Vec3{});
    return length(d);
}

struct Refiner {
    float maxEdge, grading;
    Bounds focus;
    Mesh* out;

    std::size_t* budget;  // triangles left over all meshes

    void split(const Vec3 p[3], const Vec3 n[3], int depth) {
        const float longest = std::max({length(p[1] - p[0]), length(p[2] - p[1]), length(p[0] - p[2])});
        float d = std::min({distanceToBounds(focus, p[0]), distanceToBounds(focus, p[1]), distanceToBounds(focus, p[2])});
        // A triangle straddling the focus box has all corners outside it but is close: use its centre too.
        d = std::min(d, distanceToBounds(focus, (p[0] + p[1] + p[2]) / 3.0f));
        if (longest <= maxEdge * (1.0f + grading * d) || depth >= 20) {
            // Slivers that touch the focus along their whole length (a fan of 1 km triangles around a hole)
            // would split without end; stop with a message instead of exhausting memory.
            if ((*budget)-- == 0)
                fail("--max-edge", "refinement would exceed 20 M triangles; use a larger edge or more grading");
            const auto base = std::uint32_t(out->positions.size());
            for (int k = 0; k < 3; ++k) {
                out->positions.push_back(p[k]);
                out->normals.push_back(n[k]);
            }
            out->indices.insert(out->indices.end(), {base, base + 1, base + 2});
            return;
        }
        const Vec3 m[3] = {(p[0] + p[1]) * 0.5f, (p[1] + p[2]) * 0.5f, (p[2] + p[0]) * 0.5f};
        const Vec3 mn[3] = {normalize(n[0] + n[1]), normalize(n[1] + n[2]), normalize(n[2] + n[0])};
        const Vec3 t0[3] = {p[0], m[0], m[2]}, n0[3] = {n[0], mn[0], mn[2]};
        const Vec3 t1[3] = {m[0], p[1], m[1]}, n1[3] = {mn[0], n[1], mn[1]};
        const Vec3 t2[3] = {m[2], m[1], p[2]}, n2[3] = {mn[2], mn[1], n[2]};
        const Vec3 t3[3] = {m[0], m[1], m[2]}, n3[3] = {mn[0], mn[1], mn[2]};
        split(t0, n0, depth + 1);
        split(t1, n1, depth + 1);
        split(t2, n2, depth + 1);
        split(t3, n3, depth + 1);
    }
};

} // namespace

Bounds refinementFocus(const Scene& scene, float largest) {
    Bounds focus;
    for (const Instance& inst : scene.instances) {
        Scene one;
        one.meshes.push_back(scene.meshes[inst.mesh]);
        one.instances.push_back({0, inst.worldFromObject, {}});
        const Bounds b = one.bounds();
        if (length(b.size()) <= largest) {
            focus.extend(b.lo);
            focus.extend(b.hi);
        }
    }
    return focus.empty() ? scene.bounds() : focus;
}

Scene refineScene(const Scene& scene, float maxEdge, const Bounds& focus, float grading) {
    // A NaN, zero or negative edge ran 20 s and 1.6 GB into the triangle budget, whose message advised a larger
    // edge.
    if (!(maxEdge > 0.0f) || !std::isfinite(maxEdge))
        fail("refineScene", "maxEdge must be a finite length > 0 m, got " + numberText(maxEdge));
    if (!(grading >= 0.0f) || !std::isfinite(grading))
        fail("refineScene", "grading must be a finite value >= 0 per m, got " + numberText(grading));
    std::size_t budget = 20000000;
    Scene out;
    out.instances = scene.instances;
    for (std::size_t mi = 0; mi < scene.meshes.size(); ++mi) {
        const Mesh& mesh = scene.meshes[mi];
        Mesh m;
        m.name = mesh.name;
        m.baseColor = mesh.baseColor;
        // The focus is in world space; a mesh placed once is refined as placed (instanced meshes with the
        // first instance's transform, which is what matters for the built-in scenes' small props).
        Mat4 objectFromWorld = Mat4::identity();
        for (const Instance& inst : scene.instances)
            if (inst.mesh == mi) {
                invert(inst.worldFromObject, objectFromWorld);
                break;
            }
        Bounds local;
        for (int c = 0; c < 8; ++c)
            local.extend(transformPoint(objectFromWorld, {(c & 1) ? focus.hi.x : focus.lo.x, (c & 2) ? focus.hi.y : focus.lo.y,
                                                          (c & 4) ? focus.hi.z : focus.lo.z}));
        Refiner r{maxEdge, grading, local, &m, &budget};
        const bool normals = mesh.normals.size() == mesh.positions.size();
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const std::uint32_t* v = &mesh.indices[3 * t];
            const Vec3 p[3] = {mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]};
            const Vec3 face = normalize(cross(p[1] - p[0], p[2] - p[0]));
            const Vec3 n[3] = {normals ? mesh.normals[v[0]] : face, normals ? mesh.normals[v[1]] : face,
                               normals ? mesh.normals[v[2]] : face};
            r.split(p, n, 0);
        }
        out.meshes.push_back(std::move(m));
    }
    return out;
}

QualityResult compareWithDense(const Scene& scene, const BakeSettings& settings, int referenceRays) {
    settings.validate();
    if (settings.mode != Mode::Obscurance) fail("compare", "the dense comparison is for obscurance mode");
    // Before the bake, not after it as ObscuranceSettings::validate did, naming "ao-rays".
    if (referenceRays < 1 || referenceRays > (1 << 20))
        fail("compareWithDense", "referenceRays must be in [1, 1048576], got " + std::to_string(referenceRays));
    const auto start = std::chrono::steady_clock::now();
    QualityResult q;
    q.referenceRays = referenceRays;
    const WeldedMesh mesh = weldScene(scene, settings.weldDistance(scene.bounds()), settings.creaseAngle);
    const SampleSet samples = generateSamples(mesh, settings);
    const trace::Tracer tracer(scene);
    const RayResults rays = traceSamples(tracer, samples, settings);
    const std::vector<float> baked = solveVertexValues(mesh, samples, rays, settings.alpha);
    q.vertices = mesh.positions.size();
    q.triangles = mesh.triangleCount();
    q.samples = samples.size();

    // Vertex normals of the welded vertices (crease copies included); used ones only.
    std::vector<Vec3> normal(mesh.positions.size(), Vec3{});
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        const Mesh& m = scene.meshes[inst.mesh];
        // A mesh without normals (Mesh::normals is empty until computed) was read past their end; its vertices
        // take their faces' normals below, as crease copies do.
        if (m.normals.size() != m.positions.size()) continue;
        const Mat4 nm = normalMatrix(inst.worldFromObject);
        for (std::size_t v = 0; v < m.positions.size(); ++v)
            normal[mesh.vertexMap[mesh.instanceFirst[i] + v]] += normalize(transformVector(nm, m.normals[v]));
    }
    // A crease copy no file vertex maps to (the file shares one vertex across the crease) takes the summed
    // normals of its own faces: the side it stands for.
    {
        std::vector<Vec3> faceSum(mesh.positions.size(), Vec3{});
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const std::uint32_t* v = &mesh.indices[3 * t];
            const Vec3 nf = normalize(cross(mesh.positions[v[1]] - mesh.positions[v[0]], mesh.positions[v[2]] - mesh.positions[v[0]]));
            for (int k = 0; k < 3; ++k) faceSum[v[k]] += nf;
        }
        for (std::size_t v = 0; v < normal.size(); ++v)
            if (normal[v] == Vec3{}) normal[v] = faceSum[v];
    }
    // Where the estimators look from: the vertex moved 1% of the way towards the centroid of its largest face,
    // a point on that face, so a crease copy is measured on its own side (the one-sided limit the bake's value
    // stands for), with that face's normal for the rays' offset. Exactly on a contact line (a riser's foot on the
    // floor) rays from the vertex itself start inside the floor's plane and pass through it; 1% of a 0.1 m edge
    // changes obscurance by far less than 1e-3. (Towards the mean of its faces' centroids, the point lay below
    // every face of a convex surface: on a sphere 8e-6 m inside, past the 3.9e-6 m offset, so two thirds of the
    // spheres scene's vertices were judged hidden, and the rest had references of 0.)
    std::vector<Vec3> at = mesh.positions, faceNormal(mesh.positions.size(), Vec3{});
    {
        std::vector<float> largest(mesh.positions.size(), 0.0f);
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const std::uint32_t* v = &mesh.indices[3 * t];
            const Vec3 a = mesh.positions[v[0]], b = mesh.positions[v[1]], c = mesh.positions[v[2]];
            const Vec3 cr = cross(b - a, c - a);
            const float area = length(cr);
            const Vec3 centroid = (a + b + c) * (1.0f / 3.0f);
            for (int k = 0; k < 3; ++k)
                if (area > largest[v[k]]) {
                    largest[v[k]] = area;
                    at[v[k]] = mesh.positions[v[k]] + (centroid - mesh.positions[v[k]]) * 0.01f;
                    faceNormal[v[k]] = cr * (1.0f / area);
                }
        }
    }
    // A vertex is compared only where one of its faces has a valid sample: a vertex whose faces were all
    // invalidated (a face hidden inside other geometry, split from its visible neighbours at a crease) has
    // a fill value the bake never shows, like the invalid samples themselves.
    std::vector<char> used(mesh.positions.size(), 0);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        bool valid = false;
        for (std::uint32_t k = samples.triangleFirst[t]; k < samples.triangleFirst[t + 1] && !valid; ++k) valid = rays.valid[k] != 0;
        if (valid)
            for (std::size_t k = 0; k < 3; ++k) used[mesh.indices[3 * t + k]] = 1;
    }
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
                const Vec3 p = at[v];
                // The offset along the face's normal, on n's side; a welded vertex lies up to its weldShift off
                // the surface traced.
                const Vec3 ng = dot(faceNormal[v], n) < 0.0f ? -faceNormal[v] : faceNormal[v];
                stream.closestHits(p + ng * (tracer.selfHitOffset(p, ng) + mesh.weldShift[v]), dirs.data(), 256,
                                   trace::kInfinity, t.data(), back.data());
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
                reference[v * nc + std::size_t(c)] = dense(at[v], n, faceNormal[v], std::uint32_t(v));
                point[v * nc + std::size_t(c)] = sparse(at[v], n, faceNormal[v], std::uint32_t(v));
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
            const double value = std::clamp(double(baked[k]), 0.0, 1.0);
            const double eb = std::fabs(value - ref), ep = std::fabs(double(point[k]) - ref);
            r.bakedMae += eb;
            r.pointMae += ep;
            if (!crease[v]) {
                r.bakedSmoothMae += eb;
                r.pointSmoothMae += ep;
                ++smooth;
            }
            if (eb > r.bakedMax || count == 0) {
                r.bakedMax = eb;
                r.bakedMaxAt = mesh.positions[v];
                r.bakedMaxValue = value;
                r.bakedMaxReference = ref;
            }
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
