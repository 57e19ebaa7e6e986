#include "dynmesh/quadtree/oct_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
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


/// Uniform points in the middle third of [0, 1]^3.
std::vector<Vec3> uniform_points(std::size_t n, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < n; ++i)
        out.push_back({rng.uniform(1.0 / 3, 2.0 / 3), rng.uniform(1.0 / 3, 2.0 / 3),
                       rng.uniform(1.0 / 3, 2.0 / 3)});
    return out;
}

/// Clusters of points with spreads from 1e-2 down to 1e-9 of the domain.
std::vector<Vec3> clustered_points(std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Vec3> out;
    const double spreads[] = {1e-2, 1e-5, 1e-9};
    for (double spread : spreads) {
        const Vec3 c{rng.uniform(0.4, 0.6), rng.uniform(0.4, 0.6), rng.uniform(0.4, 0.6)};
        for (int i = 0; i < 8; ++i)
            out.push_back({c.x + spread * rng.uniform(), c.y + spread * rng.uniform(),
                           c.z + spread * rng.uniform()});
    }
    return out;
}

/// Distinct points of the dyadic lattice (1/64)·ℤ^3 in the middle third: points on cell
/// boundaries and exactly half-way inside cells exercise half-open containment and the
/// "ties round up" warping rule (|p - v|∞ = s/2, the extreme warp).
std::vector<Vec3> lattice_points(std::size_t n, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<std::array<std::uint64_t, 3>> used;
    std::vector<Vec3> out;
    while (out.size() < n) {
        const std::array<std::uint64_t, 3> a{22 + rng.below(21), 22 + rng.below(21),
                                             22 + rng.below(21)};  // [1/3, 2/3]·64
        if (std::find(used.begin(), used.end(), a) != used.end()) continue;
        used.push_back(a);
        out.push_back({static_cast<double>(a[0]) / 64, static_cast<double>(a[1]) / 64,
                       static_cast<double>(a[2]) / 64});
    }
    return out;
}


/// Validity, quality and "every input point is a vertex", for one tree.
void expect_good_mesh(const DynQuadtree<3>& tree, const std::string& what) {
    const OctMesh3 mesh = oct_mesh(tree);
    const auto bad = check_oct_mesh(mesh).problems;
    EXPECT_TRUE(bad.empty()) << what << ":\n" << joined(bad);
    expect_inputs_are_vertices(tree, mesh, what);
    const DihedralRangeDeg a = dihedral_range_deg(mesh);
    EXPECT_GE(a.min, kOctMeshMinDihedralDeg) << what;
    EXPECT_LE(a.max, kOctMeshMaxDihedralDeg) << what;
    EXPECT_DOUBLE_EQ(min_dihedral_deg(mesh), a.min);
    EXPECT_DOUBLE_EQ(max_dihedral_deg(mesh), a.max);
    EXPECT_LE(mesh.tets.size(), 48 * mesh.leaves) << what;  // spec §4.6
}

TEST(OctMesh, EmptyTreeIsTheConeOfTheCube) {
    const DynQuadtree<3> tree;
    const OctMesh3 mesh = oct_mesh(tree);
    EXPECT_EQ(mesh.points.size(), 9u);  // 8 corners and the centre
    EXPECT_EQ(mesh.tets.size(), 12u);   // 6 faces × 2 triangles
    EXPECT_EQ(mesh.leaves, 1u);
    EXPECT_TRUE(check_oct_mesh(mesh).ok()) << joined(check_oct_mesh(mesh).problems);
    const DihedralRangeDeg a = dihedral_range_deg(mesh);
    EXPECT_NEAR(a.min, 45.0, 1e-9);  // cone from the centre over diagonal-split faces
    EXPECT_NEAR(a.max, 120.0, 1e-9);
}

TEST(OctMesh, SingleAndTwoPoints) {
    const std::vector<Vec3> one = {{0.5, 0.5, 0.5}};
    expect_good_mesh(DynQuadtree<3>::build(one), "one point");
    const std::vector<Vec3> off = {{0.41, 0.47, 0.6}};
    expect_good_mesh(DynQuadtree<3>::build(off), "one off-centre point");
    const std::vector<Vec3> two = {{0.4, 0.41, 0.45}, {0.6, 0.58, 0.52}};
    expect_good_mesh(DynQuadtree<3>::build(two), "two points");
    const std::vector<Vec3> corner = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.6, 0.6, 0.6}};
    expect_good_mesh(DynQuadtree<3>::build(corner), "middle-third corner");
}

TEST(OctMesh, RandomInputsAreValid) {
    for (std::uint64_t seed : {1u, 2u}) {
        const auto pts = uniform_points(seed == 1 ? 200 : 50, seed);
        expect_good_mesh(DynQuadtree<3>::build(pts), "uniform seed " + std::to_string(seed));
    }
}

TEST(OctMesh, ClusteredInputsAreValid) {
    for (std::uint64_t seed : {4u, 5u}) {
        const auto pts = clustered_points(seed);
        expect_good_mesh(DynQuadtree<3>::build(pts), "clustered seed " + std::to_string(seed));
    }
}

TEST(OctMesh, DyadicLatticePointsAreValid) {
    for (std::uint64_t seed : {21u, 22u}) {
        const auto pts = lattice_points(40, seed);
        expect_good_mesh(DynQuadtree<3>::build(pts), "lattice seed " + std::to_string(seed));
    }
}

TEST(OctMesh, NonUnitDomain) {
    const QuadtreeOptions<3> options{.origin = {-3.0, 10.0, 0.25}, .width = 6.0};
    Rng rng(9);
    std::vector<Vec3> pts;
    for (int i = 0; i < 30; ++i)
        pts.push_back({rng.uniform(-1.0, 1.0), rng.uniform(12.0, 14.0), rng.uniform(2.25, 4.25)});
    expect_good_mesh(DynQuadtree<3>::build(pts, options), "domain [-3,3]x[10,16]x[0.25,6.25]");
}

/// Dihedral angles do not depend on the magnitude of the coordinates (see the 2D test).
TEST(OctMesh, DihedralsDoNotDependOnTheMagnitudeOfTheCoordinates) {
    const OctMesh3 mesh = oct_mesh(DynQuadtree<3>::build(uniform_points(12, 5)));
    const DihedralRangeDeg ref = dihedral_range_deg(mesh);
    ASSERT_GT(ref.min, 10.0);
    for (int e : {-1000, 1000}) {
        OctMesh3 scaled = mesh;
        for (Vec3& p : scaled.points) p = {std::ldexp(p.x, e), std::ldexp(p.y, e), std::ldexp(p.z, e)};
        const DihedralRangeDeg d = dihedral_range_deg(scaled);
        EXPECT_EQ(d.min, ref.min) << "scaled by 2^" << e;
        EXPECT_EQ(d.max, ref.max) << "scaled by 2^" << e;
    }
}

/// As QuadMesh.HistoryIndependentAfterInsertsAndErases: the updated mesh-mode tree's mesh
/// against a from-scratch build on the test's own point list.
TEST(OctMesh, HistoryIndependentAfterInsertsAndErases) {
    for (std::uint64_t seed : {11u, 12u}) {
        auto pool = uniform_points(30, seed);
        const auto cl = clustered_points(seed);
        pool.insert(pool.end(), cl.begin(), cl.end());
        Rng rng(seed * 7);
        DynQuadtree<3> tree({.mode = QuadtreeMode::Mesh});
        random_walk<3>(tree, pool, 120, rng, [&](const std::vector<Vec3>& present, int step) {
            if (step % 60 == 59) {
                const std::string what =
                    "seed " + std::to_string(seed) + " step " + std::to_string(step);
                const OctMesh3 dynamic = oct_mesh(tree);
                const auto fresh = DynQuadtree<3>::build(present, {.mode = QuadtreeMode::Mesh});
                EXPECT_EQ(tree.canonical_dump(), fresh.canonical_dump()) << what;
                EXPECT_TRUE(dynamic == oct_mesh(fresh)) << what;
                if (step == 119) {
                    EXPECT_TRUE(check_oct_mesh(dynamic).ok()) << what;
                }
            }
        });
    }
}

TEST(OctMesh, InsertionOrderDoesNotMatter) {
    auto pts = uniform_points(30, 31);
    const OctMesh3 a = oct_mesh(DynQuadtree<3>::build(pts));
    std::reverse(pts.begin(), pts.end());
    DynQuadtree<3> tree;
    for (const Vec3& p : pts) ASSERT_EQ(tree.insert(p), InsertResult::Inserted);
    EXPECT_TRUE(a == oct_mesh(tree));
}

/// As QuadMesh.CheckerMeasuresTheBoxTheCornersSpan, for the volume.
TEST(OctMesh, CheckerMeasuresTheBoxTheCornersSpan) {
    const QuadtreeOptions<3> o{.origin = {0.5, 0.25, 0.75}, .width = 3e-9};
    ASSERT_NE((o.origin.x + o.width) - o.origin.x, o.width);
    const std::vector<Vec3> pts{{0.5 + 1.2e-9, 0.25 + 1.3e-9, 0.75 + 1.4e-9},
                                {0.5 + 1.7e-9, 0.25 + 1.5e-9, 0.75 + 1.8e-9}};
    const OctMesh3 mesh = oct_mesh(DynQuadtree<3>::build(pts, o));
    EXPECT_TRUE(check_oct_mesh(mesh).ok()) << joined(check_oct_mesh(mesh).problems);
}

TEST(OctMesh, CheckerFindsBrokenMeshes) {
    const std::vector<Vec3> pts = {{0.45, 0.5, 0.5}, {0.55, 0.52, 0.49}};
    const OctMesh3 mesh = oct_mesh(DynQuadtree<3>::build(pts));
    ASSERT_TRUE(check_oct_mesh(mesh).ok());
    OctMesh3 flipped = mesh;
    std::swap(flipped.tets[0][1], flipped.tets[0][2]);
    EXPECT_FALSE(check_oct_mesh(flipped).ok());
    OctMesh3 missing = mesh;
    missing.tets.pop_back();
    EXPECT_FALSE(check_oct_mesh(missing).ok());
    OctMesh3 doubled = mesh;
    doubled.tets.push_back(mesh.tets.front());
    EXPECT_FALSE(check_oct_mesh(doubled).ok());
    OctMesh3 out_of_range = mesh;
    out_of_range.tets[0][3] = static_cast<std::uint32_t>(mesh.points.size());
    EXPECT_FALSE(check_oct_mesh(out_of_range).ok());
}


}  // namespace
}  // namespace dynmesh
