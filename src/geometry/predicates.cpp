#include "dynmesh/geometry/predicates.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "dynmesh/error.hpp"

namespace dynmesh {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
inline K::Point_2 cg(const Point2& p) { return {p.x, p.y}; }
inline K::Point_3 cg(const Point3& p) { return {p.x, p.y, p.z}; }
inline Sign to_sign(CGAL::Sign s) { return static_cast<Sign>(static_cast<int>(s)); }
}  // namespace

Sign orient2d(const Point2& a, const Point2& b, const Point2& c) {
    return to_sign(CGAL::orientation(cg(a), cg(b), cg(c)));
}

Sign incircle(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
    // CGAL's side_of_oriented_circle is positive inside for a CCW circle, like Shewchuk's.
    return to_sign(CGAL::side_of_oriented_circle(cg(a), cg(b), cg(c), cg(d)));
}

Sign orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
    return to_sign(CGAL::orientation(cg(a), cg(b), cg(c), cg(d)));
}

Sign insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
              const Point3& e) {
    const CGAL::Bounded_side s = CGAL::side_of_bounded_sphere(cg(a), cg(b), cg(c), cg(d), cg(e));
    return s == CGAL::ON_BOUNDED_SIDE ? Sign::Positive
                                      : (s == CGAL::ON_BOUNDARY ? Sign::Zero : Sign::Negative);
}

Sign in_diametric_ball(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
    DYNMESH_CHECK(!collinear(a, b, c), "in_diametric_ball: triangle abc is degenerate (collinear)");
    // CGAL: the sphere of smallest radius through a, b, c.
    const CGAL::Bounded_side s = K().side_of_bounded_sphere_3_object()(cg(a), cg(b), cg(c), cg(d));
    return s == CGAL::ON_BOUNDED_SIDE ? Sign::Positive
                                      : (s == CGAL::ON_BOUNDARY ? Sign::Zero : Sign::Negative);
}

bool collinear(const Point3& a, const Point3& b, const Point3& c) {
    return CGAL::collinear(cg(a), cg(b), cg(c));
}

}  // namespace dynmesh
