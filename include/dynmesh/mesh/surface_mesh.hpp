#pragma once
/// \file SurfaceMesh: an index-based halfedge mesh of triangles with typed handles and
/// mesh-owned properties (after pmp-library's design).
///
/// Conventions
/// - Halfedges come in pairs: the twin of halfedge i is i ^ 1 and its edge is i / 2.
/// - Every face is a triangle; its three halfedges run counter-clockwise seen from outside.
/// - A halfedge without a face is a boundary halfedge; boundary halfedges are linked by
///   `next` into loops, so circulating around a boundary vertex works. A boundary vertex's
///   `halfedge()` is its outgoing boundary halfedge.
/// - Removed elements are only marked; `garbage_collection()` compacts the arrays and
///   invalidates handles (but not `Property` objects).
/// - Local operations that could break the manifold have a `is_*_ok()` test; the operation
///   itself assumes it (checked in debug builds).

#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/handles.hpp"
#include "dynmesh/mesh/properties.hpp"
#include "dynmesh/mesh/soup.hpp"

namespace dynmesh {

template <class T>
using VertexProperty = Property<Vertex, T>;
template <class T>
using HalfedgeProperty = Property<Halfedge, T>;
template <class T>
using EdgeProperty = Property<Edge, T>;
template <class T>
using FaceProperty = Property<Face, T>;

class SurfaceMesh;

/// How SurfaceMesh::from_soup works (never what it builds: the mesh is the same for every
/// setting).
struct FromSoupOptions {
    /// Threads: 0 lets the machine decide (one per hardware thread, at most 8, each with at
    /// least 2^17 triangles; one for a smaller soup), k uses k (at most 64, and at most one per
    /// triangle), 1 keeps to the calling thread.
    unsigned threads = 0;
};

/// Iterates the live (non-deleted) elements of one kind.
template <class HandleT>
class ElementRange {
public:
    class Iterator {
    public:
        using iterator_category = std::forward_iterator_tag;
        using value_type = HandleT;
        using difference_type = std::ptrdiff_t;
        using pointer = const HandleT*;
        using reference = HandleT;
        Iterator() = default;
        Iterator(std::uint32_t i, std::uint32_t end, const std::vector<bool>* deleted)
            : i_(i), end_(end), deleted_(deleted) {
            skip();
        }
        HandleT operator*() const { return HandleT(i_); }
        Iterator& operator++() {
            ++i_;
            skip();
            return *this;
        }
        Iterator operator++(int) {
            Iterator t = *this;
            ++*this;
            return t;
        }
        bool operator==(const Iterator& o) const { return i_ == o.i_; }

    private:
        void skip() {
            while (i_ < end_ && deleted_ != nullptr && (*deleted_)[i_]) ++i_;
        }
        std::uint32_t i_ = 0, end_ = 0;
        const std::vector<bool>* deleted_ = nullptr;
    };
    ElementRange(std::uint32_t end, const std::vector<bool>* deleted)
        : end_(end), deleted_(deleted) {}
    [[nodiscard]] Iterator begin() const { return Iterator(0, end_, deleted_); }
    [[nodiscard]] Iterator end() const { return Iterator(end_, end_, deleted_); }

private:
    std::uint32_t end_;
    const std::vector<bool>* deleted_;
};

/// Outgoing halfedges of a vertex, in counter-clockwise order (seen from outside).
class VertexHalfedgeRange {
public:
    class Iterator {
    public:
        using iterator_category = std::forward_iterator_tag;
        using value_type = Halfedge;
        using difference_type = std::ptrdiff_t;
        using pointer = const Halfedge*;
        using reference = Halfedge;
        Iterator() = default;
        Iterator(const SurfaceMesh* m, Halfedge start, bool at_end)
            : mesh_(m), start_(start), h_(start), active_(!at_end && start.is_valid()) {}
        Halfedge operator*() const { return h_; }
        Iterator& operator++();
        Iterator operator++(int) {
            Iterator t = *this;
            ++*this;
            return t;
        }
        bool operator==(const Iterator& o) const {
            return active_ == o.active_ && (!active_ || h_ == o.h_);
        }

    private:
        const SurfaceMesh* mesh_ = nullptr;
        Halfedge start_, h_;
        bool active_ = false;
    };
    VertexHalfedgeRange(const SurfaceMesh* m, Halfedge start) : mesh_(m), start_(start) {}
    [[nodiscard]] Iterator begin() const { return Iterator(mesh_, start_, false); }
    [[nodiscard]] Iterator end() const { return Iterator(mesh_, start_, true); }

private:
    const SurfaceMesh* mesh_;
    Halfedge start_;
};

class SurfaceMesh {
public:
    SurfaceMesh() = default;

    /// Builds a mesh from a triangle soup.
    /// \throw InvalidInput for an index out of range, a repeated index in a triangle, or a
    ///        non-finite coordinate; TopologyError for an edge with more than two triangles,
    ///        an edge used twice in the same direction (inconsistent orientation), or a
    ///        non-manifold (pinched) vertex. Each message names the triangle or vertex.
    ///        Unreferenced vertices are kept (isolated) and reported by check_mesh().
    static SurfaceMesh from_soup(const TriangleSoup& soup, const FromSoupOptions& options = {});
    /// As above, taking the soup's points over instead of copying them (a soup it refuses keeps
    /// them).
    static SurfaceMesh from_soup(TriangleSoup&& soup, const FromSoupOptions& options = {});
    /// The inverse of from_soup (live elements only, in index order after compaction).
    [[nodiscard]] TriangleSoup to_soup() const;

    // ---- sizes (live elements) -----------------------------------------------------------
    [[nodiscard]] std::size_t n_vertices() const { return vdeleted_.size() - n_deleted_vertices_; }
    [[nodiscard]] std::size_t n_edges() const { return edeleted_.size() - n_deleted_edges_; }
    [[nodiscard]] std::size_t n_halfedges() const { return 2 * n_edges(); }
    [[nodiscard]] std::size_t n_faces() const { return fdeleted_.size() - n_deleted_faces_; }
    /// Array sizes including deleted elements (valid index bound).
    [[nodiscard]] std::size_t vertices_size() const { return vdeleted_.size(); }
    [[nodiscard]] std::size_t edges_size() const { return edeleted_.size(); }
    [[nodiscard]] std::size_t halfedges_size() const { return 2 * edeleted_.size(); }
    [[nodiscard]] std::size_t faces_size() const { return fdeleted_.size(); }
    [[nodiscard]] bool has_garbage() const {
        return n_deleted_vertices_ + n_deleted_edges_ + n_deleted_faces_ > 0;
    }
    [[nodiscard]] bool is_empty() const { return n_vertices() == 0; }

    // ---- element ranges ------------------------------------------------------------------
    [[nodiscard]] ElementRange<Vertex> vertices() const {
        return {static_cast<std::uint32_t>(vdeleted_.size()), &vdeleted_};
    }
    [[nodiscard]] ElementRange<Edge> edges() const {
        return {static_cast<std::uint32_t>(edeleted_.size()), &edeleted_};
    }
    [[nodiscard]] ElementRange<Face> faces() const {
        return {static_cast<std::uint32_t>(fdeleted_.size()), &fdeleted_};
    }
    /// Outgoing halfedges of v, counter-clockwise; starts at the boundary one if any.
    [[nodiscard]] VertexHalfedgeRange outgoing_halfedges(Vertex v) const {
        return {this, halfedge(v)};
    }

    // ---- connectivity --------------------------------------------------------------------
    [[nodiscard]] Vertex to_vertex(Halfedge h) const { return Vertex(hto_[h.idx()]); }
    [[nodiscard]] Vertex from_vertex(Halfedge h) const { return to_vertex(twin(h)); }
    [[nodiscard]] Halfedge next(Halfedge h) const { return Halfedge(hnext_[h.idx()]); }
    [[nodiscard]] Halfedge prev(Halfedge h) const { return Halfedge(hprev_[h.idx()]); }
    [[nodiscard]] static Halfedge twin(Halfedge h) { return Halfedge(h.idx() ^ 1u); }
    [[nodiscard]] Face face(Halfedge h) const { return Face(hface_[h.idx()]); }
    [[nodiscard]] static Edge edge(Halfedge h) { return Edge(h.idx() >> 1); }
    [[nodiscard]] static Halfedge halfedge(Edge e, int i) { return Halfedge((e.idx() << 1) + i); }
    [[nodiscard]] Vertex vertex(Edge e, int i) const { return to_vertex(halfedge(e, 1 - i)); }
    [[nodiscard]] Halfedge halfedge(Vertex v) const { return Halfedge(vhalfedge_[v.idx()]); }
    [[nodiscard]] Halfedge halfedge(Face f) const { return Halfedge(fhalfedge_[f.idx()]); }
    /// Next outgoing halfedge counter-clockwise around from_vertex(h).
    [[nodiscard]] Halfedge ccw_rotated(Halfedge h) const { return twin(prev(h)); }
    /// Next outgoing halfedge clockwise around from_vertex(h).
    [[nodiscard]] Halfedge cw_rotated(Halfedge h) const { return next(twin(h)); }

    [[nodiscard]] bool is_boundary(Halfedge h) const { return !face(h).is_valid(); }
    [[nodiscard]] bool is_boundary(Edge e) const {
        return is_boundary(halfedge(e, 0)) || is_boundary(halfedge(e, 1));
    }
    [[nodiscard]] bool is_boundary(Vertex v) const {
        const Halfedge h = halfedge(v);
        return !h.is_valid() || is_boundary(h);
    }
    [[nodiscard]] bool is_isolated(Vertex v) const { return !halfedge(v).is_valid(); }
    [[nodiscard]] bool is_deleted(Vertex v) const { return vdeleted_[v.idx()]; }
    [[nodiscard]] bool is_deleted(Edge e) const { return edeleted_[e.idx()]; }
    [[nodiscard]] bool is_deleted(Halfedge h) const { return edeleted_[h.idx() >> 1]; }
    [[nodiscard]] bool is_deleted(Face f) const { return fdeleted_[f.idx()]; }
    /// True when the element is usable: in range and not deleted (a deleted element stays
    /// in range until garbage_collection()).
    [[nodiscard]] bool is_valid(Vertex v) const { return v.idx() < vdeleted_.size() && !vdeleted_[v.idx()]; }
    [[nodiscard]] bool is_valid(Edge e) const { return e.idx() < edeleted_.size() && !edeleted_[e.idx()]; }
    [[nodiscard]] bool is_valid(Halfedge h) const {
        return (h.idx() >> 1) < edeleted_.size() && !edeleted_[h.idx() >> 1];
    }
    [[nodiscard]] bool is_valid(Face f) const { return f.idx() < fdeleted_.size() && !fdeleted_[f.idx()]; }
    [[nodiscard]] bool is_closed() const;

    [[nodiscard]] std::size_t valence(Vertex v) const;
    /// The halfedge from a to b, or an invalid handle.
    [[nodiscard]] Halfedge find_halfedge(Vertex a, Vertex b) const;
    [[nodiscard]] Edge find_edge(Vertex a, Vertex b) const {
        const Halfedge h = find_halfedge(a, b);
        return h.is_valid() ? edge(h) : Edge();
    }
    /// The three corners of f in counter-clockwise order, starting at to_vertex(halfedge(f)).
    [[nodiscard]] std::array<Vertex, 3> face_vertices(Face f) const {
        const Halfedge h = halfedge(f), n = next(h);
        return {to_vertex(h), to_vertex(n), to_vertex(next(n))};
    }
    /// The link of v: its neighbours in counter-clockwise order.
    [[nodiscard]] std::vector<Vertex> neighbors(Vertex v) const;
    /// The vertex opposite halfedge h in its face (invalid for a boundary halfedge).
    [[nodiscard]] Vertex opposite_vertex(Halfedge h) const {
        return is_boundary(h) ? Vertex() : to_vertex(next(h));
    }

    // ---- geometry ------------------------------------------------------------------------
    [[nodiscard]] const Point3& position(Vertex v) const { return positions_[v.idx()]; }
    Point3& position(Vertex v) { return positions_[v.idx()]; }
    [[nodiscard]] const std::vector<Point3>& positions() const { return positions_; }
    std::vector<Point3>& positions() { return positions_; }

    // ---- construction and local operations -----------------------------------------------
    /// Adds an isolated vertex.
    Vertex add_vertex(const Point3& p);
    /// Deletes an isolated vertex (one no edge uses). \throw InvalidInput otherwise.
    void remove_isolated_vertex(Vertex v);

    /// True when e is interior, its two opposite vertices differ, and the other diagonal
    /// is not already an edge (a flip would otherwise create a duplicate edge).
    [[nodiscard]] bool is_flip_ok(Edge e) const;
    /// Replaces edge e (between triangles pqr and qps) by the other diagonal rs; the new
    /// triangles are (p, s, r) and (q, r, s), orientation kept. e keeps its index and the
    /// two faces keep theirs; every other handle stays valid. No vertex moves.
    /// \pre is_flip_ok(e) (checked in debug builds).
    void flip(Edge e);

    /// Splits face f 1-to-3 at a new vertex at p; returns the new vertex.
    Vertex split_face(Face f, const Point3& p);
    /// Splits edge e at a new vertex at p: each incident triangle becomes two. Returns the
    /// new vertex, whose halfedge() points to the split part towards the old to_vertex of
    /// halfedge(e, 0).
    Vertex split_edge(Edge e, const Point3& p);

    /// True when collapsing h (moving from_vertex(h) onto to_vertex(h)) keeps the mesh a
    /// manifold: the link condition holds, the two opposite vertices keep valence >= 3, and
    /// a closed mesh keeps at least four vertices.
    [[nodiscard]] bool is_collapse_ok(Halfedge h) const;
    /// Removes from_vertex(h), merging it into to_vertex(h) (which keeps its position).
    /// \pre is_collapse_ok(h) (checked in debug builds).
    void collapse(Halfedge h);

    /// Replaces the triangles `remove` of a closed mesh by `add` (vertex triples, oriented like
    /// the mesh), keeping it closed: every edge between a removed and a kept triangle must be
    /// used once by an added triangle in the direction the removed one used, and every other
    /// edge of the added triangles twice, in opposite directions. Edges between two removed
    /// triangles are deleted, and so are vertices left with no triangle. Surgery (topology
    /// changes), new components (`remove` empty) and deleted components (`add` empty) are
    /// all this one operation. Returns the new faces, in the order of `add`.
    /// \throw InvalidInput when a handle is invalid or deleted, a triangle repeats a vertex, or
    ///        the added triangles do not close the hole as above (the mesh is then unchanged).
    std::vector<Face> replace_faces(std::span<const Face> remove,
                                    std::span<const std::array<Vertex, 3>> add);

    /// Removes interior vertex v and fills its link polygon with `triangles`, whose indices
    /// refer to `neighbors(v)` (in that counter-clockwise order). The triangles must be a
    /// triangulation of the polygon consistent with its orientation (k - 2 triangles,
    /// every polygon side once, every diagonal twice in opposite directions), and no
    /// diagonal may already be an edge of the mesh.
    /// \throw InvalidInput when these fail (the mesh is then unchanged).
    void remove_vertex(Vertex v, std::span<const std::array<std::uint32_t, 3>> triangles);
    /// Removes interior vertex v and re-triangulates its link by ear clipping in the plane
    /// through v orthogonal to its area-weighted normal, choosing ears that maximise the
    /// smallest angle and never creating an existing edge. Returns false (mesh unchanged)
    /// when v is on the boundary, its link is not a simple cycle, or no valid ear exists.
    bool remove_vertex(Vertex v);

    /// Removes deleted elements and compacts all arrays and properties. Handles held by
    /// callers are invalidated; Property objects stay valid.
    void garbage_collection();
    /// Renumbers every element: new vertex i is old vertex vertex_order[i], new edge i old
    /// edge edge_order[i] (its two halfedges keep their order), new face i old face
    /// face_order[i]. Connectivity, positions and properties move with their elements, so the
    /// mesh is the same up to numbering; permuting back with the inverse orders restores it
    /// bit for bit. Handles held by callers are invalidated.
    /// \pre no garbage. \throw InvalidInput when an order is not a permutation of its range.
    void permute(std::span<const std::uint32_t> vertex_order, std::span<const std::uint32_t> edge_order,
                 std::span<const std::uint32_t> face_order);

    // ---- face log ------------------------------------------------------------------------
    /// The face log, off until enable_face_log(): while on, every face made, relinked (a flip,
    /// a split, a vertex removal, a hole filled), deleted, or given another vertex by a
    /// collapse is appended, possibly more than once, so that a caller can keep per-face data
    /// current without a pass over the mesh. Moving a vertex is not logged. A renumbering
    /// (garbage_collection() that finds garbage, permute()) empties the log: its indices are
    /// gone, and a reader must start over.
    void enable_face_log(bool on = true) {
        face_log_on_ = on;
        if (!on) face_log_.clear();
    }
    [[nodiscard]] const std::vector<std::uint32_t>& face_log() const { return face_log_; }
    void clear_face_log() { face_log_.clear(); }

    // ---- properties ----------------------------------------------------------------------
    /// add_*_property: a new property array with `def` for every element.
    /// \throw InvalidInput if a property of that kind and name (of any type) is already there.
    /// get_*_property: the property, or an invalid one (is_valid() false) when there is none
    /// of that name and type.
    template <class T>
    VertexProperty<T> add_vertex_property(const std::string& name, T def = T()) {
        return VertexProperty<T>(vprops_.add<T>(name, std::move(def)));
    }
    template <class T>
    VertexProperty<T> get_vertex_property(const std::string& name) const {
        return VertexProperty<T>(vprops_.get<T>(name));
    }
    template <class T>
    FaceProperty<T> add_face_property(const std::string& name, T def = T()) {
        return FaceProperty<T>(fprops_.add<T>(name, std::move(def)));
    }
    template <class T>
    FaceProperty<T> get_face_property(const std::string& name) const {
        return FaceProperty<T>(fprops_.get<T>(name));
    }
    template <class T>
    EdgeProperty<T> add_edge_property(const std::string& name, T def = T()) {
        return EdgeProperty<T>(eprops_.add<T>(name, std::move(def)));
    }
    template <class T>
    EdgeProperty<T> get_edge_property(const std::string& name) const {
        return EdgeProperty<T>(eprops_.get<T>(name));
    }
    template <class H, class T>
    void remove_property(Property<H, T>& p) {
        vprops_.remove(p.array());
        eprops_.remove(p.array());
        fprops_.remove(p.array());
        p = Property<H, T>();
    }
    [[nodiscard]] std::vector<std::string> vertex_property_names() const { return vprops_.names(); }
    [[nodiscard]] std::vector<std::string> face_property_names() const { return fprops_.names(); }

    /// Reserves room for this many elements of each kind.
    void reserve(std::size_t n_vertices, std::size_t n_edges, std::size_t n_faces);

private:
    friend class VertexHalfedgeRange::Iterator;
    /// The mesh of the triangles over `points`, taken over (moved from) only once the soup is
    /// accepted.
    static SurfaceMesh build(std::vector<Point3>&& points, std::span<const std::array<std::uint32_t, 3>> triangles,
                             unsigned threads);
    Halfedge new_edge(Vertex from, Vertex to);  // returns the halfedge from -> to
    Face new_face();
    void set_next(Halfedge h, Halfedge n) {
        hnext_[h.idx()] = n.idx();
        hprev_[n.idx()] = h.idx();
    }
    void set_face(Halfedge h, Face f) { hface_[h.idx()] = f.idx(); }
    /// Makes a -> b -> c the halfedge cycle of face f (and a its halfedge).
    void link_triangle(Halfedge a, Halfedge b, Halfedge c, Face f) {
        set_next(a, b);
        set_next(b, c);
        set_next(c, a);
        for (Halfedge h : {a, b, c}) set_face(h, f);
        fhalfedge_[f.idx()] = a.idx();
        log_face(f);
    }
    void log_face(Face f) {
        if (face_log_on_) face_log_.push_back(f.idx());
    }
    void set_to(Halfedge h, Vertex v) { hto_[h.idx()] = v.idx(); }
    void set_halfedge(Vertex v, Halfedge h) { vhalfedge_[v.idx()] = h.idx(); }
    void set_halfedge(Face f, Halfedge h) { fhalfedge_[f.idx()] = h.idx(); }
    /// Makes halfedge(v) the outgoing boundary halfedge if v has one.
    void adjust_outgoing_halfedge(Vertex v);
    /// Keeps the listed elements (new index i = old index keep[i]) and drops the others:
    /// compaction (garbage_collection) or renumbering (permute).
    void reindex(std::span<const std::uint32_t> vkeep, std::span<const std::uint32_t> ekeep,
                 std::span<const std::uint32_t> fkeep);
    /// Puts `by` into the cycle (face or boundary loop) of `old`, in its place.
    void replace_in_cycle(Halfedge old, Halfedge by);
    void delete_vertex(Vertex v);
    void delete_edge(Edge e);
    void delete_face(Face f);

    std::vector<Point3> positions_;
    std::vector<std::uint32_t> vhalfedge_;
    std::vector<std::uint32_t> hto_, hnext_, hprev_, hface_;
    std::vector<std::uint32_t> fhalfedge_;
    std::vector<bool> vdeleted_, edeleted_, fdeleted_;
    std::size_t n_deleted_vertices_ = 0, n_deleted_edges_ = 0, n_deleted_faces_ = 0;
    detail::PropertyContainer vprops_, eprops_, fprops_;
    std::vector<std::uint32_t> face_log_;
    bool face_log_on_ = false;
};

inline VertexHalfedgeRange::Iterator& VertexHalfedgeRange::Iterator::operator++() {
    h_ = mesh_->ccw_rotated(h_);
    if (h_ == start_) active_ = false;
    return *this;
}

}  // namespace dynmesh
