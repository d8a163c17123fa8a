// Interior edges of a welded mesh and the edge regulariser's row (Kavan et al. 2011): shared by the solve
// and the gradient-jump measure, so both speak of the same quantity.
#pragma once

#include "obscura/bake.h"

#include <utility>
#include <vector>

namespace obscura::bake::detail {

// Pairs of half-edges (triangle * 3 + opposite corner) of every edge shared by exactly two triangles whose
// opposite corners differ; boundary and non-manifold edges are left out. Sorted by edge.
std::vector<std::pair<std::uint32_t, std::uint32_t>> interiorEdges(const WeldedMesh& mesh);

// The row D_e = (A1 + A2) n_e . (grad g_1 - grad g_2) over welded vertices vertex[0..3] = (a, b, c, d),
// faces unfolded about the edge ab; sumArea = A1 + A2. False for a degenerate pair.
bool edgeRow(const WeldedMesh& mesh, std::pair<std::uint32_t, std::uint32_t> edge, std::uint32_t vertex[4],
             double coef[4], double& sumArea);

} // namespace obscura::bake::detail
