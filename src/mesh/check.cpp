#include "dynmesh/mesh/check.hpp"

#include <algorithm>
#include <numeric>
#include <unordered_set>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"

namespace dynmesh {

namespace {

/// What check_mesh() counts, before it becomes the report's figures.
struct MeshCounts {
    std::size_t vertices = 0, edges = 0, faces = 0;
    std::size_t boundary_edges = 0;
    std::size_t isolated_vertices = 0;
    std::size_t non_manifold_vertices = 0;
    std::size_t duplicate_edges = 0;
    std::size_t degenerate_faces = 0;
    std::size_t components = 0;
    long long euler = 0;
    bool closed = false;
};

CheckReport with_figures(CheckReport out, const MeshCounts& r) {
    out.add("vertices", r.vertices);
    out.add("edges", r.edges);
    out.add("faces", r.faces);
    out.add("euler", r.euler);
    out.add("closed", r.closed);
    out.add("components", r.components);
    out.add("boundary_edges", r.boundary_edges);
    out.add("degenerate_faces", r.degenerate_faces);
    out.add("isolated_vertices", r.isolated_vertices);
    out.add("non_manifold_vertices", r.non_manifold_vertices);
    out.add("duplicate_edges", r.duplicate_edges);
    return out;
}

}  // namespace

CheckReport check_mesh(const SurfaceMesh& m, const MeshCheckOptions& opt) {
    CheckReport out;
    MeshCounts r;
    auto problem = [&](std::string msg) { out.fail(std::move(msg), opt.max_listed); };
    r.vertices = m.n_vertices();
    r.edges = m.n_edges();
    r.faces = m.n_faces();
    const std::string V = "vertex ", H = "halfedge ", F = "face ";

    // Halfedge structure.
    bool structure_ok = true;
    for (Edge e : m.edges()) {
        for (int i = 0; i < 2; ++i) {
            const Halfedge h = SurfaceMesh::halfedge(e, i);
            const std::string hs = H + std::to_string(h.idx());
            const Halfedge n = m.next(h), p = m.prev(h);
            if (!n.is_valid() || !p.is_valid() || n.idx() >= m.halfedges_size() ||
                p.idx() >= m.halfedges_size() || m.is_deleted(n) || m.is_deleted(p)) {
                problem(hs + ": next/prev missing or deleted");
                structure_ok = false;
                continue;
            }
            if (m.prev(n) != h) { problem(hs + ": prev(next(h)) != h"); structure_ok = false; }
            if (m.to_vertex(h) != m.from_vertex(n)) {
                problem(hs + ": next(h) does not start where h ends");
                structure_ok = false;
            }
            const Vertex t = m.to_vertex(h);
            if (!t.is_valid() || t.idx() >= m.vertices_size() || m.is_deleted(t)) {
                problem(hs + ": points to a missing or deleted vertex");
                structure_ok = false;
            }
            if (m.face(h) != m.face(n)) { problem(hs + ": next(h) lies in another face"); structure_ok = false; }
            if (m.is_boundary(h)) ++r.boundary_edges;  // counts boundary halfedges = edges

            if (m.to_vertex(h) == m.from_vertex(h)) { problem(hs + ": a loop edge"); structure_ok = false; }
        }
    }
    for (Face f : m.faces()) {
        const Halfedge h = m.halfedge(f);
        if (!h.is_valid() || m.is_deleted(h) || m.face(h) != f) {
            problem(F + std::to_string(f.idx()) + ": its halfedge does not belong to it");
            structure_ok = false;
            continue;
        }
        if (m.next(m.next(m.next(h))) != h) {
            problem(F + std::to_string(f.idx()) + ": not a triangle");
            structure_ok = false;
        }
    }
    if (!structure_ok) {
        r.euler = static_cast<long long>(r.vertices) - static_cast<long long>(r.edges) +
                  static_cast<long long>(r.faces);
        return with_figures(std::move(out), r);
    }

    // Edges: each in at least one triangle; two triangles on an edge differ in their apex.
    for (Edge e : m.edges()) {
        const Halfedge h = SurfaceMesh::halfedge(e, 0), o = SurfaceMesh::halfedge(e, 1);
        const std::string es = "edge " + std::to_string(e.idx());
        if (m.is_boundary(h) && m.is_boundary(o))
            problem(es + ": no triangle uses it (dangling edge)");
        else if (!m.is_boundary(h) && !m.is_boundary(o) && m.opposite_vertex(h) == m.opposite_vertex(o))
            problem(es + ": both triangles have the same third vertex (a folded pair)");
    }

    // Vertices: manifold fans, outgoing boundary convention.
    std::vector<std::uint32_t> out_count(m.vertices_size(), 0);
    for (Edge e : m.edges())
        for (int i = 0; i < 2; ++i) ++out_count[m.from_vertex(SurfaceMesh::halfedge(e, i)).idx()];
    for (Vertex v : m.vertices()) {
        const std::string vs = V + std::to_string(v.idx());
        if (m.is_isolated(v)) {
            ++r.isolated_vertices;
            problem(vs + ": isolated (no triangle uses it)");
            continue;
        }
        const Halfedge h0 = m.halfedge(v);
        if (m.is_deleted(h0) || m.from_vertex(h0) != v) {
            problem(vs + ": its halfedge does not start at it");
            continue;
        }
        std::size_t n = 0, nb = 0;
        Halfedge h = h0;
        do {
            ++n;
            if (m.is_boundary(h)) ++nb;
            h = m.ccw_rotated(h);
        } while (h != h0 && n <= out_count[v.idx()]);
        if (n != out_count[v.idx()] || nb > 1) {
            ++r.non_manifold_vertices;
            problem(vs + ": non-manifold (its triangles do not form a single fan)");
        } else if (nb == 1 && !m.is_boundary(h0)) {
            problem(vs + ": on the boundary but its halfedge is not the boundary one");
        }
        // duplicate edges: two outgoing halfedges to the same vertex
        std::vector<std::uint32_t> nbrs;
        for (Halfedge g : m.outgoing_halfedges(v)) nbrs.push_back(m.to_vertex(g).idx());
        std::sort(nbrs.begin(), nbrs.end());
        for (std::size_t i = 1; i < nbrs.size(); ++i)
            if (nbrs[i] == nbrs[i - 1] && v.idx() < nbrs[i]) {
                ++r.duplicate_edges;
                problem("edge (" + std::to_string(v.idx()) + ", " + std::to_string(nbrs[i]) +
                        ") appears more than once");
            }
    }
    if (r.boundary_edges > 0 && opt.require_closed)
        problem(std::to_string(r.boundary_edges) + " boundary edges: the surface is not closed");

    if (opt.check_degenerate)
        for (Face f : m.faces()) {
            const auto vs = m.face_vertices(f);
            if (vs[0] == vs[1] || vs[1] == vs[2] || vs[0] == vs[2] ||
                collinear(m.position(vs[0]), m.position(vs[1]), m.position(vs[2]))) {
                ++r.degenerate_faces;
                problem(F + std::to_string(f.idx()) + ": degenerate (zero area)");
            }
        }

    // Components over faces and edges (union-find on vertices).
    std::vector<std::uint32_t> parent(m.vertices_size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](std::uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    for (Edge e : m.edges()) {
        const auto a = find(m.vertex(e, 0).idx()), b = find(m.vertex(e, 1).idx());
        if (a != b) parent[a] = b;
    }
    for (Vertex v : m.vertices())
        if (!m.is_isolated(v) && find(v.idx()) == v.idx()) ++r.components;
    if (opt.require_connected && r.components > 1)
        problem(std::to_string(r.components) + " connected components, expected one");

    r.closed = r.boundary_edges == 0;
    r.euler = static_cast<long long>(r.vertices) - static_cast<long long>(r.edges) +
              static_cast<long long>(r.faces);
    return with_figures(std::move(out), r);
}

void require_valid_mesh(const SurfaceMesh& mesh, const std::string& what,
                        const MeshCheckOptions& options) {
    const CheckReport r = check_mesh(mesh, options);
    if (r.ok()) return;
    std::string first = r.problems.empty() ? std::string("invalid") : r.problems.front();
    throw TopologyError(what + ": " + first +
                        (r.n_problems > 1 ? " (and " + std::to_string(r.n_problems - 1) + " more problems)" : ""));
}

}  // namespace dynmesh
