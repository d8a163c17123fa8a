// Crease splitting in the weld (smoothing groups by dihedral angle) and the two sparse solvers of the
// least-squares bake (CHOLMOD supernodal Cholesky, Eigen SimplicialLDLT) on the same system.
#include "obscura/bake.h"
#include "obscura/error.h"

#include "bake/bake_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace obscura;
using namespace obscura::bake;

namespace {

// Two unit squares sharing the edge x = 0 (file vertices 0 and 1 shared by both), the second turned up by
// `angle` degrees about that edge: a fold with that dihedral angle between the face normals.
Scene fold(float angleDegrees) {
    const float a = angleDegrees * 3.14159265f / 180.0f;
    Mesh m;
    // Floor: x in [-1, 0], facing +Y. Wall: from the edge along (cos a, sin a) in x-y.
    m.positions = {{0, 0, 0}, {0, 0, -1}, {-1, 0, 0}, {-1, 0, -1}, {std::cos(a), std::sin(a), 0}, {std::cos(a), std::sin(a), -1}};
    m.indices = {2, 0, 1, 2, 1, 3,   // floor, counter-clockwise from +Y
                 0, 4, 5, 0, 5, 1};  // second face, front side turning with it
    Scene scene;
    scene.add(m);
    return scene;
}

} // namespace

TEST(Crease, SplitsOnlyPastTheCreaseAngle) {
    // 90 degrees > 60: the shared edge's two file vertices get one copy per side (6 -> 8 vertices), the file
    // vertex maps to the copy of the first face using it (the floor), and no interior edge crosses the fold.
    {
        WeldedMesh w = weldScene(fold(90.0f), 0.0f, 60.0f);
        EXPECT_EQ(w.positions.size(), 8u);
        EXPECT_EQ(w.triangleCount(), 4u);
        EXPECT_EQ(w.vertexMap[0], w.indices[1]);  // floor's first face, corner 1 is file vertex 0
        EXPECT_EQ(w.vertexMap[1], w.indices[2]);
        EXPECT_NE(w.vertexMap[0], w.indices[6]);  // the wall's copy of the same position is another vertex
        EXPECT_EQ(w.positions[w.indices[6]], w.positions[w.vertexMap[0]]);
    }
    // 30 degrees < 60, and any angle with the split turned off (180): one vertex per position.
    EXPECT_EQ(weldScene(fold(30.0f), 0.0f, 60.0f).positions.size(), 6u);
    EXPECT_EQ(weldScene(fold(90.0f), 0.0f, 180.0f).positions.size(), 6u);
}

TEST(Crease, EachSideKeepsItsOwnValue) {
    // Signal 0.2 on the floor and 0.8 on the wall: split at the 90-degree fold, the least squares fit is
    // exactly piecewise constant (each side a constant, no edge across); welded, the edge vertices blend
    // the two and the fit cannot be exact. Tolerance: double solve, float data, 1e-9 pull: 1e-6.
    for (float crease : {60.0f, 180.0f}) {
        BakeSettings settings;
        WeldedMesh w = weldScene(fold(90.0f), 0.0f, crease);
        SampleSet s = generateSamples(w, settings);
        RayResults r;
        r.channels = 1;
        r.valid.assign(s.size(), 1);
        for (std::size_t k = 0; k < s.size(); ++k) r.values.push_back(s.triangles[k] < 2 ? 0.2f : 0.8f);
        std::vector<float> x = solveVertexValues(w, s, r, 1.0f);
        double worst = 0;
        for (std::size_t t = 0; t < w.triangleCount(); ++t)
            for (int k = 0; k < 3; ++k)
                worst = std::max(worst, std::fabs(double(x[w.indices[3 * t + std::size_t(k)]]) - (t < 2 ? 0.2 : 0.8)));
        if (crease < 180.0f)
            EXPECT_LT(worst, 1e-6) << "split";
        else
            EXPECT_GT(worst, 0.05) << "welded across the fold";
    }
}

TEST(Crease, SettingIsValidated) {
    BakeSettings s;
    s.creaseAngle = -1.0f;
    EXPECT_THROW(s.validate(), Error);
    s.creaseAngle = 181.0f;
    EXPECT_THROW(s.validate(), Error);
    s.creaseAngle = std::nanf("");
    EXPECT_THROW(s.validate(), Error);
}

TEST(LinearSolvers, CholmodMatchesSimplicialLdlt) {
    // The same system (a bumpy, folded mesh, a smooth signal, a third of the samples invalid) through both
    // factorisations; both are direct solves of a well-conditioned SPD matrix in double, so the float
    // results agree to rounding: 1e-6 is the bound asked.
    if (!cholmodAvailable()) GTEST_SKIP() << "this build has no CHOLMOD";
    Mesh m = fixtures::grid(-2, 2, -2, 2, 0, 24, false, 0.3f);
    for (Vec3& p : m.positions) p.y = 0.3f * std::sin(1.3f * p.x) * std::cos(0.9f * p.z);
    Scene scene;
    scene.add(m);
    BakeSettings settings;
    WeldedMesh w = weldScene(scene, 1e-6f, settings.creaseAngle);
    SampleSet s = generateSamples(w, settings);
    RayResults r;
    r.channels = 2;
    for (std::size_t k = 0; k < s.size(); ++k) {
        const Vec3 p = s.positions[k];
        const float f = 0.5f + 0.4f * std::sin(2.0f * p.x + p.y) * std::cos(1.5f * p.z);
        r.values.insert(r.values.end(), {f, 1.0f - f * f});
        r.valid.push_back(k % 3 != 0);
    }
    for (float alpha : {0.0f, 1.0f, 100.0f}) {
        std::vector<float> a = solveVertexValues(w, s, r, alpha, nullptr, LinearSolver::Cholmod);
        std::vector<float> b = solveVertexValues(w, s, r, alpha, nullptr, LinearSolver::SimplicialLDLT);
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-6f) << "value " << i << " alpha " << alpha;
    }
}
