// A deterministic synthetic game level for scale tests: rolling terrain, buildings with interior walls and
// floors, and instanced props. Sized by a triangle budget so benchmarks can ask for 1M or 10M triangles.
#include "obscura/builtin_scenes.h"

#include "obscura/error.h"
#include "obscura/mesh_builder.h"
#include "obscura/sampling.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace obscura {

namespace {

struct Random {
    std::uint32_t state;
    float next() { return toUnitFloat(state = hash32(state + 0x9e3779b9u)); }
    float range(float lo, float hi) { return lo + (hi - lo) * next(); }
};

float terrainHeight(float x, float z) {
    return 1.5f * std::sin(0.05f * x) * std::cos(0.043f * z) + 0.4f * std::sin(0.21f * x + 0.13f * z);
}

} // namespace

void checkLevelTriangles(const std::string& flag, long long triangles) {
    if (triangles < kMinLevelTriangles || triangles > kMaxLevelTriangles)
        fail(flag, "must be in [" + std::to_string(kMinLevelTriangles) + ", " + std::to_string(kMaxLevelTriangles) +
                       "], got " + std::to_string(triangles));
}

Scene generateLevel(std::size_t triangles, std::uint32_t seed) {
    triangles = std::max<std::size_t>(triangles, std::size_t(kMinLevelTriangles));
    Scene scene;
    Random rng{hash32(seed)};
    const float half = 150.0f;

    // About half the budget is terrain: an n x n grid has 2 n^2 triangles.
    int n = std::max(8, int(std::sqrt(double(triangles) * 0.5 / 2.0)));
    Mesh terrain;
    terrain.name = "terrain";
    terrain.baseColor = {0.35f, 0.45f, 0.25f};
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            float x = -half + 2 * half * float(i) / float(n), z = -half + 2 * half * float(j) / float(n);
            terrain.positions.push_back({x, terrainHeight(x, z), z});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            auto a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n + 1), d = c + 1;
            terrain.indices.insert(terrain.indices.end(), {a, c, b, b, c, d});
        }
    std::size_t used = terrain.triangleCount();
    scene.add(std::move(terrain));

    // A quarter in buildings: walls, floor slabs and interior partitions are boxes of 12 triangles.
    Mesh buildings;
    buildings.name = "buildings";
    buildings.baseColor = {0.7f, 0.66f, 0.6f};
    std::size_t buildingBudget = triangles / 4;
    while (buildings.triangleCount() + 200 < buildingBudget) {
        float cx = rng.range(-half * 0.8f, half * 0.8f), cz = rng.range(-half * 0.8f, half * 0.8f);
        float w = rng.range(6, 16), d = rng.range(6, 16);
        int floors = 1 + int(rng.next() * 4);
        float y0 = terrainHeight(cx, cz) - 0.5f, t = 0.25f, storey = 3.0f;
        for (int f = 0; f < floors; ++f) {
            float y = y0 + storey * float(f);
            build::addBox(buildings, {cx - w / 2, y, cz - d / 2}, {cx + w / 2, y + t, cz + d / 2});  // slab
        }
        // Walls and partition rise through every storey in one box each: boxes stacked per storey would
        // leave coincident, opposite-facing faces (duplicate triangles) at every storey boundary.
        const float top = y0 + storey * float(floors);
        build::addBox(buildings, {cx - w / 2, y0, cz - d / 2}, {cx - w / 2 + t, top, cz + d / 2});  // walls
        build::addBox(buildings, {cx + w / 2 - t, y0, cz - d / 2}, {cx + w / 2, top, cz + d / 2});
        build::addBox(buildings, {cx - w / 2, y0, cz - d / 2}, {cx + w / 2, top, cz - d / 2 + t});
        build::addBox(buildings, {cx - w / 2, y0, cz + d / 2 - t}, {cx - 0.5f, top, cz + d / 2});  // door gap
        build::addBox(buildings, {cx + 0.5f, y0, cz + d / 2 - t}, {cx + w / 2, top, cz + d / 2});
        build::addBox(buildings, {cx - t / 2, y0, cz - d / 2}, {cx + t / 2, top, cz});              // partition
        build::addBox(buildings, {cx - w / 2, y0 + storey * float(floors), cz - d / 2},
                      {cx + w / 2, y0 + storey * float(floors) + t, cz + d / 2});  // roof
    }
    used += buildings.triangleCount();
    scene.add(std::move(buildings));

    // The rest in instanced props: a rock (sphere) and a crate, placed on the terrain.
    Mesh rock;
    rock.name = "rock";
    rock.baseColor = {0.5f, 0.48f, 0.45f};
    build::addSphere(rock, {0, 0, 0}, 1.0f, 32, 16);
    Mesh crate;
    crate.name = "crate";
    crate.baseColor = {0.55f, 0.4f, 0.25f};
    build::addBox(crate, {-0.5f, 0, -0.5f}, {0.5f, 1, 0.5f});
    std::size_t rockTriangles = rock.triangleCount(), crateTriangles = crate.triangleCount();
    scene.meshes.push_back(std::move(rock));
    scene.meshes.push_back(std::move(crate));
    auto rockMesh = std::uint32_t(scene.meshes.size() - 2), crateMesh = rockMesh + 1;
    for (std::uint32_t i = 0; used < triangles; ++i) {
        float x = rng.range(-half, half), z = rng.range(-half, half), y = terrainHeight(x, z);
        bool isRock = (i % 3) != 0;
        float s = isRock ? rng.range(0.3f, 1.5f) : rng.range(0.5f, 1.2f);
        Mat4 xf = Mat4::translation({x, y - (isRock ? 0.3f * s : 0.0f), z}) *
                  Mat4::rotation({0, 1, 0}, rng.range(0, 2 * kPi)) * Mat4::scale(Vec3(s));
        scene.instances.push_back({isRock ? rockMesh : crateMesh, xf, isRock ? "rock" : "crate"});
        used += isRock ? rockTriangles : crateTriangles;
    }
    computeSmoothNormals(scene.meshes[0]);
    return scene;
}

} // namespace obscura
