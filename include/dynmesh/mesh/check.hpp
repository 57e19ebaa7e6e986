#pragma once
/// \file check_mesh(): verifies the halfedge structure and the surface's topology and reports
/// every violation (not only the first).

#include <cstddef>
#include <string>
#include <vector>

#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

struct MeshCheckOptions {
    bool require_closed = false;      ///< boundary edges count as problems
    bool require_connected = false;   ///< more than one component counts as a problem
    bool check_degenerate = true;     ///< zero-area triangles count as problems
    std::size_t max_listed = 50;      ///< problems listed in full; the rest only counted
};

struct MeshCheckReport {
    std::vector<std::string> problems;  ///< one line per violation (at most max_listed)
    std::size_t n_problems = 0;         ///< all violations, including unlisted ones
    std::size_t vertices = 0, edges = 0, faces = 0;
    std::size_t boundary_edges = 0;
    std::size_t isolated_vertices = 0;
    std::size_t non_manifold_vertices = 0;
    std::size_t duplicate_edges = 0;
    std::size_t degenerate_faces = 0;
    std::size_t components = 0;
    long long euler = 0;  ///< V - E + F
    bool closed = false;
    /// True when the connectivity is a valid oriented 2-manifold (with the options' extras).
    [[nodiscard]] bool ok() const { return n_problems == 0; }
    /// All listed problems, one per line, prefixed with `prefix`.
    [[nodiscard]] std::string summary(const std::string& prefix = "") const;
};

[[nodiscard]] MeshCheckReport check_mesh(const SurfaceMesh& mesh,
                                         const MeshCheckOptions& options = {});

/// Throws TopologyError naming `what` and the first problems when check_mesh() fails.
void require_valid_mesh(const SurfaceMesh& mesh, const std::string& what,
                        const MeshCheckOptions& options = {});

}  // namespace dynmesh
