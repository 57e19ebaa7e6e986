#pragma once
/// \file Small value types for points and vectors in 2D and 3D.

#include <array>
#include <cmath>
#include <cstddef>

namespace dynmesh {

/// A point or vector in R^3. Plain aggregate: `Vec3{1, 2, 3}`.
struct Vec3 {
    double x = 0, y = 0, z = 0;

    constexpr double& operator[](std::size_t i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr double operator[](std::size_t i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
    constexpr Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
    constexpr Vec3& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
    constexpr Vec3& operator/=(double s) { x /= s; y /= s; z /= s; return *this; }
    friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};
using Point3 = Vec3;

constexpr Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
constexpr Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
constexpr Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(Vec3 a, double s) { return a *= s; }
constexpr Vec3 operator*(double s, Vec3 a) { return a *= s; }
constexpr Vec3 operator/(Vec3 a, double s) { return a /= s; }
constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr double sqnorm(const Vec3& a) { return dot(a, a); }
inline double norm(const Vec3& a) { return std::sqrt(sqnorm(a)); }
inline double distance(const Vec3& a, const Vec3& b) { return norm(a - b); }
constexpr double sqdistance(const Vec3& a, const Vec3& b) { return sqnorm(a - b); }
/// Unit vector along `a`; the zero vector stays zero.
inline Vec3 normalized(const Vec3& a) {
    const double n = norm(a);
    return n > 0 ? a / n : a;
}
inline bool is_finite(const Vec3& a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

/// A point or vector in R^2.
struct Vec2 {
    double x = 0, y = 0;

    constexpr double& operator[](std::size_t i) { return i == 0 ? x : y; }
    constexpr double operator[](std::size_t i) const { return i == 0 ? x : y; }
    constexpr Vec2& operator+=(const Vec2& o) { x += o.x; y += o.y; return *this; }
    constexpr Vec2& operator-=(const Vec2& o) { x -= o.x; y -= o.y; return *this; }
    constexpr Vec2& operator*=(double s) { x *= s; y *= s; return *this; }
    friend constexpr bool operator==(const Vec2&, const Vec2&) = default;
};
using Point2 = Vec2;

constexpr Vec2 operator+(Vec2 a, const Vec2& b) { return a += b; }
constexpr Vec2 operator-(Vec2 a, const Vec2& b) { return a -= b; }
constexpr Vec2 operator*(Vec2 a, double s) { return a *= s; }
constexpr Vec2 operator*(double s, Vec2 a) { return a *= s; }
constexpr double dot(const Vec2& a, const Vec2& b) { return a.x * b.x + a.y * b.y; }
constexpr double cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }
inline double norm(const Vec2& a) { return std::sqrt(dot(a, a)); }
inline bool is_finite(const Vec2& a) { return std::isfinite(a.x) && std::isfinite(a.y); }

/// Axis-aligned bounding box in R^3.
struct Bbox3 {
    Vec3 min{INFINITY, INFINITY, INFINITY};
    Vec3 max{-INFINITY, -INFINITY, -INFINITY};
    constexpr void extend(const Vec3& p) {
        for (std::size_t i = 0; i < 3; ++i) {
            if (p[i] < min[i]) min[i] = p[i];
            if (p[i] > max[i]) max[i] = p[i];
        }
    }
    [[nodiscard]] double diagonal() const { return max.x >= min.x ? distance(min, max) : 0.0; }
    /// Is p in the box (its boundary included)?
    [[nodiscard]] constexpr bool contains(const Vec3& p) const {
        return p.x >= min.x && p.y >= min.y && p.z >= min.z && p.x <= max.x && p.y <= max.y && p.z <= max.z;
    }
    /// Do the two boxes meet (boundaries included)?
    [[nodiscard]] constexpr bool overlaps(const Bbox3& o) const {
        for (std::size_t i = 0; i < 3; ++i)
            if (o.max[i] < min[i] || o.min[i] > max[i]) return false;
        return true;
    }
};

}  // namespace dynmesh
