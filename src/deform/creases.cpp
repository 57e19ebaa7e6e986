#include "dynmesh/deform/creases.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "dynmesh/error.hpp"
#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/geometry/triangle.hpp"

namespace dynmesh {

namespace {

/// The polylines of the locked edges: from each corner (locked degree != 2) along each of its
/// locked spokes to the next corner, then the loops.
Creases trace(const SurfaceMesh& m, const EdgeProperty<std::uint8_t>& locked) {
    Creases c;
    std::vector<char> used(m.edges_size(), 0);
    auto walk = [&](Halfedge h) {
        std::vector<Vertex> line{m.from_vertex(h)};
        for (;;) {
            used[SurfaceMesh::edge(h).idx()] = 1;
            const Vertex v = m.to_vertex(h);
            line.push_back(v);
            if (v == line.front() || locked_degree(m, locked, v) != 2) break;
            Halfedge next;
            for (Halfedge g : m.outgoing_halfedges(v))
                if (locked[SurfaceMesh::edge(g)] && !used[SurfaceMesh::edge(g).idx()]) next = g;
            if (!next.is_valid()) break;
            h = next;
        }
        c.lines.push_back(std::move(line));
    };
    for (Vertex v : m.vertices()) {
        const std::size_t d = locked_degree(m, locked, v);
        if (d == 0 || d == 2) continue;
        c.corners.push_back(v);
        for (Halfedge h : m.outgoing_halfedges(v))
            if (locked[SurfaceMesh::edge(h)] && !used[SurfaceMesh::edge(h).idx()]) walk(h);
    }
    for (Vertex v : m.vertices())
        for (Halfedge h : m.outgoing_halfedges(v))
            if (locked[SurfaceMesh::edge(h)] && !used[SurfaceMesh::edge(h).idx()]) walk(h);
    c.edges = locked_edge_count(m);
    return c;
}

}  // namespace

Creases mark_creases(SurfaceMesh& m, const CreaseOptions& o) {
    if (!(o.feature_angle_deg > 0 && o.feature_angle_deg < 180))
        throw InvalidInput("mark_creases: feature angle must be in (0, 180) degrees (got " +
                           std::to_string(o.feature_angle_deg) + ")");
    auto locked = lock_edges_property(m);
    const double min_dihedral = std::numbers::pi * (1 - o.feature_angle_deg / 180.0);
    for (Edge e : m.edges()) {
        locked[e] = 0;
        if (m.is_boundary(e)) continue;
        const Halfedge h = SurfaceMesh::halfedge(e, 0);
        const double d = dihedral_angle(m.position(m.from_vertex(h)), m.position(m.to_vertex(h)),
                                        m.position(m.opposite_vertex(h)),
                                        m.position(m.opposite_vertex(SurfaceMesh::twin(h))));
        if (d < min_dihedral) locked[e] = 1;
    }
    for (;;) {
        Creases c = trace(m, locked);
        bool dropped = false;
        for (const auto& line : c.lines) {
            if (line.size() - 1 >= o.min_chain_edges) continue;
            for (std::size_t i = 0; i + 1 < line.size(); ++i)
                locked[SurfaceMesh::edge(m.find_halfedge(line[i], line[i + 1]))] = 0;
            dropped = true;
        }
        if (!dropped) return c;
    }
}

}  // namespace dynmesh
