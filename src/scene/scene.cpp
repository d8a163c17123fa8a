// Mesh and Scene data functions: bounds, counts, smooth normals, degenerate removal, sanitizeScene.
#include "obscura/scene.h"

#include "obscura/error.h"

#include "core/face_geometry.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace obscura {

Bounds Mesh::bounds() const {
    Bounds b;
    for (Vec3 p : positions) b.extend(p);
    return b;
}

std::uint32_t Scene::add(Mesh mesh, const Mat4& worldFromObject) {
    auto index = std::uint32_t(meshes.size());
    std::string name = mesh.name;
    meshes.push_back(std::move(mesh));
    instances.push_back(Instance{index, worldFromObject, std::move(name)});
    return index;
}

namespace {

// Each mesh's bounds, once: a mesh placed by many instances is not walked once per instance.
std::vector<Bounds> meshBounds(const Scene& scene) {
    std::vector<Bounds> out;
    out.reserve(scene.meshes.size());
    for (const Mesh& m : scene.meshes) out.push_back(m.bounds());
    return out;
}

// f(corner) for the 8 corners of `b` carried into the world, not the transformed centre and size: rotations and
// shears move any corner outward.
template <class F> void forEachWorldCorner(const Bounds& b, const Mat4& worldFromObject, const F& f) {
    for (int c = 0; c < 8; ++c) {
        const Vec3 corner{(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z};
        f(transformPoint(worldFromObject, corner));
    }
}

} // namespace

Bounds Scene::bounds() const {
    const std::vector<Bounds> local = meshBounds(*this);
    Bounds world;
    for (const Instance& inst : instances) {
        if (inst.mesh >= meshes.size()) continue;  // sanitizeScene reports these; bounds just skips them
        if (local[inst.mesh].empty()) continue;
        forEachWorldCorner(local[inst.mesh], inst.worldFromObject, [&](Vec3 p) { world.extend(p); });
    }
    return world;
}

std::size_t Scene::triangleCount() const {
    std::size_t n = 0;
    for (const Instance& inst : instances)
        if (inst.mesh < meshes.size()) n += meshes[inst.mesh].triangleCount();
    return n;
}

namespace {

// One face's weighted normal at each of its corners, or false for a face without area or a vertex out of range.
// |cross| is twice the area, so cross * angle weights by area and by the corner's angle: a vertex's normal then
// does not depend on how a flat region around it happens to be split into triangles.
bool cornerNormals(const Mesh& mesh, std::size_t t, std::uint32_t (&v)[3], Vec3 (&w)[3]) {
    const std::size_t n = mesh.positions.size();
    for (int k = 0; k < 3; ++k) v[k] = mesh.indices[t + std::size_t(k)];
    if (v[0] >= n || v[1] >= n || v[2] >= n) return false;  // left for sanitizeScene to report
    const Vec3 p[3] = {mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]};
    const Vec3 areaNormal = cross(p[1] - p[0], p[2] - p[0]);
    const float len = length(areaNormal);
    if (!(len > 0) || !std::isfinite(len)) return false;
    for (int k = 0; k < 3; ++k) {
        Vec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
        // atan2 stays accurate for the tiny and near-straight angles where acos(dot) loses digits.
        w[k] = areaNormal * std::atan2(length(cross(a, b)), dot(a, b));
    }
    return true;
}

// A sum this much smaller than the sum of its terms' lengths cancelled: the faces around the vertex face both
// ways, as in a double-sided mesh that lists each face twice with opposite windings over shared vertices. Single-sided
// geometry cancels this far only at a knife edge whose two faces meet at under 0.012 degrees.
constexpr float kCancelled = 1e-4f;

} // namespace

void computeSmoothNormals(Mesh& mesh) {
    if (mesh.normals.size() == mesh.positions.size()) return;
    const std::size_t n = mesh.positions.size();
    std::vector<Vec3> sum(n, Vec3{});
    std::vector<float> weight(n, 0.0f);
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        std::uint32_t v[3];
        Vec3 w[3];
        if (!cornerNormals(mesh, t, v, w)) continue;
        for (int k = 0; k < 3; ++k) {
            sum[v[k]] += w[k];
            weight[v[k]] += length(w[k]);
        }
    }
    std::vector<std::uint8_t> cancelled(n, 0);
    bool anyCancelled = false;
    for (std::size_t i = 0; i < n; ++i)
        if (weight[i] > 0 && !(length(sum[i]) > kCancelled * weight[i])) cancelled[i] = 1, anyCancelled = true;
    if (anyCancelled) {
        // Sum again around those vertices, counting each face once whatever its winding: the first listing of a
        // vertex triple stands for the surface, and the reversed copy after it is its back. A wall then keeps its
        // own normal, not the up vector, and a double-sided room's corner the bisector of its first-listed faces.
        std::set<std::array<std::uint32_t, 3>> seen;
        std::vector<Vec3> aligned(n, Vec3{}), largest(n, Vec3{});
        for (std::size_t i = 0; i < n; ++i)
            if (cancelled[i]) sum[i] = Vec3{};
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            std::uint32_t v[3];
            Vec3 w[3];
            if (!cornerNormals(mesh, t, v, w) || !(cancelled[v[0]] || cancelled[v[1]] || cancelled[v[2]])) continue;
            std::array<std::uint32_t, 3> key{v[0], v[1], v[2]};
            std::sort(key.begin(), key.end());
            if (!seen.insert(key).second) continue;
            for (int k = 0; k < 3; ++k)
                if (cancelled[v[k]]) {
                    sum[v[k]] += w[k];
                    if (length(w[k]) > length(largest[v[k]])) largest[v[k]] = w[k];
                }
        }
        // Faces reversed without being exact copies (each side triangulated its own way) still cancel: then
        // every term is turned to the side of the largest one, which at least keeps the normal across the surface.
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            std::uint32_t v[3];
            Vec3 w[3];
            if (!cornerNormals(mesh, t, v, w) || !(cancelled[v[0]] || cancelled[v[1]] || cancelled[v[2]])) continue;
            for (int k = 0; k < 3; ++k)
                if (cancelled[v[k]]) aligned[v[k]] += dot(w[k], largest[v[k]]) < 0 ? -w[k] : w[k];
        }
        for (std::size_t i = 0; i < n; ++i)
            if (cancelled[i] && !(length(sum[i]) > kCancelled * weight[i])) sum[i] = aligned[i];
    }
    mesh.normals.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        Vec3 nrm = normalize(sum[i]);
        // Unreferenced vertices (or ones only on degenerate faces) still need some unit normal.
        mesh.normals[i] = (nrm == Vec3{} || !isFinite(nrm)) ? Vec3{0, 1, 0} : nrm;
    }
}

std::size_t removeDegenerateTriangles(Mesh& mesh) {
    const std::size_t n = mesh.positions.size();
    // Relative to the mesh's own size, so a millimetre part and a kilometre terrain are judged alike. Over
    // finite positions only: one infinite vertex must not make every other triangle "small". Over the vertices
    // triangles use only: one stray vertex 1e7 m out once made a unit triangle "degenerate".
    Bounds finite;
    for (std::uint32_t i : mesh.indices)
        if (i < n && isFinite(mesh.positions[i])) finite.extend(mesh.positions[i]);
    const double minTwiceArea = geometry::minTwiceArea(finite.size());
    std::size_t kept = 0;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        assert(a < n && b < n && c < n);
        if (a == b || b == c || a == c) continue;
        // In double: float cross products of long thin triangles round to zero or worse.
        const double twiceArea = geometry::twiceArea(mesh.positions[a], mesh.positions[b], mesh.positions[c]);
        if (!std::isfinite(twiceArea) || !(twiceArea > minTwiceArea)) continue;
        mesh.indices[kept++] = a;
        mesh.indices[kept++] = b;
        mesh.indices[kept++] = c;
    }
    std::size_t removed = mesh.triangleCount() - kept / 3;
    mesh.indices.resize(kept);
    return removed;
}

namespace {

void checkMesh(const Mesh& mesh, const std::string& what) {
    const std::size_t n = mesh.positions.size();
    // Named, so a file of many meshes says which one.
    const std::string label = mesh.name.empty() ? "an unnamed mesh" : "mesh '" + mesh.name + "'";
    // Albedo is the fraction of light a surface reflects: above 1 the multi-bounce fit and the composite would
    // add light, below 0 (or NaN) darken past black. glTF bounds baseColorFactor to [0, 1]; OBJ's Kd and PLY's
    // float colours are read in the same range.
    const Vec3 c = mesh.baseColor;
    if (!(c.x >= 0 && c.x <= 1 && c.y >= 0 && c.y <= 1 && c.z >= 0 && c.z <= 1))
        fail(what, "mesh '" + mesh.name + "' has base colour (" + numberText(c.x) + ", " + numberText(c.y) + ", " +
                       numberText(c.z) + "), outside [0, 1]");
    if (mesh.indices.size() % 3 != 0)
        fail(what, "mesh '" + mesh.name + "' has " + std::to_string(mesh.indices.size()) +
                       " indices, not a multiple of 3");
    for (std::uint32_t i : mesh.indices)
        if (i >= n)
            fail(what, label + ": index " + std::to_string(i) + " out of range (" + std::to_string(n) +
                           " vertices)");
    for (std::size_t i = 0; i < n; ++i) {
        if (!isFinite(mesh.positions[i]))
            fail(what, "vertex " + std::to_string(i) + " of " + label + " has a non-finite position");
        if (maxAbsComponent(mesh.positions[i]) > kMaxSceneCoordinate)
            fail(what, "vertex " + std::to_string(i) + " of mesh '" + mesh.name + "' lies " +
                           numberText(maxAbsComponent(mesh.positions[i])) + " m from the origin, beyond " +
                           numberText(kMaxSceneCoordinate) + " m");
    }
    if (!mesh.normals.empty() && mesh.normals.size() != n)
        fail(what, "mesh '" + mesh.name + "' has " + std::to_string(mesh.normals.size()) + " normals for " +
                       std::to_string(n) + " vertices");
    for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
        if (!isFinite(mesh.normals[i]))
            fail(what, "vertex " + std::to_string(i) + " of " + label + " has a non-finite normal");
    }
}

bool isFinite(const Mat4& m) {
    for (const auto& row : m.m)
        for (float v : row)
            if (!std::isfinite(v)) return false;
    return true;
}

} // namespace

void checkScene(const Scene& scene, const std::string& what) {
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        if (inst.mesh >= scene.meshes.size())
            fail(what, "instance " + std::to_string(i) + " refers to mesh " + std::to_string(inst.mesh) + " (" +
                           std::to_string(scene.meshes.size()) + " meshes)");
        if (!isFinite(inst.worldFromObject))
            fail(what, "instance " + std::to_string(i) + (inst.name.empty() ? "" : " ('" + inst.name + "')") +
                           " has a non-finite transform");
    }
    // Every check before the removal: removeDegenerateTriangles may assume valid indices.
    for (const Mesh& mesh : scene.meshes) checkMesh(mesh, what);
    // In the world too: a finite transform may still carry finite positions far out (or past float's range).
    const std::vector<Bounds> local = meshBounds(scene);
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        if (local[inst.mesh].empty()) continue;
        float reach = 0.0f;
        forEachWorldCorner(local[inst.mesh], inst.worldFromObject, [&](Vec3 p) {
            const float d = maxAbsComponent(p);
            reach = std::isnan(d) ? std::numeric_limits<float>::infinity() : std::max(reach, d);
        });
        if (reach > kMaxSceneCoordinate)
            fail(what, "instance " + std::to_string(i) + (inst.name.empty() ? "" : " ('" + inst.name + "')") +
                           " places geometry " + numberText(reach) + " m from the origin, beyond " +
                           numberText(kMaxSceneCoordinate) + " m");
    }
}

void sanitizeScene(Scene& scene, const std::string& what, std::size_t* dropped) {
    checkScene(scene, what);
    std::size_t removed = 0;
    for (Mesh& mesh : scene.meshes) removed += removeDegenerateTriangles(mesh);
    if (dropped) *dropped = removed;
    // A file's zero normal (OBJ's "vn 0 0 0", PLY's nx = ny = nz = 0) once reached the G-buffer as (0, 0, 0),
    // which `ao` then refused in the G-buffer Obscura itself had written. Checked on the triangles kept: an
    // exporter's per-face normal of a face without area is zero, and that face is dropped above.
    for (const Mesh& mesh : scene.meshes)
        if (!mesh.normals.empty())
            for (std::uint32_t i : mesh.indices)
                if (mesh.normals[i] == Vec3{})
                    fail(what, "vertex " + std::to_string(i) + " of mesh '" + mesh.name + "' has a zero-length normal");
    // Counted over instances: triangles in meshes nothing places are not in the scene either.
    // Say why where triangles were there and were dropped: "no triangles" of a file of faces read as a bad file.
    if (scene.triangleCount() == 0)
        fail(what, removed == 0 ? std::string("no triangles")
                   : "no triangles left: " +
                         (removed == 1 ? std::string("its one triangle is") : "all " + std::to_string(removed) + " are") +
                         " degenerate (zero area, or too small for the mesh's extent)");
}

} // namespace obscura
