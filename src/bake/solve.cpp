// Least-squares vertex baking (Kavan, Bargteil, Sloan 2011, as used by Sloan et al. 2013 §2.1): the
// per-vertex values x of a piecewise-linear g that best fit the sampled signal f over the surface, with an
// edge regulariser that penalises jumps of the gradient across edges and leaves linear signals alone.
// One sparse factorisation of (M + alpha R) serves every channel (both distances): CHOLMOD's supernodal
// Cholesky where the build found CHOLMOD (dense BLAS on supernodes: an order of magnitude faster on a
// game level than a simplicial factorisation), else Eigen's SimplicialLDLT.
#include "obscura/bake.h"

#include "obscura/error.h"

#include "bake/edges.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#ifdef OBSCURA_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <algorithm>
#include <cmath>

namespace obscura::bake {

namespace {

constexpr std::uint32_t kUnused = 0xffffffffu;

std::uint64_t pairKey(std::uint32_t i, std::uint32_t j) {
    // Lower triangle: row >= column; packed column-major so sorting groups a column's rows together.
    if (i < j) std::swap(i, j);
    return (std::uint64_t(j) << 32) | i;
}

struct Vec3d {
    double x, y, z;
};
Vec3d toD(Vec3 v) { return {v.x, v.y, v.z}; }
Vec3d sub(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dotD(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d crossD(Vec3d a, Vec3d b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double lengthD(Vec3d a) { return std::sqrt(dotD(a, a)); }

// The compressed lower triangle of a symmetric matrix whose pattern is known before its values.
class LowerMatrix {
public:
    LowerMatrix(std::size_t n, std::vector<std::uint64_t>& keys) : n_(n) {
        for (std::size_t i = 0; i < n; ++i) keys.push_back(pairKey(std::uint32_t(i), std::uint32_t(i)));
        std::sort(keys.begin(), keys.end());
        keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
        outer_.assign(n + 1, 0);
        inner_.resize(keys.size());
        for (std::size_t k = 0; k < keys.size(); ++k) {
            ++outer_[std::size_t(keys[k] >> 32) + 1];
            inner_[k] = int(keys[k] & 0xffffffffu);
        }
        for (std::size_t c = 0; c < n; ++c) outer_[c + 1] += outer_[c];
        values_.assign(keys.size(), 0.0);
    }
    void add(std::uint32_t i, std::uint32_t j, double v) {
        if (i < j) std::swap(i, j);
        const int* begin = inner_.data() + outer_[j];
        const int* end = inner_.data() + outer_[j + 1];
        const int* at = std::lower_bound(begin, end, int(i));
        values_[std::size_t(at - inner_.data())] += v;
    }
    Eigen::SparseMatrix<double> matrix() const {
        const auto size = static_cast<Eigen::Index>(n_);
        Eigen::SparseMatrix<double> a(size, size);
        a.resizeNonZeros(Eigen::Index(values_.size()));
        std::copy(outer_.begin(), outer_.end(), a.outerIndexPtr());
        std::copy(inner_.begin(), inner_.end(), a.innerIndexPtr());
        std::copy(values_.begin(), values_.end(), a.valuePtr());
        return a;
    }
    std::size_t nonZeros() const { return values_.size(); }

private:
    std::size_t n_;
    std::vector<int> outer_, inner_;
    std::vector<double> values_;
};

template <class Solver>
Eigen::MatrixXd factorAndSolve(Solver& solver, const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& rhs) {
    solver.compute(a);
    if (solver.info() != Eigen::Success) fail("least-squares solve", "factorisation failed (" + std::to_string(a.rows()) + " unknowns)");
    Eigen::MatrixXd x = solver.solve(rhs);
    if (solver.info() != Eigen::Success) fail("least-squares solve", "back-substitution failed");
    return x;
}

} // namespace

bool cholmodAvailable() {
#ifdef OBSCURA_HAVE_CHOLMOD
    return true;
#else
    return false;
#endif
}

std::vector<float> solveVertexValues(const WeldedMesh& mesh, const SampleSet& samples, const RayResults& results,
                                     float alpha, SolveStats* stats, LinearSolver linearSolver) {
    const std::size_t triangles = mesh.triangleCount();
    const auto channels = std::size_t(results.channels);
    std::vector<float> out(mesh.positions.size() * channels, 1.0f);

    // Unknowns: welded vertices some kept triangle uses.
    std::vector<std::uint32_t> unknown(mesh.positions.size(), kUnused);
    std::uint32_t n = 0;
    for (std::uint32_t v : mesh.indices)
        if (unknown[v] == kUnused) unknown[v] = n++;
    if (n == 0) return out;

    // Pattern: every mesh edge, plus (c, d) across each interior edge, plus the diagonal.
    const std::vector<std::pair<std::uint32_t, std::uint32_t>> interior = detail::interiorEdges(mesh);
    std::vector<std::uint64_t> keys;
    keys.reserve(3 * triangles + interior.size() + n);
    for (std::size_t t = 0; t < triangles; ++t)
        for (std::size_t k = 0; k < 3; ++k)
            keys.push_back(pairKey(unknown[mesh.indices[3 * t + k]], unknown[mesh.indices[3 * t + (k + 1) % 3]]));
    for (auto [h1, h2] : interior) keys.push_back(pairKey(unknown[mesh.indices[h1]], unknown[mesh.indices[h2]]));
    LowerMatrix system(n, keys);
    keys = {};

    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(Eigen::Index(n), Eigen::Index(channels));
    std::vector<double> lumped(n, 0.0);
    std::vector<double> validSum(channels, 0.0);
    std::size_t validCount = 0;

    // Data term: the quadrature of the samples, w = A_T / N_T.
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::uint32_t v[3] = {unknown[mesh.indices[3 * t]], unknown[mesh.indices[3 * t + 1]], unknown[mesh.indices[3 * t + 2]]};
        const Vec3d p0 = toD(mesh.positions[mesh.indices[3 * t]]), p1 = toD(mesh.positions[mesh.indices[3 * t + 1]]),
                    p2 = toD(mesh.positions[mesh.indices[3 * t + 2]]);
        const double area = 0.5 * lengthD(crossD(sub(p1, p0), sub(p2, p0)));
        for (std::uint32_t k : v) lumped[k] += area / 3.0;
        const std::uint32_t first = samples.triangleFirst[t], last = samples.triangleFirst[t + 1];
        if (last == first) continue;
        const double w = area / double(last - first);
        double m[3][3] = {};
        for (std::uint32_t s = first; s < last; ++s) {
            if (!results.valid[s]) continue;
            const double l1 = samples.barycentrics[s].x, l2 = samples.barycentrics[s].y;
            const double l[3] = {1.0 - l1 - l2, l1, l2};
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) m[i][j] += w * l[i] * l[j];
            for (std::size_t c = 0; c < channels; ++c) {
                const double f = results.values[s * channels + c];
                for (int i = 0; i < 3; ++i) rhs(Eigen::Index(v[i]), Eigen::Index(c)) += w * f * l[i];
                validSum[c] += f;
            }
            ++validCount;
        }
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j <= i; ++j) system.add(v[i], v[j], m[i][j]);
    }

    // Regulariser: D_e x = (A1 + A2) * (normal derivative on face 1 - on face 2), faces unfolded about the edge.
    for (const auto& edge : interior) {
        std::uint32_t vertex[4];
        double coef[4], sumArea;
        if (!detail::edgeRow(mesh, edge, vertex, coef, sumArea)) continue;
        std::uint32_t idx[4];
        for (int i = 0; i < 4; ++i) idx[i] = unknown[vertex[i]];
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                if (idx[i] >= idx[j]) system.add(idx[i], idx[j], double(alpha) * coef[i] * coef[j]);
    }

    // A vanishing pull towards the mean of the valid samples: it fixes parts no sample and no edge reaches,
    // and keeps the matrix definite, at a relative weight far below the 1e-6 any caller can notice.
    constexpr double kPull = 1e-9;
    for (std::uint32_t i = 0; i < n; ++i) {
        system.add(i, i, kPull * lumped[i]);
        for (std::size_t c = 0; c < channels; ++c) {
            const double mean = validCount ? validSum[c] / double(validCount) : 1.0;
            rhs(Eigen::Index(i), Eigen::Index(c)) += kPull * lumped[i] * mean;
        }
    }

    if (linearSolver == LinearSolver::Cholmod && !cholmodAvailable())
        fail("least-squares solve", "CHOLMOD was asked for but this build has none");
    Eigen::MatrixXd x;
#ifdef OBSCURA_HAVE_CHOLMOD
    if (linearSolver != LinearSolver::SimplicialLDLT) {
        // Only the lower triangle is stored; Eigen hands CHOLMOD the matrix as symmetric-lower (stype -1).
        Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> solver;
        x = factorAndSolve(solver, system.matrix(), rhs);
    }
#endif
    if (x.size() == 0) {
        Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> solver;
        x = factorAndSolve(solver, system.matrix(), rhs);
    }

    for (std::size_t v = 0; v < mesh.positions.size(); ++v)
        if (unknown[v] != kUnused)
            for (std::size_t c = 0; c < channels; ++c) out[v * channels + c] = float(x(Eigen::Index(unknown[v]), Eigen::Index(c)));
    if (stats) {
        stats->unknowns = n;
        stats->edges = interior.size();
        stats->nonZeros = system.nonZeros();
    }
    return out;
}

namespace detail {

std::vector<std::pair<std::uint32_t, std::uint32_t>> interiorEdges(const WeldedMesh& mesh) {
    // Half-edges sorted by their undirected edge: (edge key, triangle * 3 + opposite corner).
    std::vector<std::pair<std::uint64_t, std::uint32_t>> halfEdges;
    halfEdges.reserve(mesh.indices.size());
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (std::uint32_t k = 0; k < 3; ++k)
            halfEdges.emplace_back(pairKey(mesh.indices[3 * t + (k + 1) % 3], mesh.indices[3 * t + (k + 2) % 3]),
                                   std::uint32_t(3 * t + k));
    std::sort(halfEdges.begin(), halfEdges.end());
    std::vector<std::pair<std::uint32_t, std::uint32_t>> interior;
    for (std::size_t i = 0; i < halfEdges.size();) {
        std::size_t j = i;
        while (j < halfEdges.size() && halfEdges[j].first == halfEdges[i].first) ++j;
        // Exactly two faces: a manifold interior edge. Boundary and non-manifold edges are not regularised.
        if (j - i == 2 && mesh.indices[halfEdges[i].second] != mesh.indices[halfEdges[i + 1].second])
            interior.emplace_back(halfEdges[i].second, halfEdges[i + 1].second);
        i = j;
    }
    return interior;
}

bool edgeRow(const WeldedMesh& mesh, std::pair<std::uint32_t, std::uint32_t> edge, std::uint32_t vertex[4],
             double coef[4], double& sumArea) {
    const auto [h1, h2] = edge;
    const std::size_t t1 = h1 / 3;
    const std::uint32_t k1 = h1 % 3;
    const std::uint32_t ga = mesh.indices[3 * t1 + (k1 + 1) % 3], gb = mesh.indices[3 * t1 + (k1 + 2) % 3];
    const std::uint32_t gc = mesh.indices[h1], gd = mesh.indices[h2];
    const Vec3d a = toD(mesh.positions[ga]), e = sub(toD(mesh.positions[gb]), a);
    const double len = lengthD(e);
    if (!(len > 0.0)) return false;
    const Vec3d u{e.x / len, e.y / len, e.z / len};
    auto unfold = [&](std::uint32_t g, double& x, double& h) {
        const Vec3d q = sub(toD(mesh.positions[g]), a);
        x = dotD(q, u);
        h = lengthD(Vec3d{q.x - x * u.x, q.y - x * u.y, q.z - x * u.z});
    };
    double xc, hc, xd, hd;
    unfold(gc, xc, hc);
    unfold(gd, xd, hd);
    if (!(hc > 0.0) || !(hd > 0.0)) return false;
    // a = (0,0), b = (len,0), c = (xc, hc) and d = (xd, -hd): the y-derivatives of the hat functions are
    // (xc - len)/(len hc), -xc/(len hc), 1/hc on face 1 and (len - xd)/(len hd), xd/(len hd), -1/hd on face 2.
    sumArea = 0.5 * len * (hc + hd);
    coef[0] = sumArea * ((xc - len) / (len * hc) - (len - xd) / (len * hd));
    coef[1] = sumArea * (-xc / (len * hc) - xd / (len * hd));
    coef[2] = sumArea / hc;
    coef[3] = sumArea / hd;
    vertex[0] = ga;
    vertex[1] = gb;
    vertex[2] = gc;
    vertex[3] = gd;
    return true;
}

} // namespace detail

double gradientJump(const WeldedMesh& mesh, const std::vector<float>& values, int channels, int channel) {
    double weighted = 0, area = 0;
    for (const auto& edge : detail::interiorEdges(mesh)) {
        std::uint32_t vertex[4];
        double coef[4], sumArea;
        if (!detail::edgeRow(mesh, edge, vertex, coef, sumArea)) continue;
        double d = 0;
        for (int i = 0; i < 4; ++i) d += coef[i] * double(values[std::size_t(vertex[i]) * std::size_t(channels) + std::size_t(channel)]);
        const double jump = d / sumArea;  // 1/m
        weighted += sumArea * jump * jump;
        area += sumArea;
    }
    return area > 0 ? std::sqrt(weighted / area) : 0.0;
}

} // namespace obscura::bake
