#pragma once
/// \file When a circumcentre computed in double is good enough (the probing and skin triangulations).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <CGAL/squared_distance_2.h>
#include <CGAL/squared_distance_3.h>

namespace dynmesh::detail {

/// True when the double circumcentre x of the points p (a cell's 4 in 3D, a face's 3 in 2D) is
/// within about 1e-12 of the radius (its squared distances to the points agree to 2e-12) and
/// the simplex is not nearly flat (radius at most 1e3 times the longest edge: a flat simplex
/// has its centre far along the normal, on a side the double construction may get wrong while
/// the distances still agree). Otherwise the callers construct it exactly.
template <class KPoint, std::size_t N>
[[nodiscard]] bool circumcenter_is_accurate(const KPoint& x, const std::array<const KPoint*, N>& p) {
    double lo = HUGE_VAL, hi = 0, edge2 = 0;
    for (std::size_t i = 0; i < N; ++i) {
        const double r = CGAL::squared_distance(x, *p[i]);
        lo = std::min(lo, r);
        hi = std::max(hi, r);
        for (std::size_t j = i + 1; j < N; ++j) edge2 = std::max(edge2, CGAL::squared_distance(*p[i], *p[j]));
    }
    return std::isfinite(hi) && hi - lo <= 2e-12 * hi && hi <= 1e6 * edge2;
}

}  // namespace dynmesh::detail
