// Per-vertex ambient obscurance baking (Sloan, Tranchida, Chen, Kavan 2013, "Ambient Obscurance Baking on
// the GPU", §2-2.1) with least-squares vertex baking (Kavan, Bargteil, Sloan 2011).
//
// The bake is a chain of stages that exchange plain arrays, so later work (decorators, dynamic regions,
// LOD resampling, GPU or multi-machine tracing) can replace or split any one of them:
//   weldScene -> generateSamples -> traceSamples -> solveVertexValues
// Every random number is a pure function of the settings' seed and an id (a triangle's or a sample's), so
// any split of the work over threads or machines gives the same bits.
//
// Errors: BakeSettings::validate() and bakeScene() throw obscura::Error naming the bad field or problem;
// the stage functions assume valid settings and a sanitized scene (sanitizeScene) and check nothing else,
// but for generateSamples' limit on the sample count.
#pragma once

#include "obscura/math.h"
#include "obscura/scene.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace obscura::trace {
class Tracer;
}

namespace obscura::bake {

enum class Mode {
    // Sloan et al. eq. 1: A = (1/pi) Integral rho(t(w)) cos dw, rho(t) = 1 - exp(a t), a = ln(0.5)/d; a miss
    // counts as rho = 1.
    Obscurance,
    // Binary visibility within d: A = (1/pi) Integral [t(w) >= d] cos dw (what Blender and MeshLab bake).
    Occlusion,
};

enum class LinearSolver {
    Auto,            // CHOLMOD where the build has it, else SimplicialLDLT
    Cholmod,         // CHOLMOD supernodal Cholesky; throws obscura::Error in a build without CHOLMOD
    SimplicialLDLT,  // Eigen's simplicial LDL^T (the fallback; slow past ~1M unknowns)
};
// Whether this build links CHOLMOD (SuiteSparse).
bool cholmodAvailable();

struct BakeSettings {
    static constexpr float kMaxDistance = 1e6f;  // the largest d, m
    Mode mode = Mode::Obscurance;
    std::vector<float> distances{2.0f, 300.0f};  // d per channel: m, (0, 1e6]; 1 or 2 (short, long); the seed's 2 and 300
    int rays = 256;                   // directions per sample: [1, 65536]; the seed traces 256
    float alpha = 1.0f;               // regulariser weight: unitless, [0, 1e6]; the seed found 1 works
    int minSamplesPerFace = 3;        // [1, maxSamplesPerFace]; 3 so every face constrains its plane
    int maxSamplesPerFace = 32;       // [minSamplesPerFace, 4096]; caps huge distant faces (§2.1)
    float sampleDensity = 4.0f;       // samples per m^2 between the two caps: (0, 1e6]; ~3.7 per face on the seed's level
    float backFaceLimit = 0.25f;      // a sample whose back-facing hit fraction exceeds this is invalid: [0, 1]; §2.1
    float weldTolerance = 1e-6f;      // weld distance relative to the scene's bounding-box diagonal: [0, 1e-2]
    float creaseAngle = 60.0f;        // degrees, [0, 180]: faces meeting at a larger dihedral angle keep their
                                      // own vertex values (a hard edge); 180 welds across every edge
    LinearSolver linearSolver = LinearSolver::Auto;  // the least-squares factorisation; results agree to 1e-6
    std::uint32_t seed = 0;           // any value; the same seed gives the same bits on any thread count

    void validate() const;  // throws obscura::Error naming the flag-style field ("--rays: ...")
    int channels() const { return int(distances.size()); }
    // The weld distance in m for a scene of these bounds: weldTolerance of its diagonal. Welding moves a vertex
    // by up to it; the bake's rays leave each face's samples as far off as welding really moved its corners
    // (WeldedMesh::weldShift), not this far.
    float weldDistance(const Bounds& sceneBounds) const { return weldTolerance * length(sceneBounds.size()); }
};

// ---- stage 1: weld -----------------------------------------------------------------------------

// The scene flattened to world space and welded by position within smoothing groups, for the solve. Each
// instance is baked on its own (instanced meshes get per-instance values). Vertex and triangle order follow
// the scene's instance order, then the mesh's order, so the result does not depend on threads.
//
// Hard creases: around each position-welded vertex, faces that share an edge through it and whose normals
// differ by at most the crease angle (plus what rounding the vertices to float can explain, so coplanar
// faces never split) are joined, and the connected components of that relation are the smoothing groups,
// whatever the faces' order; each group gets its own copy of the vertex (same position). The regulariser then has no edge across a crease, and each side of a 90-degree step keeps
// the value of the hemisphere it sees. A file vertex maps to the copy of the first kept face (in file order)
// that uses it; where one file vertex serves faces on both sides of a crease (a PLY or an OBJ without normals
// sharing a cube's corners), its output is the mean of its copies' values weighted by the area of its faces
// in each (`blends`), whatever the faces' order. (Taking the first face's copy made a cube's contact edge
// with the floor white or dark as its bottom face came first or last.) glTF and OBJ files with hard edges
// already split them into separate file vertices, so there the map is exact.
struct WeldedMesh {
    std::vector<Vec3> positions;            // world space, m; one per welded vertex
    std::vector<std::uint32_t> indices;     // 3 per kept triangle, into positions, the file's winding
    std::vector<std::size_t> instanceFirst; // per instance + 1: offset of its vertices in vertexMap
    std::vector<std::uint32_t> vertexMap;   // per (instance, mesh vertex): its welded vertex (copy, see above)
    std::vector<float> weldShift;           // per welded vertex: m, the farthest a file vertex moved to join it
                                            // (0 where none moved; empty: 0 everywhere)
    struct Blend {
        std::uint32_t file;  // index into vertexMap
        std::uint32_t copy;  // welded vertex
        float weight;        // m^2: the area of the file vertex's kept faces in that copy
    };
    std::vector<Blend> blends;              // for file vertices in more than one copy only, sorted by file
    std::size_t inputTriangles = 0;
    std::size_t droppedTriangles = 0;       // degenerate after welding (repeated vertex, or twice the area at most
                                            // 1e-12 of the square of its instance's diagonal, sanitizeScene's
                                            // rule, so a small part is not judged by a large scene)

    std::size_t triangleCount() const { return indices.size() / 3; }
};

// Welds vertices closer than `tolerance` (m) to an earlier one. A vertex joins the first welded vertex
// found within tolerance in its own or a neighbouring grid cell, so chains do not collapse. Then splits
// each welded vertex into one copy per smoothing group (creaseAngle, degrees; 180: no split).
WeldedMesh weldScene(const Scene& scene, float tolerance, float creaseAngle = 180.0f);

// ---- stage 2: samples --------------------------------------------------------------------------

// Stratified points on each face. A sample's index is its id; triangleFirst[t] .. triangleFirst[t+1] are
// the samples of welded triangle t.
struct SampleSet {
    std::vector<Vec3> positions;            // world, m
    std::vector<Vec3> normals;              // unit geometric normal of the face's front (counter-clockwise) side
    std::vector<std::uint32_t> triangles;   // welded triangle of each sample
    std::vector<float> offsets;             // per welded triangle: its rays' self-hit offset (trace::selfHitOffset)
                                            // plus how far welding moved its corners (WeldedMesh::weldShift), m
    std::vector<Vec2> barycentrics;         // (lambda1, lambda2); lambda0 = 1 - both
    std::vector<std::uint32_t> triangleFirst;  // per triangle + 1

    std::size_t size() const { return positions.size(); }
};

// Samples per face: clamp(ceil(area * density), min, max) (§2.1); points are Owen-scrambled Sobol points,
// seeded by the triangle id, mapped to the triangle with the area-preserving square-to-triangle warp.
// Areas and normals are computed in double, as the weld's degeneracy test is. Throws obscura::Error, before
// allocating, when the total passes 2^32 - 1 (sample ids are 32-bit).
SampleSet generateSamples(const WeldedMesh& mesh, const BakeSettings& settings);

// ---- stage 3: rays -----------------------------------------------------------------------------

struct RayResults {
    int channels = 0;
    std::vector<float> values;              // samples x channels, A in [0, 1] per distance
    std::vector<std::uint8_t> valid;        // per sample: 0 when back-facing hits exceeded the limit
    std::uint64_t rays = 0;
    std::size_t invalidSamples = 0;
};

using Progress = std::function<void(double fraction)>;

// settings.rays cosine-weighted, stratified directions per sample about its face normal, the origin moved
// off the surface along that normal. One closest-hit ray per direction serves every distance and the
// back-face test. The direction set's shift is seeded by (seed, sample id). Thread-safe and deterministic.
RayResults traceSamples(const trace::Tracer& tracer, const SampleSet& samples, const BakeSettings& settings,
                        const Progress& progress = {});

// ---- stage 4: least squares --------------------------------------------------------------------

struct SolveStats {
    std::size_t unknowns = 0;    // welded vertices used by a triangle
    std::size_t edges = 0;       // interior edges in the regulariser
    std::size_t nonZeros = 0;    // in the lower triangle of M + alpha R
};

// Minimises  sum_k w_k (f_k - g(p_k))^2 + alpha x^T R x  over per-vertex x, one solve per channel with a
// single factorisation (Kavan et al. 2011; Sloan et al. 2013 §2.1):
//   w_k = A_T / N_T for the N_T samples of triangle T, invalid samples left out;
//   M = sum_k w_k lambda(p_k) lambda(p_k)^T, the mass matrix of the very quadrature that gives
//       b = sum_k w_k f_k lambda(p_k); for points that integrate quadratics exactly it is the linear
//       element's (A/12)[[2,1,1],[1,2,1],[1,1,2]], and otherwise it keeps constants constant and linear
//       signals linear, which the exact matrix with sampled b would not;
//   R = sum_e D_e^T D_e, D_e x = (A_1 + A_2) n_e . (grad g_1 - grad g_2) over each edge shared by exactly
//       two triangles, unfolded into one plane (the along-edge component of the jump is zero).
// A vertex with no valid sample takes its value through R; one reached by neither (an isolated, fully
// invalid part) takes the mean of all valid samples, through a 1e-9 relative diagonal term that also
// keeps the factorisation definite. Returns welded vertices x channels (unused vertices get 1).

std::vector<float> solveVertexValues(const WeldedMesh& mesh, const SampleSet& samples, const RayResults& results,
                                     float alpha, SolveStats* stats = nullptr, LinearSolver solver = LinearSolver::Auto);

// Smoothness of a piecewise-linear result: the area-weighted RMS jump of the normal derivative across interior
// edges (faces unfolded), sqrt(sum_e (A1+A2) s_e^2 / sum_e (A1+A2)), 1/m; the quantity R penalises. `values`
// holds welded vertices x channels.
double gradientJump(const WeldedMesh& mesh, const std::vector<float>& values, int channels, int channel);

// ---- the whole bake ----------------------------------------------------------------------------

struct StageTimes {
    double processGeometry = 0, sample = 0, bvhBuild = 0, trace = 0, solve = 0, write = 0;  // seconds
    double total() const { return processGeometry + sample + bvhBuild + trace + solve + write; }
};

// Bare Embree on a uniform subset of the bake's own rays (bake_bench.h), when asked for.
struct RawTraceResult {
    std::size_t stride = 0;               // every stride-th sample's rays; 0: not measured
    std::uint64_t rays = 0, hits = 0;
    double seconds = 0;                   // wall time of the traversal alone
    double bakeSeconds = 0;               // the bake's own path (ray setup, packets, kernel) on the same rays,
                                          // in batches alternating with the bare ones
    double mrays() const { return seconds > 0 ? double(rays) / seconds * 1e-6 : 0.0; }
    double bakeMrays() const { return bakeSeconds > 0 ? double(rays) / bakeSeconds * 1e-6 : 0.0; }
};

struct BakeResult {
    int channels = 0;
    // Per scene instance, one entry per vertex of its mesh in the file's order (offsets instanceFirst),
    // channels values each, clamped to [0, 1].
    std::vector<std::size_t> instanceFirst;
    std::vector<float> values;
    std::size_t inputTriangles = 0, droppedTriangles = 0, weldedVertices = 0, inputVertices = 0;
    std::size_t samples = 0, invalidSamples = 0;
    std::uint64_t rays = 0;
    SolveStats solve;
    StageTimes times;
    RawTraceResult raw;
    double mraysPerSecond() const { return times.trace > 0 ? double(rays) / times.trace * 1e-6 : 0.0; }
};

// Reports (stage name, fraction done) as the stages run.
using StageProgress = std::function<void(const std::string& stage, double fraction)>;

// Runs every stage on the scene (validated settings; throws obscura::Error on bad settings or an Embree
// failure). Times every stage but "write", which is the caller's. With rawEmbreeStride > 0, also traces
// every rawEmbreeStride-th sample's rays with bare Embree after the trace stage (BakeResult::raw).
BakeResult bakeScene(const Scene& scene, const BakeSettings& settings, const StageProgress& progress = {},
                     std::size_t rawEmbreeStride = 0);

} // namespace obscura::bake
