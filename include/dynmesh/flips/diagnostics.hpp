#pragma once
/// \file Post-conditions of flip smoothing that tests and `--check` measure.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/flips/flip_smooth.hpp"
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

struct LocalFlipCheckOptions {
    FlipRule rule = FlipRule::AngleDef3;  ///< the rule flip_local() ran with
    double feature_angle_deg = 180.0;     ///< ... and its sharp-feature guard
    double ball_shrink = 0.95;
};

/// The local-mode acceptance check of the edge-flip digest (§7 item 9) for a flip_local()
/// run that turned `before` into `after`. F = the triangles of `after` with a corner within
/// 1 hop of V; far = the triangles with every corner more than report.final_m + 1 hops from
/// V, counting hops along the edges of `before` and of `after` together. (Flips change the
/// edge graph: a window vertex whose long edges were flipped away can end up farther from V
/// in `after` than the window that flipped them, and in `before` new short edges are
/// missing. In the union every flip of the run stays within final_m hops, as measured on
/// worsened spheres with one to three rounds.)
///
/// Figures (the keys of `dynmesh flip --report`'s check.local_check): near_faces (|F|),
/// flippable_edges and illegal_edges (edges of F flippable under the rule / illegal by
/// Definition 4), nonempty_balls (triangles of F whose shrunken ball holds a vertex),
/// unchecked_balls (... whose ball could not be searched), far_faces (far triangles compared
/// with `before`), far_faces_changed (... that are not bit-identical), moved_vertices
/// (vertices whose position changed, bits). Problems: one line per violated condition (the run
/// did not converge, a vertex moved, a far triangle changed, or F has a flippable or illegal
/// edge or a non-empty shrunken ball).
///
/// Runs the check. The ball test searches every vertex of `after` through a uniform grid,
/// so a fold from elsewhere on the surface is caught; O(mesh size).
/// \pre before and after have no garbage. \throw InvalidInput when their element counts
///      differ or V names a vertex outside the mesh.
[[nodiscard]] CheckReport check_local_flip(const SurfaceMesh& before, const SurfaceMesh& after,
                                           std::span<const Vertex> V, const LocalFlipReport& report,
                                           const LocalFlipCheckOptions& options = {});

}  // namespace dynmesh
