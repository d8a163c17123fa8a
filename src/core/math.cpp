// Matrix helpers for math.h.
#include "obscura/math.h"

#include <algorithm>
#include <cmath>

namespace obscura {

Mat4 Mat4::translation(Vec3 t) {
    Mat4 r;
    r.m[0][3] = t.x;
    r.m[1][3] = t.y;
    r.m[2][3] = t.z;
    return r;
}

Mat4 Mat4::scale(Vec3 s) {
    Mat4 r;
    r.m[0][0] = s.x;
    r.m[1][1] = s.y;
    r.m[2][2] = s.z;
    return r;
}

Mat4 Mat4::rotation(Vec3 axis, float radians) {
    Vec3 a = normalize(axis);
    float c = std::cos(radians), s = std::sin(radians), k = 1.0f - c;
    Mat4 r;
    r.m[0][0] = c + a.x * a.x * k;
    r.m[0][1] = a.x * a.y * k - a.z * s;
    r.m[0][2] = a.x * a.z * k + a.y * s;
    r.m[1][0] = a.y * a.x * k + a.z * s;
    r.m[1][1] = c + a.y * a.y * k;
    r.m[1][2] = a.y * a.z * k - a.x * s;
    r.m[2][0] = a.z * a.x * k - a.y * s;
    r.m[2][1] = a.z * a.y * k + a.x * s;
    r.m[2][2] = c + a.z * a.z * k;
    return r;
}

Mat4 Mat4::fromRowMajor(const float* v) {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = v[i * 4 + j];
    return r;
}

Mat4 Mat4::fromColumnMajor(const float* v) {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = v[j * 4 + i];
    return r;
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            float s = 0;
            for (int k = 0; k < 4; ++k) s += a.m[i][k] * b.m[k][j];
            r.m[i][j] = s;
        }
    return r;
}

Vec3 transformPoint(const Mat4& a, Vec3 p) {
    Vec3 r{a.m[0][0] * p.x + a.m[0][1] * p.y + a.m[0][2] * p.z + a.m[0][3],
           a.m[1][0] * p.x + a.m[1][1] * p.y + a.m[1][2] * p.z + a.m[1][3],
           a.m[2][0] * p.x + a.m[2][1] * p.y + a.m[2][2] * p.z + a.m[2][3]};
    float w = a.m[3][0] * p.x + a.m[3][1] * p.y + a.m[3][2] * p.z + a.m[3][3];
    return w == 1.0f || w == 0.0f ? r : r / w;
}

Vec3 transformVector(const Mat4& a, Vec3 v) {
    return {a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z,
            a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z,
            a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z};
}

Mat4 transpose(const Mat4& a) {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[j][i];
    return r;
}

bool invert(const Mat4& a, Mat4& out) {
    // Gauss-Jordan with partial pivoting, in double: instance transforms can be far from unit scale.
    double m[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            m[i][j] = double(a.m[i][j]);
            m[i][j + 4] = i == j ? 1.0 : 0.0;
        }
    for (int c = 0; c < 4; ++c) {
        int pivot = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::fabs(m[r][c]) > std::fabs(m[pivot][c])) pivot = r;
        if (std::fabs(m[pivot][c]) < 1e-30) return false;
        if (pivot != c)
            for (int j = 0; j < 8; ++j) std::swap(m[c][j], m[pivot][j]);
        double inv = 1.0 / m[c][c];
        for (int j = 0; j < 8; ++j) m[c][j] *= inv;
        for (int r = 0; r < 4; ++r) {
            if (r == c) continue;
            double f = m[r][c];
            for (int j = 0; j < 8; ++j) m[r][j] -= f * m[c][j];
        }
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) out.m[i][j] = float(m[i][j + 4]);
    return true;
}

Mat4 normalMatrix(const Mat4& aFromB) {
    // The cofactor matrix C of the linear part L: C (a x b) = (L a) x (L b) for any L, so it carries a
    // face's normal to the placed face's normal even where L is singular. (The inverse-transpose is C / det:
    // it fails there, and a plane squashed along its own normal, glTF scale [1, 1, 0], keeps its area; the
    // identity it once fell back to left such a floor's normal in object space.) In double, scaled so its
    // largest entry is 1, with det's sign so a mirror still turns normals the way the inverse-transpose does.
    double l[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) l[r][c] = double(aFromB.m[r][c]);
    double cof[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            cof[r][c] = l[r1][c1] * l[r2][c2] - l[r1][c2] * l[r2][c1];
        }
    const double det = l[0][0] * cof[0][0] + l[0][1] * cof[0][1] + l[0][2] * cof[0][2];
    double largest = 0;
    for (const auto& row : cof)
        for (double x : row) largest = std::max(largest, std::abs(x));
    Mat4 out;
    if (!(largest > 0) || !std::isfinite(largest)) return out;  // rank below 2: no face keeps any area
    const double scale = (det < 0 ? -1.0 : 1.0) / largest;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out.m[r][c] = float(cof[r][c] * scale);
    return out;
}

float determinant3(const Mat4& a) {
    return a.m[0][0] * (a.m[1][1] * a.m[2][2] - a.m[1][2] * a.m[2][1]) -
           a.m[0][1] * (a.m[1][0] * a.m[2][2] - a.m[1][2] * a.m[2][0]) +
           a.m[0][2] * (a.m[1][0] * a.m[2][1] - a.m[1][1] * a.m[2][0]);
}

} // namespace obscura
