#pragma once
/// \file When is an edge flippable? The angle rule of Cheng & Jin ("Edge flips in surface
/// meshes", Definition 3), the diametric-ball rule of the deforming-surface paper (§4), and
/// the planar empty-circle rule.
///
/// Edge pq lies in triangles pqr and qps (p->q is halfedge(e, 0)); a flip replaces them by
/// prs and qrs.

#include <string_view>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

enum class FlipRule {
    AngleDef3,      ///< Definition 3 of the edge-flip paper: all five conditions
    /// s inside the diametric ball of pqr, or r inside that of pqs; never a flip that folds
    /// the new pair (Degenerate: it turns by 90 degrees or more against itself or the old pair)
    DiametricBall,
    /// DiametricBall, and never a new fold (a turn by 90 degrees or more) against a
    /// neighbour across one of the quad's four sides unless the flip lowers the number of
    /// folds on the quad's five edges (Degenerate); the rule of the deforming mesh's updates
    DiametricBallNoFold,
    PlanarIncircle  ///< z = 0 meshes: pqrs convex and s strictly inside circle(pqr)
};

[[nodiscard]] std::string_view to_string(FlipRule rule);
/// Parses "angle" / "def3", "delaunay" / "diametric", "delaunay-nofold", "planar".
/// \throw InvalidInput.
[[nodiscard]] FlipRule parse_flip_rule(std::string_view name);

/// Why an edge is or is not flippable (counted in reports).
enum class FlipVerdict {
    Flippable,
    Boundary,        ///< a boundary edge, or a deleted one
    DiagonalExists,  ///< rs is already an edge (Definition 3 (v))
    Degenerate,      ///< one of the four triangles (old or new) has (almost) zero area, or (diametric rules) the flip folds
    RuleFails,       ///< the rule's geometric condition does not hold
    NotImproving,    ///< the rule holds but the guard against cycles does not (counted)
    FeatureLocked    ///< the edge is locked (kLockedEdges), or the rule holds but it or the one it would create is sharp
};

/// The four corners of edge e: p->q is halfedge(e, 0), r opposite it, s opposite its twin.
struct EdgeQuad {
    Vertex p, q, r, s;
};
[[nodiscard]] EdgeQuad edge_quad(const SurfaceMesh& mesh, Edge e);

/// Relative cosine slack of Definition 3 (strict inequalities by this margin).
inline constexpr double kAngleSlack = 1e-12;

/// The four geometric conditions of Definition 3 for the quad p, q, r, s, each evaluated
/// by cosines with the strict slack kAngleSlack (§2.4 of the digest):
///   (i)   angle prs > min(pi/2, angle pqs)  and  angle psr > min(pi/2, angle pqr)
///   (ii)  angle qrs > min(pi/2, angle qps)  and  angle qsr > min(pi/2, angle qpr)
///   (iii) angle rps > max(angle rpq, angle spq)  and  angle rqs > max(angle rqp, angle sqp)
///   (iv)  angle prq > max(angle prs, angle qrs)  and  angle psq > max(angle psr, angle qsr)
/// plus the anti-cycling guard, which is not part of the definition: the smallest angle of
/// the new pair (prs, qrs) beats that of the old pair (pqr, qps) by more than kAngleSlack in
/// cosine.
struct Def3Conditions {
    bool i = false, ii = false, iii = false, iv = false;
    bool min_angle_grows = false;  ///< the guard
    /// Definition 3 (i)-(iv), without the guard.
    [[nodiscard]] bool rule() const { return i && ii && iii && iv; }
    /// What flipping requires: the rule and the guard.
    [[nodiscard]] bool all() const { return rule() && min_angle_grows; }
};
[[nodiscard]] Def3Conditions def3_conditions(const Point3& p, const Point3& q, const Point3& r,
                                             const Point3& s);
/// def3_conditions(p, q, r, s).all(): Definition 3 (i)-(iv) and the guard, without the edge
/// test (v).
[[nodiscard]] bool def3_condition(const Point3& p, const Point3& q, const Point3& r,
                                  const Point3& s);
/// The diametric rule (exact predicates): s strictly inside the diametric ball of pqr or r
/// strictly inside that of pqs, and the flip lowers the larger circumradius of the pair.
[[nodiscard]] FlipVerdict diametric_condition(const Point3& p, const Point3& q, const Point3& r,
                                              const Point3& s);
/// Planar rule (exact predicates on x, y): pqrs convex with r, s on opposite sides of pq, and
/// s strictly inside the circumcircle of pqr.
[[nodiscard]] bool planar_condition(const Point3& p, const Point3& q, const Point3& r,
                                    const Point3& s);
/// True when the triangle is degenerate: area < 1e-14 * (longest edge)^2.
[[nodiscard]] bool is_degenerate_triangle(const Point3& a, const Point3& b, const Point3& c);

/// Name of the edge property (std::uint8_t, non-zero = locked) that marks edges no flip may
/// touch, e.g. the creases of a CAD mesh. Every flip routine of the library honours it
/// (FlipVerdict::FeatureLocked): flip_all(), flip_from(), the local flips of Add and Remove.
inline constexpr const char* kLockedEdges = "e:locked";
/// The mesh's kLockedEdges property, or an invalid one when it has none.
[[nodiscard]] inline EdgeProperty<std::uint8_t> locked_edges(const SurfaceMesh& mesh) {
    return mesh.get_edge_property<std::uint8_t>(kLockedEdges);
}
/// The mesh's kLockedEdges property, added (all edges free) when it has none.
EdgeProperty<std::uint8_t> lock_edges_property(SurfaceMesh& mesh);
/// Number of locked edges of the mesh (0 without the property).
[[nodiscard]] std::size_t locked_edge_count(const SurfaceMesh& mesh);
/// Number of locked spokes at v (0 without the property).
[[nodiscard]] std::size_t locked_degree(const SurfaceMesh& mesh, const EdgeProperty<std::uint8_t>& locked, Vertex v);

/// Full test of edge e under `rule`, including boundary, degeneracy and condition (v).
[[nodiscard]] FlipVerdict flip_verdict(const SurfaceMesh& mesh, Edge e, FlipRule rule);
/// As above, plus the locks: an edge marked in `locked` (when valid), or a flippable edge
/// whose 180 - dihedral, or that of the edge the flip would create, exceeds
/// feature_angle_deg, is FeatureLocked (180 = off).
[[nodiscard]] FlipVerdict flip_verdict(const SurfaceMesh& mesh, Edge e, FlipRule rule,
                                       double feature_angle_deg, const EdgeProperty<std::uint8_t>& locked);
/// As above with the mesh's own kLockedEdges property.
[[nodiscard]] inline FlipVerdict flip_verdict(const SurfaceMesh& mesh, Edge e, FlipRule rule,
                                              double feature_angle_deg) {
    return flip_verdict(mesh, e, rule, feature_angle_deg, locked_edges(mesh));
}
[[nodiscard]] inline bool is_flippable(const SurfaceMesh& mesh, Edge e, FlipRule rule,
                                       double feature_angle_deg = 180.0) {
    return flip_verdict(mesh, e, rule, feature_angle_deg) == FlipVerdict::Flippable;
}

/// Definition 4: pq is illegal iff r lies inside the diametric ball of pqs and s inside that
/// of pqr (exact predicates). Boundary edges are legal.
[[nodiscard]] bool is_illegal(const SurfaceMesh& mesh, Edge e);

}  // namespace dynmesh
