#pragma once
/// \file The edge-flip paper's experiment (§6 of its digest): measure a mesh, worsen it by
/// random flips, smooth it by flipping to termination, and measure both again.

#include <cstddef>
#include <optional>

#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/flips/worsen.hpp"
#include "dynmesh/metrics/quality.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh {

struct SmoothingExperimentOptions {
    WorsenOptions worsen = {};
    FlipOptions flip = {};
    /// The true surface, if known (normal deviation rows); not owned.
    const ImplicitSurface* surface = nullptr;
    std::size_t histogram_bins = 60;   ///< of [0, 60] degrees
    double histogram_max_deg = 60.0;
};

struct SmoothingExperimentResult {
    QualityReport initial, worsened, smoothed;
    WorsenReport worsen;
    FlipReport flip;
    /// Fraction of the smoothed mesh's edges that the initial mesh also has.
    double shared_edge_fraction = 0;
};

/// Runs the experiment on a copy of `mesh`; `smoothed_out`, if given, receives the smoothed
/// mesh and `worsened_out` the worsened one.
/// \pre mesh is a closed oriented manifold without garbage.
[[nodiscard]] SmoothingExperimentResult run_smoothing_experiment(
    const SurfaceMesh& mesh, const SmoothingExperimentOptions& options,
    SurfaceMesh* worsened_out = nullptr, SurfaceMesh* smoothed_out = nullptr);

/// Fraction of b's edges that are also edges of a (same vertex indices).
[[nodiscard]] double shared_edge_fraction(const SurfaceMesh& a, const SurfaceMesh& b);

}  // namespace dynmesh
