#pragma once
/// \file Sampled two-sided Hausdorff distances between two meshes, or between a mesh and an
/// analytic surface.
///
/// Both directions are measured at sample points and are therefore lower bounds of the
/// true one-sided distances; they converge as the sampling gets finer. Distances to a mesh
/// are exact point-to-triangle distances found with CGAL's AABB tree (O(n log n) to build,
/// about O(log n) per query, a query stopping early once it cannot raise the maximum);
/// distances to an ImplicitSurface come from its signed_distance(). Rough cost on one core:
/// 1-2 microseconds per mesh query, e.g. about 14 s for hausdorff() between two 1.3M-face
/// meshes at the default resolution (3.9M samples each way).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh {

struct HausdorffOptions {
    /// Each mesh is sampled on the barycentric grid of every triangle with this many segments
    /// per edge, plus every barycentre, shared vertices and edge points taken once:
    /// 1 = vertices and barycentres; 2 (default) = vertices, edge midpoints and barycentres;
    /// k = k + 1 points per edge, (k - 1)(k - 2) / 2 inside each face (+ the barycentre).
    std::size_t face_resolution = 2;
    /// Points drawn by ImplicitSurface::sample_uniform for the surface-to-mesh direction
    /// (0 skips that direction: b_to_a = 0).
    std::size_t surface_samples = 100000;
    /// Seed for those surface samples.
    std::uint64_t seed = 1;
};

/// The two one-sided sampled distances and their maximum.
/// Measures against an analytic surface (normal deviation, Hausdorff distance) evaluate the
/// surface at the mesh's points in absolute units, as make_surface() accepts them (sizes up
/// to 1e50). \throw InvalidInput "<what>: the mesh's coordinates (up to X) are beyond 1e50,
/// the range of analytic surfaces" otherwise.
void require_surface_range(const SurfaceMesh& mesh, const std::string& what);

struct HausdorffResult {
    double distance = 0;  ///< max(a_to_b, b_to_a): the two-sided Hausdorff distance
    double a_to_b = 0;    ///< max over the samples of a of the distance to b
    double b_to_a = 0;    ///< max over the samples of b of the distance to a
    std::size_t a_samples = 0, b_samples = 0;
};

/// The sample points used for a mesh (see HausdorffOptions::face_resolution): every vertex
/// of a face (isolated vertices are not part of the surface), the interior grid points of
/// every edge and face, and every face's barycentre.
/// \throw InvalidInput when face_resolution == 0.
[[nodiscard]] std::vector<Point3> mesh_sample_points(const SurfaceMesh& mesh,
                                                     std::size_t face_resolution);

/// The largest distance from `points` to the mesh (through an AABB tree of its faces): the
/// surface-to-mesh side of a Hausdorff distance when the surface is known only by samples.
/// \throw InvalidInput when the mesh has no face.
[[nodiscard]] double max_distance_to_mesh(const SurfaceMesh& mesh, const std::vector<Point3>& points);

/// Two-sided sampled Hausdorff distance between meshes a and b.
/// \throw InvalidInput when either mesh has no face, or face_resolution == 0.
[[nodiscard]] HausdorffResult hausdorff(const SurfaceMesh& a, const SurfaceMesh& b,
                                        const HausdorffOptions& options = {});
/// hausdorff(a, b, options).distance.
[[nodiscard]] double hausdorff_distance(const SurfaceMesh& a, const SurfaceMesh& b,
                                        const HausdorffOptions& options = {});

/// Two-sided sampled Hausdorff distance between a mesh (a) and a surface (b):
/// a_to_b = max |surface.signed_distance(x)| over the mesh samples x;
/// b_to_a = max distance to the mesh over surface.sample_uniform(surface_samples, seed).
/// \throw InvalidInput when the mesh has no face, or face_resolution == 0.
[[nodiscard]] HausdorffResult hausdorff_to_surface(const SurfaceMesh& mesh,
                                                   const ImplicitSurface& surface,
                                                   const HausdorffOptions& options = {});

}  // namespace dynmesh
