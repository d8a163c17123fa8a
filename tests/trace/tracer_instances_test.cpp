// The Tracer's placement of instances: shared meshes become Embree instances, except where Embree cannot
// trace one (a singular transform) or a mesh has nothing left to place (every triangle degenerate).
#include "obscura/mesh_builder.h"
#include "obscura/scene.h"
#include "obscura/trace.h"

#include <gtest/gtest.h>

namespace obscura::trace {
namespace {

// A 2 x 2 m quad in the plane z = 0, facing +Z, centred on the origin.
Mesh unitQuad() {
    Mesh m;
    build::addQuad(m, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0});
    return m;
}

// A mesh placed twice, the second time by a singular transform (a glTF node with "scale": [1, 1, 0] does this):
// Embree asserted on any ray against such an instance, aborting the program. It is flattened into world space
// instead, where the transform's image is traced as it is: the quad in z = 0 squashed along z is the same quad,
// and squashed along y or to a point it is a zero-area pair of triangles that nothing hits.
TEST(TracerInstances, SingularTransformOfASharedMeshIsTraced) {
    struct Case {
        Mat4 squash;
        bool seen;  // whether the squashed instance still has area, in z = 0
    };
    for (const Case& c : {Case{Mat4::scale({1, 1, 0}), true}, Case{Mat4::scale({1, 0, 1}), false},
                          Case{Mat4::scale({0, 0, 0}), false},
                          Case{Mat4::translation({0, 0, -3}) * Mat4::scale({0, 1, 1}), false}}) {
        Scene scene;
        const std::uint32_t mesh = scene.add(unitQuad(), Mat4::translation({0, 0, -5}));
        scene.instances.push_back({mesh, c.squash, "squashed"});
        sanitizeScene(scene, "test");
        const Tracer tracer(scene);
        Hit hit;
        ASSERT_TRUE(tracer.intersect({0.25f, 0.25f, 5}, {0, 0, -1}, 0, 100, hit));
        EXPECT_EQ(hit.instance, c.seen ? 1u : 0u);
        EXPECT_NEAR(hit.t, c.seen ? 5.0f : 10.0f, 1e-5f);
        EXPECT_TRUE(tracer.occluded({0.25f, 0.25f, 5}, {0, 0, -1}, 0, 100));
        // Past the quad's edge nothing is hit, though the ray crosses the squashed instance's plane.
        EXPECT_FALSE(tracer.intersect({3, 3, 5}, {0, 0, -1}, 0, 100, hit));
    }
}

// A planar mesh squashed along its own normal keeps its area: glTF allows the node scale [1, 1, 0]. Its normals
// came from the identity (the inverse-transpose's fallback for a singular matrix), so under a rotation they
// stayed in object space: a quad laid down as the floor y = 0 faced +Z, and ray-traced AO above that open floor
// was 0.5 instead of 1.
TEST(TracerInstances, SquashedPlaneKeepsItsPlacedNormal) {
    for (float squash : {1.0f, 0.0f}) {
        Scene scene;
        const std::uint32_t mesh = scene.add(unitQuad(), Mat4::translation({0, 0, 50}));  // out of the way
        scene.instances.push_back(
            {mesh, Mat4::rotation({1, 0, 0}, -1.5707963f) * Mat4::scale({1, 1, squash}), "floor"});
        sanitizeScene(scene, "test");
        const Tracer tracer(scene);
        Hit hit;
        ASSERT_TRUE(tracer.intersect({0.25f, 3, -0.25f}, {0, -1, 0}, 0, 100, hit)) << squash;
        EXPECT_EQ(hit.instance, 1u);
        EXPECT_NEAR(hit.geometricNormal.y, 1.0f, 1e-5f) << squash;
        EXPECT_NEAR(tracer.shadingNormal(hit).y, 1.0f, 1e-5f) << squash;
    }
}

// A mesh whose only triangle is degenerate keeps no triangle after sanitizeScene. Embree refuses a geometry of
// no triangles, so the Tracer failed with "embree: allocating geometry failed" for the whole scene, placed
// once or shared. It now places nothing for it; instance numbers stay those of Scene::instances.
TEST(TracerInstances, MeshWithNoTrianglesLeftPlacesNothing) {
    for (int placements : {1, 2}) {
        Scene scene;
        Mesh flat;
        build::addQuad(flat, {-1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {-1, 0, 0});  // zero area
        const std::uint32_t empty = scene.add(std::move(flat));
        if (placements == 2) scene.instances.push_back({empty, Mat4::translation({0, 0, 1}), "again"});
        scene.add(unitQuad(), Mat4::translation({0, 0, -5}));
        std::size_t dropped = 0;
        sanitizeScene(scene, "test", &dropped);
        EXPECT_EQ(dropped, 2u);
        EXPECT_EQ(scene.meshes[empty].triangleCount(), 0u);
        const Tracer tracer(scene);
        Hit hit;
        ASSERT_TRUE(tracer.intersect({0.25f, 0.25f, 5}, {0, 0, -1}, 0, 100, hit)) << placements;
        EXPECT_EQ(hit.instance, std::uint32_t(placements));
        EXPECT_NEAR(hit.t, 10.0f, 1e-5f);
    }
}

} // namespace
} // namespace obscura::trace
