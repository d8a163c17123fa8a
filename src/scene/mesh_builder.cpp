// Procedural primitives for the built-in scenes and tests.
#include "obscura/mesh_builder.h"

#include <cmath>

namespace obscura::build {

namespace {
std::uint32_t addVertex(Mesh& m, Vec3 p, Vec3 n) {
    m.positions.push_back(p);
    m.normals.push_back(n);
    return std::uint32_t(m.positions.size() - 1);
}
void addTriangle(Mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    m.indices.insert(m.indices.end(), {a, b, c});
}
} // namespace

void addQuad(Mesh& m, Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3) {
    Vec3 n = normalize(cross(p1 - p0, p3 - p0));
    std::uint32_t a = addVertex(m, p0, n), b = addVertex(m, p1, n), c = addVertex(m, p2, n),
                  d = addVertex(m, p3, n);
    addTriangle(m, a, b, c);
    addTriangle(m, a, c, d);
}

void addBox(Mesh& m, Vec3 lo, Vec3 hi) {
    Vec3 p[8];
    for (int i = 0; i < 8; ++i) p[i] = {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
    addQuad(m, p[0], p[4], p[6], p[2]);  // -x
    addQuad(m, p[1], p[3], p[7], p[5]);  // +x
    addQuad(m, p[0], p[1], p[5], p[4]);  // -y
    addQuad(m, p[2], p[6], p[7], p[3]);  // +y
    addQuad(m, p[0], p[2], p[3], p[1]);  // -z
    addQuad(m, p[4], p[5], p[7], p[6]);  // +z
}

void addSphere(Mesh& m, Vec3 center, float radius, int segments, int rings) {
    auto base = std::uint32_t(m.positions.size());
    for (int r = 0; r <= rings; ++r) {
        float theta = kPi * float(r) / float(rings);
        for (int s = 0; s <= segments; ++s) {
            float phi = 2.0f * kPi * float(s) / float(segments);
            Vec3 n{std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
            addVertex(m, center + n * radius, n);
        }
    }
    auto row = std::uint32_t(segments + 1);
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            std::uint32_t a = base + std::uint32_t(r) * row + std::uint32_t(s), b = a + 1, c = a + row, d = c + 1;
            if (r != 0) addTriangle(m, a, c, b);
            if (r != rings - 1) addTriangle(m, b, c, d);
        }
}

void addCylinderSide(Mesh& m, Vec3 baseCenter, float radius, float y0, float y1, int segments, bool inward) {
    for (int s = 0; s < segments; ++s) {
        float a0 = 2.0f * kPi * float(s) / float(segments), a1 = 2.0f * kPi * float(s + 1) / float(segments);
        Vec3 d0{std::cos(a0), 0, -std::sin(a0)}, d1{std::cos(a1), 0, -std::sin(a1)};
        Vec3 p00 = baseCenter + d0 * radius + Vec3{0, y0, 0}, p10 = baseCenter + d1 * radius + Vec3{0, y0, 0};
        Vec3 p01 = baseCenter + d0 * radius + Vec3{0, y1, 0}, p11 = baseCenter + d1 * radius + Vec3{0, y1, 0};
        // Flat sides: the well's closed form assumes a polygonal wall seen from inside, not smoothed normals.
        if (inward)
            addQuad(m, p00, p01, p11, p10);
        else
            addQuad(m, p00, p10, p11, p01);
    }
}

void addDisk(Mesh& m, Vec3 center, float radius, int segments, bool down) {
    Vec3 n{0, down ? -1.0f : 1.0f, 0};
    std::uint32_t c = addVertex(m, center, n);
    for (int s = 0; s < segments; ++s) {
        float a0 = 2.0f * kPi * float(s) / float(segments), a1 = 2.0f * kPi * float(s + 1) / float(segments);
        std::uint32_t i0 = addVertex(m, center + Vec3{std::cos(a0), 0, -std::sin(a0)} * radius, n);
        std::uint32_t i1 = addVertex(m, center + Vec3{std::cos(a1), 0, -std::sin(a1)} * radius, n);
        if (down)
            addTriangle(m, c, i1, i0);
        else
            addTriangle(m, c, i0, i1);
    }
}

void addPlaneWithHole(Mesh& m, float y, float half, float radius, int segments) {
    // Each hole edge is joined to the point where its outward ray meets the square, so the ring of
    // triangles covers the square minus the polygon exactly.
    Vec3 n{0, 1, 0};
    auto squarePoint = [&](float angle) {
        float c = std::cos(angle), s = -std::sin(angle);
        float t = half / std::fmax(std::fabs(c), std::fabs(s));
        return Vec3{c * t, y, s * t};
    };
    for (int s = 0; s < segments; ++s) {
        float a0 = 2.0f * kPi * float(s) / float(segments), a1 = 2.0f * kPi * float(s + 1) / float(segments);
        Vec3 h0{radius * std::cos(a0), y, -radius * std::sin(a0)}, h1{radius * std::cos(a1), y, -radius * std::sin(a1)};
        Vec3 o0 = squarePoint(a0), o1 = squarePoint(a1);
        std::uint32_t ih0 = addVertex(m, h0, n), ih1 = addVertex(m, h1, n);
        std::uint32_t io0 = addVertex(m, o0, n), io1 = addVertex(m, o1, n);
        addTriangle(m, ih0, io0, io1);
        addTriangle(m, ih0, io1, ih1);
        // Square corners fall between two rays: fill the gap triangle.
        for (int k = 0; k < 4; ++k) {
            float corner = kPi / 4.0f + float(k) * kPi / 2.0f;
            if (corner > a0 && corner < a1) {
                std::uint32_t ic = addVertex(m, squarePoint(corner), n);
                // Replace the straight edge o0-o1 by o0-corner-o1.
                m.indices.resize(m.indices.size() - 6);
                addTriangle(m, ih0, io0, ic);
                addTriangle(m, ih0, ic, io1);
                addTriangle(m, ih0, io1, ih1);
            }
        }
    }
}

} // namespace obscura::build
