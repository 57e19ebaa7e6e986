#pragma once
/// \file The topology a skin must have (specs/skin-surfaces.md §6.3 M2): the body bounded by the
/// skin at time t is homotopy equivalent to the weighted alpha complex of the balls at α = t
/// (every weight + t), so the skin has b0 + b2 components and Euler characteristic
/// 2(b0 − b1 + b2), with b0, b1, b2 the Betti numbers of that complex.

#include <vector>

#include "dynmesh/skin/molecule.hpp"

namespace dynmesh {

struct SkinTopology {
    long long b0 = 0;  ///< components of the body
    long long b1 = 0;  ///< independent tunnels
    long long b2 = 0;  ///< voids
    [[nodiscard]] long long euler() const { return 2 * (b0 - b1 + b2); }
    [[nodiscard]] long long components() const { return b0 + b2; }
};

/// The Betti numbers of the weighted alpha complex of `balls` at α = t (CGAL's Alpha_shape_3 on
/// the regular triangulation, in GENERAL mode): b0 by union-find over its vertices and edges,
/// b2 by union-find over the cells outside it (joined across facets outside it; the unbounded
/// part counts once), b1 from its Euler characteristic V − E + F − T = b0 − b1 + b2.
/// \throw InvalidInput for no ball or a non-finite centre or weight.
[[nodiscard]] SkinTopology skin_topology(const std::vector<WeightedPoint>& balls, double t);

}  // namespace dynmesh
