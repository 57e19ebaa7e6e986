#pragma once
/// \file Robust geometric predicates (CGAL's filtered-exact Epick kernel behind a plain API).
///
/// Each returns the exact sign for the given double coordinates: a fast interval filter,
/// exact arithmetic only when the sign is in doubt. Sign conventions follow Shewchuk/CGAL.

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

enum class Sign : int { Negative = -1, Zero = 0, Positive = 1 };

/// Positive when a, b, c make a left turn (counter-clockwise).
[[nodiscard]] Sign orient2d(const Point2& a, const Point2& b, const Point2& c);
/// Positive when d lies inside the circle through a, b, c, which must be counter-clockwise
/// (for clockwise a, b, c the sign flips, as in Shewchuk's incircle).
[[nodiscard]] Sign incircle(const Point2& a, const Point2& b, const Point2& c, const Point2& d);
/// Positive when d lies on the positive side of the plane through a, b, c, i.e. when
/// (a, b, c, d) is a positively oriented tetrahedron (CGAL's orientation convention:
/// det[b-a, c-a, d-a] > 0).
[[nodiscard]] Sign orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d);
/// Positive when e lies inside the sphere through a, b, c, d (any orientation).
[[nodiscard]] Sign insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                            const Point3& e);
/// Positive when d lies strictly inside the diametric ball of triangle abc (the smallest ball
/// whose boundary passes through a, b, c), zero on its boundary, negative outside.
/// \pre a, b, c not collinear (checked: throws InvalidInput).
[[nodiscard]] Sign in_diametric_ball(const Point3& a, const Point3& b, const Point3& c,
                                     const Point3& d);
/// True when a, b, c are exactly collinear.
[[nodiscard]] bool collinear(const Point3& a, const Point3& b, const Point3& c);

}  // namespace dynmesh
