#pragma once
/// \file Surface reconstruction from an unorganised point cloud, without a known surface:
/// CGAL's advancing-front reconstruction (Cohen-Steiner & Da, "A greedy Delaunay-based surface
/// reconstruction algorithm", 2004), which grows a manifold from Delaunay facets, preferring
/// small facets that meet the front at a plausible dihedral angle.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/reconstruct/meshing_report.hpp"

namespace dynmesh {

struct AdvancingFrontOptions {
    /// CGAL's radius_ratio_bound: candidates outside the beta-wedge are discarded when their
    /// radius exceeds this multiple of the radius of the facet they would attach to.
    double radius_ratio_bound = 5.0;
    /// CGAL's beta, in radians: half the angle of the wedge in which only a candidate's
    /// radius counts for its plausibility.
    double beta_rad = 0.52;
    /// Throw when the result has boundary edges; false returns open surfaces too.
    bool require_closed = true;
};

struct AdvancingFrontReport : SampleMeshingReport {
    std::size_t boundary_edges = 0;  ///< 0 for a closed result
    bool closed = false;
    bool flipped = false;  ///< all triangles reversed to make the volume positive
};

struct AdvancingFrontResult {
    SurfaceMesh mesh;
    AdvancingFrontReport report;
};

/// Reconstructs a surface through `samples` with CGAL::advancing_front_surface_reconstruction.
/// Vertices are the samples used by some triangle, in input order, with bit-identical
/// positions. A closed result is oriented outward (positive signed volume); an open one keeps
/// CGAL's consistent but arbitrary orientation.
/// \throw InvalidInput for fewer than 4 samples, non-finite or coincident samples, coplanar
///        samples, an empty reconstruction, a result that is not a 2-manifold, or (with
///        require_closed) a result with boundary edges; the message gives the counts.
[[nodiscard]] SurfaceMesh reconstruct_advancing_front(std::span<const Point3> samples,
                                                      const AdvancingFrontOptions& options = {});
/// As reconstruct_advancing_front(), also returning what happened.
[[nodiscard]] AdvancingFrontResult reconstruct_advancing_front_with_report(
    std::span<const Point3> samples, const AdvancingFrontOptions& options = {});

}  // namespace dynmesh
