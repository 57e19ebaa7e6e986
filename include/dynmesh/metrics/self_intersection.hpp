#pragma once
/// \file Self-intersection tests, through CGAL::Polygon_mesh_processing::self_intersections
/// (box intersection plus filtered exact triangle predicates of the Epick kernel).
///
/// CGAL's definition: two faces intersect when their triangles intersect and the
/// intersection is not just an edge or a vertex that both faces share. Two faces sharing an
/// edge intersect only when they are coplanar and overlap (a folded-over pair); two faces
/// sharing a vertex only when they meet somewhere else too. A degenerate (collinear)
/// triangle f is reported as the pair (f, f), and counted once.
///
/// Cost: O(n log n + k) for n faces and k reported pairs, plus copying the mesh into a
/// CGAL::Surface_mesh (linear).

#include <cstddef>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

/// The number of intersecting face pairs (see the file comment), 0 for an embedded mesh.
[[nodiscard]] std::size_t count_self_intersections(const SurfaceMesh& mesh);

/// The intersecting face pairs, at most max_pairs of them (stops searching once reached;
/// which pairs are found first is unspecified). Each pair is listed once.
[[nodiscard]] std::vector<std::pair<Face, Face>> self_intersections(
    const SurfaceMesh& mesh, std::size_t max_pairs = std::numeric_limits<std::size_t>::max());

/// True when some pair of faces intersects (stops at the first one found).
[[nodiscard]] bool has_self_intersections(const SurfaceMesh& mesh);

/// True when some pair of faces, both in `faces` (live faces of the mesh, each once),
/// intersects: the test of a neighbourhood (the faces that moved and every face near them).
/// Copies those faces alone (the whole mesh when CGAL cannot hold them as one surface).
[[nodiscard]] bool has_self_intersections(const SurfaceMesh& mesh, std::span<const Face> faces);

}  // namespace dynmesh
