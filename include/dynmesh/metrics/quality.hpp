#pragma once
/// \file mesh_quality(): one report with the mesh's size and topology, triangle shape
/// statistics, the paper's two smoothness statistics (spec §4.7: normal deviation and
/// 180 - dihedral) and, on request, the Hausdorff distance to the true surface and the
/// number of self-intersecting face pairs.
///
/// Angles are in degrees throughout. The statistics are population statistics (Summary).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/metrics/hausdorff.hpp"
#include "dynmesh/metrics/histogram.hpp"
#include "dynmesh/metrics/statistics.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh {

struct QualityOptions {
    /// The true surface, if known: enables the normal deviation (and Hausdorff). Not owned;
    /// must outlive the call.
    const ImplicitSurface* surface = nullptr;
    /// Also compute hausdorff_to_surface (needs `surface`; O(n log n), CGAL AABB tree).
    bool hausdorff = false;
    /// Sampling of the Hausdorff distance.
    HausdorffOptions hausdorff_sampling = {};
    /// Also count self-intersecting face pairs (O(n log n), CGAL).
    bool self_intersections = false;
    /// Bins of the two angle-deviation histograms, which span [0, histogram_max_deg]
    /// (larger values land in the last bin). Default: 18 bins of 10 degrees.
    std::size_t histogram_bins = 18;
    double histogram_max_deg = 180.0;
};

struct QualityReport {
    // ---- size and topology ---------------------------------------------------------------
    std::size_t vertices = 0, faces = 0, edges = 0;
    long long euler = 0;  ///< V - E + F
    bool closed = false;  ///< no boundary edge (and at least one face)
    std::size_t boundary_edges = 0;
    /// Zero-area faces (exactly collinear corners, as check_mesh() counts them). Their
    /// circumradius and radius-edge ratio are infinite: when there is one, radius_edge.max
    /// and circumradius.max are +infinity, and the other statistics of those two (and
    /// normal_dev) are over the non-degenerate faces. They count in angle_deg (0, 0, 180).
    std::size_t degenerate_faces = 0;

    // ---- triangle shape ------------------------------------------------------------------
    /// All 3F triangle angles: min is the mesh's min angle, max its max angle (mean is 60
    /// for any non-degenerate mesh).
    Summary angle_deg;
    /// Circumradius / shortest edge, one per face (equilateral: 1/sqrt(3) = 0.577).
    Summary radius_edge;
    /// Circumradius, one per face.
    Summary circumradius;

    // ---- smoothness (spec §4.7) ----------------------------------------------------------
    /// 180 - dihedral angle, one per interior edge (0 for a flat pair); orientation-free.
    Summary dihedral_dev_deg;
    Histogram dihedral_dev_hist;
    /// Angle between each face's outward unit normal and surface->normal(v) at each of its
    /// three vertices v: 3 values per face. Only with a surface.
    std::optional<Summary> normal_dev_deg;
    /// The same, non-obtuse variant min(a, 180 - a) (agrees with normal_dev below 90).
    std::optional<Summary> normal_dev_abs_deg;
    std::optional<Histogram> normal_dev_hist;

    // ---- on request ------------------------------------------------------------------------
    /// Two-sided sampled Hausdorff distance to the surface (distance field: the max).
    std::optional<HausdorffResult> hausdorff_to_surface;
    /// Number of intersecting face pairs (self_intersection.hpp).
    std::optional<std::size_t> self_intersecting_pairs;
};

/// Measures `mesh`. Without Hausdorff and self-intersections this is one linear pass over
/// faces and one over edges (no allocation beyond one normal per vertex with a surface).
/// Shape measures are computed per triangle (and per edge pair) in a frame of its own, its
/// edge vectors scaled by an exact power of two (scaled_frame.hpp), so meshes with
/// coordinates near the double limits (1e308, or subnormal 1e-310), or with triangles many
/// orders of magnitude smaller than their coordinates, get the same angles and ratios as the
/// same triangles near unit size. \throw InvalidInput also when a surface is given and the
/// mesh's coordinates exceed 1e50 (require_surface_range).
/// \throw InvalidInput when options.hausdorff is set without options.surface, when
///        histogram_bins == 0 or histogram_max_deg <= 0.
[[nodiscard]] QualityReport mesh_quality(const SurfaceMesh& mesh,
                                         const QualityOptions& options = {});

/// Flat named numbers for the CLI's JSON, in this order:
/// "vertices", "faces", "edges", "euler", "closed" (0/1), "boundary_edges",
/// "degenerate_faces", "min_angle_deg", "max_angle_deg", "mean_angle_deg",
/// "radius_edge_max", "radius_edge_mean", "circumradius_max", "circumradius_mean",
/// "dihedral_dev_mean_deg", "dihedral_dev_sd_deg", "dihedral_dev_max_deg";
/// with a surface "normal_dev_mean_deg", "normal_dev_sd_deg", "normal_dev_max_deg",
/// "normal_dev_abs_mean_deg", "normal_dev_abs_sd_deg", "normal_dev_abs_max_deg";
/// when computed "hausdorff", "hausdorff_mesh_to_surface", "hausdorff_surface_to_mesh";
/// when computed "self_intersections".
[[nodiscard]] std::vector<std::pair<std::string, double>> flatten(const QualityReport& report);

/// How reports write a field of flatten(), as CheckReport figures are written: "vertices",
/// "faces", "edges", "euler", "boundary_edges", "degenerate_faces" and "self_intersections" are
/// Integer, "closed" is Boolean, the others Real.
[[nodiscard]] CheckFigure::Kind quality_field_kind(std::string_view name);

}  // namespace dynmesh
