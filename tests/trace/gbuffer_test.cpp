// Primary rays: G-buffer geometry against the analytic plane, determinism of the estimator, built-in scenes.
#include "obscura/builtin_scenes.h"
#include "obscura/mesh_builder.h"
#include "obscura/parallel.h"
#include "obscura/scene.h"
#include "obscura/trace.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace obscura;
using namespace obscura::trace;

TEST(GBuffer, PlaneSeenAtAnAngle) {
    BuiltinScene s = makeBuiltinScene("plane");
    Tracer tracer(s.scene);
    Camera cam = s.camera;
    cam.position = {1.5f, 2.0f, 4.0f};
    cam.target = {-1.0f, 0.0f, -3.0f};
    cam.width = 160;
    cam.height = 90;
    GBuffer g = renderGBuffer(tracer, cam);
    // The plane y = 0 in view space: normal R * (0,1,0), through the view-space image of the world origin.
    Mat4 viewFromWorld = cam.viewFromWorld();
    Vec3 nView = normalize(transformVector(viewFromWorld, {0, 1, 0}));
    Vec3 origin = transformPoint(viewFromWorld, {0, 0, 0});
    int surface = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            if (g.isSky(x, y)) continue;
            ++surface;
            Vec3 p = g.viewPosition(x, y);
            ASSERT_LE(std::fabs(dot(p - origin, nView)), 1e-4f * length(p)) << x << "," << y;
            Vec3 n = g.viewNormal(x, y);
            ASSERT_LE(length(n - nView), 1e-5f) << x << "," << y;
            ASSERT_NEAR(g.albedo.at(x, y, 0), s.scene.meshes[0].baseColor.x, 1e-6);
        }
    EXPECT_GT(surface, cam.width * cam.height / 2);
}

TEST(GBuffer, SkyIsInfiniteWithZeroNormal) {
    BuiltinScene s = makeBuiltinScene("plane");
    Tracer tracer(s.scene);
    Camera cam = s.camera;
    cam.position = {0, 1, 0};
    cam.target = {0, 2, -1};  // looking up: nothing but sky
    cam.width = 8;
    cam.height = 6;
    GBuffer g = renderGBuffer(tracer, cam);
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x) {
            EXPECT_TRUE(std::isinf(g.depth.at(x, y)));
            EXPECT_EQ(length(g.viewNormal(x, y)), 0.0f);
        }
}

TEST(GBuffer, EstimatorIsDeterministicAcrossThreadCounts) {
    BuiltinScene s = makeBuiltinScene("demo");
    Tracer tracer(s.scene);
    Camera cam = s.camera;
    cam.width = 64;
    cam.height = 36;
    GBuffer g = renderGBuffer(tracer, cam);
    ObscuranceSettings settings;
    settings.radius = 1.0f;
    settings.rays = 16;
    settings.seed = 42;
    Image many = ambientObscurance(tracer, g, settings);
    Image one;
    {
        ThreadLimit limit(1);
        one = ambientObscurance(tracer, g, settings);
    }
    ASSERT_EQ(one.pixels.size(), many.pixels.size());
    EXPECT_EQ(std::memcmp(one.pixels.data(), many.pixels.data(), one.pixels.size() * sizeof(float)), 0);
    settings.seed = 43;
    Image other = ambientObscurance(tracer, g, settings);
    EXPECT_NE(std::memcmp(other.pixels.data(), many.pixels.data(), one.pixels.size() * sizeof(float)), 0);
}

TEST(GBuffer, SupersamplingKeepsDepthAndAveragesAlbedo) {
    BuiltinScene s = makeBuiltinScene("spheres");
    Tracer tracer(s.scene);
    Camera cam = s.camera;
    cam.width = 48;
    cam.height = 27;
    GBuffer g1 = renderGBuffer(tracer, cam);
    GBufferSettings gs;
    gs.supersample = 3;
    GBuffer g3 = renderGBuffer(tracer, cam, gs);
    EXPECT_EQ(std::memcmp(g1.depth.pixels.data(), g3.depth.pixels.data(), g1.depth.pixels.size() * sizeof(float)), 0);
    int differ = 0;
    for (std::size_t i = 0; i < g1.albedo.pixels.size(); ++i) differ += g1.albedo.pixels[i] != g3.albedo.pixels[i];
    EXPECT_GT(differ, 0);  // sphere silhouettes against the floor blend
}

// A sky pixel's albedo is (0, 0, 0) (GBuffer): with supersampling, a sky pixel beside a silhouette took the
// mean albedo of its sub-samples that hit (0.8 on 52 pixels of a lone sphere at 160x90).
TEST(GBuffer, SupersampledSkyKeepsZeroAlbedo) {
    Scene scene;
    Mesh sphere;
    build::addSphere(sphere, {0, 0, 0}, 1.0f, 32, 16);
    scene.add(std::move(sphere));
    Tracer tracer(scene);
    Camera cam;
    cam.position = {0, 0, 4};
    cam.target = {0, 0, 0};
    cam.width = 160;
    cam.height = 90;
    GBufferSettings gs;
    gs.supersample = 4;
    const GBuffer g = renderGBuffer(tracer, cam, gs);
    int sky = 0, surface = 0;
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            const float r = g.albedo.at(x, y, 0), gr = g.albedo.at(x, y, 1), b = g.albedo.at(x, y, 2);
            if (g.isSky(x, y)) {
                ++sky;
                EXPECT_TRUE(r == 0.0f && gr == 0.0f && b == 0.0f) << "sky pixel " << x << "," << y << ": " << r;
            } else {
                ++surface;
            }
        }
    EXPECT_GT(sky, 1000);
    EXPECT_GT(surface, 1000);
}

// Normals are optional in a Scene: a mesh built from positions and indices alone crashed the tracer, which
// read its shading normal. It now shades with the geometric normal.
TEST(GBuffer, AMeshWithoutNormalsShadesWithItsGeometricNormal) {
    Scene scene;
    Mesh m;
    m.positions = {{-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}};
    m.indices = {0, 1, 2, 0, 2, 3};
    scene.add(std::move(m));
    ASSERT_TRUE(scene.meshes[0].normals.empty());
    Tracer tracer(scene);
    Camera cam;
    cam.position = {0, 2, 0.01f};
    cam.target = {0, 0, 0};
    cam.width = cam.height = 8;
    const GBuffer g = renderGBuffer(tracer, cam);
    ASSERT_FALSE(g.isSky(4, 4));
    const Vec3 world = transformVector(cam.worldFromView(), g.viewNormal(4, 4));
    EXPECT_NEAR(world.y, 1.0f, 1e-5f);
}

TEST(BuiltinScenes, WindingAgreesWithNormals) {
    // The geometric normal from the winding and the interpolated normal must agree on every triangle,
    // or AO hemispheres and ray offsets would point into surfaces.
    for (const std::string& name : builtinSceneNames()) {
        BuiltinScene s = makeBuiltinScene(name);
        EXPECT_FALSE(s.description.empty());
        EXPECT_GT(s.scene.triangleCount(), 0u);
        for (const Mesh& m : s.scene.meshes)
            for (std::size_t t = 0; t < m.triangleCount(); ++t) {
                const std::uint32_t* i = &m.indices[3 * t];
                Vec3 ng = cross(m.positions[i[1]] - m.positions[i[0]], m.positions[i[2]] - m.positions[i[0]]);
                Vec3 ns = m.normals[i[0]] + m.normals[i[1]] + m.normals[i[2]];
                ASSERT_GT(dot(ng, ns), 0.0f) << name << " mesh " << m.name << " triangle " << t;
            }
        EXPECT_NO_THROW(s.camera.validate()) << name;
    }
}

TEST(BuiltinScenes, GeneratedLevelHitsItsBudget) {
    Scene level = generateLevel(200000, 3);
    EXPECT_GE(level.triangleCount(), 200000u);
    EXPECT_LT(level.triangleCount(), 200000u * 11 / 10);
    Scene again = generateLevel(200000, 3);
    EXPECT_EQ(again.triangleCount(), level.triangleCount());
    EXPECT_EQ(again.instances.back().worldFromObject.m[0][3], level.instances.back().worldFromObject.m[0][3]);
}

// A double-sided copy of a scene (each face listed again with the opposite winding, over the same vertices) is
// seen as the scene itself: the same G-buffer normals and the same obscurance. Its vertex normals once cancelled
// to the up vector, which turned every wall's shading normal along the wall.
TEST(GBuffer, DoubleSidedMeshesSeeLikeSingleSided) {
    BuiltinScene single = makeBuiltinScene("demo");
    BuiltinScene twice = single;
    for (Mesh& m : single.scene.meshes) {
        m.normals.clear();
        computeSmoothNormals(m);
    }
    for (Mesh& m : twice.scene.meshes) {
        const std::size_t count = m.indices.size();
        for (std::size_t t = 0; t < count; t += 3)
            m.indices.insert(m.indices.end(), {m.indices[t + 2], m.indices[t + 1], m.indices[t]});
        m.normals.clear();
        computeSmoothNormals(m);
    }
    Camera cam = single.camera;
    cam.width = 64;
    cam.height = 36;
    Tracer a(single.scene), b(twice.scene);
    GBuffer ga = renderGBuffer(a, cam), gb = renderGBuffer(b, cam);
    float worstNormal = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            ASSERT_EQ(ga.isSky(x, y), gb.isSky(x, y)) << x << "," << y;
            if (!ga.isSky(x, y)) worstNormal = std::max(worstNormal, length(ga.viewNormal(x, y) - gb.viewNormal(x, y)));
        }
    EXPECT_LE(worstNormal, 1e-4f);
    ObscuranceSettings settings;
    settings.radius = 1.0f;
    settings.rays = 32;
    const Image aoA = ambientObscurance(a, ga, settings), aoB = ambientObscurance(b, gb, settings);
    double diff = 0;
    for (std::size_t i = 0; i < aoA.pixels.size(); ++i) diff += std::fabs(double(aoA.pixels[i]) - double(aoB.pixels[i]));
    EXPECT_LE(diff / double(aoA.pixels.size()), 1e-3);
}
