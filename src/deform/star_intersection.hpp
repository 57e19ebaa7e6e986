#pragma once
// Local self-intersection test of a deforming mesh (spec deforming-mesh.md §10.4): the faces
// around one vertex against the faces near it, with exact predicates (CGAL Epick), so that an
// operation that would make the mesh intersect itself can be undone.

#include <cstdint>
#include <functional>

#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh::detail {

/// True when a face around v intersects a face of the mesh that shares no edge with it: two
/// faces sharing one vertex intersect when an edge of one opposite that vertex meets the
/// other; faces sharing nothing when their triangles meet. The candidates are the faces
/// around the vertices that `grid` holds within `radius` of v (ids mapped to vertices by
/// `vertex_of`; invalid or deleted vertices are skipped), so `radius` must reach every vertex
/// of a face that can meet v's star: its largest edge plus the star's.
[[nodiscard]] bool star_intersects(const SurfaceMesh& mesh, Vertex v, const PointGrid& grid, double radius,
                                   const std::function<Vertex(std::uint32_t)>& vertex_of);

}  // namespace dynmesh::detail
