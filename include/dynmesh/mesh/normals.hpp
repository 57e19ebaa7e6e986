#pragma once
/// \file Vertex normals of a surface mesh.

#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

/// Angle-weighted unit normal of every vertex (indexed by vertex index; the zero vector for
/// a vertex no face uses). Deleted faces are skipped.
[[nodiscard]] std::vector<Vec3> vertex_normals(const SurfaceMesh& mesh);

}  // namespace dynmesh
