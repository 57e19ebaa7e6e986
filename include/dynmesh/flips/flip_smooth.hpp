#pragma once
/// \file Flipping to termination: globally in linear time (edge-flip paper, L4.3) and locally
/// around a vertex subset with the practical doubling-window method (§6 of that paper).

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

/// Called now and then with (flips so far, queue length); for progress output.
using FlipProgress = std::function<void(std::size_t flips, std::size_t queued)>;

struct FlipOptions {
    FlipRule rule = FlipRule::AngleDef3;
    /// Diagnostic cap: stop after max_flips_per_vertex * n_vertices flips (converged = false).
    /// The theory bounds flips by O(n) for dense meshes.
    std::size_t max_flips_per_vertex = 100;
    /// Sharp-feature guard: an edge whose 180 - dihedral exceeds this (degrees) is never
    /// flipped, and no flip may create such an edge. 180 = off (the papers' algorithms).
    /// 60 keeps the creases of CAD meshes.
    double feature_angle_deg = 180.0;
    FlipProgress progress = {};
};

struct FlipReport {
    std::size_t flips = 0;           ///< flips performed
    std::size_t checks = 0;          ///< flippability tests evaluated (one per queue pop)
    std::size_t pushes = 0;          ///< queue insertions
    std::size_t degenerate = 0;      ///< tests refused for a degenerate triangle (never flipped)
    std::size_t not_improving = 0;   ///< tests refused by the anti-cycling guard
    std::size_t feature_locked = 0;  ///< flippable edges refused by the sharp-feature guard
    bool converged = false;          ///< the queue emptied (no flippable edge is left)
    double seconds = 0;              ///< wall time of the flipping alone
};

/// Queue-based flipping until no edge is flippable under options.rule (FIFO with an in-queue
/// flag; stale entries are re-checked at pop time). Vertex positions and indices never
/// change. Face and edge indices are kept (a flip reuses its edge and two faces).
/// \pre mesh has no garbage (call garbage_collection() first). \throw InvalidInput otherwise.
FlipReport flip_all(SurfaceMesh& mesh, const FlipOptions& options = {});

/// Lawson propagation from a seed set: queues `seeds`, and after every flip the four outer
/// edges of its quad, until the queue empties (no bound on the region). Unlike flip_all()
/// the mesh may hold deleted elements (deleted seeds are skipped). options.progress is
/// ignored; the cap is options.max_flips_per_vertex * n_vertices().
FlipReport flip_from(SurfaceMesh& mesh, std::span<const Edge> seeds, const FlipOptions& options);

struct LocalFlipOptions {
    FlipRule rule = FlipRule::AngleDef3;
    double feature_angle_deg = 180.0;  ///< as FlipOptions::feature_angle_deg
    std::size_t m0 = 3;           ///< first window radius in edge hops
    std::size_t max_rounds = 16;  ///< doubling rounds before giving up (converged = false)
    /// Diagnostic cap per round: max_flips_per_vertex * (vertices in the window).
    std::size_t max_flips_per_vertex = 100;
};

struct LocalFlipReport {
    FlipReport flips;                 ///< accumulated over all rounds
    std::size_t rounds = 0;           ///< doubling rounds run
    std::size_t final_m = 0;          ///< the window radius of the last round
    std::vector<Face> changed_faces;  ///< faces touched by a flip (sorted, unique)
    /// The stop test checks each triangle of F against the triangles of the first ring
    /// outside the window (the cheaper variant of §4.4 of the digest), not a global search.
    bool converged = false;
};

/// Flips around the vertex set V: runs the queue on the edges whose endpoints are both within
/// m hops of V, m = m0, 2 m0, ..., until every triangle incident to V or to a neighbour of V
/// has a diametric ball that meets only triangles within the window.
/// Cost is proportional to the window, not to the mesh.
LocalFlipReport flip_local(SurfaceMesh& mesh, std::span<const Vertex> V,
                           const LocalFlipOptions& options = {});

}  // namespace dynmesh
