#include "dynmesh/skin/growth.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_set>

#include "dynmesh/deform/local_ops.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/skin/critical_events.hpp"
#include "dynmesh/skin/static_mesh.hpp"
#include "surgery.hpp"

namespace dynmesh {

const char* schedule_name(SkinSchedule s) { return s == SkinSchedule::Relaxed ? "relaxed" : "every-step"; }

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// What the queue holds. At equal times topology changes come first, then checks.
enum class Kind : int { Birth, SurgeryOn, SurgerySwitch, SurgeryOff, Death, CheckEdge, CheckFace, Step, Snapshot, End };

struct Entry {
    double time = 0;
    Kind kind = Kind::End;
    std::uint32_t id = 0;       ///< element index, event index or snapshot number
    std::uint32_t version = 0;  ///< the element's version when pushed (stale entries are skipped)
    bool operator>(const Entry& o) const {
        if (time != o.time) return time > o.time;
        if (kind != o.kind) return static_cast<int>(kind) > static_cast<int>(o.kind);
        return id > o.id;
    }
};

/// The size-scale ratio of an element (§3.2) with the ϱ it was measured against.
struct Measure {
    double ratio = 0;
    double rho0 = 0;       ///< min ϱ over the element's vertices (the safe durations' ϱ0), floored
    bool floored = false;  ///< λ fell under the floor: left out of the violation count
};

/// A sorted vertex triple (an edge has a third index of kNone): an element's identity.
using Signature = std::array<std::uint32_t, 3>;
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

struct ElementState {
    std::uint32_t version = 0;
    Signature sig{kNone, kNone, kNone};
    double checked_at = 0;
    bool checked = false;
    bool beyond = false;   ///< its last check found its ratio beyond the Q1 threshold (floored λ)
    bool floored = false;  ///< and ϱ under the floor, which leaves it out of the counts
};

class Grower {
public:
    Grower(const SkinFunction& phi, const SkinGrowthOptions& o) : phi_(phi), o_(o), q_(o.quality) {
        DYNMESH_CHECK(phi.shrink() == 0.5, "grow_skin: the growth needs s = 1/2 (got s = " +
                                               std::to_string(phi.shrink()) + ")");
        const auto problems = feasibility_problems(q_);
        DYNMESH_CHECK(problems.empty(), "grow_skin: " + (problems.empty() ? std::string() : problems.front()));
        DYNMESH_CHECK(std::isfinite(o.fixed_step) && o.fixed_step >= 0,
                      "grow_skin: the fixed step must be finite and not negative");
        DYNMESH_CHECK(o.fixed_step == 0 || o.schedule == SkinSchedule::EveryStep,
                      "grow_skin: a fixed step needs the every-step scheduler");
        double sum = 0;
        std::size_t n = 0;
        for (std::size_t i = 0; i < phi.input_balls(); ++i)
            if (phi.balls()[i].weight > 0) {
                sum += std::sqrt(0.5 * phi.balls()[i].weight);
                ++n;
            }
        DYNMESH_CHECK(n > 0, "grow_skin: no ball has a positive weight");
        floor_ = o.rho_floor_factor * sum / double(n);
        report_.t_start = skin_growth_start(phi, o);
        report_.t_end = o.t_end;
        DYNMESH_CHECK(o.t_end > report_.t_start, "grow_skin: t_end is before the first birth");
        DYNMESH_CHECK(o.fixed_step == 0 || o.fixed_step >= SkinGrowthOptions::kMinFixedStep * (o.t_end - report_.t_start),
                      "grow_skin: the fixed step is under " + std::to_string(SkinGrowthOptions::kMinFixedStep) +
                          " of the growth's time span");
        report_.rho_floor = floor_;
    }

    SkinGrowthResult run() {
        const auto start = std::chrono::steady_clock::now();
        schedule_events();
        double last_progress = report_.t_start;
        const double span = report_.t_end - report_.t_start;
        while (!heap_.empty()) {
            const Entry e = heap_.top();
            heap_.pop();
            t_ = e.time;
            if (o_.progress && t_ - last_progress >= 0.01 * span) {
                o_.progress(t_);
                last_progress = t_;
            }
            if (e.kind == Kind::End) break;
            dispatch(e);
            drain();
        }
        t_ = report_.t_end;
        unfold();
        SkinGrowthResult result;
        result.final = snapshot();
        report_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        result.report = report_;
        return result;
    }

private:
    // ---- the queue -------------------------------------------------------------------------
    void push(double time, Kind kind, std::uint32_t id, std::uint32_t version = 0) {
        heap_.push({time, kind, id, version});
        ++c().heap_pushes;
    }

    void schedule_events() {
        const auto events = critical_events(phi_, report_.t_start, report_.t_end);
        for (const SkinEvent& ev : events) {
            const double inr = mixed_cell_inradius(phi_, ev.simplex);
            const auto id = static_cast<std::uint32_t>(surgeries_.size());
            Surgery s = make_surgery(phi_, ev, inr, o_.neighbourhood, o_.inner);
            if (ev.kind == SkinEvent::Kind::Birth || ev.kind == SkinEvent::Kind::Death) {
                const double r = o_.birth_radius * inr;
                s.t_on = ev.kind == SkinEvent::Kind::Birth ? ev.time + 2 * r * r : ev.time - 2 * r * r;
                if (s.t_on > report_.t_start && s.t_on <= report_.t_end)
                    push(s.t_on, ev.kind == SkinEvent::Kind::Birth ? Kind::Birth : Kind::Death, id);
            } else {
                if (s.t_on > report_.t_start && s.t_on <= report_.t_end) push(s.t_on, Kind::SurgeryOn, id);
                if (s.W <= report_.t_end) push(s.W, Kind::SurgerySwitch, id);
                if (s.t_off <= report_.t_end) push(s.t_off, Kind::SurgeryOff, id);
            }
            surgeries_.push_back(s);
        }
        report_.events = events.size();
        const double span = report_.t_end - report_.t_start;
        for (std::size_t i = 1; i <= o_.snapshots; ++i) {
            const double t = i == o_.snapshots ? report_.t_end : report_.t_start + span * double(i) / double(o_.snapshots);
            push(t, Kind::Snapshot, static_cast<std::uint32_t>(i));
        }
        push(report_.t_end, Kind::End, 0);
    }

    void dispatch(const Entry& e) {
        switch (e.kind) {
            case Kind::CheckEdge:
                if (e.id < edges_.size() && edges_[e.id].version == e.version && !mesh_.is_deleted(Edge(e.id)))
                    check_edge(Edge(e.id), "flip");
                break;
            case Kind::CheckFace:
                if (e.id < faces_.size() && faces_[e.id].version == e.version && !mesh_.is_deleted(Face(e.id)))
                    check_face(Face(e.id), "flip");
                break;
            case Kind::Step: step(); break;
            case Kind::Birth: birth(e.id); break;
            case Kind::Death: death(e.id); break;
            case Kind::SurgeryOn: surgery_on(e.id); break;
            case Kind::SurgerySwitch: surgery_switch(e.id); break;
            case Kind::SurgeryOff: surgery_off(e.id); break;
            case Kind::Snapshot:
                unfold();
                if (o_.on_snapshot) o_.on_snapshot(snapshot());
                ++report_.snapshots;
                break;
            case Kind::End: break;
        }
    }

    SkinGrowthCounters& c() { return report_.counters; }

    // ---- vertices: lazy positions along the flow --------------------------------------------
    void fit_arrays() {
        vt_.resize(mesh_.vertices_size(), t_);
        vcell_.resize(mesh_.vertices_size(), 0);
        vtag_.resize(mesh_.vertices_size(), -1);
        edges_.resize(mesh_.edges_size());
        faces_.resize(mesh_.faces_size());
    }

    Vertex new_vertex(const Point3& p, std::size_t cell, double t, int tag) {
        const Vertex v = mesh_.add_vertex(p);
        fit_arrays();
        vt_[v.idx()] = t;
        vcell_[v.idx()] = cell;
        vtag_[v.idx()] = tag;
        return v;
    }

    /// x0 (on the level t0, in cell `cell`) moved along the flow to the level t.
    Point3 flow(Point3 x0, double t0, std::size_t& cell, double t) {
        for (int leg = 0; leg < 64; ++leg) {
            Point3 x1;
            if (!flow_in(cell, x0, t, x1)) break;
            if (phi_.in_mixed_cell(cell, x1)) return x1;
            // The times the path spends in the cell are an interval: bisect for its end.
            double lo = t0, hi = t;
            Point3 xhi = x1;
            for (int it = 0; it < 64 && std::abs(hi - lo) > 1e-15 * (1 + std::abs(hi)); ++it) {
                const double mid = 0.5 * (lo + hi);
                Point3 xm;
                if (flow_in(cell, x0, mid, xm) && phi_.in_mixed_cell(cell, xm)) {
                    lo = mid;
                } else if (flow_in(cell, x0, mid, xm)) {
                    hi = mid;
                    xhi = xm;
                } else {
                    hi = mid;
                }
            }
            const std::size_t next = phi_.locate(xhi, cell);
            if (next == cell) break;
            cell = next;
            x0 = xhi;
            t0 = hi;
        }
        ++c().flow_fallbacks;
        return project_to_skin(phi_, x0, t, cell);
    }

    bool flow_in(std::size_t cell, const Point3& x0, double t, Point3& out) const {
        try {
            out = phi_.flow_in_cell(cell, x0, t);
            return is_finite(out);
        } catch (const InvalidInput&) {
            return false;
        }
    }

    const Point3& pos(Vertex v) {
        const std::uint32_t i = v.idx();
        if (vt_[i] == t_ || (vtag_[i] >= 0 && t_ < vt_[i])) return mesh_.position(v);
        ++c().evaluations;
        mesh_.position(v) = flow(mesh_.position(v), vt_[i], vcell_[i], t_);
        vt_[i] = t_;
        return mesh_.position(v);
    }

    /// The position at time t without moving the cached one (the auditor).
    Point3 peek(Vertex v, double t) {
        std::size_t cell = vcell_[v.idx()];
        ++c().evaluations;
        return flow(mesh_.position(v), vt_[v.idx()], cell, t);
    }

    double rho_at(const Point3& x, std::size_t cell) const { return norm(x - phi_.simplices()[cell].z); }

    // ---- measuring ---------------------------------------------------------------------------
    Measure edge_measure(const Point3& a, const Point3& b, double ra, double rb) const {
        Measure m;
        double lambda = std::max(ra, rb);
        m.floored = lambda < floor_;
        lambda = std::max(lambda, floor_);
        m.ratio = 0.5 * norm(a - b) / lambda;
        m.rho0 = std::max(std::min(ra, rb), floor_);
        return m;
    }
    Measure face_measure(const Point3& a, const Point3& b, const Point3& p, double ra, double rb, double rc) const {
        Measure m;
        double lambda = std::min({ra, rb, rc});
        m.floored = lambda < floor_;
        lambda = std::max(lambda, floor_);
        m.ratio = circumradius(a, b, p) / lambda;
        m.rho0 = lambda;
        return m;
    }

    static Signature sig_of(std::uint32_t a, std::uint32_t b, std::uint32_t p = kNone) {
        Signature s{a, b, p};
        std::sort(s.begin(), s.end());
        return s;
    }

    bool exempt(Face f) const {
        for (Vertex v : mesh_.face_vertices(f))
            if (vtag_[v.idx()] >= 0) return true;
        return false;
    }
    bool exempt(Edge e) const {
        for (int i = 0; i < 2; ++i) {
            const Face f = mesh_.face(SurfaceMesh::halfedge(e, i));
            if (f.is_valid() && exempt(f)) return true;
        }
        return false;
    }
    /// The surgery whose template is next to v (v or a neighbour is a template vertex), or −1.
    int blocking(Vertex v) const {
        if (vtag_[v.idx()] >= 0) return vtag_[v.idx()];
        for (Halfedge h : mesh_.outgoing_halfedges(v))
            if (vtag_[mesh_.to_vertex(h).idx()] >= 0) return vtag_[mesh_.to_vertex(h).idx()];
        return -1;
    }

    // ---- checks ------------------------------------------------------------------------------
    void check_edge(Edge e, const char* cause) {
        if (mesh_.is_deleted(e) || exempt(e)) return;
        const Vertex a = mesh_.vertex(e, 0), b = mesh_.vertex(e, 1);
        ++c().checks_edge;
        budget(mesh_.position(a));
        const Point3 pa = pos(a), pb = pos(b);
        const Measure m = edge_measure(pa, pb, rho_at(pa, vcell_[a.idx()]), rho_at(pb, vcell_[b.idx()]));
        ElementState& st = edges_[e.idx()];
        const Signature sig = sig_of(a.idx(), b.idx());
        const bool persisted = st.checked && st.sig == sig;
        const double low = q_.C / q_.Q1;
        bool missed = false;
        if (persisted && !st.beyond && o_.audit)
            missed = audit(st.checked_at, [&](double t) {
                const Point3 xa = peek(a, t), xb = peek(b, t);
                std::size_t ca = vcell_[a.idx()], cb = vcell_[b.idx()];
                ca = phi_.locate(xa, ca);
                cb = phi_.locate(xb, cb);
                const Measure mm = edge_measure(xa, xb, rho_at(xa, ca), rho_at(xb, cb));
                return !mm.floored && mm.ratio <= low;
            });
        record_check(st, sig, persisted, m.ratio <= low, m.floored, missed, "edge", cause, m.ratio, pa);
        const double gamma = m.ratio / (q_.C / q_.Q0);
        if (gamma < 1) {
            const int block = std::max(blocking(a), blocking(b));
            if (block >= 0) {
                // Next to a template: exempt until it dissolves, then checked as new.
                ++c().deferred;
                st.checked = false;
                schedule(e, std::max(surgeries_[block].t_off, t_ + 1e-12 * (1 + std::abs(t_))));
                return;
            }
            if (contract(e)) return;
            ++c().refused_contractions;
            // Refused (link condition or a fold): look again later, not sooner than 1e-3·ϱ0²,
            // so that a stuck edge cannot stall the clock.
            const double g = std::max(gamma, q_.Q0 / q_.Q1 * (1 + 1e-6));
            schedule(e, t_ + std::max(edge_safe_duration(g, m.rho0, q_), 1e-3 * m.rho0 * m.rho0));
            return;
        }
        schedule(e, t_ + edge_safe_duration(gamma, m.rho0, q_));
    }

    void check_face(Face f, const char* cause) {
        if (mesh_.is_deleted(f) || exempt(f)) return;
        const auto v = mesh_.face_vertices(f);
        ++c().checks_triangle;
        budget(mesh_.position(v[0]));
        std::array<Point3, 3> p;
        std::array<double, 3> r{};
        for (int i = 0; i < 3; ++i) {
            p[i] = pos(v[i]);
            r[i] = rho_at(p[i], vcell_[v[i].idx()]);
        }
        const Measure m = face_measure(p[0], p[1], p[2], r[0], r[1], r[2]);
        ElementState& st = faces_[f.idx()];
        const Signature sig = sig_of(v[0].idx(), v[1].idx(), v[2].idx());
        const bool persisted = st.checked && st.sig == sig;
        const double high = q_.C * q_.Q1;
        bool missed = false;
        if (persisted && !st.beyond && o_.audit)
            missed = audit(st.checked_at, [&](double t) {
                std::array<Point3, 3> x;
                std::array<double, 3> rr{};
                for (int i = 0; i < 3; ++i) {
                    x[i] = peek(v[i], t);
                    rr[i] = rho_at(x[i], phi_.locate(x[i], vcell_[v[i].idx()]));
                }
                const Measure mm = face_measure(x[0], x[1], x[2], rr[0], rr[1], rr[2]);
                return !mm.floored && mm.ratio >= high;
            });
        record_check(st, sig, persisted, m.ratio >= high, m.floored, missed, "triangle", cause, m.ratio, p[0]);
        const double gamma = m.ratio / (q_.C * q_.Q0);
        if (gamma > 1) {
            const int block = std::max({blocking(v[0]), blocking(v[1]), blocking(v[2])});
            if (block >= 0) {
                ++c().deferred;
                st.checked = false;
                schedule(f, std::max(surgeries_[block].t_off, t_ + 1e-12 * (1 + std::abs(t_))));
                return;
            }
            if (insert(f)) return;
            ++c().refused_insertions;
            const double g = std::min(gamma, q_.Q1 / q_.Q0 * (1 - 1e-6));
            schedule(f, t_ + std::max(triangle_safe_duration(g, m.rho0, q_), 1e-3 * m.rho0 * m.rho0));
            return;
        }
        schedule(f, t_ + triangle_safe_duration(gamma, m.rho0, q_));
    }

    /// Counts a check's outcome and records it in the element's state. An element found beyond
    /// the Q1 threshold (§8 correction 2) is a miss when its previous check found it in range,
    /// born bad when it is new, or when its previous check found it beyond but under the floor
    /// of ϱ (excluded then: cause "floor"), still bad when its previous check found it beyond
    /// already (the repair then was refused or undone); `missed` also carries what the auditor
    /// saw. Under the floor nothing is counted.
    void record_check(ElementState& st, const Signature& sig, bool persisted, bool beyond, bool floored,
                      bool missed, const char* what, const char* cause, double ratio, const Point3& where) {
        if (beyond && !floored) switch (classify_beyond(persisted, st.beyond, st.floored)) {
                case BeyondCount::BornBad: ++c().born_bad[cause]; break;
                case BeyondCount::LeftFloor: ++c().born_bad["floor"]; break;
                case BeyondCount::StillBad: ++c().still_bad; break;
                case BeyondCount::Miss: missed = true; break;
            }
        if (missed) note_violation(what, st.checked_at, ratio, where);
        st.beyond = beyond;
        st.floored = floored;
        st.sig = sig;
        st.checked = true;
        st.checked_at = t_;
    }

    void note_violation(const char* what, double since, double ratio, const Point3& where) {
        ++c().violations;
        if (report_.violation_examples.size() >= 10) return;
        // The nearest critical point, for the record.
        double best = kInf;
        std::size_t near = 0;
        for (std::size_t i = 0; i < surgeries_.size(); ++i)
            if (norm(surgeries_[i].z - where) < best) {
                best = norm(surgeries_[i].z - where);
                near = i;
            }
        std::string line = std::string(what) + " at t = " + std::to_string(t_) + " (checked at " +
                           std::to_string(since) + "): ratio " + std::to_string(ratio);
        if (best < kInf)
            line += "; nearest critical point: dim " + std::to_string(surgeries_[near].dim) + " at distance " +
                    std::to_string(best) + " (r " + std::to_string(surgeries_[near].r) + "), W " +
                    std::to_string(surgeries_[near].W) + ", window [" + std::to_string(surgeries_[near].t_on) + ", " +
                    std::to_string(surgeries_[near].t_off) + "]";
        report_.violation_examples.push_back(line);
    }

    void budget(const Point3& where) {
        if (c().checks() <= o_.max_checks) return;
        throw InternalError("grow_skin: more than " + std::to_string(o_.max_checks) + " checks by t = " +
                            std::to_string(t_) + ": the mesh does not settle near (" + std::to_string(where.x) + ", " +
                            std::to_string(where.y) + ", " + std::to_string(where.z) + ")");
    }

    /// Samples 19 times strictly between `since` and now: does `beyond` hold at one of them?
    template <class Beyond>
    bool audit(double since, Beyond&& beyond) {
        for (int i = 1; i < 20; ++i) {
            ++c().audit_samples;
            if (beyond(since + (t_ - since) * double(i) / 20.0)) return true;
        }
        return false;
    }

    void schedule(Edge e, double when) {
        if (o_.schedule == SkinSchedule::EveryStep) {
            step_min_ = std::min(step_min_, when - t_);
            return;
        }
        push(when, Kind::CheckEdge, e.idx(), ++edges_[e.idx()].version);
    }
    void schedule(Face f, double when) {
        if (o_.schedule == SkinSchedule::EveryStep) {
            step_min_ = std::min(step_min_, when - t_);
            return;
        }
        push(when, Kind::CheckFace, f.idx(), ++faces_[f.idx()].version);
    }

    /// Elements created or changed by an operation: checked at once, in this order.
    struct Pending {
        bool face;
        std::uint32_t id;
        const char* cause;
    };
    std::vector<Pending> pending_;

    /// Checks the pending elements (and those their repairs create) until none is left. When
    /// the repairs do not settle (next to a singular point of the skin, insertions and
    /// contractions can undo each other), the mesh is rebuilt at this time (the fallback);
    /// a second time at the same time is an internal error.
    void drain() {
        std::size_t guard = 0;
        std::size_t limit = kSettleChecks * (mesh_.n_faces() + 1000);
        while (!pending_.empty()) {
            const Pending p = pending_.back();
            pending_.pop_back();
            if (p.face) {
                if (p.id < mesh_.faces_size()) check_face(Face(p.id), p.cause);
            } else if (p.id < mesh_.edges_size()) {
                check_edge(Edge(p.id), p.cause);
            }
            if (++guard <= limit) continue;
            const std::string what = "the operations at t = " + std::to_string(t_) + " do not settle (" +
                                     std::to_string(guard) + " checks)";
            if (unsettled_at_ == t_) throw InternalError("grow_skin: " + what + ", after remeshing");
            unsettled_at_ = t_;
            remesh(what);
            guard = 0;
            limit = kSettleChecks * (mesh_.n_faces() + 1000);
        }
    }
    /// Checks per triangle (plus 1,000) after which one instant's repairs count as not settling.
    static constexpr std::size_t kSettleChecks = 20;
    double unsettled_at_ = kInf;  ///< the time of the last remesh for repairs that did not settle

    /// Queues for an immediate check the edges and faces within two rings of `seeds` whose
    /// vertex set is new since their last check.
    void recheck_around(const std::vector<Vertex>& seeds, const char* cause, bool all = false) {
        fit_arrays();
        std::unordered_set<std::uint32_t> verts, fs, es;
        std::vector<Vertex> frontier;
        for (Vertex v : seeds)
            if (!mesh_.is_deleted(v) && verts.insert(v.idx()).second) frontier.push_back(v);
        for (int ring = 0; ring < 2; ++ring) {
            std::vector<Vertex> next;
            for (Vertex v : frontier)
                for (Halfedge h : mesh_.outgoing_halfedges(v)) {
                    const Vertex w = mesh_.to_vertex(h);
                    if (verts.insert(w.idx()).second) next.push_back(w);
                }
            frontier.swap(next);
        }
        for (std::uint32_t vi : verts)
            for (Halfedge h : mesh_.outgoing_halfedges(Vertex(vi))) {
                es.insert(SurfaceMesh::edge(h).idx());
                if (mesh_.face(h).is_valid()) fs.insert(mesh_.face(h).idx());
            }
        for (std::uint32_t ei : es) {
            const Edge e(ei);
            const ElementState& st = edges_[ei];
            if (all || !st.checked || st.sig != sig_of(mesh_.vertex(e, 0).idx(), mesh_.vertex(e, 1).idx()))
                pending_.push_back({false, ei, cause});
        }
        for (std::uint32_t fi : fs) {
            const auto v = mesh_.face_vertices(Face(fi));
            const ElementState& st = faces_[fi];
            if (all || !st.checked || st.sig != sig_of(v[0].idx(), v[1].idx(), v[2].idx()))
                pending_.push_back({true, fi, cause});
        }
    }

    void queue_faces_and_edges(const std::vector<Face>& faces, const char* cause) {
        for (Face f : faces) {
            pending_.push_back({true, f.idx(), cause});
            for (Edge e : face_edges(f)) pending_.push_back({false, e.idx(), cause});
        }
    }

    std::array<Edge, 3> face_edges(Face f) const {
        const Halfedge h = mesh_.halfedge(f), n = mesh_.next(h);
        return {SurfaceMesh::edge(h), SurfaceMesh::edge(n), SurfaceMesh::edge(mesh_.next(n))};
    }

    void refresh_around(const std::vector<Vertex>& seeds, int rings) {
        std::unordered_set<std::uint32_t> seen;
        std::vector<Vertex> frontier;
        for (Vertex v : seeds)
            if (seen.insert(v.idx()).second) frontier.push_back(v);
        for (Vertex v : frontier) (void)pos(v);
        for (int ring = 0; ring < rings; ++ring) {
            std::vector<Vertex> next;
            for (Vertex v : frontier)
                for (Halfedge h : mesh_.outgoing_halfedges(v)) {
                    const Vertex w = mesh_.to_vertex(h);
                    if (seen.insert(w.idx()).second) {
                        (void)pos(w);
                        next.push_back(w);
                    }
                }
            frontier.swap(next);
        }
    }

    // ---- operations --------------------------------------------------------------------------
    /// Contracts e to its midpoint moved onto the skin, when the link condition holds and no
    /// triangle around it turns over; then flips (diametric ball) around the merged vertex.
    bool contract(Edge e) {
        Halfedge h = SurfaceMesh::halfedge(e, 0);
        if (!mesh_.is_collapse_ok(h)) h = SurfaceMesh::twin(h);
        if (!mesh_.is_collapse_ok(h)) return false;
        const Vertex gone = mesh_.from_vertex(h), kept = mesh_.to_vertex(h);
        refresh_around({gone, kept}, 2);
        std::size_t cell = vcell_[kept.idx()];
        const Point3 m = project_to_skin(phi_, 0.5 * (mesh_.position(gone) + mesh_.position(kept)), t_, cell);
        if (!is_finite(m)) return false;
        const Vec3 grad = phi_.evaluate_in(cell, m).gradient;
        for (Vertex v : {gone, kept})
            for (Halfedge o : mesh_.outgoing_halfedges(v)) {
                const Face f = mesh_.face(o);
                if (!f.is_valid()) continue;
                auto fv = mesh_.face_vertices(f);
                if (std::count(fv.begin(), fv.end(), gone) + std::count(fv.begin(), fv.end(), kept) == 2) continue;
                const Vec3 before = triangle_normal_raw(mesh_.position(fv[0]), mesh_.position(fv[1]), mesh_.position(fv[2]));
                std::array<Point3, 3> after;
                for (int i = 0; i < 3; ++i) after[i] = (fv[i] == gone || fv[i] == kept) ? m : mesh_.position(fv[i]);
                const Vec3 n = triangle_normal_raw(after[0], after[1], after[2]);
                if (dot(n, before) <= 0 || dot(n, grad) <= 0) return false;
            }
        mesh_.collapse(h);
        mesh_.position(kept) = m;
        vt_[kept.idx()] = t_;
        vcell_[kept.idx()] = cell;
        ++c().contractions;
        // The merged vertex moved: every element around it is new (the lemmas covered the
        // old positions only).
        forget_star(kept);
        flip_around(kept);
        recheck_around({kept}, "contraction");
        return true;
    }

    void forget_star(Vertex v) {
        fit_arrays();
        for (Halfedge h : mesh_.outgoing_halfedges(v)) {
            edges_[SurfaceMesh::edge(h).idx()].checked = false;
            if (mesh_.face(h).is_valid()) faces_[mesh_.face(h).idx()].checked = false;
        }
    }

    void flip_around(Vertex v) {
        std::vector<Edge> seeds;
        for (Halfedge h : mesh_.outgoing_halfedges(v)) {
            seeds.push_back(SurfaceMesh::edge(h));
            seeds.push_back(SurfaceMesh::edge(mesh_.next(h)));
        }
        FlipOptions fo;
        fo.rule = FlipRule::DiametricBall;
        c().flips += flip_from(mesh_, seeds, fo).flips;
    }

    /// Inserts the point where the normal line through f's circumcentre meets the skin (here:
    /// the circumcentre moved onto the skin along ∇Φ), by the deforming mesh's Add.
    bool insert(Face f) {
        const auto v = mesh_.face_vertices(f);
        refresh_around({v[0], v[1], v[2]}, 2);
        const Point3 a = mesh_.position(v[0]), b = mesh_.position(v[1]), p = mesh_.position(v[2]);
        std::size_t cell = vcell_[v[0].idx()];
        const double R = circumradius(a, b, p);
        const Point3 cc = circumcenter(a, b, p);  // not finite for a degenerate triangle
        Point3 target = is_finite(cc) ? project_to_skin(phi_, cc, t_, cell) : cc;
        if (!is_finite(target) || !(norm(target - cc) <= 2 * R)) {
            cell = vcell_[v[0].idx()];
            target = project_to_skin(phi_, (a + b + p) / 3.0, t_, cell);
        }
        if (!is_finite(target)) return false;
        // The triangle nearest to the new point, among those two rings around f.
        Face nearest = f;
        double best = kInf;
        std::unordered_set<std::uint32_t> seen;
        std::vector<Vertex> ring(v.begin(), v.end());
        for (int k = 0; k < 2; ++k) {
            std::vector<Vertex> next;
            for (Vertex u : ring)
                for (Halfedge h : mesh_.outgoing_halfedges(u)) {
                    const Face g = mesh_.face(h);
                    if (g.is_valid() && seen.insert(g.idx()).second) {
                        const auto gv = mesh_.face_vertices(g);
                        const double d = sq_dist_to_triangle(target, mesh_.position(gv[0]), mesh_.position(gv[1]),
                                                             mesh_.position(gv[2]));
                        if (d < best) {
                            best = d;
                            nearest = g;
                        }
                    }
                    next.push_back(mesh_.to_vertex(h));
                }
            ring.swap(next);
        }
        for (Vertex u : mesh_.face_vertices(nearest))
            if (blocking(u) >= 0) return false;
        const AddResult r = add_point(mesh_, target, nearest, {.rule = FlipRule::DiametricBall});
        if (r.kind == AddCase::Vertex) return false;
        fit_arrays();
        vt_[r.vertex.idx()] = t_;
        vcell_[r.vertex.idx()] = cell;
        vtag_[r.vertex.idx()] = -1;
        ++c().insertions;
        c().flips += r.flips;
        recheck_around({r.vertex}, "insertion");
        return true;
    }

    // ---- topology ----------------------------------------------------------------------------
    void birth(std::uint32_t id) {
        const Surgery& s = surgeries_[id];
        const double radius = std::sqrt(std::max(0.0, (t_ - s.W) / 2));
        const TriangleSoup ico = unit_icosphere(2);
        std::vector<Vertex> vs;
        for (const Point3& p : ico.points) vs.push_back(new_vertex(s.z + radius * p, s.simplex, t_, -1));
        std::vector<std::array<Vertex, 3>> tris;
        for (const auto& t : ico.triangles) tris.push_back({vs[t[0]], vs[t[1]], vs[t[2]]});
        const std::vector<Face> faces = mesh_.replace_faces({}, tris);
        ++c().births;
        fit_arrays();
        queue_faces_and_edges(faces, "birth");
        ensure_step();
    }

    /// The live vertices that may be within `radius` of z now (cached positions, plus the
    /// farthest a point can travel since its cache: √(Δt/2), §4.2), at their current positions.
    std::vector<Vertex> vertices_near(const Point3& z, double radius) {
        std::vector<Vertex> out;
        for (Vertex v : mesh_.vertices()) {
            const double slack = std::sqrt(std::abs(t_ - vt_[v.idx()]) / 2) + 1e-9 * radius;
            if (norm(mesh_.position(v) - z) > radius + slack) continue;
            if (norm(pos(v) - z) < radius) out.push_back(v);
        }
        return out;
    }

    void death(std::uint32_t id) {
        const Surgery& s = surgeries_[id];
        const double radius = std::sqrt(std::max(0.0, (s.W - t_) / 2));
        // The void: every component with a vertex this close to z_δ.
        std::vector<Vertex> near = vertices_near(s.z, 1.5 * radius + 1e-12);
        if (near.empty()) return;
        std::unordered_set<std::uint32_t> comp;
        std::vector<Vertex> stack = near;
        for (Vertex v : near) comp.insert(v.idx());
        while (!stack.empty()) {
            const Vertex v = stack.back();
            stack.pop_back();
            for (Halfedge h : mesh_.outgoing_halfedges(v))
                if (comp.insert(mesh_.to_vertex(h).idx()).second) stack.push_back(mesh_.to_vertex(h));
        }
        for (std::uint32_t vi : comp)
            if (norm(pos(Vertex(vi)) - s.z) > 3 * radius + 1e-12) {
                remesh("a dying void is not a small sphere");
                return;
            }
        std::unordered_set<std::uint32_t> fs;
        for (std::uint32_t vi : comp)
            for (Halfedge h : mesh_.outgoing_halfedges(Vertex(vi)))
                if (mesh_.face(h).is_valid()) fs.insert(mesh_.face(h).idx());
        std::vector<Face> faces;
        for (std::uint32_t fi : fs) faces.push_back(Face(fi));
        (void)mesh_.replace_faces(faces, {});
        ++c().deaths;
    }

    static const char* event_name(const Surgery& s) { return s.dim == 1 ? "neck" : "tunnel"; }

    void surgery_on(std::uint32_t id) {
        Surgery& s = surgeries_[id];
        if (s.cancelled) return;
        // The ball of §3.3 first, then smaller ones (more than two loops), then larger ones:
        // a critical point whose cell is tiny next to the mesh there (a near-degenerate
        // simplex) has no vertex in its ball, and the cut must reach the mesh around it.
        std::vector<double> radii{s.r, 0.8 * s.r, 0.64 * s.r};
        for (double grow = 1.5; radii.size() < 24; grow *= 1.5) radii.push_back(grow * s.r);
        for (double r : radii) {
            const std::vector<Vertex> inside = vertices_near(s.z, r);
            if (inside.empty()) continue;
            std::unordered_set<std::uint32_t> fs;
            for (Vertex v : inside)
                for (Halfedge h : mesh_.outgoing_halfedges(v))
                    if (mesh_.face(h).is_valid()) fs.insert(mesh_.face(h).idx());
            std::vector<Face> cut;
            for (std::uint32_t fi : fs) cut.push_back(Face(fi));
            if (apply_template(s, id, cut, t_)) {
                s.active = true;
                return;
            }
        }
        if (s.r < floor_) {
            // No template fits and the event is smaller than the mesh resolves: the mesh is
            // rebuilt once the skin has passed the critical point (at t_off), with the new
            // topology, rather than now, before it.
            s.remesh_at_off = true;
            return;
        }
        remesh(std::string(event_name(s)) + " at z = (" + std::to_string(s.z.x) + ", " +
               std::to_string(s.z.y) + ", " + std::to_string(s.z.z) + "), r = " + std::to_string(s.r) +
               ": no template fits (" + last_template_failure_ + ")");
        s.cancelled = true;
    }

    void surgery_switch(std::uint32_t id) {
        Surgery& s = surgeries_[id];
        (s.dim == 1 ? c().necks : c().tunnels) += 1;
        if (s.remesh_at_off) return;  // rebuilt at t_off
        if (s.cancelled || !s.active) {
            if (!s.cancelled) remesh("the skin reached a critical point without surgery");
            s.cancelled = true;
            return;
        }
        std::vector<Face> cut = template_faces(id);
        const double eta = 1e-3 * (s.t_off - s.W);
        if (!apply_template(s, id, cut, s.W + eta)) {
            remesh("the template could not be swapped");
            s.cancelled = true;
        }
    }

    void surgery_off(std::uint32_t id) {
        Surgery& s = surgeries_[id];
        if (s.remesh_at_off && !s.cancelled) {
            // Right after the critical point the static mesher may still see the pinch: then
            // it tries again when the skin is twice as far past it.
            std::string failure;
            if (rebuild(std::string(event_name(s)) + " smaller than the floor (r = " +
                            std::to_string(s.r) + "), after it",
                        t_, failure)) {
                s.remesh_at_off = false;
                return;
            }
            const double next = t_ + std::max(t_ - s.W, 1e-9 * (1 + std::abs(t_)));
            if (next > report_.t_end || ++s.remesh_attempts > 40)
                throw InternalError("grow_skin: remeshing after the critical point at t = " + std::to_string(s.W) +
                                    " failed: " + failure);
            push(next, Kind::SurgeryOff, id);
            return;
        }
        if (s.cancelled || !s.active) return;
        // Its elements were exempt: their exemption clears now, so they count as new (§8
        // correction 2), whatever state they had before the template.
        fit_arrays();
        for (Face f : template_faces(id)) {
            faces_[f.idx()].checked = false;
            for (Edge e : face_edges(f)) edges_[e.idx()].checked = false;
        }
        std::vector<Vertex> region;
        for (Vertex v : mesh_.vertices())
            if (vtag_[v.idx()] == static_cast<int>(id)) {
                vtag_[v.idx()] = -1;
                region.push_back(v);
            }
        s.active = false;
        for (Vertex v : region) recheck_around({v}, "dissolution", true);
    }

    std::vector<Face> template_faces(std::uint32_t id) const {
        std::unordered_set<std::uint32_t> fs;
        for (Vertex v : mesh_.vertices())
            if (vtag_[v.idx()] == static_cast<int>(id))
                for (Halfedge h : mesh_.outgoing_halfedges(v))
                    if (mesh_.face(h).is_valid()) fs.insert(mesh_.face(h).idx());
        std::vector<Face> out;
        for (std::uint32_t fi : fs) out.push_back(Face(fi));
        return out;
    }

    /// Replaces `cut` (a region around s.z with two boundary loops) by the template of the
    /// phase at time `at`, its new vertices tagged with the surgery.
    bool apply_template(const Surgery& s, std::uint32_t id, const std::vector<Face>& cut, double at) {
        std::vector<std::vector<Vertex>> loops;
        if (!boundary_loops(mesh_, cut, loops)) {
            last_template_failure_ = "the cut region's boundary is not simple";
            return false;
        }
        if (loops.size() != 2) {
            last_template_failure_ = std::to_string(loops.size()) + " boundary loops";
            return false;
        }
        for (auto& loop : loops)
            for (Vertex v : loop) (void)pos(v);
        TemplatePlan plan;
        if (!plan_template(s, at, loops, [&](Vertex v) { return mesh_.position(v); }, plan)) {
            last_template_failure_ = "the loops are not on both sides of the waist, or do not wind around the axis";
            return false;
        }
        for (const Point3& p : plan.points)
            if (!is_finite(p)) {
                last_template_failure_ = "a template vertex is not finite";
                return false;
            }
        std::vector<Vertex> created;
        for (const Point3& p : plan.points) created.push_back(new_vertex(p, s.simplex, at, static_cast<int>(id)));
        std::vector<std::array<Vertex, 3>> tris;
        for (const auto& t : plan.triangles) {
            std::array<Vertex, 3> tv;
            for (int i = 0; i < 3; ++i) tv[i] = t[i].is_new ? created[t[i].index] : t[i].vertex;
            tris.push_back(tv);
        }
        try {
            (void)mesh_.replace_faces(cut, tris);
        } catch (const InvalidInput& e) {
            last_template_failure_ = e.what();
            for (Vertex v : created) mesh_.remove_isolated_vertex(v);
            return false;
        }
        fit_arrays();
        return true;
    }

    /// The fallback of §3.3: the whole mesh rebuilt by the static mesher at the current time.
    void remesh(const std::string& why) {
        // Next to a critical point the static mesher may not resolve the pinch: mesh a little
        // earlier instead, and let the vertices flow to now.
        const double h = 1e-3 * (report_.t_end - report_.t_start);
        std::string failure;
        for (int attempt = 0; attempt < 5; ++attempt)
            if (rebuild(why, attempt == 0 ? t_ : t_ - h * double(1 << (attempt - 1)), failure)) return;
        throw InternalError("grow_skin: remeshing at t = " + std::to_string(t_) + " (" + why + ") failed: " + failure);
    }

    /// The whole mesh replaced by the static mesh at time `at` (≤ now), its vertices flowing to
    /// now; false (mesh unchanged, `failure` set) when the static mesher fails there.
    bool rebuild(const std::string& why, double at, std::string& failure) {
        SkinMeshOptions mo;
        mo.time = at;
        mo.quality = q_;
        mo.rho_floor_factor = o_.rho_floor_factor;
        SkinMeshResult r;
        try {
            r = mesh_skin(phi_, mo);
        } catch (const Error& e) {
            failure = e.what();
            return false;
        }
        ++c().fallbacks;
        if (report_.fallback_reasons.size() < 10)
            report_.fallback_reasons.push_back("t = " + std::to_string(t_) + ": " + why);
        mesh_ = std::move(r.mesh);
        vt_.assign(mesh_.vertices_size(), at);
        vtag_.assign(mesh_.vertices_size(), -1);
        vcell_.assign(mesh_.vertices_size(), 0);
        std::size_t hint = 0;
        for (Vertex v : mesh_.vertices()) {
            hint = phi_.locate(mesh_.position(v), hint);
            vcell_[v.idx()] = hint;
        }
        edges_.assign(mesh_.edges_size(), {});
        faces_.assign(mesh_.faces_size(), {});
        // Entries of the old mesh are stale: their versions are far ahead of the new ones.
        ++epoch_;
        for (auto& st : edges_) st.version = epoch_ << 20;
        for (auto& st : faces_) st.version = epoch_ << 20;
        for (auto& s : surgeries_)
            if (s.active) {
                s.active = false;
                s.cancelled = true;
            }
        pending_.clear();
        for (Edge e : mesh_.edges()) pending_.push_back({false, e.idx(), "remesh"});
        for (Face f : mesh_.faces()) pending_.push_back({true, f.idx(), "remesh"});
        ensure_step();
        return true;
    }

    // ---- every-step scheduling ---------------------------------------------------------------
    void ensure_step() {
        if (o_.schedule != SkinSchedule::EveryStep || step_pending_) return;
        step_pending_ = true;
        push(t_, Kind::Step, 0);
    }

    void step() {
        step_pending_ = false;
        step_min_ = kInf;
        ++c().steps;
        for (Edge e : mesh_.edges()) pending_.push_back({false, e.idx(), "flip"});
        drain();
        for (Face f : mesh_.faces()) pending_.push_back({true, f.idx(), "flip"});
        drain();
        if (mesh_.n_faces() == 0) return;
        if (o_.fixed_step > 0) {
            step_pending_ = true;
            push(t_ + o_.fixed_step, Kind::Step, 0);
            return;
        }
        if (!std::isfinite(step_min_)) return;
        step_pending_ = true;
        push(t_ + std::max(step_min_, 1e-15 * (1 + std::abs(t_))), Kind::Step, 0);
    }

    // ---- output ------------------------------------------------------------------------------
    /// Before a snapshot: triangles (not exempt) whose normal points against ∇Φ at the foot of
    /// their centroid form a fold, which the local operations cannot undo (a contraction next
    /// to it is refused, as it would turn a triangle over): the mesh is rebuilt (a fallback).
    void unfold() {
        std::size_t inward = 0;
        for (Face f : mesh_.faces()) {
            if (exempt(f)) continue;
            const auto v = mesh_.face_vertices(f);
            const Point3 a = pos(v[0]), b = pos(v[1]), c = pos(v[2]);
            std::size_t cell = vcell_[v[0].idx()];
            const Point3 foot = project_to_skin(phi_, (a + b + c) / 3.0, t_, cell);
            if (!is_finite(foot)) continue;
            if (dot(cross(b - a, c - a), phi_.evaluate(foot, cell).gradient) <= 0) ++inward;
        }
        if (inward > 0) remesh(std::to_string(inward) + " triangle(s) turned inward at a snapshot");
    }

    SkinSnapshot snapshot() {
        SkinSnapshot out;
        out.time = t_;
        for (Vertex v : mesh_.vertices()) (void)pos(v);
        SurfaceMesh copy = mesh_;
        auto rho = copy.add_vertex_property<double>("skin:rho", 0.0);
        auto ex = copy.add_face_property<char>("skin:exempt", 0);
        for (Vertex v : mesh_.vertices()) rho[v] = rho_at(mesh_.position(v), vcell_[v.idx()]);
        for (Face f : mesh_.faces()) ex[f] = exempt(f) ? 1 : 0;
        copy.garbage_collection();
        rho = copy.get_vertex_property<double>("skin:rho");
        ex = copy.get_face_property<char>("skin:exempt");
        for (Vertex v : copy.vertices()) out.rho.push_back(rho[v]);
        for (Face f : copy.faces()) out.exempt.push_back(ex[f] != 0);
        copy.remove_property(rho);
        copy.remove_property(ex);
        out.mesh = std::move(copy);
        return out;
    }

    const SkinFunction& phi_;
    SkinGrowthOptions o_;
    SkinQuality q_;
    double floor_ = 0;
    double t_ = 0;
    SurfaceMesh mesh_;
    std::vector<double> vt_;
    std::vector<std::size_t> vcell_;
    std::vector<int> vtag_;
    std::vector<ElementState> edges_, faces_;
    std::vector<Surgery> surgeries_;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap_;
    double step_min_ = kInf;
    bool step_pending_ = false;
    std::uint32_t epoch_ = 0;
    std::string last_template_failure_ = "no vertex in the ball";
    SkinGrowthReport report_;
};

}  // namespace

double skin_growth_start(const SkinFunction& phi, const SkinGrowthOptions& options) {
    (void)options;
    double w_max = -kInf;
    for (std::size_t i = 0; i < phi.input_balls(); ++i) w_max = std::max(w_max, phi.balls()[i].weight);
    return -w_max;
}

SkinGrowthResult grow_skin(const SkinFunction& phi, const SkinGrowthOptions& options) {
    Grower g(phi, options);
    return g.run();
}

}  // namespace dynmesh
