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
    // Non-convex quads (s beyond p's side, or beyond q's): not flippable, although the
    // smallest angle would grow (the guard alone would let them through).
    for (const auto& [r, s] : {std::pair<Point3, Point3>{{-0.6, 0.1, 0}, {-0.5, -0.1, 0}},
                               std::pair<Point3, Point3>{{1.4, 0.1, 0}, {1.3, -0.1, 0}}}) {
        const Def3Conditions c = def3_conditions(p, q, r, s);
        EXPECT_FALSE(c.iv) << "the quad is not convex";
        EXPECT_TRUE(c.min_angle_grows);
        EXPECT_FALSE(c.rule());
        EXPECT_FALSE(planar_def3(p, q, r, s));
    }
}

// Acceptance check 1: one 3D hand case per condition, in which only that condition fails
// while the smallest angle of the pair would still grow, so the guard cannot stand in for
// the condition. The cases keep their verdicts when any coordinate moves by 1e-3.
TEST(Def3, EachConditionFailingAloneIn3D) {
    const Point3 p{0, 0, 0}, q{1, 0, 0};
    struct Case {
        const char* name;
        Point3 r, s;
        Def3Conditions expected;
    };
    const Case cases[] = {
        {"(i)", {0.1, 0.1, -0.2}, {1.0, -0.2, 0.0}, {.i = false, .ii = true, .iii = true, .iv = true}},
        {"(ii)", {-0.5, 0.1, -0.3}, {0.4, -0.1, 0.0}, {.i = true, .ii = false, .iii = true, .iv = true}},
        {"(iii)", {-0.1, 0.2, -0.2}, {0.4, -0.1, -0.1}, {.i = true, .ii = true, .iii = false, .iv = true}},
    };
    for (const Case& k : cases) {
        const Def3Conditions c = def3_conditions(p, q, k.r, k.s);
        EXPECT_EQ(c.i, k.expected.i) << k.name;
        EXPECT_EQ(c.ii, k.expected.ii) << k.name;
        EXPECT_EQ(c.iii, k.expected.iii) << k.name;
        EXPECT_EQ(c.iv, k.expected.iv) << k.name;
        EXPECT_TRUE(c.min_angle_grows) << k.name << ": the guard holds";
        EXPECT_FALSE(c.rule()) << k.name;
        EXPECT_FALSE(def3_condition(p, q, k.r, k.s)) << k.name;
        // As a mesh: the edge is refused by the rule, not by the guard or the topology.
        TriangleSoup soup;
        soup.points = {p, q, k.r, k.s};
        soup.triangles = {{0, 1, 2}, {1, 0, 3}};
        const SurfaceMesh m = SurfaceMesh::from_soup(soup);
        EXPECT_EQ(flip_verdict(m, m.find_edge(Vertex(0), Vertex(1)), FlipRule::AngleDef3), FlipVerdict::RuleFails)
            << k.name;
    }
    // Condition (iv) never fails alone: when (i)-(iii) hold, (iv) holds too (see
    // ConditionsOneToThreeImplyFour), so its hand case fails together with (i) and (iii).
    const Def3Conditions c = def3_conditions(p, q, {1.4, 0.1, 0.3}, {1.3, -0.1, -0.2});
    EXPECT_FALSE(c.iv);
    EXPECT_FALSE(c.rule());
}

// The angle algebra behind Definition 3: (i) and (iii) give angle prq > angle prs when the
// old angle at q is acute, and (ii) and (iii) give angle prq > angle qrs likewise, so (iv)
// is implied in practice. Measured on random 3D quads, including obtuse ones.
TEST(Def3, ConditionsOneToThreeImplyFour) {
    Rng rng(5);
    std::size_t hold = 0;
    for (int i = 0; i < 1500000; ++i) {
        const double sc = i % 3 == 0 ? 0.3 : i % 3 == 1 ? 1.5 : 4.0;
        const Point3 p{0, 0, 0}, q{1, 0, 0};
        const Point3 r{rng.uniform(-sc, 1 + sc), rng.uniform(-sc, sc), rng.uniform(-sc, sc)};
        const Point3 s{rng.uniform(-sc, 1 + sc), rng.uniform(-sc, sc), rng.uniform(-sc, sc)};
        const Def3Conditions c = def3_conditions(p, q, r, s);
        if (!(c.i && c.ii && c.iii)) continue;
        ++hold;
        ASSERT_TRUE(c.iv) << "case " << i;
    }
    EXPECT_GT(hold, 50000u);
}

// The rule without the guard: whenever Definition 3 (i)-(iv) holds, the smallest angle of
// the new pair exceeds that of the old pair (the paper's termination argument), so the
// guard only matters within rounding.
TEST(Def3, RuleAloneRaisesTheMinimumAngle) {
    Rng rng(11);
    std::size_t rule = 0;
    for (int i = 0; i < 500000; ++i) {
        const Point3 p{0, 0, 0}, q{1, 0, 0};
        const Point3 r{rng.uniform(-0.5, 1.5), rng.uniform(-0.2, 1.5), rng.uniform(-0.6, 0.6)};
        const Point3 s{rng.uniform(-0.5, 1.5), rng.uniform(-1.5, 0.2), rng.uniform(-0.6, 0.6)};
        const Def3Conditions c = def3_conditions(p, q, r, s);
        if (!c.rule()) continue;
        ++rule;
        const double before = std::min(min_angle(p, q, r), min_angle(q, p, s));
        const double after = std::min(min_angle(p, s, r), min_angle(q, r, s));
        ASSERT_GT(after, before) << "case " << i;
        ASSERT_TRUE(c.min_angle_grows) << "case " << i;
    }
    EXPECT_GT(rule, 10000u);
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
        const Def3Conditions def3 = def3_conditions(p, q, r, s);
        const bool del = planar_condition(p, q, r, s);
        flippable += del;
        // Definition 3 itself (without the guard) and what flipping uses (with it).
        agree += def3.rule() == del && def3.all() == del;
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

TEST(DiametricNoFoldRule, RefusesAFlipThatFoldsANeighbour) {
    // The pair pqr, qps bends down along pq and the diametric rule takes pq (s lies in the
    // ball of pqr). Across the side qr lies a face rqt turned 70 degrees from pqr: after the
    // flip, the new face qrs turns more than 90 degrees from it (a new fold), so the flip is
    // refused; with t mirrored so that rqt continues pqr, it is taken.
    const Point3 p{-1, 0, 0}, q{1, 0, 0}, r{0, 0.5, 0}, s{0, -0.5, -0.4};
    const Vec3 side = q - r, tilt{0.5, 1, 0.3};  // tilt: the normal of rqt, orthogonal to qr
    ASSERT_EQ(dot(side, tilt), 0.0);
    const Point3 folding = r + 0.5 * cross(tilt, side);
    const Point3 flat = r + 0.5 * cross(Vec3{0, 0, 1}, side);
    ASSERT_EQ(diametric_condition(p, q, r, s), FlipVerdict::Flippable);
    const Vec3 n_qrs = triangle_normal_raw(q, r, s);
    ASSERT_GT(dot(tilt, triangle_normal_raw(p, q, r)), 0.0);  // no fold before the flip
    ASSERT_LE(dot(tilt, n_qrs), 0.0);                          // a fold after it
    for (const bool fold : {true, false}) {
        TriangleSoup soup;
        soup.points = {p, q, r, s, fold ? folding : flat};
        soup.triangles = {{0, 1, 2}, {1, 0, 3}, {2, 1, 4}};
        const SurfaceMesh m = SurfaceMesh::from_soup(soup);
        const Edge pq = m.find_edge(Vertex(0), Vertex(1));
        EXPECT_EQ(flip_verdict(m, pq, FlipRule::DiametricBallNoFold),
                  fold ? FlipVerdict::Degenerate : FlipVerdict::Flippable)
            << (fold ? "folding" : "flat") << " neighbour";
        EXPECT_EQ(flip_verdict(m, pq, FlipRule::DiametricBall), FlipVerdict::Flippable);  // the plain rule
    }
}

TEST(DiametricNoFoldRule, AllowsAFlipThatUnfoldsMoreThanItFolds) {
    // The quad of the test above, with the folding neighbour across qr, and neighbours across
    // ps and sq that fold against qps but not against the new faces. The flip makes one fold
    // and removes one (ps alone): refused; it makes one and removes two (ps and sq): an
    // update mends a folded patch that way, and the flip is taken.
    const Point3 p{-1, 0, 0}, q{1, 0, 0}, r{0, 0.5, 0}, s{0, -0.5, -0.4};
    const Vec3 n_qr{0.5, 1, 0.3}, n_ps{0.7, 1, 0.5}, n_sq{-0.7, 1, 0.5};  // the neighbours' normals
    ASSERT_EQ(dot(n_qr, q - r), 0.0);
    ASSERT_NEAR(dot(n_ps, s - p), 0.0, 1e-15);
    ASSERT_NEAR(dot(n_sq, q - s), 0.0, 1e-15);
    const Vec3 old_qps = triangle_normal_raw(q, p, s), new_psr = triangle_normal_raw(p, s, r),
               new_qrs = triangle_normal_raw(q, r, s);
    ASSERT_LE(dot(n_ps, old_qps), 0.0);
    ASSERT_GT(dot(n_ps, new_psr), 0.0);
    ASSERT_LE(dot(n_sq, old_qps), 0.0);
    ASSERT_GT(dot(n_sq, new_qrs), 0.0);
    for (const bool both : {false, true}) {
        TriangleSoup soup;
        soup.points = {p, q, r, s, r + 0.5 * cross(n_qr, q - r), s + 0.5 * cross(n_ps, p - s),
                       q + 0.5 * cross(n_sq, s - q)};
        soup.triangles = {{0, 1, 2}, {1, 0, 3}, {2, 1, 4}, {3, 0, 5}};
        if (both) soup.triangles.push_back({1, 3, 6});
        const SurfaceMesh m = SurfaceMesh::from_soup(soup);
        EXPECT_EQ(flip_verdict(m, m.find_edge(Vertex(0), Vertex(1)), FlipRule::DiametricBallNoFold),
                  both ? FlipVerdict::Flippable : FlipVerdict::Degenerate)
            << (both ? "two folds removed" : "one fold removed");
    }
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
    EXPECT_EQ(parse_flip_rule("delaunay-nofold"), FlipRule::DiametricBallNoFold);
    EXPECT_EQ(to_string(FlipRule::DiametricBallNoFold), "delaunay-nofold");
    EXPECT_THROW((void)parse_flip_rule("bogus"), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
