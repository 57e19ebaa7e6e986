#include "dynmesh/geometry/triangle.hpp"

#include <algorithm>
#include <cmath>
#include <array>
#include <limits>

#include "dynmesh/geometry/scaled_frame.hpp"

namespace dynmesh {

double angle_between(const Vec3& u0, const Vec3& v0) {
    // Each vector scaled on its own (the angle does not change): no overflow or underflow.
    const Vec3 u = ExactScale::to_unit(std::array{u0}).apply(u0);
    const Vec3 v = ExactScale::to_unit(std::array{v0}).apply(v0);
    // atan2 of |u x v| and u.v is accurate for angles near 0 and pi, unlike acos.
    const double s = norm(cross(u, v));
    const double c = dot(u, v);
    if (s == 0.0 && c == 0.0) return 0.0;
    return std::atan2(s, c);
}

double angle_at(const Point3& a0, const Point3& b0, const Point3& c0) {
    const auto [p, scale] = to_unit(std::array{a0, b0, c0});
    return angle_between(p[0] - p[1], p[2] - p[1]);
}

double cos_angle_at(const Point3& a0, const Point3& b0, const Point3& c0) {
    const auto [p, scale] = to_unit(std::array{a0, b0, c0});
    const Vec3 u = p[0] - p[1], v = p[2] - p[1];
    const double d = std::sqrt(sqnorm(u) * sqnorm(v));
    return d > 0 ? std::clamp(dot(u, v) / d, -1.0, 1.0) : 1.0;
}

Point3 circumcenter(const Point3& a0, const Point3& b0, const Point3& c0) {
    const auto [p, scale] = to_unit(std::array{a0, b0, c0});
    const Point3 &a = p[0], &b = p[1], &c = p[2];
    const Vec3 ab = b - a, ac = c - a;
    const Vec3 n = cross(ab, ac);
    const double d = 2.0 * sqnorm(n);
    if (d == 0.0) {
        const double inf = std::numeric_limits<double>::infinity();
        return {inf, inf, inf};
    }
    const Vec3 num = cross(n, ab) * sqnorm(ac) + cross(ac, n) * sqnorm(ab);
    const Point3 x = a + num / d;
    return {scale.length(x.x), scale.length(x.y), scale.length(x.z)};
}

namespace {

/// Circumradius of a triangle already in the unit frame.
double unit_circumradius(const Point3& a, const Point3& b, const Point3& c) {
    const double la = distance(b, c), lb = distance(a, c), lc = distance(a, b);
    const double area2 = norm(triangle_normal_raw(a, b, c));  // twice the area
    if (area2 == 0.0) return std::numeric_limits<double>::infinity();
    return la * lb * lc / (2.0 * area2);
}

/// The three angles of a triangle already in the unit frame.
std::array<double, 3> unit_angles(const Point3& a, const Point3& b, const Point3& c) {
    return {angle_between(b - a, c - a), angle_between(a - b, c - b), angle_between(a - c, b - c)};
}

}  // namespace

double circumradius(const Point3& a0, const Point3& b0, const Point3& c0) {
    const auto [p, scale] = to_unit(std::array{a0, b0, c0});
    return scale.length(unit_circumradius(p[0], p[1], p[2]));
}

double min_angle(const Point3& a0, const Point3& b0, const Point3& c0) {
    const auto [p, scale] = to_unit(std::array{a0, b0, c0});
    const auto t = unit_angles(p[0], p[1], p[2]);
    return std::min({t[0], t[1], t[2]});
}

double max_angle(const Point3& a0, const Point3& b0, const Point3& c0) {
    const auto [p, scale] = to_unit(std::array{a0, b0, c0});
    const auto t = unit_angles(p[0], p[1], p[2]);
    return std::max({t[0], t[1], t[2]});
}

double radius_edge_ratio(const Point3& a0, const Point3& b0, const Point3& c0) {
    const auto [p, scale] = to_unit(std::array{a0, b0, c0});
    const Point3 &a = p[0], &b = p[1], &c = p[2];
    const double shortest = std::sqrt(std::min({sqdistance(a, b), sqdistance(b, c), sqdistance(a, c)}));
    if (shortest == 0.0) return std::numeric_limits<double>::infinity();
    return unit_circumradius(a, b, c) / shortest;
}

double dihedral_angle(const Point3& p0, const Point3& q0, const Point3& r0, const Point3& s0) {
    const auto [u, scale] = to_unit(std::array{p0, q0, r0, s0});
    const Point3 &p = u[0], &q = u[1], &r = u[2], &s = u[3];
    const Vec3 e = normalized(q - p);
    Vec3 x = r - p, y = s - p;
    x -= e * dot(x, e);
    y -= e * dot(y, e);
    return angle_between(x, y);
}

Point2 circumcenter(const Point2& a, const Point2& b, const Point2& c) {
    const Vec2 ab = b - a, ac = c - a;
    const double d = 2.0 * cross(ab, ac);
    const double b2 = dot(ab, ab), c2 = dot(ac, ac);
    return {a.x + (ac.y * b2 - ab.y * c2) / d, a.y + (ab.x * c2 - ac.x * b2) / d};
}

double min_angle(const Point2& a, const Point2& b, const Point2& c) {
    return min_angle(Point3{a.x, a.y, 0}, Point3{b.x, b.y, 0}, Point3{c.x, c.y, 0});
}

double segment_parameter(const Point3& p, const Point3& a, const Point3& b) {
    const Vec3 ab = b - a;
    const double len2 = dot(ab, ab);
    if (!(len2 > 0)) return 0.0;
    return std::clamp(dot(p - a, ab) / len2, 0.0, 1.0);
}

namespace {

ClosestPoint make_closest(const Point3& p, const Point3& x, double u, double v, double w) {
    return {x, u, v, w, distance(p, x)};
}

}  // namespace

ClosestPoint closest_point_on_triangle(const Point3& p, const Point3& a, const Point3& b,
                                       const Point3& c) {
    // Ericson, "Real-Time Collision Detection", 5.1.5: Voronoi regions of the corners, then
    // of the edges, else the interior.
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return make_closest(p, a, 1, 0, 0);
    const Vec3 bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return make_closest(p, b, 0, 1, 0);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double t = d1 / (d1 - d3);
        return make_closest(p, a + ab * t, 1 - t, t, 0);
    }
    const Vec3 cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return make_closest(p, c, 0, 0, 1);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double t = d2 / (d2 - d6);
        return make_closest(p, a + ac * t, 1 - t, 0, t);
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return make_closest(p, b + (c - b) * t, 0, 1 - t, t);
    }
    const double sum = va + vb + vc;
    if (!(sum > 0) || !std::isfinite(sum)) {
        // Degenerate triangle: the best of its three edges.
        const double tab = segment_parameter(p, a, b), tbc = segment_parameter(p, b, c),
                     tca = segment_parameter(p, c, a);
        ClosestPoint best = make_closest(p, a + (b - a) * tab, 1 - tab, tab, 0);
        const ClosestPoint e2 = make_closest(p, b + (c - b) * tbc, 0, 1 - tbc, tbc);
        const ClosestPoint e3 = make_closest(p, c + (a - c) * tca, tca, 0, 1 - tca);
        if (e2.distance < best.distance) best = e2;
        if (e3.distance < best.distance) best = e3;
        return best;
    }
    const double v = vb / sum, w = vc / sum;
    return make_closest(p, a + ab * v + ac * w, 1 - v - w, v, w);
}

}  // namespace dynmesh
