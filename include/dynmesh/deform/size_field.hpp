#pragma once
/// \file The local size field of a deforming mesh (spec deforming-mesh.md §10.2; not in the
/// paper, which uses one global sampling radius): an estimate of the local feature size of a
/// closed mesh at its vertices, and the graded size r = min(cap, rho lfs) smoothed to be
/// L-Lipschitz along the mesh. DeformingMesh uses r in place of the global R in RefineVert,
/// Decimation and the spacing repair, so that thin parts (ears, legs, tubes) get as many
/// vertices across as their thickness needs.

#include <span>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

/// Local feature size estimate at every vertex of a closed mesh (vertex index order):
/// lfs(v) = min(curvature radius, d_in / 2, d_out / 2), where
/// - the curvature radius is min over the neighbours u of |uv| / (2 sin(angle(n_u, n_v) / 2))
///   (n the angle-weighted vertex normals; the radius of the circle through u and v with
///   those normals), and
/// - d_in and d_out are the distances from v to the first face hit by the rays from v along
///   -n_v and +n_v (CGAL AABB tree over the faces, v's own faces skipped): the thickness of
///   the part behind v and the gap to the part in front of it (a leg against the body).
/// A vertex where nothing bounds it (a flat disc's centre seen by no ray) gets +inf.
/// \throw InvalidInput for a mesh with a boundary or no face.
[[nodiscard]] std::vector<double> mesh_feature_size(const SurfaceMesh& mesh);

/// The graded size at every vertex: r(v) = min over u of (min(cap, rho lfs(u)) + grading
/// |uv|_mesh), the largest L-Lipschitz function along the mesh edges (L = grading) below
/// min(cap, rho lfs) (Dijkstra from every vertex at once). cap may be +inf.
/// \pre lfs.size() == mesh.vertices_size(); rho > 0; grading >= 0.
[[nodiscard]] std::vector<double> graded_size(const SurfaceMesh& mesh, std::span<const double> lfs, double rho,
                                              double grading, double cap);

}  // namespace dynmesh
