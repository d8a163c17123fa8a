// Geometry with closed-form AO, shared by the ray-tracing and the screen-space tests.
#pragma once

#include "obscura/mesh_builder.h"
#include "obscura/scene.h"

namespace obscura::test {

// Floor y = 0 and a wall z = 0 facing +Z, both 2 km wide: "infinite" at every radius the tests use. A
// point at the wall's foot has cosine-weighted AO 1/2 for any distance from the wall.
inline Scene wallAndFloor() {
    Scene scene;
    Mesh m;
    const float h = 1000.0f;
    build::addQuad(m, {-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h});
    build::addQuad(m, {-h, 0, 0}, {h, 0, 0}, {h, h, 0}, {-h, h, 0});
    scene.add(std::move(m));
    return scene;
}

} // namespace obscura::test
