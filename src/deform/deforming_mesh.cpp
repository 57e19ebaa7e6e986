#include "dynmesh/deform/deforming_mesh.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <cmath>
#include <numbers>
#include <numeric>
#include <unordered_set>

#include "dynmesh/deform/creases.hpp"
#include "dynmesh/deform/initial_mesh.hpp"
#include "dynmesh/deform/local_ops.hpp"
#include "dynmesh/deform/size_field.hpp"
#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/spatial_sort.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/metrics/self_intersection.hpp"
#include "dynmesh/reconstruct/advancing_front.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "max_tree.hpp"
#include "rigid_fit.hpp"
#include "star_intersection.hpp"

namespace dynmesh {

using Clock = std::chrono::steady_clock;

std::string_view to_string(Violation v) {
    switch (v) {
        case Violation::DisplacementExceedsLambda: return "displacement_exceeds_lambda";
        case Violation::StepTooShort: return "step_too_short";
        case Violation::EdgeAngleBelow90: return "edge_angle_below_90";
        case Violation::NormalInverted: return "normal_inverted";
        case Violation::CircumradiusGrowth: return "circumradius_growth";
        case Violation::RefineCapHit: return "refine_cap_hit";
        case Violation::DeletionCapHit: return "deletion_cap_hit";
        case Violation::AddVertexCase: return "add_vertex_case";
        case Violation::FarSample: return "far_sample";
        case Violation::AddFolded: return "add_folded";
        case Violation::RemoveFailed: return "remove_failed";
        case Violation::NonEmptyBall: return "non_empty_ball";
        case Violation::Rebuild: return "rebuild";
        case Violation::TopologyRollback: return "rollback";
        case Violation::Coarsened: return "coarsened";
        case Violation::InitFallback: return "init_fallback";
        case Violation::SubstepCapHit: return "substep_cap_hit";
    }
    return "unknown";
}

UpdateCounters& UpdateCounters::operator+=(const UpdateCounters& o) {
    flips += o.flips;
    insertions += o.insertions;
    removals += o.removals;
    dormant_moves += o.dormant_moves;
    refine_passes += o.refine_passes;
    deletion_iterations += o.deletion_iterations;
    spacing_repairs += o.spacing_repairs;
    flip_refusals += o.flip_refusals;
    samples_inserted += o.samples_inserted;
    samples_deleted += o.samples_deleted;
    rebuilds += o.rebuilds;
    rollbacks += o.rollbacks;
    distance_evals += o.distance_evals;
    seconds += o.seconds;
    return *this;
}

namespace {

enum class State : std::uint8_t { Dead, Pending, Dormant, Vertex };

/// L3.6's bound on R(t) / R(t1) between steps, for kappa > 348; a practical monitor
/// threshold (2) below that, where the lemma gives no bound.
double growth_bound(double kappa) {
    if (kappa > 348.0) return (kappa * kappa - 144.0) / (kappa * (kappa - 348.0));
    return 2.0;
}

std::string id_str(SampleId id) { return "sample " + std::to_string(id); }

constexpr std::uint32_t kNoSlot = std::numeric_limits<std::uint32_t>::max();

/// The squared circumradius of face f (infinite for a degenerate triangle, 0 for NaN
/// positions), from R^2 = |ab|^2 |bc|^2 |ca|^2 / (4 |ab x ac|^2).
double circumradius2(const SurfaceMesh& m, Face f) {
    const auto vs = m.face_vertices(f);
    const Point3 &a = m.position(vs[0]), &b = m.position(vs[1]), &c = m.position(vs[2]);
    const Vec3 ab = b - a, ac = c - a, bc = c - b;
    const double den = 4 * sqnorm(cross(ab, ac));
    const double num = sqnorm(ab) * sqnorm(bc) * sqnorm(ac);
    const double r2 = den > 0 ? num / den : std::numeric_limits<double>::infinity();
    return r2 >= 0 ? r2 : 0.0;
}

/// The largest triangle circumradius of m (infinite for a degenerate triangle).
double largest_circumradius(const SurfaceMesh& m) {
    double r2max = 0;
    for (Face f : m.faces()) r2max = std::max(r2max, circumradius2(m, f));
    return std::sqrt(r2max);
}

}  // namespace

/// Inside Impl a sample is named by its slot: its rank along the Morton curve of P(0) (samples
/// inserted later take the next slots), so that loops over samples and mesh vertices (which
/// canonicalize() numbers in slot order) visit the surface in a spatially coherent order.
/// ext[slot] is the caller's SampleId; every message and accessor translates.
struct DeformingMesh::Impl {
    DeformOptions params;
    InitReport init;
    std::vector<SampleId> ext;         ///< slot -> SampleId
    std::vector<std::uint32_t> slot_of;  ///< SampleId -> slot
    std::vector<Point3> pos;
    std::vector<State> state;
    std::vector<SampleId> owner;            ///< for a dormant sample: its owner's id
    std::vector<std::vector<SampleId>> dl;  ///< dormant list of a vertex sample
    std::vector<std::uint32_t> dpos;        ///< index of a dormant sample in its owner's list
    std::vector<Vertex> vert_of;
    SurfaceMesh mesh;
    VertexProperty<SampleId> vsample;
    std::vector<SampleId> pending_insert;
    std::vector<SampleId> pending_delete;
    std::vector<char> marked;  ///< samples to delete (during Deletion)
    long long euler = 2;
    std::size_t components = 1;
    int t = 0;
    int next = 0;
    double R_last = 0;
    std::vector<Vec3> ref_normals;  ///< face normals at the end of the last update
    std::vector<ViolationRecord> violations;
    std::vector<ViolationRecord> pending_violations;  ///< collected during one call
    UpdateCounters totals;
    UpdateCounters cur;
    std::size_t n_updates = 0;
    bool emergency_requested = false;
    std::size_t folded_at_step = 0;
    std::size_t live = 0;

    /// Samples whose Add was refused during the current update (far from the mesh, on a
    /// vertex, folding the mesh or making it intersect itself): RefineVert does not promote
    /// them again until the next update, so a refusal costs one try, not one per pass.
    std::vector<char> refused;
    std::vector<SampleId> refused_ids;  // the slots set in `refused`
    void refuse(SampleId p) {
        if (!refused[p]) refused_ids.push_back(p);
        refused[p] = 1;
    }
    void clear_refused() {
        for (SampleId p : refused_ids)
            if (p < refused.size()) refused[p] = 0;
        refused_ids.clear();
    }
    /// size_factor * lfs of each slot, graded (+inf: no bound; NaN: not yet known, a sample
    /// inserted after t = 0 until it is placed). Read only when size_on.
    std::vector<double> size;
    bool size_on = false;  ///< a size field was set up at t = 0
    /// The mesh intersected itself at the end of the last unit (intersection_checks): a
    /// unit that starts so is not retried for it.
    bool intersecting = false;
    /// The last global flip converged and the mesh has changed since only by Add and Remove,
    /// which flip locally from every edge they touch (Lawson propagation): a global flip
    /// would find nothing to do. Cleared when the vertices move or a mesh is installed.
    /// (Not quite: an edge refused as DiagonalExists can become flippable when a local flip
    /// elsewhere removes that diagonal, and only a global flip would see it; rare, and the
    /// ball diagnostic reports any ball it leaves non-empty.)
    bool flips_settled = false;

    /// Creases (spec §10.3; DeformOptions::feature_angle_deg): the polylines of crease
    /// samples (slots, in order; corners at the ends), each crease sample's polyline and
    /// rank, and the corners with their number of crease edges. The mesh marks the crease
    /// edges in kLockedEdges: consecutive vertices of each polyline.
    std::vector<std::vector<SampleId>> lines;
    std::vector<char> line_closed;
    std::vector<std::uint32_t> crease_line;  ///< per slot (kNoSlot: none, or a corner)
    std::vector<std::uint32_t> crease_rank;
    std::vector<std::uint8_t> corner_degree;  ///< per slot, > 0 for a corner
    bool creases_on = false;
    /// The local size of a sample against the pass-level R: min(R, size) (R when off).
    [[nodiscard]] double rs(SampleId s, double R) const {
        return !size_on || !(size[s] < R) ? R : size[s];
    }
    /// Gives a sample inserted after t = 0 its size from its nearest vertex w at distance d.
    void inherit_size(SampleId p, SampleId w, double d) {
        if (size_on && std::isnan(size[p]))
            size[p] = w == kNoSample ? std::numeric_limits<double>::infinity() : size[w] + params.grading * d;
    }

    // ---- small helpers --------------------------------------------------------------------
    void violation(Violation kind, std::string detail) {
        ViolationRecord r{t, kind, std::move(detail)};
        violations.push_back(r);
        pending_violations.push_back(std::move(r));
    }
    [[nodiscard]] SampleId sid(Vertex v) const { return vsample[v]; }
    [[nodiscard]] std::string idstr(std::uint32_t s) const { return id_str(ext[s]); }
    /// "(a, b, c)": the SampleIds of a face's vertices.
    [[nodiscard]] std::string face_str(Face f) const {
        const auto vs = mesh.face_vertices(f);
        return "(" + std::to_string(ext[sid(vs[0])]) + ", " + std::to_string(ext[sid(vs[1])]) + ", " +
               std::to_string(ext[sid(vs[2])]) + ")";
    }
    [[nodiscard]] const Point3& P(SampleId s) const { return pos[s]; }

    /// A new slot for the next SampleId.
    std::uint32_t new_slot() {
        const auto slot = static_cast<std::uint32_t>(pos.size());
        slot_of.push_back(slot);
        ext.push_back(static_cast<SampleId>(slot_of.size() - 1));
        grow(pos.size() + 1);
        return slot;
    }
    void grow(std::size_t n) {
        refused.resize(n, 0);
        crease_line.resize(n, std::numeric_limits<std::uint32_t>::max());
        crease_rank.resize(n, 0);
        corner_degree.resize(n, 0);
        size.resize(n, std::numeric_limits<double>::quiet_NaN());
        pos.resize(n);
        state.resize(n, State::Dead);
        owner.resize(n, kNoSample);
        dl.resize(n);
        dpos.resize(n, 0);
        vert_of.resize(n);
        marked.resize(n, 0);
    }

    void attach(SampleId p, SampleId w) {
        if (p < strain_d.size()) strain_d[p] = 0;  // a new pair
        state[p] = State::Dormant;
        owner[p] = w;
        dpos[p] = static_cast<std::uint32_t>(dl[w].size());
        dl[w].push_back(p);
        ++cur.dormant_moves;
    }
    void detach(SampleId p) {
        auto& list = dl[owner[p]];
        const std::uint32_t i = dpos[p];
        list[i] = list.back();
        dpos[list[i]] = i;
        list.pop_back();
        owner[p] = kNoSample;
    }
    void make_vertex(SampleId s, Vertex v) {
        if (!region.empty() && !region[s]) {  // a local update's new vertex is in its region
            region[s] = 1;
            region_ids.push_back(s);
        }
        state[s] = State::Vertex;
        owner[s] = kNoSample;
        vert_of[s] = v;
        vsample[v] = s;
    }

    // ---- what changed in the mesh since a reader last looked ---------------------------------
    /// The mesh logs the faces it changes (SurfaceMesh::face_log()), and moved_log the
    /// vertices moved. A reader (the circumradius tree, the normals and strains at the end of
    /// an update) keeps a Cursor and takes the changes since; `gen` advances when every face
    /// may have changed (a renumbering, a new mesh, every vertex moved), and a reader then
    /// starts over.
    struct Cursor {
        std::uint64_t gen = 0;
        std::size_t faces = 0, moved = 0;
    };
    std::uint64_t gen = 1;
    std::vector<Vertex> moved_log;
    void all_changed() {
        ++gen;
        mesh.clear_face_log();
        moved_log.clear();
    }
    /// Calls f(face) for every face changed since `c` (made, relinked, deleted, or with a
    /// moved vertex; possibly more than once) and returns true, or returns false without a
    /// call when everything may have changed since. Brings `c` up to now.
    template <class F>
    bool changes_since(Cursor& c, F&& f) const {
        const std::vector<std::uint32_t>& log = mesh.face_log();
        const bool known = c.gen == gen && c.faces <= log.size() && c.moved <= moved_log.size();
        if (known) {
            for (std::size_t i = c.faces; i < log.size(); ++i) f(Face(log[i]));
            for (std::size_t i = c.moved; i < moved_log.size(); ++i) {
                const Vertex v = moved_log[i];
                if (mesh.is_deleted(v)) continue;  // its faces were logged when it went
                for (Halfedge h : mesh.outgoing_halfedges(v))
                    if (const Face g = mesh.face(h); g.is_valid()) f(g);
            }
        }
        c = Cursor{gen, log.size(), moved_log.size()};
        return known;
    }

    /// Largest circumradius, from a max tree over the faces' squared circumradii kept current
    /// through changes_since().
    [[nodiscard]] double max_circumradius() const {
        const bool known = changes_since(r2_cursor, [&](Face f) {
            r2_tree.set(f.idx(), mesh.is_deleted(f) ? 0.0 : circumradius2(mesh, f));
        });
        if (!known) {
            std::vector<double> r2(mesh.faces_size(), 0.0);
            for (Face f : mesh.faces()) r2[f.idx()] = circumradius2(mesh, f);
            r2_tree.assign(r2);
        }
        return std::sqrt(r2_tree.max());
    }
    mutable Cursor r2_cursor;
    mutable detail::MaxTree r2_tree;

    /// `cell`, or when it is not positive and finite (R of a mesh with a degenerate triangle
    /// is infinite) the bounding-box diagonal of the vertices over the cube root of their
    /// count.
    [[nodiscard]] double grid_cell(double cell) const {
        if (std::isfinite(cell) && cell > 0) return cell;
        Bbox3 box;
        for (Vertex v : mesh.vertices()) box.extend(mesh.position(v));
        const double n = static_cast<double>(std::max<std::size_t>(1, mesh.n_vertices()));
        return std::max(box.diagonal() / std::cbrt(n), 1e-300);
    }
    /// Grid of the current vertices (ids = sample ids), cell grid_cell(cell).
    /// In a local update, only the vertices within kRegionMargin R of the region's box: the
    /// update's queries start near the region and find what they look for within a few R.
    PointGrid vertex_grid(double cell) const { return vertex_grid(cell, region_box()); }
    /// The same over the vertices in `box`.
    PointGrid vertex_grid(double cell, const Bbox3& box) const {
        std::vector<Vertex> vs;
        if (!locate(box, vs)) {
            vs.reserve(mesh.n_vertices());
            for (Vertex v : mesh.vertices())
                if (box.contains(mesh.position(v))) vs.push_back(v);
        }
        return PointGrid::bulk(grid_cell(cell), vs.size(), [&](std::size_t k) { return mesh.position(vs[k]); },
                               [&](std::size_t k) { return sid(vs[k]); });
    }

    /// A grid of every vertex (by sample id) kept across updates, so that the work of a local
    /// update finds the vertices in its box without a pass over the mesh: brought up to date
    /// from the changes (the vertices of every face changed since) when read, built again
    /// when everything may have changed. A sample that stopped being a vertex may linger in
    /// it; readers keep only current vertices.
    struct Locator {
        PointGrid grid;
        std::vector<Point3> at;  // by slot: where the grid holds it
        std::vector<char> in;    // by slot: held
        Cursor cursor;
    };
    mutable Locator loc;
    /// Brings loc up to date.
    void locator_catch_up() const {
        const bool known = changes_since(loc.cursor, [&](Face f) {
            if (mesh.is_deleted(f)) return;
            for (Vertex v : mesh.face_vertices(f)) {
                const SampleId s = sid(v);
                const Point3& p = mesh.position(v);
                if (s >= loc.in.size()) {
                    loc.in.resize(state.size(), 0);
                    loc.at.resize(state.size());
                }
                if (loc.in[s]) {
                    if (loc.at[s] == p) continue;
                    loc.grid.erase(s, loc.at[s]);
                }
                loc.grid.insert(s, p);
                loc.at[s] = p;
                loc.in[s] = 1;
            }
        });
        if (known) return;
        loc.in.assign(state.size(), 0);
        loc.at.assign(state.size(), Point3{});
        std::vector<Vertex> vs;
        vs.reserve(mesh.n_vertices());
        for (Vertex v : mesh.vertices()) {
            vs.push_back(v);
            loc.in[sid(v)] = 1;
            loc.at[sid(v)] = mesh.position(v);
        }
        loc.grid = PointGrid::bulk(grid_cell(kLocatorCell * max_circumradius()), vs.size(),
                                   [&](std::size_t k) { return mesh.position(vs[k]); },
                                   [&](std::size_t k) { return sid(vs[k]); });
    }
    /// The locator's cell, in units of R.
    static constexpr double kLocatorCell = 4;
    /// The vertices in `box`, in index order, through the locator. False (and `out`
    /// untouched) when a pass over the vertices is cheaper: an unbounded box, or one that
    /// spans more cells than there are vertices.
    bool locate(const Bbox3& box, std::vector<Vertex>& out) const {
        if (!(std::isfinite(box.min.x) && std::isfinite(box.min.y) && std::isfinite(box.min.z) &&
              std::isfinite(box.max.x) && std::isfinite(box.max.y) && std::isfinite(box.max.z)))
            return false;
        if (box.min.x > box.max.x || box.min.y > box.max.y || box.min.z > box.max.z) return true;  // empty
        locator_catch_up();
        const Vec3 half = (box.max - box.min) * 0.5;
        const double r = std::max({half.x, half.y, half.z});
        const double side = 2 * r / loc.grid.cell() + 2;
        if (side * side * side > static_cast<double>(mesh.n_vertices())) return false;
        loc.grid.for_each_candidate((box.min + box.max) * 0.5, r, [&](std::uint32_t s) {
            if (state[s] != State::Vertex) return;
            const Vertex v = vert_of[s];
            if (box.contains(mesh.position(v))) out.push_back(v);
        });
        std::sort(out.begin(), out.end(), [](Vertex a, Vertex b) { return a.idx() < b.idx(); });
        return true;
    }

    /// The face nearest to p, among the faces around vertices within search radius r
    /// (growing), falling back to all faces.
    Face nearest_face(const Point3& p, const PointGrid& grid, double r, double* dist) {
        Face best;
        double bd = std::numeric_limits<double>::infinity();
        auto consider = [&](Face f) {
            const auto vs = mesh.face_vertices(f);
            const ClosestPoint cp = closest_point_on_triangle(p, mesh.position(vs[0]), mesh.position(vs[1]),
                                                              mesh.position(vs[2]));
            ++cur.distance_evals;
            if (cp.distance < bd || (cp.distance == bd && f.idx() < best.idx())) {
                bd = cp.distance;
                best = f;
            }
        };
        for (int round = 0; round < 4 && !best.is_valid(); ++round, r *= 2) {
            grid.for_each_candidate(p, r, [&](std::uint32_t s) {
                if (state[s] != State::Vertex) return;
                const Vertex v = vert_of[s];
                if (distance(mesh.position(v), p) > r) return;
                for (Halfedge h : mesh.outgoing_halfedges(v))
                    if (mesh.face(h).is_valid()) consider(mesh.face(h));
            });
        }
        if (!best.is_valid())
            for (Face f : mesh.faces()) consider(f);
        if (dist) *dist = bd;
        return best;
    }

    /// Makes sample p a vertex with Add (or keeps it dormant when Add refuses). The grid gets
    /// the new vertex.
    void add_sample(SampleId p, PointGrid& grid, double R) {
        double d = 0;
        const Face f = nearest_face(P(p), grid, 2 * R, &d);
        DYNMESH_ASSERT(f.is_valid(), "add_sample: no face");
        if (d > 2 * R) {
            const auto [w, dw] = grid.nearest(P(p), [&](std::uint32_t s) { return P(s); },
                                              [&](std::uint32_t s) { return state[s] == State::Vertex; });
            violation(Violation::FarSample, idstr(p) + " is " + std::to_string(d) +
                                                " from the mesh (R = " + std::to_string(R) + "); kept dormant");
            refuse(p);
            attach(p, w);
            return;
        }
        const Vec3 old_normal = face_normal(f);
        AddOptions ao;
        bool on_crease = crease_line[p] != kNoSlot;
        if (on_crease) {
            // A crease sample splits the crease edge between its polyline's neighbouring
            // vertices (spec §10.3); without that edge it waits.
            ao.split_edge = crease_edge_around(p);
            if (!ao.split_edge.is_valid()) {
                refuse(p);
                attach(p, grid.nearest(P(p), [&](std::uint32_t s) { return P(s); },
                                       [&](std::uint32_t s) { return state[s] == State::Vertex; }).first);
                return;
            }
        }
        AddResult r = add_point(mesh, P(p), f, ao);
        if (r.kind == AddCase::LockedEdge && !on_crease && adopt_into_crease(p, f)) {
            // A sample inserted on a crease edge after t = 0 is a crease sample: it splits it.
            on_crease = true;
            ao.split_edge = crease_edge_around(p);
            if (ao.split_edge.is_valid()) r = add_point(mesh, P(p), f, ao);
        }
        cur.flips += r.flips;
        if (r.kind == AddCase::Vertex || r.kind == AddCase::LockedEdge) {
            violation(Violation::AddVertexCase, idstr(p) + " falls on the vertex of " + idstr(sid(r.near_vertex)) +
                                                    (r.kind == AddCase::LockedEdge ? " or on its crease edge" : ""));
            refuse(p);
            attach(p, sid(r.near_vertex));
            return;
        }
        ++cur.insertions;
        make_vertex(p, r.vertex);
        const bool folded = star_folded(r.vertex, on_crease ? nullptr : &old_normal);
        if (folded || star_intersects(r.vertex, grid, R)) {
            // Sparse samples or thin parts only (the theory rules it out): take the vertex out
            // again.
            violation(Violation::AddFolded, idstr(p) + (folded ? " would fold the mesh" : " would make the mesh intersect itself") +
                                                "; kept dormant");
            refuse(p);
            if (remove_sample(p, nullptr)) {
                const auto [w, dw] = grid.nearest(P(p), [&](std::uint32_t s) { return P(s); },
                                                  [&](std::uint32_t s) { return state[s] == State::Vertex; });
                attach(p, w);
                return;
            }
        }
        grid.insert(p, P(p));
    }

    /// star_intersects() with the candidates of `grid` (ids are samples): faces meeting v's
    /// star have their vertices within the star's longest edge plus 2 R of v.
    [[nodiscard]] bool star_intersects(Vertex v, const PointGrid& grid, double R) const {
        double longest = 0;
        for (Halfedge h : mesh.outgoing_halfedges(v)) {
            longest = std::max(longest, distance(mesh.position(v), mesh.position(mesh.to_vertex(h))));
            if (!mesh.is_boundary(h))
                longest = std::max(longest, distance(mesh.position(mesh.to_vertex(h)),
                                                     mesh.position(mesh.to_vertex(mesh.next(h)))));
        }
        return detail::star_intersects(mesh, v, grid, longest + 2 * R,
                                       [&](std::uint32_t s) { return state[s] == State::Vertex ? vert_of[s] : Vertex(); });
    }

    /// True when a triangle around v turns by 90 degrees or more against `reference` (when
    /// given) or against the triangle across one of v's spokes, crease edges excepted.
    bool star_folded(Vertex v, const Vec3* reference) const {
        const auto locked = locked_edges(mesh);
        for (Halfedge h : mesh.outgoing_halfedges(v)) {
            const Face f = mesh.face(h), g = mesh.face(SurfaceMesh::twin(h));
            if (!f.is_valid()) continue;
            const Vec3 n = face_normal(f);
            if (reference && !(dot(n, *reference) > 0)) return true;
            if (g.is_valid() && !(locked.is_valid() && locked[SurfaceMesh::edge(h)]) && !(dot(n, face_normal(g)) > 0))
                return true;
        }
        return false;
    }

    // ---- creases (spec §10.3) -----------------------------------------------------------------
    /// The nearest vertices (samples) of crease sample p's polyline on either side of it
    /// (kNoSample where there is none).
    [[nodiscard]] std::pair<SampleId, SampleId> crease_neighbours(SampleId p) const {
        const std::uint32_t c = crease_line[p];
        auto vertex_from = [&](std::ptrdiff_t step) {
            const std::ptrdiff_t i = next_line_vertex(c, static_cast<std::ptrdiff_t>(crease_rank[p]), step, p);
            return i < 0 ? kNoSample : lines[c][static_cast<std::size_t>(i)];
        };
        return {vertex_from(-1), vertex_from(+1)};
    }
    /// Walking polyline c from index i by `step` (+1 or -1; around a closed line), the index
    /// of the first vertex other than `skip`, or -1 at the line's end; `passed` (when given)
    /// receives the indices of the samples walked over before it.
    [[nodiscard]] std::ptrdiff_t next_line_vertex(std::uint32_t c, std::ptrdiff_t i, std::ptrdiff_t step,
                                                  SampleId skip = kNoSample,
                                                  std::vector<std::ptrdiff_t>* passed = nullptr) const {
        const auto& line = lines[c];
        const auto n = static_cast<std::ptrdiff_t>(line.size());
        for (std::ptrdiff_t k = 0; k < n; ++k) {
            i += step;
            if (line_closed[c]) i = (i + n) % n;
            if (i < 0 || i >= n) return -1;
            const SampleId x = line[static_cast<std::size_t>(i)];
            if (x != skip && state[x] == State::Vertex) return i;
            if (passed) passed->push_back(i);
        }
        return -1;
    }
    /// Patch of every face: the components of the faces joined across edges that are no
    /// crease (empty without creases).
    [[nodiscard]] std::vector<std::uint32_t> face_patches() const {
        const auto locked = locked_edges(mesh);
        if (!creases_on || !locked.is_valid()) return {};
        std::vector<std::uint32_t> patch(mesh.faces_size(), kNoSlot);
        std::vector<Face> stack;
        std::uint32_t next_id = 0;
        for (Face f : mesh.faces()) {
            if (patch[f.idx()] != kNoSlot) continue;
            patch[f.idx()] = next_id;
            stack.push_back(f);
            while (!stack.empty()) {
                const Face g = stack.back();
                stack.pop_back();
                const Halfedge h0 = mesh.halfedge(g);
                for (Halfedge h : {h0, mesh.next(h0), mesh.prev(h0)}) {
                    const Face n = mesh.face(SurfaceMesh::twin(h));
                    if (!n.is_valid() || locked[SurfaceMesh::edge(h)] || patch[n.idx()] != kNoSlot) continue;
                    patch[n.idx()] = next_id;
                    stack.push_back(n);
                }
            }
            ++next_id;
        }
        return patch;
    }
    /// The crease edge a dormant crease sample p lies on: the mesh edge between the nearest
    /// vertices of its polyline on either side (invalid when there is no such locked edge).
    [[nodiscard]] Edge crease_edge_around(SampleId p) const {
        const auto [sa, sb] = crease_neighbours(p);
        if (sa == kNoSample || sb == kNoSample || sa == sb) return Edge();
        const Vertex a = vert_of[sa], b = vert_of[sb];
        const Halfedge h = mesh.find_halfedge(a, b);
        const auto locked = locked_edges(mesh);
        if (!h.is_valid() || !locked.is_valid() || !locked[SurfaceMesh::edge(h)]) return Edge();
        return SurfaceMesh::edge(h);
    }

    /// Makes p, which lies on a crease edge of face f (add_point() said AddCase::LockedEdge),
    /// a sample of that crease: it joins the polyline between the edge's two ends, among the
    /// dormant samples there in the order of their projections on the edge. False when f has
    /// no crease edge or its polyline is not found.
    bool adopt_into_crease(SampleId p, Face f) {
        const auto locked = locked_edges(mesh);
        if (!creases_on || !locked.is_valid()) return false;
        Halfedge best;
        double bd = std::numeric_limits<double>::infinity();
        const Halfedge h0 = mesh.halfedge(f);
        for (Halfedge h : {h0, mesh.next(h0), mesh.prev(h0)}) {
            if (!locked[SurfaceMesh::edge(h)]) continue;
            const Point3 &x = mesh.position(mesh.from_vertex(h)), &y = mesh.position(mesh.to_vertex(h));
            const double d = distance(P(p), x + (y - x) * segment_parameter(P(p), x, y));
            if (d < bd) {
                bd = d;
                best = h;
            }
        }
        if (!best.is_valid()) return false;
        const SampleId a = sid(mesh.from_vertex(best)), b = sid(mesh.to_vertex(best));
        for (std::uint32_t c = 0; c < lines.size(); ++c) {
            if (crease_line[a] != kNoSlot && crease_line[a] != c) continue;
            if (crease_line[b] != kNoSlot && crease_line[b] != c) continue;
            auto& line = lines[c];
            const auto n = static_cast<std::ptrdiff_t>(line.size());
            for (std::ptrdiff_t ia = 0; ia < n; ++ia) {
                if (line[static_cast<std::size_t>(ia)] != a) continue;
                for (const std::ptrdiff_t step : {std::ptrdiff_t{1}, std::ptrdiff_t{-1}}) {
                    // The next vertex of the line from a must be b.
                    std::vector<std::ptrdiff_t> between;
                    const std::ptrdiff_t j = next_line_vertex(c, ia, step, kNoSample, &between);
                    if (j < 0 || line[static_cast<std::size_t>(j)] != b) continue;
                    const double tp = segment_parameter(P(p), P(a), P(b));
                    std::ptrdiff_t after = ia;  // p goes right after this index, walking by step
                    for (std::ptrdiff_t q : between)
                        if (segment_parameter(P(line[static_cast<std::size_t>(q)]), P(a), P(b)) < tp) after = q;
                    const std::ptrdiff_t at = step > 0 ? after + 1 : after;  // vector position
                    line.insert(line.begin() + at, p);
                    crease_line[p] = c;
                    for (std::uint32_t k = 0; k < line.size(); ++k)
                        if (corner_degree[line[k]] == 0) crease_rank[line[k]] = k;
                    return true;
                }
            }
        }
        return false;
    }

    /// Marks the creases of `m` (feature_angle_deg) and records their polylines over the
    /// samples; vertex_slot(v) is the slot of a vertex of m, or kNoSlot when it is no sample
    /// (the polyline then skips it). Returns the crease edge count (0: creases stay off).
    template <class VertexSlot>
    std::size_t setup_creases(SurfaceMesh& m, VertexSlot&& vertex_slot) {
        const Creases c = mark_creases(m, {.feature_angle_deg = params.feature_angle_deg});
        const auto locked = locked_edges(m);
        for (Vertex v : c.corners)
            if (const std::uint32_t s = vertex_slot(v); s != kNoSlot)
                corner_degree[s] = static_cast<std::uint8_t>(std::min<std::size_t>(255, locked_degree(m, locked, v)));
        for (const auto& poly : c.lines) {
            const bool closed = poly.size() > 2 && poly.front() == poly.back();
            std::vector<SampleId> line;
            for (std::size_t i = 0; i + (closed ? 1 : 0) < poly.size(); ++i)
                if (const std::uint32_t s = vertex_slot(poly[i]); s != kNoSlot) line.push_back(s);
            const auto id = static_cast<std::uint32_t>(lines.size());
            for (std::uint32_t k = 0; k < line.size(); ++k)
                if (corner_degree[line[k]] == 0) {
                    crease_line[line[k]] = id;
                    crease_rank[line[k]] = k;
                }
            lines.push_back(std::move(line));
            line_closed.push_back(closed ? 1 : 0);
        }
        creases_on = c.edges > 0;
        init.crease_edges = c.edges;
        init.crease_lines = c.lines.size();
        init.corners = c.corners.size();
        return c.edges;
    }
    /// Forgets the creases (the mesh could not be built with them).
    void drop_creases() {
        lines.clear();
        line_closed.clear();
        std::fill(crease_line.begin(), crease_line.end(), kNoSlot);
        std::fill(corner_degree.begin(), corner_degree.end(), 0);
        creases_on = false;
        init.crease_edges = init.crease_lines = init.corners = 0;
        flips_settled = false;  // unlocked edges may flip
        stale_flip.all = true;
    }
    /// The crease edges as sample pairs, to carry them to a renumbered or rebuilt mesh.
    [[nodiscard]] std::vector<std::pair<SampleId, SampleId>> crease_pairs() const {
        std::vector<std::pair<SampleId, SampleId>> out;
        const auto locked = locked_edges(mesh);
        if (!locked.is_valid()) return out;
        for (Edge e : mesh.edges())
            if (locked[e]) out.emplace_back(sid(mesh.vertex(e, 0)), sid(mesh.vertex(e, 1)));
        return out;
    }
    /// Marks the given pairs on the mesh (those that are edges of it).
    void relock(const std::vector<std::pair<SampleId, SampleId>>& pairs) {
        if (!creases_on) return;
        auto locked = lock_edges_property(mesh);
        for (const auto& [a, b] : pairs)
            if (state[a] == State::Vertex && state[b] == State::Vertex)
                if (const Halfedge h = mesh.find_halfedge(vert_of[a], vert_of[b]); h.is_valid())
                    locked[SurfaceMesh::edge(h)] = 1;
    }
    /// Crease integrity: along every polyline, consecutive vertices are joined by a crease
    /// edge, corners are vertices with their crease edges, and there is no other crease edge.
    /// Appends a line per problem (at most `cap`) and returns the problem count.
    std::size_t crease_problems(std::vector<std::string>& out, std::size_t cap) const {
        if (!creases_on) return 0;
        std::size_t n = 0, expected = 0;
        auto problem = [&](std::string s) {
            if (n++ < cap) out.push_back(std::move(s));
        };
        const auto locked = locked_edges(mesh);
        if (!locked.is_valid()) {
            problem("the crease marks are lost");
            return n;
        }
        for (SampleId s = 0; s < corner_degree.size(); ++s) {
            if (corner_degree[s] == 0) continue;
            if (state[s] != State::Vertex)
                problem("corner " + idstr(s) + " is no longer a vertex");
            else if (locked_degree(mesh, locked, vert_of[s]) != corner_degree[s])
                problem("corner " + idstr(s) + " has " + std::to_string(locked_degree(mesh, locked, vert_of[s])) +
                        " crease edges instead of " + std::to_string(corner_degree[s]));
        }
        for (std::size_t l = 0; l < lines.size(); ++l) {
            std::vector<SampleId> vs;
            for (SampleId s : lines[l])
                if (state[s] == State::Vertex) vs.push_back(s);
            if (line_closed[l] && vs.size() > 2) vs.push_back(vs.front());
            for (std::size_t i = 0; i + 1 < vs.size(); ++i) {
                ++expected;
                const Halfedge h = mesh.find_halfedge(vert_of[vs[i]], vert_of[vs[i + 1]]);
                if (!h.is_valid() || !locked[SurfaceMesh::edge(h)])
                    problem("crease vertices " + idstr(vs[i]) + " and " + idstr(vs[i + 1]) +
                            (h.is_valid() ? " are joined by an unmarked edge" : " are no longer joined by an edge"));
            }
        }
        const std::size_t marked = locked_edge_count(mesh);
        if (marked != expected)
            problem(std::to_string(marked) + " crease edges where the polylines have " + std::to_string(expected));
        return n;
    }

    /// Remove(v) of the vertex of sample s (a crease vertex is collapsed along its crease, a
    /// corner stays: remove_point()). On success the sample is no longer a vertex (state
    /// Dead; the caller decides what it becomes) and leaves the grid.
    bool remove_sample(SampleId s, PointGrid* grid) {
        const Vertex v = vert_of[s];
        const RemoveResult r = remove_point(mesh, v, RemoveOptions{});
        cur.flips += r.flips;
        if (!r.removed) {
            violation(Violation::RemoveFailed, "vertex of " + idstr(s) + ": " + r.reason);
            return false;
        }
        ++cur.removals;
        if (grid) grid->erase(s, P(s));
        vert_of[s] = Vertex();
        state[s] = State::Dead;
        return true;
    }

    std::vector<Edge> all_edges() const {
        std::vector<Edge> e;
        e.reserve(mesh.n_edges());
        for (Edge x : mesh.edges()) e.push_back(x);
        return e;
    }
    /// The global flip of §4.3 (its cap, when hit, is reported at once; the emptiness of the
    /// balls is checked by report_balls() on the mesh an update or the initialisation ends
    /// with).
    /// In a local update (spec §10.1) the flips start from the edges around the region's
    /// vertices only, and propagate from there. Otherwise from the edges of the faces changed
    /// since the last global flip converged (stale_flip; every edge after one that did not):
    /// an edge whose two faces neither changed nor moved since then needs no flip.
    void global_flip() {
        if (flips_settled) return;
        FlipOptions fo;
        fo.rule = FlipRule::DiametricBallNoFold;
        const auto edges = region.empty() ? stale_edges() : region_edges();
        const FlipReport r = flip_from(mesh, edges, fo);
        cur.flips += r.flips;
        cur.flip_refusals += r.not_improving;
        if (!r.converged)
            violation(Violation::NonEmptyBall, "the global flip stopped at its cap after " + std::to_string(r.flips) + " flips");
        if (region.empty()) {
            flips_settled = r.converged;
            looked(stale_flip, r.converged);
        }
    }
    /// The edges of the faces changed since the last converged global flip, each once, in
    /// index order (all edges when stale_flip.all).
    std::vector<Edge> stale_edges() {
        if (stale_flip.all) return all_edges();
        std::vector<Edge> e;
        for (Face f : stale_faces(stale_flip)) for_each_edge(f, [&](Edge x) { e.push_back(x); });
        std::sort(e.begin(), e.end(), [](Edge a, Edge b) { return a.idx() < b.idx(); });
        e.erase(std::unique(e.begin(), e.end()), e.end());
        return e;
    }
    /// The edges with an end in the region (each once).
    std::vector<Edge> region_edges() const {
        std::vector<Edge> e;
        for (SampleId s : region_ids) {
            if (state[s] != State::Vertex) continue;
            for (Halfedge h : mesh.outgoing_halfedges(vert_of[s])) {
                const SampleId w = sid(mesh.to_vertex(h));
                if (!region[w] || s < w) e.push_back(SurfaceMesh::edge(h));
            }
        }
        return e;
    }

    /// §4.3: every diametric ball must be empty of vertices after the global flips (a grid
    /// over the vertices); reports the balls that still hold one.
    void report_balls(const char* when) {
        if (!params.verify_balls) return;
        const double R = max_circumradius();
        if (!(R > 0)) return;
        const BallScan b = scan_changed_balls(R);
        if (b.count == 0) return;
        violation(Violation::NonEmptyBall, std::to_string(b.count) + " diametric balls hold a vertex " + when +
                                               ", e.g. that of triangle " + face_str(b.first) + " holds " +
                                               idstr(b.inside) + " (" + std::to_string(cur.flip_refusals) +
                                               " flips refused by the circumradius guard)");
    }

    /// Triangles whose diametric ball holds a vertex strictly inside (exact predicate).
    struct BallScan {
        std::size_t count = 0;  ///< such triangles
        Face first;             ///< the first one met, in mesh order
        std::uint32_t inside = kNoSlot;  ///< a vertex (slot) in its ball
        std::size_t first_hits = 0;      ///< vertices in its ball
    };
    /// `grid` holds every vertex (slots); with a cell of at least twice the largest
    /// circumradius, the cube around a ball meets at most 2 x 2 x 2 cells.
    /// With creases, a vertex counts only for the balls of the triangles of its own patches
    /// (spec §10.3: the faces reached from it without crossing a crease edge).
    [[nodiscard]] BallScan scan_balls(const PointGrid& grid) const {
        BallScan b;
        const std::vector<std::uint32_t> patch = face_patches();
        for (Face f : mesh.faces()) {
            const auto [hits, any] = ball_hits(f, grid, patch);
            if (hits == 0) continue;
            if (b.count++ == 0) {
                b.first = f;
                b.inside = any;
                b.first_hits = hits;
            }
        }
        return b;
    }
    /// The vertices strictly inside f's diametric ball (scan_balls(): `grid` holds every
    /// vertex near it, `patch` from face_patches()), and the smallest of their slots.
    [[nodiscard]] std::pair<std::size_t, std::uint32_t> ball_hits(Face f, const PointGrid& grid,
                                                                  const std::vector<std::uint32_t>& patch) const {
        auto shares_patch = [&](std::uint32_t w) {
            if (patch.empty()) return true;
            for (Halfedge h : mesh.outgoing_halfedges(vert_of[w]))
                if (const Face g = mesh.face(h); g.is_valid() && patch[g.idx()] == patch[f.idx()]) return true;
            return false;
        };
        const auto vs = mesh.face_vertices(f);
        const Point3 &a = mesh.position(vs[0]), &bb = mesh.position(vs[1]), &c = mesh.position(vs[2]);
        const Point3 cc = circumcenter(a, bb, c);
        if (!is_finite(cc)) return {0, kNoSlot};  // collinear
        const double r2 = sqnorm(cc - a);
        const double r2s = r2 * (1 + 2e-9);
        std::size_t hits = 0;
        std::uint32_t any = kNoSlot;
        grid.for_each_candidate(cc, std::sqrt(r2), [&](std::uint32_t w) {
            if (sqnorm(pos[w] - cc) > r2s) return;
            const Vertex x = vert_of[w];
            if (x == vs[0] || x == vs[1] || x == vs[2]) return;
            if (!collinear(a, bb, c) && in_diametric_ball(a, bb, c, pos[w]) == Sign::Positive && shares_patch(w)) {
                ++hits;
                if (any == kNoSlot || w < any) any = w;
            }
        });
        return {hits, any};
    }
    /// kStale's bit for the faces whose ball held a vertex at the last scan_changed_balls().
    static constexpr std::uint8_t kBallHeld = 8;
    /// The faces with kBallHeld (some may have been deleted since).
    std::vector<Face> ball_held;
    /// scan_balls() from the faces whose answer may have changed since the last call
    /// (stale_balls): those changed, those with a vertex within 2R of a changed face's vertex
    /// (a ball, of radius <= R, that a moved or new vertex entered), and those whose ball held
    /// a vertex then (kBallHeld; one may have left). The whole mesh the first time, after
    /// every face may have changed, with creases, or when more than half of the faces changed.
    [[nodiscard]] BallScan scan_changed_balls(double R) {
        const std::vector<Face> changed = stale_faces(stale_balls);
        auto flag = stale_property();
        std::vector<Face> test;
        std::vector<char> in(mesh.faces_size(), 0);
        auto take = [&](Face f) {
            if (!in[f.idx()]) {
                in[f.idx()] = 1;
                test.push_back(f);
            }
        };
        PointGrid grid;
        if (creases_on || 2 * changed.size() > mesh.n_faces()) {
            for (Face f : mesh.faces()) take(f);
            grid = vertex_grid(2 * R, region_box());
        } else {
            Bbox3 box;
            std::vector<SampleId> moved;
            for (Face f : changed)
                for (Vertex v : mesh.face_vertices(f)) {
                    box.extend(mesh.position(v));
                    moved.push_back(sid(v));
                }
            for (Face f : ball_held)
                if (!mesh.is_deleted(f) && (flag[f] & kBallHeld)) {
                    take(f);
                    for (Vertex v : mesh.face_vertices(f)) box.extend(mesh.position(v));
                }
            const Vec3 m{5 * R, 5 * R, 5 * R};  // the faces 2R from the box and their balls
            box.min = box.min - m;
            box.max = box.max + m;
            grid = vertex_grid(2 * R, box);
            std::sort(moved.begin(), moved.end());
            moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
            const double reach2 = 4 * R * R * (1 + 1e-9);
            for (SampleId x : moved)
                grid.for_each_candidate(P(x), 2 * R * (1 + 1e-9), [&](std::uint32_t w) {
                    if (sqnorm(P(w) - P(x)) > reach2) return;
                    for (Halfedge h : mesh.outgoing_halfedges(vert_of[w]))
                        if (const Face g = mesh.face(h); g.is_valid()) take(g);
                });
            for (Face f : changed) take(f);
        }
        const std::vector<std::uint32_t> patch = face_patches();
        // Every face that held a vertex is in `test`, so the faces that hold one now are
        // those of `test` that do.
        BallScan b;
        ball_held.clear();
        for (Face f : test) {
            const auto [hits, inside] = ball_hits(f, grid, patch);
            flag[f] = static_cast<std::uint8_t>(hits > 0 ? flag[f] | kBallHeld : flag[f] & ~kBallHeld);
            if (hits == 0) continue;
            ball_held.push_back(f);
            if (b.count++ == 0 || f.idx() < b.first.idx()) {
                b.first = f;
                b.first_hits = hits;
                b.inside = inside;
            }
        }
        looked(stale_balls, true);
        return b;
    }

    // ---- RefineVert (§4.5) ------------------------------------------------------------------
    void refine_vert() {
        for (std::size_t pass = 0;; ++pass) {
            if (pass >= params.refine_max_iters) {
                violation(Violation::RefineCapHit, "RefineVert stopped after " + std::to_string(pass) + " passes");
                return;
            }
            const double R = max_circumradius();
            std::vector<SampleId> S;
            bool local = false;  // a sample was promoted by its local size below R
            // In a local update, the dormant samples of the region's vertices, in slot order.
            std::vector<SampleId> of_region;
            if (!region.empty()) {
                for (SampleId w : region_ids)
                    if (state[w] == State::Vertex) of_region.insert(of_region.end(), dl[w].begin(), dl[w].end());
                std::sort(of_region.begin(), of_region.end());
            }
            const std::size_t n_scan = region.empty() ? state.size() : of_region.size();
            for (std::size_t k = 0; k < n_scan; ++k) {
                const SampleId p = region.empty() ? static_cast<SampleId>(k) : of_region[k];
                if (state[p] != State::Dormant || refused[p]) continue;
                ++cur.distance_evals;
                if (distance(P(p), P(owner[p])) > rs(p, R) / 3) {
                    if (!(rs(p, R) >= R)) local = true;
                    detach(p);
                    state[p] = State::Pending;
                    S.push_back(p);
                }
            }
            ++cur.refine_passes;
            if (!S.empty()) {
                PointGrid grid = vertex_grid(R);
                place(S, grid, R);
            }
            global_flip();
            // The paper's stop, and with a size field no promotion below R in this pass
            // (spec §10.2): where r < R the pass-level R need not drop.
            if (max_circumradius() > 2 * R / 3 && !local) return;
        }
    }

    /// Step (c) of RefineVert and the loop of Insertion: each sample becomes dormant at the
    /// nearest vertex when one is within R/3, or a vertex.
    void place(const std::vector<SampleId>& S, PointGrid& grid, double R) {
        for (SampleId p : S) {
            const auto [w, d] = grid.nearest(P(p), [&](std::uint32_t s) { return P(s); },
                                             [&](std::uint32_t s) { return state[s] == State::Vertex; });
            ++cur.distance_evals;
            inherit_size(p, w, d);
            if (w != kNoSample && d <= rs(p, R) / 3)
                attach(p, w);
            else
                add_sample(p, grid, R);
        }
    }

    // ---- Insertion (§4.6) -------------------------------------------------------------------
    void insertion() {
        if (pending_insert.empty()) return;
        std::vector<SampleId> S = std::move(pending_insert);
        pending_insert.clear();
        std::sort(S.begin(), S.end());
        const double R = max_circumradius();
        PointGrid grid = vertex_grid(R);
        place(S, grid, R);
        cur.samples_inserted += S.size();
        refine_vert();
    }

    // ---- Deletion (§4.7) --------------------------------------------------------------------
    void deletion() {
        if (pending_delete.empty()) return;
        std::vector<SampleId> D = std::move(pending_delete);
        pending_delete.clear();
        std::sort(D.begin(), D.end());
        D.erase(std::unique(D.begin(), D.end()), D.end());
        std::size_t n_marked = 0;
        for (SampleId s : D)
            if (state[s] == State::Dormant || state[s] == State::Vertex) {
                marked[s] = 1;
                ++n_marked;
            }
        for (std::size_t iter = 0; n_marked > 0; ++iter) {
            if (iter >= params.deletion_max_iters) {
                violation(Violation::DeletionCapHit, std::to_string(n_marked) + " samples still to delete after " +
                                                         std::to_string(iter) + " iterations; queued again");
                for (SampleId s = 0; s < marked.size(); ++s)
                    if (marked[s]) {
                        marked[s] = 0;
                        pending_delete.push_back(s);
                    }
                return;
            }
            ++cur.deletion_iterations;
            // 1. marked dormant samples leave P
            for (SampleId s = 0; s < marked.size(); ++s)
                if (marked[s] && state[s] == State::Dormant) {
                    detach(s);
                    kill(s, n_marked);
                }
            const std::size_t before = n_marked;
            user_deletion(n_marked);
            decimation();
            refine_vert();
            if (n_marked == before && !any_marked_dormant()) {
                // Marked vertices that no Remove could take out: try again next step.
                for (SampleId s = 0; s < marked.size(); ++s)
                    if (marked[s]) {
                        marked[s] = 0;
                        pending_delete.push_back(s);
                    }
                return;
            }
        }
    }
    bool any_marked_dormant() const {
        for (SampleId s = 0; s < marked.size(); ++s)
            if (marked[s] && state[s] == State::Dormant) return true;
        return false;
    }
    void kill(SampleId s, std::size_t& n_marked) {
        state[s] = State::Dead;
        owner[s] = kNoSample;
        vert_of[s] = Vertex();
        if (marked[s]) {
            marked[s] = 0;
            --n_marked;
        }
        ++cur.samples_deleted;
        --live;
    }

    void user_deletion(std::size_t& n_marked) {
        const double R = max_circumradius();
        PointGrid grid = vertex_grid(R);
        std::vector<SampleId> mv;
        for (Vertex v : mesh.vertices())
            if (marked[sid(v)]) mv.push_back(sid(v));
        std::sort(mv.begin(), mv.end());
        auto is_vertex = [&](std::uint32_t s) { return state[s] == State::Vertex; };
        auto posf = [&](std::uint32_t s) { return P(s); };
        for (SampleId v : mv) {
            if (state[v] != State::Vertex || !marked[v]) continue;
            std::vector<SampleId> S1, S2;
            grid.for_each_candidate(P(v), 4 * R, [&](std::uint32_t w) {
                if (state[w] != State::Vertex || !marked[w]) return;
                const double d = distance(P(w), P(v));
                ++cur.distance_evals;
                if (d <= 2 * R)
                    S1.push_back(w);
                else if (d <= 4 * R)
                    S2.push_back(w);
            });
            std::sort(S1.begin(), S1.end());
            std::sort(S2.begin(), S2.end());
            const auto [u, du] = grid.nearest(P(v), posf, [&](std::uint32_t s) { return is_vertex(s) && !marked[s]; });
            const bool has_u = u != kNoSample && du <= 4 * R;
            SampleId wstar = kNoSample;
            for (SampleId w : S1)
                if (!dl[w].empty()) {
                    wstar = w;
                    break;
                }
            if (!has_u && wstar == kNoSample) {
                for (SampleId w : S1)
                    if (remove_sample(w, &grid)) kill_vertex_sample(w, n_marked);
                return;
            }
            std::vector<SampleId> gone;
            for (const auto* S : {&S1, &S2})
                for (SampleId w : *S)
                    if (remove_sample(w, &grid)) gone.push_back(w);
            std::vector<SampleId> orphans;
            for (SampleId w : gone) {
                for (SampleId p : dl[w]) orphans.push_back(p);
                dl[w].clear();
                kill_vertex_sample(w, n_marked);
            }
            std::sort(orphans.begin(), orphans.end());
            if (has_u) {
                for (SampleId p : orphans) attach(p, u);
            } else if (!orphans.empty()) {
                const SampleId q = orphans.front();
                state[q] = State::Pending;
                add_sample(q, grid, R);
                const SampleId to = state[q] == State::Vertex ? q : owner[q];
                for (std::size_t i = 1; i < orphans.size(); ++i) attach(orphans[i], to);
            }
        }
    }
    void kill_vertex_sample(SampleId w, std::size_t& n_marked) {
        if (!marked[w]) return;  // a removed vertex that was not marked stays a sample
        kill(w, n_marked);
    }

    /// Decimation of §4.7 (factor 1/2). With factor 1/3 it is the spacing repair of §9 P7.
    /// Returns the number of vertices it removed.
    std::vector<char> decimation_black;  // by slot, all 0 between calls

    /// What lets the spacing repair of an update at an integer time look only where a close
    /// pair can be: the close pairs found by the last full scan, at R_near (a superset of the
    /// close pairs of the vertices unchanged since, while R <= R_near: the threshold grows
    /// with R), and the vertices changed since then (moved, made, or with a face made or
    /// relinked), by slot.
    struct SpacingScan {
        bool valid = false;
        double R_near = 0;
        std::vector<std::pair<SampleId, SampleId>> near;
        Cursor cursor;
        std::vector<char> touched;
        std::vector<SampleId> touched_ids;
    };
    SpacingScan spacing;
    /// Brings spacing.touched up to date (false: everything may have changed since).
    bool spacing_catch_up() {
        if (!spacing.valid) return false;
        const bool known = changes_since(spacing.cursor, [&](Face f) {
            if (mesh.is_deleted(f)) return;
            for (Vertex v : mesh.face_vertices(f)) {
                const SampleId x = sid(v);
                if (x >= spacing.touched.size()) spacing.touched.resize(state.size(), 0);
                if (!spacing.touched[x]) {
                    spacing.touched[x] = 1;
                    spacing.touched_ids.push_back(x);
                }
            }
        });
        if (!known) spacing.valid = false;
        return spacing.valid;
    }

    std::size_t decimation(double factor = 0.5) {
        const double R = max_circumradius();
        // The spacing repair at an integer time, without creases: every vertex when the last
        // full scan is out of date, otherwise the vertices of a close pair among those changed
        // since, their close partners and the near pairs of that scan (a superset of the
        // vertices that have a close partner; the others mark nothing, so the marks are those
        // of a scan of every vertex).
        const bool spacing_global = region.empty() && factor < 0.4 && !creases_on;
        const bool incremental = spacing_global && params.incremental_spacing && spacing_catch_up() && R <= spacing.R_near &&
                                 4 * spacing.touched_ids.size() < mesh.n_vertices();
        std::vector<SampleId> vs;  // the vertices looked around (a local update: the region's)
        PointGrid grid;
        if (incremental) {
            locator_catch_up();
            for (SampleId x : spacing.touched_ids) {
                if (state[x] != State::Vertex) continue;
                bool close = false;
                loc.grid.for_each_candidate(P(x), factor * rs(x, R), [&](std::uint32_t w) {
                    if (w == x || state[w] != State::Vertex) return;
                    ++cur.distance_evals;
                    if (distance(P(w), P(x)) < factor * std::min(rs(x, R), rs(w, R))) {
                        vs.push_back(w);
                        close = true;
                    }
                });
                if (close) vs.push_back(x);
            }
            for (const auto& [a, b] : spacing.near)
                if (state[a] == State::Vertex && state[b] == State::Vertex) {
                    vs.push_back(a);
                    vs.push_back(b);
                }
            std::sort(vs.begin(), vs.end());
            vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
        } else {
            grid = vertex_grid(R);
            vs.reserve(region.empty() ? mesh.n_vertices() : region_ids.size());
            if (region.empty())
                for (Vertex v : mesh.vertices()) vs.push_back(sid(v));
            else
                for (SampleId s : region_ids)
                    if (state[s] == State::Vertex) vs.push_back(s);
        }
        const PointGrid& candidates = incremental ? loc.grid : grid;
        // A full scan at an integer time starts the record of what changes after it.
        const bool record = spacing_global && !incremental;
        const double R_near = R;  // a margin above R makes the list long (most edges are near R / 3)
        // The close pairs go to the list in the marking loop below, which then also looks
        // around the vertices marked before their turn (they mark nothing).
        if (record) {
            spacing.valid = true;
            spacing.R_near = R_near;
            spacing.near.clear();
            for (SampleId x : spacing.touched_ids)
                if (x < spacing.touched.size()) spacing.touched[x] = 0;
            spacing.touched_ids.clear();
            spacing.cursor = Cursor{gen, mesh.face_log().size(), moved_log.size()};
        }
        std::vector<char> on_crease;
        if (creases_on) {
            on_crease.assign(state.size(), 0);
            const auto locked = locked_edges(mesh);
            for (Vertex x : mesh.vertices())
                on_crease[sid(x)] = corner_degree[sid(x)] > 0 || locked_degree(mesh, locked, x) > 0;
        }
        auto rank = [&](SampleId s) { return corner_degree[s] > 0 ? 0 : !on_crease.empty() && on_crease[s] ? 1 : 2; };
        auto before = [&](SampleId a, SampleId b) { return std::pair(rank(a), a) < std::pair(rank(b), b); };
        std::sort(vs.begin(), vs.end(), before);
        // The Deletion's decimation (factor 1/2) leaves crease vertices: removing them
        // lengthens crease edges, which no flip can shorten, and R would grow with every
        // deletion. The spacing repair (1/3) still thins a compressed crease.
        const bool spare_creases = factor > 0.4;
        std::vector<char>& black = decimation_black;
        black.resize(state.size(), 0);
        std::vector<SampleId> blacks;
        struct Whiten {  // leaves `black` all 0 for the next call
            std::vector<char>& black;
            std::vector<SampleId>& blacks;
            ~Whiten() {
                for (SampleId w : blacks) black[w] = 0;
            }
        } whiten{black, blacks};
        for (SampleId v : vs) {
            if (black[v] && !record) continue;
            const bool marks = !black[v];
            candidates.for_each_candidate(P(v), factor * rs(v, R), [&](std::uint32_t w) {
                if (record && w > v && state[w] == State::Vertex &&
                    distance(P(w), P(v)) < factor * std::min(rs(v, R_near), rs(w, R_near)))
                    spacing.near.emplace_back(v, w);
                if (!marks) return;
                if (w == v || state[w] != State::Vertex || corner_degree[w] > 0 || (spare_creases && !on_crease.empty() && on_crease[w]))
                    return;
                if (!region.empty() && !region[w]) return;  // a local update removes only in its region
                ++cur.distance_evals;
                if (!black[w] && distance(P(w), P(v)) < factor * std::min(rs(v, R), rs(w, R))) {
                    black[w] = 1;
                    blacks.push_back(w);
                }
            });
        }
        if (blacks.empty()) return 0;
        std::sort(blacks.begin(), blacks.end(), before);
        // The samples of the removed vertices go to the nearest of the others (the vertices
        // of `grid` that are not black: the removals below take only black ones).
        auto posf = [&](std::uint32_t s) { return P(s); };
        auto white = [&](std::uint32_t s) { return state[s] == State::Vertex && !black[s]; };
        std::size_t removed = 0;
        for (SampleId u : blacks) {
            if (mesh.n_vertices() <= 4) break;
            std::vector<SampleId> moving = dl[u];
            dl[u].clear();
            if (!remove_sample(u, nullptr)) {
                dl[u] = std::move(moving);
                for (std::uint32_t i = 0; i < dl[u].size(); ++i) dpos[dl[u][i]] = i;
                continue;
            }
            ++removed;
            moving.push_back(u);
            for (SampleId p : moving) {
                const auto [w, d] = candidates.nearest(P(p), posf, white);
                ++cur.distance_evals;
                attach(p, w);
            }
        }
        if (removed > 0) clear_refused();  // the mesh changed around the refusals
        return removed;
    }

    /// §9 P7 (not in the paper): vertex pairs that came closer than R/3 (old vertices under
    /// compression) lose one vertex, then RefineVert restores the density.
    void spacing_repair() {
        if (!params.spacing_repair) return;
        // RefineVert may raise R a little after the removals; repeat (rarely more than once).
        for (int round = 0; round < 4 && decimation(1.0 / 3.0) > 0; ++round) {
            ++cur.spacing_repairs;
            refine_vert();
        }
    }

    /// One unit of advance() after its checks: the sub-steps (at least min_n) and the With `save`, the state before the unit is copied there when the unit is
    /// cut into sub-steps.
    StepReport frame(int t, std::span<const Point3> positions, std::size_t min_n, std::unique_ptr<Impl>* save);
    /// A deep copy (the sample property handle re-bound to the copy's mesh).
    [[nodiscard]] std::unique_ptr<Impl> copy() const {
        auto c = std::make_unique<Impl>(*this);
        c->vsample = c->mesh.get_vertex_property<SampleId>("v:sample");
        return c;
    }
    /// Becomes a copy of `saved` in place, so that references to this state (mesh(),
    /// init_report()) stay valid across a retry.
    void restore(const Impl& saved) {
        *this = saved;
        vsample = mesh.get_vertex_property<SampleId>("v:sample");
    }

    // ---- sub-stepping (spec §10.1) -----------------------------------------------------------
    /// Relative displacement since the last update: of each edge's ends (by edge index; the
    /// connectivity does not change between updates) and of each dormant sample and its owner
    /// (by slot). Reset by every update.
    std::vector<double> strain_e, strain_d;
    /// How far a pair's relative displacement may go between two updates: 2 R / kappa, the
    /// floor schedule's allowance 2 lambda floor(R / (kappa lambda)) when the model holds;
    /// 2 min(r_a, r_b) / kappa for a pair (a, b) with the size field.
    [[nodiscard]] double budget() const { return 2 * R_last / params.kappa; }
    /// The budget of the pair (a, b): 2 min(r_a, r_b) / kappa.
    [[nodiscard]] double pair_budget(SampleId a, SampleId b) const {
        return budget() * std::min(rs(a, R_last), rs(b, R_last)) / R_last;
    }

    /// Calls f(k, a, b) for every pair the budget covers: mesh edges (k = edge index) and
    /// dormant samples with their owners (k = edges_size() + slot); strain(k) is its strain.
    template <class F>
    void for_each_pair(F&& f) const {
        for (Edge e : mesh.edges()) {
            const Halfedge h = SurfaceMesh::halfedge(e, 0);
            f(e.idx(), sid(mesh.from_vertex(h)), sid(mesh.to_vertex(h)));
        }
        const std::size_t ne = mesh.edges_size();
        for (SampleId s = 0; s < pos.size(); ++s)
            if (state[s] == State::Dormant) f(ne + s, s, owner[s]);
    }
    double& strain(std::size_t k) {
        return k < strain_e.size() ? strain_e[k] : strain_d[k - strain_e.size()];
    }
    [[nodiscard]] double strain(std::size_t k) const {
        return k < strain_e.size() ? strain_e[k] : strain_d[k - strain_e.size()];
    }
    /// The pairs of for_each_pair(), in its order, as flat arrays for the loops that run at
    /// every sub-step (strain_ratio(), over_budget(), move_samples()): pair index k, ends a
    /// and b, budget pair_budget(a, b). Invalid from the start of an update or a mesh install
    /// (pairs_dirty) and rebuilt on the next read, so a sub-step without an update reads no
    /// mesh.
    struct PairTable {
        std::vector<std::size_t> key;
        std::vector<SampleId> a, b;
        std::vector<double> budget;
    };
    PairTable pairs;
    bool pairs_dirty = true;
    /// The samples the current unit moves (its `to` differs from pos; every live sample when
    /// the unit turns the whole), with a flag per slot, and the rows of the pairs with an end
    /// among them (moving_pairs()): the only pairs whose strain a sub-step changes, so that a
    /// sub-step costs O(|moving|) and not O(|P|) (spec §10.1: a frame costs O(n |U| + |Vert|)).
    /// Rebuilt after every update (mpairs_dirty, invalidate_pairs()) while the unit lasts.
    std::vector<SampleId> moving;
    std::vector<char> is_moving;
    PairTable mpairs;
    bool mpairs_dirty = true;
    /// Both tables are stale: new edges, dormant pairs and budgets (an update, a mesh install).
    void invalidate_pairs() { pairs_dirty = mpairs_dirty = true; }
    static void clear(PairTable& t) {
        t.key.clear();
        t.a.clear();
        t.b.clear();
        t.budget.clear();
    }
    void push(PairTable& t, std::size_t k, SampleId a, SampleId b) const {
        t.key.push_back(k);
        t.a.push_back(a);
        t.b.push_back(b);
        t.budget.push_back(pair_budget(a, b));
    }
    /// The pairs of for_each_pair() with an end in `moving`, each once: a vertex's edges (an
    /// edge between two moving vertices from its smaller end) and its dormant samples that do
    /// not move, and a moving dormant sample with its owner.
    const PairTable& moving_pairs() {
        if (!mpairs_dirty) return mpairs;
        clear(mpairs);
        const std::size_t ne = mesh.edges_size();
        for (SampleId s : moving) {
            if (state[s] == State::Vertex) {
                for (Halfedge h : mesh.outgoing_halfedges(vert_of[s])) {
                    const SampleId u = sid(mesh.to_vertex(h));
                    if (!is_moving[u] || s < u) push(mpairs, SurfaceMesh::edge(h).idx(), s, u);
                }
                for (SampleId p : dl[s])
                    if (!is_moving[p]) push(mpairs, ne + p, p, s);
            } else if (state[s] == State::Dormant) {
                push(mpairs, ne + s, s, owner[s]);
            }
        }
        mpairs_dirty = false;
        return mpairs;
    }
    const PairTable& pair_table() {
        if (pairs_dirty) {
            clear(pairs);
            for_each_pair([&](std::size_t k, SampleId a, SampleId b) { push(pairs, k, a, b); });
            pairs_dirty = false;
        }
        return pairs;
    }
    /// How far a and b move relative to each other when every sample goes from pos to `to`,
    /// apart from the rotation `turn` of the whole (a rigid motion moves no pair).
    /// The smaller of the plain relative displacement (spec §10.1's D, which the paper's
    /// model bounds by 2 lambda per unit) and the one measured after the turn.
    [[nodiscard]] double relative_move(const std::vector<Point3>& to, SampleId a, SampleId b,
                                       const detail::Mat3& turn, bool turned = true) const {
        const Vec3 e0 = pos[b] - pos[a], e1 = to[b] - to[a];
        const double plain = norm(e1 - e0);
        return turned ? std::min(plain, norm(e1 - turn * e0)) : plain;
    }
    /// Largest (strain + relative move) / budget over the pairs when every sample goes from
    /// pos to `to` (the move alone, when !with_strain). `moves` (when given) receives each
    /// pair's relative move by its row in pair_table(), for over_budget() and move_samples()
    /// while the mesh stays as it is.
    [[nodiscard]] double strain_ratio(const PairTable& pt, const std::vector<Point3>& to, const detail::Mat3& turn,
                                      bool with_strain, std::vector<double>* moves = nullptr) const {
        const std::size_t n = pt.key.size();
        if (moves) moves->resize(n);
        const bool turned = !turn.is_identity();  // else both measures of relative_move() agree
        double worst = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double m = relative_move(to, pt.a[i], pt.b[i], turn, turned);
            if (moves) (*moves)[i] = m;
            worst = std::max(worst, ((with_strain ? strain(pt.key[i]) : 0.0) + m) / pt.budget[i]);
        }
        return worst;
    }
    /// A local update takes in the pairs past this share of their budget, not only those over
    /// it (departure from spec §10.1, which takes the pairs over the budget): pairs about to
    /// run out are reset with them, so the updates are fewer and larger (fandisk twisted over
    /// 200 units: 168 updates between sub-steps instead of 301, and no inverted triangle
    /// instead of one).
    static constexpr double kRegionStrainShare = 0.5;
    /// substep_to(): a best-fit turn whose largest displacement is at most this share of the
    /// budget is taken as none.
    static constexpr double kNegligibleTurn = 0.01;
    /// The vertices (samples) at the ends of the pairs whose strain plus move to `to` exceeds
    /// kRegionStrainShare of their budget (for a dormant pair, its owner), each once.
    /// `moves`: from strain_ratio() on the same mesh and `to`.
    [[nodiscard]] std::vector<SampleId> over_budget(const PairTable& pt, const std::vector<double>& moves) const {
        std::vector<SampleId> out;
        std::vector<char> seen(pos.size(), 0);
        auto add = [&](SampleId s) {
            if (!seen[s]) {
                seen[s] = 1;
                out.push_back(s);
            }
        };
        for (std::size_t i = 0; i < pt.key.size(); ++i)
            if ((strain(pt.key[i]) + moves[i]) / pt.budget[i] > kRegionStrainShare) {
                if (state[pt.a[i]] == State::Vertex) add(pt.a[i]);
                add(pt.b[i]);
            }
        return out;
    }
    /// Moves every sample that is not dead to `to` (slot order); with `moves` (strain_ratio()'s
    /// on this mesh and `to`), each pair's relative move is added to its strain.
    void move_samples(const std::vector<Point3>& to) {
        for (SampleId s = 0; s < pos.size(); ++s)
            if (state[s] != State::Dead) pos[s] = to[s];
        for (Vertex v : mesh.vertices()) mesh.position(v) = pos[sid(v)];
        all_changed();
        flips_settled = false;
    }
    /// Moves the samples of `moving` to `to` (the others are there already), adding each
    /// pair's relative move (`moves`, strain_ratio()'s on moving_pairs() and `to`) to its
    /// strain.
    void move_moving(const std::vector<Point3>& to, const std::vector<double>& moves) {
        const PairTable& pt = moving_pairs();
        for (std::size_t i = 0; i < pt.key.size(); ++i) strain(pt.key[i]) += moves[i];
        std::size_t moving_vertices = 0;
        for (SampleId s : moving) moving_vertices += state[s] == State::Vertex ? 1 : 0;
        const bool most = 2 * moving_vertices > mesh.n_vertices();  // cheaper to start over
        for (SampleId s : moving) {
            pos[s] = to[s];
            if (state[s] == State::Vertex) {
                mesh.position(vert_of[s]) = pos[s];
                if (!most) moved_log.push_back(vert_of[s]);
            }
        }
        if (most) all_changed();
        flips_settled = false;
    }

    /// Moves the samples from pos to `to` in n = ceil(max relative move / budget) equal
    /// sub-steps (at most max_substeps), the relative move measured apart from the best-fit
    /// rotation of the whole (fit_rigid: rotation G about axis a by angle phi, centroids c0 and
    /// c1). Sub-step k places slot s at c0 + f (c1 - c0) + G(f)(from_s - c0) + f res_s, with
    /// f = k / n, G(f) the turn by f phi about a and res_s = to_s - c1 - G(1)(from_s - c0)
    /// (from_s + f (to_s - from_s) when phi = 0); sub-step n at to exactly. Before a sub-step
    /// that would take some pair's strain beyond the budget, an internal update runs.
    void substep_to(const std::vector<Point3>& to, StepReport& rep, std::size_t min_n, std::unique_ptr<Impl>* save,
                    int t_before) {
        if (params.max_substeps <= 1 || !(budget() > 0) || !std::isfinite(budget())) {
            move_samples(to);
            return;
        }
        const std::vector<Point3> from = pos;
        const detail::RigidFit fit =
            detail::fit_rigid(from, to, [&](std::size_t s) { return state[s] != State::Dead; });
        const double need = std::ceil(strain_ratio(pair_table(), to, fit.rotation(), false));
        std::size_t n = std::max<std::size_t>(1, min_n);
        if (need > 1) n = std::max(n, static_cast<std::size_t>(std::min(need, static_cast<double>(params.max_substeps))));
        n = std::min(n, params.max_substeps);
        if (save != nullptr && n > 1) {  // the state before the unit, for a retry
            *save = copy();
            (*save)->t = t_before;
        }
        if (need > static_cast<double>(params.max_substeps))
            violation(Violation::SubstepCapHit, "the unit needs " + std::to_string(need) + " sub-steps; " +
                                                    std::to_string(n) + " used (max_substeps)");
        rep.substeps = n;
        // A turn that moves no sample by more than kNegligibleTurn of the budget is left out
        // of the interpolation (a local motion fits a turn of numerical noise), so that the
        // samples the unit leaves in place stay there at every sub-step.
        detail::RigidFit path = fit;
        if (path.angle != 0) {
            double reach = 0;
            for (SampleId s = 0; s < from.size(); ++s)
                if (state[s] != State::Dead) reach = std::max(reach, sqnorm(from[s] - fit.c_from));
            if (path.angle * std::sqrt(reach) <= kNegligibleTurn * budget()) path.angle = 0;
        }
        moving.clear();
        is_moving.assign(pos.size(), 0);
        for (SampleId s = 0; s < from.size(); ++s)
            if (state[s] != State::Dead && (path.angle != 0 || to[s] != from[s])) {
                moving.push_back(s);
                is_moving[s] = 1;
            }
        mpairs_dirty = true;
        // The pairs that do not move keep their strain through the unit (an update only resets
        // it): their largest ratio, for the report.
        double still = 0;
        {
            const PairTable& pt = pair_table();
            for (std::size_t i = 0; i < pt.key.size(); ++i)
                if (!is_moving[pt.a[i]] && !is_moving[pt.b[i]]) still = std::max(still, strain(pt.key[i]) / pt.budget[i]);
        }
        rep.max_strain_ratio = std::max(rep.max_strain_ratio, still);
        std::vector<Point3> at = pos;
        const detail::Mat3 full = path.rotation(), step = path.rotation(1.0 / static_cast<double>(n));
        std::vector<Vec3> res;  // each sample's move apart from the turn
        if (path.angle != 0 && n > 1) {
            res.resize(pos.size());
            for (SampleId s : moving) res[s] = to[s] - fit.c_to - full * (from[s] - fit.c_from);
        }
        std::vector<double> moves;  // each pair's relative move in this sub-step
        // Clears the region when an update between sub-steps throws (finish_local() clears it
        // otherwise), so that later updates are not taken for local ones.
        struct RegionGuard {
            Impl& impl;
            bool armed = false;
            ~RegionGuard() {
                if (armed) impl.clear_region();
            }
        } guard{*this};
        for (std::size_t k = 1; k <= n; ++k) {
            const double f = static_cast<double>(k) / static_cast<double>(n);
            if (k == n) {
                for (SampleId s : moving) at[s] = to[s];
            } else if (path.angle == 0) {
                for (SampleId s : moving) at[s] = from[s] + (to[s] - from[s]) * f;
            } else {
                const detail::Mat3 turn = path.rotation(f);
                const Point3 c = fit.c_from + (fit.c_to - fit.c_from) * f;
                for (SampleId s : moving) at[s] = c + turn * (from[s] - fit.c_from) + res[s] * f;
            }
            double ratio = strain_ratio(moving_pairs(), at, step, true, &moves);
            if (ratio > 1) {
                if (params.local_updates) {
                    // U: the ends of the pairs past kRegionStrainShare of their budget (a
                    // dormant pair: its owner), and their 2-ring; global when that is more than
                    // half of the mesh.
                    const std::vector<SampleId> seeds = over_budget(moving_pairs(), moves);
                    set_region(seeds);
                    guard.armed = true;
                    if (2 * region_ids.size() > mesh.n_vertices()) {
                        clear_region();
                    } else {
                        ++rep.local_updates;
                        rep.region_vertices += region_ids.size();
                    }
                }
                const DeformUpdateReport u = mesh_update(true);
                rep.internal += u.counters;
                ++rep.internal_updates;
                ratio = strain_ratio(moving_pairs(), at, step, true, &moves);
            }
            rep.max_strain_ratio = std::max(rep.max_strain_ratio, ratio);
            move_moving(at, moves);
        }
    }

    /// MeshUpdate at the current positions: RefineVert, the queued insertions and deletions
    /// (not when `internal`, an update between integer times), the spacing repair, the ball
    /// check, the next step. With a region (set_region(); internal updates only) RefineVert,
    /// the flips and the spacing repair work there (spec §10.1's U), and the strain is reset
    /// there.
    DeformUpdateReport mesh_update(bool internal) {
        const auto t0 = Clock::now();
        DeformUpdateReport rep;
        rep.t = t;
        rep.emergency = !internal && emergency_requested;
        cur = {};
        invalidate_pairs();  // nothing in an update reads the tables
        clear_refused();
        rep.R_before = max_circumradius();
        rep.vertices_before = mesh.n_vertices();
        refine_vert();
        if (!internal) {
            insertion();
            deletion();
        }
        spacing_repair();
        // The ball check is a diagnostic of the states the caller sees, at integer times (an
        // update between sub-steps is followed by more motion within the same unit).
        if (!internal) report_balls("after the update's global flips");
        // An update between sub-steps refreshes R (the budget's scale) but leaves the next
        // step where the last update at an integer time put it (spec §10.1: t2 = t1 +
        // floor(R / (kappa lambda)) stays in force, and the caller's edits wait for it).
        // A local update resets the strain in its region only: R_last does not drop, so that no
        // pair outside it finds its budget (2 R_last / kappa) shrunk below its strain.
        if (internal)
            R_last = region.empty() ? max_circumradius() : std::max(R_last, max_circumradius());
        else
            schedule();
        if (region.empty())
            finish_update();
        else
            finish_local();
        if (!internal) emergency_requested = false;
        rep.R_after = R_last;
        if (rep.R_before > 0 && rep.R_after > kCoarseningWarningFactor * rep.R_before)
            violation(Violation::Coarsened, "the update coarsened the mesh: R " + std::to_string(rep.R_before) + " -> " +
                                                std::to_string(rep.R_after) + " (" +
                                                std::to_string(rep.R_after / rep.R_before) + "x), vertices " +
                                                std::to_string(rep.vertices_before) + " -> " +
                                                std::to_string(mesh.n_vertices()));
        rep.next_step = next;
        rep.samples = live;
        rep.vertices = mesh.n_vertices();
        cur.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
        rep.counters = cur;
        totals += cur;
        ++n_updates;
        return rep;
    }

    // ---- MeshUpdate ---------------------------------------------------------------------------
    void schedule() {
        const double R = max_circumradius();
        const double steps = std::floor(R / (params.kappa * params.lambda));
        int delta = 1;
        if (!(steps >= 1)) {
            // With sub-stepping the budget keeps the motion within the model inside every
            // unit, so a step of 0 units is no violation: the next update is one unit on.
            if (params.max_substeps <= 1)
                violation(Violation::StepTooShort, "floor(R / (kappa lambda)) = 0 with R = " + std::to_string(R) +
                                                   ", kappa = " + std::to_string(params.kappa) +
                                                   ", lambda = " + std::to_string(params.lambda) +
                                                   ": the motion is too fast for this sampling; updating every unit");
        } else {
            delta = static_cast<int>(std::min(steps, 1e9));
        }
        const long long nx = static_cast<long long>(t) + delta;
        next = static_cast<int>(std::min<long long>(nx, std::max(params.horizon, t + 1)));
        R_last = R;
    }

    void finish_update() {
        if (mesh.has_garbage()) {
            for (Tracker* tr : trackers()) drain(*tr);  // what they have not seen survives the renumbering
            // The locator and the spacing scan go by sample: the renumbering moves nothing.
            const bool locator_known = loc.cursor.gen == gen;
            if (locator_known) locator_catch_up();
            const bool spacing_known = spacing_catch_up();
            mesh.garbage_collection();
            all_changed();
            for (Tracker* tr : trackers()) tr->cursor = Cursor{gen, 0, 0};
            if (locator_known) loc.cursor = Cursor{gen, 0, 0};
            if (spacing_known) spacing.cursor = Cursor{gen, 0, 0};
            relist();
        }
        strain_e.assign(mesh.edges_size(), 0.0);
        strain_d.assign(pos.size(), 0.0);
        edge_ends.assign(mesh.edges_size(), {});
        for (Edge e : mesh.edges()) edge_ends[e.idx()] = ends_of(e);
        std::fill(vert_of.begin(), vert_of.end(), Vertex());
        for (Vertex v : mesh.vertices()) vert_of[sid(v)] = v;
        std::vector<Face> changed;
        finish_normals(changes_since(finish_cursor, [&](Face f) { changed.push_back(f); }) ? &changed : nullptr);
    }
    /// The end of a local update: no garbage collection (handles stay valid until the next
    /// update at an integer time); the strain restarts on the region's pairs and on every edge
    /// the update made or flipped (its ends changed), and holds elsewhere.
    /// The edges it looks at: those of the faces changed since the last update's end (an
    /// edge made or flipped is in one) and those of the region's vertices; every edge when
    /// everything may have changed.
    void finish_local() {
        strain_e.resize(mesh.edges_size(), 0.0);
        edge_ends.resize(mesh.edges_size(), {});
        auto reset = [&](Edge e) {
            const auto ab = ends_of(e);
            if (ab != edge_ends[e.idx()] || region[ab[0]] || region[ab[1]]) {
                strain_e[e.idx()] = 0;
                edge_ends[e.idx()] = ab;
            }
        };
        std::vector<Face> changed;
        const bool known = changes_since(finish_cursor, [&](Face f) { changed.push_back(f); });
        if (known) {
            for (Face f : changed)
                if (!mesh.is_deleted(f))
                    for_each_edge(f, reset);
            for (SampleId s : region_ids)
                if (state[s] == State::Vertex)
                    for (Halfedge h : mesh.outgoing_halfedges(vert_of[s])) reset(SurfaceMesh::edge(h));
        } else {
            for (Edge e : mesh.edges()) reset(e);
        }
        strain_d.resize(pos.size(), 0.0);
        for (SampleId s : region_ids)
            if (state[s] == State::Vertex)
                for (SampleId p : dl[s]) strain_d[p] = 0;
        finish_normals(known ? &changed : nullptr);
        clear_region();
    }
    /// Calls fn(e) for the three edges of face f.
    template <class F>
    void for_each_edge(Face f, F&& fn) const {
        Halfedge h = mesh.halfedge(f);
        for (int i = 0; i < 3; ++i, h = mesh.next(h)) fn(SurfaceMesh::edge(h));
    }
    /// Where the last update's end left the changes (finish_update(), finish_local()).
    Cursor finish_cursor;
    /// The face normals of the update's end (ref_normals) and its folded edges
    /// (folded_at_step): over the faces `changed` since the last end and the edges folded
    /// then, or (nullptr) over the whole mesh.
    void finish_normals(const std::vector<Face>* changed) {
        const auto locked = locked_edges(mesh);
        auto fold = [&](Edge e) {  // recounts e
            const bool now = !mesh.is_deleted(e) && is_folded(e, locked);
            if (now && !fold_flag[e.idx()]) fold_list.push_back(e.idx());
            fold_flag[e.idx()] = now ? 1 : 0;
        };
        if (changed == nullptr) {
            ref_normals.assign(mesh.faces_size(), Vec3{});
            for (Face f : mesh.faces()) ref_normals[f.idx()] = normalized(face_normal(f));
            fold_flag.assign(mesh.edges_size(), 0);
            fold_list.clear();
            for (Edge e : mesh.edges()) fold(e);
        } else {
            ref_normals.resize(mesh.faces_size(), Vec3{});
            fold_flag.resize(mesh.edges_size(), 0);
            const std::vector<std::uint32_t> before = fold_list;
            for (std::uint32_t e : before) fold(Edge(e));  // a fold may have gone with its edge
            for (Face f : *changed)
                if (!mesh.is_deleted(f)) {
                    ref_normals[f.idx()] = normalized(face_normal(f));
                    for_each_edge(f, fold);
                }
            // Each folded edge once.
            std::erase_if(fold_list, [&](std::uint32_t e) {
                if (fold_flag[e] != 1) return true;
                fold_flag[e] = 2;
                return false;
            });
            for (std::uint32_t e : fold_list) fold_flag[e] = 1;
        }
        folded_at_step = fold_list.size();
    }
    std::vector<char> fold_flag;           ///< per edge: folded at the last update's end
    std::vector<std::uint32_t> fold_list;  ///< those edges
    /// The samples of an edge's ends, smaller first.
    [[nodiscard]] std::array<SampleId, 2> ends_of(Edge e) const {
        const Halfedge h = SurfaceMesh::halfedge(e, 0);
        const SampleId a = sid(mesh.from_vertex(h)), b = sid(mesh.to_vertex(h));
        return {std::min(a, b), std::max(a, b)};
    }

    // ---- the local intersection test (spec §10.4) ----------------------------------------------
    /// Readers of the changes whose last look may lie before a renumbering (the intersection
    /// test, the global flip, the ball scan): each owns a bit of the face property kStale, set
    /// on the faces changed since it last looked (drain(), also run before every garbage
    /// collection), and reads every face when `all` (it never looked, its last look found the
    /// mesh wanting, or every face may have changed since).
    struct Tracker {
        std::uint8_t bit;
        Cursor cursor;
        bool all = true;
        /// The faces whose bit drain() set since t last looked (each once; some may have been
        /// deleted since): what stale_faces() and looked() read instead of every face.
        std::vector<Face> list;
    };
    static constexpr const char* kStale = "f:stale";
    Tracker stale_intersection{1}, stale_flip{2}, stale_balls{4};
    [[nodiscard]] std::array<Tracker*, 3> trackers() { return {&stale_intersection, &stale_flip, &stale_balls}; }
    [[nodiscard]] FaceProperty<std::uint8_t> stale_property() const {
        return mesh.get_face_property<std::uint8_t>(kStale);
    }
    /// Moves the changes since t's cursor into its bit.
    void drain(Tracker& t) {
        auto flag = stale_property();
        const bool known = changes_since(t.cursor, [&](Face f) {
            if (!mesh.is_deleted(f) && !(flag[f] & t.bit)) {
                flag[f] |= t.bit;
                t.list.push_back(f);
            }
        });
        if (!known) t.all = true;
    }
    /// The live faces changed since t last looked, in index order (all faces when t.all),
    /// after drain(t).
    [[nodiscard]] std::vector<Face> stale_faces(Tracker& t) {
        drain(t);
        std::vector<Face> out;
        if (t.all) {
            out.reserve(mesh.n_faces());
            for (Face f : mesh.faces()) out.push_back(f);
            return out;
        }
        const auto flag = stale_property();
        for (Face f : t.list)
            if (!mesh.is_deleted(f) && (flag[f] & t.bit)) out.push_back(f);
        std::sort(out.begin(), out.end(), [](Face a, Face b) { return a.idx() < b.idx(); });
        return out;
    }
    /// t has looked at everything (`ok`: and found it good; otherwise it reads every face
    /// next time).
    void looked(Tracker& t, bool ok) {
        drain(t);  // the changes t's own work made
        auto flag = stale_property();
        const auto keep = static_cast<std::uint8_t>(~t.bit);
        if (t.all) {
            for (Face f : mesh.faces()) flag[f] &= keep;
        } else {
            for (Face f : t.list)
                if (f.idx() < mesh.faces_size()) flag[f] &= keep;
        }
        t.list.clear();
        t.all = !ok;
    }
    /// After a renumbering, the lists again from the bits (one pass over the faces).
    void relist() {
        for (Tracker* tr : trackers()) tr->list.clear();
        ball_held.clear();
        const auto flag = stale_property();
        for (Face f : mesh.faces()) {
            for (Tracker* tr : trackers())
                if (flag[f] & tr->bit) tr->list.push_back(f);
            if (flag[f] & kBallHeld) ball_held.push_back(f);
        }
    }

    /// Whether the mesh intersects itself now (spec §10.4). Two faces that neither moved nor
    /// changed since the last embedded test cannot meet, so the faces tested are the changed
    /// ones (an Add, a Remove, a flip or a move made them, in a unit or in an update) and every
    /// face whose box meets one of theirs (its vertices lie within the longest edge, <= 2R, of
    /// that box). The whole mesh when more than half of the faces changed. Leaves the faces
    /// checked when it finds none.
    [[nodiscard]] bool intersection_test() {
        const std::vector<Face> changed = stale_faces(stale_intersection);
        bool hit = false;
        if (2 * changed.size() > mesh.n_faces()) {
            hit = has_self_intersections(mesh);
        } else if (!changed.empty()) {
            const double R = max_circumradius();
            Bbox3 box;
            for (Face f : changed)
                for (Vertex v : mesh.face_vertices(f)) box.extend(mesh.position(v));
            const Vec3 m{4 * R, 4 * R, 4 * R};  // a face's half box (<= R) plus its reach (2R)
            box.min = box.min - m;
            box.max = box.max + m;
            const PointGrid grid = vertex_grid(R, box);
            std::vector<char> in(mesh.faces_size(), 0);
            std::vector<Face> near;
            auto take = [&](Face g) {
                if (!in[g.idx()]) {
                    in[g.idx()] = 1;
                    near.push_back(g);
                }
                return false;
            };
            for (Face f : changed) {
                const Bbox3 b = detail::face_box(mesh, f);
                const Vec3 half = (b.max - b.min) * 0.5;
                const double reach = std::max({half.x, half.y, half.z}) + 2 * R * (1 + 1e-9);
                detail::for_each_face_meeting(mesh, grid, (b.min + b.max) * 0.5, reach, b,
                                              [&](std::uint32_t s) { return vert_of[s]; }, take);
                take(f);
            }
            hit = has_self_intersections(mesh, near);
        }
        looked(stale_intersection, !hit);
        return hit;
    }

    // ---- the region of a local update (spec §10.1) ---------------------------------------------
    /// Samples in the region (by slot; empty: no local update running) and their list; a
    /// vertex made during the update joins it (make_vertex).
    std::vector<char> region;
    std::vector<SampleId> region_ids;
    /// The ends (samples) of each edge at the last reset of its strain: an edge whose ends
    /// differ now was made or flipped since.
    std::vector<std::array<SampleId, 2>> edge_ends;
    /// Sets the region to the vertices `seeds` and their 2-ring.
    void set_region(const std::vector<SampleId>& seeds) {
        region.assign(pos.size(), 0);
        region_ids.clear();
        auto add = [&](SampleId s) {
            if (!region[s]) {
                region[s] = 1;
                region_ids.push_back(s);
            }
        };
        for (SampleId s : seeds) add(s);
        for (int ring = 0; ring < 2; ++ring) {
            const std::size_t n = region_ids.size();
            for (std::size_t i = 0; i < n; ++i)
                for (Halfedge h : mesh.outgoing_halfedges(vert_of[region_ids[i]])) add(sid(mesh.to_vertex(h)));
        }
    }
    /// How far around the region's box a local update's grids reach, in units of R.
    static constexpr double kRegionMargin = 8;
    /// The box of the region's vertices grown by kRegionMargin R (everything outside a local
    /// update).
    [[nodiscard]] Bbox3 region_box() const {
        Bbox3 b;
        if (region.empty()) {
            b.min = Vec3{-INFINITY, -INFINITY, -INFINITY};
            b.max = Vec3{INFINITY, INFINITY, INFINITY};
            return b;
        }
        for (SampleId s : region_ids)
            if (state[s] == State::Vertex) b.extend(P(s));
        const double m = kRegionMargin * max_circumradius();
        b.min = b.min - Vec3{m, m, m};
        b.max = b.max + Vec3{m, m, m};
        return b;
    }
    void clear_region() {
        region.clear();
        region_ids.clear();
    }

    /// Max fold between adjacent triangles (dot of normals <= 0 means an edge-angle <= 90);
    /// crease edges, sharp by design, do not count.
    std::size_t folded_edges() const {
        std::size_t n = 0;
        const auto locked = locked_edges(mesh);
        for (Edge e : mesh.edges()) n += is_folded(e, locked) ? 1 : 0;
        return n;
    }
    /// Whether e (not a crease edge) joins two faces whose normals make a dot <= 0.
    [[nodiscard]] bool is_folded(Edge e, const EdgeProperty<std::uint8_t>& locked) const {
        if (locked.is_valid() && locked[e]) return false;
        const Face f0 = mesh.face(SurfaceMesh::halfedge(e, 0)), f1 = mesh.face(SurfaceMesh::halfedge(e, 1));
        return f0.is_valid() && f1.is_valid() && dot(face_normal(f0), face_normal(f1)) <= 0;
    }
    Vec3 face_normal(Face f) const {
        const auto vs = mesh.face_vertices(f);
        return triangle_normal_raw(mesh.position(vs[0]), mesh.position(vs[1]), mesh.position(vs[2]));
    }

    /// The size field at t = 0 (DeformOptions::size_factor): from the caller's feature sizes,
    /// the reference mesh (estimated and graded there, then carried to each sample from its
    /// nearest reference vertex) or the analytic surface.
    void initial_size(std::span<const Point3> positions, const InitialSurface& initial) {
        if (!(params.size_factor > 0)) return;
        const double inf = std::numeric_limits<double>::infinity();
        std::vector<double> by_id(positions.size(), inf);
        if (!initial.feature_size.empty()) {
            if (initial.feature_size.size() != positions.size())
                throw InvalidInput("deform: " + std::to_string(initial.feature_size.size()) + " feature sizes for " +
                                   std::to_string(positions.size()) + " samples");
            for (std::size_t i = 0; i < by_id.size(); ++i) {
                const double f = initial.feature_size[i];
                if (!(f > 0)) throw InvalidInput("deform: the feature size of " + id_str(static_cast<SampleId>(i)) +
                                                 " is not positive");
                by_id[i] = params.size_factor * f;
            }
        } else if (initial.reference != nullptr) {
            const SurfaceMesh& ref = *initial.reference;
            const std::vector<double> r = graded_size(ref, mesh_feature_size(ref), params.size_factor, params.grading, inf);
            PointGrid g(init.h0);
            for (Vertex v : ref.vertices()) g.insert(static_cast<std::uint32_t>(v.idx()), ref.position(v));
            const auto at = [&](std::uint32_t i) { return ref.position(Vertex(i)); };
            for (std::size_t i = 0; i < by_id.size(); ++i) {
                const auto [w, d] = g.nearest(positions[i], at, [](std::uint32_t) { return true; });
                if (w != std::numeric_limits<std::uint32_t>::max()) by_id[i] = r[w] + params.grading * d;
            }
        } else if (initial.surface != nullptr) {
            for (std::size_t i = 0; i < by_id.size(); ++i)
                by_id[i] = params.size_factor * initial.surface->local_feature_size(positions[i]);
        } else {
            return;
        }
        size.assign(pos.size(), inf);
        for (std::size_t i = 0; i < by_id.size(); ++i) size[slot_of[i]] = std::max(by_id[i], 1e-300);
        size_on = true;
    }

    /// Step 1 of §4.1: h0 given, or estimated from the surface, the reference, the initial
    /// mesh or (last) an advancing-front reconstruction. `positions` in SampleId order.
    double initial_h0(std::span<const Point3> positions, const InitialSurface& initial) {
        double h0 = 0;
        if (params.h0) {
            h0 = *params.h0;
        } else if (initial.surface != nullptr) {
            // A seed unrelated to the samples (which may come from the same generator).
            const auto probes = initial.surface->sample_uniform(params.h0_probes, params.seed ^ 0x9E3779B97F4A7C15ULL);
            h0 = covering_radius(probes, pos);
            init.h0_estimated = true;
        } else if (initial.reference != nullptr) {
            h0 = covering_radius(reference_probes(*initial.reference), pos);
            init.h0_estimated = true;
        } else if (initial.mesh != nullptr) {
            h0 = largest_circumradius(*initial.mesh);
            init.h0_estimated = true;
        } else {
            h0 = largest_circumradius(reconstruct_advancing_front(positions));
            init.h0_estimated = true;
        }
        if (!(h0 > 0)) throw InvalidInput("deform: could not estimate h0 (the sampling radius) from the input");
        return h0;
    }

    /// Steps 2-4 of §4.1: Vert(0) (the greedy h0-net in slot order, or the caller's mesh) and
    /// Tri(0) (the caller's mesh, on the reference, the restricted Delaunay triangulation on
    /// the surface, or the advancing front), installed with every other sample dormant.
    void initial_triangulation(std::span<const Point3> positions, double h0, const InitialSurface& initial) {
        if (initial.mesh != nullptr) {
            const SurfaceMesh& m = *initial.mesh;
            if (initial.vertex_samples.size() != m.vertices_size())
                throw InvalidInput("deform: the initial mesh has " + std::to_string(m.vertices_size()) +
                                   " vertices but " + std::to_string(initial.vertex_samples.size()) + " sample ids");
            std::vector<char> seen(positions.size(), 0);
            for (SampleId s : initial.vertex_samples) {
                if (s >= positions.size()) throw InvalidInput("deform: initial mesh vertex names unknown " + id_str(s));
                if (seen[s]) throw InvalidInput("deform: initial mesh uses " + id_str(s) + " twice");
                seen[s] = 1;
            }
            require_valid_mesh(m, "deform: the initial mesh", MeshCheckOptions{.require_closed = true});
            SurfaceMesh copy = m;
            std::vector<SampleId> vs;
            for (SampleId s : initial.vertex_samples) vs.push_back(slot_of[s]);
            for (Vertex v : copy.vertices()) copy.position(v) = pos[vs[v.idx()]];
            init.net = vs.size();
            init.tri0 = "given";
            if (params.feature_angle_deg < 180.0)
                setup_creases(copy, [&](Vertex v) { return vs[v.idx()]; });
            install_mesh(std::move(copy), vs);
        } else {
            // Creases of the reference (spec §10.3), on a copy that carries their marks.
            SurfaceMesh creased;
            if (initial.reference != nullptr && params.feature_angle_deg < 180.0) {
                creased = *initial.reference;
                std::map<std::array<double, 3>, std::uint32_t> at;
                for (std::uint32_t s = 0; s < pos.size(); ++s) at.emplace(std::array<double, 3>{pos[s].x, pos[s].y, pos[s].z}, s);
                setup_creases(creased, [&](Vertex v) {
                    const Point3& q = creased.position(v);
                    const auto it = at.find({q.x, q.y, q.z});
                    return it == at.end() ? kNoSlot : it->second;
                });
            }
            // The greedy h0-net, scanning the corners, then the crease samples, then the
            // others, each in slot order.
            std::vector<SampleId> scan(pos.size());
            std::iota(scan.begin(), scan.end(), 0u);
            if (creases_on)
                std::stable_sort(scan.begin(), scan.end(), [&](SampleId a, SampleId b) {
                    auto rank = [&](SampleId s) { return corner_degree[s] > 0 ? 0 : crease_line[s] != kNoSlot ? 1 : 2; };
                    return rank(a) < rank(b);
                });
            std::vector<SampleId> vs;
            PointGrid g(h0);
            for (SampleId s : scan) {
                // With a size field, the net is as dense as the size asks (spec §10.2).
                const double hs = size_on ? std::min(h0, size[s]) : h0;
                bool close = false;
                g.for_each_candidate(pos[s], hs, [&](std::uint32_t w) {
                    if (!close && distance(pos[w], pos[s]) < hs) close = true;
                });
                if (!close) {
                    g.insert(s, pos[s]);
                    vs.push_back(s);
                }
            }
            std::sort(vs.begin(), vs.end());
            init.net = vs.size();
            if (vs.size() < 4)
                throw InvalidInput("deform: the sample set is too sparse: only " + std::to_string(vs.size()) +
                                   " samples are at least h0 = " + std::to_string(h0) + " apart");
            SurfaceMesh m;
            std::vector<SampleId> mapped;
            if (initial.reference != nullptr) {
                ReferenceMesh r;
                try {
                    r = initial_mesh_on_reference(pos, vs, creases_on ? creased : *initial.reference,
                                                  {.refine = params.init_refine,
                                                   .decimate_first = creases_on,
                                                   .size = size_on ? std::span<const double>(size) : std::span<const double>()});
                } catch (const InvalidInput& e) {
                    throw InvalidInput(std::string("deform: cannot build Tri(0) on the reference mesh (") + e.what() + ")");
                }
                m = std::move(r.mesh);
                mapped.assign(r.vertex_sample.begin(), r.vertex_sample.end());
                init.tri0 = std::string(to_string(r.path));
                init.net_added = r.added;
                init.init_insertions = r.promoted;
                if (creases_on && r.path != ReferenceMeshPath::Decimated) {
                    violation(Violation::InitFallback, "the creases are dropped: decimating the reference failed (" +
                                                           r.fallback_reason + ")");
                    drop_creases();
                } else if (!r.fallback_reason.empty() && !creases_on) {
                    violation(Violation::InitFallback, "Tri(0) by decimating the reference: " + r.fallback_reason);
                }
            } else {
                std::vector<Point3> pts;
                for (SampleId s : vs) pts.push_back(pos[s]);
                std::vector<std::uint32_t> used;
                try {
                    init.tri0 = initial.surface != nullptr ? "restricted_delaunay_surface" : "advancing_front";
                    if (initial.surface != nullptr) {
                        auto r = restricted_delaunay_with_report(pts, *initial.surface);
                        m = std::move(r.mesh);
                        used = std::move(r.report.vertex_sample);
                    } else {
                        auto r = reconstruct_advancing_front_with_report(pts);
                        m = std::move(r.mesh);
                        used = std::move(r.report.vertex_sample);
                    }
                } catch (const InvalidInput& e) {
                    throw InvalidInput(std::string("deform: the sample set is too sparse to mesh (") + e.what() +
                                       (initial.surface == nullptr
                                            ? "); with a mesh of the surface, pass it as InitialSurface::reference"
                                            : ")"));
                }
                if (used.size() != pts.size())
                    throw InvalidInput("deform: the sample set is too sparse to mesh: " +
                                       std::to_string(pts.size() - used.size()) + " of " + std::to_string(pts.size()) +
                                       " chosen vertices are in no triangle of the initial mesh");
                for (std::uint32_t i : used) mapped.push_back(vs[i]);
            }
            install_mesh(std::move(m), mapped);
        }
    }

    /// Makes `m` (vertex i = sample vs[i]) the mesh; every other live sample becomes dormant
    /// at its nearest vertex.
    void install_mesh(SurfaceMesh m, const std::vector<SampleId>& vs) {
        mesh = std::move(m);
        mesh.enable_face_log();
        all_changed();
        flips_settled = false;
        invalidate_pairs();
        // A caller's mesh may carry the properties already (e.g. another DeformingMesh's mesh).
        if (auto old = mesh.get_vertex_property<SampleId>("v:sample"); old.is_valid()) mesh.remove_property(old);
        if (auto locks = locked_edges(mesh); locks.is_valid() && !creases_on) mesh.remove_property(locks);
        vsample = mesh.add_vertex_property<SampleId>("v:sample", kNoSample);
        if (auto old = stale_property(); old.is_valid()) mesh.remove_property(old);
        (void)mesh.add_face_property<std::uint8_t>(kStale, 0);
        for (Tracker* tr : trackers()) {
            tr->all = true;
            tr->list.clear();
        }
        ball_held.clear();
        // The samples that were vertices or dormant (queued insertions stay queued).
        std::vector<SampleId> reassign;
        for (SampleId s = 0; s < state.size(); ++s) {
            dl[s].clear();
            vert_of[s] = Vertex();
            owner[s] = kNoSample;
            if (state[s] == State::Vertex || state[s] == State::Dormant) {
                state[s] = State::Pending;
                reassign.push_back(s);
            }
        }
        std::uint32_t i = 0;
        for (Vertex v : mesh.vertices()) make_vertex(vs[i++], v);
        double L = 0;
        for (Edge e : mesh.edges()) L = std::max(L, distance(mesh.position(mesh.vertex(e, 0)), mesh.position(mesh.vertex(e, 1))));
        PointGrid grid = vertex_grid(std::max(L, 1e-300));
        auto posf = [&](std::uint32_t s) { return P(s); };
        for (SampleId s : reassign) {
            if (state[s] != State::Pending) continue;  // became a vertex of m
            const auto [w, d] = grid.nearest(P(s), posf, [&](std::uint32_t x) { return state[x] == State::Vertex; });
            attach(s, w);
        }
    }
    /// Renumbers the mesh canonically: vertices in sample-id order, triangles sorted by their
    /// sample ids (each rotated to start at its smallest). Makes everything after it
    /// independent of how the mesh was built (CGAL's advancing front, for one, returns
    /// different but equally valid triangles from run to run).
    void canonicalize() {
        std::vector<SampleId> vs;
        for (Vertex v : mesh.vertices()) vs.push_back(sid(v));
        std::sort(vs.begin(), vs.end());
        std::vector<std::uint32_t> index(state.size(), 0);
        TriangleSoup soup;
        for (std::uint32_t i = 0; i < vs.size(); ++i) {
            index[vs[i]] = i;
            soup.points.push_back(P(vs[i]));
        }
        for (Face f : mesh.faces()) {
            const auto c = mesh.face_vertices(f);
            std::array<std::uint32_t, 3> t{index[sid(c[0])], index[sid(c[1])], index[sid(c[2])]};
            std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
            soup.triangles.push_back(t);
        }
        std::sort(soup.triangles.begin(), soup.triangles.end());
        const auto creases = crease_pairs();
        install_mesh(SurfaceMesh::from_soup(soup), vs);
        relock(creases);
    }

};

// ---- construction ---------------------------------------------------------------------------

DeformingMesh::~DeformingMesh() = default;
DeformingMesh::DeformingMesh(DeformingMesh&&) noexcept = default;
DeformingMesh& DeformingMesh::operator=(DeformingMesh&&) noexcept = default;

DeformingMesh::DeformingMesh(std::span<const Point3> positions, const DeformOptions& params,
                             const InitialSurface& initial)
    : impl_(std::make_unique<Impl>()) {
    const auto t0 = Clock::now();
    Impl& I = *impl_;
    if (!(std::isfinite(params.lambda) && params.lambda > 0))
        throw InvalidInput("deform: lambda (the displacement bound per time unit) must be positive and finite, got " +
                           std::to_string(params.lambda));
    if (!(std::isfinite(params.kappa) && params.kappa > 0))
        throw InvalidInput("deform: kappa must be positive and finite, got " + std::to_string(params.kappa));
    if (params.h0 && !(std::isfinite(*params.h0) && *params.h0 > 0))
        throw InvalidInput("deform: h0 must be positive and finite, got " + std::to_string(*params.h0));
    if (positions.size() < 4)
        throw InvalidInput("deform: at least 4 samples are needed, got " + std::to_string(positions.size()));
    if (positions.size() >= kNoSample) throw InvalidInput("deform: too many samples");
    for (std::size_t i = 0; i < positions.size(); ++i)
        if (!is_finite(positions[i]))
            throw InvalidInput("deform: sample " + std::to_string(i) + " has a non-finite coordinate");
    I.params = params;
    // Slots along the Morton curve of P(0).
    {
        const std::vector<std::uint32_t> order = spatial_order(positions);
        I.grow(positions.size());
        I.ext.assign(order.begin(), order.end());
        I.slot_of.assign(positions.size(), kNoSlot);
        for (std::uint32_t k = 0; k < order.size(); ++k) {
            I.slot_of[order[k]] = k;
            I.pos[k] = positions[order[k]];
        }
    }
    // Every sample is in P(0): install_mesh() makes it a vertex or places it in a dormant list.
    std::fill(I.state.begin(), I.state.end(), State::Dormant);
    I.live = positions.size();
    {   // coincident samples
        std::vector<std::uint32_t> order(positions.size());
        std::iota(order.begin(), order.end(), 0u);
        std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
            const Point3 &p = positions[a], &q = positions[b];
            if (p.x != q.x) return p.x < q.x;
            if (p.y != q.y) return p.y < q.y;
            if (p.z != q.z) return p.z < q.z;
            return a < b;
        });
        for (std::size_t i = 1; i < order.size(); ++i)
            if (positions[order[i]] == positions[order[i - 1]])
                throw InvalidInput("deform: samples " + std::to_string(order[i - 1]) + " and " +
                                   std::to_string(order[i]) + " coincide");
    }

    // 1-4 of §4.1: h0, Vert(0), dormant lists, Tri(0)
    I.init.h0 = I.initial_h0(positions, initial);
    I.initial_size(positions, initial);
    I.initial_triangulation(positions, I.init.h0, initial);
    {
        const auto rep = check_mesh(I.mesh, MeshCheckOptions{.require_closed = true});
        if (!rep.ok())
            throw InvalidInput("deform: the initial mesh is not a closed manifold (the sample set may be too sparse):\n" +
                               rep.summary("  "));
        I.euler = rep.integer("euler");
        I.components = static_cast<std::size_t>(rep.integer("components"));
    }
    I.global_flip();
    I.canonicalize();
    // Not in the paper: RefineVert until nothing changes, so that the first steps do not pay
    // for the initialisation (and a rigid motion then needs no change at all, spec §8.8).
    for (int round = 0; round < (params.init_refine ? 16 : 0); ++round) {
        const std::size_t before = I.cur.insertions;
        I.refine_vert();
        if (I.cur.insertions == before) break;
    }
    if (params.init_refine) I.spacing_repair();
    I.report_balls("after the initialisation's global flips");
    I.init.init_flips = I.cur.flips;
    I.init.init_insertions += I.cur.insertions;
    I.init.init_removals = I.cur.removals;
    I.init.euler = I.euler;
    I.init.components = I.components;
    I.cur = {};
    I.schedule();
    I.finish_update();
    I.init.samples = positions.size();
    I.init.vertices = I.mesh.n_vertices();
    I.init.faces = I.mesh.n_faces();
    I.init.R0 = I.R_last;
    I.init.next_step = I.next;
    I.init.self_intersecting = I.intersection_test();
    {   // spec §4.1: check the invariants at 0 and report any violation
        InvariantOptions io;
        io.self_intersections = false;
        io.empty_balls_soft = true;
        const CheckReport inv = check_invariants(io);
        I.init.invariant_failures = inv.problems;
        I.init.nonempty_balls = static_cast<std::size_t>(inv.integer("nonempty_balls"));
        I.init.first_nonempty_ball = inv.notes.empty() ? std::string() : inv.notes.front();
    }
    I.init.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    I.pending_violations.clear();
}

const InitReport& DeformingMesh::init_report() const { return impl_->init; }

// ---- time ----------------------------------------------------------------------------------

StepReport DeformingMesh::advance(int t, std::span<const Point3> positions) {
    {
        const Impl& I = *impl_;
        if (t <= I.t)
            throw InvalidInput("deform: advance(t = " + std::to_string(t) + ") after time " + std::to_string(I.t) +
                               ": time must increase");
        if (positions.size() < I.pos.size())
            throw InvalidInput("deform: the position table has " + std::to_string(positions.size()) +
                               " entries but sample ids go up to " + std::to_string(I.pos.size() - 1));
        for (SampleId id = 0; id < I.pos.size(); ++id)
            if (I.state[I.slot_of[id]] != State::Dead && !is_finite(positions[id]))
                throw InvalidInput("deform: sample " + std::to_string(id) + " has a non-finite position at t = " +
                                   std::to_string(t));
    }
    // Spec §10.4: a unit that ends with a new fold or (with intersection_checks) intersecting
    // itself is redone from its start with twice the sub-steps, up to max_retries times.
    const bool retry = impl_->params.max_substeps > 1 && impl_->params.max_retries > 0;
    // The state before the unit, taken by the first try once it cuts the unit into sub-steps
    // (a unit moved at once, the paper's case, costs no copy).
    std::unique_ptr<Impl> start;
    const bool was_intersecting = impl_->intersecting;
    std::size_t min_n = 1;
    for (std::size_t attempt = 0;; ++attempt) {
        StepReport rep;
        try {
            rep = impl_->frame(t, positions, min_n, retry && !start ? &start : nullptr);
        } catch (...) {
            if (start) impl_->restore(*start);  // the state before the unit
            throw;
        }
        rep.retries = attempt;
        impl_->intersecting = rep.self_intersecting;
        // New folds and new intersections, not normals against those of the last update,
        // which a rigid turn by more than 90 degrees since then inverts too.
        const bool bad = rep.new_folds > 0 || (rep.self_intersecting && !was_intersecting);
        if (!bad || !start || attempt >= impl_->params.max_retries || rep.substeps >= impl_->params.max_substeps)
            return rep;
        min_n = 2 * rep.substeps;
        impl_->restore(*start);
    }
}

StepReport DeformingMesh::Impl::frame(int t, std::span<const Point3> positions, std::size_t min_n,
                                      std::unique_ptr<Impl>* save) {
    Impl& I = *this;
    I.pending_violations.clear();
    StepReport rep;
    rep.t = t;
    const int dt = t - I.t;
    I.t = t;
    // The positions at t, in slot order (dead slots keep theirs).
    std::vector<Point3> to(I.pos.size());
    double maxd = 0;
    SampleId worst = kNoSample;
    for (SampleId s = 0; s < I.pos.size(); ++s) {
        if (I.state[s] == State::Dead) {
            to[s] = I.pos[s];
            continue;
        }
        to[s] = positions[I.ext[s]];
        const double d = distance(to[s], I.pos[s]);
        if (d > maxd) {
            maxd = d;
            worst = s;
        }
    }
    I.substep_to(to, rep, min_n, save, t - dt);
    rep.max_displacement = maxd;
    bool trip = false;
    if (maxd > I.params.lambda * dt * (1 + 1e-9)) {
        I.violation(Violation::DisplacementExceedsLambda,
                    I.idstr(worst) + " moved " + std::to_string(maxd) + " > lambda = " + std::to_string(I.params.lambda) +
                        (dt > 1 ? " x " + std::to_string(dt) + " units" : ""));
        trip = true;
    }
    rep.R = I.max_circumradius();
    const double bound = growth_bound(I.params.kappa);
    if (rep.R > bound * I.R_last) {
        I.violation(Violation::CircumradiusGrowth, "R = " + std::to_string(rep.R) + " > " + std::to_string(bound) +
                                                       " x R at the last step (" + std::to_string(I.R_last) + ")");
        trip = true;
    }
    std::size_t inverted = 0;
    Face first_inv;
    for (Face f : I.mesh.faces())
        if (f.idx() < I.ref_normals.size() && dot(I.face_normal(f), I.ref_normals[f.idx()]) <= 0) {
            if (inverted++ == 0) first_inv = f;
        }
    if (inverted > 0) {
        I.violation(Violation::NormalInverted, std::to_string(inverted) +
                                                   " triangle normals turned by >= 90 degrees, e.g. " +
                                                   I.face_str(first_inv));
        trip = true;
    }
    const std::size_t folded = I.folded_edges();
    if (folded > I.folded_at_step) {
        I.violation(Violation::EdgeAngleBelow90, std::to_string(folded) + " edges with an edge-angle <= 90 degrees (" +
                                                     std::to_string(I.folded_at_step) + " at the last step)");
        trip = true;
    }
    rep.inverted_triangles = inverted;
    rep.new_folds = folded > I.folded_at_step ? folded - I.folded_at_step : 0;
    // Only a cut unit, or one that ends with a new fold or an inverted triangle, is tested: one
    // moved at once within the budget (the paper's case) keeps the state it had.
    rep.self_intersecting = I.intersecting;
    if (I.params.intersection_checks && (rep.substeps > 1 || rep.internal_updates > 0 || rep.new_folds > 0 || inverted > 0)) {
        // Spec §10.4: local, against the state of the last test, when that one was embedded.
        rep.self_intersecting = I.intersection_test();
    }
    rep.emergency = trip && I.params.emergency_steps && t < I.next;
    I.emergency_requested = rep.emergency;
    rep.update_due = t >= I.next || rep.emergency;
    rep.violations = I.pending_violations;
    return rep;
}

DeformUpdateReport DeformingMesh::update() {
    Impl& I = *impl_;
    I.pending_violations.clear();
    DeformUpdateReport rep = I.mesh_update(false);
    rep.violations = I.pending_violations;
    return rep;
}

SampleId DeformingMesh::queue_insertion(const Point3& p) {
    Impl& I = *impl_;
    if (!is_finite(p)) throw InvalidInput("deform: an inserted sample has a non-finite position");
    if (I.pos.size() + 1 >= kNoSample) throw InvalidInput("deform: too many samples");
    const std::uint32_t s = I.new_slot();
    I.pos[s] = p;
    I.state[s] = State::Pending;
    I.pending_insert.push_back(s);
    ++I.live;
    return I.ext[s];
}

void DeformingMesh::queue_deletion(SampleId id) {
    Impl& I = *impl_;
    if (id >= I.pos.size() || I.state[I.slot_of[id]] == State::Dead)
        throw InvalidInput("deform: cannot delete " + id_str(id) + ": no such live sample");
    if (I.state[I.slot_of[id]] == State::Pending)
        throw InvalidInput("deform: cannot delete " + id_str(id) + ": its insertion is still queued");
    I.pending_delete.push_back(I.slot_of[id]);
}

int DeformingMesh::time() const { return impl_->t; }
int DeformingMesh::next_step() const { return impl_->next; }
double DeformingMesh::lambda() const { return impl_->params.lambda; }
const DeformOptions& DeformingMesh::params() const { return impl_->params; }
const SurfaceMesh& DeformingMesh::mesh() const { return impl_->mesh; }
SampleId DeformingMesh::sample_of(Vertex v) const {
    if (!v.is_valid() || v.idx() >= impl_->mesh.vertices_size()) return kNoSample;
    const SampleId s = impl_->vsample[v];
    return s == kNoSample ? kNoSample : impl_->ext[s];
}
Vertex DeformingMesh::vertex_of(SampleId id) const {
    if (id >= impl_->pos.size()) return Vertex();
    const std::uint32_t s = impl_->slot_of[id];
    if (impl_->state[s] != State::Vertex) return Vertex();
    return impl_->vert_of[s];
}
SampleId DeformingMesh::owner_of(SampleId id) const {
    if (id >= impl_->pos.size()) return kNoSample;
    const std::uint32_t s = impl_->slot_of[id];
    if (impl_->state[s] != State::Dormant) return kNoSample;
    return impl_->ext[impl_->owner[s]];
}
std::size_t DeformingMesh::id_capacity() const { return impl_->pos.size(); }
bool DeformingMesh::is_live(SampleId id) const {
    return id < impl_->pos.size() && impl_->state[impl_->slot_of[id]] != State::Dead;
}
std::size_t DeformingMesh::live_samples() const { return impl_->live; }
double DeformingMesh::max_circumradius() const { return impl_->max_circumradius(); }
const std::vector<ViolationRecord>& DeformingMesh::violations() const { return impl_->violations; }
const UpdateCounters& DeformingMesh::totals() const { return impl_->totals; }
std::size_t DeformingMesh::updates() const { return impl_->n_updates; }

// ---- invariants -----------------------------------------------------------------------------

CheckReport DeformingMesh::check_invariants(const InvariantOptions& options) const {
    const Impl& I = *impl_;
    CheckReport r;
    auto fail = [&](std::string s) { r.fail(std::move(s), 50); };
    // The figures, added at the end in this order.
    double R = 0, min_spacing = 0, max_radius_edge = 0, max_dormant_distance = 0;
    std::size_t nonempty_balls = 0, self_intersections = 0, samples = 0, vertices = 0, dormant = 0;
    const auto mc = check_mesh(I.mesh, MeshCheckOptions{.require_closed = true});
    if (!mc.ok()) fail("mesh: " + mc.summary());
    if (mc.integer("euler") != I.euler)
        fail("Euler characteristic " + std::to_string(mc.integer("euler")) + " != " + std::to_string(I.euler) + " at t = 0");
    if (static_cast<std::size_t>(mc.integer("components")) != I.components)
        fail(std::to_string(mc.integer("components")) + " components != " + std::to_string(I.components) + " at t = 0");
    vertices = I.mesh.n_vertices();
    R = I.max_circumradius();
    // sample states and the mesh agree
    for (Vertex v : I.mesh.vertices()) {
        const SampleId s = I.sid(v);
        if (s >= I.pos.size() || I.state[s] != State::Vertex || I.vert_of[s] != v)
            fail("vertex " + std::to_string(v.idx()) + " is not tied to its sample" +
                 (s < I.pos.size() ? " " + std::to_string(I.ext[s]) : ""));
        else if (I.mesh.position(v) != I.pos[s])
            fail("vertex of " + I.idstr(s) + " is not at its sample's position");
    }
    // the sub-step bookkeeping covers the pairs of this mesh: a pair table not due for a
    // rebuild lists every mesh edge and dormant pair, in order, with its current budget
    if (!I.pairs_dirty) {
        const auto& pt = I.pairs;
        std::size_t i = 0, stale = 0;
        I.for_each_pair([&](std::size_t k, SampleId a, SampleId b) {
            if (i >= pt.key.size() || pt.key[i] != k || pt.a[i] != a || pt.b[i] != b ||
                pt.budget[i] != I.pair_budget(a, b))
                ++stale;
            ++i;
        });
        if (stale > 0 || i != pt.key.size())
            fail("the sub-step pair table is stale: " + std::to_string(stale) + " of " + std::to_string(i) +
                 " pairs differ, " + std::to_string(pt.key.size()) + " listed");
    }
    // dormant lists partition P \ Vert
    std::size_t in_lists = 0;
    for (SampleId s = 0; s < I.pos.size(); ++s) {
        if (I.state[s] == State::Vertex) {
            for (std::uint32_t i = 0; i < I.dl[s].size(); ++i) {
                const SampleId p = I.dl[s][i];
                if (I.state[p] != State::Dormant || I.owner[p] != s || I.dpos[p] != i)
                    fail("dormant list of " + I.idstr(s) + " holds " + I.idstr(p) + " inconsistently");
            }
            in_lists += I.dl[s].size();
        } else if (I.state[s] == State::Dormant) {
            ++dormant;
            const SampleId o = I.owner[s];
            if (o >= I.pos.size() || I.state[o] != State::Vertex) {
                fail(I.idstr(s) + " is dormant but its owner is not a vertex");
                continue;
            }
            const double d = distance(I.pos[s], I.pos[o]);
            max_dormant_distance = std::max(max_dormant_distance, d);
            if (d > options.dormant_factor * R)
                fail(I.idstr(s) + " is " + std::to_string(d / R) + " R from its owner " + I.idstr(o));
        }
        if (I.state[s] == State::Vertex || I.state[s] == State::Dormant) ++samples;
    }
    if (in_lists != dormant)
        fail("dormant lists hold " + std::to_string(in_lists) + " samples but " + std::to_string(dormant) +
             " samples are dormant");
    // triangle shape (a graded size allows 3 (1 + 2 L), spec §10.2)
    const double re_bound = options.radius_edge_bound * (I.size_on ? 1.0 + 2.0 * I.params.grading : 1.0);
    for (Face f : I.mesh.faces()) {
        const auto vs = I.mesh.face_vertices(f);
        const double re = radius_edge_ratio(I.mesh.position(vs[0]), I.mesh.position(vs[1]), I.mesh.position(vs[2]));
        max_radius_edge = std::max(max_radius_edge, re);
        if (!(re <= re_bound))
            fail("triangle " + I.face_str(f) + " has radius-edge ratio " + std::to_string(re));
    }
    // spacing and empty balls
    if (R > 0) {
        PointGrid g = I.vertex_grid(R);
        min_spacing = std::numeric_limits<double>::infinity();
        for (Vertex v : I.mesh.vertices()) {
            const SampleId s = I.sid(v);
            g.for_each_candidate(I.pos[s], R, [&](std::uint32_t w) {
                if (w == s) return;
                const double d = distance(I.pos[w], I.pos[s]);
                min_spacing = std::min(min_spacing, d);
                const double r = std::min(I.rs(s, R), I.rs(w, R));
                // Two corners of the creases are fixed by the input and never removed.
                const bool corners = I.corner_degree[s] > 0 && I.corner_degree[w] > 0;
                if (I.ext[w] > I.ext[s] && d < options.spacing_factor * r && !corners)
                    fail("vertices " + I.idstr(s) + " and " + I.idstr(w) + " are " + std::to_string(d / r) +
                         (r < R ? " r (their local size) apart" : " R apart"));
            });
        }
        if (options.empty_balls) {
            const auto b = I.scan_balls(g);
            nonempty_balls = b.count;
            if (b.count > 0) {
                std::string first = "the diametric ball of triangle " + I.face_str(b.first) + " holds " +
                                    std::to_string(b.first_hits) + " vertices (e.g. " + I.idstr(b.inside) + ")";
                if (options.empty_balls_soft) {
                    r.notes.push_back(std::move(first));
                } else {
                    fail(std::move(first));
                    if (b.count > 1) fail(std::to_string(b.count) + " diametric balls hold vertices in all");
                }
            }
        }
    }
    std::vector<std::string> crease_lines;
    const std::size_t crease_problems = I.crease_problems(crease_lines, 10);
    for (auto& line : crease_lines) fail(std::move(line));
    if (I.creases_on) {
        r.add("crease_edges", locked_edge_count(I.mesh));
        r.add("crease_problems", crease_problems);
    }
    if (options.self_intersections) {
        self_intersections = count_self_intersections(I.mesh);
        if (self_intersections > 0) fail(std::to_string(self_intersections) + " pairs of triangles intersect");
    }
    r.add("R", R);
    r.add("min_spacing", min_spacing);
    r.add("max_radius_edge", max_radius_edge);
    r.add("max_dormant_distance", max_dormant_distance);
    r.add("nonempty_balls", nonempty_balls);
    r.add("self_intersections", self_intersections);
    r.add("samples", samples);
    r.add("vertices", vertices);
    r.add("dormant", dormant);
    return r;
}

}  // namespace dynmesh
