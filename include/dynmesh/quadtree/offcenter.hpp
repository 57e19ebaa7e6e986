#pragma once
/// \file Off-center Delaunay refinement in 2D after Har-Peled & Üngör ("A time-optimal Delaunay
/// refinement algorithm in two dimensions", SoCG 2005) as used by Acar & Hudson (CMU-CS-07-121,
/// Figure 3): the static DynHPU algorithm of shared/specs/dynamic-quadtree.md §5.3, driven by the
/// points and domain of a DynQuadtree<2>.
///
/// Vocabulary (spec §5.1), for a pair pq of length ℓ and a side (ccw or cw of lo→hi):
///   * **leaf**: the disc through p and q of radius ρℓ centred on that side. A point t on the
///     same side lies in the closed leaf iff the angle ∠ptq ≥ θ_min = arcsin(1/(2ρ)); a point u on
///     the other side iff ∠puq ≥ 180° − θ_min.
///   * **loose pair**: the closed leaf holds no point other than p, q. A loose pair is a Delaunay
///     edge, so pairs are enumerated from Delaunay edges, and looseness is two angle tests against
///     the two opposite vertices t (this side) and u (other side).
///   * **crescent / off-center**: with σ measured along perp(q − p) (unit = ℓ), the apex of the
///     leaf is at height σ_a = ρ + √(ρ² − ¼) = ½·cot(θ_min/2); the circumcentre of pqt is at σ_t.
///     The crescent is empty iff σ_a ≤ σ_t; the off-center is m + min(σ_a, σ_t)·perp(q − p)
///     (Üngör's rule with the exact factor ½, not Triangle's 0.475).
///   * **size class** of a pair: ⌊lg(ℓ / W)⌋, absolute (W = domain width), never rescaled.
///
/// Algorithm (deterministic, from scratch on each call):
///   1. V = tree points ∪ the 4 corners of the domain box Ω. The output triangulates **the box Ω**
///      (= the convex hull of input ∪ box corners, since inputs lie in Ω's middle third). Box
///      sides are split into subsegments; "round 0" splits, at its midpoint, every subsegment
///      whose closed diametral disc holds another vertex, until none does.
///   2. Rounds: the class finger i only increases. A round of class i takes a snapshot of all
///      pending loose (pair, side) candidates of class ≤ i, sorts it by the canonical key
///      (class, ℓ², lexicographic lo, lexicographic hi, ccw before cw) and processes it; new
///      candidates (they always contain the new vertex) go to the next round. When no candidate
///      of class ≤ i remains, i jumps to the smallest pending class.
///   3. A candidate is skipped if it is no longer loose on its side. Otherwise its off-center r
///      is computed. If r lies in the closed diametral disc of a box subsegment (or outside the
///      open box), the encroached subsegments are split at their midpoints instead and the
///      candidate is retried in the next round; else r is inserted.
///   4. Output: the Delaunay triangulation of the final vertex set (CGAL
///      Delaunay_triangulation_2, Epick; degenerate cells canonicalised, see below). No loose
///      pair remains, hence every triangle has
///      circumradius / shortest edge ≤ ρ, i.e. minimum angle ≥ arcsin(1/(2ρ)).
///
/// Resolutions of spec ambiguities (see also the .cpp):
///   * FIFO per size class (paper) vs canonical key order (spec §5.3.4): the canonical key is
///     used inside a round; rounds snapshot-then-process, as Lemma A.8 needs.
///   * Closed leaf (spec §5.1 [D]): a point counts as inside the leaf when its angle is within a
///     slack δ(ℓ) = 1e-12 + 64·ε·S/ℓ radians of the boundary (S = largest |coordinate| of Ω,
///     ε = DBL_EPSILON), so that an inserted apex, which carries rounding error, always clears
///     its pair. The quality bound therefore holds up to that slack (≈1e-10° for ℓ ≥ 1e-4·W):
///     the promised minimum angle is offcenter_promised_min_angle_deg().
///   * Resolution: two inputs closer than offcenter_min_separation() = 128·ε·S/θ_min (about
///     400 ulps of S at ρ = 1.5; S as above) are refused (InvalidInput naming them; insert():
///     InsertResult::BeyondPrecision). Below it the slack of their pair would exceed θ_min/2,
///     and soon θ_min itself, where no pair near them is ever loose and the output keeps
///     slivers: the promise would be void. An off-center's insertion radius is at least ρ·ℓ
///     of its pair (Lemma A.7), so the inputs' closest pair bounds the shortest edge.
///   * Range: the refinement computes off-centers, circumcentres and squared lengths in double
///     precision, so the domain must keep them normal numbers: its width W and its largest
///     |coordinate| S must lie in [kOffCenterMinScale, kOffCenterMaxScale] = [1e-120, 1e120]
///     (S may be 0). Other domains are refused (InvalidInput naming the range); the quadtree
///     mesher (quad_mesh, DynQuadMesh) has no such limit. Scale the input by a power of two
///     (exact) to mesh beyond it.
///   * Degenerate (cocircular) configurations, instead of the symbolic perturbation of §5.3.6:
///     (a) where a loose test or an off-center reads "the vertex t opposite pq", and several
///     vertices on that side are cocircular with p, q (a degenerate Delaunay cell), t is the
///     lexicographically smallest of them (spec §7.2); (b) in the output, every degenerate
///     Delaunay cell (a maximal set of triangles sharing one empty circumcircle, found with the
///     exact incircle test) is re-triangulated as a fan from its smallest output index. Both
///     make the result a function of the vertex set alone, whatever triangulation CGAL built,
///     which is what DynOffCenterMesh2 (dyn_offcenter.hpp) relies on to reproduce it exactly.
///   * Role of the quadtree: it supplies Ω and the canonical, snapped point set; the pair-length
///     classes of §5.3.2 replace Figure 3's cell queues Q_i (spec §5.3.7). The cell-based
///     "active point" machinery is not used.
///   * This is the oracle mode of spec §5.4, a deterministic recomputation from scratch; history
///     independence holds by construction. The dynamic ("fast mode") counterpart is
///     DynOffCenterMesh2 in dyn_offcenter.hpp, which reproduces this function's output exactly.
///   * Round structure, stated precisely (DynOffCenterMesh2 relies on it): a candidate found
///     when its later endpoint v is inserted is processed in round (i, k + 1) if v was inserted
///     in round k of class i and the candidate's class is ≤ i, else in the first round of its
///     own class; candidates found initially are processed in the first round of their class;
///     a retried candidate is processed again in the next round of the same class. (This is
///     what step 2 does; it only spells it out.)
///   * ρ must exceed √2 (spec §5.5 also allows √2 itself; this function, as its issue asks, does
///     not): the guarantee of termination and size is the appendix's ρ > √2.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh {

struct OffCenterOptions {
    double rho = 1.5;             // radius-edge bound ρ, finite and > √2
    bool use_offcenters = true;   // false: circumcentres only (spec §6.4 ablation), same order
    std::size_t max_steiner = 50'000'000;  // step cap: throw InternalError beyond this
};

/// The refined mesh of the box Ω = [origin, origin + width]^2.
struct OffCenterMesh2 {
    Vec2 origin{};
    double width = 1.0;
    /// Input points (DynQuadtree::points() order, bit-identical), then Steiner points (box
    /// corners, boundary midpoints, off-centers) sorted lexicographically by (x, y).
    std::vector<Vec2> points;
    /// Counter-clockwise triangles, each rotated to start at its smallest index, sorted;
    /// degenerate (cocircular) Delaunay cells are fans from their smallest index.
    std::vector<std::array<std::uint32_t, 3>> triangles;
    /// The vertex of each tree point, in DynQuadtree::points() order (= 0, 1, ..., n-1).
    std::vector<std::uint32_t> input_vertices;
    std::size_t steiner = 0;             // points.size() − input count (corners included)
    std::size_t boundary_steiner = 0;    // corners and box-side midpoints
    std::size_t apex_offcenters = 0;     // Steiner points at the leaf apex (crescent empty)
    std::size_t circumcentres = 0;       // Steiner points at a circumcentre of pqt
    std::size_t rounds = 0;              // rounds processed (round 0 excluded)
    std::size_t stuck_pairs = 0;         // loose pairs whose off-center was already a vertex
                                         // (rounding at extreme spread; expected 0)
    double min_angle_deg = 180.0;        // smallest triangle angle of the output
};

/// Runs the static off-center refinement (see the file comment) on the tree's point set and
/// domain. Deterministic: a function of (domain, point set, options) only.
/// \throw InvalidInput if options.rho is not finite or ρ ≤ √2, or if two points are closer than
///        offcenter_min_separation() (naming both).
/// \throw InternalError if more than options.max_steiner Steiner points would be needed.
[[nodiscard]] OffCenterMesh2 offcenter_mesh(const DynQuadtree<2>& tree,
                                            const OffCenterOptions& options = {});

/// The minimum angle (degrees) that radius-edge bound ρ guarantees: arcsin(1/(2ρ)).
[[nodiscard]] double offcenter_min_angle_deg(double rho);

/// The range of domain widths and coordinates the off-center refinement accepts (file
/// comment, "Range"); messages print them as 1e-120 and 1e120.
inline constexpr double kOffCenterMinScale = 1e-120;
inline constexpr double kOffCenterMaxScale = 1e120;
/// The smallest distance between two inputs that the refinement over this domain resolves
/// (file comment, "Resolution"): the ℓ at which the closed-leaf slack reaches θ_min/2.
/// \throw InvalidInput if options.rho is not finite or ρ ≤ √2.
[[nodiscard]] double offcenter_min_separation(const QuadtreeOptions<2>& domain,
                                              const OffCenterOptions& options);
/// The smallest angle (degrees) the algorithm promises for this mesh: offcenter_min_angle_deg(ρ)
/// minus the closed-leaf slack δ(ℓ) = 1e-12 + 64·ε·S/ℓ of its shortest edge ℓ (file comment,
/// "Closed leaf"), the tolerance of the bound for off-centers computed in double precision. A
/// checker of mesh.min_angle_deg should compare against this, not against the exact bound:
/// points a few thousand ulps apart make δ visible.
[[nodiscard]] double offcenter_promised_min_angle_deg(const OffCenterMesh2& mesh,
                                                      const OffCenterOptions& options);

namespace detail {

/// The numeric kernel shared by offcenter_mesh() and DynOffCenterMesh2, so that both compute
/// bit-identical off-centers, size classes and loose tests. Not a stable API.
struct OffCenterKernel {
    OffCenterKernel(const Vec2& origin, double width, const OffCenterOptions& options);

    Vec2 origin{}, hi{};        // corners of Ω
    double width = 1;           // W
    double theta = 0;           // θ_min = arcsin(1/(2ρ))
    double sigma_apex = 0;      // apex height over pq in units of ℓ: ρ + √(ρ² − ¼)
    double scale = 1;           // largest |coordinate| of Ω (or W)
    bool use_offcenters = true;

    /// Angle slack δ(ℓ) of the closed-leaf test (see the file comment).
    [[nodiscard]] double slack(double len2) const;
    /// The ℓ at which slack() reaches θ/2 (offcenter_min_separation()).
    [[nodiscard]] double min_separation() const;
    /// ⌊lg(ℓ / W)⌋ for ℓ² = len2.
    [[nodiscard]] int size_class(double len2) const;
    /// The point at coordinate c along box side `side` (0 bottom, 1 right, 2 top, 3 left).
    [[nodiscard]] Vec2 side_point(int side, double c) const;
    /// The coordinate of p along box side `side` (x for even sides, y for odd ones).
    [[nodiscard]] static double along(int side, const Vec2& p);
    /// Angle ∠ptq in radians.
    [[nodiscard]] static double angle_at(const Vec2& t, const Vec2& p, const Vec2& q);
    /// True when t, on the tested side of pq, lies in the closed leaf (∠ptq ≥ θ − δ).
    [[nodiscard]] bool in_leaf_same_side(const Vec2& t, const Vec2& lo, const Vec2& hi,
                                         double len2) const;
    /// True when u, on the other side of pq, lies in the closed leaf (∠puq ≥ π − θ − δ).
    [[nodiscard]] bool in_leaf_other_side(const Vec2& u, const Vec2& lo, const Vec2& hi,
                                          double len2) const;
    /// The off-center of the pair (lo, hi) on side cw (false: ccw of lo → hi) whose canonical
    /// opposite vertex on that side is t; `apex` tells whether the leaf apex was used.
    [[nodiscard]] Vec2 offcenter(const Vec2& lo, const Vec2& hi, bool cw, double len2,
                                 const Vec2& t, bool& apex) const;
    /// The leaf apex of (lo, hi) on side cw: what offcenter() returns when `apex` is set.
    [[nodiscard]] Vec2 apex_point(const Vec2& lo, const Vec2& hi, bool cw) const;
};

/// \throw InvalidInput ("<who>: rho = ... must be finite and > sqrt(2)") unless ρ is valid.
void require_rho(const OffCenterOptions& options, const char* who);
/// \throw InvalidInput if the domain is outside the off-center range (file comment, "Range").
void require_offcenter_domain(const QuadtreeOptions<2>& domain, const char* who);

/// Finishes an OffCenterMesh2 whose points (inputs first) and counter-clockwise Delaunay
/// triangles are set: re-triangulates every degenerate Delaunay cell as a fan from its
/// smallest index, rotates each triangle to start at its smallest index, sorts the triangles
/// and sets min_angle_deg. The result depends on the vertex set only.
void finish_offcenter_mesh(OffCenterMesh2& mesh);

}  // namespace detail

/// Every violated property, one problem each (no figures); ok() when valid: indices in range,
/// every triangle counter-clockwise (exact orient2d), every edge shared by two oppositely
/// oriented triangles or on the box boundary, total area = box area (relative 1e-12), no unused
/// or duplicate vertex, every input point a vertex, and the empty-circle property (exact
/// incircle: no vertex opposite an interior edge strictly inside the other triangle's
/// circumcircle).
[[nodiscard]] CheckReport check_offcenter_mesh(const OffCenterMesh2& mesh);

}  // namespace dynmesh
