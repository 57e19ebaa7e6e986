#include "dynmesh/deform/local_ops.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <exception>
#include <numeric>
#include <optional>
#include <span>
#include <unordered_set>
#include <variant>

#include "dynmesh/error.hpp"
#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/triangle.hpp"

namespace dynmesh {

// ---- closest point -----------------------------------------------------------------------

namespace {



}  // namespace


// ---- local flip with a final emptiness check ---------------------------------------------

namespace {

std::string vname(Vertex v) {
    std::string s = "vertex ";  // (not "v" + to_string: GCC 12 warns -Wrestrict on that)
    return s += std::to_string(v.idx());
}

/// The live vertices within `rings` edge hops of `centre` (centre included), BFS order.
std::vector<Vertex> hop_set(const SurfaceMesh& m, std::span<const Vertex> centre,
                            std::size_t rings) {
    std::vector<Vertex> out;
    std::unordered_set<std::uint32_t> seen;
    for (Vertex v : centre)
        if (seen.insert(v.idx()).second) out.push_back(v);
    std::size_t begin = 0;
    for (std::size_t d = 0; d < rings; ++d) {
        const std::size_t end = out.size();
        for (std::size_t i = begin; i < end; ++i) {
            if (m.is_isolated(out[i])) continue;
            for (Halfedge h : m.outgoing_halfedges(out[i])) {
                const Vertex w = m.to_vertex(h);
                if (seen.insert(w.idx()).second) out.push_back(w);
            }
        }
        begin = end;
    }
    return out;
}

/// The faces incident to the given vertices, sorted and unique.
std::vector<Face> incident_faces(const SurfaceMesh& m, std::span<const Vertex> vs) {
    std::vector<Face> out;
    for (Vertex v : vs) {
        if (m.is_isolated(v)) continue;
        for (Halfedge h : m.outgoing_halfedges(v))
            if (!m.is_boundary(h)) out.push_back(m.face(h));
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

struct BallViolations {
    std::size_t star = 0;    ///< (triangle incident to centre, vertex within rings) pairs
    std::size_t nearby = 0;  ///< (triangle around a neighbour, centre vertex) pairs
};

/// Vertices strictly inside diametric balls: the triangles incident to `centre` against the
/// vertices within `rings` hops of it, and (when `centre_in_nearby_balls`) the other
/// triangles around the neighbours of `centre` against the centre vertices. Collinear
/// triangles are skipped.
BallViolations count_ball_violations(const SurfaceMesh& m, std::span<const Vertex> centre,
                                     std::size_t rings, bool centre_in_nearby_balls) {
    auto test = [&](Face f, std::span<const Vertex> candidates) {
        std::size_t bad = 0;
        const auto t = m.face_vertices(f);
        const Point3 &a = m.position(t[0]), &b = m.position(t[1]), &c = m.position(t[2]);
        if (collinear(a, b, c)) return bad;
        for (Vertex w : candidates) {
            if (w == t[0] || w == t[1] || w == t[2]) continue;
            if (in_diametric_ball(a, b, c, m.position(w)) == Sign::Positive) ++bad;
        }
        return bad;
    };
    BallViolations out;
    const std::vector<Vertex> ring = hop_set(m, centre, rings);
    const std::vector<Face> star = incident_faces(m, centre);
    for (Face f : star) out.star += test(f, ring);
    if (centre_in_nearby_balls) {
        const std::vector<Vertex> one_ring = hop_set(m, centre, 1);
        for (Face f : incident_faces(m, one_ring))
            if (!std::binary_search(star.begin(), star.end(), f)) out.nearby += test(f, centre);
    }
    return out;
}

struct LocalFlipOutcome {
    std::size_t flips = 0;
    std::size_t not_improving = 0;
    BallViolations left;  ///< after the last round
};

/// The local flip of §4.3: Lawson propagation (flip_from) from `seeds`, then the emptiness
/// check around `centre`; while it finds a violation, flip again from every edge within
/// `rings` hops of `centre`, until none is left, a round makes no flip, or max_rounds is
/// reached.
LocalFlipOutcome local_flip(SurfaceMesh& m, std::span<const Vertex> centre,
                            std::span<const Edge> seeds, FlipRule rule, double feature_angle_deg,
                            std::size_t rings, std::size_t max_rounds, bool centre_in_nearby_balls,
                            bool do_flip) {
    LocalFlipOutcome out;
    FlipOptions fo;
    fo.rule = rule;
    fo.feature_angle_deg = feature_angle_deg;
    auto run = [&](std::span<const Edge> s) {
        const FlipReport rep = flip_from(m, s, fo);
        out.flips += rep.flips;
        out.not_improving += rep.not_improving;
        return rep.flips;
    };
    if (do_flip) run(seeds);
    for (std::size_t round = 0;; ++round) {
        out.left = count_ball_violations(m, centre, rings, centre_in_nearby_balls);
        if (out.left.star + out.left.nearby == 0 || !do_flip || round >= max_rounds) break;
        std::vector<Edge> region;
        for (Vertex v : hop_set(m, centre, rings)) {
            if (m.is_isolated(v)) continue;
            for (Halfedge h : m.outgoing_halfedges(v)) region.push_back(SurfaceMesh::edge(h));
        }
        std::sort(region.begin(), region.end());
        region.erase(std::unique(region.begin(), region.end()), region.end());
        if (run(region) == 0) break;
    }
    return out;
}

}  // namespace

// ---- Add(p, abc) -------------------------------------------------------------------------

AddResult add_point(SurfaceMesh& m, const Point3& p, Face f, const AddOptions& o) {
    DYNMESH_CHECK(m.is_valid(f) && !m.is_deleted(f),
                  "add_point: face f" + std::to_string(f.idx()) + " is invalid or deleted");
    DYNMESH_CHECK(is_finite(p), "add_point: the point is not finite");
    AddResult r;
    // Corners a, b, c = to_vertex of h0, h1, h2; the edge ca is h0, ab is h1, bc is h2.
    const Halfedge h0 = m.halfedge(f), h1 = m.next(h0), h2 = m.next(h1);
    const std::array<Vertex, 3> abc{m.to_vertex(h0), m.to_vertex(h1), m.to_vertex(h2)};
    const Point3 &pa = m.position(abc[0]), &pb = m.position(abc[1]), &pc = m.position(abc[2]);
    const ClosestPoint cp = closest_point_on_triangle(p, pa, pb, pc);
    const std::array<double, 3> bary{cp.u, cp.v, cp.w};
    int n_small = 0, smallest = 0, largest = 0;
    for (int i = 0; i < 3; ++i) {
        if (bary[i] < o.bary_tol) ++n_small;
        if (bary[i] < bary[smallest]) smallest = i;
        if (bary[i] > bary[largest]) largest = i;
    }

    if (o.split_edge.is_valid()) {
        DYNMESH_CHECK(m.is_valid(o.split_edge) && !m.is_deleted(o.split_edge),
                      "add_point: edge e" + std::to_string(o.split_edge.idx()) + " is invalid or deleted");
        n_small = 1;
    }
    if (n_small >= 2) {  // Vertex case: refused, mesh unchanged
        r.kind = AddCase::Vertex;
        r.near_vertex = abc[largest];
        r.projected = m.position(r.near_vertex);
        r.offset = cp.distance;
        return r;
    }

    // Candidate edges for the conditional flip, in the paper's order.
    std::vector<Edge> candidates;
    if (n_small == 1) {
        r.kind = AddCase::Edge;
        const Halfedge opposite[3] = {h2, h0, h1};  // the edge opposite corner i
        const Halfedge he = o.split_edge.is_valid() ? SurfaceMesh::halfedge(o.split_edge, 0) : opposite[smallest];
        const Vertex vx = m.from_vertex(he), vy = m.to_vertex(he);
        const Point3 &x = m.position(vx), &y = m.position(vy);
        auto locked = locked_edges(m);
        const bool was_locked = locked.is_valid() && locked[SurfaceMesh::edge(he)];
        if (was_locked && !o.split_edge.is_valid()) {
            r.kind = AddCase::LockedEdge;
            r.near_vertex = distance(p, x) <= distance(p, y) ? vx : vy;
            r.projected = cp.point;
            r.offset = cp.distance;
            return r;
        }
        double at = segment_parameter(p, x, y);
        if (o.split_edge.is_valid()) at = std::clamp(at, 0.1, 0.9);  // never on an end
        r.projected = x + (y - x) * at;  // exactly on the edge
        r.vertex = m.split_edge(SurfaceMesh::edge(he), r.projected);
        if (was_locked)
            for (Halfedge h : m.outgoing_halfedges(r.vertex))
                if (m.to_vertex(h) == vx || m.to_vertex(h) == vy) locked[SurfaceMesh::edge(h)] = 1;
        for (Halfedge h : m.outgoing_halfedges(r.vertex))
            if (!m.is_boundary(h)) candidates.push_back(SurfaceMesh::edge(m.next(h)));
    } else {
        r.kind = AddCase::Interior;
        r.projected = cp.point;
        r.vertex = m.split_face(f, r.projected);
        // split_face keeps the three old halfedges: ab, ca, bc.
        candidates = {SurfaceMesh::edge(h1), SurfaceMesh::edge(h0), SurfaceMesh::edge(h2)};
    }

    // The paper's conditional single flip: obtuse angle at p~ and the old edge flippable.
    const Point3 pt = m.position(r.vertex);
    for (Edge e : candidates) {
        const Point3 &x = m.position(m.vertex(e, 0)), &y = m.position(m.vertex(e, 1));
        if (!(dot(x - pt, y - pt) < 0)) continue;
        const FlipVerdict verdict = flip_verdict(m, e, o.rule, o.feature_angle_deg);
        if (verdict == FlipVerdict::NotImproving) ++r.not_improving;
        if (verdict != FlipVerdict::Flippable) continue;
        m.flip(e);
        ++r.flips;
        r.conditional_flip = true;
        break;
    }

    // Move to p exactly, then flip locally around p.
    m.position(r.vertex) = p;
    r.offset = distance(p, r.projected);
    std::vector<Edge> seeds;
    for (Halfedge h : m.outgoing_halfedges(r.vertex)) {
        seeds.push_back(SurfaceMesh::edge(h));
        if (!m.is_boundary(h)) seeds.push_back(SurfaceMesh::edge(m.next(h)));
    }
    const Vertex centre[1] = {r.vertex};
    const LocalFlipOutcome lf = local_flip(m, centre, seeds, o.rule, o.feature_angle_deg, o.check_rings,
                                           o.max_repair_rounds, /*centre_in_nearby_balls=*/true,
                                           /*do_flip=*/true);
    r.flips += lf.flips;
    r.not_improving += lf.not_improving;
    r.balls_empty = lf.left.star == 0;
    r.nearby_balls_containing_p = lf.left.nearby;
    return r;
}

// ---- Remove(v) ---------------------------------------------------------------------------

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
struct CdtFaceInfo {
    int nesting_level = -1;
};
using CdtVb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using CdtFbb = CGAL::Triangulation_face_base_with_info_2<CdtFaceInfo, K>;
using CdtFb = CGAL::Constrained_triangulation_face_base_2<K, CdtFbb>;
using CdtTds = CGAL::Triangulation_data_structure_2<CdtVb, CdtFb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    K, CdtTds, CGAL::No_constraint_intersection_requiring_constructions_tag>;
using Triangles = std::vector<std::array<std::uint32_t, 3>>;

bool lex_less(const Point2& a, const Point2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

/// c lies on the closed segment ab, given that a, b, c are collinear.
bool on_collinear_segment(const Point2& a, const Point2& b, const Point2& c) {
    return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
           c.y <= std::max(a.y, b.y);
}

/// Closed segments ab and cd share a point (exact).
bool segments_meet(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
    const Sign o1 = orient2d(a, b, c), o2 = orient2d(a, b, d), o3 = orient2d(c, d, a),
               o4 = orient2d(c, d, b);
    if (o1 != o2 && o3 != o4 && o1 != Sign::Zero && o2 != Sign::Zero && o3 != Sign::Zero &&
        o4 != Sign::Zero)
        return true;
    if (o1 == Sign::Zero && on_collinear_segment(a, b, c)) return true;
    if (o2 == Sign::Zero && on_collinear_segment(a, b, d)) return true;
    if (o3 == Sign::Zero && on_collinear_segment(c, d, a)) return true;
    if (o4 == Sign::Zero && on_collinear_segment(c, d, b)) return true;
    return false;
}

/// Why a polygon is not simple and counter-clockwise, or nullopt when it is (exact tests on
/// the given coordinates).
std::optional<std::string> polygon_problem(const std::vector<Point2>& q) {
    const std::size_t k = q.size();
    for (std::size_t i = 0; i < k; ++i)
        for (std::size_t j = i + 1; j < k; ++j)
            if (q[i] == q[j]) return "two link vertices project to the same point";
    // Adjacent sides (i-1, i), (i, i+1) may not fold back onto each other.
    for (std::size_t i = 0; i < k; ++i) {
        const Point2 &a = q[(i + k - 1) % k], &b = q[i], &c = q[(i + 1) % k];
        if (orient2d(a, b, c) == Sign::Zero && lex_less(a, b) == lex_less(c, b))
            return "the projected link folds back on itself";
    }
    // Non-adjacent sides may not meet.
    for (std::size_t i = 0; i < k; ++i)
        for (std::size_t j = i + 2; j < k; ++j) {
            if (i == 0 && j == k - 1) continue;  // adjacent through vertex 0
            if (segments_meet(q[i], q[(i + 1) % k], q[j], q[(j + 1) % k]))
                return "the projected link is not a simple polygon";
        }
    // Orientation at the lexicographically smallest vertex (a convex corner).
    std::size_t lo = 0;
    for (std::size_t i = 1; i < k; ++i)
        if (lex_less(q[i], q[lo])) lo = i;
    if (orient2d(q[(lo + k - 1) % k], q[lo], q[(lo + 1) % k]) != Sign::Positive)
        return "the projected link is clockwise (the plane sees the star from behind)";
    return std::nullopt;
}

/// Flood fill from the infinite face: nesting level 0 outside, 1 inside the polygon.
void mark_domains(Cdt& cdt) {
    for (auto f : cdt.all_face_handles()) f->info().nesting_level = -1;
    std::deque<Cdt::Edge> border;
    auto fill = [&](Cdt::Face_handle start, int level) {
        if (start->info().nesting_level != -1) return;
        std::deque<Cdt::Face_handle> queue{start};
        while (!queue.empty()) {
            const Cdt::Face_handle fh = queue.front();
            queue.pop_front();
            if (fh->info().nesting_level != -1) continue;
            fh->info().nesting_level = level;
            for (int i = 0; i < 3; ++i) {
                const Cdt::Face_handle n = fh->neighbor(i);
                if (n->info().nesting_level != -1) continue;
                if (cdt.is_constrained(Cdt::Edge(fh, i)))
                    border.emplace_back(fh, i);
                else
                    queue.push_back(n);
            }
        }
    };
    fill(cdt.infinite_face(), 0);
    while (!border.empty()) {
        const Cdt::Edge e = border.front();
        border.pop_front();
        const Cdt::Face_handle n = e.first->neighbor(e.second);
        if (n->info().nesting_level == -1) fill(n, e.first->info().nesting_level + 1);
    }
}

/// The CDT of the interior of the simple counter-clockwise polygon q, as index triples
/// (counter-clockwise), or the reason it failed.
std::variant<Triangles, std::string> polygon_cdt(const std::vector<Point2>& q) {
    const std::size_t k = q.size();
    if (k == 3) return Triangles{{0u, 1u, 2u}};
    try {
        Cdt cdt;
        std::vector<Cdt::Vertex_handle> vh(k);
        for (std::size_t i = 0; i < k; ++i) {
            vh[i] = cdt.insert(K::Point_2(q[i].x, q[i].y));
            vh[i]->info() = static_cast<std::uint32_t>(i);
        }
        if (cdt.number_of_vertices() != k) return std::string("CGAL merged projected vertices");
        for (std::size_t i = 0; i < k; ++i) cdt.insert_constraint(vh[i], vh[(i + 1) % k]);
        if (cdt.number_of_vertices() != k)
            return std::string("CGAL split a constraint (the polygon is not simple)");
        mark_domains(cdt);
        Triangles tris;
        for (auto f : cdt.finite_face_handles()) {
            if (f->info().nesting_level != 1) continue;
            tris.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
        }
        if (tris.size() != k - 2)
            return "the CDT has " + std::to_string(tris.size()) + " inside triangles, expected " +
                   std::to_string(k - 2);
        return tris;
    } catch (const std::exception& e) {
        return std::string("CGAL failed: ") + e.what();
    }
}

}  // namespace

namespace {

/// Remove(v) of a vertex inside a chain of locked edges a - v - b (spec §10.3): v is
/// collapsed onto a or b, so that the chain becomes a - b, still locked. Of the two, the
/// collapse that keeps every surviving triangle's normal within 60 degrees of its old one is
/// taken, the shorter edge first; then the local flip around the merged vertex.
RemoveResult remove_crease_point(SurfaceMesh& m, Vertex v, const RemoveOptions& o,
                                 EdgeProperty<std::uint8_t> locked, RemoveResult& r) {
    std::vector<Halfedge> chain;
    for (Halfedge h : m.outgoing_halfedges(v))
        if (locked[SurfaceMesh::edge(h)]) chain.push_back(h);
    const Point3 pv = m.position(v);
    if (distance(pv, m.position(m.to_vertex(chain[1]))) < distance(pv, m.position(m.to_vertex(chain[0]))))
        std::swap(chain[0], chain[1]);
    for (std::size_t i = 0; i < 2; ++i) {
        const Halfedge h = chain[i];
        const Vertex a = m.to_vertex(h), b = m.to_vertex(chain[1 - i]);
        if (!m.is_collapse_ok(h) || m.find_halfedge(a, b).is_valid()) continue;
        // Triangles of v's star without a keep their other corners and get a for v: none may
        // turn by 60 degrees or more, nor get a circumradius beyond twice the star's largest
        // (a near-degenerate triangle would blow up the mesh's R).
        bool bad = false;
        const Point3& pa = m.position(a);
        double star_r = 0;
        for (Halfedge g : m.outgoing_halfedges(v))
            if (!m.is_boundary(g))
                star_r = std::max(star_r, circumradius(pv, m.position(m.to_vertex(g)), m.position(m.to_vertex(m.next(g)))));
        for (Halfedge g : m.outgoing_halfedges(v)) {
            if (m.is_boundary(g)) continue;
            const Vertex x = m.to_vertex(g), y = m.to_vertex(m.next(g));
            if (x == a || y == a) continue;
            const Vec3 before = triangle_normal_raw(pv, m.position(x), m.position(y));
            const Vec3 after = triangle_normal_raw(pa, m.position(x), m.position(y));
            if (!(dot(before, after) > 0.5 * norm(before) * norm(after))) bad = true;
            if (!(circumradius(pa, m.position(x), m.position(y)) <= 2 * star_r)) bad = true;
        }
        if (bad) continue;
        // The collapse merges edge pairs (v x, a x) and may keep either index: re-mark every
        // locked edge at a (and v b, which becomes a b) afterwards.
        std::vector<Vertex> keep{b};
        for (Halfedge g : m.outgoing_halfedges(a))
            if (locked[SurfaceMesh::edge(g)] && m.to_vertex(g) != v) keep.push_back(m.to_vertex(g));
        m.collapse(h);
        for (Vertex x : keep) {
            const Halfedge ax = m.find_halfedge(a, x);
            DYNMESH_ASSERT(ax.is_valid(), "remove_point: the locked chain lost its edge");
            if (ax.is_valid()) locked[SurfaceMesh::edge(ax)] = 1;
        }
        r.removed = true;
        if (o.flip_after) {
            std::vector<Edge> seeds;
            for (Halfedge g : m.outgoing_halfedges(a)) {
                seeds.push_back(SurfaceMesh::edge(g));
                if (!m.is_boundary(g)) seeds.push_back(SurfaceMesh::edge(m.next(g)));
            }
            const Vertex centre[1] = {a};
            const LocalFlipOutcome lf = local_flip(m, centre, seeds, o.rule, o.feature_angle_deg, o.check_rings,
                                                   o.max_repair_rounds, false, true);
            r.flips = lf.flips;
            r.not_improving = lf.not_improving;
            r.balls_empty = lf.left.star == 0;
        }
        return r;
    }
    r.removed = false;
    r.reason = "remove_point(" + vname(v) + "): no collapse along its locked edges keeps the mesh valid";
    return r;
}

}  // namespace

RemoveResult remove_point(SurfaceMesh& m, Vertex v, const RemoveOptions& o) {
    DYNMESH_CHECK(m.is_valid(v) && !m.is_deleted(v),
                  "remove_point: vertex " + vname(v) + " is invalid or deleted");
    RemoveResult r;
    auto refuse = [&](std::string why) {
        r.removed = false;
        r.reason = "remove_point(" + vname(v) + "): " + std::move(why);
        return r;
    };
    if (m.is_isolated(v)) return refuse("isolated vertex");
    if (m.is_boundary(v)) return refuse("boundary vertex");
    if (m.n_vertices() < 5) return refuse("removal would leave fewer than 4 vertices");
    r.link = m.neighbors(v);
    const std::vector<Vertex>& link = r.link;
    const std::size_t k = link.size();
    if (k < 3) return refuse("valence below 3");
    {
        std::vector<Vertex> sorted = link;
        std::sort(sorted.begin(), sorted.end());
        if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
            return refuse("the link is not a simple cycle");
    }
    if (k == 3 && m.opposite_vertex(m.find_halfedge(link[1], link[0])) == link[2])
        return refuse("the link triangle is already a face (tetrahedron)");
    if (const auto locked = locked_edges(m); locked.is_valid()) {
        const std::size_t deg = locked_degree(m, locked, v);
        if (deg == 2) return remove_crease_point(m, v, o, locked, r);
        if (deg != 0) return refuse("a corner of the locked edges (" + std::to_string(deg) + " of them meet there)");
    }

    // Candidate planes: the incident triangles, the one closest to the star normal first.
    const Point3& pv = m.position(v);
    std::vector<Vec3> normals(k);
    Vec3 star{};
    for (std::size_t i = 0; i < k; ++i) {
        const Vec3 n = triangle_normal_raw(pv, m.position(link[i]), m.position(link[(i + 1) % k]));
        star += n;
        normals[i] = normalized(n);
    }
    star = normalized(star);
    std::vector<std::size_t> order;
    std::vector<double> score(k);
    for (std::size_t i = 0; i < k; ++i) {
        if (sqnorm(normals[i]) == 0 || !is_finite(normals[i])) continue;  // degenerate
        score[i] = dot(normals[i], star);
        order.push_back(i);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return score[a] > score[b]; });

    std::string last_failure = "no incident triangle has a normal";
    Triangles chosen;
    for (std::size_t i : order) {
        ++r.planes_tried;
        const Vec3& n = normals[i];
        // A right-handed basis (u, w, n): counter-clockwise seen from +n stays so in 2D.
        const Vec3 axis = std::abs(n.x) <= std::abs(n.y) && std::abs(n.x) <= std::abs(n.z)
                              ? Vec3{1, 0, 0}
                              : (std::abs(n.y) <= std::abs(n.z) ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
        const Vec3 u = normalized(cross(n, axis));
        const Vec3 w = cross(n, u);
        std::vector<Point2> q(k);
        for (std::size_t j = 0; j < k; ++j) {
            const Vec3 d = m.position(link[j]) - pv;
            q[j] = {dot(d, u), dot(d, w)};
        }
        if (auto problem = polygon_problem(q)) {
            last_failure = *problem;
            continue;
        }
        auto cdt = polygon_cdt(q);
        if (auto* why = std::get_if<std::string>(&cdt)) {
            last_failure = *why;
            continue;
        }
        Triangles tris = std::get<Triangles>(std::move(cdt));
        // Reject diagonals that are already mesh edges, and degenerate 3D triangles.
        bool ok = true;
        for (const auto& t : tris) {
            if (is_degenerate_triangle(m.position(link[t[0]]), m.position(link[t[1]]),
                                       m.position(link[t[2]]))) {
                last_failure = "a new triangle would be degenerate";
                ok = false;
                break;
            }
            for (int j = 0; j < 3 && ok; ++j) {
                const std::uint32_t a = t[j], b = t[(j + 1) % 3];
                const bool side = b == (a + 1) % k || a == (b + 1) % k;
                if (!side && m.find_halfedge(link[a], link[b]).is_valid()) {
                    last_failure = "diagonal (" + vname(link[a]) + ", " + vname(link[b]) +
                                   ") is already a mesh edge";
                    ok = false;
                }
            }
            if (!ok) break;
        }
        if (!ok) continue;
        try {
            m.remove_vertex(v, tris);
        } catch (const InvalidInput& e) {  // the mesh is unchanged
            last_failure = e.what();
            continue;
        }
        r.plane_normal = n;
        chosen = std::move(tris);
        r.removed = true;
        break;
    }
    if (!r.removed) {
        return refuse("no plane works (" + std::to_string(r.planes_tried) +
                      " tried; last: " + last_failure + ")");
    }
    r.triangles = std::move(chosen);

    // Local flip seeded with every edge among the link vertices.
    std::unordered_set<std::uint32_t> in_link;
    for (Vertex x : link) in_link.insert(x.idx());
    std::vector<Edge> seeds;
    for (Vertex x : link)
        for (Halfedge h : m.outgoing_halfedges(x))
            if (in_link.count(m.to_vertex(h).idx()) != 0 && x.idx() < m.to_vertex(h).idx())
                seeds.push_back(SurfaceMesh::edge(h));
    const LocalFlipOutcome lf =
        local_flip(m, link, seeds, o.rule, o.feature_angle_deg, o.check_rings, o.max_repair_rounds,
                   /*centre_in_nearby_balls=*/false, o.flip_after);
    r.flips = lf.flips;
    r.not_improving = lf.not_improving;
    r.balls_empty = lf.left.star == 0;
    return r;
}

}  // namespace dynmesh
