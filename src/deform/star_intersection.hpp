#pragma once
// Local self-intersection test of a deforming mesh (spec deforming-mesh.md §10.4): the faces
// around one vertex against the faces near it, with exact predicates (CGAL Epick), so that an
// operation that would make the mesh intersect itself can be undone.

#include <cstdint>
#include <functional>

#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh::detail {

/// The box of face f.
[[nodiscard]] inline Bbox3 face_box(const SurfaceMesh& m, Face f) {
    Bbox3 b;
    for (Vertex x : m.face_vertices(f)) b.extend(m.position(x));
    return b;
}

/// The broad phase of the local intersection tests: calls f(g) for every face g whose box
/// meets `box`, among the faces around the vertices that `grid` holds within the cube of
/// half-width `reach` about `centre` (ids mapped to vertices by `vertex_of`; invalid or
/// deleted vertices are skipped). A face comes once per vertex of it found; f returns true to
/// stop the visit.
template <class VertexOf, class F>
void for_each_face_meeting(const SurfaceMesh& m, const PointGrid& grid, const Point3& centre, double reach,
                           const Bbox3& box, VertexOf&& vertex_of, F&& f) {
    bool stop = false;
    grid.for_each_candidate(centre, reach, [&](std::uint32_t id) {
        if (stop) return;
        const Vertex w = vertex_of(id);
        if (!w.is_valid() || w.idx() >= m.vertices_size() || m.is_deleted(w)) return;
        for (Halfedge h : m.outgoing_halfedges(w)) {
            const Face g = m.face(h);
            if (!g.is_valid() || !face_box(m, g).overlaps(box)) continue;
            if (f(g)) {
                stop = true;
                return;
            }
        }
    });
}

/// True when a face around v intersects a face of the mesh that shares no edge with it: two
/// faces sharing one vertex intersect when an edge of one opposite that vertex meets the
/// other; faces sharing nothing when their triangles meet. The candidates are the faces
/// around the vertices that `grid` holds within `radius` of v (ids mapped to vertices by
/// `vertex_of`; invalid or deleted vertices are skipped), so `radius` must reach every vertex
/// of a face that can meet v's star: its largest edge plus the star's.
[[nodiscard]] bool star_intersects(const SurfaceMesh& mesh, Vertex v, const PointGrid& grid, double radius,
                                   const std::function<Vertex(std::uint32_t)>& vertex_of);

}  // namespace dynmesh::detail
