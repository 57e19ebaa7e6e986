#include "dynmesh/mesh/mesh_order.hpp"

#include <algorithm>
#include <numeric>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/spatial_sort.hpp"

namespace dynmesh {

MeshOrder spatial_mesh_order(const SurfaceMesh& mesh) {
    DYNMESH_CHECK(!mesh.has_garbage(), "spatial_mesh_order: the mesh has deleted elements");
    MeshOrder o;
    o.vertices = spatial_order(mesh.positions());
    const std::size_t n = o.vertices.size();
    std::vector<std::uint32_t> rank(n);
    for (std::uint32_t i = 0; i < n; ++i) rank[o.vertices[i]] = i;
    // Every edge and face is keyed by the smallest rank of its vertices, in one sequential
    // pass over the halfedges; then a counting sort by key (stable: ties keep index order).
    std::vector<std::uint32_t> edge_key(mesh.edges_size(), UINT32_MAX), face_key(mesh.faces_size(), UINT32_MAX);
    for (std::uint32_t h = 0; h < mesh.halfedges_size(); ++h) {
        const std::uint32_t r = rank[mesh.to_vertex(Halfedge(h)).idx()];
        std::uint32_t& ek = edge_key[h >> 1];
        ek = std::min(ek, r);
        const Face f = mesh.face(Halfedge(h));
        if (f.is_valid()) face_key[f.idx()] = std::min(face_key[f.idx()], r);
    }
    auto by_key = [n](const std::vector<std::uint32_t>& key) {
        std::vector<std::uint32_t> start(n + 1, 0), out(key.size());
        for (std::uint32_t k : key) ++start[k + 1];
        for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
        for (std::uint32_t i = 0; i < key.size(); ++i) out[start[key[i]]++] = i;
        return out;
    };
    o.edges = by_key(edge_key);
    o.faces = by_key(face_key);
    return o;
}

MeshOrder random_mesh_order(const SurfaceMesh& mesh, std::uint64_t seed) {
    DYNMESH_CHECK(!mesh.has_garbage(), "random_mesh_order: the mesh has deleted elements");
    Rng rng(seed);
    auto random_order = [&rng](std::size_t n) {
        std::vector<std::uint32_t> p(n);
        std::iota(p.begin(), p.end(), 0u);
        for (std::size_t i = n; i > 1; --i) std::swap(p[i - 1], p[rng.below(i)]);
        return p;
    };
    MeshOrder o;
    o.vertices = random_order(mesh.vertices_size());
    o.edges = random_order(mesh.edges_size());
    o.faces = random_order(mesh.faces_size());
    return o;
}

MeshOrder inverse(const MeshOrder& order) {
    auto inv = [](const std::vector<std::uint32_t>& p) {
        std::vector<std::uint32_t> q(p.size());
        for (std::uint32_t i = 0; i < p.size(); ++i) q[p[i]] = i;
        return q;
    };
    return {inv(order.vertices), inv(order.edges), inv(order.faces)};
}

void permute(SurfaceMesh& mesh, const MeshOrder& order) {
    mesh.permute(order.vertices, order.edges, order.faces);
}

double scattered_edge_fraction(const SurfaceMesh& mesh, std::uint32_t max_gap, std::size_t samples) {
    const std::size_t n = mesh.edges_size();
    const std::size_t stride = std::max<std::size_t>(1, n / std::max<std::size_t>(samples, 1));
    std::size_t tested = 0, far = 0;
    for (std::size_t i = 0; i < n; i += stride) {
        const Edge e(static_cast<std::uint32_t>(i));
        if (mesh.is_deleted(e)) continue;
        const std::uint32_t a = mesh.vertex(e, 0).idx(), b = mesh.vertex(e, 1).idx();
        ++tested;
        far += (a > b ? a - b : b - a) > max_gap;
    }
    return tested ? double(far) / double(tested) : 0.0;
}

}  // namespace dynmesh
