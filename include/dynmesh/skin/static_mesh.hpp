#pragma once
/// \file The static skin mesh (specs/skin-surfaces.md §3.1–§3.2, §6.3): a restricted Delaunay
/// mesh of the level set Φ = t of a SkinFunction, refined until every triangle meets the
/// curvature-adapted size bound [U] at Q0 and a radius-edge bound.
///
/// Method (Delaunay refinement in the manner of Chew and of Boissonnat–Oudot): a 3D Delaunay
/// triangulation (CGAL, exact predicates) of sample points on the skin; a facet is restricted
/// when its dual Voronoi edge (segment between the circumcentres of its two cells, or the outward
/// ray of a hull facet) crosses the skin, and the crossing is the centre of its surface
/// Delaunay ball. While a restricted facet is bad, its ball centre is inserted (largest balls
/// first). A restricted facet abc with ball radius r is bad when
///   - r > C·Q0·λ with λ = max(min(ϱ(a), ϱ(b), ϱ(c)), rho_floor) (size, [U] at Q0; the
///     triangle's circumradius is at most r);
///   - r > radius_edge_bound · (its shortest edge) (shape: every kept triangle then has
///     angles ≥ asin(1/(2·bound)), 30° at the default 1);
///   - its dual edge crosses the skin more than once (topology; detected by sampling).
/// Seeds, one set per component: points where rays from each born atom centre (a local
/// minimum of Φ) and from each living void centre (a local maximum) meet the skin.
///
/// The result is the restricted Delaunay triangulation of the final samples: vertices on the
/// skin (Newton-projected to |Φ − t| ≤ 1e-12 relative), triangles oriented along ∇Φ.

#include <cstddef>
#include <functional>
#include <vector>

#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/skin/safe_duration.hpp"
#include "dynmesh/skin/skin_function.hpp"

namespace dynmesh {

struct SkinMeshOptions {
    double time = 0;                 ///< the level t: the skin at growth time t is Φ = t
    SkinQuality quality{};           ///< C and Q0 of the size bound [U]
    double radius_edge_bound = 1.0;  ///< surface Delaunay ball radius over shortest edge
    /// The floor under ϱ in the size bound, as a fraction of the mean input atom radius
    /// √(s·w): near a critical point ϱ → 0 (spec U9), so the floor keeps the mesh finite there.
    double rho_floor_factor = 1e-2;
    std::size_t max_vertices = 20'000'000;  ///< refinement stops with an error beyond this
    /// Called about every 1% of progress with (vertices so far, restricted facets still bad).
    std::function<void(std::size_t, std::size_t)> progress;
};

struct SkinMeshReport {
    std::size_t seeds = 0;            ///< seed points on the skin
    std::size_t refined_size = 0;     ///< insertions for [U]
    std::size_t refined_shape = 0;    ///< insertions for the radius-edge bound
    std::size_t refined_topology = 0; ///< insertions for a dual edge crossing twice
    std::size_t refused = 0;          ///< ball centres that coincided with a sample
    std::size_t delaunay_vertices = 0;
    std::size_t locate_fallbacks = 0; ///< mixed-cell walks that fell back to a scan
    std::size_t flat_cells = 0;       ///< Delaunay cells with no finite circumcentre
    double rho_floor = 0;             ///< the absolute floor under ϱ
    double seconds = 0;
};

struct SkinMeshResult {
    SurfaceMesh mesh;                 ///< closed, oriented outward (along ∇Φ)
    std::vector<double> rho;          ///< ϱ at each mesh vertex
    SkinMeshReport report;
};

/// The static restricted Delaunay mesh of the skin Φ = options.time.
/// \throw InvalidInput when the skin is empty at that time, or options are out of range;
///        ResourceLimit-like InvalidInput when max_vertices is exceeded (naming it).
[[nodiscard]] SkinMeshResult mesh_skin(const SkinFunction& phi, const SkinMeshOptions& options = {});

/// Moves x along ∇Φ onto Φ = t (Newton steps x ← x − (Φ − t)∇Φ/‖∇Φ‖², §1.7), at most 50
/// steps, to |Φ − t| ≤ 1e-12·scale². `hint` is the walk's start and receives the last cell.
[[nodiscard]] Point3 project_to_skin(const SkinFunction& phi, const Point3& x, double t, std::size_t& hint);

}  // namespace dynmesh
