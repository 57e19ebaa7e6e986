#include "dynmesh/quadtree/offcenter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/quadtree/dyn_offcenter.hpp"
#include "dynmesh/quadtree/quadtree.hpp"
#include "quadtree_fixtures.hpp"

namespace dynmesh {
namespace {
using testing_quadtree::expect_inputs_are_vertices;
using testing_quadtree::joined;


/// Uniform points in the middle third of [o, o + w]^2.
std::vector<Vec2> uniform_points(std::size_t n, std::uint64_t seed, Vec2 o = {}, double w = 1) {
    Rng rng(seed);
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < n; ++i)
        out.push_back({o.x + w * rng.uniform(1.0 / 3, 2.0 / 3), o.y + w * rng.uniform(1.0 / 3, 2.0 / 3)});
    return out;
}

/// Clusters with spreads from 1e-2 down to 1e-5 of the unit domain.
std::vector<Vec2> clustered_points(std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Vec2> out;
    for (double spread : {1e-2, 1e-3, 1e-4, 1e-5}) {
        const Vec2 c{rng.uniform(0.4, 0.6), rng.uniform(0.4, 0.6)};
        for (int i = 0; i < 10; ++i)
            out.push_back({c.x + spread * rng.uniform(), c.y + spread * rng.uniform()});
    }
    return out;
}

/// Largest circumradius / shortest edge over all triangles.
double max_radius_edge(const OffCenterMesh2& mesh) {
    double worst = 0;
    for (const auto& t : mesh.triangles) {
        const Vec2 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &c = mesh.points[t[2]];
        const double la = norm(b - c), lb = norm(c - a), lc = norm(a - b);
        const double area2 = std::fabs(cross(b - a, c - a));
        const double r = la * lb * lc / (2 * area2);
        worst = std::max(worst, r / std::min({la, lb, lc}));
    }
    return worst;
}

/// Validity (CCW, conforming, covers the box, Delaunay), every input point a vertex, quality.
void expect_good_mesh(const DynQuadtree<2>& tree, double rho, const std::string& what) {
    const OffCenterMesh2 mesh = offcenter_mesh(tree, {.rho = rho});
    const auto bad = check_offcenter_mesh(mesh).problems;
    EXPECT_TRUE(bad.empty()) << what << ":\n" << joined(bad);
    expect_inputs_are_vertices(tree, mesh, what);
    EXPECT_EQ(mesh.points.size(), tree.size() + mesh.steiner) << what;
    EXPECT_EQ(mesh.steiner, mesh.boundary_steiner + mesh.apex_offcenters + mesh.circumcentres)
        << what;
    EXPECT_EQ(mesh.stuck_pairs, 0u) << what;
    EXPECT_GE(mesh.min_angle_deg, offcenter_min_angle_deg(rho) - 1e-7) << what;
    EXPECT_LE(max_radius_edge(mesh), rho * (1 + 1e-8)) << what;
}

TEST(OffCenterMesh, EmptyTreeIsTwoTriangles) {
    const DynQuadtree<2> tree;
    const OffCenterMesh2 mesh = offcenter_mesh(tree);
    EXPECT_EQ(mesh.points.size(), 4u);
    EXPECT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.steiner, 4u);
    EXPECT_TRUE(check_offcenter_mesh(mesh).ok()) << joined(check_offcenter_mesh(mesh).problems);
}

TEST(OffCenterMesh, SmallInputs) {
    for (double rho : {1.5, 2.0}) {
        expect_good_mesh(DynQuadtree<2>::build(std::vector<Vec2>{{0.5, 0.5}}), rho, "one point");
        expect_good_mesh(DynQuadtree<2>::build(std::vector<Vec2>{{0.4, 0.41}, {0.6, 0.58}}), rho,
                         "two points");
        expect_good_mesh(DynQuadtree<2>::build(std::vector<Vec2>{{1.0 / 3, 1.0 / 3}, {0.6, 0.6}}),
                         rho, "middle-third corner");
        // Cocircular and collinear inputs (a lattice).
        std::vector<Vec2> grid;
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j) grid.push_back({0.4 + 0.05 * i, 0.4 + 0.05 * j});
        expect_good_mesh(DynQuadtree<2>::build(grid), rho, "lattice");
    }
}

TEST(OffCenterMesh, UniformInputsAreValidDelaunayAndGood) {
    for (double rho : {1.5, 2.0})
        for (std::uint64_t seed : {1u, 2u, 3u})
            expect_good_mesh(DynQuadtree<2>::build(uniform_points(300, seed)), rho,
                             "uniform seed " + std::to_string(seed) + " rho " + std::to_string(rho));
}

TEST(OffCenterMesh, ClusteredInputsAreValidDelaunayAndGood) {
    for (double rho : {1.5, 2.0})
        for (std::uint64_t seed : {4u, 5u})
            expect_good_mesh(DynQuadtree<2>::build(clustered_points(seed)), rho,
                             "clustered seed " + std::to_string(seed) + " rho " + std::to_string(rho));
}

TEST(OffCenterMesh, OtherDomainBox) {
    const Vec2 o{-3.0, 5.0};
    const double w = 8.0;
    const auto pts = uniform_points(200, 9, o, w);
    const auto tree = DynQuadtree<2>::build(pts, {.origin = o, .width = w});
    expect_good_mesh(tree, 1.5, "box (-3, 5) + 8");
    const OffCenterMesh2 mesh = offcenter_mesh(tree, {.rho = 1.5});
    EXPECT_EQ(mesh.origin, o);
    EXPECT_EQ(mesh.width, w);
}

TEST(OffCenterMesh, NearSqrt2Terminates) {
    const double rho = std::nextafter(std::sqrt(2.0), 2.0);
    expect_good_mesh(DynQuadtree<2>::build(uniform_points(200, 11)), rho, "rho = sqrt(2)+");
}

TEST(OffCenterMesh, CircumcentreAblationIsValidToo) {
    const auto tree = DynQuadtree<2>::build(uniform_points(200, 12));
    const OffCenterMesh2 mesh = offcenter_mesh(tree, {.rho = 1.5, .use_offcenters = false});
    EXPECT_TRUE(check_offcenter_mesh(mesh).ok()) << joined(check_offcenter_mesh(mesh).problems);
    EXPECT_EQ(mesh.apex_offcenters, 0u);
    EXPECT_LE(max_radius_edge(mesh), 1.5 * (1 + 1e-8));
}

/// The off-center mesh maintained by DynOffCenterMesh2 through random inserts and erases
/// equals offcenter_mesh() of a tree built from scratch on the point list the test keeps
/// itself (in reverse order); erase then re-insert restores it.
TEST(OffCenterMesh, HistoryIndependent) {
    for (std::uint64_t seed : {21u, 22u}) {
        Rng rng(seed);
        const auto pool = uniform_points(150, seed);
        for (double rho : {1.5, 2.0}) {
            DynOffCenterMesh2 dyn({}, {.rho = rho});
            std::vector<Vec2> present;
            for (int step = 0; step < 250; ++step) {
                if (present.empty() || rng.coin(0.6)) {
                    const Vec2& p = pool[rng.below(pool.size())];
                    if (dyn.insert(p) == InsertResult::Inserted) present.push_back(p);
                } else {
                    const std::size_t k = rng.below(present.size());
                    ASSERT_EQ(dyn.erase(present[k]), EraseResult::Erased);
                    present.erase(present.begin() + static_cast<std::ptrdiff_t>(k));
                }
            }
            std::vector<Vec2> shuffled = present;
            std::reverse(shuffled.begin(), shuffled.end());
            const OffCenterMesh2 a = dyn.mesh();
            const OffCenterMesh2 b = offcenter_mesh(DynQuadtree<2>::build(shuffled), {.rho = rho});
            EXPECT_EQ(a.points, b.points) << "seed " << seed;
            EXPECT_EQ(a.triangles, b.triangles) << "seed " << seed;
            EXPECT_EQ(a.input_vertices, b.input_vertices) << "seed " << seed;
            EXPECT_EQ(a.steiner, b.steiner) << "seed " << seed;
            // Erase then re-insert a point restores the identical mesh.
            ASSERT_FALSE(present.empty());
            ASSERT_EQ(dyn.erase(present.front()), EraseResult::Erased);
            ASSERT_EQ(dyn.insert(present.front()), InsertResult::Inserted);
            const OffCenterMesh2 after = dyn.mesh();
            EXPECT_EQ(a.points, after.points);
            EXPECT_EQ(a.triangles, after.triangles);
        }
    }
}

/// As QuadMesh.CheckerMeasuresTheBoxTheCornersSpan, for the off-center mesh's box.
TEST(OffCenterMesh, CheckerMeasuresTheBoxTheCornersSpan) {
    const QuadtreeOptions<2> o{.origin = {0.5, 0.25}, .width = 3e-9};
    ASSERT_NE((o.origin.x + o.width) - o.origin.x, o.width);
    const std::vector<Vec2> pts{{0.5 + 1.2e-9, 0.25 + 1.3e-9},
                                {0.5 + 1.7e-9, 0.25 + 1.5e-9},
                                {0.5 + 1.5e-9, 0.25 + 1.9e-9}};
    const OffCenterMesh2 mesh = offcenter_mesh(DynQuadtree<2>::build(pts, o), {.rho = 1.5});
    EXPECT_TRUE(check_offcenter_mesh(mesh).ok()) << joined(check_offcenter_mesh(mesh).problems);
}

TEST(OffCenterMesh, RejectsBadRho) {
    const auto tree = DynQuadtree<2>::build(uniform_points(10, 3));
    const double bad[] = {std::sqrt(2.0), 1.0, 0.5, -2.0, 0.0,
                          std::numeric_limits<double>::quiet_NaN(),
                          std::numeric_limits<double>::infinity()};
    for (double rho : bad)
        EXPECT_THROW((void)offcenter_mesh(tree, {.rho = rho}), InvalidInput) << "rho " << rho;
}

TEST(OffCenterMesh, MinAngleOfRho) {
    EXPECT_NEAR(offcenter_min_angle_deg(std::sqrt(2.0)), 20.7048, 1e-4);
    EXPECT_NEAR(offcenter_min_angle_deg(1.0), 30.0, 1e-12);
}

}  // namespace
}  // namespace dynmesh
