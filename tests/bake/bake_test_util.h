// Small meshes for the bake tests.
#pragma once

#include "obscura/scene.h"
#include "obscura/sampling.h"

namespace obscura::bake::fixtures {

// A (cells x cells) grid over [x0,x1] x [z0,z1] at height y, facing +Y (or -Y when `down`). `jitter` moves
// interior vertices by up to that fraction of a cell (deterministically), so the mesh is irregular; the
// diagonals alternate so no direction is preferred.
inline Mesh grid(float x0, float x1, float z0, float z1, float y, int cells, bool down = false, float jitter = 0.0f) {
    Mesh m;
    m.name = "grid";
    const float dx = (x1 - x0) / float(cells), dz = (z1 - z0) / float(cells);
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
            float x = x0 + dx * float(i), z = z0 + dz * float(j);
            if (jitter > 0 && i > 0 && j > 0 && i < cells && j < cells) {
                std::uint32_t h = hash32(std::uint32_t(j * (cells + 1) + i));
                x += jitter * dx * (toUnitFloat(h) - 0.5f) * 2.0f;
                z += jitter * dz * (toUnitFloat(hash32(h)) - 0.5f) * 2.0f;
            }
            m.positions.push_back({x, y, z});
        }
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            auto a = std::uint32_t(j * (cells + 1) + i), b = a + 1, c = a + std::uint32_t(cells + 1), d = c + 1;
            // Counter-clockwise seen from +Y is (a, c, b) for x right, z towards the viewer.
            bool flip = ((i + j) & 1) != 0;
            std::uint32_t t[6];
            if (!flip) {
                std::uint32_t q[6] = {a, c, b, b, c, d};
                std::copy(q, q + 6, t);
            } else {
                std::uint32_t q[6] = {a, c, d, a, d, b};
                std::copy(q, q + 6, t);
            }
            if (down) {
                std::swap(t[1], t[2]);
                std::swap(t[4], t[5]);
            }
            m.indices.insert(m.indices.end(), t, t + 6);
        }
    computeSmoothNormals(m);
    return m;
}

} // namespace obscura::bake::fixtures
