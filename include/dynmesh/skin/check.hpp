#pragma once
/// \file The invariants of a skin mesh (specs/skin-surfaces.md §6.3 M1, M2, M4, M5), measured
/// and checked in one pass: what the tests assert and `dynmesh skin --check` runs.

#include <cstddef>
#include <string>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/skin/safe_duration.hpp"
#include "dynmesh/skin/skin_function.hpp"

namespace dynmesh {

struct SkinMeshCheckOptions {
    double time = 0;             ///< the level t the mesh stands for
    SkinQuality quality{};       ///< Q1 sets the angle floor asin(1/Q1²) and the bound (C·Q1)²
    double rho_floor = 0;        ///< ϱ below this counts as this (the mesher's floor)
    double max_normal_deviation_deg = 25;
    double max_vertex_offset = 1e-9;  ///< |Φ − t|/‖∇Φ‖ over the skin's extent
    /// Per face index, the triangles exempt from the bounds (surgery templates of a growing
    /// skin, §3.3): measured for topology and vertex offsets only. Empty: none.
    std::vector<bool> exempt;
};

/// Measures `mesh` against the skin Φ = options.time and lists every violated invariant:
/// not a closed oriented 2-manifold; Euler characteristic or components unlike the alpha
/// complex (skin_topology of the input balls); a vertex off the skin; a triangle turned
/// inward; an angle under asin(1/Q1²); mesh-to-skin distance over (C·Q1)²·ϱ; normal deviation
/// over the limit.
///
/// Figures (the keys of `dynmesh skin --report`): euler, components, expected_euler and
/// expected_components (2(b0 − b1 + b2) and b0 + b2 of the alpha complex at t),
/// min_angle_deg (smallest angle of any triangle), angle_floor_deg (asin(1/Q1²)),
/// frac_angles_below_15, frac_angles_below_20, frac_below_floor (shares of triangles with an
/// angle under 15°, 20°, the floor), exempt_triangles (left out of the angle, distance and
/// normal measures), hausdorff_over_rho_max and hausdorff_max (mesh to skin: the largest
/// distance of a triangle point, 10 per triangle, from the skin, over ϱ at its foot and in
/// absolute units), normal_dev_max_deg and normal_dev_mean_deg (triangle normal against ∇Φ at
/// its projected centroid); and vertex_offset_max (max |Φ − t|/‖∇Φ‖ over vertices, relative
/// to the extent) and inward_faces (triangles whose normal opposes ∇Φ), which the CLI does
/// not write.
[[nodiscard]] CheckReport check_skin_mesh(const SkinFunction& phi, const SurfaceMesh& mesh,
                                          const SkinMeshCheckOptions& options = {});

}  // namespace dynmesh
