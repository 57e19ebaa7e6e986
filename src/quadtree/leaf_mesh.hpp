#pragma once
/// \file Internal: the per-leaf form of the BEG-style postprocess (spec §4), shared by the static
/// meshes (quad_mesh.cpp, oct_mesh.cpp) and the dynamic one (dyn_mesh.cpp).
///
/// The simplices of a leaf L of a mesh-mode tree are a function of L and a small **leaf code**:
///   * one bit per midpoint probe of L: every lattice point lo + (s/2)·e with e in {0, 1, 2}^D
///     having between 1 and D − 1 coordinates equal to 1 (2D: the 4 side midpoints; 3D: the 12
///     edge midpoints and the 6 face centres), set when the point is a vertex of the
///     subdivision (a corner of some leaf);
///   * the star bit and the apex corner when L lies in the star of an input point (the 2^D
///     leaves around the point's warped corner v, §4.1), and whether L holds that point.
/// In a balanced tree the code reads only L's 3^D block of equal-size cells: whether each is
/// internal (its children make the midpoints vertices) and the point of each leaf among them.
/// Hence a leaf's simplices change only when a cell of its block is split, merged, or gains
/// or loses a point, which is what the dynamic mesh uses to find the leaves to recompute.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "dynmesh/quadtree/dyn_mesh.hpp"
#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh::detail {

/// A lattice point in grid units (coordinates in [0, 2^52]).
template <int D>
using Lattice = std::array<std::uint64_t, D>;
/// A simplex over lattice keys (D + 1 vertices).
template <int D>
using LatticeSimplex = std::array<Lattice<D>, D + 1>;
using LeafCode = std::uint32_t;

/// The code of leaf `leaf` of the mesh-mode tree `tree`.
/// \throw InternalError if two stars share the leaf, or (for a point leaf) a star cell is not
///        a leaf of the point leaf's size (the star lemma).
template <int D>
[[nodiscard]] LeafCode leaf_code(const DynQuadtree<D>& tree, const CellId<D>& leaf);

/// Whether lattice point v, a corner, side/edge midpoint or face centre of leaf, is a vertex of
/// the subdivision according to the code (corners always are; other points never).
template <int D>
[[nodiscard]] bool code_has_vertex(const CellId<D>& leaf, LeafCode code, const Lattice<D>& v);
/// True when the leaf is one of the 2^D cells of a star.
template <int D>
[[nodiscard]] bool code_is_star(LeafCode code);
/// True when the leaf holds the star's point.
template <int D>
[[nodiscard]] bool code_holds_point(LeafCode code);
/// The star's warped corner (a corner of the leaf). Only meaningful when code_is_star().
template <int D>
[[nodiscard]] Lattice<D> code_apex(const CellId<D>& leaf, LeafCode code);

/// "cell (level L; i j [k])", for messages.
template <int D>
[[nodiscard]] std::string cell_name(const CellId<D>& c);

/// Appends to `bad` one message per unused vertex ("vertex V is unused") and per pair of
/// vertices at one position ("vertices U and V coincide"), for the mesh checkers.
template <int D>
void append_vertex_problems(std::span<const PointD<D>> points, const std::vector<bool>& used,
                            std::vector<std::string>& bad);

/// The lower corner of a cell and its side, in grid units.
template <int D>
[[nodiscard]] std::pair<Lattice<D>, std::uint64_t> cell_box(const CellId<D>& c);

/// Appends the simplices of one leaf (spec §4.3, §4.4). Defined per dimension: quad_mesh.cpp
/// (D = 2, counter-clockwise triangles) and oct_mesh.cpp (D = 3, orientation not fixed).
template <int D>
void leaf_simplices(const CellId<D>& leaf, LeafCode code, std::vector<LatticeSimplex<D>>& out);
template <>
void leaf_simplices<2>(const CellId<2>& leaf, LeafCode code,
                       std::vector<LatticeSimplex<2>>& out);
template <>
void leaf_simplices<3>(const CellId<3>& leaf, LeafCode code,
                       std::vector<LatticeSimplex<3>>& out);

/// Orients a lattice simplex of leaf_simplices() positively by the exact lattice orientation
/// (3D: swaps its last two vertices when negative).
/// \throw InternalError if it is flat, or (2D) clockwise, which the construction never makes.
template <int D>
void orient_lattice_simplex(LatticeSimplex<D>& t);
/// Throws InternalError unless the simplex at its real vertex positions (warped corners moved
/// onto their points) is positively oriented (exact orient2d / orient3d).
template <int D>
void check_warped_orientation(const std::array<PointD<D>, D + 1>& p);
/// The position of an unwarped lattice vertex: origin + k·W·2^-52 per axis.
template <int D>
[[nodiscard]] PointD<D> lattice_position(const QuadtreeOptions<D>& domain, const Lattice<D>& k);
/// The input point the star's apex code_apex(leaf, code) is moved onto, when the leaf is a
/// star cell and the star's point leaf is at least two input quanta wide (else nullptr: the
/// apex stays at its lattice position, see assemble()).
template <int D>
[[nodiscard]] const PointD<D>* star_point(const DynQuadtree<D>& tree, const CellId<D>& leaf,
                                          LeafCode code);

/// A mesh in index form, vertices sorted by lattice key.
template <int D>
struct AssembledMesh {
    std::vector<PointD<D>> points;
    std::vector<std::array<std::uint32_t, D + 1>> simplices;  // positively oriented
    std::vector<std::uint32_t> input_vertices;               // in tree.points() order
};

/// Assembles the simplices of every leaf (leaves sorted by (level, index), with their codes):
/// vertices sorted by lattice key at their lattice positions, warped corners at their input
/// point; simplices in leaf order, oriented positively (exact orient2d / orient3d).
/// \throw InternalError if two points warp to one corner or a simplex is flat.
template <int D>
[[nodiscard]] AssembledMesh<D> assemble(const DynQuadtree<D>& tree,
                                        std::span<const std::pair<CellId<D>, LeafCode>> leaves);

template <int D>
using PublicMesh = SimplexMeshD<D>;

/// The public mesh of a mesh-mode tree from its coded leaves (sorted by (level, index)).
template <int D>
[[nodiscard]] PublicMesh<D> mesh_from_leaves(
    const DynQuadtree<D>& tree, std::span<const std::pair<CellId<D>, LeafCode>> leaves);

/// quad_mesh() / oct_mesh(): the mesh of any tree's point set, from scratch.
template <int D>
[[nodiscard]] PublicMesh<D> mesh_of_tree(const DynQuadtree<D>& tree);

/// The mesh-mode tree of tree's point set: tree itself if it is in mesh mode, else a build.
/// `storage` holds the built tree when one is needed.
template <int D>
[[nodiscard]] const DynQuadtree<D>& mesh_mode_tree(const DynQuadtree<D>& tree,
                                                   DynQuadtree<D>& storage);

/// Every leaf of a mesh-mode tree with its code, sorted by (level, index).
template <int D>
[[nodiscard]] std::vector<std::pair<CellId<D>, LeafCode>> coded_leaves(
    const DynQuadtree<D>& tree);

}  // namespace dynmesh::detail
