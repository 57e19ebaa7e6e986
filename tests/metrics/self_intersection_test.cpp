#include "dynmesh/metrics/self_intersection.hpp"

#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

/// Icosphere with vertex 0 pushed through the centre to the opposite side.
SurfaceMesh pierced_icosphere(int level) {
    SurfaceMesh mesh = test::icosphere(level);
    mesh.position(Vertex(0)) = mesh.position(Vertex(0)) * -1.3;
    return mesh;
}

bool share_vertex(const SurfaceMesh& mesh, Face f, Face g) {
    const auto a = mesh.face_vertices(f), b = mesh.face_vertices(g);
    for (Vertex u : a)
        for (Vertex v : b)
            if (u == v) return true;
    return false;
}

TEST(SelfIntersection, EmbeddedMeshesHaveNone) {
    for (const SurfaceMesh& mesh :
         {test::icosphere(0), test::icosphere(3), test::octahedron(), test::grid(6)}) {
        EXPECT_EQ(count_self_intersections(mesh), 0u);
        EXPECT_FALSE(has_self_intersections(mesh));
        EXPECT_TRUE(self_intersections(mesh).empty());
    }
    EXPECT_EQ(count_self_intersections(SurfaceMesh()), 0u);
}

TEST(SelfIntersection, PushedThroughVertexIntersects) {
    const SurfaceMesh mesh = pierced_icosphere(2);
    const std::size_t n = count_self_intersections(mesh);
    EXPECT_GT(n, 0u);
    EXPECT_TRUE(has_self_intersections(mesh));
    const auto pairs = self_intersections(mesh);
    EXPECT_EQ(pairs.size(), n);
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    for (const auto& [f, g] : pairs) {
        EXPECT_TRUE(mesh.is_valid(f) && mesh.is_valid(g));
        EXPECT_NE(f, g);
        // The moved vertex's star cuts through faces on the far side.
        EXPECT_FALSE(share_vertex(mesh, f, g));
        EXPECT_TRUE(seen.insert(std::minmax(f.idx(), g.idx())).second) << "pair listed twice";
    }
}

TEST(SelfIntersection, AFaceRangeIsTestedWithinItself) {
    const SurfaceMesh mesh = pierced_icosphere(2);
    const auto pairs = self_intersections(mesh);
    ASSERT_FALSE(pairs.empty());
    const auto [f, g] = pairs.front();
    const std::vector<Face> both{f, g}, first{f}, second{g};
    EXPECT_TRUE(has_self_intersections(mesh, both));
    EXPECT_FALSE(has_self_intersections(mesh, first));  // a pair needs both its faces
    EXPECT_FALSE(has_self_intersections(mesh, second));
    // Every face that meets no other: none of them intersects.
    std::set<std::uint32_t> touched;
    for (const auto& [a, b] : pairs) {
        touched.insert(a.idx());
        touched.insert(b.idx());
    }
    std::vector<Face> clean;
    for (Face x : mesh.faces())
        if (!touched.count(x.idx())) clean.push_back(x);
    EXPECT_FALSE(has_self_intersections(mesh, clean));
    clean.push_back(f);
    clean.push_back(g);
    EXPECT_TRUE(has_self_intersections(mesh, clean));
    EXPECT_FALSE(has_self_intersections(mesh, std::vector<Face>{}));
    EXPECT_THROW((void)has_self_intersections(mesh, std::vector<Face>{Face(100000)}), InvalidInput);
}

TEST(SelfIntersection, MaxPairsLimitsTheList) {
    const SurfaceMesh mesh = pierced_icosphere(3);
    const std::size_t n = count_self_intersections(mesh);
    ASSERT_GT(n, 3u);
    EXPECT_EQ(self_intersections(mesh, 3).size(), 3u);
    EXPECT_EQ(self_intersections(mesh, 1).size(), 1u);
    EXPECT_TRUE(self_intersections(mesh, 0).empty());
    EXPECT_EQ(self_intersections(mesh, n + 10).size(), n);
}

TEST(SelfIntersection, FoldedOverCoplanarPairIntersects) {
    // Two triangles sharing edge 0-1, the second folded flat onto the first: they overlap.
    TriangleSoup soup;
    soup.points = {{0, 0, 0}, {2, 0, 0}, {1, 2, 0}, {1, 1, 0}};
    soup.triangles = {{0, 1, 2}, {1, 0, 3}};
    EXPECT_EQ(count_self_intersections(SurfaceMesh::from_soup(soup)), 1u);
    // Unfolded (the apex on the other side), they only share the edge.
    soup.points[3] = {1, -1, 0};
    EXPECT_EQ(count_self_intersections(SurfaceMesh::from_soup(soup)), 0u);
}

TEST(SelfIntersection, DegenerateFaceIsReportedWithItself) {
    TriangleSoup soup;
    soup.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 1, 0}};
    soup.triangles = {{0, 1, 3}, {1, 2, 3}, {0, 2, 1}};  // the last one is collinear
    const SurfaceMesh mesh = SurfaceMesh::from_soup(soup);
    const auto pairs = self_intersections(mesh);
    ASSERT_EQ(pairs.size(), 1u);
    EXPECT_EQ(pairs[0].first, Face(2));
    EXPECT_EQ(pairs[0].second, Face(2));
    EXPECT_EQ(count_self_intersections(mesh), 1u);
}

TEST(SelfIntersection, ReportsLiveFacesOfAMeshWithGarbage) {
    SurfaceMesh mesh = pierced_icosphere(2);
    // Collapse an edge far from the pierced vertex 0 (its antipode is near (-1.3) * p0).
    const Point3 p0 = mesh.position(Vertex(0));
    for (const Edge e : mesh.edges()) {
        const Halfedge h = SurfaceMesh::halfedge(e, 0);
        if (dot(mesh.position(mesh.from_vertex(h)), p0) > -0.2) continue;
        if (!mesh.is_collapse_ok(h)) continue;
        const Vertex gone = mesh.from_vertex(h);
        bool near_star = false;
        for (const Vertex n : mesh.neighbors(gone)) near_star |= n == Vertex(0);
        if (near_star || gone == Vertex(0)) continue;
        mesh.collapse(h);
        break;
    }
    ASSERT_TRUE(mesh.has_garbage());
    const auto pairs = self_intersections(mesh);
    EXPECT_GT(pairs.size(), 0u);
    EXPECT_EQ(pairs.size(), count_self_intersections(mesh));
    auto has_v0 = [&](Face f) {
        const auto vs = mesh.face_vertices(f);
        return vs[0] == Vertex(0) || vs[1] == Vertex(0) || vs[2] == Vertex(0);
    };
    for (const auto& [f, g] : pairs) {
        EXPECT_FALSE(mesh.is_deleted(f));
        EXPECT_FALSE(mesh.is_deleted(g));
        EXPECT_TRUE(has_v0(f) || has_v0(g));  // only the moved vertex's star is misplaced
    }
}

TEST(SelfIntersection, AnyFaceRangeAgreesWithTheWholeMeshPairs) {
    // A range is copied alone: faces that share an edge or a vertex in the mesh must share it
    // in the copy, or they would be taken for intersecting. Random ranges, from scattered
    // faces (no shared edge) to whole neighbourhoods, on an embedded and a pierced mesh: the
    // range intersects itself exactly when one of the mesh's pairs lies in it.
    std::size_t hits = 0, misses = 0;
    for (const SurfaceMesh& mesh : {test::icosphere(3), pierced_icosphere(2)}) {
        const auto pairs = self_intersections(mesh);
        Rng rng(11);
        for (int trial = 0; trial < 60; ++trial) {
            const double keep = trial % 3 == 0 ? 0.2 : trial % 3 == 1 ? 0.6 : 0.95;
            std::vector<char> in(mesh.faces_size(), 0);
            std::vector<Face> range;
            for (Face f : mesh.faces())
                if (rng.uniform() < keep) {
                    in[f.idx()] = 1;
                    range.push_back(f);
                }
            bool expected = false;
            for (const auto& [f, g] : pairs) expected = expected || (in[f.idx()] && in[g.idx()]);
            EXPECT_EQ(has_self_intersections(mesh, range), expected) << "trial " << trial;
            (expected ? hits : misses) += 1;
        }
    }
    EXPECT_GT(hits, 10u);
    EXPECT_GT(misses, 10u);
}

}  // namespace
}  // namespace dynmesh
