#pragma once
/// \file The probing refinement (private; specs/probing.md §3–§5, §8, §10), written once for
/// both dimensions over a triangulation adapter (Triangulation3 for surfaces, Triangulation2
/// for curves). See include/dynmesh/probing/refine.hpp for what it computes.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/probing/device.hpp"
#include "dynmesh/probing/refine.hpp"
#include "path_forest.hpp"
#include "probe_common.hpp"
#include "refiner_types.hpp"

namespace dynmesh::detail {

/// The options after validation, with ε resolved.
void check_probing_options(const ProbingOptions& o, int dim);
[[nodiscard]] double resolved_eps(const ProbingOptions& o);
/// Does the closed oriented surface (or, in 2D, the closed polygons) `soup`/`polygons` of
/// one component enclose p? Parity of the crossings of a ray from p.
[[nodiscard]] bool surface_encloses(const TriangleSoup& soup, const std::vector<std::size_t>& faces,
                                    const Point3& p);
[[nodiscard]] bool polygon_encloses(const TriangleSoup& soup, const std::vector<std::uint32_t>& loop,
                                    const Point3& p);

template <class Tri>
class Refiner {
    using Cell = typename Tri::Cell;
    static constexpr int kDim = Tri::kDim;
    static constexpr int kFacets = Tri::kFacets;
    using Info = typename Tri::Info;

public:
    Refiner(const Oracle& oracle, const ProbingOptions& o)
        : oracle_(oracle), o_(o), C_(o.omega.center), R_(o.omega.radius), eps_(resolved_eps(o)),
          tau_(std::max(oracle.tolerance(), 1e-12 * o.omega.radius)),
          omniscient_(o.mode == ProbingMode::Omniscient),
          walk_(o.ground_truth != nullptr || o.record_path),
          device_(oracle, o.omega, omniscient_ ? nullptr : o.ground_truth) {
        device_.set_recording(o.record_path && !omniscient_);
    }

    ProbingResult run() {
        const auto t0 = std::chrono::steady_clock::now();
        rep_.eps = eps_;
        bootstrap();
        for (;;) {
            refine();
            if (reinitialise_missing_components() == 0) break;
        }
        if (o_.check_every != SIZE_MAX) check_invariants();
        ProbingResult res;
        output(res.mesh, res.polygons);
        check_enclosure(res.mesh, res.polygons);
        res.sample = sample_;
        rep_.vertices = res.mesh.points.size();
        rep_.facets = kDim == 3 ? res.mesh.triangles.size() : count_polygon_edges(res.polygons);
        rep_.voronoi_edges_travelled = rep_.detection_edges + rep_.positioning_edges;
        const DeviceCounters& dc = device_.counters();
        rep_.probes += dc.probes;
        rep_.path_length = dc.inside_length;
        rep_.exterior_path_length = dc.exterior_length;
        rep_.segments_checked = dc.monitored_segments;
        if (o_.on_snapshot) {
            const auto path = device_.take_recorded_paths();
            o_.on_snapshot({rep_.insertions, &res.mesh, &res.polygons, &path, true});
            full_path_.insert(full_path_.end(), path.begin(), path.end());
        } else if (o_.record_path) {
            full_path_ = device_.take_recorded_paths();
        }
        res.path = std::move(full_path_);
        rep_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        res.report = rep_;
        res.problems = problems_;
        return res;
    }

private:
    // ---- the main loop (spec §4.5) ------------------------------------------------------------
    void refine() {
        while (!queue_.empty()) {
            const BallEntry e = queue_.top();
            queue_.pop();
            const Node& n = nodes_[e.node];
            if (!n.alive || info(e.node).rec[e.facet].stamp != e.stamp ||
                info(e.node).rec[e.facet].state != Record::Hit) {
                ++rep_.stale_pops;
                continue;
            }
            if (sample_.size() >= o_.max_points)
                throw InvalidInput("probe: more than max_points = " + std::to_string(o_.max_points) +
                                   " samples: eps is too small for this object");
            // The ball must still be empty (spec §8.2): its centre is then more than eps from
            // every sample, which is what bounds the run.
            const Cell c = cells_[e.node];
            const Point3 x = Tri::info(c).rec[e.facet].x;
            if (!ball_is_empty(c, e.facet, x)) {
                ++rep_.nonempty_pops;
                continue;
            }
            insert(x, c, e.facet);
            ++rep_.insertions;
            after_insertion();
        }
    }

    void after_insertion() {
        if (o_.check_every != 0 && o_.check_every != SIZE_MAX && rep_.insertions % o_.check_every == 0)
            check_invariants();
        if (o_.on_progress && rep_.insertions % 1000 == 0)
            o_.on_progress({rep_.insertions, queue_.size(), rep_.probes + device_.counters().probes});
        if (o_.on_snapshot && o_.snapshot_every != 0 && rep_.insertions % o_.snapshot_every == 0) {
            TriangleSoup mesh;
            std::vector<std::vector<std::uint32_t>> polygons;
            output(mesh, polygons, false);
            auto path = device_.take_recorded_paths();
            o_.on_snapshot({rep_.insertions, &mesh, &polygons, &path, false});
            full_path_.insert(full_path_.end(), std::make_move_iterator(path.begin()),
                              std::make_move_iterator(path.end()));
        }
    }

    // ---- the device: where it is and how it gets elsewhere (spec §3.3, §3.5) -------------------
    /// Positioning and detection moves are counted as Voronoi edge pieces by the refiner; their
    /// lengths by the device. The device is at the in-Ω node at_node_, or outside Ω.
    void climb_out() {
        if (at_node_ == kNoNode) return;
        climb_to(nodes_[nodes_[at_node_].top].prev);
        at_node_ = kNoNode;
    }
    /// Travel outside Ω to p (on or outside ∂Ω).
    void exterior_to(const Point3& p) {
        climb_out();
        if (!(device_.position() == p)) device_.move_exterior(p);
    }
    /// Positioning: brings the device to the in-Ω active node u: through the lowest common
    /// ancestor when the device sits on a node of u's path tree (ProbingPositioning::Lca), via
    /// ∂Ω otherwise.
    void go_to_node(std::uint32_t u) {
        if (at_node_ == u) return;
        const Node& n = nodes_[u];
        std::uint32_t l = nodes_[n.top].prev;  // the root above u's tree: via ∂Ω
        if (o_.positioning == ProbingPositioning::Lca && at_node_ != kNoNode && nodes_[at_node_].top == n.top) {
            l = lowest_common_ancestor(nodes_, at_node_, u);
            climb_to(l);
        } else {
            exterior_to(nodes_[n.top].entry);
        }
        descend_from(l, u);
    }
    /// Up the device's path tree from at_node_ to its ancestor l (the root above the tree: out to
    /// the top's entry on ∂Ω). Roots have depth and path length 0.
    void climb_to(std::uint32_t l) {
        const Node& a = nodes_[at_node_];
        const Node& L = nodes_[l];
        rep_.positioning_edges += a.depth - L.depth;
        if (walk_) {
            for (std::uint32_t x = at_node_; x != l; x = nodes_[x].prev) device_.move_to(nodes_[x].entry);
        } else {
            device_.retrace(L.root() ? nodes_[a.top].entry : L.pos, a.depth - L.depth,
                            std::max(0.0, a.path_len - L.path_len));
        }
    }
    /// Down u's path tree from its ancestor l (where the device is) to u.
    void descend_from(std::uint32_t l, std::uint32_t u) {
        const Node& n = nodes_[u];
        const Node& L = nodes_[l];
        rep_.positioning_edges += n.depth - L.depth;
        if (walk_) {
            chain_.clear();
            for (std::uint32_t x = u; x != l; x = nodes_[x].prev) chain_.push_back(x);
            for (auto it = chain_.rbegin(); it != chain_.rend(); ++it) device_.move_to(nodes_[*it].pos);
        } else {
            device_.retrace(n.pos, n.depth - L.depth, std::max(0.0, n.path_len - L.path_len));
        }
        at_node_ = u;
    }
    /// A cast from s (the device is there, or anywhere in omniscient mode).
    std::optional<ProbeHit> cast_from(const Point3& s, const Vec3& d, double t_max) {
        std::optional<ProbeHit> h;
        if (omniscient_) {
            ++rep_.probes;
            h = oracle_.cast(s, d, t_max);
        } else {
            if (!(device_.position() == s))
                throw InternalError("probe: a cast from " + format_point(s) + " while the device is at " +
                                    format_point(device_.position()));
            h = device_.cast(d, t_max);
        }
        if (h && h->grazing) ++rep_.grazing_hits;
        if (h && distance(h->x, C_) > R_ * (1 - 1e-6))
            throw InvalidInput("probe: the object reaches the margin of Omega at " + format_point(h->x) +
                               ": Omega must contain it with a margin");
        return h;
    }
    [[nodiscard]] std::size_t probes_so_far() const { return rep_.probes + device_.counters().probes; }

    // ---- nodes --------------------------------------------------------------------------------
    Info& info(std::uint32_t node) { return Tri::info(cells_[node]); }

    std::uint32_t new_node(Cell c) {
        std::uint32_t id;
        if (!free_ids_.empty()) {
            id = free_ids_.back();
            free_ids_.pop_back();
        } else {
            id = static_cast<std::uint32_t>(nodes_.size());
            nodes_.emplace_back();
            cells_.emplace_back();
        }
        Node n;
        n.infinite = tri_.is_infinite(c);
        if (!n.infinite) {
            n.pos = Tri::circumcenter(c);
            n.in_omega = distance(n.pos, C_) < R_;
        }
        if (n.root()) {
            n.active = true;
            n.prev = id;
        }
        nodes_[id] = n;
        cells_[id] = c;
        Tri::info(c) = Info{};
        Tri::info(c).node = id;
        ++rep_.cells_created;
        return id;
    }
    /// A simplex dies: an active node is retained (paths may use it), an inactive one freed.
    void retire(Cell c) {
        const std::uint32_t id = Tri::info(c).node;
        Node& n = nodes_[id];
        n.alive = false;
        cells_[id] = Cell{};
        if (n.active) {
            ++rep_.nodes_retained;
        } else {
            free_ids_.push_back(id);
        }
    }

    // ---- the Voronoi edge of a facet (spec §3.3, §10 "far roots") -----------------------------
    /// The line of the Voronoi edge dual to facet (c, i), oriented from c's end toward the
    /// neighbour's: points O + t·D for t in [lo, hi], clipped to Ω: [clo, chi] (empty when
    /// clo ≥ chi).
    struct EdgeLine {
        Point3 O{};
        Vec3 D{};
        double lo = 0, hi = 0;
        double clo = 0, chi = -1;
        bool touches = false;  ///< the edge meets Ω (possibly in one point)
        [[nodiscard]] bool meets_omega() const { return touches; }
        [[nodiscard]] Point3 start() const { return O + clo * D; }
        [[nodiscard]] Point3 end() const { return O + chi * D; }
    };
    EdgeLine edge_line(Cell c, int i) const {
        const Cell w = Tri::neighbor(c, i);
        const Node& nu = nodes_[Tri::info(c).node];
        const Node& nw = nodes_[Tri::info(w).node];
        EdgeLine L;
        // The edge lies on the line through the facet's circumcentre along its normal, in the
        // direction the exact predicates give. Circumcentres of nearly flat cells far outside
        // Ω carry large absolute errors, so the line is anchored at an end inside Ω, or else
        // at the facet's circumcentre; the ends are the projections of the nodes (±infinity
        // for an infinite one).
        L.D = tri_.edge_direction(c, i);
        if (nu.in_omega) {
            L.O = nu.pos;
        } else if (nw.in_omega) {
            L.O = nw.pos;
        } else {
            L.O = Tri::facet_circumcenter(Tri::facet_points(c, i));
        }
        constexpr double inf = std::numeric_limits<double>::infinity();
        L.lo = nu.infinite ? -inf : nu.in_omega ? 0.0 : dot(nu.pos - L.O, L.D);
        L.hi = nw.infinite ? inf : (nw.in_omega && !nu.in_omega) ? 0.0 : dot(nw.pos - L.O, L.D);
        const double m = dot(C_ - L.O, L.D);
        const Vec3 off = L.O + m * L.D - C_;
        const double h2 = R_ * R_ - dot(off, off);
        if (h2 > 0) {
            // An end inside Ω is its own clip point. The edge from a root (outside Ω) enters Ω
            // where the line does, unless the root lies beyond the chord (then the edge misses
            // Ω); a root whose rounded position projects inside the chord still clips there.
            const double entry = m - std::sqrt(h2), exit = m + std::sqrt(h2);
            L.clo = nu.in_omega || L.lo >= exit ? L.lo : entry;
            L.chi = nw.in_omega || L.hi <= entry ? L.hi : exit;
        } else if (nu.in_omega || nw.in_omega) {  // rounding: the line grazes ∂Ω at the anchor
            L.clo = L.chi = 0;
        }
        // An edge with an end inside Ω meets Ω even when its rounded length is zero or slightly
        // negative (cospherical samples): a zero-length edge, never "outside Omega". A clearly
        // negative length would mean positions and the exact direction disagree: the device
        // must not walk such an edge.
        if (nu.in_omega || nw.in_omega) {
            if (L.chi < L.clo - 1e-9 * R_)
                throw InternalError("probe: the Voronoi edge from " + format_point(nu.pos) + " to " +
                                    format_point(nw.pos) + " runs against its exact direction " + format_point(L.D));
            L.touches = true;
            L.chi = std::max(L.chi, L.clo);
        } else {
            L.touches = L.clo < L.chi;
        }
        return L;
    }

    std::uint64_t next_stamp() { return ++stamp_; }

    // ---- probing one directed edge (spec §4.1) ------------------------------------------------
    /// Probes the directed edge (c, i) unless its record is known or can be inferred from the
    /// other end's record; returns the record. A root's probe starts at the edge's clip point,
    /// reached by exterior travel.
    const Record& probe_edge(Cell c, int i) {
        Record& r = Tri::info(c).rec[i];
        if (r.state != Record::Unprobed) return r;
        const EdgeLine L = edge_line(c, i);
        r.stamp = next_stamp();
        r.d = L.D;
        r.s = L.meets_omega() ? L.start() : L.O;
        if (!L.meets_omega()) {
            r.state = Record::OutsideOmega;
            return r;
        }
        // The other end's record is about the same edge (records of live simplices always
        // describe their current edge): a free edge is free both ways.
        const Cell w = Tri::neighbor(c, i);
        const Record& back = Tri::info(w).rec[Tri::index(w, c)];
        if (back.state == Record::Miss || back.state == Record::OutsideOmega) {
            r.state = back.state;
            ++rep_.probes_inferred;
            return r;
        }
        const double len = L.chi - L.clo;
        if (len <= tau_) {  // a zero-length edge (cospherical samples): nothing to cross
            r.state = Record::Miss;
            return r;
        }
        if (nodes_[Tri::info(c).node].root()) exterior_to(r.s);
        const auto hit = cast_from(r.s, r.d, len);
        if (!hit) {
            r.state = Record::Miss;
            return r;
        }
        r.state = Record::Hit;
        r.x = hit->x;
        r.t = hit->t;
        push_ball(c, i, r);
        return r;
    }

    /// Omniscient mode: the edge (c, i) tested from whichever end is outside O (from a free
    /// point inside it when neither is); the record is kept on c's side.
    void test_edge(Cell c, int i) {
        Record& r = Tri::info(c).rec[i];
        const EdgeLine L = edge_line(c, i);
        r.stamp = next_stamp();
        r.d = L.D;
        r.s = L.meets_omega() ? L.start() : L.O;
        r.state = Record::Miss;
        if (!L.meets_omega()) {
            r.state = Record::OutsideOmega;
            return;
        }
        const double len = L.chi - L.clo;
        if (len <= tau_) return;
        std::optional<ProbeHit> hit;
        if (o_.ground_truth->is_free(L.start())) {
            hit = cast_from(L.start(), L.D, len);
        } else if (o_.ground_truth->is_free(L.end())) {
            r.s = L.end();
            r.d = -L.D;
            hit = cast_from(r.s, r.d, len);
        } else if (const auto t = o_.ground_truth->free_point_on(L.start(), L.end())) {
            // Both ends inside O, yet the edge leaves it (it joins two components, say): cast
            // both ways from a free point of it.
            r.s = L.start() + *t * L.D;
            hit = cast_from(r.s, L.D, std::max(0.0, len - *t));
            if (!hit) {
                r.d = -L.D;
                hit = cast_from(r.s, r.d, *t);
            }
        }
        if (!hit) return;
        r.state = Record::Hit;
        r.x = hit->x;
        r.t = hit->t;
        push_ball(c, i, r);
    }

    /// Is the ball at x through facet (c, i) free of samples? x lies on the facet's dual line
    /// only up to the rounding of node positions, so its distances to the facet's vertices
    /// differ slightly: a sample closer than the nearest of them is inside; one between the
    /// nearest and the farthest lies on the sphere up to that rounding and does not count.
    bool ball_is_empty(Cell c, int i, const Point3& x) const {
        double nearest_vertex = std::numeric_limits<double>::infinity();
        for (const Point3& p : Tri::facet_points(c, i)) nearest_vertex = std::min(nearest_vertex, distance(p, x));
        return tri_.nearest_sample_distance(x, c) >= nearest_vertex * (1 - 1e-9);
    }
    double ball_radius(Cell c, int i, const Point3& x) const {
        double r = 0;
        for (const Point3& p : Tri::facet_points(c, i)) r = std::max(r, distance(p, x));
        return r;
    }
    void push_ball(Cell c, int i, const Record& r) {
        const double rad = ball_radius(c, i, r.x);
        if (rad > eps_) {
            queue_.push({rad * rad, Tri::info(c).node, i, r.stamp, seq_++});
            ++rep_.queue_pushes;
        }
    }

    // ---- detect_access (spec §4.2, §10.2) -----------------------------------------------------
    void detect_access(std::uint32_t s) {
        ++rep_.detect_access_calls;
        stack_.clear();
        stack_.push_back({s, 0});
        while (!stack_.empty()) {
            Frame& f = stack_.back();
            if (f.i == kFacets) {
                const std::uint32_t u = f.node;
                stack_.pop_back();
                if (u != s) {  // back along the edge it came by
                    const Node& n = nodes_[u];
                    ++rep_.detection_edges;
                    device_.move_to(n.entry);
                    at_node_ = nodes_[n.prev].root() ? kNoNode : n.prev;
                }
                continue;
            }
            const int i = f.i++;
            const std::uint32_t u = f.node;
            const Cell c = cells_[u];
            const Cell wc = Tri::neighbor(c, i);
            const std::uint32_t w = Tri::info(wc).node;
            if (nodes_[u].infinite && nodes_[w].infinite) continue;
            const Record& r = probe_edge(c, i);
            if (r.state != Record::Miss || nodes_[w].active) continue;
            // w is in Ω: walk to it along the certified edge (from its clip point for a root).
            const Node& pu = nodes_[u];
            if (pu.root()) exterior_to(r.s);
            Node& n = nodes_[w];
            n.active = true;
            n.prev = u;
            n.entry = r.s;
            n.depth = pu.root() ? 1 : pu.depth + 1;
            n.top = pu.root() ? w : pu.top;
            n.jump = pu.root() ? w : skew_jump(nodes_, u);
            n.path_len = (pu.root() ? 0 : pu.path_len) + distance(n.pos, r.s);
            ++rep_.activations;
            ++rep_.detection_edges;
            device_.move_to(n.pos);
            at_node_ = w;
            stack_.push_back({w, 0});
        }
    }

    // ---- initialisation (spec §4.3, §8.3, §10.4, §10.10) -------------------------------------
    struct Seed {
        std::vector<Point3> points;       ///< the bootstrap simplex (kDim hits)
        std::optional<ProbeHit> x_near;   ///< the dual line's hit on the device's side
        std::optional<ProbeHit> x_far;    ///< and on the other side
        double small_radius = 0;          ///< |x_near − a| when x_near exists
        int attempt = 0;                  ///< the direction it came from (see seed_component)
    };

    /// Directions on the unit sphere (2D: circle in z = 0), spread by the golden angle.
    Vec3 fibonacci_direction(int k, int n) const {
        const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
        if (kDim == 2) {
            const double a = golden * k;
            return {std::cos(a), std::sin(a), 0};
        }
        const double z = 1 - (2 * k + 1.0) / n;
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        return {r * std::cos(golden * k), r * std::sin(golden * k), z};
    }

    /// Steps 1–3 of spec §4.3 for the interior point o, starting from direction attempt
    /// `first` (0: toward o from the point of ∂Ω nearest it; k > 0: the k-th of 64 Fibonacci
    /// directions). Returns nothing when every attempt failed the shape test.
    std::optional<Seed> seed_component(const Point3& o, int first) {
        for (int attempt = first; attempt <= 64; ++attempt) {
            Vec3 u0;
            if (attempt == 0) {
                u0 = o - C_;
                if (kDim == 2) u0.z = 0;
                const double dist = norm(u0);
                u0 = dist > 1e-9 * R_ ? u0 / dist : Vec3{1, 0, 0};
            } else {
                u0 = fibonacci_direction(attempt - 1, 64);
            }
            const Point3 p = C_ + R_ * u0;
            travel_outside(p);
            const Vec3 d = (o - p) / norm(o - p);
            const auto a = cast_from(p, d, norm(o - p));
            // o is inside O only if neither ray from ∂Ω along this line reaches it freely.
            const Point3 p2 = o + (dot(C_ - o, d) + std::sqrt(std::max(0.0, R_ * R_ - sqdistance(C_, o) +
                                                                          dot(C_ - o, d) * dot(C_ - o, d)))) * d;
            std::optional<ProbeHit> back;
            if (a) {
                travel_outside(p2);
                back = cast_from(p2, -d, distance(p2, o));
            }
            if (!a || !back)
                throw InvalidInput("probe: the interior point " + format_point(o) +
                                   " is not inside the object (a ray from the boundary of Omega reaches it "
                                   "without crossing the surface)");
            travel_outside(p);
            Vec3 e1 = kDim == 2 ? Vec3{-d.y, d.x, 0}
                                : (std::fabs(d.x) < 0.9 ? cross(d, Vec3{1, 0, 0}) : cross(d, Vec3{0, 1, 0}));
            e1 = normalized(e1);
            const Vec3 e2 = cross(d, e1);
            // b and c 60° apart around a: at normal incidence abc is equilateral with side
            // θ·t = 0.4ε (circumradius 0.23ε ≤ ε/4), as large as the test allows, so that the
            // triangles the refinement builds next to it keep reasonable angles.
            double theta = 0.4 * eps_ / std::max(a->t, tau_);
            for (int k = 0; k < 30; ++k, theta /= 2) {
                Seed seed;
                seed.attempt = attempt;
                seed.points.push_back(a->x);
                const auto b = cast_from(p, normalized(d + theta * e1), 2 * R_);
                if (!b) continue;
                seed.points.push_back(b->x);
                if (kDim == 3) {
                    const auto c = cast_from(p, normalized(d + theta * (0.5 * e1 + 0.8660254037844386 * e2)), 2 * R_);
                    if (!c) continue;
                    seed.points.push_back(c->x);
                }
                if (!well_shaped(seed.points)) continue;
                // The dual line of the bootstrap simplex, clipped by Ω, probed from both ends.
                Point3 cc;
                Vec3 n;
                if constexpr (kDim == 3) {
                    const std::array<Point3, 3> f{seed.points[0], seed.points[1], seed.points[2]};
                    cc = Tri::facet_circumcenter(f);
                    n = Tri::facet_normal(f);
                } else {
                    const std::array<Point3, 2> f{seed.points[0], seed.points[1]};
                    cc = Tri::facet_circumcenter(f);
                    n = Tri::facet_normal(f);
                }
                if (dot(n, d) < 0) n = -n;  // from the device's side toward the far side
                const double m = dot(C_ - cc, n);
                const Vec3 off = cc + m * n - C_;
                const double h = std::sqrt(std::max(0.0, R_ * R_ - dot(off, off)));
                const Point3 q1 = cc + (m - h) * n, q2 = cc + (m + h) * n;
                travel_outside(q1);
                seed.x_near = cast_from(q1, n, 2 * h);
                travel_outside(q2);
                seed.x_far = cast_from(q2, -n, 2 * h);
                travel_outside(p);
                if (!seed.x_near) continue;
                seed.small_radius = distance(seed.x_near->x, a->x);
                if (seed.small_radius > eps_ / 3) continue;  // not the persistent facet: shrink θ
                return seed;
            }
        }
        return std::nullopt;
    }
    /// Exterior travel in device mode (placing the device first); nothing in omniscient mode.
    void travel_outside(const Point3& p) {
        if (omniscient_) return;
        if (!device_.placed()) {
            device_.place(p);
        } else {
            exterior_to(p);
        }
    }
    /// The bootstrap test: circumradius ≤ ε/4 and no angle below 15° (2D: length ≤ ε/2).
    bool well_shaped(const std::vector<Point3>& p) const {
        if (kDim == 2) {
            const double l = distance(p[0], p[1]);
            return l > 0 && l <= eps_ / 2;
        }
        const double ab = distance(p[0], p[1]), bc = distance(p[1], p[2]), ca = distance(p[2], p[0]);
        const double area2 = norm(cross(p[1] - p[0], p[2] - p[0]));
        if (!(area2 > 0)) return false;
        if (ab * bc * ca / (2 * area2) > eps_ / 4) return false;
        const double sin_min = area2 / std::max({ab * ca, ab * bc, bc * ca});
        return sin_min >= std::sin(15 * std::numbers::pi / 180);
    }

    void bootstrap() {
        std::vector<Seed> seeds;
        for (const Point3& o : o_.interior_points) {
            auto seed = seed_component(o, 0);
            if (!seed)
                throw InvalidInput("probe: no well-shaped bootstrap triangle near the interior point " +
                                   format_point(o) + " from 64 directions");
            // A seed whose small ball holds points of another seed repeats that component.
            // (closed ball, with room for rounding: a seed found again along the same ray has its
            // points on the other seed's small sphere)
            bool repeat = false;
            for (const Seed& s : seeds)
                for (const Point3& q : s.points)
                    if (distance(q, seed->x_near->x) <= seed->small_radius * (1 + 1e-6)) repeat = true;
            if (!repeat) seeds.push_back(std::move(*seed));
        }
        rep_.probes_bootstrap = probes_so_far();
        for (const Seed& s : seeds)
            for (const Point3& q : s.points) add_sample(q);
        if (tri_.dimension() < kDim) {
            // One component: the largest ball of the dual line is the next sample (spec §4.3
            // step 4); it lies where the line leaves O on the far side.
            const Seed& s = seeds.front();
            std::optional<ProbeHit> best;
            for (const auto& x : {s.x_near, s.x_far})
                if (x && (!best || distance(x->x, s.points[0]) > distance(best->x, s.points[0]))) best = x;
            if (!best || distance(best->x, s.points[0]) <= eps_)
                throw InvalidInput("probe: eps is larger than the object (no ball of the first "
                                   "triangle exceeds it)");
            add_sample(best->x);
        }
        if (tri_.dimension() != kDim)
            throw InternalError("probe: the bootstrap samples do not span the space");
        rep_.bootstrap_samples = sample_.size();
        build_state();
    }

    /// A bootstrap sample; one within 1e-9 R_Ω of an earlier one is the same point (spec §8.2's
    /// guard) and is not inserted again.
    void add_sample(const Point3& q) {
        for (const Point3& p : sample_)
            if (distance(p, q) <= 1e-9 * R_) return;
        tri_.insert(q, static_cast<std::uint32_t>(sample_.size()));
        sample_.push_back(q);
    }

    /// Every simplex is new (spec §4.3 step 4): nodes for all, every edge counted, and
    /// detect_access from every root (omniscient: every edge tested).
    void build_state() {
        const std::vector<Cell> cells = tri_.all_cells();
        std::vector<std::uint32_t> ids;
        for (Cell c : cells) ids.push_back(new_node(c));
        for (Cell c : cells)
            for (int i = 0; i < kFacets; ++i) {
                const Cell w = Tri::neighbor(c, i);
                if (Tri::info(w).node < Tri::info(c).node) continue;
                if (nodes_[Tri::info(c).node].infinite && nodes_[Tri::info(w).node].infinite) continue;
                ++rep_.voronoi_edges_created;
                if (omniscient_) test_edge(c, i);
            }
        if (!omniscient_)
            for (std::uint32_t id : ids)
                if (nodes_[id].root()) detect_access(id);
    }

    // ---- several components (spec §8.3) -------------------------------------------------------
    /// After the queue emptied: every interior point must be enclosed by a component of the
    /// output. For one that is not, bootstrap its component again from the next Fibonacci
    /// directions, keep a seed whose points are more than 2ε from every sample, insert it and
    /// return the number of seeds inserted (0: nothing to do).
    std::size_t reinitialise_missing_components() {
        TriangleSoup mesh;
        std::vector<std::vector<std::uint32_t>> polygons;
        output(mesh, polygons, false);
        std::size_t inserted = 0;
        for (std::size_t k = 0; k < o_.interior_points.size(); ++k) {
            const Point3& o = o_.interior_points[k];
            if (encloses_point(mesh, polygons, o)) continue;
            while (next_direction_.size() <= k) next_direction_.push_back(1);
            const std::size_t probes0 = probes_so_far();
            while (next_direction_[k] <= 64) {
                const auto seed = seed_component(o, next_direction_[k]);
                if (!seed) {
                    next_direction_[k] = 65;
                    break;
                }
                next_direction_[k] = seed->attempt + 1;
                bool far = true;
                for (const Point3& q : seed->points) far = far && nearest_sample(q) > 2 * eps_;
                if (!far) continue;
                for (const Point3& q : seed->points) insert(q, cells_[any_alive_node()], -1);
                ++rep_.reinitialisations;
                ++inserted;
                break;
            }
            rep_.probes_bootstrap += probes_so_far() - probes0;
        }
        return inserted;
    }
    std::uint32_t any_alive_node() const {
        for (std::uint32_t id = static_cast<std::uint32_t>(nodes_.size()); id-- > 0;)
            if (nodes_[id].alive && !nodes_[id].infinite) return id;
        throw InternalError("probe: no live simplex");
    }
    double nearest_sample(const Point3& q) const {
        double best = std::numeric_limits<double>::infinity();
        for (const Point3& p : sample_) best = std::min(best, distance(p, q));
        return best;
    }

    /// The output's components (by shared vertices) and whether one of them encloses o.
    bool encloses_point(const TriangleSoup& mesh, const std::vector<std::vector<std::uint32_t>>& polygons,
                        const Point3& o) const {
        if (kDim == 2) {
            for (const auto& loop : polygons)
                if (polygon_encloses(mesh, loop, o)) return true;
            return false;
        }
        for (const auto& faces : components_of(mesh))
            if (surface_encloses(mesh, faces, o)) return true;
        return false;
    }
    static std::vector<std::vector<std::size_t>> components_of(const TriangleSoup& mesh) {
        std::vector<std::uint32_t> parent(mesh.points.size());
        for (std::uint32_t v = 0; v < parent.size(); ++v) parent[v] = v;
        const auto find = [&](std::uint32_t v) {
            while (parent[v] != v) v = parent[v] = parent[parent[v]];
            return v;
        };
        for (const auto& t : mesh.triangles) {
            parent[find(t[1])] = find(t[0]);
            parent[find(t[2])] = find(t[0]);
        }
        std::vector<std::vector<std::size_t>> comps;
        std::vector<std::int64_t> slot(mesh.points.size(), -1);
        for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
            const std::uint32_t r = find(mesh.triangles[f][0]);
            if (slot[r] < 0) {
                slot[r] = static_cast<std::int64_t>(comps.size());
                comps.emplace_back();
            }
            comps[static_cast<std::size_t>(slot[r])].push_back(f);
        }
        return comps;
    }
    void check_enclosure(const TriangleSoup& mesh, const std::vector<std::vector<std::uint32_t>>& polygons) {
        rep_.components = kDim == 2 ? polygons.size() : components_of(mesh).size();
        for (const Point3& o : o_.interior_points)
            if (!encloses_point(mesh, polygons, o))
                problems_.push_back("the interior point " + format_point(o) +
                                    " is not enclosed by the output (its component was not found)");
    }

    // ---- the update after an insertion (spec §4.4, §10.1, §10.6) ------------------------------
    void insert(const Point3& x, Cell c, int i) {
        tri_.insert_in_cavity(x, static_cast<std::uint32_t>(sample_.size()), c, i,
                              [this](Cell k) { retire(k); }, fresh_);
        sample_.push_back(x);
        fresh_ids_.clear();
        for (Cell n : fresh_) fresh_ids_.push_back(new_node(n));
        // Edges created: the facets through x (shared by two new simplices) and the cavity's
        // boundary facets.
        for (Cell n : fresh_) {
            const std::uint32_t id = Tri::info(n).node;
            for (int j = 0; j < kFacets; ++j) {
                const Cell w = Tri::neighbor(n, j);
                const std::uint32_t wid = Tri::info(w).node;
                if (nodes_[id].infinite && nodes_[wid].infinite) continue;
                const bool w_fresh = j != tri_.fresh_index(n);
                if (w_fresh && wid < id) continue;
                ++rep_.voronoi_edges_created;
                if (omniscient_) {
                    if (!w_fresh) {  // the old side's record described the old edge
                        Record& old = Tri::info(w).rec[Tri::index(w, n)];
                        old = Record{};
                        old.stamp = next_stamp();
                    }
                    test_edge(n, j);
                }
            }
        }
        if (omniscient_) return;
        // The records along the cavity's boundary (spec §4.4, §10.1). The new node n replaces
        // the dead end of the old edge from k_out; the new edge is the old one cut at n, a
        // prefix from k_out's side (exact arithmetic; positions are not needed to know it).
        // A hit stays on the new edge iff its ball is still empty, i.e. x is not inside it:
        // |hit − x| against the ball's radius, without the rounded position of n.
        candidates_.clear();
        for (Cell n : fresh_) {
            if (tri_.is_infinite(n)) continue;  // its old neighbour is infinite too
            const Cell k_out = Tri::neighbor(n, tri_.fresh_index(n));
            const int j = Tri::index(k_out, n);
            Record& r = Tri::info(k_out).rec[j];
            const bool n_in_omega = nodes_[Tri::info(n).node].in_omega;
            switch (r.state) {
                case Record::Unprobed:
                case Record::OutsideOmega:  // a prefix of an edge missing Ω misses it too
                    break;
                case Record::Miss:  // a prefix of a free edge is free
                    r.stamp = next_stamp();
                    if (n_in_omega) candidates_.emplace_back(k_out, j);
                    break;
                case Record::Hit: {
                    // The hit lies on the dual line up to rounding: its distances to the facet's
                    // vertices span [near, far]; x strictly outside or inside that band decides.
                    double near = std::numeric_limits<double>::infinity(), far = 0;
                    for (const Point3& p : Tri::facet_points(k_out, j)) {
                        near = std::min(near, distance(p, r.x));
                        far = std::max(far, distance(p, r.x));
                    }
                    const double dx = distance(r.x, x);
                    if (dx > far * (1 + 1e-9)) break;  // same ball, same stamp: still on the edge
                    r.stamp = next_stamp();
                    if (dx < near * (1 - 1e-9)) {
                        // The new edge ends before the hit: inside the free part [s, x).
                        r.state = Record::Miss;
                        if (n_in_omega) candidates_.emplace_back(k_out, j);
                    } else {  // too close to call: probe the new edge again
                        r.state = Record::Unprobed;
                        candidates_.emplace_back(k_out, j);
                    }
                    break;
                }
            }
        }
        for (std::uint32_t id : fresh_ids_)
            if (nodes_[id].root()) detect_access(id);
        for (const auto& [k_out, j] : candidates_) {
            const std::uint32_t u = Tri::info(k_out).node;
            const std::uint32_t w = Tri::info(Tri::neighbor(k_out, j)).node;
            if (!nodes_[u].active) continue;
            if (nodes_[w].active && Tri::info(k_out).rec[j].state != Record::Unprobed) continue;
            if (!nodes_[u].root()) go_to_node(u);
            detect_access(u);
        }
    }

    // ---- output (spec §4.5, §10.7) ------------------------------------------------------------
    /// The facets (2D: edges) with a hit record, each oriented so that its normal points
    /// against the probe that found it, with the samples they use numbered in sample order.
    /// 3D: triangles rotated to start at their smallest index and sorted, so that the same run
    /// gives the same bytes. 2D: the edges chained into closed polygons.
    void output(TriangleSoup& soup, std::vector<std::vector<std::uint32_t>>& polygons, bool final_run = true) {
        std::vector<std::array<std::uint32_t, kDim>> simplices;
        tri_.for_each_finite_facet([&](Cell c, int i) {
            const Cell w = Tri::neighbor(c, i);
            const Record& r1 = Tri::info(c).rec[i];
            const Record& r2 = Tri::info(w).rec[Tri::index(w, c)];
            const Record* r = r1.state == Record::Hit ? &r1 : r2.state == Record::Hit ? &r2 : nullptr;
            if (r == nullptr) return;
            if (final_run && r2.state == Record::Hit)  // both ends hit: both balls count
                rep_.max_ball_radius = std::max(rep_.max_ball_radius, ball_radius(w, Tri::index(w, c), r2.x));
            // The outward normal opposes the probe, which enters O at the hit. In 3D it is
            // facet_normal; in 2D (counter-clockwise loops) the right-hand normal, −facet_normal.
            auto t = Tri::facet_samples(c, i);
            const double side = dot(Tri::facet_normal(Tri::facet_points(c, i)), r->d);
            if (kDim == 3 ? side > 0 : side < 0) std::swap(t[0], t[1]);
            if (final_run) rep_.max_ball_radius = std::max(rep_.max_ball_radius, ball_radius(c, i, r->x));
            if constexpr (kDim == 3) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
            simplices.push_back(t);
        });
        std::sort(simplices.begin(), simplices.end());
        std::vector<std::uint32_t> index(sample_.size(), kNoNode);
        for (const auto& t : simplices)
            for (std::uint32_t v : t) index[v] = 0;
        soup.points.clear();
        soup.triangles.clear();
        polygons.clear();
        for (std::uint32_t v = 0; v < sample_.size(); ++v)
            if (index[v] == 0) {
                index[v] = static_cast<std::uint32_t>(soup.points.size());
                soup.points.push_back(sample_[v]);
            }
        if constexpr (kDim == 3) {
            for (const auto& t : simplices) soup.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
        } else {
            chain_polygons(simplices, index, soup.points.size(), polygons, final_run);
        }
    }
    /// 2D: directed edges a → b (O on the left) chained into closed loops, each starting at
    /// its smallest vertex; loops in order of that vertex. A vertex without exactly one edge
    /// in and one out ends its chain (reported by the checks).
    void chain_polygons(const std::vector<std::array<std::uint32_t, kDim>>& edges,
                        const std::vector<std::uint32_t>& index, std::size_t n,
                        std::vector<std::vector<std::uint32_t>>& polygons, bool final_run) {
        std::vector<std::uint32_t> next(n, kNoNode);
        std::vector<int> in(n, 0), out(n, 0);
        for (const auto& e : edges) {
            const std::uint32_t a = index[e[0]], b = index[e[1]];
            next[a] = b;
            ++out[a];
            ++in[b];
        }
        std::vector<char> seen(n, 0);
        for (std::uint32_t v = 0; v < n; ++v) {
            if (seen[v] || out[v] == 0) continue;
            std::vector<std::uint32_t> loop{v};
            seen[v] = 1;
            std::uint32_t u = next[v];
            while (u != kNoNode && !seen[u]) {
                loop.push_back(u);
                seen[u] = 1;
                u = next[u];
            }
            if (u == v) loop.push_back(v);  // closed
            polygons.push_back(std::move(loop));
        }
        for (std::uint32_t v = 0; final_run && v < n; ++v)  // snapshots show unfinished loops
            if ((in[v] != 1 || out[v] != 1) && problems_.size() < 20)
                problems_.push_back("the output vertex " + std::to_string(v) + " has " + std::to_string(in[v]) +
                                    " incoming and " + std::to_string(out[v]) + " outgoing edges");
    }
    static std::size_t count_polygon_edges(const std::vector<std::vector<std::uint32_t>>& polygons) {
        std::size_t n = 0;
        for (const auto& p : polygons) n += p.size() - 1;
        return n;
    }

    // ---- invariants (spec §5.2, §10 "debug invariant") ----------------------------------------
    void check_invariants() {
        const std::string when = "after insertion " + std::to_string(rep_.insertions) + ": ";
        auto fail = [&](const std::string& what) {
            if (problems_.size() < 20) problems_.push_back(when + what);
        };
        if (!omniscient_) {
            for (std::uint32_t id = 0; id < nodes_.size(); ++id) {
                const Node& n = nodes_[id];
                if (!n.active || n.root()) continue;
                // P1 by induction on the depth: the chain's previous node is active, one step
                // nearer ∂Ω, and its end is where this node's certified segment starts.
                const bool ok = n.prev != kNoNode && n.prev < nodes_.size() && nodes_[n.prev].active &&
                                (nodes_[n.prev].root()
                                     ? n.depth == 1 && n.top == id
                                     : n.depth == nodes_[n.prev].depth + 1 && n.top == nodes_[n.prev].top &&
                                           n.entry == nodes_[n.prev].pos);
                if (!ok) fail("P1: node " + std::to_string(id) + " has no active chain to outside Omega");
                if (o_.ground_truth != nullptr && !n.verified) {  // frozen: checked once
                    if (!o_.ground_truth->segment_is_free(n.entry, n.pos))
                        fail("P1: the certified segment of node " + std::to_string(id) + " crosses the object");
                    nodes_[id].verified = true;
                }
            }
        }
        for (std::uint32_t id = 0; id < nodes_.size(); ++id) {
            if (!nodes_[id].alive) continue;
            const Cell c = cells_[id];
            const Node& u = nodes_[id];
            for (int i = 0; i < kFacets; ++i) {
                const Cell wc = Tri::neighbor(c, i);
                const Node& w = nodes_[Tri::info(wc).node];
                if (u.infinite && w.infinite) continue;
                const Record& r = Tri::info(c).rec[i];
                if (!omniscient_ && u.active && r.state == Record::Unprobed)
                    fail("an edge of active node " + std::to_string(id) + " has no record");
                if (r.state == Record::OutsideOmega && (u.in_omega || w.in_omega))
                    fail("an edge of node " + std::to_string(id) + " with an end inside Omega is recorded outside it");
                // P2 (local): an edge known to be free joins nodes of the same status.
                if (!omniscient_ && r.state == Record::Miss && u.active && !w.active)
                    fail("P2: a free edge joins active node " + std::to_string(id) + " and inactive node " +
                         std::to_string(Tri::info(wc).node));
                if (r.state == Record::Hit) {
                    if (!ball_is_empty(c, i, r.x))
                        fail("the ball at a hit of node " + std::to_string(id) + " holds a sample");
                }
            }
        }
    }

    const Oracle& oracle_;
    const ProbingOptions& o_;
    Point3 C_;
    double R_;
    double eps_;
    double tau_;
    bool omniscient_;
    bool walk_;  ///< walk positioning chains segment by segment (monitor or recording)
    ProbingDevice device_;
    Tri tri_;
    std::vector<Node> nodes_;
    std::vector<Cell> cells_;  ///< per node: its simplex while alive
    std::vector<std::uint32_t> free_ids_;
    std::vector<Point3> sample_;
    std::priority_queue<BallEntry> queue_;
    std::uint64_t stamp_ = 0, seq_ = 0;
    std::uint32_t at_node_ = kNoNode;
    ProbingReport rep_;
    std::vector<std::string> problems_;
    std::vector<std::vector<Point3>> full_path_;
    std::vector<int> next_direction_;
    // scratch
    std::vector<Cell> fresh_;
    std::vector<std::uint32_t> fresh_ids_;
    std::vector<std::pair<Cell, int>> candidates_;
    std::vector<std::uint32_t> chain_;
    struct Frame {
        std::uint32_t node;
        int i;
    };
    std::vector<Frame> stack_;
};

}  // namespace dynmesh::detail
