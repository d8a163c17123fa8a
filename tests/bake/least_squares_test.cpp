// Least-squares vertex baking (Kavan et al. 2011) on hand-made signals with exact expected values: no ray
// is traced, the sample values are written straight into RayResults.
#include "obscura/bake.h"
#include "obscura/error.h"

#include "bake/bake_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace obscura;
using namespace obscura::bake;

namespace {

struct Staged {
    WeldedMesh mesh;
    SampleSet samples;
    RayResults results;
};

Staged stage(const Scene& scene, const BakeSettings& settings) {
    Staged s;
    s.mesh = weldScene(scene, settings.weldTolerance * length(scene.bounds().size()), settings.creaseAngle);
    s.samples = generateSamples(s.mesh, settings);
    s.results.channels = settings.channels();
    s.results.values.assign(s.samples.size() * std::size_t(s.results.channels), 0.0f);
    s.results.valid.assign(s.samples.size(), 1);
    return s;
}

// The linear function's value at a sample, from its barycentrics and the exact values at the corners, in
// double, so the data are exactly linear over each face.
template <class F>
float atSample(const Staged& s, std::size_t k, F f) {
    const std::uint32_t t = s.samples.triangles[k];
    const double l1 = s.samples.barycentrics[k].x, l2 = s.samples.barycentrics[k].y;
    const Vec3 p0 = s.mesh.positions[s.mesh.indices[3 * t]], p1 = s.mesh.positions[s.mesh.indices[3 * t + 1]],
               p2 = s.mesh.positions[s.mesh.indices[3 * t + 2]];
    return float((1 - l1 - l2) * f(p0) + l1 * f(p1) + l2 * f(p2));
}

Scene irregularPlane() {
    Scene scene;
    scene.add(fixtures::grid(-3, 3, -2, 2, 0, 12, false, 0.35f));
    return scene;
}

// A linear function with float-exact values: the data stay exactly linear after rounding to float.
double linearA(Vec3 p) { return 0.5 + 0.0625 * double(p.x) - 0.03125 * double(p.z); }
double linearB(Vec3 p) { return 0.25 - 0.125 * double(p.x) + 0.0625 * double(p.z); }

} // namespace

TEST(LeastSquares, LinearSignalIsReproducedForAnyAlpha) {
    // On a flat mesh the unfolded gradient of a linear function is the same on both sides of every edge,
    // so R x = 0, and the data term is zero at the exact vertex values: they minimise for every alpha.
    // What is left is rounding (double solve; the data are rounded to float, whose error at |f| < 1 is
    // below 6e-8) and the 1e-9 relative pull to the mean: well under 1e-6.
    Scene scene = irregularPlane();
    BakeSettings settings;
    Staged s = stage(scene, settings);
    // Rounding to float would break linearity; the functions above are linear in the positions, and the
    // barycentric combination is evaluated in double and rounded once.
    for (std::size_t k = 0; k < s.samples.size(); ++k) {
        s.results.values[2 * k] = atSample(s, k, linearA);
        s.results.values[2 * k + 1] = atSample(s, k, linearB);
    }
    for (float alpha : {0.0f, 0.01f, 1.0f, 100.0f, 1e4f}) {
        std::vector<float> x = solveVertexValues(s.mesh, s.samples, s.results, alpha);
        double worst = 0;
        for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) {
            worst = std::max(worst, std::fabs(double(x[2 * v]) - linearA(s.mesh.positions[v])));
            worst = std::max(worst, std::fabs(double(x[2 * v + 1]) - linearB(s.mesh.positions[v])));
        }
        EXPECT_LT(worst, 1e-6) << "alpha " << alpha;
    }
}

TEST(LeastSquares, ConstantStaysConstantOnFoldedMeshWithInvalidSamples) {
    // A box on a floor (folded edges, where R does not vanish for linear signals but does for constants),
    // a third of the samples invalid: every vertex must still get the constant.
    Scene scene;
    scene.add(fixtures::grid(-2, 2, -2, 2, 0, 8));
    Mesh box;
    {
        Vec3 lo{-0.5f, 0, -0.5f}, hi{0.5f, 1, 0.5f};
        Vec3 p[8];
        for (int i = 0; i < 8; ++i) p[i] = {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
        box.positions.assign(p, p + 8);
        box.indices = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
    }
    scene.add(std::move(box));
    BakeSettings settings;
    Staged s = stage(scene, settings);
    for (std::size_t k = 0; k < s.samples.size(); ++k) {
        s.results.values[2 * k] = 0.7f;
        s.results.values[2 * k + 1] = 0.2f;
        s.results.valid[k] = k % 3 != 0;
    }
    for (float alpha : {0.0f, 1.0f, 100.0f}) {
        std::vector<float> x = solveVertexValues(s.mesh, s.samples, s.results, alpha);
        for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) {
            EXPECT_NEAR(x[2 * v], 0.7f, 1e-6f) << "vertex " << v << " alpha " << alpha;
            EXPECT_NEAR(x[2 * v + 1], 0.2f, 1e-6f) << "vertex " << v << " alpha " << alpha;
        }
    }
}

TEST(LeastSquares, TriangleSoupEqualsIndexedMesh) {
    // The same bumpy surface as an indexed mesh and as soup (three vertices of its own per face): welding
    // gives the same connectivity, the samples depend only on face ids and positions, so the solve sees the
    // same system with its unknowns in another order. Values agree to rounding; 1e-5 is the bound asked.
    Mesh indexed = fixtures::grid(-2, 2, -2, 2, 0, 10, false, 0.3f);
    for (Vec3& p : indexed.positions) p.y = 0.3f * std::sin(1.3f * p.x) * std::cos(0.9f * p.z);
    Mesh soup;
    for (std::uint32_t i : indexed.indices) {
        soup.indices.push_back(std::uint32_t(soup.positions.size()));
        soup.positions.push_back(indexed.positions[i]);
    }
    Scene a, b;
    a.add(indexed);
    b.add(soup);
    BakeSettings settings;
    Staged sa = stage(a, settings), sb = stage(b, settings);
    ASSERT_EQ(sa.mesh.positions.size(), indexed.positions.size());
    ASSERT_EQ(sb.mesh.positions.size(), indexed.positions.size());
    ASSERT_EQ(sa.samples.size(), sb.samples.size());
    auto signal = [](Vec3 p) { return 0.5f + 0.4f * std::sin(2.0f * p.x + p.y) * std::cos(1.5f * p.z); };
    for (Staged* s : {&sa, &sb})
        for (std::size_t k = 0; k < s->samples.size(); ++k) {
            s->results.values[2 * k] = signal(s->samples.positions[k]);
            s->results.values[2 * k + 1] = 1.0f - signal(s->samples.positions[k]);
        }
    std::vector<float> xa = solveVertexValues(sa.mesh, sa.samples, sa.results, 1.0f);
    std::vector<float> xb = solveVertexValues(sb.mesh, sb.samples, sb.results, 1.0f);
    // Compare per file vertex: soup vertex i is corner i of the face list, indexed vertex indices[i].
    for (std::size_t i = 0; i < indexed.indices.size(); ++i) {
        const std::uint32_t va = sa.mesh.vertexMap[indexed.indices[i]], vb = sb.mesh.vertexMap[i];
        for (int c = 0; c < 2; ++c) EXPECT_NEAR(xa[2 * va + std::size_t(c)], xb[2 * vb + std::size_t(c)], 1e-5f);
    }
}

TEST(LeastSquares, RegulariserSmoothsNoise) {
    // Noise on a constant: a larger alpha must bring the vertices closer to the constant (the edge term
    // penalises gradient jumps, which noise creates), while alpha = 0 fits the noise.
    Scene scene = irregularPlane();
    BakeSettings settings;
    Staged s = stage(scene, settings);
    for (std::size_t k = 0; k < s.samples.size(); ++k) {
        float noise = (toUnitFloat(hash32(std::uint32_t(k))) - 0.5f) * 0.2f;
        s.results.values[2 * k] = 0.5f + noise;
        s.results.values[2 * k + 1] = 0.5f;
    }
    auto spread = [&](float alpha) {
        std::vector<float> x = solveVertexValues(s.mesh, s.samples, s.results, alpha);
        double sum = 0;
        for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) sum += std::pow(double(x[2 * v]) - 0.5, 2);
        return std::sqrt(sum / double(s.mesh.positions.size()));
    };
    double rough = spread(0.0f), smooth = spread(10.0f);
    EXPECT_LT(smooth, 0.5 * rough) << "rms deviation alpha 0: " << rough << ", alpha 10: " << smooth;
}

TEST(Weld, SoupWeldsAndCountsNewlyDegenerateFaces) {
    // Two faces; the second has two corners 1e-9 m apart, which welding merges, so it is dropped.
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, -1}, {1, 0, 0}, {1, 0, -1}, {1, 0, -1.0f + 1e-7f}};
    m.indices = {0, 1, 2, 3, 4, 5};
    Scene scene;
    scene.add(m);
    WeldedMesh w = weldScene(scene, 1e-5f);
    EXPECT_EQ(w.inputTriangles, 2u);
    EXPECT_EQ(w.droppedTriangles, 1u);
    EXPECT_EQ(w.triangleCount(), 1u);
    EXPECT_EQ(w.positions.size(), 4u);          // (1,0,0) twice and (1,0,-1) twice collapse
    EXPECT_EQ(w.vertexMap[1], w.vertexMap[3]);  // file order kept in the map
    EXPECT_EQ(w.vertexMap[4], w.vertexMap[5]);
    // How far each welded vertex's file vertices moved to join it: exact duplicates not at all.
    ASSERT_EQ(w.weldShift.size(), w.positions.size());
    EXPECT_EQ(w.weldShift[w.vertexMap[0]], 0.0f);
    EXPECT_EQ(w.weldShift[w.vertexMap[1]], 0.0f);
    EXPECT_EQ(w.weldShift[w.vertexMap[4]], m.positions[5].z - m.positions[4].z);
}

// Faces are judged degenerate against their own instance's extent, as removeDegenerateTriangles judges a
// mesh: against the scene's diagonal, a 12 mm part of 3 mm cells lost all 32 of its faces beside a 1 m^2
// quad 1000 km away, and the quad its 2 (its vertices then bake as open), even with no weld tolerance.
TEST(Weld, ASmallPartBesideAFarObjectKeepsItsFaces) {
    Scene scene;
    scene.add(fixtures::grid(-0.006f, 0.006f, -0.006f, 0.006f, 0.0f, 4));
    Mesh far;
    far.positions = {{1e6f, 0, 1}, {1e6f + 1, 0, 1}, {1e6f + 1, 0, 0}, {1e6f, 0, 0}};
    far.indices = {0, 1, 2, 0, 2, 3};
    scene.add(far);
    for (float tolerance : {0.0f, 1e-6f}) {
        const WeldedMesh w = weldScene(scene, tolerance);
        EXPECT_EQ(w.droppedTriangles, 0u) << "tolerance " << tolerance;
        EXPECT_EQ(w.triangleCount(), 34u);
    }
}

TEST(Samples, CountsAreClampedAndAreaProportional) {
    // Faces of area 0.02, 2 and 200 m^2 at 4 samples/m^2: 3 (the minimum), ceil(8) = 8, and 32 (the cap).
    Scene scene;
    Mesh m;
    auto tri = [&](float s, float x) {
        auto b = std::uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), {{x, 0, 0}, {x + s, 0, 0}, {x, 0, -s}});
        m.indices.insert(m.indices.end(), {b, b + 1, b + 2});
    };
    tri(0.2f, 0);    // 0.02
    tri(2.0f, 10);   // 2
    tri(20.0f, 20);  // 200
    scene.add(m);
    BakeSettings settings;
    WeldedMesh w = weldScene(scene, 0);
    SampleSet s = generateSamples(w, settings);
    ASSERT_EQ(s.triangleFirst.size(), 4u);
    EXPECT_EQ(s.triangleFirst[1] - s.triangleFirst[0], 3u);
    EXPECT_EQ(s.triangleFirst[2] - s.triangleFirst[1], 8u);
    EXPECT_EQ(s.triangleFirst[3] - s.triangleFirst[2], 32u);
    for (std::size_t k = 0; k < s.size(); ++k) {
        Vec2 l = s.barycentrics[k];
        EXPECT_GE(l.x, 0.0f);
        EXPECT_GE(l.y, 0.0f);
        EXPECT_LE(l.x + l.y, 1.0f);
        EXPECT_NEAR(s.normals[k].y, 1.0f, 1e-6f);
    }
}

TEST(Samples, CountPast32BitsFailsBeforeAllocating) {
    // 2^20 + 1 faces at 4096 samples each: 2^32 + 4096 samples, which a 32-bit running total wrapped to 4096
    // before the per-face writes ran past the arrays; 2^20 faces (exactly 2^32) is the first count too many.
    // The faces share three vertices: the count alone matters, and it must fail before ~150 GB of samples.
    for (std::size_t faces : {std::size_t(1) << 20, (std::size_t(1) << 20) + 1}) {
        WeldedMesh w;
        w.positions = {{0, 0, 0}, {100, 0, 0}, {0, 0, -100}};  // 5000 m^2: the cap decides
        w.indices.resize(3 * faces);
        for (std::size_t i = 0; i < w.indices.size(); ++i) w.indices[i] = std::uint32_t(i % 3);
        BakeSettings settings;
        settings.minSamplesPerFace = settings.maxSamplesPerFace = 4096;
        const std::string count = std::to_string(std::uint64_t(faces) * 4096u);
        try {
            generateSamples(w, settings);
            ADD_FAILURE() << faces << " faces: no error";
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(count + " samples"), std::string::npos) << message;
            EXPECT_NE(message.find("--max-samples-per-face"), std::string::npos) << message;
        }
    }
}

TEST(Samples, SliverNormalIsUnitInDouble) {
    // Three nearly collinear float points whose float cross product is exactly zero while the weld's
    // double area test keeps the face: its samples once got the normal (0, 0, 0), so their rays started
    // on the surface and went nowhere. A floor below sets the scene's size for the weld's area floor.
    Mesh m;
    m.positions = {{-0.192421168f, -0.706987262f, -0.245998502f}, {0.78435421f, 0.212644503f, 0.00793144014f},
                   {1.76112962f, 1.1322763f, 0.261861384f},        {-2, -1, -2}, {2, -1, -2}, {2, -1, 2}, {-2, -1, 2}};
    m.indices = {0, 1, 2, 3, 6, 5, 3, 5, 4};
    Scene scene;
    scene.add(m);
    WeldedMesh w = weldScene(scene, 0.0f, 180.0f);
    ASSERT_EQ(w.triangleCount(), 3u) << "the weld keeps the sliver";
    BakeSettings settings;
    settings.minSamplesPerFace = settings.maxSamplesPerFace = 1;
    SampleSet s = generateSamples(w, settings);
    ASSERT_EQ(s.size(), 3u);
    // The reference: the cross product of the float positions' edges in long double.
    const Vec3 p0 = m.positions[0], p1 = m.positions[1], p2 = m.positions[2];
    using Long = long double;
    const Long u[3] = {Long(p1.x) - Long(p0.x), Long(p1.y) - Long(p0.y), Long(p1.z) - Long(p0.z)};
    const Long v[3] = {Long(p2.x) - Long(p0.x), Long(p2.y) - Long(p0.y), Long(p2.z) - Long(p0.z)};
    const Long c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const Long l = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    ASSERT_GT(l, 0.0L);
    for (std::size_t k = 0; k < s.size(); ++k) {
        const Vec3 n = s.normals[k];
        // Unit to float rounding of each component: 1e-6.
        EXPECT_NEAR(double(length(n)), 1.0, 1e-6) << "sample " << k << " on face " << s.triangles[k];
        if (s.triangles[k] == 0) {
            // The same direction as the reference to float rounding: 1e-6 per component.
            EXPECT_NEAR(double(n.x), double(c[0] / l), 1e-6);
            EXPECT_NEAR(double(n.y), double(c[1] / l), 1e-6);
            EXPECT_NEAR(double(n.z), double(c[2] / l), 1e-6);
        } else {
            EXPECT_NEAR(double(n.y), 1.0, 1e-6) << "floor faces +Y";
        }
    }
}
