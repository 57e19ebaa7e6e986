#include "dynmesh/quadtree/offcenter.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/spatial_sort.hpp"
#include "dynmesh/geometry/format.hpp"

namespace dynmesh {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;
using VertexHandle = Delaunay::Vertex_handle;
using FaceHandle = Delaunay::Face_handle;

enum class Side : std::uint8_t { Ccw = 0, Cw = 1 };  // side of the directed pair lo -> hi

inline bool lex_less(const Vec2& a, const Vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }
inline Vec2 to_vec(const K::Point_2& p) { return {p.x(), p.y()}; }
inline K::Point_2 to_cgal(const Vec2& p) { return {p.x, p.y}; }

/// One (pair, side) that was loose when found. Ordered by the canonical key of spec §5.3.4.
struct Candidate {
    int size_class = 0;
    double len2 = 0;  // |hi − lo|², rounded (a deterministic function of lo, hi)
    Vec2 lo, hi;      // lo lexicographically smaller
    Side side = Side::Ccw;
    VertexHandle vlo, vhi;

    [[nodiscard]] auto key() const {
        return std::make_tuple(size_class, len2, lo.x, lo.y, hi.x, hi.y, static_cast<int>(side));
    }
};

/// What the loose test found: the face of the pair on the tested side and its apex t.
struct LooseInfo {
    FaceHandle face;
    Vec2 t;
};


/// The box sides, numbered bottom, right, top, left; coordinates along a side are x for even
/// sides and y for odd ones.
struct Subsegment {
    int side = 0;
    double a = 0, b = 0;  // a < b along the side
};

/// Worker of offcenter_mesh(): the state of one static run (spec §5.3).
class OffCenterRefiner {
public:
    OffCenterRefiner(const DynQuadtree<2>& tree, const OffCenterOptions& options)
        : tree_(tree), options_(options),
          kernel_(tree.options().origin, tree.options().width, options) {
        origin_ = kernel_.origin;
        width_ = kernel_.width;
        hi_ = kernel_.hi;
    }

    OffCenterMesh2 run();

private:
    [[nodiscard]] int size_class(double len2) const { return kernel_.size_class(len2); }
    [[nodiscard]] Vec2 side_point(int side, double c) const { return kernel_.side_point(side, c); }
    [[nodiscard]] static double along(int side, const Vec2& p) {
        return detail::OffCenterKernel::along(side, p);
    }
    /// The lexicographically smallest vertex on the given side of lo -> hi among those of the
    /// degenerate Delaunay cell of face f (f itself when no neighbour is cocircular).
    [[nodiscard]] VertexHandle canonical_opposite(FaceHandle f, VertexHandle lo, VertexHandle hi,
                                                  bool left) const;

    /// Inserts p; returns an invalid handle if p is already a vertex.
    VertexHandle add_vertex(const Vec2& p, FaceHandle hint);
    /// The subsegment of `side` whose span contains coordinate c (clamped to the side).
    [[nodiscard]] Subsegment subsegment_at(int side, double c) const;
    [[nodiscard]] bool encroaches(const Subsegment& s, const Vec2& p) const;
    void split(const Subsegment& s);
    /// The loose test of spec §5.1 for (lo, hi, side); nullopt when pq is not a Delaunay edge
    /// or not loose on that side.
    [[nodiscard]] std::optional<LooseInfo> loose(VertexHandle lo, VertexHandle hi, Side side) const;
    /// Queues every loose (pair, side) with an endpoint v.
    void enqueue_incident(VertexHandle v);
    void enqueue_edge(VertexHandle a, VertexHandle b);
    void process(const Candidate& c);
    void round_zero();

    const DynQuadtree<2>& tree_;
    OffCenterOptions options_;
    detail::OffCenterKernel kernel_;
    Vec2 origin_{}, hi_{};
    double width_ = 1;

    Delaunay dt_;
    std::vector<VertexHandle> vertices_;  // by insertion id (= info())
    std::size_t input_count_ = 0;
    std::array<std::set<double>, 4> side_coords_;
    std::vector<Candidate> pending_;
    OffCenterMesh2 out_;
};

VertexHandle OffCenterRefiner::add_vertex(const Vec2& p, FaceHandle hint) {
    const std::size_t before = dt_.number_of_vertices();
    VertexHandle v = hint == FaceHandle() ? dt_.insert(to_cgal(p)) : dt_.insert(to_cgal(p), hint);
    if (dt_.number_of_vertices() == before) return VertexHandle();
    v->info() = static_cast<std::uint32_t>(vertices_.size());
    vertices_.push_back(v);
    if (vertices_.size() - input_count_ > options_.max_steiner)
        throw InternalError("offcenter_mesh: more than " + std::to_string(options_.max_steiner) +
                            " Steiner points (rho = " + std::to_string(options_.rho) + ")");
    return v;
}

Subsegment OffCenterRefiner::subsegment_at(int side, double c) const {
    const auto& coords = side_coords_[static_cast<std::size_t>(side)];
    auto it = coords.upper_bound(c);
    if (it == coords.end()) --it;
    if (it == coords.begin()) ++it;
    return {side, *std::prev(it), *it};
}

bool OffCenterRefiner::encroaches(const Subsegment& s, const Vec2& p) const {
    // Closed diametral disc (spec §5.3.1), exact.
    return CGAL::side_of_bounded_circle(to_cgal(side_point(s.side, s.a)),
                                        to_cgal(side_point(s.side, s.b)),
                                        to_cgal(p)) != CGAL::ON_UNBOUNDED_SIDE;
}

void OffCenterRefiner::split(const Subsegment& s) {
    const double mid = s.a + 0.5 * (s.b - s.a);
    if (!(s.a < mid && mid < s.b))
        throw InternalError("offcenter_mesh: box subsegment too short to split (rho = " +
                            std::to_string(options_.rho) + ")");
    const VertexHandle v = add_vertex(side_point(s.side, mid), FaceHandle());
    if (v == VertexHandle())
        throw InternalError("offcenter_mesh: box midpoint is already a vertex");
    side_coords_[static_cast<std::size_t>(s.side)].insert(mid);
    ++out_.boundary_steiner;
    enqueue_incident(v);
}

VertexHandle OffCenterRefiner::canonical_opposite(FaceHandle f, VertexHandle lo,
                                                 VertexHandle hi, bool left) const {
    // Walk the faces reachable from f across edges whose far vertex is cocircular with the
    // face (exact test), never across the edge lo-hi itself.
    std::vector<FaceHandle> stack{f}, seen{f};
    VertexHandle best;
    const Vec2 p = to_vec(lo->point()), q = to_vec(hi->point());
    while (!stack.empty()) {
        const FaceHandle g = stack.back();
        stack.pop_back();
        for (int k = 0; k < 3; ++k) {
            const VertexHandle v = g->vertex(k);
            if (v != lo && v != hi && !dt_.is_infinite(v)) {
                const Sign o = orient2d(p, q, to_vec(v->point()));
                if (o == (left ? Sign::Positive : Sign::Negative) &&
                    (best == VertexHandle() || lex_less(to_vec(v->point()), to_vec(best->point()))))
                    best = v;
            }
            const VertexHandle a = g->vertex(Delaunay::ccw(k)), b = g->vertex(Delaunay::cw(k));
            if ((a == lo && b == hi) || (a == hi && b == lo)) continue;
            const FaceHandle h = g->neighbor(k);
            if (dt_.is_infinite(h) || std::find(seen.begin(), seen.end(), h) != seen.end())
                continue;
            const VertexHandle far = h->vertex(dt_.mirror_index(g, k));
            if (dt_.side_of_oriented_circle(g, far->point()) != CGAL::ON_ORIENTED_BOUNDARY)
                continue;
            seen.push_back(h);
            stack.push_back(h);
        }
    }
    return best;
}

std::optional<LooseInfo> OffCenterRefiner::loose(VertexHandle lo, VertexHandle hi,
                                                 Side side) const {
    FaceHandle f;
    int i = 0;
    if (!dt_.is_edge(lo, hi, f, i)) return std::nullopt;
    // Face f lies to the left of vertex(ccw(i)) -> vertex(cw(i)).
    const FaceHandle g = f->neighbor(i);
    const int j = dt_.mirror_index(f, i);
    const bool f_left_of_lohi = f->vertex(Delaunay::ccw(i)) == lo;
    const bool want_left = side == Side::Ccw;
    const FaceHandle this_face = f_left_of_lohi == want_left ? f : g;
    const FaceHandle other_face = f_left_of_lohi == want_left ? g : f;
    VertexHandle t = f_left_of_lohi == want_left ? f->vertex(i) : g->vertex(j);
    VertexHandle u = f_left_of_lohi == want_left ? g->vertex(j) : f->vertex(i);
    if (dt_.is_infinite(t)) return std::nullopt;  // outside the box: no leaf to refine
    // Canonical opposite vertices (file comment, degenerate configurations).
    t = canonical_opposite(this_face, lo, hi, want_left);
    if (!dt_.is_infinite(u)) u = canonical_opposite(other_face, lo, hi, !want_left);
    const Vec2 p = to_vec(lo->point()), q = to_vec(hi->point()), tp = to_vec(t->point());
    const double len2 = dot(q - p, q - p);
    // Closed leaf: t (same side) is inside iff ∠ptq ≥ θ; u (other side) iff ∠puq ≥ π − θ.
    if (kernel_.in_leaf_same_side(tp, p, q, len2)) return std::nullopt;
    if (!dt_.is_infinite(u) && kernel_.in_leaf_other_side(to_vec(u->point()), p, q, len2))
        return std::nullopt;
    return LooseInfo{this_face, tp};
}

void OffCenterRefiner::enqueue_edge(VertexHandle a, VertexHandle b) {
    if (lex_less(to_vec(b->point()), to_vec(a->point()))) std::swap(a, b);
    const Vec2 lo = to_vec(a->point()), hi = to_vec(b->point());
    const double len2 = dot(hi - lo, hi - lo);
    for (Side s : {Side::Ccw, Side::Cw})
        if (loose(a, b, s)) pending_.push_back({size_class(len2), len2, lo, hi, s, a, b});
}

void OffCenterRefiner::enqueue_incident(VertexHandle v) {
    auto ec = dt_.incident_edges(v);
    const auto done = ec;
    if (ec == nullptr) return;
    do {
        if (dt_.is_infinite(ec)) continue;
        const FaceHandle f = ec->first;
        const int i = ec->second;
        enqueue_edge(f->vertex(Delaunay::ccw(i)), f->vertex(Delaunay::cw(i)));
    } while (++ec != done);
}

void OffCenterRefiner::round_zero() {
    // Split every box subsegment whose closed diametral disc holds another vertex, until none
    // does. Only inputs can encroach (corners and midpoints never do), and they lie in the
    // middle third, so this stops after splitting long subsegments a few times.
    const auto pts = tree_.points();
    bool changed = true;
    while (changed) {
        changed = false;
        for (int side = 0; side < 4; ++side) {
            const std::vector<double> coords(side_coords_[static_cast<std::size_t>(side)].begin(),
                                             side_coords_[static_cast<std::size_t>(side)].end());
            for (std::size_t k = 0; k + 1 < coords.size(); ++k) {
                const Subsegment s{side, coords[k], coords[k + 1]};
                const bool hit = std::any_of(pts.begin(), pts.end(), [&](const auto& e) {
                    return encroaches(s, e.second);
                });
                if (hit) {
                    split(s);
                    changed = true;
                }
            }
        }
    }
}

void OffCenterRefiner::process(const Candidate& c) {
    const auto info = loose(c.vlo, c.vhi, c.side);
    if (!info) return;  // no longer loose: an earlier insertion filled its leaf
    // Off-center (spec §5.1): m + min(σ_apex, σ_t)·perp, perp = (hi − lo) turned to the side.
    bool apex = false;
    const Vec2 r = kernel_.offcenter(c.lo, c.hi, c.side == Side::Cw, c.len2, info->t, apex);

    // Boundary (spec §5.3.1): an off-center in the closed diametral disc of a box subsegment
    // (or outside the open box) is replaced by the midpoints of the subsegments it encroaches;
    // the pair is retried in the next round.
    std::vector<Subsegment> hit;
    for (int side = 0; side < 4; ++side) {
        const Subsegment s = subsegment_at(side, along(side, r));
        if (encroaches(s, r)) hit.push_back(s);
    }
    const bool inside = origin_.x < r.x && r.x < hi_.x && origin_.y < r.y && r.y < hi_.y;
    if (hit.empty() && !inside) {
        // Not expected (an off-center lies between m and the circumcentre of pqt, both in the
        // box while no subsegment is encroached); split the subsegment nearest to r anyway.
        const Vec2 cl{std::clamp(r.x, origin_.x, hi_.x), std::clamp(r.y, origin_.y, hi_.y)};
        const int side = cl.y == origin_.y ? 0 : cl.x == hi_.x ? 1 : cl.y == hi_.y ? 2 : 3;
        hit.push_back(subsegment_at(side, along(side, cl)));
    }
    if (!hit.empty()) {
        for (const Subsegment& s : hit) split(s);
        pending_.push_back(c);
        return;
    }
    const VertexHandle v = add_vertex(r, info->face);
    if (v == VertexHandle()) {
        ++out_.stuck_pairs;  // rounding put r onto an existing vertex; give up on this pair
        return;
    }
    ++(apex ? out_.apex_offcenters : out_.circumcentres);
    enqueue_incident(v);
    // An off-center lies in the closed leaf, so the pair is done; a circumcentre beyond the apex
    // (use_offcenters = false) may leave it loose: retry it in the next round.
    if (loose(c.vlo, c.vhi, c.side)) pending_.push_back(c);
}

OffCenterMesh2 OffCenterRefiner::run() {
    out_.origin = origin_;
    out_.width = width_;
    const auto pts = tree_.points();  // canonical order: sorted by grid coordinates
    input_count_ = pts.size();

    // Inputs in a deterministic spatial order (the triangulation of a cocircular set depends on
    // the insertion sequence, so the sequence must be a function of the point set).
    std::vector<Point3> p3;
    p3.reserve(pts.size());
    for (const auto& e : pts) p3.push_back({e.second.x, e.second.y, 0.0});
    const auto order = spatial_order(p3);
    FaceHandle hint;
    vertices_.resize(pts.size());
    for (std::uint32_t k : order) {
        const VertexHandle v = hint == FaceHandle() ? dt_.insert(to_cgal(pts[k].second))
                                                    : dt_.insert(to_cgal(pts[k].second), hint);
        v->info() = k;
        vertices_[k] = v;
        hint = v->face();
    }
    // Resolution (file comment): the closest pair of inputs is a Delaunay edge.
    const double min_sep2 = kernel_.min_separation() * kernel_.min_separation();
    for (auto e = dt_.finite_edges_begin(); e != dt_.finite_edges_end(); ++e) {
        const Vec2 a = to_vec(e->first->vertex(Delaunay::ccw(e->second))->point());
        const Vec2 b = to_vec(e->first->vertex(Delaunay::cw(e->second))->point());
        if (dot(b - a, b - a) < min_sep2)
            throw InvalidInput("offcenter_mesh: points " + format_point(a) + " and " +
                               format_point(b) + " are closer than the " +
                               format_number(kernel_.min_separation()) +
                               " the off-center refinement resolves in this domain at rho = " +
                               format_number(options_.rho));
    }
    // Box corners: the hull of V is the box from now on.
    for (int side = 0; side < 4; ++side) {
        side_coords_[static_cast<std::size_t>(side)] = {side % 2 == 0 ? origin_.x : origin_.y,
                                                         side % 2 == 0 ? hi_.x : hi_.y};
    }
    for (const Vec2& corner : {origin_, Vec2{hi_.x, origin_.y}, hi_, Vec2{origin_.x, hi_.y}}) {
        if (add_vertex(corner, FaceHandle()) == VertexHandle())
            throw InternalError("offcenter_mesh: a box corner coincides with an input point");
        ++out_.boundary_steiner;
    }
    round_zero();

    // Initial candidates: every loose (Delaunay edge, side).
    pending_.clear();
    for (auto e = dt_.finite_edges_begin(); e != dt_.finite_edges_end(); ++e)
        enqueue_edge(e->first->vertex(Delaunay::ccw(e->second)),
                     e->first->vertex(Delaunay::cw(e->second)));

    // Rounds by size class (spec §5.3.3–4).
    int finger = std::numeric_limits<int>::min();
    while (!pending_.empty()) {
        int lowest = std::numeric_limits<int>::max();
        for (const Candidate& c : pending_) lowest = std::min(lowest, c.size_class);
        finger = std::max(finger, lowest);
        const auto split_at = std::partition(pending_.begin(), pending_.end(), [&](const auto& c) {
            return c.size_class > finger;
        });
        std::vector<Candidate> round(split_at, pending_.end());
        pending_.erase(split_at, pending_.end());
        std::sort(round.begin(), round.end(),
                  [](const Candidate& a, const Candidate& b) { return a.key() < b.key(); });
        round.erase(std::unique(round.begin(), round.end(),
                                [](const Candidate& a, const Candidate& b) {
                                    return a.key() == b.key();
                                }),
                    round.end());
        ++out_.rounds;
        for (const Candidate& c : round) process(c);
    }

    // Canonical output: inputs in tree order, then Steiner points sorted by (x, y).
    std::vector<std::uint32_t> steiner_ids;
    for (std::size_t id = input_count_; id < vertices_.size(); ++id)
        steiner_ids.push_back(static_cast<std::uint32_t>(id));
    std::sort(steiner_ids.begin(), steiner_ids.end(), [&](std::uint32_t a, std::uint32_t b) {
        return lex_less(to_vec(vertices_[a]->point()), to_vec(vertices_[b]->point()));
    });
    std::vector<std::uint32_t> final_index(vertices_.size());
    out_.points.reserve(vertices_.size());
    for (std::size_t k = 0; k < input_count_; ++k) {
        final_index[k] = static_cast<std::uint32_t>(k);
        out_.points.push_back(pts[k].second);
        out_.input_vertices.push_back(static_cast<std::uint32_t>(k));
    }
    for (std::uint32_t id : steiner_ids) {
        final_index[id] = static_cast<std::uint32_t>(out_.points.size());
        out_.points.push_back(to_vec(vertices_[id]->point()));
    }
    out_.steiner = steiner_ids.size();
    out_.triangles.reserve(dt_.number_of_faces());
    for (auto f = dt_.finite_faces_begin(); f != dt_.finite_faces_end(); ++f) {
        std::array<std::uint32_t, 3> t{};
        for (int k = 0; k < 3; ++k) t[static_cast<std::size_t>(k)] = final_index[f->vertex(k)->info()];
        out_.triangles.push_back(t);
    }
    detail::finish_offcenter_mesh(out_);
    return std::move(out_);
}

long double twice_area(const Vec2& a, const Vec2& b, const Vec2& c) {
    return static_cast<long double>(b.x - a.x) * (c.y - a.y) -
           static_cast<long double>(b.y - a.y) * (c.x - a.x);
}

}  // namespace

namespace detail {

OffCenterKernel::OffCenterKernel(const Vec2& origin_in, double width_in,
                                 const OffCenterOptions& options)
    : origin(origin_in), hi{origin_in.x + width_in, origin_in.y + width_in}, width(width_in),
      theta(std::asin(1.0 / (2.0 * options.rho))),
      sigma_apex(options.rho + std::sqrt(options.rho * options.rho - 0.25)),
      scale(std::max({std::fabs(origin_in.x), std::fabs(origin_in.y), std::fabs(hi.x),
                      std::fabs(hi.y), width_in})),
      use_offcenters(options.use_offcenters) {}

double OffCenterKernel::slack(double len2) const {
    return 1e-12 + 64.0 * DBL_EPSILON * scale / std::sqrt(len2);
}

void require_rho(const OffCenterOptions& options, const char* who) {
    if (!std::isfinite(options.rho) || !(options.rho > std::sqrt(2.0)))
        throw InvalidInput(std::string(who) + ": rho = " + std::to_string(options.rho) +
                           " must be finite and > sqrt(2)");
}

void require_offcenter_domain(const QuadtreeOptions<2>& domain, const char* who) {
    const double w = domain.width;
    const double s = std::max({std::fabs(domain.origin.x), std::fabs(domain.origin.y),
                               std::fabs(domain.origin.x + w), std::fabs(domain.origin.y + w)});
    if (!std::isfinite(w) || !std::isfinite(s)) return;  // DynQuadtree's constructor says why
    if (w < kOffCenterMinScale || w > kOffCenterMaxScale || s > kOffCenterMaxScale)
        throw InvalidInput(std::string(who) + ": the domain (width " + format_number(w) +
                           ", coordinates up to " + format_number(s) +
                           ") is outside the range of the off-center refinement: width and "
                           "coordinates must lie in [1e-120, 1e120] (scale the points by a power "
                           "of two)");
}

double OffCenterKernel::min_separation() const {
    return 64.0 * DBL_EPSILON * scale / (0.5 * theta - 1e-12);
}

int OffCenterKernel::size_class(double len2) const {
    int e = 0;
    (void)std::frexp(len2 / (width * width), &e);  // len2/W² in [2^(e-1), 2^e)
    return static_cast<int>(std::floor((e - 1) / 2.0));
}

Vec2 OffCenterKernel::side_point(int side, double c) const {
    switch (side) {
        case 0: return {c, origin.y};
        case 1: return {hi.x, c};
        case 2: return {c, hi.y};
        default: return {origin.x, c};
    }
}

double OffCenterKernel::along(int side, const Vec2& p) { return side % 2 == 0 ? p.x : p.y; }

double OffCenterKernel::angle_at(const Vec2& t, const Vec2& p, const Vec2& q) {
    const Vec2 u = p - t, v = q - t;
    return std::atan2(std::fabs(cross(u, v)), dot(u, v));
}

bool OffCenterKernel::in_leaf_same_side(const Vec2& t, const Vec2& lo, const Vec2& hi_pt,
                                        double len2) const {
    return angle_at(t, lo, hi_pt) >= theta - slack(len2);
}

bool OffCenterKernel::in_leaf_other_side(const Vec2& u, const Vec2& lo, const Vec2& hi_pt,
                                         double len2) const {
    return angle_at(u, lo, hi_pt) >= std::numbers::pi - theta - slack(len2);
}

// Both work relative to lo: the midpoint is lo + d/2 with d/2 exact, and t − lo is exact for
// nearby points, so σ_t carries a relative error of a few ε of the pair, not an ulp of the
// coordinates (which is a large part of a pair a few thousand ulps long); the result is
// rounded once, when lo is added back. DynOffCenterMesh2's searches use the same frame.
Vec2 OffCenterKernel::offcenter(const Vec2& lo, const Vec2& hi_pt, bool cw, double len2,
                                const Vec2& t, bool& apex) const {
    const Vec2 d = hi_pt - lo;
    const Vec2 perp = cw ? Vec2{d.y, -d.x} : Vec2{-d.y, d.x};
    const Vec2 hm{0.5 * d.x, 0.5 * d.y};
    const Vec2 w = (t - lo) - hm;
    const double sigma_t = (dot(w, w) - 0.25 * len2) / (2.0 * dot(w, perp));
    apex = use_offcenters && sigma_apex <= sigma_t;
    const double sigma = apex ? sigma_apex : sigma_t;
    return lo + (hm + sigma * perp);
}

Vec2 OffCenterKernel::apex_point(const Vec2& lo, const Vec2& hi_pt, bool cw) const {
    const Vec2 d = hi_pt - lo;
    const Vec2 perp = cw ? Vec2{d.y, -d.x} : Vec2{-d.y, d.x};
    const Vec2 hm{0.5 * d.x, 0.5 * d.y};
    return lo + (hm + sigma_apex * perp);
}

void finish_offcenter_mesh(OffCenterMesh2& mesh) {
    auto& tris = mesh.triangles;
    const auto& pts = mesh.points;
    // Directed edge -> triangle.
    std::unordered_map<std::uint64_t, std::uint32_t> edge_tri;
    edge_tri.reserve(3 * tris.size());
    auto ekey = [](std::uint32_t a, std::uint32_t b) {
        return (static_cast<std::uint64_t>(a) << 32) | b;
    };
    for (std::uint32_t t = 0; t < tris.size(); ++t)
        for (std::size_t k = 0; k < 3; ++k) edge_tri[ekey(tris[t][k], tris[t][(k + 1) % 3])] = t;
    // Union the two triangles of every interior edge whose four points are cocircular.
    std::vector<std::uint32_t> parent(tris.size());
    for (std::uint32_t t = 0; t < tris.size(); ++t) parent[t] = t;
    auto find = [&](std::uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    bool any = false;
    for (std::uint32_t t = 0; t < tris.size(); ++t)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t a = tris[t][k], b = tris[t][(k + 1) % 3], c = tris[t][(k + 2) % 3];
            if (a > b) continue;
            const auto it = edge_tri.find(ekey(b, a));
            if (it == edge_tri.end()) continue;
            const auto& o = tris[it->second];
            const std::uint32_t d =
                o[0] != a && o[0] != b ? o[0] : (o[1] != a && o[1] != b ? o[1] : o[2]);
            if (incircle(pts[a], pts[b], pts[c], pts[d]) != Sign::Zero) continue;
            parent[find(t)] = find(it->second);
            any = true;
        }
    if (any) {
        // Each degenerate cell: its boundary cycle (directed edges without a twin inside the
        // cell), then a fan from its smallest vertex.
        std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> cells;
        for (std::uint32_t t = 0; t < tris.size(); ++t) cells[find(t)].push_back(t);
        std::vector<std::array<std::uint32_t, 3>> out;
        out.reserve(tris.size());
        for (std::uint32_t t = 0; t < tris.size(); ++t) {
            const auto& cell = cells[find(t)];
            if (cell.size() == 1) {
                out.push_back(tris[t]);
                continue;
            }
            if (cell.front() != t) continue;  // handle each cell once
            std::unordered_map<std::uint32_t, std::uint32_t> next;
            for (std::uint32_t f : cell)
                for (std::size_t k = 0; k < 3; ++k) {
                    const std::uint32_t a = tris[f][k], b = tris[f][(k + 1) % 3];
                    const auto it = edge_tri.find(ekey(b, a));
                    if (it != edge_tri.end() && find(it->second) == find(t)) continue;
                    next[a] = b;
                }
            std::uint32_t v0 = std::numeric_limits<std::uint32_t>::max();
            for (const auto& [a, b] : next) v0 = std::min(v0, a);
            std::vector<std::uint32_t> ring{v0};
            for (std::uint32_t v = next.at(v0); v != v0 && ring.size() <= next.size();
                 v = next.at(v))
                ring.push_back(v);
            if (ring.size() != next.size())
                throw InternalError("offcenter_mesh: a degenerate Delaunay cell is not a polygon");
            for (std::size_t j = 1; j + 1 < ring.size(); ++j)
                out.push_back({v0, ring[j], ring[j + 1]});
        }
        tris = std::move(out);
    }
    for (auto& t : tris) {
        const auto first = std::min_element(t.begin(), t.end());
        std::rotate(t.begin(), first, t.end());  // keeps the ccw orientation
    }
    std::sort(tris.begin(), tris.end());
    mesh.min_angle_deg = 180.0;
    for (const auto& t : tris)
        for (std::size_t k = 0; k < 3; ++k) {
            const double a = OffCenterKernel::angle_at(pts[t[k]], pts[t[(k + 1) % 3]],
                                                       pts[t[(k + 2) % 3]]);
            mesh.min_angle_deg = std::min(mesh.min_angle_deg, a * 180.0 / std::numbers::pi);
        }
}

}  // namespace detail

double offcenter_min_angle_deg(double rho) {
    return std::asin(1.0 / (2.0 * rho)) * 180.0 / std::numbers::pi;
}

double offcenter_min_separation(const QuadtreeOptions<2>& domain,
                                const OffCenterOptions& options) {
    detail::require_rho(options, "offcenter_min_separation");
    detail::require_offcenter_domain(domain, "offcenter_min_separation");
    return detail::OffCenterKernel(domain.origin, domain.width, options).min_separation();
}

double offcenter_promised_min_angle_deg(const OffCenterMesh2& mesh,
                                        const OffCenterOptions& options) {
    double shortest2 = std::numeric_limits<double>::infinity();
    for (const auto& t : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            const Vec2 d = mesh.points[t[k]] - mesh.points[t[(k + 1) % 3]];
            shortest2 = std::min(shortest2, dot(d, d));
        }
    const detail::OffCenterKernel kernel(mesh.origin, mesh.width, options);
    const double slack = std::isfinite(shortest2) ? kernel.slack(shortest2) : 0.0;
    return offcenter_min_angle_deg(options.rho) - slack * 180.0 / std::numbers::pi;
}

OffCenterMesh2 offcenter_mesh(const DynQuadtree<2>& tree, const OffCenterOptions& options) {
    detail::require_rho(options, "offcenter_mesh");
    detail::require_offcenter_domain(tree.options(), "offcenter_mesh");
    OffCenterRefiner refiner(tree, options);
    return refiner.run();
}

CheckReport check_offcenter_mesh(const OffCenterMesh2& mesh) {
    std::vector<std::string> bad;
    const auto n = mesh.points.size();
    std::vector<bool> used(n, false);
    // Directed edge (a, b) -> the third vertex of its triangle.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> apex;
    long double area2 = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        if (tri[0] >= n || tri[1] >= n || tri[2] >= n) {
            bad.push_back("triangle " + std::to_string(t) + ": index out of range");
            continue;
        }
        const Vec2 &a = mesh.points[tri[0]], &b = mesh.points[tri[1]], &c = mesh.points[tri[2]];
        if (orient2d(a, b, c) != Sign::Positive)
            bad.push_back("triangle " + std::to_string(t) + " is not counter-clockwise");
        area2 += twice_area(a, b, c);
        for (std::size_t k = 0; k < 3; ++k) {
            used[tri[k]] = true;
            if (!apex.emplace(std::make_pair(tri[k], tri[(k + 1) % 3]), tri[(k + 2) % 3]).second)
                bad.push_back("directed edge (" + std::to_string(tri[k]) + ", " +
                              std::to_string(tri[(k + 1) % 3]) + ") used twice");
        }
    }
    // The box the corners span: its far corner is origin + W rounded, as the mesh places it.
    const double x0 = mesh.origin.x, y0 = mesh.origin.y, x1 = x0 + mesh.width, y1 = y0 + mesh.width;
    const long double want = (static_cast<long double>(x1) - x0) * (static_cast<long double>(y1) - y0);
    if (std::fabs(area2 / 2 - want) > 1e-12L * want)
        bad.push_back("total area " + format_number(static_cast<double>(area2 / 2)) +
                      " differs from the box area " + format_number(static_cast<double>(want)));
    for (const auto& [e, c] : apex) {
        const auto twin = apex.find({e.second, e.first});
        const Vec2 &a = mesh.points[e.first], &b = mesh.points[e.second];
        if (twin == apex.end()) {
            const bool on_box = (a.x == x0 && b.x == x0) || (a.x == x1 && b.x == x1) ||
                                (a.y == y0 && b.y == y0) || (a.y == y1 && b.y == y1);
            if (!on_box)
                bad.push_back("edge (" + std::to_string(e.first) + ", " +
                              std::to_string(e.second) + ") has one triangle but is not on the box");
            continue;
        }
        if (e.first > e.second) continue;  // test each interior edge once
        // Empty circle: the far apex d is not strictly inside the circle of (a, b, c).
        if (incircle(a, b, mesh.points[c], mesh.points[twin->second]) == Sign::Positive)
            bad.push_back("edge (" + std::to_string(e.first) + ", " + std::to_string(e.second) +
                          ") is not locally Delaunay");
    }
    for (std::size_t v = 0; v < n; ++v)
        if (!used[v]) bad.push_back("vertex " + std::to_string(v) + " is unused");
    std::vector<std::pair<double, double>> sorted;
    sorted.reserve(n);
    for (const Vec2& p : mesh.points) sorted.emplace_back(p.x, p.y);
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
        bad.push_back("two vertices share a position");
    for (std::size_t k = 0; k < mesh.input_vertices.size(); ++k)
        if (mesh.input_vertices[k] >= n)
            bad.push_back("input point " + std::to_string(k) + " has no vertex");
    return CheckReport::of_problems(std::move(bad));
}

}  // namespace dynmesh
