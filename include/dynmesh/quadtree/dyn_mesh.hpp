#pragma once
/// \file DynQuadMesh<D>: the quality simplicial mesh of quad_mesh.hpp (D = 2, triangles) and
/// oct_mesh.hpp (D = 3, tetrahedra), maintained under point insertions and deletions
/// (shared/specs/dynamic-quadtree.md §4.6).
///
/// State: a mesh-mode DynQuadtree and, for every leaf, its **leaf code**, the few bits its
/// simplices are a function of (which side/edge midpoints and face centres are vertices, and
/// the star of an input point it belongs to, if any). An update
///   1. updates the tree incrementally (support counting, O(lg L/s) cells, spec §3.2);
///   2. collects the changed cells X = cells split ∪ cells merged ∪ the leaf of the point;
///   3. recomputes the codes of the leaves that can read a cell of X: a leaf's code reads only
///      its 3^D block of equal-size cells (their kind and points), so these are the current
///      leaves of size |x|/2 or |x| whose closure meets x's closure, for x in X (at most
///      16 + 9 cells per x in 2D, 64 + 27 in 3D);
///   4. drops the codes of the leaves that disappeared, and reports the simplex delta.
/// The cost is O(|X|) = O(lg L/s) lookups, independent of n.
///
/// The mesh is a function of (domain, point set) alone: mesh() equals quad_mesh() / oct_mesh()
/// of the same point set (byte-identical output files), whatever the history; check_invariants()
/// certifies it without a rebuild by recomputing every stored code.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "dynmesh/quadtree/oct_mesh.hpp"
#include "dynmesh/quadtree/quad_mesh.hpp"
#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh {

/// The mesh type of dimension D: QuadMesh2 (triangles) or OctMesh3 (tetrahedra).
template <int D>
using SimplexMeshD = std::conditional_t<D == 2, QuadMesh2, OctMesh3>;

/// What the last insert/erase changed.
template <int D>
struct MeshUpdateReport {
    QuadtreeUpdateReport<D> tree;       // cells split / merged, crowding and support work
    std::size_t leaves_examined = 0;    // leaves whose code was recomputed
    std::size_t leaves_removed = 0;     // leaves that disappeared (split, or merged away)
    std::size_t leaves_created = 0;     // new leaves
    std::size_t leaves_remeshed = 0;    // surviving leaves whose simplices changed
    std::size_t simplices_removed = 0;  // simplices of removed and remeshed leaves (old)
    std::size_t simplices_added = 0;    // simplices of created and remeshed leaves (new)
};

template <int D>
class DynQuadMesh {
public:
    using Point = PointD<D>;
    using Mesh = SimplexMeshD<D>;

    /// An empty point set over the domain of `domain` (its mode is ignored: mesh mode).
    /// \throw InvalidInput as DynQuadtree's constructor.
    explicit DynQuadMesh(const QuadtreeOptions<D>& domain = {});
    /// From-scratch build. \throw InvalidInput as DynQuadtree::build.
    [[nodiscard]] static DynQuadMesh build(std::span<const Point> points,
                                           const QuadtreeOptions<D>& domain = {});

    /// Inserts p and updates the mesh. On any result other than Inserted nothing changes.
    [[nodiscard]] InsertResult insert(const Point& p);
    /// Erases the stored point with p's snapped coordinates. On NotFound nothing changes.
    [[nodiscard]] EraseResult erase(const Point& p);

    /// The mesh-mode tree.
    [[nodiscard]] const DynQuadtree<D>& tree() const { return tree_; }
    [[nodiscard]] std::size_t size() const { return tree_.size(); }
    /// Number of simplices of the current mesh (maintained, O(1)).
    [[nodiscard]] std::size_t simplex_count() const { return simplices_; }
    /// The change report of the last successful insert or erase.
    [[nodiscard]] const MeshUpdateReport<D>& last_update() const { return last_update_; }

    /// The current mesh in canonical form (vertices sorted by lattice key, simplices in leaf
    /// order). O(size log size): this is output, not part of an update.
    [[nodiscard]] Mesh mesh() const;
    /// Deterministic text form of the tree and the mesh: the tree's canonical_dump(), then the
    /// mesh's vertices (hexadecimal floats, exact) and simplices in canonical order. Equal point
    /// sets over equal domains give byte-identical dumps, whatever the history of updates.
    [[nodiscard]] std::string canonical_dump() const;
    /// Every violated invariant: the tree's (check_invariants), one stored code per leaf and
    /// no other, every stored code equal to its recomputation, the simplex count. Empty when
    /// valid. O(size).
    [[nodiscard]] std::vector<std::string> check_invariants() const;

private:
    struct CellHash {
        std::size_t operator()(const CellId<D>& c) const noexcept;
    };
    void refresh(const typename DynQuadtree<D>::GridPoint& g);

    DynQuadtree<D> tree_;
    std::unordered_map<CellId<D>, std::uint32_t, CellHash> codes_;  // leaf -> leaf code
    std::size_t simplices_ = 0;
    MeshUpdateReport<D> last_update_;
};

extern template class DynQuadMesh<2>;
extern template class DynQuadMesh<3>;

}  // namespace dynmesh
