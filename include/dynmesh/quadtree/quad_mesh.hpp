#pragma once
/// \file A quality triangle mesh of the domain box from a 2D DynQuadtree, by the BEG-style
/// postprocess of shared/specs/dynamic-quadtree.md §4 (D = 2).
///
/// The spec's rules need the **mesh-mode** tree (isolation radius k = 2 plus rules U and R,
/// §1.4), which guarantees that the four leaves around the warped corner of every input point
/// all have the point leaf's size (the star lemma, §4.1). quad_mesh() uses the tree itself when
/// it is in mesh mode (QuadtreeMode::Mesh) and otherwise builds the mesh-mode tree of the same
/// point set. Each leaf is then triangulated from a few bits of its neighbourhood
/// (src/quadtree/leaf_mesh.hpp), for D = 2:
///   * warping (§4.2): the corner v of a point's leaf nearest to the point (ties round up) is
///     moved onto the point; the vertex keeps its lattice key;
///   * the point's leaf: cone from the point over the sides not incident to v;
///   * the other three star cells: fan from the cell centre over the boundary cycle;
///   * every other leaf: two triangles split by the lower-left/upper-right diagonal when no
///     side carries a hanging vertex, else a fan from the cell centre.
/// The mesh is a function of (domain, point set) alone, so it inherits the tree's history
/// independence. quad_mesh() computes it from scratch; DynQuadMesh<2> (dyn_mesh.hpp) maintains
/// it under insertions and deletions, with identical output.
/// Quality (§4.5): every angle lies in [arctan(1/3), 135°] = [18.43°, 135°].

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh {

/// The promised angle range of quad_mesh() output, in degrees (spec §4.5, 2D).
inline constexpr double kQuadMeshMinAngleDeg = 18.434948822922010;  // arctan(1/3)
inline constexpr double kQuadMeshMaxAngleDeg = 135.0;

/// A triangle mesh of the domain box [origin, origin + width]^2.
struct QuadMesh2 {
    Vec2 origin{};  // the tree's domain box
    double width = 1.0;
    /// Vertices sorted by lattice key (grid coordinates): leaf corners and cell centres at
    /// their lattice positions, warped corners at their input point (bit-identical), except
    /// in a point leaf smaller than two input quanta (2^(kGuardBits+1) grid units: points within
    /// about W·2^-48 of each other), where the point sits at its grid position (within one
    /// quantum W·2^-49 of the input), which keeps every simplex positively oriented.
    std::vector<Vec2> points;
    /// Counter-clockwise triangles (indices into points), in leaf order.
    std::vector<std::array<std::uint32_t, 3>> triangles;
    /// The vertex of each tree point, in DynQuadtree::points() order.
    std::vector<std::uint32_t> input_vertices;
    /// Leaves of the mesh-mode refinement the triangles were derived from.
    std::size_t leaves = 0;
};

/// Meshes the domain of `tree` (see the file comment). Deterministic: equal point sets over
/// equal domains give identical meshes, whatever the history of the tree.
/// \throw InternalError if an invariant of the construction fails (star lemma).
[[nodiscard]] QuadMesh2 quad_mesh(const DynQuadtree<2>& tree);

/// Every violated property, one problem each (no figures); ok() when the mesh is valid: indices
/// in range, every triangle counter-clockwise by orient2d (exact), total signed area equal to
/// the domain area (relative tolerance 1e-12), every edge used by one triangle (then it lies on
/// the box boundary) or by two with opposite directions, no two vertices at one position, no
/// unused vertex.
[[nodiscard]] CheckReport check_quad_mesh(const QuadMesh2& mesh);

struct AngleRangeDeg {
    double min = 180.0;
    double max = 0.0;
};
/// The smallest and largest triangle angle, in degrees.
[[nodiscard]] AngleRangeDeg angle_range_deg(const QuadMesh2& mesh);

}  // namespace dynmesh
