#include "dynmesh/quadtree/quad_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "quadtree_fixtures.hpp"

#include "dynmesh/geometry/random.hpp"
#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh {
namespace {
using testing_quadtree::expect_inputs_are_vertices;
using testing_quadtree::joined;
using testing_quadtree::random_walk;


/// Uniform points in the middle third of [0, 1]^2.
std::vector<Vec2> uniform_points(std::size_t n, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < n; ++i)
        out.push_back({rng.uniform(1.0 / 3, 2.0 / 3), rng.uniform(1.0 / 3, 2.0 / 3)});
    return out;
}

/// Clusters of points with spreads from 1e-2 down to 1e-9 of the domain.
std::vector<Vec2> clustered_points(std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Vec2> out;
    const double spreads[] = {1e-2, 1e-4, 1e-6, 1e-9};
    for (double spread : spreads) {
        const Vec2 c{rng.uniform(0.4, 0.6), rng.uniform(0.4, 0.6)};
        for (int i = 0; i < 12; ++i)
            out.push_back({c.x + spread * rng.uniform(), c.y + spread * rng.uniform()});
    }
    return out;
}

/// Validity, quality and "every input point is a vertex", for one tree.
void expect_good_mesh(const DynQuadtree<2>& tree, const std::string& what) {
    const QuadMesh2 mesh = quad_mesh(tree);
    const auto bad = check_quad_mesh(mesh).problems;
    EXPECT_TRUE(bad.empty()) << what << ":\n" << joined(bad);
    expect_inputs_are_vertices(tree, mesh, what);
    const AngleRangeDeg a = angle_range_deg(mesh);
    EXPECT_GE(a.min, kQuadMeshMinAngleDeg - 1e-6) << what;
    EXPECT_LE(a.max, kQuadMeshMaxAngleDeg + 1e-6) << what;
    EXPECT_LE(mesh.triangles.size(), 8 * mesh.leaves) << what;  // spec §4.6
}

TEST(QuadMesh, EmptyTreeIsTwoTriangles) {
    const DynQuadtree<2> tree;
    const QuadMesh2 mesh = quad_mesh(tree);
    EXPECT_EQ(mesh.points.size(), 4u);
    EXPECT_EQ(mesh.triangles.size(), 2u);
    EXPECT_TRUE(check_quad_mesh(mesh).ok());
}

TEST(QuadMesh, SingleAndTwoPoints) {
    const std::vector<Vec2> one = {{0.5, 0.5}};
    expect_good_mesh(DynQuadtree<2>::build(one), "one point");
    const std::vector<Vec2> two = {{0.4, 0.41}, {0.6, 0.58}};
    expect_good_mesh(DynQuadtree<2>::build(two), "two points");
    const std::vector<Vec2> corner = {{1.0 / 3, 1.0 / 3}, {0.6, 0.6}};
    expect_good_mesh(DynQuadtree<2>::build(corner), "middle-third corner");
}

TEST(QuadMesh, RandomInputsAreValid) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        const auto pts = uniform_points(300, seed);
        expect_good_mesh(DynQuadtree<2>::build(pts), "uniform seed " + std::to_string(seed));
    }
}

TEST(QuadMesh, ClusteredInputsAreValid) {
    for (std::uint64_t seed : {4u, 5u, 6u}) {
        const auto pts = clustered_points(seed);
        expect_good_mesh(DynQuadtree<2>::build(pts), "clustered seed " + std::to_string(seed));
    }
}

TEST(QuadMesh, DyadicLatticePointsAreValid) {
    // Points on cell boundaries and exactly half-way inside cells: exercises the half-open
    // containment and the "ties round up" warping rule.
    for (std::uint64_t seed : {21u, 22u, 23u}) {
        Rng rng(seed);
        std::vector<Vec2> pts;
        std::vector<std::pair<std::uint64_t, std::uint64_t>> used;
        for (int i = 0; i < 120; ++i) {
            const std::uint64_t a = 86 + rng.below(85), b = 86 + rng.below(85);  // [1/3, 2/3]·256
            if (std::find(used.begin(), used.end(), std::pair{a, b}) != used.end()) continue;
            used.push_back({a, b});
            pts.push_back({static_cast<double>(a) / 256, static_cast<double>(b) / 256});
        }
        expect_good_mesh(DynQuadtree<2>::build(pts), "lattice seed " + std::to_string(seed));
    }
}

TEST(QuadMesh, NonUnitDomain) {
    const QuadtreeOptions<2> options{.origin = {-3.0, 10.0}, .width = 6.0};
    Rng rng(9);
    std::vector<Vec2> pts;
    for (int i = 0; i < 100; ++i) pts.push_back({rng.uniform(-1.0, 1.0), rng.uniform(12.0, 14.0)});
    expect_good_mesh(DynQuadtree<2>::build(pts, options), "domain [-3,3]x[10,16]");
}

void expect_same_mesh(const QuadMesh2& a, const QuadMesh2& b, const std::string& what) {
    EXPECT_EQ(a.points, b.points) << what;
    EXPECT_EQ(a.triangles, b.triangles) << what;
}

/// The mesh of a mesh-mode tree updated by random inserts and erases (quad_mesh() reads that
/// tree's leaves directly) equals the mesh of a tree built from scratch on the point list the
/// test keeps itself.
TEST(QuadMesh, HistoryIndependentAfterInsertsAndErases) {
    for (std::uint64_t seed : {11u, 12u}) {
        auto pool = uniform_points(150, seed);
        const auto cl = clustered_points(seed);
        pool.insert(pool.end(), cl.begin(), cl.end());
        Rng rng(seed * 7);
        DynQuadtree<2> tree({.mode = QuadtreeMode::Mesh});
        random_walk<2>(tree, pool, 400, rng, [&](const std::vector<Vec2>& present, int step) {
            if (step % 100 == 99) {
                const std::string what =
                    "seed " + std::to_string(seed) + " step " + std::to_string(step);
                const QuadMesh2 dynamic = quad_mesh(tree);
                const auto fresh = DynQuadtree<2>::build(present, {.mode = QuadtreeMode::Mesh});
                EXPECT_EQ(tree.canonical_dump(), fresh.canonical_dump()) << what;
                expect_same_mesh(dynamic, quad_mesh(fresh), what);
                EXPECT_TRUE(check_quad_mesh(dynamic).ok()) << what;
            }
        });
    }
}

/// A box of width 3e-9 at (0.5, 0.25) (not dyadic): its far corner origin + W rounds, by up to
/// 4e-8 of W. The checker measures the box the mesh's corners span, not W².
TEST(QuadMesh, CheckerMeasuresTheBoxTheCornersSpan) {
    const QuadtreeOptions<2> o{.origin = {0.5, 0.25}, .width = 3e-9};
    ASSERT_NE((o.origin.x + o.width) - o.origin.x, o.width);  // the premise: W rounds there
    const std::vector<Vec2> pts{{0.5 + 1.2e-9, 0.25 + 1.3e-9},
                                {0.5 + 1.7e-9, 0.25 + 1.5e-9},
                                {0.5 + 1.5e-9, 0.25 + 1.9e-9}};
    const QuadMesh2 mesh = quad_mesh(DynQuadtree<2>::build(pts, o));
    EXPECT_TRUE(check_quad_mesh(mesh).ok()) << joined(check_quad_mesh(mesh).problems);
}

/// Angles do not depend on the magnitude of the coordinates: the same mesh scaled by 2^-1000
/// (coordinates near 1e-301, where products of edge vectors underflow) and by 2^1000 (near
/// 1e301, where they overflow) has bit-identical angle extremes.
TEST(QuadMesh, AnglesDoNotDependOnTheMagnitudeOfTheCoordinates) {
    const QuadMesh2 mesh = quad_mesh(DynQuadtree<2>::build(uniform_points(40, 5)));
    const AngleRangeDeg ref = angle_range_deg(mesh);
    ASSERT_GT(ref.min, 10.0);
    for (int e : {-1000, 1000}) {
        QuadMesh2 scaled = mesh;
        for (Vec2& p : scaled.points) p = {std::ldexp(p.x, e), std::ldexp(p.y, e)};
        const AngleRangeDeg a = angle_range_deg(scaled);
        EXPECT_EQ(a.min, ref.min) << "scaled by 2^" << e;
        EXPECT_EQ(a.max, ref.max) << "scaled by 2^" << e;
    }
}

TEST(QuadMesh, CheckerFindsBrokenMeshes) {
    const std::vector<Vec2> pts = {{0.45, 0.5}, {0.55, 0.52}};
    QuadMesh2 mesh = quad_mesh(DynQuadtree<2>::build(pts));
    ASSERT_TRUE(check_quad_mesh(mesh).ok());
    QuadMesh2 flipped = mesh;
    std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
    EXPECT_FALSE(check_quad_mesh(flipped).ok());
    QuadMesh2 missing = mesh;
    missing.triangles.pop_back();
    EXPECT_FALSE(check_quad_mesh(missing).ok());
}

}  // namespace
}  // namespace dynmesh
