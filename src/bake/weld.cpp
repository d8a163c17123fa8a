// Pre-processing of triangle soup for the least-squares bake (Sloan et al. 2013 §2.1, "process geometry"):
// every instance flattened to world space, vertices welded by position so the solve sees the surface's
// connectivity, and faces that welding made degenerate dropped and counted. Welded vertices are then split
// along hard creases (one copy per smoothing group), so one value never has to serve two faces that see
// different hemispheres.
#include "obscura/bake.h"

#include "core/face_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace obscura::bake {

namespace {

using geometry::twiceArea;

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

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

// How far rounding the vertices to float can turn a face's normal, at most: each coordinate is off by half
// an ulp of the largest one, sqrt(3) of that per vertex, taken as 2^-22 |p|max to leave room for the
// instance transform's own rounding; moving the corners by d turns u x v by at most 2 d (|u| + |v|). Capped
// at 1 degree, so that a sliver whose normal rounding decides does not join the faces on both sides of a
// crease it lies on.
double normalSlack(Vec3 a, Vec3 b, Vec3 c, double twiceAreaABC) {
    double largest = 0;
    for (Vec3 p : {a, b, c}) largest = std::max({largest, std::fabs(double(p.x)), std::fabs(double(p.y)), std::fabs(double(p.z))});
    const double d = 0x1p-22 * largest;
    const double edges = double(length(b - a)) + double(length(c - a));
    constexpr double kMaxSlack = 3.14159265358979323846 / 180.0;
    return twiceAreaABC > 0 ? std::min(2.0 * d * edges / twiceAreaABC, kMaxSlack) : kMaxSlack;
}

// One copy of each welded vertex per smoothing group of its faces. Around a vertex, two faces join when they
// share an edge through it and the angle between their normals is at most the crease angle plus both faces'
// normalSlack; the groups are the connected components of that relation, so they depend on the faces alone,
// never on their order in the file. (Comparing only the first face on an edge with the others once split two
// fins 10 degrees apart on a floor or not, as the floor came first or last.) The slack keeps faces that are
// coplanar before rounding together at any crease angle, 0 included: in float, cos(0.01 degrees) is 1 and
// the float normals of such faces agree only to about 1e-7. Rewrites out.indices, out.positions and
// out.vertexMap; fileCorner[c] is the file vertex (vertexMap index) of kept corner c.
void splitCreases(WeldedMesh& out, const std::vector<std::uint32_t>& fileCorner, float creaseAngle) {
    const std::size_t corners = out.indices.size(), vertices = out.positions.size();
    const double limit = double(creaseAngle) * 3.14159265358979323846 / 180.0;
    std::vector<std::array<double, 3>> normal(corners / 3);  // unit, in double
    for (std::size_t t = 0; t < normal.size(); ++t) {
        const geometry::FaceCross n = geometry::faceCross(out.positions[out.indices[3 * t]], out.positions[out.indices[3 * t + 1]],
                                                      out.positions[out.indices[3 * t + 2]]);
        const double l = n.length();  // > 0: the weld dropped faces without area
        normal[t] = {n.x / l, n.y / l, n.z / l};
    }
    std::vector<double> faceSlack(normal.size());  // once per face: the edge groups below read it often
    for (std::size_t t = 0; t < faceSlack.size(); ++t) {
        const Vec3 a = out.positions[out.indices[3 * t]], b = out.positions[out.indices[3 * t + 1]],
                   c = out.positions[out.indices[3 * t + 2]];
        faceSlack[t] = normalSlack(a, b, c, geometry::twiceArea(a, b, c));
    }
    const double cosLimit = std::cos(limit);
    auto joined = [&](std::uint32_t s, std::uint32_t t) {
        const std::array<double, 3>& m = normal[s];
        const std::array<double, 3>& n = normal[t];
        const double cosine = m[0] * n[0] + m[1] * n[1] + m[2] * n[2];
        // Within the crease angle itself: the common case, decided without the slack.
        if (cosine >= cosLimit) return true;
        // atan2 of the cross and dot products: acos of the dot cannot tell angles below ~1e-8 from 0.
        const double x = m[1] * n[2] - m[2] * n[1], y = m[2] * n[0] - m[0] * n[2], z = m[0] * n[1] - m[1] * n[0];
        return std::atan2(std::sqrt(x * x + y * y + z * z), cosine) <= limit + faceSlack[s] + faceSlack[t];
    };
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
    std::vector<std::uint32_t> onEdge;                            // the corners of one edge's faces
    for (std::size_t v = 0; v < vertices; ++v) {
        spokes.clear();
        for (std::uint32_t i = first[v]; i < first[v + 1]; ++i) {
            const std::uint32_t c = around[i], t = c / 3, k = c % 3;
            spokes.emplace_back(out.indices[3 * t + (k + 1) % 3], c);
            spokes.emplace_back(out.indices[3 * t + (k + 2) % 3], c);
        }
        std::sort(spokes.begin(), spokes.end());
        // Every pair of faces on each edge through v (a manifold edge has one pair). Faces of one normal join
        // each other, and any other face joins one of them if and only if it joins the one of most slack, so
        // they are joined first and only that one is compared with the rest: 40000 copies of a triangle on one
        // edge took 1.6e9 pair tests (9 s), and the time grew with the square of a file's size.
        // Unites corners c and d's groups where `always` or their faces join (not tested once they are one).
        auto unite = [&](std::uint32_t c, std::uint32_t d, bool always) {
            const std::uint32_t a = findRoot(parent, c), b = findRoot(parent, d);
            if (a != b && (always || joined(c / 3, d / 3))) parent[std::max(a, b)] = std::min(a, b);
        };
        for (std::size_t i = 0; i < spokes.size();) {
            std::size_t end = i + 1;
            while (end < spokes.size() && spokes[end].first == spokes[i].first) ++end;
            onEdge.clear();
            for (std::size_t j = i; j < end; ++j) onEdge.push_back(spokes[j].second);
            i = end;
            if (onEdge.size() > 2) {  // a manifold edge has one pair, nothing to merge
                // By normal, then by slack, most first; the corner breaks ties, so the order is the faces' own.
                std::sort(onEdge.begin(), onEdge.end(), [&](std::uint32_t p, std::uint32_t q) {
                    const std::array<double, 3>&m = normal[p / 3], &n = normal[q / 3];
                    if (m != n) return m < n;
                    if (faceSlack[p / 3] != faceSlack[q / 3]) return faceSlack[p / 3] > faceSlack[q / 3];
                    return p < q;
                });
                std::size_t kept = 0;
                for (std::uint32_t c : onEdge) {
                    if (kept > 0 && normal[onEdge[kept - 1] / 3] == normal[c / 3])
                        unite(onEdge[kept - 1], c, true);
                    else
                        onEdge[kept++] = c;
                }
                onEdge.resize(kept);
            }
            for (std::size_t j = 0; j < onEdge.size(); ++j)
                for (std::size_t k = j + 1; k < onEdge.size(); ++k) unite(onEdge[j], onEdge[k], false);
        }
    }
    // New vertices in welded-vertex order, then the order of each group's first corner: deterministic.
    std::vector<std::uint32_t> copyOf(corners, 0xffffffffu), firstCopy(vertices, 0xffffffffu);
    std::vector<Vec3> positions;
    std::vector<float> shift;
    positions.reserve(vertices);
    shift.reserve(vertices);
    for (std::size_t v = 0; v < vertices; ++v) {
        for (std::uint32_t i = first[v]; i < first[v + 1]; ++i) {
            const std::uint32_t root = findRoot(parent, around[i]);
            if (copyOf[root] == 0xffffffffu) {
                copyOf[root] = std::uint32_t(positions.size());
                positions.push_back(out.positions[v]);
                shift.push_back(out.weldShift[v]);
            }
            copyOf[around[i]] = copyOf[root];
        }
        // A welded vertex no kept face uses stays as one (unused) vertex, so every file vertex maps somewhere.
        if (first[v] == first[v + 1]) {
            positions.push_back(out.positions[v]);
            shift.push_back(out.weldShift[v]);
            firstCopy[v] = std::uint32_t(positions.size() - 1);
        } else {
            firstCopy[v] = copyOf[around[first[v]]];
        }
    }
    // File vertex -> the copy of the first kept face that uses it, else its welded vertex's first copy.
    std::vector<std::uint32_t> fileCopy(out.vertexMap.size(), 0xffffffffu);
    for (std::size_t c = 0; c < corners; ++c)
        if (fileCopy[fileCorner[c]] == 0xffffffffu) fileCopy[fileCorner[c]] = copyOf[c];
    // File vertices whose faces fell into more than one copy: their output blends the copies by face area.
    std::vector<char> several(out.vertexMap.size(), 0);
    for (std::size_t c = 0; c < corners; ++c)
        if (copyOf[c] != fileCopy[fileCorner[c]]) several[fileCorner[c]] = 1;
    out.blends.clear();
    for (std::size_t c = 0; c < corners; ++c) {
        if (!several[fileCorner[c]]) continue;
        const std::size_t t = c / 3;
        const float area = float(0.5 * geometry::twiceArea(out.positions[out.indices[3 * t]],
                                                           out.positions[out.indices[3 * t + 1]],
                                                           out.positions[out.indices[3 * t + 2]]));
        out.blends.push_back({fileCorner[c], copyOf[c], area});
    }
    std::stable_sort(out.blends.begin(), out.blends.end(), [](const WeldedMesh::Blend& a, const WeldedMesh::Blend& b) {
        return a.file != b.file ? a.file < b.file : a.copy < b.copy;
    });
    // One entry per (file vertex, copy), the areas summed in corner order: the same bits for any thread count.
    std::size_t kept = 0;
    for (std::size_t i = 0; i < out.blends.size(); ++i) {
        if (kept > 0 && out.blends[kept - 1].file == out.blends[i].file && out.blends[kept - 1].copy == out.blends[i].copy)
            out.blends[kept - 1].weight += out.blends[i].weight;
        else
            out.blends[kept++] = out.blends[i];
    }
    out.blends.resize(kept);
    for (std::size_t f = 0; f < fileCopy.size(); ++f)
        out.vertexMap[f] = fileCopy[f] != 0xffffffffu ? fileCopy[f] : firstCopy[out.vertexMap[f]];
    for (std::size_t c = 0; c < corners; ++c) out.indices[c] = copyOf[c];
    out.positions = std::move(positions);
    out.weldShift = std::move(shift);
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
                out.weldShift.push_back(0.0f);
                auto [it, inserted] = head.try_emplace(CellGrid::key(cx, cy, cz), found);
                next.push_back(inserted ? kNone : it->second);
                if (!inserted) it->second = found;
            } else {
                out.weldShift[found] = std::max(out.weldShift[found], length(out.positions[found] - p));
            }
            out.vertexMap.push_back(found);
        }
        // removeDegenerateTriangles' rule, per instance in world space: a face of a 12 mm part beside a 3 km
        // level is no sliver. (The scene's diagonal once dropped every face of a 4 m room baked beside an
        // object 100 km away, and its vertices baked as open.)
        Bounds used;
        for (std::uint32_t i : mesh.indices) used.extend(out.positions[out.vertexMap[first + i]]);
        const double minTwiceArea = geometry::minTwiceArea(used.size());
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
