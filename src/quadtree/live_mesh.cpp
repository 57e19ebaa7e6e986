#include "dynmesh/quadtree/live_mesh.hpp"

#include "dynmesh/error.hpp"

namespace dynmesh {

template <int D>
std::uint32_t LiveMesh<D>::add_vertex(const Point& p, MeshDelta<D>& delta) {
    std::uint32_t v;
    if (!free_vertices_.empty()) {
        v = free_vertices_.back();
        free_vertices_.pop_back();
        points_[v] = p;
        vertex_alive_[v] = 1;
    } else {
        v = static_cast<std::uint32_t>(points_.size());
        if (v == kNone) throw InternalError("LiveMesh: too many vertices");
        points_.push_back(p);
        vertex_alive_.push_back(1);
    }
    ++vertex_count_;
    delta.added_vertices.push_back({v, p});
    return v;
}

template <int D>
void LiveMesh<D>::remove_vertex(std::uint32_t v, MeshDelta<D>& delta) {
    DYNMESH_ASSERT(has_vertex(v), "LiveMesh: removing a dead vertex");
    vertex_alive_[v] = 0;
    --vertex_count_;
    dead_vertices_.push_back(v);
    delta.removed_vertices.push_back(v);
}

template <int D>
std::uint32_t LiveMesh<D>::add_simplices(std::span<const Simplex> simplices,
                                         MeshDelta<D>& delta) {
    const auto count = static_cast<std::uint32_t>(simplices.size());
    if (count == 0) return static_cast<std::uint32_t>(simplices_.size());
    std::uint32_t first;
    auto& reusable = free_blocks_[count];
    if (!reusable.empty()) {
        first = reusable.back();
        reusable.pop_back();
    } else {
        if (simplices_.size() + count >= kNone) throw InternalError("LiveMesh: too many simplices");
        first = static_cast<std::uint32_t>(simplices_.size());
        simplices_.resize(simplices_.size() + count);
    }
    for (std::uint32_t k = 0; k < count; ++k) {
        simplices_[first + k] = simplices[k];
        delta.added_simplices.push_back({first + k, simplices[k]});
    }
    simplex_count_ += count;
    return first;
}

template <int D>
void LiveMesh<D>::remove_simplices(std::uint32_t first, std::uint32_t count, MeshDelta<D>& delta) {
    if (count == 0) return;
    for (std::uint32_t k = 0; k < count; ++k) {
        DYNMESH_ASSERT(has_simplex(first + k), "LiveMesh: removing a dead simplex");
        simplices_[first + k].fill(kNone);
        delta.removed_simplices.push_back(first + k);
    }
    simplex_count_ -= count;
    dead_blocks_.emplace_back(first, count);
}

template <int D>
void LiveMesh<D>::recycle() {
    free_vertices_.insert(free_vertices_.end(), dead_vertices_.begin(), dead_vertices_.end());
    dead_vertices_.clear();
    for (const auto& [first, count] : dead_blocks_) free_blocks_[count].push_back(first);
    dead_blocks_.clear();
}

template <int D>
void LiveMesh<D>::reset() { *this = LiveMesh{}; }

template class LiveMesh<2>;
template class LiveMesh<3>;

}  // namespace dynmesh
