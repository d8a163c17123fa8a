// Triangle meshes and the scenes built from them: meshes placed by instances with world transforms.
#pragma once

#include "obscura/math.h"

#include <cstdint>
#include <string>
#include <vector>

namespace obscura {

// The farthest a scene's geometry may lie from the origin, in object and in world space, m. Embree asserts on a
// ray whose origin lies beyond about 1.8e18 (its FLT_LARGE), in world space or carried into an instance's
// object space: a corrupt glTF's translation of 9.2e18 aborted the process. 1e12 m is beyond any scene (the
// Earth is 1.5e11 m from the Sun) and leaves a factor of 1e6 for cameras placed away from it
// (kMaxCameraCoordinate, camera.h) and for rays carried into scaled-down instances.
inline constexpr float kMaxSceneCoordinate = 1e12f;

struct Bounds {
    Vec3 lo{1e30f, 1e30f, 1e30f};
    Vec3 hi{-1e30f, -1e30f, -1e30f};
    bool empty() const { return lo.x > hi.x; }
    void extend(Vec3 p) { lo = min(lo, p); hi = max(hi, p); }
    Vec3 center() const { return (lo + hi) * 0.5f; }
    Vec3 size() const { return empty() ? Vec3{} : hi - lo; }
};

// Indexed triangle mesh in its own object space. Counter-clockwise triangles face their normal.
struct Mesh {
    std::string name;
    std::vector<Vec3> positions;          // object space, m
    std::vector<Vec3> normals;            // unit, one per position; empty until computed or loaded
    std::vector<std::uint32_t> indices;   // 3 per triangle, each < positions.size()
    Vec3 baseColor{0.8f, 0.8f, 0.8f};     // linear albedo, [0,1]

    std::size_t triangleCount() const { return indices.size() / 3; }
    Bounds bounds() const;
};

struct Instance {
    std::uint32_t mesh = 0;   // index into Scene::meshes
    Mat4 worldFromObject;     // any affine transform, mirroring allowed
    std::string name;
};

struct Scene {
    std::vector<Mesh> meshes;
    std::vector<Instance> instances;

    // Adds a mesh and one instance of it; returns the mesh index.
    std::uint32_t add(Mesh mesh, const Mat4& worldFromObject = Mat4::identity());
    Bounds bounds() const;                  // world-space bounds over all instances
    std::size_t triangleCount() const;      // over all instances
};

// Fills mesh.normals with area-and-angle weighted vertex normals where they are missing (size mismatch).
void computeSmoothNormals(Mesh& mesh);

// Removes triangles with repeated indices or (near) zero area; returns how many were removed.
std::size_t removeDegenerateTriangles(Mesh& mesh);

// The checks every loader and builder ends with: at least one triangle over all meshes, indices in range,
// finite positions and normals, every position within kMaxSceneCoordinate of the origin in its mesh's space
// and in the world, instances pointing at existing meshes. Degenerate triangles are dropped
// and counted in *dropped. Throws obscura::Error("<what>: <problem>").
void sanitizeScene(Scene& scene, const std::string& what, std::size_t* dropped = nullptr);
// sanitizeScene's checks that change nothing (indices, instances, finite positions, normals and transforms, the
// coordinate bound), which trace::Tracer and bake::bakeScene make on a scene they are given: one built by hand
// and never sanitized was read past its meshes' ends. O(vertices).
void checkScene(const Scene& scene, const std::string& what);

} // namespace obscura
