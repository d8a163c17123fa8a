// A deterministic synthetic game level for scale tests: rolling terrain, buildings with interior walls and
// floors, and instanced props. Sized by a triangle budget so benchmarks can ask for 1M or 10M triangles.
#include "obscura/builtin_scenes.h"

#include "obscura/error.h"
#include "obscura/mesh_builder.h"
#include "obscura/sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>
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

namespace {

// The terrain as triangulated: an n x n grid over [-half, half]^2, each cell split along its (i+1, j)-(i, j+1)
// diagonal. Heights read from it, not from terrainHeight, are where the mesh is: between its vertices the two
// differ by up to a few centimetres, enough for a crate to float.
struct TerrainGrid {
    int n;
    float half;
    float cell() const { return 2 * half / float(n); }
    float vertexHeight(int i, int j) const {
        return terrainHeight(-half + cell() * float(i), -half + cell() * float(j));
    }
    float height(float x, float z) const {
        const float gx = std::clamp((x + half) / cell(), 0.0f, float(n)), gz = std::clamp((z + half) / cell(), 0.0f, float(n));
        const int i = std::min(int(gx), n - 1), j = std::min(int(gz), n - 1);
        const float u = gx - float(i), v = gz - float(j);
        const float a = vertexHeight(i, j), b = vertexHeight(i + 1, j), c = vertexHeight(i, j + 1), d = vertexHeight(i + 1, j + 1);
        return u + v <= 1 ? a + u * (b - a) + v * (c - a) : d + (1 - u) * (c - d) + (1 - v) * (b - d);
    }
    // Least and greatest height over [x0, x1] x [z0, z1]. The mesh is planar per triangle, so its extremes there
    // lie at the rectangle's corners, at grid vertices inside, or where the rectangle's sides cross the grid lines
    // and the cells' diagonals: each is sampled.
    std::pair<float, float> range(float x0, float x1, float z0, float z1) const {
        float lo = std::numeric_limits<float>::infinity(), hi = -lo;
        const auto sample = [&](float x, float z) {
            if (!(x >= x0 && x <= x1 && z >= z0 && z <= z1)) return;
            const float h = height(x, z);
            lo = std::min(lo, h);
            hi = std::max(hi, h);
        };
        const auto lines = [&](float a0, float a1) {  // a0, a1 and the grid lines between
            std::vector<float> at{a0, a1};
            for (float g = std::ceil((a0 + half) / cell()); -half + g * cell() < a1; g += 1) at.push_back(-half + g * cell());
            return at;
        };
        for (float x : lines(x0, x1))
            for (float z : lines(z0, z1)) sample(x, z);
        // The diagonal of cell (i, j) is u + v = 1: a side x = const crosses it at v = 1 - u in each row of cells.
        for (float x : {x0, x1}) {
            const float u = (x + half) / cell() - std::floor((x + half) / cell());
            for (float g = std::floor((z0 + half) / cell()); -half + g * cell() <= z1; g += 1)
                sample(x, -half + (g + 1 - u) * cell());
        }
        for (float z : {z0, z1}) {
            const float v = (z + half) / cell() - std::floor((z + half) / cell());
            for (float g = std::floor((x0 + half) / cell()); -half + g * cell() <= x1; g += 1)
                sample(-half + (g + 1 - v) * cell(), z);
        }
        return {lo, hi};
    }
};

// Footprints placed so far, by the cells of a coarse grid they touch: a new building is tried against its
// neighbours only.
class Footprints {
public:
    explicit Footprints(float cellSize) : cell_(cellSize) {}
    bool overlaps(float x0, float x1, float z0, float z1) const {
        for (long long cx = key(x0); cx <= key(x1); ++cx)
            for (long long cz = key(z0); cz <= key(z1); ++cz) {
                auto it = cells_.find({cx, cz});
                if (it == cells_.end()) continue;
                for (std::size_t r : it->second) {
                    const Rect& o = rects_[r];
                    if (x0 < o.x1 && o.x0 < x1 && z0 < o.z1 && o.z0 < z1) return true;
                }
            }
        return false;
    }
    void add(float x0, float x1, float z0, float z1) {
        rects_.push_back({x0, x1, z0, z1});
        for (long long cx = key(x0); cx <= key(x1); ++cx)
            for (long long cz = key(z0); cz <= key(z1); ++cz) cells_[{cx, cz}].push_back(rects_.size() - 1);
    }

private:
    struct Rect {
        float x0, x1, z0, z1;
    };
    long long key(float v) const { return static_cast<long long>(std::floor(v / cell_)); }
    float cell_;
    std::vector<Rect> rects_;
    std::map<std::pair<long long, long long>, std::vector<std::size_t>> cells_;
};

} // namespace

Scene generateLevel(std::size_t triangles, std::uint32_t seed) {
    triangles = std::max<std::size_t>(triangles, std::size_t(kMinLevelTriangles));
    Scene scene;
    Random rng{hash32(seed)};
    // The level grows with its budget at a constant density: about 1.1 buildings (114 triangles each on average)
    // per 1000 m^2 of the inner area and a terrain cell of about 3.5 m. On a fixed 300 m square, buildings
    // overlapped ever more as the budget rose: 52% of their surface lay inside other buildings at 1 M triangles.
    const float half = std::max(60.0f, 0.88f * float(std::sqrt(double(triangles))));

    // About half the budget is terrain: an n x n grid has 2 n^2 triangles.
    const int n = std::max(8, int(std::sqrt(double(triangles) * 0.5 / 2.0)));
    const TerrainGrid grid{n, half};
    Mesh terrain;
    terrain.name = "terrain";
    terrain.baseColor = {0.35f, 0.45f, 0.25f};
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            terrain.positions.push_back({-half + grid.cell() * float(i), grid.vertexHeight(i, j), -half + grid.cell() * float(j)});
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            auto a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n + 1), d = c + 1;
            terrain.indices.insert(terrain.indices.end(), {a, c, b, b, c, d});
        }
    std::size_t used = terrain.triangleCount();
    scene.add(std::move(terrain));

    // A quarter in buildings: walls, floor slabs, an interior partition and a roof, each a box of 12 triangles.
    // Boxes only touch: the walls rise through the roof and slabs, which fill the interior between them, so no two
    // faces facing the same way lie in one plane (a rasterizer would z-fight them, and a bake sample them twice).
    Mesh buildings;
    buildings.name = "buildings";
    buildings.baseColor = {0.7f, 0.66f, 0.6f};
    const std::size_t buildingBudget = triangles / 4;
    const float t = 0.25f, storey = 3.0f, gap = 2.0f;  // wall thickness, storey height, least street width (m)
    Footprints placed(32.0f);
    for (int misses = 0; buildings.triangleCount() + 200 < buildingBudget && misses < 100;) {
        const float cx = rng.range(-half * 0.8f, half * 0.8f), cz = rng.range(-half * 0.8f, half * 0.8f);
        const float w = rng.range(6, 16), d = rng.range(6, 16);
        const int floors = 1 + int(rng.next() * 4);
        const float x0 = cx - w / 2, x1 = cx + w / 2, z0 = cz - d / 2, z1 = cz + d / 2;
        if (placed.overlaps(x0 - gap, x1 + gap, z0 - gap, z1 + gap)) {
            ++misses;
            continue;
        }
        misses = 0;
        placed.add(x0, x1, z0, z1);
        // Seated on the terrain as meshed: the walls start half a metre under its lowest point on the footprint
        // and the ground floor's top lies above its highest, so no gap opens under a wall and the terrain does not
        // show through the floor. (From the centre's height alone, walls hung up to 0.77 m above a slope.)
        const auto [low, high] = grid.range(x0, x1, z0, z1);
        const float base = low - 0.5f, ground = high + 0.1f, top = ground + storey * float(floors);
        const float ix0 = x0 + t, ix1 = x1 - t, iz0 = z0 + t, iz1 = z1 - t;  // the interior
        build::addBox(buildings, {ix0, base, iz0}, {ix1, ground, iz1});           // ground floor
        for (int f = 1; f < floors; ++f) {
            const float y = ground + storey * float(f);
            build::addBox(buildings, {ix0, y - t, iz0}, {ix1, y, iz1});           // upper floors
        }
        build::addBox(buildings, {ix0, top - t, iz0}, {ix1, top, iz1});           // roof
        build::addBox(buildings, {x0, base, z0}, {ix0, top + t, z1});             // side walls, full depth
        build::addBox(buildings, {ix1, base, z0}, {x1, top + t, z1});
        build::addBox(buildings, {ix0, base, z0}, {ix1, top + t, iz0});           // back wall, between them
        build::addBox(buildings, {ix0, base, iz1}, {cx - 0.5f, top + t, z1});     // front wall, door gap
        build::addBox(buildings, {cx + 0.5f, base, iz1}, {ix1, top + t, z1});
        build::addBox(buildings, {cx - t / 2, ground, iz0}, {cx + t / 2, top - t, cz});  // partition, floor to roof
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
    const std::size_t rockTriangles = rock.triangleCount(), crateTriangles = crate.triangleCount();
    scene.meshes.push_back(std::move(rock));
    scene.meshes.push_back(std::move(crate));
    auto rockMesh = std::uint32_t(scene.meshes.size() - 2), crateMesh = rockMesh + 1;
    for (std::uint32_t i = 0; used < triangles;) {
        const float x = rng.range(-half, half), z = rng.range(-half, half);
        // Crates close the budget: a last rock overshot it by up to 960 triangles (4000 gave 4742).
        const bool isRock = (i % 3) != 0 && triangles - used >= rockTriangles;
        const float s = isRock ? rng.range(0.3f, 1.5f) : rng.range(0.5f, 1.2f), angle = rng.range(0, 2 * kPi);
        // Props stand in the open, not in a building.
        if (placed.overlaps(x - s, x + s, z - s, z + s)) continue;
        ++i;
        float y = grid.height(x, z) - 0.3f * s;  // a rock sits a third of its radius deep
        if (!isRock) {
            // A crate rests on the lowest of its base corners, so none floats on a slope (from its centre's height,
            // 121 of 130 crates had a corner 1 cm to 12 cm up); the uphill side sinks in.
            y = std::numeric_limits<float>::infinity();
            const float c = std::cos(angle) * 0.5f * s, sn = std::sin(angle) * 0.5f * s;
            for (const auto& [u, v] : {std::pair{1.0f, 1.0f}, std::pair{1.0f, -1.0f}, std::pair{-1.0f, 1.0f},
                                       std::pair{-1.0f, -1.0f}})
                y = std::min(y, grid.height(x + c * u + sn * v, z - sn * u + c * v));
        }
        const Mat4 xf = Mat4::translation({x, y, z}) * Mat4::rotation({0, 1, 0}, angle) * Mat4::scale(Vec3(s));
        scene.instances.push_back({isRock ? rockMesh : crateMesh, xf, isRock ? "rock" : "crate"});
        used += isRock ? rockTriangles : crateTriangles;
    }
    computeSmoothNormals(scene.meshes[0]);
    return scene;
}

} // namespace obscura
