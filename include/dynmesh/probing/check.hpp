#pragma once
/// \file check_probing(): what a probing run promises (specs/probing.md §5.1, §7), verified
/// against the object's ground truth, which the run itself never saw.
///
/// Checked: the run's own invariants (ProbingResult::problems); the output is a closed
/// oriented 2-manifold (2D: disjoint simple closed polygons, every vertex with one edge in and
/// one out), oriented outward (positive enclosed volume; 2D: counter-clockwise, positive
/// area), with the object's Euler characteristic and number of components; every ball of
/// the output is at most ε; the sample is a 2ε-sample of S (every ground-truth sample of S has
/// a sample point within 2ε); the two-sided Hausdorff distance between the output and S is
/// within the paper's bound 4.5·diam(S)·ε²/ε_S² (Theorem 2.1 with ε_S ≤ rch(S); for a
/// polyhedron, whose reach is 0, the bound is the one the user's ε_S asserts).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/probing/oracle.hpp"
#include "dynmesh/probing/refine.hpp"

namespace dynmesh {

struct ProbingCheckOptions {
    /// Spacing of the ground-truth samples of S for the Hausdorff and 2ε-sample measures
    /// (0: ε/4, coarsened so that at most about 2e5 samples are drawn).
    double spacing = 0;
};

/// The default spacing of ProbingCheckOptions: ε/4, coarsened so that S gets at most about
/// 2e5 samples (area / spacing² in 3D, length / spacing in 2D).
[[nodiscard]] double default_check_spacing(const GroundTruth& truth, double eps, int dim);

/// Verifies `result` (of probe_surface when dim is 3, probe_curve when dim is 2, run with
/// `options`) against `truth`. Problems: the run's own (ProbingResult::problems), then one
/// line per violation. Figures (the keys of `dynmesh probe --report`): euler (V − E + F; 2D:
/// V − E), components, max_ball_radius (≤ ε), hausdorff (two-sided, sampled: a lower bound of
/// the true distance; 3D: measured only on a closed manifold, else 0), hausdorff_bound
/// (4.5·diam(S)·ε²/ε_S²), sample_gap (largest distance from a sample of S to the nearest
/// sample, ≤ 2ε), and the flag closed_manifold (2D: disjoint simple closed polygons).
[[nodiscard]] CheckReport check_probing(const ProbingResult& result, const GroundTruth& truth,
                                        const ProbingOptions& options, int dim,
                                        const ProbingCheckOptions& check = {});

/// The two-sided sampled Hausdorff distance between a triangle mesh and the object's surface:
/// the mesh sampled at vertices, edge midpoints and barycentres against GroundTruth::distance,
/// and `surface_samples` against the mesh (AABB tree). \throw InvalidInput for a mesh that is
/// not an oriented 2-manifold or has no face.
[[nodiscard]] double surface_hausdorff(const TriangleSoup& mesh, const GroundTruth& truth,
                                       const std::vector<Point3>& surface_samples);

/// The two-sided sampled Hausdorff distance between a closed polyline (polygons, indices into
/// points; z = 0) and a curve known by its distance function and samples.
[[nodiscard]] double polyline_hausdorff(const std::vector<Point3>& points,
                                        const std::vector<std::vector<std::uint32_t>>& polygons,
                                        const GroundTruth& truth, const std::vector<Point3>& curve_samples);

}  // namespace dynmesh
