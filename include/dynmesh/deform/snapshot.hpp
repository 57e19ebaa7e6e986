#pragma once
/// \file Meshes taken from a deforming-mesh run at one moment: the input of the edge-flip
/// paper's Table 3 (a "boomerang-like" snapshot of a deforming ball, dihedral statistics).

#include <cstddef>
#include <cstdint>

#include "dynmesh/deform/run.hpp"
#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

/// The mesh the DeformingMesh maintains at time unit t of run_deform(s, options), the run
/// stopped there (options.stop_after and on_frame are replaced). The mesh is compacted (no
/// deleted elements). \throw InvalidInput for t outside [0, horizon].
[[nodiscard]] SurfaceMesh deform_snapshot(const Scenario& s, int t, DeformRunOptions options = {});

/// Default sample count of boomerang_snapshot(): the mesh keeps about 5.8K of them as
/// vertices at the snapshot, the size of the paper's snapshot (5,802 vertices).
inline constexpr std::size_t kBoomerangSamples = 14000;

/// The edge-flip paper's Table 3 input, as the digest (§6) reproduces it: the "boomerang"
/// scenario (unit sphere stretched to 3:1:1 and bent into a 120-degree arc) with `samples`
/// samples, at its most bent time t = horizon / 2, measuring nothing on the way.
[[nodiscard]] SurfaceMesh boomerang_snapshot(std::size_t samples = kBoomerangSamples, std::uint64_t seed = 1);

}  // namespace dynmesh
