#include "dynmesh/flips/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_set>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/geometry/triangle.hpp"

namespace dynmesh {

namespace {

/// Shrunken-ball queries against every vertex of a mesh: a uniform grid over the vertices
/// with cell = mean edge length.
class VertexBallProbe {
public:
    enum class Result { Empty, HoldsVertex, Unchecked };

    explicit VertexBallProbe(const SurfaceMesh& m) : mesh_(m) {
        double len = 0;
        std::size_t n = 0;
        for (Edge e : m.edges()) {
            len += distance(m.position(m.vertex(e, 0)), m.position(m.vertex(e, 1)));
            ++n;
        }
        const double cell = n ? len / double(n) : 1.0;
        grid_.reset(std::isfinite(cell) && cell > 0 ? cell : 1.0);
        for (Vertex v : m.vertices()) grid_.insert(v.idx(), m.position(v));
    }

    /// Does B(c, shrink * circumradius) of face f hold a vertex other than f's corners?
    /// Unchecked when the ball is not finite or spans more than 16 cells (a near-degenerate
    /// triangle), which would make the search scan most of the grid.
    [[nodiscard]] Result test(Face f, double shrink) const {
        const auto vs = mesh_.face_vertices(f);
        const Point3 &a = mesh_.position(vs[0]), &b = mesh_.position(vs[1]), &c = mesh_.position(vs[2]);
        const Point3 cc = circumcenter(a, b, c);
        const double rad = shrink * distance(cc, a);
        if (!is_finite(cc) || !(rad / grid_.cell() <= 16.0)) return Result::Unchecked;
        const double r2 = rad * rad;
        bool hit = false;
        grid_.for_each_candidate(cc, rad, [&](std::uint32_t w) {
            if (hit || w == vs[0].idx() || w == vs[1].idx() || w == vs[2].idx()) return;
            hit = sqdistance(mesh_.position(Vertex(w)), cc) < r2;
        });
        return hit ? Result::HoldsVertex : Result::Empty;
    }

private:
    const SurfaceMesh& mesh_;
    PointGrid grid_;
};

}  // namespace

FlipDiagnostics flip_diagnostics(const SurfaceMesh& m, FlipRule rule, double shrink) {
    FlipDiagnostics d;
    d.ball_shrink = shrink;
    for (Edge e : m.edges()) {
        ++d.edges;
        if (is_flippable(m, e, rule)) ++d.flippable;
        if (is_illegal(m, e)) ++d.illegal;
    }
    const VertexBallProbe probe(m);
    for (Face f : m.faces()) {
        ++d.faces;
        const auto r = probe.test(f, shrink);
        d.unchecked_balls += r == VertexBallProbe::Result::Unchecked;
        d.nonempty_balls += r == VertexBallProbe::Result::HoldsVertex;
    }
    return d;
}

namespace {

/// What check_local_flip() counts, before it becomes the report's figures.
struct LocalFlipCounts {
    std::size_t near_faces = 0, flippable_edges = 0, illegal_edges = 0, nonempty_balls = 0,
                unchecked_balls = 0, far_faces = 0, far_faces_changed = 0, moved_vertices = 0;
    std::vector<std::string> problems;
};

}  // namespace

CheckReport check_local_flip(const SurfaceMesh& before, const SurfaceMesh& after, std::span<const Vertex> V,
                                const LocalFlipReport& report, const LocalFlipCheckOptions& options) {
    DYNMESH_CHECK(!before.has_garbage() && !after.has_garbage(), "check_local_flip: a mesh has deleted elements");
    DYNMESH_CHECK(before.vertices_size() == after.vertices_size() && before.edges_size() == after.edges_size() &&
                      before.faces_size() == after.faces_size(),
                  "check_local_flip: the two meshes differ in size (flips never add or remove elements)");
    for (Vertex v : V)
        DYNMESH_CHECK(after.is_valid(v), "check_local_flip: vertex " + std::to_string(v.idx()) + " is not in the mesh");
    LocalFlipCounts out;
    auto problem = [&](std::size_t count, const std::string& what) {
        if (count) out.problems.push_back(std::to_string(count) + " " + what);
    };
    if (!report.converged) out.problems.push_back("flip_local did not converge");

    for (Vertex v : after.vertices())
        out.moved_vertices += std::memcmp(&before.position(v), &after.position(v), sizeof(Point3)) != 0;
    problem(out.moved_vertices, "vertices moved");

    // Far triangles: no corner within final_m + 1 hops in the union of both edge graphs.
    IndexMap<std::uint32_t> hops;
    const SurfaceMesh* both[] = {&before, &after};
    hop_distances(both, V, report.final_m + 1, hops);
    auto near = [&](Vertex v) { return hops.contains(v.idx()); };
    for (Face f : after.faces()) {
        const auto c = after.face_vertices(f);
        if (near(c[0]) || near(c[1]) || near(c[2])) continue;
        ++out.far_faces;
        out.far_faces_changed += c != before.face_vertices(f);
    }
    problem(out.far_faces_changed, "triangles more than final_m + 1 = " + std::to_string(report.final_m + 1) +
                                       " hops from V differ from before");

    // F and its edges (hops in `after`).
    hop_distances(after, V, 1, hops);
    std::unordered_set<std::uint32_t> F, edges;
    hops.for_each([&](std::uint32_t vi, std::uint32_t) {
        for (Halfedge h : after.outgoing_halfedges(Vertex(vi)))
            if (after.face(h).is_valid()) F.insert(after.face(h).idx());
    });
    const VertexBallProbe probe(after);
    for (std::uint32_t fi : F) {
        const Face f(fi);
        Halfedge h = after.halfedge(f);
        for (int k = 0; k < 3; ++k, h = after.next(h)) edges.insert(SurfaceMesh::edge(h).idx());
        const auto r = probe.test(f, options.ball_shrink);
        out.unchecked_balls += r == VertexBallProbe::Result::Unchecked;
        out.nonempty_balls += r == VertexBallProbe::Result::HoldsVertex;
    }
    out.near_faces = F.size();
    for (std::uint32_t ei : edges) {
        out.flippable_edges += is_flippable(after, Edge(ei), options.rule, options.feature_angle_deg);
        out.illegal_edges += is_illegal(after, Edge(ei));
    }
    problem(out.flippable_edges, "flippable edges in F (triangles within 1 hop of V)");
    problem(out.illegal_edges, "illegal edges in F");
    problem(out.nonempty_balls, "triangles of F whose shrunken diametric ball holds a vertex");
    CheckReport rep = CheckReport::of_problems(std::move(out.problems));
    rep.add("near_faces", out.near_faces);
    rep.add("flippable_edges", out.flippable_edges);
    rep.add("illegal_edges", out.illegal_edges);
    rep.add("nonempty_balls", out.nonempty_balls);
    rep.add("unchecked_balls", out.unchecked_balls);
    rep.add("far_faces", out.far_faces);
    rep.add("far_faces_changed", out.far_faces_changed);
    rep.add("moved_vertices", out.moved_vertices);
    return rep;
}

}  // namespace dynmesh
