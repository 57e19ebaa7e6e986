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
///   4. drops the codes of the leaves that disappeared;
///   5. updates the live mesh (live_mesh.hpp): removes the simplices of the leaves that
///      disappeared or whose code changed, adds those of the new and re-coded leaves, and
///      removes the vertices no simplex uses any more; the change is recorded in last_change().
/// The cost is O(|X|) = O(lg L/s) lookups plus the simplices changed, independent of n.
///
/// Live mesh. current_mesh() is kept up to date by every update (never rebuilt): vertex ids
/// are per lattice position (a warped corner is a vertex of its own, at its input point: when a
/// corner is warped or unwarped its old vertex is removed and a new one added), simplex ids
/// are per leaf block (the simplices of one leaf have consecutive ids). Its simplices are those
/// of mesh() (same coordinates, same orientation) in slot order.
///
/// The canonical mesh is a function of (domain, point set) alone: mesh() equals quad_mesh() /
/// oct_mesh() of the same point set (byte-identical output files), whatever the history;
/// check_invariants() certifies it without a rebuild by recomputing every stored code.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "dynmesh/quadtree/live_mesh.hpp"
#include "dynmesh/quadtree/oct_mesh.hpp"
#include "dynmesh/quadtree/quad_mesh.hpp"
#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh {

/// The mesh type of dimension D: QuadMesh2 (triangles) or OctMesh3 (tetrahedra).
template <int D>
using SimplexMeshD = std::conditional_t<D == 2, QuadMesh2, OctMesh3>;

/// What the last insert/erase changed.
template <int D>
struct QuadMeshUpdateReport {
    QuadtreeUpdateReport<D> tree;       // cells split / merged, crowding and support work
    std::size_t leaves_examined = 0;    // leaves whose code was recomputed
    std::size_t leaves_removed = 0;     // leaves that disappeared (split, or merged away)
    std::size_t leaves_created = 0;     // new leaves
    std::size_t leaves_remeshed = 0;    // surviving leaves whose simplices changed
    std::size_t simplices_removed = 0;  // simplices of removed and remeshed leaves (old)
    std::size_t simplices_added = 0;    // simplices of created and remeshed leaves (new)
    std::size_t vertices_removed = 0;   // live-mesh vertices no simplex uses any more
    std::size_t vertices_added = 0;     // new live-mesh vertices
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

    /// Inserts p and updates the mesh. On any result other than Inserted nothing changes
    /// (BeyondPrecision: DynQuadtree::insert's resolution rule).
    [[nodiscard]] InsertResult insert(const Point& p);
    /// Erases the stored point with p's snapped coordinates. On NotFound nothing changes.
    [[nodiscard]] EraseResult erase(const Point& p);

    /// The mesh-mode tree.
    [[nodiscard]] const DynQuadtree<D>& tree() const { return tree_; }
    [[nodiscard]] std::size_t size() const { return tree_.size(); }
    /// Number of simplices of the current mesh (maintained, O(1)).
    [[nodiscard]] std::size_t simplex_count() const { return live_.simplex_count(); }
    /// The change report of the last successful insert or erase.
    [[nodiscard]] const QuadMeshUpdateReport<D>& last_update() const { return last_update_; }
    /// The current mesh with stable ids, maintained by every update (see the file comment).
    [[nodiscard]] const LiveMesh<D>& current_mesh() const { return live_; }
    /// What the last successful insert or erase changed in current_mesh(); empty after
    /// construction and build().
    [[nodiscard]] const MeshDelta<D>& last_change() const { return delta_; }

    /// The current mesh in canonical form (vertices sorted by lattice key, simplices in leaf
    /// order). O(size log size): this is output, not part of an update.
    [[nodiscard]] Mesh mesh() const;
    /// Deterministic text form of the tree and the mesh: the tree's canonical_dump(), then the
    /// mesh's vertices (hexadecimal floats, exact) and simplices in canonical order. Equal point
    /// sets over equal domains give byte-identical dumps, whatever the history of updates.
    [[nodiscard]] std::string canonical_dump() const;
    /// Every violated invariant, one problem each: the tree's (check_invariants), one stored
    /// code per leaf and no other, every stored code equal to its recomputation, the live mesh
    /// (vertex use counts, one vertex per lattice position, each leaf's block holding the
    /// simplices its code gives, at their positions: then the live simplices are mesh()'s).
    /// ok() when valid; no figure. O(size).
    [[nodiscard]] CheckReport check_invariants() const;

private:
    using Lattice = std::array<std::uint64_t, D>;
    struct CellHash {
        std::size_t operator()(const CellId<D>& c) const noexcept;
    };
    struct LatticeHash {
        std::size_t operator()(const Lattice& k) const noexcept;
    };
    /// A leaf: its code and its block of simplices in the live mesh.
    struct LeafRecord {
        std::uint32_t code = 0;
        std::uint32_t first = 0;  // first simplex id
        std::uint32_t count = 0;
    };
    /// A live-mesh vertex: its lattice position and the number of simplices using it.
    struct VertexRecord {
        Lattice key{};
        std::uint32_t uses = 0;
    };
    void refresh(const typename DynQuadtree<D>::GridPoint& g);
    /// The simplices of leaf c with this code, positively oriented: lattice positions (the
    /// vertex keys) and real positions (warped corners at their input point).
    void leaf_geometry(const CellId<D>& c, std::uint32_t code, std::vector<Lattice>& keys,
                       std::vector<Point>& points) const;
    /// Adds the simplices of leaf c with this code to the live mesh.
    void add_leaf(const CellId<D>& c, std::uint32_t code);
    /// Removes the simplices of a leaf from the live mesh (vertices left unused are removed by
    /// drop_unused_vertices()).
    void remove_leaf(const LeafRecord& r);
    /// The live vertex at lattice position k with coordinates p (created if needed).
    std::uint32_t acquire_vertex(const Lattice& k, const Point& p);
    void drop_unused_vertices();
    /// Fills the live mesh from scratch from the current tree (construction, build()).
    void rebuild_live();

    DynQuadtree<D> tree_;
    std::unordered_map<CellId<D>, LeafRecord, CellHash> leaves_;
    LiveMesh<D> live_;
    MeshDelta<D> delta_;
    std::vector<VertexRecord> vertices_;                        // by live vertex id
    std::unordered_map<Lattice, std::uint32_t, LatticeHash> vertex_at_;  // position -> id
    std::vector<std::uint32_t> unused_;                         // vertices whose use fell to 0
    QuadMeshUpdateReport<D> last_update_;
};

extern template class DynQuadMesh<2>;
extern template class DynQuadMesh<3>;

}  // namespace dynmesh
