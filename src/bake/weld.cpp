// Pre-processing of triangle soup for the least-squares bake (Sloan et al. 2013 §2.1, "process geometry"):
// every instance flattened to world space, vertices welded by position so the solve sees the surface's
// connectivity, and faces that welding made degenerate dropped and counted. Welded vertices are then split
// along hard creases (one copy per smoothing group), so one value never has to serve two faces that see
// different hemispheres.
#include "obscura/bake.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace obscura::bake {

namespace {

// Cells of the weld grid, packed 21 bits per axis; positions lie inside the scene bounds, so cell
// coordinates are in [0, diagonal / cell] and the tolerance floor below keeps that under 2^21.
struct CellGrid {
    Vec3 origin;
    float inverseCell = 1.0f;
    std::int64_t cell(float x, float o) const { return std::int64_t(std::floor((x - o) * inverseCell)); }
    static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
        const auto m = (std::uint64_t(1) << 21) - 1;
        return (std::uint64_t(x) & m) | ((std::uint64_t(y) & m) << 21) | ((std::uint64_t(z) & m) << 42);
    }
};

double twiceArea(Vec3 a, Vec3 b, Vec3 c) {
    // In double: float cross products of long thin triangles round to zero or worse.
    const double u[3] = {double(b.x) - double(a.x), double(b.y) - double(a.y), double(b.z) - double(a.z)};
    const double v[3] = {double(c.x) - double(a.x), double(c.y) - double(a.y), double(c.z) - double(a.z)};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    return std::sqrt(x * x + y * y + z * z);
}

Vec3 unitNormal(Vec3 a, Vec3 b, Vec3 c) {
    const double u[3] = {double(b.x) - double(a.x), double(b.y) - double(a.y), double(b.z) - double(a.z)};
    const double v[3] = {double(c.x) - double(a.x), double(c.y) - double(a.y), double(c.z) - double(a.z)};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    const double l = std::sqrt(x * x + y * y + z * z);
    return l > 0 ? Vec3{float(x / l), float(y / l), float(z / l)} : Vec3{};
}

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

// One copy of each welded vertex per smoothing group of its faces: corners of two faces that share an edge
// through the vertex join when the faces' normals are within the crease angle. Rewrites out.indices,
// out.positions and out.vertexMap; fileCorner[c] is the file vertex (vertexMap index) of kept corner c.
void splitCreases(WeldedMesh& out, const std::vector<std::uint32_t>& fileCorner, float creaseAngle) {
    const std::size_t corners = out.indices.size(), vertices = out.positions.size();
    const float cosLimit = float(std::cos(double(creaseAngle) * 3.14159265358979323846 / 180.0));
    std::vector<Vec3> faceNormal(corners / 3);
    for (std::size_t t = 0; t < faceNormal.size(); ++t)
        faceNormal[t] = unitNormal(out.positions[out.indices[3 * t]], out.positions[out.indices[3 * t + 1]],
                                   out.positions[out.indices[3 * t + 2]]);
    // Corners around each welded vertex (CSR), in corner order.
    std::vector<std::uint32_t> first(vertices + 1, 0), around(corners);
    for (std::uint32_t v : out.indices) ++first[v + 1];
    for (std::size_t v = 0; v < vertices; ++v) first[v + 1] += first[v];
    {
        std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
        for (std::size_t c = 0; c < corners; ++c) around[fill[out.indices[c]]++] = std::uint32_t(c);
    }
    std::vector<std::uint32_t> parent(corners);
    std::iota(parent.begin(), parent.end(), 0u);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> spokes;  // (other vertex, corner)
    for (std::size_t v = 0; v < vertices; ++v) {
        spokes.clear();
        for (std::uint32_t i = first[v]; i < first[v + 1]; ++i) {
            const std::uint32_t c = around[i], t = c / 3, k = c % 3;
            spokes.emplace_back(out.indices[3 * t + (k + 1) % 3], c);
            spokes.emplace_back(out.indices[3 * t + (k + 2) % 3], c);
        }
        std::sort(spokes.begin(), spokes.end());
        for (std::size_t i = 0; i < spokes.size();) {
            std::size_t j = i + 1;
            for (; j < spokes.size() && spokes[j].first == spokes[i].first; ++j)
                if (dot(faceNormal[spokes[i].second / 3], faceNormal[spokes[j].second / 3]) >= cosLimit) {
                    const std::uint32_t a = findRoot(parent, spokes[i].second), b = findRoot(parent, spokes[j].second);
                    if (a != b) parent[std::max(a, b)] = std::min(a, b);
                }
            i = j;
        }
    }
    // New vertices in welded-vertex order, then the order of each group's first corner: deterministic.
    std::vector<std::uint32_t> copyOf(corners, 0xffffffffu), firstCopy(vertices, 0xffffffffu);
    std::vector<Vec3> positions;
    positions.reserve(vertices);
    for (std::size_t v = 0; v < vertices; ++v) {
        for (std::uint32_t i = first[v]; i < first[v + 1]; ++i) {
            const std::uint32_t root = findRoot(parent, around[i]);
            if (copyOf[root] == 0xffffffffu) {
                copyOf[root] = std::uint32_t(positions.size());
                positions.push_back(out.positions[v]);
            }
            copyOf[around[i]] = copyOf[root];
        }
        // A welded vertex no kept face uses stays as one (unused) vertex, so every file vertex maps somewhere.
        if (first[v] == first[v + 1]) positions.push_back(out.positions[v]), firstCopy[v] = std::uint32_t(positions.size() - 1);
        else firstCopy[v] = copyOf[around[first[v]]];
    }
    // File vertex -> the copy of the first kept face that uses it, else its welded vertex's first copy.
    std::vector<std::uint32_t> fileCopy(out.vertexMap.size(), 0xffffffffu);
    for (std::size_t c = 0; c < corners; ++c)
        if (fileCopy[fileCorner[c]] == 0xffffffffu) fileCopy[fileCorner[c]] = copyOf[c];
    for (std::size_t f = 0; f < fileCopy.size(); ++f)
        out.vertexMap[f] = fileCopy[f] != 0xffffffffu ? fileCopy[f] : firstCopy[out.vertexMap[f]];
    for (std::size_t c = 0; c < corners; ++c) out.indices[c] = copyOf[c];
    out.positions = std::move(positions);
}

} // namespace

WeldedMesh weldScene(const Scene& scene, float tolerance, float creaseAngle) {
    WeldedMesh out;
    const Bounds bounds = scene.bounds();
    const Vec3 size = bounds.size();
    const float diagonal = length(size);
    // The grid cell is the tolerance, but never finer than 1e-6 of the diagonal (the 21-bit key range).
    const float cell = std::max(tolerance, 1e-6f * std::max(diagonal, 1e-30f));
    CellGrid grid{bounds.lo, 1.0f / cell};
    const float tolerance2 = tolerance * tolerance;
    const double minTwiceArea = 2.0 * 1e-12 * double(diagonal) * double(diagonal);

    std::size_t totalVertices = 0;
    for (const Instance& inst : scene.instances) totalVertices += scene.meshes[inst.mesh].positions.size();
    out.vertexMap.reserve(totalVertices);
    out.instanceFirst.reserve(scene.instances.size() + 1);

    // Cell -> first welded vertex in it; next[] chains the rest of the cell's vertices.
    std::unordered_map<std::uint64_t, std::uint32_t> head;
    head.reserve(totalVertices);
    std::vector<std::uint32_t> next;
    std::vector<std::uint32_t> fileCorner;  // per kept corner: its file vertex (index into vertexMap)
    const bool split = creaseAngle < 180.0f;
    constexpr std::uint32_t kNone = 0xffffffffu;

    for (const Instance& inst : scene.instances) {
        const Mesh& mesh = scene.meshes[inst.mesh];
        const std::size_t first = out.vertexMap.size();
        out.instanceFirst.push_back(first);
        for (Vec3 objectP : mesh.positions) {
            const Vec3 p = transformPoint(inst.worldFromObject, objectP);
            const std::int64_t cx = grid.cell(p.x, grid.origin.x), cy = grid.cell(p.y, grid.origin.y),
                               cz = grid.cell(p.z, grid.origin.z);
            std::uint32_t found = kNone;
            // Own cell first: exact duplicates, the common case, end the search at once.
            for (int n = 0; n < 27 && found == kNone; ++n) {
                const int dx = (n % 3 + 1) % 3 - 1, dy = (n / 3 % 3 + 1) % 3 - 1, dz = (n / 9 + 1) % 3 - 1;
                auto it = head.find(CellGrid::key(cx + dx, cy + dy, cz + dz));
                if (it == head.end()) continue;
                for (std::uint32_t w = it->second; w != kNone; w = next[w]) {
                    const Vec3 d = out.positions[w] - p;
                    if (dot(d, d) <= tolerance2) {
                        found = w;
                        break;
                    }
                }
            }
            if (found == kNone) {
                found = std::uint32_t(out.positions.size());
                out.positions.push_back(p);
                auto [it, inserted] = head.try_emplace(CellGrid::key(cx, cy, cz), found);
                next.push_back(inserted ? kNone : it->second);
                if (!inserted) it->second = found;
            }
            out.vertexMap.push_back(found);
        }
        // A mirroring transform turns counter-clockwise into clockwise; swap two corners to keep the front.
        const bool mirrored = determinant3(inst.worldFromObject) < 0.0f;
        out.inputTriangles += mesh.triangleCount();
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            std::uint32_t v[3], f[3];
            for (int k = 0; k < 3; ++k) {
                f[k] = std::uint32_t(first + mesh.indices[3 * t + std::size_t(k)]);
                v[k] = out.vertexMap[f[k]];
            }
            if (mirrored) std::swap(v[1], v[2]), std::swap(f[1], f[2]);
            if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] ||
                !(twiceArea(out.positions[v[0]], out.positions[v[1]], out.positions[v[2]]) > minTwiceArea)) {
                ++out.droppedTriangles;
                continue;
            }
            out.indices.insert(out.indices.end(), {v[0], v[1], v[2]});
            if (split) fileCorner.insert(fileCorner.end(), {f[0], f[1], f[2]});
        }
    }
    out.instanceFirst.push_back(out.vertexMap.size());
    if (split) splitCreases(out, fileCorner, creaseAngle);
    return out;
}

} // namespace obscura::bake
