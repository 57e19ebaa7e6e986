#pragma once
/// \file check_mesh(): verifies the halfedge structure and the surface's topology and reports
/// every violation (not only the first).

#include <cstddef>
#include <string>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

struct MeshCheckOptions {
    bool require_closed = false;      ///< boundary edges count as problems
    bool require_connected = false;   ///< more than one component counts as a problem
    bool check_degenerate = true;     ///< zero-area triangles count as problems
    std::size_t max_listed = 50;      ///< problems listed in full; the rest only counted
};

/// Figures (the keys of `dynmesh check --report`): vertices, edges, faces, euler (V − E + F),
/// closed (no boundary edge), components, boundary_edges, degenerate_faces, and the counts
/// isolated_vertices, non_manifold_vertices, duplicate_edges. After a broken halfedge
/// structure only the element counts and euler are measured (the rest stay 0 / false).
/// ok(): the connectivity is a valid oriented 2-manifold (with the options' extras).
[[nodiscard]] CheckReport check_mesh(const SurfaceMesh& mesh, const MeshCheckOptions& options = {});

/// Throws TopologyError naming `what` and the first problems when check_mesh() fails.
void require_valid_mesh(const SurfaceMesh& mesh, const std::string& what,
                        const MeshCheckOptions& options = {});

}  // namespace dynmesh
