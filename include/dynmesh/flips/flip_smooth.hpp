#pragma once
/// \file Flipping to termination: globally in linear time (edge-flip paper, L4.3) and locally
/// around a vertex subset with the practical doubling-window method (§6 of that paper).

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/mesh/index_map.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

/// Called now and then with (flips so far, queue length); for progress output.
using FlipProgress = std::function<void(std::size_t flips, std::size_t queued)>;

/// Whether flip_all() works on a spatially renumbered mesh (mesh_order.hpp) and numbers it
/// back at the end. Measured by bench/flips/flip_bench.cpp on worsened meshes: a 1M-vertex
/// sphere numbered at random flips 3.2x faster with renumbering (renumbering included); the
/// Armadillo subdivided to 1.66M vertices, in file order (random order of its coarse faces,
/// each one's 64 children together) flips 1.55x slower than sorted, and renumbering just
/// breaks even there (the two permutations cost what the flips gain); renumbering a mesh
/// that is sorted already costs about 0.25 us per vertex (+30%).
enum class FlipReorder {
    /// Renumber when the mesh has at least kReorderMinVertices vertices (smaller ones stay
    /// in cache) and more than kReorderScatteredFraction of its edges join vertices whose
    /// indices are more than 4096 apart (scattered_edge_fraction: 0.03 sorted, 0.63 for
    /// the subdivided scan, 0.99 at random).
    Auto,
    Always,
    Never  ///< flip in the caller's numbering
};
inline constexpr std::size_t kReorderMinVertices = std::size_t(1) << 17;
inline constexpr double kReorderScatteredFraction = 0.25;

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
    /// flip_all() only (flip_from() keeps the caller's numbering and order).
    FlipReorder reorder = FlipReorder::Auto;
};

struct FlipReport {
    std::size_t flips = 0;           ///< flips performed
    std::size_t checks = 0;          ///< flippability tests evaluated (one per queue pop)
    std::size_t pushes = 0;          ///< queue insertions
    std::size_t degenerate = 0;      ///< tests refused for a degenerate triangle (never flipped)
    std::size_t not_improving = 0;   ///< tests refused by the anti-cycling guard
    std::size_t feature_locked = 0;  ///< flippable edges refused by the sharp-feature guard
    bool converged = false;          ///< the queue emptied (no flippable edge is left)
    bool renumbered = false;         ///< flip_all() flipped a spatially renumbered mesh
    double seconds = 0;              ///< wall time of the flipping (and renumbering) alone
};

/// Queue-based flipping until no edge is flippable under options.rule (FIFO with an in-queue
/// flag; stale entries are re-checked at pop time). The queue starts with every edge in index
/// order; with renumbering (options.reorder) that order follows a space-filling curve.
/// Vertex positions and indices never change. Face and edge indices are kept (a flip reuses
/// its edge and two faces), also when the mesh is renumbered internally.
/// \pre mesh has no garbage (call garbage_collection() first). \throw InvalidInput otherwise.
FlipReport flip_all(SurfaceMesh& mesh, const FlipOptions& options = {});

/// Lawson propagation from a seed set: queues `seeds`, and after every flip the four outer
/// edges of its quad, until the queue empties (no bound on the region). Unlike flip_all()
/// the mesh may hold deleted elements (deleted seeds are skipped). options.progress and
/// options.reorder are ignored; the cap is options.max_flips_per_vertex * n_vertices().
/// A seed set much smaller than the mesh keeps its in-queue flags in a hash set, so the call
/// costs what its flips cost, not O(mesh).
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
    /// What the stop test checks (the cheaper variant of §4.4 of the digest): F = the
    /// triangles with a corner within 1 hop of V; the ring = the triangles that are not
    /// marked (a corner beyond m hops) but touch a vertex within m + 1 hops. The window is
    /// final when no diametric ball of F meets a ring triangle (closest point closer than the
    /// circumradius). Ring triangles are found through a uniform grid over their centroids,
    /// so the test costs O(|F| + |ring|). It does not search the rest of the mesh: a fold of
    /// the surface that reaches a ball of F from elsewhere is not seen (check_local_flip()
    /// in diagnostics.hpp searches the whole mesh).
    bool converged = false;
    std::size_t window_vertices = 0;  ///< vertices within final_m hops of V (last round)
    std::size_t ring_faces = 0;       ///< ring triangles of the last stop test
    std::size_t ball_tests = 0;       ///< triangles of F tested by the last stop test
    /// Triangles of F without a finite diametric ball (degenerate) in the last stop test:
    /// not tested.
    std::size_t unchecked_balls = 0;
};

/// Flips around the vertex set V: runs the queue on the edges whose endpoints are both within
/// m hops of V, m = m0, 2 m0, ..., until the stop test (LocalFlipReport::converged) passes.
/// Hops are counted in the current edge graph, recomputed after each round's flips.
/// Cost is proportional to the window, not to the mesh: no per-call array over the mesh
/// (IndexMap / IndexSet for hops, queue flags and changed faces).
/// \pre mesh has no garbage; V holds live vertices. \throw InvalidInput otherwise.
LocalFlipReport flip_local(SurfaceMesh& mesh, std::span<const Vertex> V,
                           const LocalFlipOptions& options = {});

/// Hop distance from V of every vertex within `limit` edge hops (breadth-first in the current
/// edge graph), into `out` (cleared first); V itself is at 0.
void hop_distances(const SurfaceMesh& mesh, std::span<const Vertex> V, std::size_t limit,
                   IndexMap<std::uint32_t>& out);
/// The same in the union of the edge graphs of several meshes on one vertex set (an edge of
/// any of them is a hop). \pre every mesh has the vertices of V.
void hop_distances(std::span<const SurfaceMesh* const> meshes, std::span<const Vertex> V, std::size_t limit,
                   IndexMap<std::uint32_t>& out);

}  // namespace dynmesh
