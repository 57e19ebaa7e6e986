#pragma once
/// \file Creases of a closed mesh (spec deforming-mesh.md §10.3): its sharp edges, found once
/// by a dihedral-angle threshold, marked as locked edges (kLockedEdges: no flip touches them,
/// remove_point() keeps their chains) and cut into polylines between corners.

#include <cstddef>
#include <vector>

#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

struct CreaseOptions {
    /// An edge is a crease when 180 degrees minus its dihedral angle exceeds this (the
    /// feature angle of `flip --feature-angle`); in (0, 180).
    double feature_angle_deg = 45.0;
    /// Polylines of fewer edges are dropped (scan noise), repeatedly, since dropping one can
    /// join two others at a former corner.
    std::size_t min_chain_edges = 3;
};

struct Creases {
    /// Each polyline's vertices in order, corner to corner; a loop through no corner starts
    /// and ends at the same vertex.
    std::vector<std::vector<Vertex>> lines;
    /// Vertices where one or more than two crease edges meet.
    std::vector<Vertex> corners;
    std::size_t edges = 0;  ///< crease edges marked
};

/// Marks the creases of `mesh` in its kLockedEdges property (added when missing; edges not on
/// a crease are cleared) and returns their polylines. Deterministic: polylines start at the
/// corners in vertex order, then the loops at their smallest vertex.
/// \throw InvalidInput when feature_angle_deg is not in (0, 180).
Creases mark_creases(SurfaceMesh& mesh, const CreaseOptions& options = {});

}  // namespace dynmesh
