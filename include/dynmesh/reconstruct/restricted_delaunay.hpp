#pragma once
/// \file Initial meshes from surface samples: the restricted Delaunay triangulation (RDT) of
/// a point sample with respect to a known implicit surface.
///
/// The RDT keeps the Delaunay facets whose dual Voronoi edge meets the surface. For a dense
/// enough sample (an epsilon-sample with small epsilon, Amenta-Bern / Edelsbrunner-Shah) it is
/// a closed 2-manifold homeomorphic to the surface whose vertices are exactly the samples.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/reconstruct/meshing_report.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh {

struct RestrictedDelaunayOptions {
    /// Signed-distance evaluations allowed per dual Voronoi edge while deciding whether it
    /// meets the surface (see restricted_delaunay()); an edge still undecided then comes
    /// within a tiny distance of the surface without crossing it, and counts as not meeting
    /// it. Almost every edge is decided by its two end values alone.
    std::size_t max_evaluations_per_edge = 256;
};

struct RestrictedDelaunayReport : SampleMeshingReport {
    std::size_t delaunay_cells = 0;  ///< finite tetrahedra of the 3D Delaunay triangulation
};

struct RestrictedDelaunayResult {
    SurfaceMesh mesh;
    RestrictedDelaunayReport report;
};

/// The restricted Delaunay triangulation of `samples` with respect to `surface`, as a closed,
/// outward-oriented mesh (each facet's normal agrees with surface.normal() at its centroid).
/// Vertices are the samples that occur in a kept facet, in input order, with bit-identical
/// positions; triangles are in a canonical order, so equal input gives an equal mesh.
///
/// How facets are chosen: the 3D Delaunay triangulation uses CGAL's exact predicates (and its
/// symbolic perturbation for cospherical points); Voronoi vertices (circumcentres) are computed
/// in double precision. A facet is kept when its dual Voronoi edge (segment between the two
/// circumcentres, or for a convex-hull facet the outward ray, cut beyond surface.bbox())
/// meets the surface. This is decided with surface.signed_distance(), which is 1-Lipschitz:
/// a sign change proves a crossing, and a piece whose end distances have one sign and sum to
/// more than its length cannot meet the surface; undecided pieces are halved. So an edge that
/// enters and leaves the surface is kept too, as the definition of the RDT requires; only an
/// edge that grazes the surface without crossing it (undecided after
/// options.max_evaluations_per_edge evaluations) is not.
/// \pre surface.signed_distance() is the Euclidean signed distance (or a 1-Lipschitz lower
///      bound of its magnitude with the same sign), and the surface lies inside surface.bbox().
/// \throw InvalidInput for fewer than 4 samples, non-finite or coincident samples (naming
///        their indices), samples that are all coplanar, or an RDT that is not a closed
///        2-manifold ("... is not a 2-manifold: N non-manifold edges (...); the sample is too
///        sparse for this surface"). A closed manifold is returned as is: for a very sparse
///        sample it may have the wrong topology, which this function cannot know; compare
///        the Euler characteristic if it matters.
[[nodiscard]] SurfaceMesh restricted_delaunay(std::span<const Point3> samples,
                                              const ImplicitSurface& surface,
                                              const RestrictedDelaunayOptions& options = {});
/// As restricted_delaunay(), also returning what happened.
[[nodiscard]] RestrictedDelaunayResult restricted_delaunay_with_report(
    std::span<const Point3> samples, const ImplicitSurface& surface,
    const RestrictedDelaunayOptions& options = {});

struct MeshRestrictedDelaunayOptions {
    /// Delaunay triangulations computed at most (the first on the net alone, then one per
    /// refinement round).
    std::size_t max_rounds = 8;
    /// Also refine where a facet's diametric ball holds a net point (so that the result
    /// needs few diametric flips; the deforming mesh's Tri(0)).
    bool refine_diametric_balls = false;
    /// A sample added for a multiple hit or a diametric ball (not for the topology) keeps at
    /// least this factor times the largest facet circumradius from the net (0: any).
    double min_spacing_factor = 0;
    /// Without a correct result after max_rounds: throw (true) or return report.correct =
    /// false with report.defect_points (the mesh is then empty).
    bool throw_on_failure = true;
};

struct MeshRestrictedDelaunayReport : RestrictedDelaunayReport {
    std::size_t rounds = 0;     ///< Delaunay triangulations computed
    std::size_t net = 0;        ///< size of the net given
    std::size_t added = 0;      ///< samples the refinement rounds added to the net
    /// In the result: restricted facets whose dual Voronoi edge meets the surface more than
    /// once (left where no sample could be added near the hits).
    std::size_t multi_hit_facets = 0;
    /// In the result, with refine_diametric_balls: facets whose diametric ball holds a vertex.
    std::size_t nonempty_balls = 0;
    long long euler = 0;        ///< of the result, equal to the surface's
    bool correct = false;       ///< false only with throw_on_failure = false
    /// Without a correct result: where the last round failed (vertices at the defects).
    std::vector<Point3> defect_points;
};

struct MeshRestrictedDelaunayResult {
    SurfaceMesh mesh;
    MeshRestrictedDelaunayReport report;
};

/// The restricted Delaunay triangulation of a net of samples with respect to a closed
/// triangle mesh `surface` (spec deforming-mesh.md §10.5 B): for each facet of the Delaunay
/// triangulation of the net, the dual Voronoi edge (segment, or outward ray cut beyond the
/// surface's bounding box) is tested against the surface's triangles with CGAL's AABB tree
/// (exact predicates); a facet is kept when it meets the surface and is oriented like the
/// surface triangle it meets nearest the facet's centroid.
///
/// `samples` is the pool and `net` the indices of the initial vertices (each sample is
/// expected on the surface). Refinement rounds, until the result is a closed oriented
/// 2-manifold with the surface's Euler characteristic and number of components and no dual
/// edge meets the surface twice: wherever a dual edge meets the surface more than once, and
/// at every facet around a non-manifold edge or vertex, the pool sample nearest each hit
/// joins the net. A correct result whose remaining multiple hits have no pool sample to add
/// is returned (counted in multi_hit_facets). Vertices are the net samples used, in pool
/// order (report.vertex_sample gives their pool indices); deterministic.
/// \throw InvalidInput for an empty or out-of-range net, bad samples (as restricted_delaunay),
///        a surface that is not a closed 2-manifold, or no correct result after max_rounds
///        (naming a point of the region that failed).
[[nodiscard]] MeshRestrictedDelaunayResult restricted_delaunay_on_mesh(
    std::span<const Point3> samples, std::span<const std::uint32_t> net, const SurfaceMesh& surface,
    const MeshRestrictedDelaunayOptions& options = {});

/// restricted_delaunay(surface.sample_uniform(n, seed), surface): a closed mesh of the
/// surface with n area-uniform random vertices (n must be large enough for the surface; e.g.
/// 10,000 suffice for torus:5,3).
[[nodiscard]] SurfaceMesh sample_and_mesh(const ImplicitSurface& surface, std::size_t n,
                                          std::uint64_t seed);

}  // namespace dynmesh
