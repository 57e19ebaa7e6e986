#include "dynmesh/flips/flip_rules.hpp"

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

// Quad with pq = (0,0)-(1,0), r above, s below.
bool planar_def3(Point3 p, Point3 q, Point3 r, Point3 s) { return def3_condition(p, q, r, s); }

TEST(Def3, PlanarHandCases) {
    const Point3 p{0, 0, 0}, q{1, 0, 0};
    // r inside circumcircle of pqs: a long thin pair, flippable.
    EXPECT_TRUE(planar_def3(p, q, {0.5, 0.2, 0}, {0.5, -0.2, 0}));
    // r and s far from pq: the diagonal rs is longer and pq is Delaunay: not flippable.
    EXPECT_FALSE(planar_def3(p, q, {0.5, 2, 0}, {0.5, -2, 0}));
    // Non-convex quad (s beyond p's side): not flippable even though the pair is skinny.
    EXPECT_FALSE(planar_def3(p, q, {-0.6, 0.1, 0}, {-0.5, -0.1, 0}));
    // Condition (iv) alone: s lies on the far side so that angle at r is split unevenly
    // beyond the old angle: quad not convex at q.
    EXPECT_FALSE(planar_def3(p, q, {1.4, 0.1, 0}, {1.3, -0.1, 0}));
}

TEST(Def3, DiagonalAlreadyAnEdgeIsNotFlippable) {
    // A flat tetrahedron: the pair on pq is thin (Definition 3 (i)-(iv) hold), but the other
    // diagonal rs is already an edge, so condition (v) fails.
    TriangleSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0.5, 0.2, 0}, {0.5, -0.2, 0}};
    s.triangles = {{0, 1, 2}, {1, 0, 3}, {2, 3, 0}, {3, 2, 1}};
    const SurfaceMesh tet = SurfaceMesh::from_soup(s);
    const Edge pq = tet.find_edge(Vertex(0), Vertex(1));
    ASSERT_TRUE(def3_condition(s.points[0], s.points[1], s.points[2], s.points[3]));
    EXPECT_FALSE(tet.is_flip_ok(pq));
    EXPECT_EQ(flip_verdict(tet, pq, FlipRule::AngleDef3), FlipVerdict::DiagonalExists);
    EXPECT_EQ(flip_verdict(tet, pq, FlipRule::DiametricBall), FlipVerdict::DiagonalExists);
    for (Edge e : tet.edges()) EXPECT_FALSE(is_flippable(tet, e, FlipRule::AngleDef3));
}

TEST(Def3, BoundaryAndDegenerate) {
    SurfaceMesh g = test::grid(2);
    std::size_t boundary = 0;
    for (Edge e : g.edges())
        if (g.is_boundary(e)) {
            ++boundary;
            EXPECT_EQ(flip_verdict(g, e, FlipRule::AngleDef3), FlipVerdict::Boundary);
        }
    EXPECT_EQ(boundary, 8u);
    EXPECT_TRUE(is_degenerate_triangle({0, 0, 0}, {1, 0, 0}, {2, 0, 0}));
    EXPECT_TRUE(is_degenerate_triangle({0, 0, 0}, {0, 0, 0}, {2, 0, 0}));
    EXPECT_FALSE(is_degenerate_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
}

// Acceptance check 2: in the plane, Definition 3 equals "convex and incircle".
TEST(Def3, PlanarEquivalenceOnRandomQuads) {
    Rng rng(42);
    std::size_t agree = 0, tested = 0, flippable = 0;
    for (int i = 0; i < 1000000; ++i) {
        const Point3 p{0, 0, 0}, q{1, 0, 0};
        const Point3 r{rng.uniform(-1, 2), rng.uniform(1e-3, 0.8), 0};
        const Point3 s{rng.uniform(-1, 2), rng.uniform(-0.8, -1e-3), 0};
        // Exclude near-degenerate cases (near-cocircular or near-collinear).
        const Point2 p2{p.x, p.y}, q2{q.x, q.y}, r2{r.x, r.y}, s2{s.x, s.y};
        const Point2 c = circumcenter(p2, q2, r2);
        const double rad = norm(p2 - c);
        if (std::abs(norm(s2 - c) - rad) < 1e-6) continue;
        if (std::abs(cross(s2 - r2, p2 - r2)) < 1e-6 || std::abs(cross(s2 - r2, q2 - r2)) < 1e-6) continue;
        if (min_angle(p, q, r) < 1e-3 || min_angle(p, q, s) < 1e-3) continue;
        ++tested;
        const bool def3 = def3_condition(p, q, r, s);
        const bool del = planar_condition(p, q, r, s);
        flippable += del;
        agree += def3 == del;
    }
    EXPECT_GT(tested, 900000u);
    EXPECT_GT(flippable, tested / 10);  // both outcomes occur often
    EXPECT_EQ(agree, tested);
}

// Acceptance check 3: every Definition 3 flip raises the smallest angle of the pair.
TEST(Def3, FlipRaisesMinimumAngleIn3D) {
    Rng rng(7);
    std::size_t flippable = 0;
    for (int i = 0; i < 200000; ++i) {
        const Point3 p{0, 0, 0}, q{1, 0, 0};
        const Point3 r{rng.uniform(-0.5, 1.5), rng.uniform(0.05, 1.5), rng.uniform(-0.3, 0.3)};
        const Point3 s{rng.uniform(-0.5, 1.5), rng.uniform(-1.5, -0.05), rng.uniform(-0.3, 0.3)};
        if (!def3_condition(p, q, r, s)) continue;
        ++flippable;
        const double before = std::min(min_angle(p, q, r), min_angle(q, p, s));
        const double after = std::min(min_angle(p, s, r), min_angle(q, r, s));
        ASSERT_GT(after, before) << "case " << i;
    }
    EXPECT_GT(flippable, 1000u);
}

TEST(DiametricRule, MatchesBallMembership) {
    const Point3 p{0, 0, 0}, q{1, 0, 0};
    // s inside the diametric ball of pqr (thin pair): flippable, circumradius drops.
    EXPECT_EQ(diametric_condition(p, q, {0.5, 0.2, 0.05}, {0.5, -0.2, 0.0}), FlipVerdict::Flippable);
    EXPECT_EQ(diametric_condition(p, q, {0.5, 2, 0}, {0.5, -2, 0.1}), FlipVerdict::RuleFails);
}

TEST(Illegal, SymmetricInThePlane) {
    TriangleSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0.5, 0.2, 0}, {0.5, -0.2, 0}};
    s.triangles = {{0, 1, 2}, {1, 0, 3}};
    SurfaceMesh m = SurfaceMesh::from_soup(s);
    const Edge e = m.find_edge(Vertex(0), Vertex(1));
    EXPECT_TRUE(is_illegal(m, e));
    m.flip(e);
    EXPECT_FALSE(is_illegal(m, m.find_edge(Vertex(2), Vertex(3))));
}

TEST(FlipRule, ParsesNames) {
    EXPECT_EQ(parse_flip_rule("angle"), FlipRule::AngleDef3);
    EXPECT_EQ(parse_flip_rule("delaunay"), FlipRule::DiametricBall);
    EXPECT_THROW((void)parse_flip_rule("bogus"), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
