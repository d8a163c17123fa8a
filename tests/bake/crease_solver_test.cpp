// Crease splitting in the weld (smoothing groups by dihedral angle) and the two sparse solvers of the
// least-squares bake (CHOLMOD supernodal Cholesky, Eigen SimplicialLDLT) on the same system.
#include "obscura/bake.h"
#include "obscura/error.h"

#include "bake/bake_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
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

// A flat (n x n)-cell grid of `cell`-metre squares, turned by 0.37 rad about x and 0.61 rad about z and moved
// to `offset`: coplanar faces whose float vertices put their float normals ~1e-7 apart.
Scene tiltedGrid(int n, double cell, Vec3 offset) {
    Mesh m;
    const double ax = 0.37, az = 0.61;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double x = i * cell, y = 0, z = -j * cell;
            const double y1 = y * std::cos(ax) - z * std::sin(ax), z1 = y * std::sin(ax) + z * std::cos(ax);
            const double x2 = x * std::cos(az) - y1 * std::sin(az), y2 = x * std::sin(az) + y1 * std::cos(az);
            m.positions.push_back({float(x2 + double(offset.x)), float(y2 + double(offset.y)), float(z1 + double(offset.z))});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const auto a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n) + 2, d = a + std::uint32_t(n) + 1;
            m.indices.insert(m.indices.end(), {a, b, d, b, c, d});
        }
    Scene scene;
    scene.add(m);
    return scene;
}

// A floor and two fins 10 degrees apart on one shared edge (0, 1), the three faces in the order given.
Scene floorAndFins(const std::array<int, 3>& order) {
    const float s = std::sin(10.0f * 3.14159265f / 180.0f), c = std::cos(10.0f * 3.14159265f / 180.0f);
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 0, -1}, {0.5f, 1, 0}, {0.5f, c, s}};
    const std::uint32_t faces[3][3] = {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}};  // floor, fin, fin
    for (int f : order) m.indices.insert(m.indices.end(), faces[f], faces[f] + 3);
    Scene scene;
    scene.add(m);
    return scene;
}

} // namespace

TEST(Crease, CoplanarFacesAreNeverSplit) {
    // In float, cos(0.01 degrees) is 1 and the normals of these coplanar faces agree to ~1e-7 only, so
    // crease angles of 0.01 degrees and below once split a flat grid (121 vertices) into 168. Near the
    // origin and 1 km away (where a vertex rounds by ~6e-5 m): one vertex per grid point, exactly.
    for (const Vec3 offset : {Vec3{0.123f, 0.456f, 0.789f}, Vec3{1000.0f, -500.0f, 250.0f}})
        for (const float crease : {0.0f, 0.001f, 0.01f, 1.0f, 60.0f}) {
            const WeldedMesh w = weldScene(tiltedGrid(10, offset.x > 100 ? 0.5 : 0.1, offset), 0.0f, crease);
            EXPECT_EQ(w.triangleCount(), 200u);
            EXPECT_EQ(w.positions.size(), 121u) << "crease " << crease << " offset " << offset.x;
        }
}

TEST(Crease, SmallCreaseAnglesStillSplitRealFolds) {
    // The rounding slack (~1e-6 rad here) must not swallow a real fold: at a crease angle of 0.01 degrees a
    // 0.05-degree fold splits (6 -> 8 vertices) and a 0.005-degree one does not; at 0, a 0.05-degree fold splits.
    EXPECT_EQ(weldScene(fold(0.05f), 0.0f, 0.01f).positions.size(), 8u);
    EXPECT_EQ(weldScene(fold(0.005f), 0.0f, 0.01f).positions.size(), 6u);
    EXPECT_EQ(weldScene(fold(0.05f), 0.0f, 0.0f).positions.size(), 8u);
}

TEST(Crease, GroupsDoNotDependOnFaceOrder) {
    // Crease 60: the fins (10 degrees apart) join, the floor (80 and 90 degrees from them) stays apart, so the
    // shared edge's two vertices get two copies each: 5 + 2 = 7 vertices in any order. Comparing only the
    // edge's first face with the others gave 9 with the floor first (the fins never compared) and 7 last.
    std::array<int, 3> order{0, 1, 2};
    do {
        const WeldedMesh w = weldScene(floorAndFins(order), 0.0f, 60.0f);
        ASSERT_EQ(w.triangleCount(), 3u);
        EXPECT_EQ(w.positions.size(), 7u) << "order " << order[0] << order[1] << order[2];
        // Corners 0 and 1 of each face are the shared edge's; the fins' copies agree, the floor's differ.
        std::array<std::size_t, 3> slot{};  // face (0 floor, 1 and 2 fins) -> its triangle in w
        for (std::size_t t = 0; t < 3; ++t) slot[std::size_t(order[t])] = t;
        for (std::size_t k = 0; k < 2; ++k) {
            EXPECT_EQ(w.indices[3 * slot[1] + k], w.indices[3 * slot[2] + k]);
            EXPECT_NE(w.indices[3 * slot[0] + k], w.indices[3 * slot[1] + k]);
        }
    } while (std::next_permutation(order.begin(), order.end()));
}

// Copies of a face on one edge (a non-manifold file: the same triangle listed again and again) join each other
// and whatever the one of most slack joins, so they are united before the pairs are compared (every pair took
// the square of the copies' count in time: 40000 copies of one triangle, 9.4 s; now 0.16 s, measured with
// obscura bake, not here). What this holds is that the shortcut keeps the groups of the three faces above:
// crease 60, fins together (7 vertices); crease 5, all apart (5 + 2 + 2 = 9).
TEST(Crease, StackedCopiesOnOneEdgeGroupAsTheirFaceDoes) {
    for (const int copies : {1, 2, 50}) {
        Scene scene = floorAndFins({2, 0, 1});
        Mesh& m = scene.meshes[0];
        const std::vector<std::uint32_t> once = m.indices;
        for (int c = 1; c < copies; ++c) m.indices.insert(m.indices.end(), once.begin(), once.end());
        for (const auto& [crease, vertices] : {std::pair{60.0f, 7u}, std::pair{5.0f, 9u}}) {
            const WeldedMesh w = weldScene(scene, 0.0f, crease);
            ASSERT_EQ(w.triangleCount(), 3u * std::size_t(copies));
            EXPECT_EQ(w.positions.size(), vertices) << copies << " copies, crease " << crease;
            for (std::size_t t = 3; t < w.triangleCount(); ++t)
                for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(w.indices[3 * t + k], w.indices[3 * (t % 3) + k]);
        }
    }
}

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

// A file vertex on both sides of a crease is one output value: the mean of its copies weighted by the area of
// its faces in each. The fold's edge vertex 0 has one floor face (0.5 m^2) and both wall faces (1 m^2), vertex
// 1 the other way round; the vertices off the edge are in one copy and blend nothing.
TEST(Crease, AFileVertexOnBothSidesBlendsItsCopiesByArea) {
    const WeldedMesh w = weldScene(fold(90.0f), 0.0f, 60.0f);
    ASSERT_EQ(w.blends.size(), 4u);
    for (std::uint32_t file : {0u, 1u}) {
        const auto first = std::find_if(w.blends.begin(), w.blends.end(), [&](const WeldedMesh::Blend& b) { return b.file == file; });
        ASSERT_NE(first, w.blends.end());
        ASSERT_EQ(first[1].file, file);
        EXPECT_NE(first[0].copy, first[1].copy);
        // The floor's copy: the floor's faces come first in the file, and vertexMap holds the first face's copy.
        const std::uint32_t floorCopy = w.vertexMap[file];
        const WeldedMesh::Blend& floorPart = first[0].copy == floorCopy ? first[0] : first[1];
        const WeldedMesh::Blend& wallPart = first[0].copy == floorCopy ? first[1] : first[0];
        EXPECT_FLOAT_EQ(floorPart.weight, file == 0 ? 0.5f : 1.0f) << "file vertex " << file;
        EXPECT_FLOAT_EQ(wallPart.weight, file == 0 ? 1.0f : 0.5f) << "file vertex " << file;
    }
    EXPECT_TRUE(weldScene(fold(90.0f), 0.0f, 180.0f).blends.empty());  // welded across: one copy each
}

// A cube of 8 shared corners (a PLY's, or an OBJ's without normals) 1 cm above a floor: each corner's faces
// fall into three copies. Its output was the copy of whichever face came first in the file, so the bottom
// corners baked about 0.7 (a side's) or about 0 (the bottom's, facing the floor 1 cm away) as the bottom
// face came last or first. With the blend, both orders give the same value to the sampling noise: bound
// 0.05, against differences of 0.3 or more before.
TEST(Crease, ACubesSharedCornersDoNotDependOnFaceOrder) {
    auto bake = [](bool bottomFirst) {
        Mesh cube;
        cube.positions = {{0, 0.01f, 0}, {1, 0.01f, 0}, {1, 0.01f, -1}, {0, 0.01f, -1},
                          {0, 1.01f, 0}, {1, 1.01f, 0}, {1, 1.01f, -1}, {0, 1.01f, -1}};
        const std::vector<std::uint32_t> bottom = {0, 3, 2, 0, 2, 1};
        const std::vector<std::uint32_t> sides = {4, 5, 6, 4, 6, 7,   // top
                                                  0, 1, 5, 0, 5, 4,   // front (+z side at z = 0)
                                                  1, 2, 6, 1, 6, 5,   // right
                                                  2, 3, 7, 2, 7, 6,   // back
                                                  3, 0, 4, 3, 4, 7};  // left
        if (bottomFirst) cube.indices = bottom;
        cube.indices.insert(cube.indices.end(), sides.begin(), sides.end());
        if (!bottomFirst) cube.indices.insert(cube.indices.end(), bottom.begin(), bottom.end());
        Scene scene;
        scene.add(fixtures::grid(-10, 10, -10, 10, 0, 4));
        scene.add(std::move(cube));
        BakeSettings settings;
        settings.distances = {0.5f, 2.0f};
        settings.rays = 256;
        settings.minSamplesPerFace = settings.maxSamplesPerFace = 32;
        const BakeResult r = bakeScene(scene, settings);
        return std::vector<float>(r.values.begin() + std::ptrdiff_t(2 * r.instanceFirst[1]), r.values.end());
    };
    const std::vector<float> first = bake(true), last = bake(false);
    ASSERT_EQ(first.size(), 16u);
    ASSERT_EQ(last.size(), 16u);
    for (std::size_t i = 0; i < 16; ++i) EXPECT_NEAR(first[i], last[i], 0.05f) << "corner " << i / 2 << " channel " << i % 2;
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
