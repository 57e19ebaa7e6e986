#include "dynmesh/probing/refine.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>
#include <queue>
#include <string>

#include "dynmesh/error.hpp"

namespace dynmesh {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/// What is known about a directed Voronoi edge, probed from its cell's end (spec §3.1, §10.1).
struct Record {
    enum State : std::uint8_t { Unprobed, Miss, Hit, OutsideOmega };
    State state = Unprobed;
    Point3 s{};   ///< probe start
    Vec3 d{};     ///< unit probe direction
    Point3 x{};   ///< hit
    double t = 0; ///< |x - s| for a hit
    std::uint64_t stamp = 0;
};

struct CellInfo {
    std::uint32_t node = kNone;
    Record rec[4];
};

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K>;  // sample index
using Cb = CGAL::Triangulation_cell_base_with_info_3<CellInfo, K, CGAL::Delaunay_triangulation_cell_base_3<K>>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using DT = CGAL::Delaunay_triangulation_3<K, Tds>;
using Cell = DT::Cell_handle;
using KPoint = K::Point_3;

Point3 to_p(const KPoint& p) { return {p.x(), p.y(), p.z()}; }
KPoint to_k(const Point3& p) { return {p.x, p.y, p.z}; }

/// A Voronoi vertex, current or former (spec §3.2).
struct Node {
    bool infinite = false;
    bool in_omega = false;
    bool alive = true;
    bool active = false;
    Point3 pos{};
    Cell cell{};                 ///< valid while alive
    std::uint32_t prev = kNone;  ///< self for roots
    Point3 entry{};              ///< start of the free segment that reached this node
    Point3 root_entry{};         ///< where its chain leaves Ω (on ∂Ω)
    std::uint32_t depth = 0;     ///< edges from ∂Ω
    double path_len = 0;         ///< length from root_entry along the chain
    [[nodiscard]] bool root() const { return infinite || !in_omega; }
};

struct BallEntry {
    double r2;
    std::uint32_t node;
    int facet;
    std::uint64_t stamp;
    std::uint64_t seq;
    bool operator<(const BallEntry& o) const {  // max-heap on r2, then first pushed first
        if (r2 != o.r2) return r2 < o.r2;
        return seq > o.seq;
    }
};

class Refiner {
public:
    Refiner(const Oracle& oracle, const ProbingOptions& o)
        : oracle_(oracle), o_(o), C_(o.omega_center), R_(o.omega_radius),
          tau_(std::max(oracle.tolerance(), 1e-12 * o.omega_radius)) {}

    ProbingResult run() {
        const auto t0 = std::chrono::steady_clock::now();
        bootstrap();
        while (!queue_.empty()) {
            const BallEntry e = queue_.top();
            queue_.pop();
            const Node& n = nodes_[e.node];
            if (!n.alive || n.cell->info().rec[e.facet].stamp != e.stamp ||
                n.cell->info().rec[e.facet].state != Record::Hit) {
                ++rep_.stale_pops;
                continue;
            }
            if (sample_.size() >= o_.max_points)
                throw InvalidInput("probe_surface: more than max_points = " + std::to_string(o_.max_points) +
                                   " samples: eps is too small for this object");
            // The ball must still be empty (spec §8.2): its centre is then more than eps from
            // every sample, which is what bounds the run.
            const Point3 x = n.cell->info().rec[e.facet].x;
            const auto nv = dt_.nearest_vertex(to_k(x), n.cell);
            if (norm(to_p(nv->point()) - x) < std::sqrt(e.r2) * (1 - 1e-9)) {
                ++rep_.nonempty_pops;
                continue;
            }
            insert(n.cell, e.facet, x);
            if (o_.check_every != 0 && o_.check_every != SIZE_MAX && rep_.insertions % o_.check_every == 0)
                check_invariants();
        }
        if (o_.check_every != SIZE_MAX) check_invariants();
        ProbingResult res;
        res.sample = sample_;
        res.mesh = output();
        rep_.vertices = res.mesh.points.size();
        rep_.facets = res.mesh.triangles.size();
        rep_.voronoi_edges_travelled = rep_.detection_edges + rep_.positioning_edges;
        rep_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        res.report = rep_;
        res.problems = problems_;
        return res;
    }

private:
    // ---- the device: a position in free space and what moving there costs -------------------
    /// The device is either at an in-Ω node (at_node_) or at a point of ∂Ω (at_point_).
    void climb_out(bool positioning) {
        if (at_node_ == kNone) return;
        const Node& a = nodes_[at_node_];
        count_edges(a.depth, positioning);
        rep_.path_length += a.path_len;
        at_point_ = a.root_entry;
        at_node_ = kNone;
    }
    void arc_to(const Point3& p) {
        const Vec3 u = at_point_ - C_, v = p - C_;
        rep_.exterior_path_length += R_ * std::atan2(norm(cross(u, v)), dot(u, v));
        at_point_ = p;
    }
    /// Positioning: brings the device to the in-Ω node u (via ∂Ω).
    void go_to_node(std::uint32_t u) {
        if (at_node_ == u) return;
        const Node& n = nodes_[u];
        climb_out(true);
        arc_to(n.root_entry);
        count_edges(n.depth, true);
        rep_.path_length += n.path_len;
        at_node_ = u;
    }
    void go_to_boundary_point(const Point3& p) {
        climb_out(true);
        arc_to(p);
    }
    void count_edges(std::size_t k, bool positioning) {
        (positioning ? rep_.positioning_edges : rep_.detection_edges) += k;
    }
    std::optional<ProbeHit> cast(const Point3& s, const Vec3& d, double t_max) {
        ++rep_.probes;
        auto h = oracle_.cast(s, d, t_max);
        if (h && h->grazing) ++rep_.grazing_hits;
        if (h && norm(h->x - C_) > R_ * (1 - 1e-6))
            throw InvalidInput("probe_surface: the object reaches the margin of Omega at " +
                               std::to_string(h->x.x) + ", " + std::to_string(h->x.y) + ", " +
                               std::to_string(h->x.z) + ": Omega must contain it with a margin");
        return h;
    }

    // ---- nodes -----------------------------------------------------------------------------
    std::uint32_t new_node(Cell c) {
        Node n;
        n.cell = c;
        n.infinite = dt_.is_infinite(c);
        if (!n.infinite) {
            n.pos = to_p(CGAL::circumcenter(c->vertex(0)->point(), c->vertex(1)->point(),
                                            c->vertex(2)->point(), c->vertex(3)->point()));
            n.in_omega = norm(n.pos - C_) < R_;
        }
        const auto id = static_cast<std::uint32_t>(nodes_.size());
        if (n.root()) {
            n.active = true;
            n.prev = id;
        }
        nodes_.push_back(n);
        c->info() = CellInfo{};
        c->info().node = id;
        ++rep_.cells_created;
        return id;
    }

    // ---- probing one directed edge (spec §4.1) ----------------------------------------------
    /// The line of the Voronoi edge dual to facet (c, i), oriented from c's end toward the
    /// neighbour's: points O + t·D for t in [lo, hi].
    struct EdgeLine {
        Point3 O{};
        Vec3 D{};
        double lo = 0, hi = 0;
        bool degenerate = false;  ///< both ends at the same point
    };
    EdgeLine edge_line(Cell c, int i) const {
        const Cell w = c->neighbor(i);
        const Node& nu = nodes_[c->info().node];
        const Node& nw = nodes_[w->info().node];
        EdgeLine L;
        // The facet's normal pointing away from c's vertex opposite it.
        const Point3 a = to_p(c->vertex((i + 1) & 3)->point()), b = to_p(c->vertex((i + 2) & 3)->point()),
                     cc = to_p(c->vertex((i + 3) & 3)->point());
        Vec3 n = cross(b - a, cc - a);
        n = n / norm(n);
        if (!nu.infinite && !nw.infinite) {
            // The edge lies on the line through the facet's circumcentre along its normal.
            // Circumcentres of nearly flat cells far outside Ω carry large absolute errors
            // (spec §10, "far roots"), so the line is anchored at an end inside Ω, or at the
            // facet's circumcentre, never at a far end.
            L.D = dot(n, nw.pos - nu.pos) >= 0 ? n : -n;
            if (nu.in_omega) {
                L.O = nu.pos;
            } else if (nw.in_omega) {
                L.O = nw.pos;
            } else {
                L.O = to_p(CGAL::circumcenter(to_k(a), to_k(b), to_k(cc)));
            }
            L.lo = nu.in_omega ? 0.0 : dot(nu.pos - L.O, L.D);
            L.hi = (nw.in_omega && !nu.in_omega) ? 0.0 : dot(nw.pos - L.O, L.D);
            L.degenerate = L.hi - L.lo <= tau_;
            return L;
        }
        if (nw.infinite) {  // a ray from pos(u) to infinity, away from u's vertex opposite i
            const Point3 q = to_p(c->vertex(i)->point());
            L.O = nu.pos;
            L.D = dot(n, q - a) > 0 ? -n : n;
            L.lo = 0;
            L.hi = std::numeric_limits<double>::infinity();
            return L;
        }
        // u infinite: the ray comes from infinity toward pos(w); w's vertex opposite the facet
        // is on the inner side.
        const Point3 q = to_p(w->vertex(w->index(c))->point());
        const Vec3 out = dot(n, q - a) > 0 ? -n : n;
        L.O = nw.pos;
        L.D = -out;
        L.lo = -std::numeric_limits<double>::infinity();
        L.hi = 0;
        return L;
    }

    std::uint64_t next_stamp() { return ++stamp_; }

    /// The safety monitor: every in-Ω move is along segments certified here (positioning moves
    /// replay chains of them; moves on ∂Ω are free because S lies inside Ω with a margin).
    void monitor(const Point3& a, const Point3& b) {
        if (o_.ground_truth == nullptr) return;
        ++rep_.segments_checked;
        if (!o_.ground_truth->segment_is_free(a, b))
            throw InternalError("probe_surface: the device would cross the object along the segment (" +
                                std::to_string(a.x) + ", " + std::to_string(a.y) + ", " + std::to_string(a.z) +
                                ") - (" + std::to_string(b.x) + ", " + std::to_string(b.y) + ", " +
                                std::to_string(b.z) + ")");
    }

    // ---- invariants (spec §5.2, §10 "debug invariant") ---------------------------------------
    void check_invariants() {
        const std::string when = "after insertion " + std::to_string(rep_.insertions) + ": ";
        auto fail = [&](const std::string& what) {
            if (problems_.size() < 20) problems_.push_back(when + what);
        };
        for (std::uint32_t id = 0; id < nodes_.size(); ++id) {
            const Node& n = nodes_[id];
            if (!n.active || n.root()) continue;
            // P1: the chain reaches a root through active nodes, with decreasing depth.
            std::uint32_t a = id;
            std::size_t steps = 0;
            while (!nodes_[a].root() && steps <= n.depth) {
                const std::uint32_t p = nodes_[a].prev;
                if (p == kNone || !nodes_[p].active) break;
                a = p;
                ++steps;
            }
            if (!nodes_[a].root() || steps != n.depth)
                fail("P1: node " + std::to_string(id) + " has no active chain of its depth to outside Omega");
        }
        for (Cell c : dt_.all_cell_handles()) {
            const Node& u = nodes_[c->info().node];
            for (int i = 0; i < 4; ++i) {
                const Cell wc = c->neighbor(i);
                const Node& w = nodes_[wc->info().node];
                if (u.infinite && w.infinite) continue;
                const Record& r = c->info().rec[i];
                if (u.active && r.state == Record::Unprobed)
                    fail("an edge of active node " + std::to_string(c->info().node) + " has no record");
                // P2 (local): an edge known to be free joins nodes of the same status.
                if (r.state == Record::Miss && u.active && !w.active)
                    fail("P2: a free edge joins active node " + std::to_string(c->info().node) +
                         " and inactive node " + std::to_string(wc->info().node));
                if (r.state == Record::Hit) {
                    const double rad = ball_radius(c, i, r.x);
                    const auto nv = dt_.nearest_vertex(to_k(r.x), c);
                    if (norm(to_p(nv->point()) - r.x) < rad * (1 - 1e-9))
                        fail("the ball at a hit of node " + std::to_string(c->info().node) + " holds a sample");
                }
            }
        }
    }

    /// Probes the directed edge (c, i) unless its record is known; returns the record.
    const Record& probe_edge(Cell c, int i) {
        Record& r = c->info().rec[i];
        if (r.state != Record::Unprobed) return r;
        const EdgeLine L = edge_line(c, i);
        const double m = dot(C_ - L.O, L.D);
        const Vec3 off = L.O + m * L.D - C_;
        const double h2 = R_ * R_ - dot(off, off);
        const double lo = h2 > 0 ? std::max(L.lo, m - std::sqrt(h2)) : 0;
        const double hi = h2 > 0 ? std::min(L.hi, m + std::sqrt(h2)) : -1;
        r.stamp = next_stamp();
        r.d = L.D;
        r.s = L.O + (std::isfinite(lo) ? lo : 0) * L.D;
        if (!(h2 > 0) || !(lo < hi)) {
            r.state = Record::OutsideOmega;
            return r;
        }
        const Node& nu = nodes_[c->info().node];
        if (nu.root()) go_to_boundary_point(r.s);
        const double len = hi - lo;
        if (L.degenerate || len <= tau_) {
            r.state = Record::Miss;
            return r;
        }
        const auto hit = cast(r.s, r.d, len);
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

    double ball_radius(Cell c, int i, const Point3& x) const {
        double r = 0;
        for (int k = 1; k <= 3; ++k) r = std::max(r, norm(to_p(c->vertex((i + k) & 3)->point()) - x));
        return r;
    }
    void push_ball(Cell c, int i, const Record& r) {
        const double rad = ball_radius(c, i, r.x);
        if (rad > o_.eps) queue_.push({rad * rad, c->info().node, i, r.stamp, seq_++});
    }

    // ---- detect_access (spec §4.2, §10.2) -----------------------------------------------------
    void detect_access(std::uint32_t s) {
        struct Frame {
            std::uint32_t node;
            int i;
        };
        std::vector<Frame> stack{{s, 0}};
        while (!stack.empty()) {
            Frame& f = stack.back();
            if (f.i == 4) {
                const std::uint32_t u = f.node;
                stack.pop_back();
                if (u != s) {  // back along the edge it came by
                    const Node& n = nodes_[u];
                    count_edges(1, false);
                    rep_.path_length += norm(n.pos - n.entry);
                    const Node& p = nodes_[n.prev];
                    if (p.root()) {
                        at_node_ = kNone;
                        at_point_ = n.entry;
                    } else {
                        at_node_ = n.prev;
                    }
                }
                continue;
            }
            const int i = f.i++;
            const std::uint32_t u = f.node;
            const Cell c = nodes_[u].cell;
            const Cell wc = c->neighbor(i);
            const std::uint32_t w = wc->info().node;
            if (nodes_[u].infinite && nodes_[w].infinite) continue;
            const Record& r = probe_edge(c, i);
            if (r.state != Record::Miss || nodes_[w].active) continue;
            // w is in Ω: walk to it along the certified edge.
            if (nodes_[u].root()) go_to_boundary_point(r.s);
            monitor(r.s, nodes_[w].pos);
            Node& n = nodes_[w];
            const Node& pu = nodes_[u];
            n.active = true;
            n.prev = u;
            n.entry = r.s;
            n.depth = pu.root() ? 1 : pu.depth + 1;
            n.root_entry = pu.root() ? r.s : pu.root_entry;
            n.path_len = (pu.root() ? 0 : pu.path_len) + norm(n.pos - r.s);
            count_edges(1, false);
            rep_.path_length += norm(n.pos - r.s);
            at_node_ = w;
            stack.push_back({w, 0});
        }
    }

    // ---- initialisation (spec §4.3, one component) -------------------------------------------
    void bootstrap() {
        const Point3 o = o_.interior_points.front();
        Vec3 u0 = o - C_;
        const double dist = norm(u0);
        u0 = dist > 1e-9 * R_ ? u0 / dist : Vec3{1, 0, 0};
        const Point3 p = C_ + R_ * u0;
        at_point_ = p;
        const Vec3 d = (o - p) / norm(o - p);
        const auto a = cast(p, d, norm(o - p));
        if (!a)
            throw InvalidInput("probe_surface: the ray from the boundary of Omega toward the interior point (" +
                               std::to_string(o.x) + ", " + std::to_string(o.y) + ", " + std::to_string(o.z) +
                               ") meets no surface: the point is not inside the object");
        // Two directions close to d whose hits make a small well-shaped triangle.
        const Vec3 e1 = normalized(std::fabs(d.x) < 0.9 ? cross(d, Vec3{1, 0, 0}) : cross(d, Vec3{0, 1, 0}));
        const Vec3 e2 = cross(d, e1);
        double theta = o_.eps / (8 * a->t);
        std::optional<ProbeHit> b, c;
        for (int k = 0; k < 30; ++k, theta /= 2) {
            b = cast(p, normalized(d + theta * e1), 2 * R_);
            c = cast(p, normalized(d + theta * e2), 2 * R_);
            if (b && c && norm(b->x - a->x) > 0 && norm(c->x - a->x) > 0 && norm(b->x - c->x) > 0) break;
        }
        if (!b || !c) throw InvalidInput("probe_surface: no bootstrap triangle near the first hit");
        rep_.probes_bootstrap = rep_.probes;
        // The line dual to abc, clipped by Ω, probed from both ends; the larger ball is the
        // fourth point.
        const Point3 cc = to_p(CGAL::circumcenter(to_k(a->x), to_k(b->x), to_k(c->x)));
        const Vec3 n = normalized(cross(b->x - a->x, c->x - a->x));
        const double m = dot(C_ - cc, n);
        const Vec3 off = cc + m * n - C_;
        const double h = std::sqrt(std::max(0.0, R_ * R_ - dot(off, off)));
        const Point3 q1 = cc + (m - h) * n, q2 = cc + (m + h) * n;
        std::optional<ProbeHit> best;
        for (const auto& [from, to] : {std::pair{q1, q2}, std::pair{q2, q1}}) {
            go_to_boundary_point(from);
            const auto x = cast(from, normalized(to - from), norm(to - from));
            if (x && (!best || norm(x->x - a->x) > norm(best->x - a->x))) best = x;
        }
        rep_.probes_bootstrap = rep_.probes;
        if (!best || norm(best->x - a->x) <= o_.eps)
            throw InvalidInput("probe_surface: eps is larger than the object (no ball of the first "
                               "triangle exceeds it)");
        for (const Point3& q : {a->x, b->x, c->x, best->x}) {
            dt_.insert(to_k(q))->info() = static_cast<std::uint32_t>(sample_.size());
            sample_.push_back(q);
        }
        if (dt_.dimension() != 3) throw InternalError("probe_surface: the first four samples are coplanar");
        // Every cell is new (spec §4.3 step 4).
        std::vector<Cell> cells;
        for (Cell ch : dt_.all_cell_handles()) cells.push_back(ch);
        std::vector<std::uint32_t> ids;
        for (Cell ch : cells) ids.push_back(new_node(ch));
        for (std::uint32_t id : ids)
            if (nodes_[id].root()) detect_access(id);
    }

    // ---- the update after an insertion (spec §4.4, §10.1, §10.6) ------------------------------
    void insert(Cell c, int i, const Point3& x) {
        const KPoint kx = to_k(x);
        Cell seed = c;
        if (dt_.side_of_sphere(c, kx, true) != CGAL::ON_BOUNDED_SIDE) {
            seed = c->neighbor(i);
            if (dt_.side_of_sphere(seed, kx, true) != CGAL::ON_BOUNDED_SIDE) seed = dt_.locate(kx, c);
        }
        std::vector<Cell> cavity;
        std::vector<DT::Facet> boundary;
        dt_.find_conflicts(kx, seed, std::back_inserter(boundary), std::back_inserter(cavity));
        for (Cell k : cavity) {
            Node& n = nodes_[k->info().node];
            n.alive = false;
            n.cell = Cell{};
            if (n.active) ++rep_.nodes_retained;
        }
        const auto v = dt_.insert_in_hole(kx, cavity.begin(), cavity.end(), boundary.front().first,
                                          boundary.front().second);
        v->info() = static_cast<std::uint32_t>(sample_.size());
        sample_.push_back(x);
        ++rep_.insertions;
        std::vector<Cell> fresh;
        dt_.incident_cells(v, std::back_inserter(fresh));
        for (Cell n : fresh) (void)new_node(n);
        std::vector<std::pair<Cell, int>> candidates;
        for (Cell n : fresh) {
            if (dt_.is_infinite(n)) continue;  // its old neighbour is infinite too
            const Cell k_out = n->neighbor(n->index(v));
            const int j = k_out->index(n);
            Record& r = k_out->info().rec[j];
            const Node& nn = nodes_[n->info().node];
            if (r.state == Record::Unprobed) continue;
            const double l = dot(nn.pos - r.s, r.d);
            const double line_off = norm(nn.pos - (r.s + l * r.d));
            const double band = 1e-9 * R_;
            if (r.state == Record::OutsideOmega || (l < 0 && line_off <= band)) {
                r.state = Record::OutsideOmega;
                r.stamp = next_stamp();
            } else if (line_off > band) {
                r.state = Record::Unprobed;
                candidates.emplace_back(k_out, j);
            } else if (r.state == Record::Hit && r.t < l - band) {
                // same ball, same stamp: the edge shrank but still holds the hit
            } else if (std::fabs(r.t - l) > band || r.state == Record::Miss) {
                r.state = Record::Miss;
                r.stamp = next_stamp();
                if (nn.in_omega) candidates.emplace_back(k_out, j);
            } else {
                r.state = Record::Unprobed;
                candidates.emplace_back(k_out, j);
            }
        }
        for (Cell n : fresh) {
            const std::uint32_t id = n->info().node;
            if (nodes_[id].root()) detect_access(id);
        }
        for (const auto& [k_out, j] : candidates) {
            const std::uint32_t u = k_out->info().node;
            const std::uint32_t w = k_out->neighbor(j)->info().node;
            if (!nodes_[u].active) continue;
            if (nodes_[w].active && k_out->info().rec[j].state != Record::Unprobed) continue;
            if (!nodes_[u].root()) go_to_node(u);
            detect_access(u);
        }
    }

    // ---- output (spec §4.5, §10.7) ------------------------------------------------------------
    /// The marked facets with their vertices numbered in sample order, each rotated to start
    /// at its smallest index and sorted: the same run gives the same bytes.
    TriangleSoup output() {
        std::vector<std::array<std::uint32_t, 3>> tris;
        for (auto f = dt_.finite_facets_begin(); f != dt_.finite_facets_end(); ++f) {
            const Cell c = f->first;
            const int i = f->second;
            const Cell w = c->neighbor(i);
            const Record& r1 = c->info().rec[i];
            const Record& r2 = w->info().rec[w->index(c)];
            const Record* r = r1.state == Record::Hit ? &r1 : r2.state == Record::Hit ? &r2 : nullptr;
            if (r == nullptr) continue;
            std::array<std::uint32_t, 3> t{c->vertex((i + 1) & 3)->info(), c->vertex((i + 2) & 3)->info(),
                                           c->vertex((i + 3) & 3)->info()};
            const Point3 &a = sample_[t[0]], &b = sample_[t[1]], &cc = sample_[t[2]];
            if (dot(cross(b - a, cc - a), r->d) > 0) std::swap(t[1], t[2]);
            std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
            rep_.max_ball_radius = std::max(rep_.max_ball_radius, ball_radius(c, i, r->x));
            tris.push_back(t);
        }
        std::sort(tris.begin(), tris.end());
        std::vector<std::uint32_t> index(sample_.size(), kNone);
        TriangleSoup soup;
        for (const auto& t : tris)
            for (std::uint32_t v : t) index[v] = 0;
        for (std::uint32_t v = 0; v < sample_.size(); ++v)
            if (index[v] == 0) {
                index[v] = static_cast<std::uint32_t>(soup.points.size());
                soup.points.push_back(sample_[v]);
            }
        for (const auto& t : tris) soup.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
        return soup;
    }

    const Oracle& oracle_;
    const ProbingOptions& o_;
    Point3 C_;
    double R_;
    double tau_;
    DT dt_;
    std::vector<Node> nodes_;
    std::vector<Point3> sample_;
    std::priority_queue<BallEntry> queue_;
    std::uint64_t stamp_ = 0, seq_ = 0;
    std::uint32_t at_node_ = kNone;
    Point3 at_point_{};
    ProbingReport rep_;
    std::vector<std::string> problems_;
};

void check_options(const ProbingOptions& o) {
    const auto bad = [](const std::string& what) { return InvalidInput("probe_surface: " + what); };
    if (!(std::isfinite(o.eps) && o.eps > 0)) throw bad("eps must be finite and > 0");
    if (!(std::isfinite(o.eps_S) && o.eps_S > 0)) throw bad("eps_S must be finite and > 0");
    if (!(std::isfinite(o.omega_radius) && o.omega_radius > 0) || !is_finite(o.omega_center))
        throw bad("Omega must be a finite ball of positive radius");
    if (o.eps >= 0.091 * o.eps_S && !o.allow_unguaranteed)
        throw bad("eps = " + std::to_string(o.eps) + " is not below 0.091 * eps_S = " +
                  std::to_string(0.091 * o.eps_S) + ": the output would carry no guarantee");
    if (o.interior_points.empty()) throw bad("no interior point");
    for (const Point3& p : o.interior_points) {
        if (!is_finite(p)) throw bad("an interior point is not finite");
        if (!(norm(p - o.omega_center) < o.omega_radius)) throw bad("an interior point lies outside Omega");
    }
}

}  // namespace

double probing_eps_from_delta(double delta, double eps_S, double omega_radius) {
    DYNMESH_CHECK(std::isfinite(delta) && delta > 0, "probing_eps_from_delta: delta must be finite and > 0");
    return eps_S * std::sqrt(delta / (4.5 * 2 * omega_radius));
}

ProbingResult probe_surface(const Oracle& oracle, const ProbingOptions& options) {
    check_options(options);
    Refiner r(oracle, options);
    return r.run();
}

}  // namespace dynmesh
