#pragma once
/// \file DynOffCenterMesh2: dynamic off-center refinement in 2D (DynHPU "fast mode", spec
/// shared/specs/dynamic-quadtree.md §5.4). It keeps the off-center refinement of a dynamic point
/// set and, after every insert or erase, equals the static offcenter_mesh() of the current point
/// set exactly (same Steiner points, bit for bit, same triangles, same counters): the result is
/// history independent. An update re-executes only the part of the static run that the change
/// reaches.
///
/// How (change propagation over an explicit timeline, spec §5.4, specialised by hand):
///   * The static run (offcenter.hpp) is recorded as a trace of **evaluations**, each stamped
///     with its place in the static execution order:
///       - a *creation* evaluation per vertex v, at v's stamp (initial vertices: after round 0):
///         the loose (pair, side) candidates whose later endpoint is v, found from v's Delaunay
///         star among the vertices stamped ≤ v;
///       - a *processing* evaluation per candidate and round, at stamp (round class i, round
///         index k, canonical key of the pair, side): loose test, off-center, encroachment test,
///         then insert the off-center (or split box subsegments) and decide the retry.
///     Every vertex carries the stamp of the evaluation that created it (inputs and box corners
///     −∞, round-0 midpoints next, then (i, k, key, output number)).
///   * Every query an evaluation makes is **time-filtered**: "vertices stamped before me". The
///     queries are best-first searches in bucket PR-quadtrees holding every vertex, one for the
///     initial vertices and one for the Steiner points, each node carrying the smallest
///     (phase, class, round) of its subtree for pruning: the Delaunay neighbour of a pair on one
///     side (the vertex minimising the circle through the pair; exact incircle comparisons, all
///     exact ties returned), the nearest neighbour, and the Delaunay star of a vertex by
///     gift-wrapping with the former. Their cost depends on the vertices near the answer, not
///     on the number in the region (a dense cluster behind a pair is not enumerated).
///   * Loose tests and off-centers use the same numeric kernel as offcenter_mesh()
///     (detail::OffCenterKernel) on the same canonical opposite vertex (the lexicographically
///     smallest of the exact minimisers), hence bit-identical Steiner points.
///   * Every evaluation records its **read region**: closed discs (the enlarged leaves and the
///     crescent disc up to the opposite vertex for a processing; the circumdiscs of the star for
///     a creation) and, for the encroachment test, the box subsegments it looked at. An update
///     inserts or removes the input (the dirty set Δ starts with it), then runs a priority queue
///     of evaluations in timeline order: an evaluation is re-run when a vertex stamped before it
///     appears or vanishes inside its read region (or on a subsegment it read). A re-run whose
///     outcome differs removes the vertices and candidates it created before (recursively, with
///     everything they created) and creates the new ones; each vertex that appears or vanishes
///     joins Δ and schedules the later evaluations reading it. By induction over the timeline
///     the trace then equals the trace of a static run on the new point set.
///   * The output Delaunay triangulation (CGAL Delaunay_triangulation_2) is updated by removing
///     and inserting the symmetric difference of the vertex sets; mesh() then canonicalises
///     degenerate cells exactly as offcenter_mesh() does (detail::finish_offcenter_mesh).
///   * The live mesh (current_mesh(), live_mesh.hpp) holds the same canonical triangles with
///     stable ids and is updated locally: the Delaunay cells (maximal sets of triangles with
///     one empty circumcircle) incident to a vertex that was inserted or removed, or to one of
///     its neighbours at that moment, are re-derived from the triangulation, each as a fan from
///     its smallest vertex in mesh()'s index order (inputs by snapped coordinates, then Steiner
///     points by (x, y)); cells whose ring did not change keep their triangles and ids. Every
///     cell created or destroyed by the update has such a vertex, so the rest is unchanged.
///     last_change() lists the triangles and vertices removed and added.
///
/// Deviations and limits (see also the .cpp):
///   * The static algorithm was made canonical where it used to depend on CGAL's choice among
///     cocircular vertices (offcenter.hpp, "degenerate configurations"); its guarantees and tests
///     are unchanged.
///   * Spec §5.4 suggests re-enumerating candidates from local triangulations of time-filtered
///     points; here candidates are owned by the creation evaluation of their later endpoint, and
///     all reads are best-first searches, which bounds the work per evaluation by the points near
///     the answer (the cluster pitfall of §5.4). HPU's "active points" are not used: the
///     per-update bound is measured (offcenter_update_bench), not proved.
///   * Round 0 is maintained by counting, per box side, the inputs in its closed diametral disc
///     (a middle-third input can only encroach a whole side, so round 0 splits each side at most
///     once).
///   * No full recompute is ever done (OffCenterUpdateReport::full_recomputes stays 0; it is
///     kept so a future fallback would be counted). build() runs the same propagation on an
///     empty trace.
///   * Read regions are conservative (enlarged by a relative 1e-9 and by the angle slack), so
///     some re-runs find the same outcome; they are counted in `evaluations`.
///   * mesh() costs O(n + m) (it returns the whole canonical mesh); the stored state, the
///     triangulation and current_mesh() are updated locally.
///   * Precision: the best-first searches measure every candidate relative to the pair's first
///     endpoint (differences of nearby doubles are exact), never to a rounded absolute midpoint,
///     and read-region discs are enlarged by the rounding of their centres, so pairs of any
///     resolvable length (offcenter_min_separation()) are searched exactly.
///   * A read region that would be unbounded (only when the closed-leaf slack exceeds θ_min,
///     which offcenter_min_separation() now rules out for input pairs) is registered as global:
///     such an evaluation is re-run on every change stamped before it. Correct, but not local.
///   * build() is slower than offcenter_mesh() (best-first searches instead of one CGAL
///     triangulation: about 6–8× at n = 1e4–1e5) and the trace costs memory per vertex.
///   * Measured (offcenter_update_bench, ρ = 1.5, one update = an insert or an erase):
///     0.4–0.75 ms per update for uniform inputs at n = 1e3, 1e4, 1e5 (about 14–18 evaluations,
///     3 Steiner points changed), 0.75–1.6 ms for clustered ones (about 30 evaluations); with a
///     cluster of side 10^-k among 4000 points, about 4–5 more evaluations and 0.5 ms more per
///     decade of spread (linear in lg L/s).

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/quadtree/live_mesh.hpp"
#include "dynmesh/quadtree/offcenter.hpp"
#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh {

/// What the last successful insert or erase of a DynOffCenterMesh2 did.
struct OffCenterUpdateReport {
    std::size_t steiner_added = 0;      // Steiner points (incl. boundary midpoints) now present
                                        // that were not before
    std::size_t steiner_removed = 0;    // ... present before and not now
    std::size_t simplices_added = 0;    // triangles of the canonical mesh that are new (exact:
                                        // last_change().added_simplices.size())
    std::size_t simplices_removed = 0;  // ... that disappeared (last_change().removed_simplices)
    std::size_t evaluations = 0;        // creation and processing evaluations (re-)run
    std::size_t rounds_visited = 0;     // distinct rounds (class, index) of those evaluations
    std::size_t queries = 0;            // best-first searches made by those evaluations
    std::size_t full_recomputes = 0;    // from-scratch recomputations (always 0, see file comment)
};

/// The off-center refinement of a dynamic point set in the box Ω (see the file comment).
class DynOffCenterMesh2 {
public:
    /// An empty point set over the domain (the mesh is the box, two triangles).
    /// \throw InvalidInput if the domain is invalid (as DynQuadtree) or options.rho is not finite
    ///        and > √2.
    DynOffCenterMesh2(const QuadtreeOptions<2>& domain, const OffCenterOptions& options);
    ~DynOffCenterMesh2();
    DynOffCenterMesh2(DynOffCenterMesh2&&) noexcept;
    DynOffCenterMesh2& operator=(DynOffCenterMesh2&&) noexcept;

    /// From-scratch construction on `points`.
    /// \throw InvalidInput as DynQuadtree::build (the point naming its index), for a bad ρ, or
    ///        naming a point closer to another than offcenter_min_separation() (offcenter.hpp).
    [[nodiscard]] static DynOffCenterMesh2 build(std::span<const Vec2> points,
                                                 const QuadtreeOptions<2>& domain,
                                                 const OffCenterOptions& options);

    /// Inserts p, with DynQuadtree<2>::insert's validation (snapping, middle third, duplicates,
    /// NaN, resolution); BeyondPrecision also when p is closer to an input than
    /// offcenter_min_separation(). On any result other than Inserted nothing changes
    /// (last_update() and last_change() included).
    /// \throw InternalError if more than options.max_steiner Steiner points would be needed
    ///        (the object is then unusable).
    [[nodiscard]] InsertResult insert(const Vec2& p);
    /// Erases the stored point with p's snapped grid coordinates; on NotFound nothing changes.
    [[nodiscard]] EraseResult erase(const Vec2& p);

    /// The point set and domain.
    [[nodiscard]] const DynQuadtree<2>& tree() const;
    [[nodiscard]] const OffCenterOptions& options() const;
    /// The refined mesh, equal (points, triangles, input_vertices and every counter) to
    /// offcenter_mesh(tree(), options()). O(n + m).
    [[nodiscard]] OffCenterMesh2 mesh() const;
    /// Number of vertices (inputs + Steiner points) of the current mesh. O(1).
    [[nodiscard]] std::size_t vertex_count() const;
    /// The work of the last successful insert or erase.
    [[nodiscard]] const OffCenterUpdateReport& last_update() const;
    /// The current mesh with stable ids (live_mesh.hpp), maintained by every update: the
    /// triangles of mesh() in slot order. O(1).
    [[nodiscard]] const LiveMesh<2>& current_mesh() const;
    /// What the last successful insert or erase changed in current_mesh(); empty after
    /// construction and build().
    [[nodiscard]] const MeshDelta<2>& last_change() const;

    /// Every violated invariant, one problem each (ok() when the state is valid; no figure).
    /// Compares the stored trace (vertices with stamps and kinds, candidates, outcomes), the
    /// triangulation and mesh() with a from-scratch build and with offcenter_mesh(), and checks
    /// the spatial indices. O((n + m) log(n + m)).
    [[nodiscard]] CheckReport check_invariants() const;

private:
    struct Impl;
    explicit DynOffCenterMesh2(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace dynmesh
