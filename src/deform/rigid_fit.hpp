#pragma once
// The best-fit rotation between two placements of the same points (the rigid part of a
// motion), for sub-stepping (spec deforming-mesh.md §10.1 "rigid+linear"): a time unit is
// interpolated as the rotation turned gradually about its axis plus the rest linearly, so a
// rigid motion keeps its shape at every sub-step, where linear blending would shrink it.

#include <algorithm>
#include <cmath>
#include <span>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh::detail {

/// A 3x3 matrix by rows.
struct Mat3 {
    Vec3 r[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    [[nodiscard]] Vec3 operator*(const Vec3& v) const { return {dot(r[0], v), dot(r[1], v), dot(r[2], v)}; }
    /// Exactly the identity (then M v = v bit for bit, for finite v).
    [[nodiscard]] bool is_identity() const {
        return r[0] == Vec3{1, 0, 0} && r[1] == Vec3{0, 1, 0} && r[2] == Vec3{0, 0, 1};
    }
};

/// The rotation about the unit axis by angle a (Rodrigues).
[[nodiscard]] inline Mat3 axis_rotation(const Vec3& axis, double a) {
    const double c = std::cos(a), s = std::sin(a), t = 1 - c;
    const double x = axis.x, y = axis.y, z = axis.z;
    Mat3 m;
    m.r[0] = {t * x * x + c, t * x * y - s * z, t * x * z + s * y};
    m.r[1] = {t * x * y + s * z, t * y * y + c, t * y * z - s * x};
    m.r[2] = {t * x * z - s * y, t * y * z + s * x, t * z * z + c};
    return m;
}

/// A rigid fit to = rotation (from - c_from) + c_to + residual.
struct RigidFit {
    Point3 c_from, c_to;
    Vec3 axis{0, 0, 1};
    double angle = 0;  ///< 0: no rotation (also when the fit is degenerate)
    [[nodiscard]] Mat3 rotation(double fraction = 1.0) const { return axis_rotation(axis, angle * fraction); }
};

/// The rotation R minimising sum |R (from_i - c_from) - (to_i - c_to)|^2 over the points
/// with keep(i) (Kabsch), as the orthogonal polar factor of sum (to_i - c_to)(from_i -
/// c_from)^T (Newton's iteration X <- (X + X^-T) / 2). Angles below 1e-9 rad count as 0, and
/// so does a degenerate or reflecting fit (coplanar or collinear points).
template <class Keep>
[[nodiscard]] RigidFit fit_rigid(std::span<const Point3> from, std::span<const Point3> to, Keep&& keep) {
    RigidFit f;
    double n = 0;
    Vec3 s0{}, s1{};
    for (std::size_t i = 0; i < from.size(); ++i)
        if (keep(i)) {
            s0 += from[i] - Point3{};
            s1 += to[i] - Point3{};
            n += 1;
        }
    if (n < 3) return f;
    f.c_from = Point3{} + s0 / n;
    f.c_to = Point3{} + s1 / n;
    Mat3 m;
    m.r[0] = m.r[1] = m.r[2] = Vec3{};
    for (std::size_t i = 0; i < from.size(); ++i)
        if (keep(i)) {
            const Vec3 p = from[i] - f.c_from, q = to[i] - f.c_to;
            for (int k = 0; k < 3; ++k) m.r[k] += p * q[k];
        }
    for (int it = 0; it < 64; ++it) {
        // Inverse transpose = cofactor matrix / determinant.
        const Vec3 c0 = cross(m.r[1], m.r[2]), c1 = cross(m.r[2], m.r[0]), c2 = cross(m.r[0], m.r[1]);
        const double det = dot(m.r[0], c0);
        if (!(det > 0) || !std::isfinite(det)) return f;  // degenerate or a reflection
        Mat3 next;
        next.r[0] = (m.r[0] + c0 / det) * 0.5;
        next.r[1] = (m.r[1] + c1 / det) * 0.5;
        next.r[2] = (m.r[2] + c2 / det) * 0.5;
        double change = 0;
        for (int k = 0; k < 3; ++k) change = std::max(change, norm(next.r[k] - m.r[k]));
        m = next;
        if (change < 1e-15) break;
    }
    // Axis and angle of m.
    const double tr = m.r[0].x + m.r[1].y + m.r[2].z;
    const double angle = std::acos(std::clamp((tr - 1) / 2, -1.0, 1.0));
    const Vec3 w{m.r[2].y - m.r[1].z, m.r[0].z - m.r[2].x, m.r[1].x - m.r[0].y};
    if (!(angle > 1e-9) || !(norm(w) > 0)) return f;
    f.axis = w / norm(w);
    f.angle = angle;
    if (angle > 3.0) {  // near pi the skew part loses precision: the axis is the column of m + I
        f.angle = 0;
    }
    return f;
}

}  // namespace dynmesh::detail
