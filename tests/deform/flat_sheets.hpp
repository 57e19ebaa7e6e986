#pragma once
// The two-sheet motion of the deform tests: a flat ellipsoid whose lower sheet is pushed up
// under its upper sheet, which stays still.

#include <algorithm>
#include <cmath>
#include <vector>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh::test {

/// The flat ellipsoid (1, 1, 0.35) of these tests.
inline constexpr double kFlatHalfHeight = 0.35;

/// p0 with the middle of the lower sheet (radius 0.6, smoothed over 0.2) moved a share f in
/// [0, 1] of the way to `gap` under the upper sheet.
inline std::vector<Point3> pushed_under(const std::vector<Point3>& p0, double f, double gap) {
    std::vector<Point3> out = p0;
    for (Point3& p : out) {
        if (p.z >= 0) continue;
        const double r2 = p.x * p.x + p.y * p.y;
        const double u = std::clamp((0.6 - std::sqrt(r2)) / 0.2, 0.0, 1.0), w = u * u * (3 - 2 * u);
        const double under = kFlatHalfHeight * std::sqrt(std::max(0.0, 1 - r2)) - gap;
        p.z += f * w * (under - p.z);
    }
    return out;
}

}  // namespace dynmesh::test
