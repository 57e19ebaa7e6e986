#pragma once
/// \file The planar corollary of the edge-flip paper (Theorem 1): a planar triangulation with
/// angles bounded below reaches the Delaunay triangulation after O(n) flips.
///
/// Planar meshes are SurfaceMeshes with z = 0 and counter-clockwise triangles.

#include <cstddef>
#include <cstdint>

#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

/// A triangulation of an n x n jittered grid of the unit square (boundary points stay on the
/// square, interior points move by up to `jitter` cell widths), each cell split by a random
/// diagonal. With jitter <= 0.1 the minimum angle is about 20 degrees or more.
[[nodiscard]] SurfaceMesh jittered_grid_triangulation(std::size_t n, double jitter,
                                                      std::uint64_t seed);

struct DelaunayComparison {
    std::size_t edges_here = 0;       ///< edges of the mesh
    std::size_t edges_delaunay = 0;   ///< edges of CGAL's Delaunay triangulation
    std::size_t only_here = 0;        ///< mesh edges CGAL does not have
    std::size_t only_delaunay = 0;    ///< CGAL edges the mesh does not have
    [[nodiscard]] bool identical() const { return only_here == 0 && only_delaunay == 0; }
};

/// Compares the mesh's edges with CGAL's 2D Delaunay triangulation of the same vertices
/// (x, y). Meaningful when the mesh triangulates the convex hull of its vertices and no four
/// points are cocircular.
[[nodiscard]] DelaunayComparison compare_with_cgal_delaunay_2(const SurfaceMesh& planar_mesh);

/// Interior edges that fail the exact empty-circle test (0 iff the mesh is Delaunay).
[[nodiscard]] std::size_t count_non_locally_delaunay(const SurfaceMesh& planar_mesh);

}  // namespace dynmesh
