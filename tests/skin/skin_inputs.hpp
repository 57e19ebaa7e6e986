#pragma once
/// \file Synthetic weighted-point sets shared by the skin tests (specs/skin-surfaces.md §6.4).
#include <cmath>
#include <vector>

#include "dynmesh/skin/molecule.hpp"

namespace dynmesh::test {

/// CGAL's four-ball example: the even-parity cube corners, all of weight w (§8 correction 5).
inline std::vector<WeightedPoint> four_balls(double w) {
    std::vector<WeightedPoint> B;
    for (const Point3& p : {Point3{1, -1, -1}, Point3{1, 1, 1}, Point3{-1, 1, -1}, Point3{-1, -1, 1}}) B.push_back({p, w});
    return B;
}

/// n balls on a circle of radius R, slightly off its plane; every other weight is w·(1 + dw).
inline std::vector<WeightedPoint> ring(int n, double R, double w, double dw = 0) {
    std::vector<WeightedPoint> B;
    for (int k = 0; k < n; ++k) {
        const double a = 2 * M_PI * k / n;
        B.push_back({{R * std::cos(a), R * std::sin(a), 0.01 * (k % 3)}, w * (1 + dw * (k % 2))});
    }
    return B;
}

}  // namespace dynmesh::test
