#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/spatial_sort.hpp"
#include "dynmesh/geometry/triangle.hpp"

namespace dynmesh {
namespace {

TEST(Predicates, SignConventions) {
    EXPECT_EQ(orient2d({0, 0}, {1, 0}, {0, 1}), Sign::Positive);
    EXPECT_EQ(orient2d({0, 0}, {0, 1}, {1, 0}), Sign::Negative);
    EXPECT_EQ(orient2d({0, 0}, {1, 1}, {2, 2}), Sign::Zero);
    EXPECT_EQ(incircle({0, 0}, {1, 0}, {0, 1}, {0.5, 0.5}), Sign::Positive);
    EXPECT_EQ(incircle({0, 0}, {1, 0}, {0, 1}, {2, 2}), Sign::Negative);
    EXPECT_EQ(incircle({0, 0}, {1, 0}, {0, 1}, {1, 1}), Sign::Zero);  // cocircular
    EXPECT_EQ(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), Sign::Positive);
    EXPECT_EQ(insphere({1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0.5}), Sign::Positive);
    EXPECT_EQ(insphere({1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}), Sign::Zero);
}

TEST(Predicates, DiametricBallIsExact) {
    const Point3 a{1, 0, 0}, b{-1, 0, 0}, c{0, 1, 0};  // diametric ball: unit ball at 0
    EXPECT_EQ(in_diametric_ball(a, b, c, {0, 0, 0.999}), Sign::Positive);
    EXPECT_EQ(in_diametric_ball(a, b, c, {0, 0, 1}), Sign::Zero);
    EXPECT_EQ(in_diametric_ball(a, b, c, {0, 0, 1.001}), Sign::Negative);
    EXPECT_THROW((void)in_diametric_ball(a, b, {3, 0, 0}, {0, 0, 0}), InvalidInput);
    // A near-degenerate case that plain floating point gets wrong: 1 + 2^-52 on the sphere.
    EXPECT_EQ(in_diametric_ball(a, b, c, {0, 0, 1.0 + 0x1p-52}), Sign::Negative);
}

TEST(TriangleMeasures, KnownValues) {
    const Point3 a{0, 0, 0}, b{2, 0, 0}, c{0, 2, 0};
    const Point3 cc = circumcenter(a, b, c);
    EXPECT_NEAR(distance(cc, a), distance(cc, b), 1e-15);
    EXPECT_NEAR(distance(cc, a), distance(cc, c), 1e-15);
    EXPECT_NEAR(circumradius(a, b, c), std::sqrt(2.0), 1e-15);
    EXPECT_NEAR(rad_to_deg(min_angle(a, b, c)), 45.0, 1e-12);
    EXPECT_NEAR(rad_to_deg(max_angle(a, b, c)), 90.0, 1e-12);
    EXPECT_NEAR(radius_edge_ratio(a, b, c), std::sqrt(2.0) / 2.0, 1e-15);
    EXPECT_NEAR(triangle_area(a, b, c), 2.0, 1e-15);
    EXPECT_EQ(triangle_normal(a, b, c), (Vec3{0, 0, 1}));
    EXPECT_FALSE(std::isfinite(circumradius(a, b, {4, 0, 0})));
    // Dihedral angle: flat pair = pi, folded square = pi/2, orientation-free.
    EXPECT_NEAR(dihedral_angle(a, b, {1, 1, 0}, {1, -1, 0}), kPi, 1e-15);
    EXPECT_NEAR(dihedral_angle(a, b, {1, 1, 0}, {1, 0, 1}), kPi / 2, 1e-15);
    EXPECT_NEAR(dihedral_angle(b, a, {1, 0, 1}, {1, 1, 0}), kPi / 2, 1e-15);
}

TEST(Rng, ReproducibleAndInRange) {
    Rng a(5), b(5), c(6);
    bool differs = false;
    for (int i = 0; i < 1000; ++i) {
        const double x = a.uniform();
        EXPECT_EQ(x, b.uniform());
        differs = differs || x != c.uniform();
        EXPECT_GE(x, 0.0);
        EXPECT_LT(x, 1.0);
        EXPECT_LT(a.below(7), 7u);
        (void)b.below(7);
        (void)c.below(7);
        EXPECT_NEAR(norm(a.unit_vector()), 1.0, 1e-12);
        (void)b.unit_vector();
        (void)c.unit_vector();
    }
    EXPECT_TRUE(differs);
}

TEST(SpatialOrder, IsADeterministicPermutationThatGroupsNeighbours) {
    Rng rng(1);
    std::vector<Point3> pts(5000);
    for (auto& p : pts) p = {rng.uniform(), rng.uniform(), rng.uniform()};
    const auto order = spatial_order(pts);
    std::vector<std::uint32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<std::uint32_t> iota(pts.size());
    std::iota(iota.begin(), iota.end(), 0u);
    EXPECT_EQ(sorted, iota);
    EXPECT_EQ(order, spatial_order(pts));
    // Consecutive points are much closer along the curve than in input order.
    double along = 0, input = 0;
    for (std::size_t i = 1; i < pts.size(); ++i) {
        along += distance(pts[order[i]], pts[order[i - 1]]);
        input += distance(pts[i], pts[i - 1]);
    }
    EXPECT_LT(along, 0.2 * input);
}

}  // namespace
}  // namespace dynmesh
