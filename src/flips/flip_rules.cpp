#include "dynmesh/flips/flip_rules.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/scaled_frame.hpp"
#include "dynmesh/geometry/triangle.hpp"

namespace dynmesh {

std::string_view to_string(FlipRule rule) {
    switch (rule) {
        case FlipRule::AngleDef3: return "angle";
        case FlipRule::DiametricBall: return "delaunay";
        case FlipRule::DiametricBallNoFold: return "delaunay-nofold";
        case FlipRule::PlanarIncircle: return "planar";
    }
    return "?";
}

FlipRule parse_flip_rule(std::string_view name) {
    if (name == "angle" || name == "def3") return FlipRule::AngleDef3;
    if (name == "delaunay" || name == "diametric") return FlipRule::DiametricBall;
    if (name == "delaunay-nofold") return FlipRule::DiametricBallNoFold;
    if (name == "planar") return FlipRule::PlanarIncircle;
    throw InvalidInput("unknown flip criterion '" + std::string(name) +
                       "' (expected angle, delaunay, delaunay-nofold or planar)");
}

EdgeQuad edge_quad(const SurfaceMesh& m, Edge e) {
    const Halfedge h0 = SurfaceMesh::halfedge(e, 0), h1 = SurfaceMesh::halfedge(e, 1);
    return {m.to_vertex(h1), m.to_vertex(h0), m.opposite_vertex(h0), m.opposite_vertex(h1)};
}

namespace {

// The geometric tests on points already in the unit frame (scaled_frame.hpp): the public
// functions scale their points first, flip_verdict() scales the quad once for all of them.

bool unit_degenerate_triangle(const Point3& a, const Point3& b, const Point3& c) {
    const double l2 = std::max({sqdistance(a, b), sqdistance(b, c), sqdistance(a, c)});
    const double area = 0.5 * norm(cross(b - a, c - a));
    return !(area >= 1e-14 * l2) || l2 == 0.0;
}

Def3Conditions unit_def3_conditions(const Point3& p, const Point3& q, const Point3& r,
                                    const Point3& s) {
    // Unit vectors along the six segments; cos of the angle xyz at y is dot(e_yx, e_yz).
    const Vec3 pq = normalized(q - p), pr = normalized(r - p), ps = normalized(s - p);
    const Vec3 qr = normalized(r - q), qs = normalized(s - q), rs = normalized(s - r);
    // at p
    const double c_qpr = dot(pq, pr), c_qps = dot(pq, ps), c_rps = dot(pr, ps);
    // at q
    const double c_pqr = -dot(pq, qr), c_pqs = -dot(pq, qs), c_rqs = dot(qr, qs);
    // at r
    const double c_prq = dot(pr, qr), c_prs = -dot(pr, rs), c_qrs = -dot(qr, rs);
    // at s
    const double c_psq = dot(ps, qs), c_psr = dot(ps, rs), c_qsr = dot(qs, rs);
    const double t = kAngleSlack;
    // angle A > min(pi/2, X)  <=>  cos A < max(0, cos X)
    // angle A > max(X, Y)     <=>  cos A < min(cos X, cos Y)
    // (Degenerate triangles make cosines NaN, and every comparison with NaN is false.)
    Def3Conditions c;
    c.i = c_prs < std::max(0.0, c_pqs) - t && c_psr < std::max(0.0, c_pqr) - t;
    c.ii = c_qrs < std::max(0.0, c_qps) - t && c_qsr < std::max(0.0, c_qpr) - t;
    c.iii = c_rps < std::min(c_qpr, c_qps) - t && c_rqs < std::min(c_pqr, c_pqs) - t;
    c.iv = c_prq < std::min(c_prs, c_qrs) - t && c_psq < std::min(c_psr, c_qsr) - t;
    // The smallest angle has the largest cosine.
    const double old_max = std::max({c_qpr, c_pqr, c_prq, c_qps, c_pqs, c_psq});
    const double new_max = std::max({c_rps, c_prs, c_psr, c_rqs, c_qrs, c_qsr});
    c.min_angle_grows = new_max < old_max - t;
    return c;
}

/// Floating-point filter: true when x is certainly outside the diametric ball of abc (by a
/// relative margin far above rounding error). False means "unknown": ask the exact predicate.
bool clearly_outside_ball(const Point3& a, const Point3& b, const Point3& c, const Point3& x) {
    const Point3 cc = circumcenter(a, b, c);
    const double r2 = sqnorm(cc - a);
    return std::isfinite(r2) && sqnorm(x - cc) > r2 * (1 + 1e-6);
}

FlipVerdict unit_diametric_condition(const Point3& p, const Point3& q, const Point3& r,
                                     const Point3& s) {
    if (clearly_outside_ball(p, q, r, s) && clearly_outside_ball(p, q, s, r)) return FlipVerdict::RuleFails;
    const bool s_in = in_diametric_ball(p, q, r, s) == Sign::Positive;
    const bool r_in = s_in || in_diametric_ball(p, q, s, r) == Sign::Positive;
    if (!r_in) return FlipVerdict::RuleFails;
    // Termination guard: the larger circumradius of the pair must drop.
    const double old_r = std::max(circumradius(p, q, r), circumradius(q, p, s));
    const double new_r = std::max(circumradius(p, s, r), circumradius(q, r, s));
    // Relative slack, so that rounding of tied radii cannot make pq -> rs -> pq cycle.
    return new_r < old_r * (1.0 - 1e-12) ? FlipVerdict::Flippable : FlipVerdict::NotImproving;
}

}  // namespace

bool is_degenerate_triangle(const Point3& a, const Point3& b, const Point3& c) {
    const auto [u, scale] = to_unit(std::array{a, b, c});
    return unit_degenerate_triangle(u[0], u[1], u[2]);
}

Def3Conditions def3_conditions(const Point3& p, const Point3& q, const Point3& r, const Point3& s) {
    const auto [u, scale] = to_unit(std::array{p, q, r, s});
    return unit_def3_conditions(u[0], u[1], u[2], u[3]);
}

bool def3_condition(const Point3& p, const Point3& q, const Point3& r, const Point3& s) {
    return def3_conditions(p, q, r, s).all();
}

FlipVerdict diametric_condition(const Point3& p, const Point3& q, const Point3& r,
                                const Point3& s) {
    // Scaling by a power of two is exact, so the exact predicates decide as on the originals.
    const auto [u, scale] = to_unit(std::array{p, q, r, s});
    return unit_diametric_condition(u[0], u[1], u[2], u[3]);
}

bool planar_condition(const Point3& p, const Point3& q, const Point3& r, const Point3& s) {
    const Point2 p2{p.x, p.y}, q2{q.x, q.y}, r2{r.x, r.y}, s2{s.x, s.y};
    // pqr is CCW in a valid planar mesh; r and s must be on opposite sides of pq, and p, q
    // on opposite sides of rs (convex quad).
    const Sign side_r = orient2d(p2, q2, r2), side_s = orient2d(p2, q2, s2);
    if (side_r == Sign::Zero || side_s == Sign::Zero || side_r == side_s) return false;
    const Sign side_p = orient2d(r2, s2, p2), side_q = orient2d(r2, s2, q2);
    if (side_p == Sign::Zero || side_q == Sign::Zero || side_p == side_q) return false;
    const Sign in = side_r == Sign::Positive ? incircle(p2, q2, r2, s2) : incircle(q2, p2, r2, s2);
    return in == Sign::Positive;
}

namespace {

/// The (unnormalised) normals of the faces of an edge's quad p, q, r, s before a flip (pqr,
/// qps) and after it (psr, qrs), in its scaled frame.
struct QuadNormals {
    Vec3 pqr, qps, psr, qrs;
};

/// Flipping e (its quad scaled by `scale`, with normals `n`) makes a new fold across one of
/// the quad's four sides (the new face there turns by 90 degrees or more against the face
/// across that side, where the old face did not) without lowering the number of folds on the
/// quad's five edges. A flip that unfolds more than it folds stays allowed: an update mends a
/// folded patch with such flips. The new pair itself is known not to fold.
bool makes_outer_fold(const SurfaceMesh& m, Edge e, const ExactScale& scale, const QuadNormals& n) {
    int before = dot(n.pqr, n.qps) > 0 ? 0 : 1, after = 0;
    bool new_fold = false;
    const auto side = [&](Halfedge h, const Vec3& old_n, const Vec3& new_n) {
        const Halfedge out = m.twin(h);
        if (m.is_boundary(out)) return;
        const auto at = [&](Vertex v) { return scale.apply(m.position(v)); };
        const Vec3 beyond =
            triangle_normal_raw(at(m.from_vertex(out)), at(m.to_vertex(out)), at(m.opposite_vertex(out)));
        const bool was = !(dot(beyond, old_n) > 0), is = !(dot(beyond, new_n) > 0);
        before += was;
        after += is;
        new_fold |= is && !was;
    };
    // The face of halfedge 0 is p q r, that of halfedge 1 is q p s (edge_quad()).
    const Halfedge qr = m.next(SurfaceMesh::halfedge(e, 0)), rp = m.next(qr);
    const Halfedge ps = m.next(SurfaceMesh::halfedge(e, 1)), sq = m.next(ps);
    side(qr, n.pqr, n.qrs);
    side(rp, n.pqr, n.psr);
    side(ps, n.qps, n.psr);
    side(sq, n.qps, n.qrs);
    return new_fold && after >= before;
}

}  // namespace

FlipVerdict flip_verdict(const SurfaceMesh& m, Edge e, FlipRule rule) {
    if (m.is_deleted(e) || m.is_boundary(e)) return FlipVerdict::Boundary;
    const EdgeQuad k = edge_quad(m, e);
    if (k.r == k.s) return FlipVerdict::DiagonalExists;
    // The quad in its unit frame (exact scaling: the same decisions as on the originals,
    // without overflow or underflow near the double limits).
    const auto [u, scale] = to_unit(std::array{m.position(k.p), m.position(k.q), m.position(k.r),
                                               m.position(k.s)});
    const Point3 &p = u[0], &q = u[1], &r = u[2], &s = u[3];
    // The geometric rule first: most edges fail it, and it is cheaper than the edge lookup.
    FlipVerdict v = FlipVerdict::Flippable;
    if (rule == FlipRule::PlanarIncircle) {
        if (!planar_condition(p, q, r, s)) return FlipVerdict::RuleFails;
    } else if (rule == FlipRule::AngleDef3) {
        // Degenerate triangles make the cosines NaN, and every comparison with NaN fails.
        if (!unit_def3_conditions(p, q, r, s).all()) return FlipVerdict::RuleFails;
        if (unit_degenerate_triangle(p, q, r) || unit_degenerate_triangle(q, p, s) ||
            unit_degenerate_triangle(p, s, r) || unit_degenerate_triangle(q, r, s))
            return FlipVerdict::Degenerate;
    } else {
        if (unit_degenerate_triangle(p, q, r) || unit_degenerate_triangle(q, p, s))
            return FlipVerdict::Degenerate;  // the diametric ball is undefined
        v = unit_diametric_condition(p, q, r, s);
        if (v == FlipVerdict::RuleFails) return v;
        if (unit_degenerate_triangle(p, s, r) || unit_degenerate_triangle(q, r, s))
            return FlipVerdict::Degenerate;
        // Never fold: the new pair must not turn by 90 degrees or more against each other or
        // against the old pair (it cannot for dense samples, Theorem 4.1 (iv) of the deforming
        // paper; on sparse ones the diametric rule alone could flip across a sharp ridge).
        // DiametricBallNoFold: nor against a neighbour across one of the quad's four sides
        // where the old pair did not (it would lay the new pair over that neighbour).
        const QuadNormals n{triangle_normal_raw(p, q, r), triangle_normal_raw(q, p, s), triangle_normal_raw(p, s, r),
                            triangle_normal_raw(q, r, s)};
        const Vec3 n_old = n.pqr + n.qps;
        if (!(dot(n.psr, n.qrs) > 0 && dot(n.psr, n_old) > 0 && dot(n.qrs, n_old) > 0)) return FlipVerdict::Degenerate;
        if (rule == FlipRule::DiametricBallNoFold && makes_outer_fold(m, e, scale, n)) return FlipVerdict::Degenerate;
    }
    if (m.find_halfedge(k.r, k.s).is_valid()) return FlipVerdict::DiagonalExists;
    return v;
}

EdgeProperty<std::uint8_t> lock_edges_property(SurfaceMesh& mesh) {
    auto p = locked_edges(mesh);
    return p.is_valid() ? p : mesh.add_edge_property<std::uint8_t>(kLockedEdges, 0);
}

std::size_t locked_edge_count(const SurfaceMesh& m) {
    const auto locked = locked_edges(m);
    std::size_t n = 0;
    if (locked.is_valid())
        for (Edge e : m.edges()) n += locked[e] != 0;
    return n;
}

std::size_t locked_degree(const SurfaceMesh& m, const EdgeProperty<std::uint8_t>& locked, Vertex v) {
    if (!locked.is_valid() || m.is_isolated(v)) return 0;
    std::size_t n = 0;
    for (Halfedge h : m.outgoing_halfedges(v)) n += locked[SurfaceMesh::edge(h)] != 0;
    return n;
}

FlipVerdict flip_verdict(const SurfaceMesh& m, Edge e, FlipRule rule, double feature_angle_deg,
                         const EdgeProperty<std::uint8_t>& locked) {
    if (locked.is_valid() && !m.is_deleted(e) && locked[e]) return FlipVerdict::FeatureLocked;
    const FlipVerdict v = flip_verdict(m, e, rule);
    if (v != FlipVerdict::Flippable || feature_angle_deg >= 180.0) return v;
    const double min_dihedral = kPi - deg_to_rad(feature_angle_deg);
    const EdgeQuad k = edge_quad(m, e);
    const Point3 &p = m.position(k.p), &q = m.position(k.q), &r = m.position(k.r),
                 &s = m.position(k.s);
    if (dihedral_angle(p, q, r, s) < min_dihedral || dihedral_angle(r, s, q, p) < min_dihedral)
        return FlipVerdict::FeatureLocked;
    return v;
}

bool is_illegal(const SurfaceMesh& m, Edge e) {
    if (m.is_deleted(e) || m.is_boundary(e)) return false;
    const EdgeQuad k = edge_quad(m, e);
    const Point3 &p = m.position(k.p), &q = m.position(k.q), &r = m.position(k.r),
                 &s = m.position(k.s);
    if (collinear(p, q, r) || collinear(p, q, s)) return false;
    return in_diametric_ball(p, q, s, r) == Sign::Positive &&
           in_diametric_ball(p, q, r, s) == Sign::Positive;
}

}  // namespace dynmesh
