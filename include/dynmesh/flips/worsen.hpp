#pragma once
/// \file The worsening procedure of the edge-flip paper's experiments: random flips that keep
/// every dihedral angle at or above a floor.

#include <cstddef>
#include <cstdint>
#include <functional>

#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

struct WorsenOptions {
    std::size_t rounds = 5;          ///< passes over the edge list
    double probability = 0.5;        ///< chance to try each edge
    double min_dihedral_deg = 120;   ///< a flip is undone if a dihedral angle would drop below
    std::uint64_t seed = 1;
    /// When set, only edges for which it returns true are tried (e.g. a region around some
    /// vertices, for local experiments); the coin is still drawn for every edge.
    std::function<bool(const SurfaceMesh&, Edge)> only = {};
};

struct WorsenReport {
    std::size_t flips = 0;      ///< flips kept
    std::size_t attempts = 0;   ///< edges drawn (coin came up)
    std::size_t rejected = 0;   ///< flips undone because of the dihedral floor
};

/// Each round takes a snapshot of the edges as sorted vertex pairs; for each pair that is
/// still an edge, with the given probability, flips it unless the flip is topologically
/// invalid or leaves a dihedral angle below the floor at the new edge or the four quad edges.
/// Deterministic for a seed. An undone flip restores the edge pq and both triangles, but
/// the two faces may swap indices and start at another corner. Its geometric tests
/// run in each quad's unit frame (scaled_frame.hpp): the same flips for a mesh and for the
/// mesh scaled by any power of two, at 1e308 or at 1e-310 as at unit size. \pre no garbage.
WorsenReport worsen(SurfaceMesh& mesh, const WorsenOptions& options = {});

}  // namespace dynmesh
