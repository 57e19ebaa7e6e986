#pragma once
/// \file Floating-point measures of triangles and edges (angles, circumcentres, normals).
///
/// These are measurements, not decisions; decisions that must be exact go through
/// predicates.hpp. The angle and ratio measures, the circumcentre and the circumradius are
/// computed on their points scaled by an exact power of two (scaled_frame.hpp): correct
/// near the double limits (coordinates near 1e308 or subnormal), and bit-identical to the
/// plain computation everywhere else.

#include <numbers>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double rad_to_deg(double r) { return r * (180.0 / kPi); }
inline constexpr double deg_to_rad(double d) { return d * (kPi / 180.0); }

/// Angle in radians between vectors u and v, in [0, pi]; 0 when either is zero.
double angle_between(const Vec3& u, const Vec3& v);
/// The angle abc at b, in radians.
double angle_at(const Point3& a, const Point3& b, const Point3& c);
/// Cosine of the angle abc at b; 1 when a or c coincides with b.
double cos_angle_at(const Point3& a, const Point3& b, const Point3& c);
/// Non-normalised normal (b - a) x (c - a); its length is twice the area.
inline Vec3 triangle_normal_raw(const Point3& a, const Point3& b, const Point3& c) {
    return cross(b - a, c - a);
}
/// Unit normal of the counter-clockwise triangle abc (zero vector if degenerate).
inline Vec3 triangle_normal(const Point3& a, const Point3& b, const Point3& c) {
    return normalized(triangle_normal_raw(a, b, c));
}
inline double triangle_area(const Point3& a, const Point3& b, const Point3& c) {
    return 0.5 * norm(triangle_normal_raw(a, b, c));
}
/// Centre of the circle through a, b, c in their plane (the diametric ball's centre).
/// Returns a non-finite point for collinear input.
Point3 circumcenter(const Point3& a, const Point3& b, const Point3& c);
/// Radius of the circle through a, b, c (infinity when collinear).
double circumradius(const Point3& a, const Point3& b, const Point3& c);
/// Smallest of the three angles, in radians.
double min_angle(const Point3& a, const Point3& b, const Point3& c);
/// Largest of the three angles, in radians.
double max_angle(const Point3& a, const Point3& b, const Point3& c);
/// Circumradius over shortest edge (1/sqrt(3) for an equilateral triangle).
double radius_edge_ratio(const Point3& a, const Point3& b, const Point3& c);
/// Dihedral angle at edge pq between triangles pqr and pqs, in radians in [0, pi]: the
/// smaller sector cut by a plane orthogonal to pq (pi for a flat pair). Orientation-free.
double dihedral_angle(const Point3& p, const Point3& q, const Point3& r, const Point3& s);

/// 2D measures.
Point2 circumcenter(const Point2& a, const Point2& b, const Point2& c);
double min_angle(const Point2& a, const Point2& b, const Point2& c);

/// Closest point of triangle abc to p: point = u a + v b + w c with u + v + w = 1, all >= 0
/// (Ericson's region classification: a coordinate is exactly 0 when the point is on the
/// opposite edge, two are exactly 0 at a corner).
struct ClosestPoint {
    Point3 point;
    double u = 0, v = 0, w = 0;  ///< barycentric coordinates for a, b, c
    double distance = 0;         ///< |p - point|
};
[[nodiscard]] ClosestPoint closest_point_on_triangle(const Point3& p, const Point3& a,
                                                     const Point3& b, const Point3& c);
/// The closest point of segment ab to p as the parameter t of a + t (b - a), in [0, 1]
/// (0 for a = b).
[[nodiscard]] double segment_parameter(const Point3& p, const Point3& a, const Point3& b);
/// Squared distance from p to triangle abc.
[[nodiscard]] inline double sq_dist_to_triangle(const Point3& p, const Point3& a, const Point3& b,
                                                const Point3& c) {
    return sqnorm(p - closest_point_on_triangle(p, a, b, c).point);
}

}  // namespace dynmesh
