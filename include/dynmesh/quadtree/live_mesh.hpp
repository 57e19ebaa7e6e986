#pragma once
/// \file The change interface of the dynamic meshers (DynQuadMesh<D> in dyn_mesh.hpp,
/// DynOffCenterMesh2 in dyn_offcenter.hpp): a LiveMesh<D>, the current mesh with stable vertex
/// and simplex ids, kept up to date by every insert/erase (never rebuilt), and the MeshDelta<D>
/// of the last update, which lists exactly what changed in it.
///
/// Ids. Every vertex and simplex has an id (a slot index) that stays valid while it exists.
/// A removed id is recycled (free list) by a later update, never by the one that removed it, so
/// one delta never names an id both as removed and as added. The simplices one leaf (or one
/// Delaunay cell) contributes get consecutive ids, and a block of freed ids is reused by a block
/// of the same size; the slot counts are therefore bounded by the peak number of live blocks of
/// each size, not by the history. Dead slots are tombstones (has_vertex / has_simplex false).
/// There is no compaction: a caller that mirrors the mesh in a buffer of slot_count() entries
/// never has to move anything.
///
/// Applying a delta to a copy of the mesh (a GPU buffer, a solver's arrays): drop the removed
/// simplices, drop the removed vertices, write the added vertices (id, coordinates), then the
/// added simplices (id, vertex ids). Afterwards the copy equals the LiveMesh slot for slot.
///
/// The LiveMesh holds the same simplices as the mesher's canonical mesh() (same vertex
/// coordinates, same oriented simplices), in slot order instead of canonical order; the
/// meshers' check_invariants() and the tests compare the two as sets.

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <unordered_map>
#include <vector>

#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh {

/// What one insert or erase changed in the LiveMesh (see the file comment for the order in
/// which to apply it). Empty after construction or build().
template <int D>
struct MeshDelta {
    using Simplex = std::array<std::uint32_t, D + 1>;
    struct AddedVertex {
        std::uint32_t id = 0;
        PointD<D> point{};
    };
    struct AddedSimplex {
        std::uint32_t id = 0;
        Simplex vertices{};  // positively oriented (counter-clockwise in 2D)
    };
    std::vector<std::uint32_t> removed_simplices;  // ids that no longer exist
    std::vector<std::uint32_t> removed_vertices;
    std::vector<AddedVertex> added_vertices;
    std::vector<AddedSimplex> added_simplices;

    void clear() {
        removed_simplices.clear();
        removed_vertices.clear();
        added_vertices.clear();
        added_simplices.clear();
    }
    [[nodiscard]] bool empty() const {
        return removed_simplices.empty() && removed_vertices.empty() && added_vertices.empty() &&
               added_simplices.empty();
    }
};

/// The current mesh of a dynamic mesher, with stable ids (see the file comment). The meshers
/// own it and change it only through the mutators below, each of which records itself in the
/// delta it is given; callers read it through a const reference.
template <int D>
class LiveMesh {
public:
    using Point = PointD<D>;
    using Simplex = std::array<std::uint32_t, D + 1>;
    static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

    /// Number of vertex / simplex slots (ids are below these); dead slots included.
    [[nodiscard]] std::size_t vertex_slots() const { return points_.size(); }
    [[nodiscard]] std::size_t simplex_slots() const { return simplices_.size(); }
    /// Live vertices / simplices.
    [[nodiscard]] std::size_t vertex_count() const { return vertex_count_; }
    [[nodiscard]] std::size_t simplex_count() const { return simplex_count_; }
    [[nodiscard]] bool has_vertex(std::uint32_t v) const {
        return v < vertex_alive_.size() && vertex_alive_[v];
    }
    [[nodiscard]] bool has_simplex(std::uint32_t s) const {
        return s < simplices_.size() && simplices_[s][0] != kNone;
    }
    /// Coordinates of a vertex (stale for a dead slot).
    [[nodiscard]] const Point& point(std::uint32_t v) const { return points_[v]; }
    /// Vertex ids of a simplex, positively oriented (all kNone for a dead slot).
    [[nodiscard]] const Simplex& simplex(std::uint32_t s) const { return simplices_[s]; }

    // ---- mutators (used by the meshers) ------------------------------------------------------
    /// A new vertex; its id is recorded in `delta`.
    std::uint32_t add_vertex(const Point& p, MeshDelta<D>& delta);
    void remove_vertex(std::uint32_t v, MeshDelta<D>& delta);
    /// New simplices with consecutive ids; returns the first id.
    std::uint32_t add_simplices(std::span<const Simplex> simplices, MeshDelta<D>& delta);
    /// Removes the block [first, first + count) added by one add_simplices() call.
    void remove_simplices(std::uint32_t first, std::uint32_t count, MeshDelta<D>& delta);
    /// End of an update: the ids removed by it become reusable.
    void recycle();
    /// Everything removed, no delta recorded (before a rebuild of the whole mesh).
    void reset();

private:
    std::vector<Point> points_;
    std::vector<char> vertex_alive_;
    std::vector<Simplex> simplices_;
    std::size_t vertex_count_ = 0, simplex_count_ = 0;
    std::vector<std::uint32_t> free_vertices_, dead_vertices_;
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> free_blocks_;  // size -> firsts
    std::vector<std::pair<std::uint32_t, std::uint32_t>> dead_blocks_;          // (first, size)
};

extern template class LiveMesh<2>;
extern template class LiveMesh<3>;

}  // namespace dynmesh
