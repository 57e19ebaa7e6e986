#include "dynmesh/flips/flip_smooth.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <unordered_map>
#include <unordered_set>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"

namespace dynmesh {

namespace {

using Clock = std::chrono::steady_clock;

/// The FIFO flip loop shared by global and local flipping. `allowed(e)` restricts which
/// edges may enter the queue; `on_flip(e)` observes each flip.
class FlipQueue {
public:
    FlipQueue(SurfaceMesh& m, FlipRule rule, double feature_angle_deg, FlipReport& report)
        : mesh_(m),
          rule_(rule),
          feature_angle_deg_(feature_angle_deg),
          report_(report),
          in_queue_(m.edges_size(), 0) {}

    bool test(Edge e) {
        ++report_.checks;
        const FlipVerdict v = flip_verdict(mesh_, e, rule_, feature_angle_deg_);
        if (v == FlipVerdict::Degenerate) ++report_.degenerate;
        if (v == FlipVerdict::NotImproving) ++report_.not_improving;
        if (v == FlipVerdict::FeatureLocked) ++report_.feature_locked;
        return v == FlipVerdict::Flippable;
    }
    /// Queues e unless it is queued already; it is tested once, when popped.
    void push(Edge e) {
        if (in_queue_[e.idx()]) return;
        in_queue_[e.idx()] = 1;
        queue_.push_back(e);
        ++report_.pushes;
    }
    template <class Allowed, class OnFlip>
    void run(std::size_t max_flips, const FlipProgress& progress, Allowed&& allowed,
             OnFlip&& on_flip) {
        report_.converged = true;
        while (!queue_.empty()) {
            const Edge e = queue_.front();
            queue_.pop_front();
            in_queue_[e.idx()] = 0;
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
        queue_.clear();
    }

private:
    SurfaceMesh& mesh_;
    FlipRule rule_;
    double feature_angle_deg_;
    FlipReport& report_;
    std::vector<char> in_queue_;
    std::deque<Edge> queue_;
};

/// per_vertex * n, saturating instead of wrapping.
std::size_t flip_cap(std::size_t per_vertex, std::size_t n) {
    per_vertex = std::max<std::size_t>(per_vertex, 1);
    n = std::max<std::size_t>(n, 1);
    return per_vertex > SIZE_MAX / n ? SIZE_MAX : per_vertex * n;
}

}  // namespace

FlipReport flip_all(SurfaceMesh& mesh, const FlipOptions& options) {
    DYNMESH_CHECK(!mesh.has_garbage(), "flip_all: the mesh has deleted elements; call garbage_collection() first");
    FlipReport report;
    const auto t0 = Clock::now();
    FlipQueue q(mesh, options.rule, options.feature_angle_deg, report);
    for (Edge e : mesh.edges()) q.push(e);
    const std::size_t cap = flip_cap(options.max_flips_per_vertex, mesh.n_vertices());
    q.run(cap, options.progress, [](Edge) { return true; }, [](Edge) {});
    report.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return report;
}

FlipReport flip_from(SurfaceMesh& mesh, std::span<const Edge> seeds, const FlipOptions& options) {
    FlipReport report;
    const auto t0 = Clock::now();
    FlipQueue q(mesh, options.rule, options.feature_angle_deg, report);
    for (Edge e : seeds)
        if (e.is_valid() && e.idx() < mesh.edges_size() && !mesh.is_deleted(e)) q.push(e);
    const std::size_t cap = flip_cap(options.max_flips_per_vertex, mesh.n_vertices());
    q.run(cap, {}, [](Edge) { return true; }, [](Edge) {});
    report.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return report;
}

namespace {

/// Hop distances from V up to `limit` (BFS in the current edge graph).
std::unordered_map<std::uint32_t, std::uint32_t> hop_distances(const SurfaceMesh& m,
                                                               std::span<const Vertex> V,
                                                               std::size_t limit) {
    std::unordered_map<std::uint32_t, std::uint32_t> dist;
    std::vector<Vertex> frontier;
    for (Vertex v : V)
        if (dist.emplace(v.idx(), 0).second) frontier.push_back(v);
    for (std::uint32_t d = 1; d <= limit && !frontier.empty(); ++d) {
        std::vector<Vertex> next;
        for (Vertex v : frontier)
            for (Halfedge h : m.outgoing_halfedges(v)) {
                const Vertex w = m.to_vertex(h);
                if (dist.emplace(w.idx(), d).second) next.push_back(w);
            }
        frontier.swap(next);
    }
    return dist;
}


}  // namespace

LocalFlipReport flip_local(SurfaceMesh& mesh, std::span<const Vertex> V,
                           const LocalFlipOptions& options) {
    DYNMESH_CHECK(!mesh.has_garbage(), "flip_local: the mesh has deleted elements; call garbage_collection() first");
    for (Vertex v : V)
        DYNMESH_CHECK(mesh.is_valid(v) && !mesh.is_deleted(v),
                      "flip_local: vertex " + std::to_string(v.idx()) + " is not in the mesh");
    DYNMESH_CHECK(options.m0 >= 1, "flip_local: m0 must be at least 1");
    LocalFlipReport out;
    const auto t0 = Clock::now();
    std::unordered_set<std::uint32_t> changed;
    std::size_t m = options.m0;
    FlipQueue q(mesh, options.rule, options.feature_angle_deg, out.flips);
    for (std::size_t round = 0; round < options.max_rounds; ++round, m *= 2) {
        ++out.rounds;
        out.final_m = m;
        const auto dist = hop_distances(mesh, V, m);
        auto inside = [&](Vertex v) { return dist.count(v.idx()) != 0; };
        auto allowed = [&](Edge e) { return inside(mesh.vertex(e, 0)) && inside(mesh.vertex(e, 1)); };
        for (const auto& [vi, d] : dist)
            for (Halfedge h : mesh.outgoing_halfedges(Vertex(vi))) {
                const Edge e = SurfaceMesh::edge(h);
                if (vi < mesh.to_vertex(h).idx() && allowed(e)) q.push(e);
            }
        q.run(flip_cap(options.max_flips_per_vertex, dist.size()), {}, allowed, [&](Edge e) {
            changed.insert(mesh.face(SurfaceMesh::halfedge(e, 0)).idx());
            changed.insert(mesh.face(SurfaceMesh::halfedge(e, 1)).idx());
        });
        // Stop test. Marked: triangles with all corners within m hops (after the flips).
        const auto d2 = hop_distances(mesh, V, m + 1);
        auto hop = [&](Vertex v) {
            auto it = d2.find(v.idx());
            return it == d2.end() ? m + 2 : std::size_t(it->second);
        };
        std::vector<Face> F, first_outside;
        std::unordered_set<std::uint32_t> seenF, seenO;
        for (const auto& [vi, d] : d2)
            for (Halfedge h : mesh.outgoing_halfedges(Vertex(vi))) {
                const Face f = mesh.face(h);
                if (!f.is_valid()) continue;
                const auto vs = mesh.face_vertices(f);
                const std::size_t lo = std::min({hop(vs[0]), hop(vs[1]), hop(vs[2])});
                const std::size_t hi = std::max({hop(vs[0]), hop(vs[1]), hop(vs[2])});
                if (lo <= 1 && seenF.insert(f.idx()).second) F.push_back(f);
                if (hi > m && seenO.insert(f.idx()).second) first_outside.push_back(f);
            }
        bool ok = true;
        for (Face f : F) {
            const auto vs = mesh.face_vertices(f);
            const Point3 &a = mesh.position(vs[0]), &b = mesh.position(vs[1]), &c = mesh.position(vs[2]);
            const Point3 cc = circumcenter(a, b, c);
            const double rad = distance(cc, a);
            for (Face g : first_outside) {
                const auto ws = mesh.face_vertices(g);
                if (closest_point_on_triangle(cc, mesh.position(ws[0]), mesh.position(ws[1]),
                                              mesh.position(ws[2]))
                        .distance < rad) {
                    ok = false;
                    break;
                }
            }
            if (!ok) break;
        }
        if (!out.flips.converged) break;  // the flip cap was reached
        if (ok) {
            out.converged = true;
            break;
        }
    }
    out.changed_faces.reserve(changed.size());
    for (std::uint32_t f : changed) out.changed_faces.push_back(Face(f));
    std::sort(out.changed_faces.begin(), out.changed_faces.end());
    out.flips.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    out.flips.converged = out.converged;
    return out;
}

}  // namespace dynmesh
