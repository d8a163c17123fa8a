// Small vector and matrix types. Plain data, float, no SIMD wrappers: the hot loops that need SIMD
// are written over structure-of-arrays buffers instead.
//
// Matrices are named by the spaces they map between (viewFromWorld maps world points into view space)
// and stored row-major: m[row][col], applied to column vectors, so (aFromB * bFromC) is aFromC.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace obscura {

constexpr float kPi = 3.14159265358979323846f;

struct Vec2 {
    float x = 0, y = 0;
};

struct Vec3 {
    float x = 0, y = 0, z = 0;
    constexpr Vec3() = default;
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}
    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
constexpr Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator*(float s, Vec3 a) { return a * s; }
constexpr Vec3 operator/(Vec3 a, float s) { return {a.x / s, a.y / s, a.z / s}; }
constexpr Vec3& operator+=(Vec3& a, Vec3 b) { return a = a + b; }
constexpr Vec3& operator-=(Vec3& a, Vec3 b) { return a = a - b; }
constexpr Vec3& operator*=(Vec3& a, float s) { return a = a * s; }
constexpr bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

constexpr float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
// Returns the zero vector for a zero input rather than NaNs.
inline Vec3 normalize(Vec3 a) {
    float l = length(a);
    return l > 0 ? a / l : Vec3{};
}
inline Vec3 min(Vec3 a, Vec3 b) { return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)}; }
inline Vec3 max(Vec3 a, Vec3 b) { return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)}; }
inline bool isFinite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
// The largest coordinate's magnitude (the box norm): how far from the origin the scene and camera limits measure.
inline float maxAbsComponent(Vec3 a) { return std::max(std::abs(a.x), std::max(std::abs(a.y), std::abs(a.z))); }

// Builds an orthonormal basis (t, b, n) around unit n without branches that flip (Duff et al. 2017).
inline void orthonormalBasis(Vec3 n, Vec3& t, Vec3& b) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float c = n.x * n.y * a;
    t = {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
    b = {c, sign + n.y * n.y * a, -n.y};
}

struct Mat4 {
    float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

    static Mat4 identity() { return {}; }
    static Mat4 translation(Vec3 t);
    static Mat4 scale(Vec3 s);
    // Rotation by `radians` about unit `axis`, right-handed.
    static Mat4 rotation(Vec3 axis, float radians);
    // Rows given as 16 floats in row-major order.
    static Mat4 fromRowMajor(const float* v);
    // Columns given as 16 floats in column-major order (glTF's layout).
    static Mat4 fromColumnMajor(const float* v);
};

Mat4 operator*(const Mat4& a, const Mat4& b);
Vec3 transformPoint(const Mat4& aFromB, Vec3 p);
Vec3 transformVector(const Mat4& aFromB, Vec3 v);
Mat4 transpose(const Mat4& a);
// General 4x4 inverse; returns false (and leaves out unchanged) for a singular matrix.
bool invert(const Mat4& a, Mat4& out);
// For transforming normals: the upper 3x3's inverse-transpose up to a positive scale (normalize after), also
// where that 3x3 is singular but keeps some face's area (its cofactor matrix); identity below rank 2.
Mat4 normalMatrix(const Mat4& aFromB);
// Determinant of the upper 3x3 (negative for mirroring transforms).
float determinant3(const Mat4& a);

} // namespace obscura
