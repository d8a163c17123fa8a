// Triangle areas, normals and edge lengths in double, shared by the scene's degeneracy test, the tracer's
// self-hit offset and the bake (weld, crease split, samples). A float cross product of a long thin triangle
// rounds to zero (or turns) where the double one does not; every stage has to agree with the degeneracy
// tests, or a face they keep gets a zero normal downstream.
#pragma once

#include "obscura/math.h"

#include <algorithm>
#include <cmath>

namespace obscura::geometry {

// (b - a) x (c - a) in double, where the differences of float coordinates are exact (short of magnitudes
// 2^29 apart) and the products nearly so: good to double precision, not float's.
struct FaceCross {
    double x = 0, y = 0, z = 0;
    double length() const { return std::sqrt(x * x + y * y + z * z); }
};

inline FaceCross faceCross(Vec3 a, Vec3 b, Vec3 c) {
    const double u[3] = {double(b.x) - double(a.x), double(b.y) - double(a.y), double(b.z) - double(a.z)};
    const double v[3] = {double(c.x) - double(a.x), double(c.y) - double(a.y), double(c.z) - double(a.z)};
    return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

inline double twiceArea(Vec3 a, Vec3 b, Vec3 c) { return faceCross(a, b, c).length(); }

// The square of the triangle's longest edge.
inline double longestEdge2(Vec3 a, Vec3 b, Vec3 c) {
    const auto length2 = [](Vec3 from, Vec3 to) {
        const double x = double(to.x) - double(from.x), y = double(to.y) - double(from.y), z = double(to.z) - double(from.z);
        return x * x + y * y + z * z;
    };
    return std::max({length2(a, b), length2(a, c), length2(b, c)});
}

// A face is degenerate where twice its area is at most this, for a mesh whose used vertices span `size`:
// relative to the mesh's own extent, so a millimetre part and a kilometre terrain are judged alike.
inline double minTwiceArea(Vec3 size) {
    return 2.0 * 1e-12 * (double(size.x) * double(size.x) + double(size.y) * double(size.y) + double(size.z) * double(size.z));
}

// The unit normal of the counter-clockwise side, rounded to float only at the end (so its length is 1 to
// float precision for any face the weld keeps); zero for a face that is degenerate in double too.
inline Vec3 unitNormal(Vec3 a, Vec3 b, Vec3 c) {
    const FaceCross n = faceCross(a, b, c);
    const double l = n.length();
    return l > 0 ? Vec3{float(n.x / l), float(n.y / l), float(n.z / l)} : Vec3{};
}

} // namespace obscura::geometry
