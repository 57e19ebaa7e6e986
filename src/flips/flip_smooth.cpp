#include "dynmesh/flips/flip_smooth.hpp"

#include <algorithm>
#include <chrono>
#include <deque>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/mesh_order.hpp"

namespace dynmesh {

namespace {

using Clock = std::chrono::steady_clock;

/// In-queue flags with one byte per edge of the mesh: for runs over the whole mesh.
class DenseEdgeFlags {
public:
    explicit DenseEdgeFlags(std::size_t edges) : flag_(edges, 0) {}
    /// Sets the flag; false when it was set already.
    bool set(Edge e) {
        char& f = flag_[e.idx()];
        if (f) return false;
        f = 1;
        return true;
    }
    void clear(Edge e) { flag_[e.idx()] = 0; }

private:
    std::vector<char> flag_;
};

/// The same in a hash set: for runs whose region is much smaller than the mesh.
class SparseEdgeFlags {
public:
    bool set(Edge e) { return set_.insert(e.idx()); }
    void clear(Edge e) { set_.erase(e.idx()); }

private:
    IndexSet set_;
};

/// The FIFO flip loop shared by global and local flipping. `allowed(e)` restricts which
/// edges may enter the queue after a flip; `on_flip(e)` observes each flip.
template <class Flags>
class FlipQueue {
public:
    FlipQueue(SurfaceMesh& m, FlipRule rule, double feature_angle_deg, FlipReport& report, Flags flags)
        : mesh_(m), rule_(rule), feature_angle_deg_(feature_angle_deg), locked_(locked_edges(m)), report_(report),
          in_queue_(std::move(flags)) {}

    bool test(Edge e) {
        ++report_.checks;
        const FlipVerdict v = flip_verdict(mesh_, e, rule_, feature_angle_deg_, locked_);
        if (v == FlipVerdict::Degenerate) ++report_.degenerate;
        if (v == FlipVerdict::NotImproving) ++report_.not_improving;
        if (v == FlipVerdict::FeatureLocked) ++report_.feature_locked;
        return v == FlipVerdict::Flippable;
    }
    /// Queues e unless it is queued already; it is tested once, when popped.
    void push(Edge e) {
        if (!in_queue_.set(e)) return;
        queue_.push_back(e);
        ++report_.pushes;
    }
    template <class Allowed, class OnFlip>
    void run(std::size_t max_flips, const FlipProgress& progress, Allowed&& allowed, OnFlip&& on_flip) {
        report_.converged = true;
        while (!queue_.empty()) {
            const Edge e = queue_.front();
            queue_.pop_front();
            in_queue_.clear(e);
            if (!test(e)) continue;
            if (report_.flips >= max_flips) {
                report_.converged = false;
                break;
            }
            const Halfedge h0 = SurfaceMesh::halfedge(e, 0), h1 = SurfaceMesh::halfedge(e, 1);
            mesh_.flip(e);
            ++report_.flips;
            on_flip(e);
            // The four outer edges of the quad.
            for (Halfedge h : {mesh_.next(h0), mesh_.prev(h0), mesh_.next(h1), mesh_.prev(h1)}) {
                const Edge b = SurfaceMesh::edge(h);
                if (allowed(b)) push(b);
            }
            if (progress && (report_.flips & 0xFFFFF) == 0) progress(report_.flips, queue_.size());
        }
        while (!queue_.empty()) {  // left over after the cap
            in_queue_.clear(queue_.front());
            queue_.pop_front();
        }
    }

private:
    SurfaceMesh& mesh_;
    FlipRule rule_;
    double feature_angle_deg_;
    EdgeProperty<std::uint8_t> locked_;  ///< the mesh's kLockedEdges (fixed while it runs)
    FlipReport& report_;
    Flags in_queue_;
    std::deque<Edge> queue_;
};

/// per_vertex * n, saturating instead of wrapping.
std::size_t flip_cap(std::size_t per_vertex, std::size_t n) {
    per_vertex = std::max<std::size_t>(per_vertex, 1);
    n = std::max<std::size_t>(n, 1);
    return per_vertex > SIZE_MAX / n ? SIZE_MAX : per_vertex * n;
}

constexpr auto kAnyEdge = [](Edge) { return true; };
constexpr auto kNoObserver = [](Edge) {};

bool should_renumber(const SurfaceMesh& mesh, FlipReorder reorder) {
    switch (reorder) {
        case FlipReorder::Always: return true;
        case FlipReorder::Never: return false;
        case FlipReorder::Auto: break;
    }
    return mesh.n_vertices() >= kReorderMinVertices &&
           scattered_edge_fraction(mesh) > kReorderScatteredFraction;
}

/// Runs the queue over every edge of the mesh, in index order.
void flip_every_edge(SurfaceMesh& mesh, const FlipOptions& options, FlipReport& report) {
    FlipQueue q(mesh, options.rule, options.feature_angle_deg, report, DenseEdgeFlags(mesh.edges_size()));
    for (Edge e : mesh.edges()) q.push(e);
    q.run(flip_cap(options.max_flips_per_vertex, mesh.n_vertices()), options.progress, kAnyEdge, kNoObserver);
}

}  // namespace

FlipReport flip_all(SurfaceMesh& mesh, const FlipOptions& options) {
    DYNMESH_CHECK(!mesh.has_garbage(), "flip_all: the mesh has deleted elements; call garbage_collection() first");
    FlipReport report;
    const auto t0 = Clock::now();
    report.renumbered = should_renumber(mesh, options.reorder);
    if (!report.renumbered) {
        flip_every_edge(mesh, options, report);
    } else {
        // Flip in a spatially coherent numbering, then give the caller's numbering back (a
        // permutation and its inverse: positions come back bit for bit, and every edge and
        // face index means what a flip in place would have made it mean).
        const MeshOrder order = spatial_mesh_order(mesh);
        permute(mesh, order);
        try {
            flip_every_edge(mesh, options, report);
        } catch (...) {
            permute(mesh, inverse(order));
            throw;
        }
        permute(mesh, inverse(order));
    }
    report.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return report;
}

namespace {

template <class Flags>
void flip_from_seeds(SurfaceMesh& mesh, std::span<const Edge> seeds, const FlipOptions& options,
                     FlipReport& report, Flags flags) {
    FlipQueue q(mesh, options.rule, options.feature_angle_deg, report, std::move(flags));
    for (Edge e : seeds)
        if (e.is_valid() && e.idx() < mesh.edges_size() && !mesh.is_deleted(e)) q.push(e);
    q.run(flip_cap(options.max_flips_per_vertex, mesh.n_vertices()), {}, kAnyEdge, kNoObserver);
}

}  // namespace

FlipReport flip_from(SurfaceMesh& mesh, std::span<const Edge> seeds, const FlipOptions& options) {
    FlipReport report;
    const auto t0 = Clock::now();
    // A byte per edge costs O(mesh) to clear; a hash set costs O(1) per queued edge.
    if (seeds.size() >= mesh.edges_size() / 64)
        flip_from_seeds(mesh, seeds, options, report, DenseEdgeFlags(mesh.edges_size()));
    else
        flip_from_seeds(mesh, seeds, options, report, SparseEdgeFlags());
    report.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return report;
}

void hop_distances(std::span<const SurfaceMesh* const> meshes, std::span<const Vertex> V, std::size_t limit,
                   IndexMap<std::uint32_t>& dist) {
    dist.clear();
    std::vector<Vertex> frontier, next;
    for (Vertex v : V)
        if (dist.try_emplace(v.idx(), 0).second) frontier.push_back(v);
    for (std::uint32_t d = 1; d <= limit && !frontier.empty(); ++d) {
        next.clear();
        for (Vertex v : frontier)
            for (const SurfaceMesh* m : meshes)
                for (Halfedge h : m->outgoing_halfedges(v)) {
                    const Vertex w = m->to_vertex(h);
                    if (dist.try_emplace(w.idx(), d).second) next.push_back(w);
                }
        frontier.swap(next);
    }
}

void hop_distances(const SurfaceMesh& m, std::span<const Vertex> V, std::size_t limit,
                   IndexMap<std::uint32_t>& dist) {
    const SurfaceMesh* one = &m;
    hop_distances(std::span<const SurfaceMesh* const>(&one, 1), V, limit, dist);
}

namespace {

using HopMap = IndexMap<std::uint32_t>;

struct StopTest {
    bool pass = true;
    std::size_t ring_faces = 0, ball_tests = 0, unchecked_balls = 0;
};

/// The stop test of the doubling window (see LocalFlipReport): `hops` holds the vertices
/// within m + 1 hops of V after the round's flips.
StopTest local_stop_test(const SurfaceMesh& mesh, const HopMap& hops, std::size_t m) {
    auto hop = [&](Vertex v) {
        const std::uint32_t* d = hops.find(v.idx());
        return d ? std::size_t(*d) : m + 2;
    };
    // F: the faces around the vertices at hop <= 1. The ring: the faces around the vertices
    // at hop m + 1 (hops change by at most 1 along an edge, so every unmarked face that
    // touches a vertex within m + 1 hops has a corner at m + 1). Each face is taken once,
    // from its first corner (in face_vertices order) in that layer.
    std::vector<Face> F, ring;
    auto collect = [&](Vertex v, auto&& in_layer, std::vector<Face>& out) {
        for (Halfedge h : mesh.outgoing_halfedges(v)) {
            const Face f = mesh.face(h);
            if (!f.is_valid()) continue;
            const auto c = mesh.face_vertices(f);
            const Vertex first = in_layer(c[0]) ? c[0] : in_layer(c[1]) ? c[1] : c[2];
            if (first == v) out.push_back(f);
        }
    };
    hops.for_each([&](std::uint32_t vi, std::uint32_t d) {
        if (d <= 1) collect(Vertex(vi), [&](Vertex x) { return hop(x) <= 1; }, F);
        if (d == m + 1) collect(Vertex(vi), [&](Vertex x) { return hop(x) == m + 1; }, ring);
    });
    StopTest st;
    st.ring_faces = ring.size();
    if (ring.empty()) {
        st.ball_tests = F.size();
        return st;
    }
    // Uniform grid over the ring's centroids, cell = twice its mean edge length (a query box
    // of a typical ball spans 2-3 cells per axis). A triangle lies within `reach` of its
    // centroid; the few much larger than a cell are tested always.
    double len = 0;
    for (Face f : ring) {
        const auto c = mesh.face_vertices(f);
        len += distance(mesh.position(c[0]), mesh.position(c[1])) + distance(mesh.position(c[1]), mesh.position(c[2])) +
               distance(mesh.position(c[2]), mesh.position(c[0]));
    }
    const double cell = 2 * len / double(3 * ring.size());
    PointGrid grid(std::isfinite(cell) && cell > 0 ? cell : 1.0);
    std::vector<Face> big;
    double reach = 0;
    for (std::uint32_t i = 0; i < ring.size(); ++i) {
        const auto c = mesh.face_vertices(ring[i]);
        const Point3 &a = mesh.position(c[0]), &b = mesh.position(c[1]), &d = mesh.position(c[2]);
        const Point3 g = (a + b + d) * (1.0 / 3.0);
        const double r = std::max({distance(g, a), distance(g, b), distance(g, d)});
        if (r > 4 * grid.cell()) {
            big.push_back(ring[i]);
        } else {
            grid.insert(i, g);
            reach = std::max(reach, r);
        }
    }
    auto meets = [&](Face g, const Point3& cc, double rad) {
        const auto c = mesh.face_vertices(g);
        return closest_point_on_triangle(cc, mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2])).distance < rad;
    };
    for (Face f : F) {
        const auto c = mesh.face_vertices(f);
        const Point3 &a = mesh.position(c[0]), &b = mesh.position(c[1]), &d = mesh.position(c[2]);
        const Point3 cc = circumcenter(a, b, d);
        const double rad = distance(cc, a);
        if (!is_finite(cc) || !std::isfinite(rad)) {
            ++st.unchecked_balls;
            continue;
        }
        ++st.ball_tests;
        bool hit = std::any_of(big.begin(), big.end(), [&](Face g) { return meets(g, cc, rad); });
        if (!hit)
            grid.for_each_candidate(cc, rad + reach, [&](std::uint32_t i) { hit = hit || meets(ring[i], cc, rad); });
        if (hit) {
            st.pass = false;
            return st;
        }
    }
    return st;
}

}  // namespace

LocalFlipReport flip_local(SurfaceMesh& mesh, std::span<const Vertex> V, const LocalFlipOptions& options) {
    DYNMESH_CHECK(!mesh.has_garbage(), "flip_local: the mesh has deleted elements; call garbage_collection() first");
    for (Vertex v : V)
        DYNMESH_CHECK(mesh.is_valid(v) && !mesh.is_deleted(v),
                      "flip_local: vertex " + std::to_string(v.idx()) + " is not in the mesh");
    DYNMESH_CHECK(options.m0 >= 1, "flip_local: m0 must be at least 1");
    LocalFlipReport out;
    const auto t0 = Clock::now();
    IndexSet changed;
    HopMap hops;
    std::vector<std::uint32_t> window;
    std::size_t m = options.m0;
    FlipQueue q(mesh, options.rule, options.feature_angle_deg, out.flips, SparseEdgeFlags());
    for (std::size_t round = 0; round < options.max_rounds; ++round, m *= 2) {
        ++out.rounds;
        out.final_m = m;
        hop_distances(mesh, V, m, hops);
        auto inside = [&](Vertex v) { return hops.contains(v.idx()); };
        auto allowed = [&](Edge e) { return inside(mesh.vertex(e, 0)) && inside(mesh.vertex(e, 1)); };
        // Seed the window's edges in vertex order (the hash map's order is not portable).
        window.clear();
        hops.for_each([&](std::uint32_t v, std::uint32_t) { window.push_back(v); });
        std::sort(window.begin(), window.end());
        for (std::uint32_t vi : window)
            for (Halfedge h : mesh.outgoing_halfedges(Vertex(vi))) {
                const Vertex w = mesh.to_vertex(h);
                if (vi < w.idx() && inside(w)) q.push(SurfaceMesh::edge(h));
            }
        q.run(flip_cap(options.max_flips_per_vertex, hops.size()), {}, allowed, [&](Edge e) {
            changed.insert(mesh.face(SurfaceMesh::halfedge(e, 0)).idx());
            changed.insert(mesh.face(SurfaceMesh::halfedge(e, 1)).idx());
        });
        // Stop test, in the edge graph after the flips.
        hop_distances(mesh, V, m + 1, hops);
        out.window_vertices = 0;
        hops.for_each([&](std::uint32_t, std::uint32_t d) { out.window_vertices += d <= m; });
        if (!out.flips.converged) break;  // the flip cap was reached
        const StopTest st = local_stop_test(mesh, hops, m);
        out.ring_faces = st.ring_faces;
        out.ball_tests = st.ball_tests;
        out.unchecked_balls = st.unchecked_balls;
        if (st.pass) {
            out.converged = true;
            break;
        }
    }
    out.changed_faces.reserve(changed.size());
    changed.for_each([&](std::uint32_t f) { out.changed_faces.push_back(Face(f)); });
    std::sort(out.changed_faces.begin(), out.changed_faces.end());
    out.flips.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    out.flips.converged = out.converged;
    return out;
}

}  // namespace dynmesh
