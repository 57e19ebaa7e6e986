#pragma once
/// \file Post-conditions of flip smoothing that tests and `--check` measure.

#include <cstddef>

#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

struct FlipDiagnostics {
    std::size_t edges = 0;
    std::size_t flippable = 0;           ///< edges flippable under the rule asked for
    std::size_t illegal = 0;             ///< Definition 4 illegal edges
    std::size_t faces = 0;
    std::size_t nonempty_balls = 0;      ///< faces whose shrunken diametric ball holds a vertex
    /// Faces whose ball spans too many grid cells to be searched (huge circumradius next to
    /// small edges, typically a near-degenerate triangle): not tested, counted here.
    std::size_t unchecked_balls = 0;
    double ball_shrink = 0.95;
};

/// Counts flippable and illegal edges, and faces whose ball B(c, shrink * radius) contains a
/// vertex of the mesh (uniform grid over the vertices). Linear in the mesh size for meshes of
/// bounded local density.
[[nodiscard]] FlipDiagnostics flip_diagnostics(const SurfaceMesh& mesh, FlipRule rule,
                                               double ball_shrink = 0.95);

}  // namespace dynmesh
