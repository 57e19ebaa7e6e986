#include "dynmesh/geometry/triangle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dynmesh {

double angle_between(const Vec3& u, const Vec3& v) {
    // atan2 of |u x v| and u.v is accurate for angles near 0 and pi, unlike acos.
    const double s = norm(cross(u, v));
    const double c = dot(u, v);
    if (s == 0.0 && c == 0.0) return 0.0;
    return std::atan2(s, c);
}

double cos_angle_at(const Point3& a, const Point3& b, const Point3& c) {
    const Vec3 u = a - b, v = c - b;
    const double d = std::sqrt(sqnorm(u) * sqnorm(v));
    return d > 0 ? std::clamp(dot(u, v) / d, -1.0, 1.0) : 1.0;
}

Point3 circumcenter(const Point3& a, const Point3& b, const Point3& c) {
    const Vec3 ab = b - a, ac = c - a;
    const Vec3 n = cross(ab, ac);
    const double d = 2.0 * sqnorm(n);
    if (d == 0.0) {
        const double inf = std::numeric_limits<double>::infinity();
        return {inf, inf, inf};
    }
    const Vec3 num = cross(n, ab) * sqnorm(ac) + cross(ac, n) * sqnorm(ab);
    return a + num / d;
}

double circumradius(const Point3& a, const Point3& b, const Point3& c) {
    const double la = distance(b, c), lb = distance(a, c), lc = distance(a, b);
    const double area2 = norm(triangle_normal_raw(a, b, c));  // twice the area
    if (area2 == 0.0) return std::numeric_limits<double>::infinity();
    return la * lb * lc / (2.0 * area2);
}

double min_angle(const Point3& a, const Point3& b, const Point3& c) {
    return std::min({angle_at(b, a, c), angle_at(a, b, c), angle_at(a, c, b)});
}

double max_angle(const Point3& a, const Point3& b, const Point3& c) {
    return std::max({angle_at(b, a, c), angle_at(a, b, c), angle_at(a, c, b)});
}

double radius_edge_ratio(const Point3& a, const Point3& b, const Point3& c) {
    const double shortest = std::sqrt(std::min({sqdistance(a, b), sqdistance(b, c), sqdistance(a, c)}));
    if (shortest == 0.0) return std::numeric_limits<double>::infinity();
    return circumradius(a, b, c) / shortest;
}

double dihedral_angle(const Point3& p, const Point3& q, const Point3& r, const Point3& s) {
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

}  // namespace dynmesh
