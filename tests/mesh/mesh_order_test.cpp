#include "dynmesh/mesh/mesh_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "dynmesh/error.hpp"
#include "dynmesh/mesh/check.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

bool is_permutation_of_range(std::vector<std::uint32_t> p, std::size_t n) {
    if (p.size() != n) return false;
    std::sort(p.begin(), p.end());
    for (std::size_t i = 0; i < n; ++i)
        if (p[i] != i) return false;
    return true;
}

TEST(MeshOrder, PermuteAndInverseRestoreTheMeshBitForBit) {
    const SurfaceMesh original = test::icosphere(3);
    SurfaceMesh m = original;
    auto prop = m.add_vertex_property<int>("v:tag");
    for (Vertex v : m.vertices()) prop[v] = static_cast<int>(v.idx());
    const SurfaceMesh tagged = m;
    const MeshOrder order = spatial_mesh_order(m);
    ASSERT_TRUE(is_permutation_of_range(order.vertices, m.vertices_size()));
    ASSERT_TRUE(is_permutation_of_range(order.edges, m.edges_size()));
    ASSERT_TRUE(is_permutation_of_range(order.faces, m.faces_size()));
    permute(m, order);
    // Renumbered, but the same closed surface: vertex i sits where vertex order[i] was, and
    // the property moved with it.
    EXPECT_FALSE(test::mesh_difference(m, original).empty());
    const auto chk = check_mesh(m, {.require_closed = true});
    EXPECT_TRUE(chk.ok()) << chk.summary();
    EXPECT_EQ(chk.integer("euler"), 2);
    auto moved = m.get_vertex_property<int>("v:tag");
    for (std::uint32_t i = 0; i < m.vertices_size(); ++i) {
        EXPECT_EQ(m.position(Vertex(i)), original.position(Vertex(order.vertices[i])));
        EXPECT_EQ(moved[Vertex(i)], static_cast<int>(order.vertices[i]));
    }
    // Faces keep their corners (renamed) and their orientation.
    for (std::uint32_t i = 0; i < m.faces_size(); ++i) {
        const auto now = m.face_vertices(Face(i));
        const auto was = original.face_vertices(Face(order.faces[i]));
        for (int k = 0; k < 3; ++k) EXPECT_EQ(order.vertices[now[k].idx()], was[k].idx());
    }
    permute(m, inverse(order));
    EXPECT_EQ(test::mesh_difference(m, tagged), "");
    auto back = m.get_vertex_property<int>("v:tag");
    for (Vertex v : m.vertices()) EXPECT_EQ(back[v], static_cast<int>(v.idx()));
}

TEST(MeshOrder, SpatialOrderGathersAShuffledNumbering) {
    const SurfaceMesh m = test::shuffled(test::icosphere(5), 7);
    const double before = scattered_edge_fraction(m, 256);
    SurfaceMesh sorted = m;
    permute(sorted, spatial_mesh_order(sorted));
    const double after = scattered_edge_fraction(sorted, 256);
    EXPECT_GT(before, 0.9);  // 10242 vertices numbered at random
    EXPECT_LT(after, 0.15) << "before " << before;
    // Edges and faces follow their smallest vertex index.
    auto smallest = [&](Face f) {
        const auto c = sorted.face_vertices(f);
        return std::min({c[0].idx(), c[1].idx(), c[2].idx()});
    };
    for (std::uint32_t i = 1; i < sorted.faces_size(); ++i) EXPECT_LE(smallest(Face(i - 1)), smallest(Face(i)));
    auto lo = [&](Edge e) { return std::min(sorted.vertex(e, 0).idx(), sorted.vertex(e, 1).idx()); };
    for (std::uint32_t i = 1; i < sorted.edges_size(); ++i) EXPECT_LE(lo(Edge(i - 1)), lo(Edge(i)));
}

TEST(MeshOrder, PermuteRejectsWhatIsNotAPermutation) {
    SurfaceMesh m = test::octahedron();
    std::vector<std::uint32_t> v(m.vertices_size()), e(m.edges_size()), f(m.faces_size());
    std::iota(v.begin(), v.end(), 0u);
    std::iota(e.begin(), e.end(), 0u);
    std::iota(f.begin(), f.end(), 0u);
    const SurfaceMesh copy = m;
    auto bad = v;
    bad[1] = 0;  // 0 twice
    EXPECT_THROW(m.permute(bad, e, f), InvalidInput);
    EXPECT_THROW(m.permute(v, std::vector<std::uint32_t>(e.begin(), e.end() - 1), f), InvalidInput);
    auto out_of_range = f;
    out_of_range[0] = 99;
    EXPECT_THROW(m.permute(v, e, out_of_range), InvalidInput);
    EXPECT_EQ(test::mesh_difference(m, copy), "");
    m.permute(v, e, f);  // the identity
    EXPECT_EQ(test::mesh_difference(m, copy), "");
}

TEST(MeshOrder, ScatteredEdgeFractionCountsLongIndexGaps) {
    // Row-major 21 x 21 vertices: 420 horizontal edges (index gap 1), 420 vertical (gap 21)
    // and 400 diagonal (gap 22).
    const SurfaceMesh g = test::grid(20);
    EXPECT_EQ(scattered_edge_fraction(g, 22), 0.0);
    EXPECT_NEAR(scattered_edge_fraction(g, 21), 400.0 / 1240.0, 1e-12);
    EXPECT_NEAR(scattered_edge_fraction(g, 20), 820.0 / 1240.0, 1e-12);
    EXPECT_NEAR(scattered_edge_fraction(g, 0), 1.0, 1e-12);
    EXPECT_EQ(scattered_edge_fraction(SurfaceMesh(), 1), 0.0);
}

}  // namespace
}  // namespace dynmesh
