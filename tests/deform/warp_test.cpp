#include "dynmesh/deform/warp.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/metrics/self_intersection.hpp"
#include "scenario_cases.hpp"

namespace dynmesh {
namespace {

using namespace test;

TEST(Warp, IsExactlyTheIdentityAtTimeZeroAndCloses) {
    for (const std::string& key : all_cases()) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        const auto& p = s.reference.positions();
        double back = 0, moved = 0;
        for (const Point3& x : p) {
            ASSERT_EQ(s.warp->apply(0.0, x), x);
            back = std::max(back, distance(s.warp->apply(s.time_units, x), x));
            for (double f : {0.25, 0.5})  // the twist swings: straight again at 0.5
                moved = std::max(moved, distance(s.warp->apply(f * s.time_units, x), x));
        }
        EXPECT_LT(back, 1e-9 * s.length_scale);  // one full cycle
        // And it really moves (the dimples move locally, by about one sample spacing).
        EXPECT_GT(moved, key == "dimple" ? s.h0 : 0.05 * s.length_scale);
    }
}

TEST(Warp, AnalyticShapesAtThePeak) {
    // Pulse: radius 1.5 at half-cycle; stretch: the ellipsoid 3:1:1.
    const Scenario& pulse = cached("pulse");
    const Scenario& stretch = cached("stretch");
    const double t = 0.5 * kSteps;
    for (std::size_t i = 0; i < pulse.pool_size(); i += 13) {
        EXPECT_NEAR(norm(pulse.warp->apply(t, pulse.reference.positions()[i])), 1.5, 1e-12);
        const Point3 q = stretch.warp->apply(t, stretch.reference.positions()[i]);
        EXPECT_NEAR(q.x * q.x / 9 + q.y * q.y + q.z * q.z, 1.0, 1e-12);
    }
    // Bend: the stretched x axis becomes an arc turning by 2 pi / 3 at the peak.
    const Scenario& bend = cached("bend");
    const Point3 tip = bend.warp->apply(t, Point3{1, 0, 0});
    const double rho = 6.0 / (2 * kPi / 3);
    EXPECT_NEAR(tip.x, rho * std::sin(kPi / 3), 1e-9);
    EXPECT_NEAR(tip.y, rho * (1 - std::cos(kPi / 3)), 1e-9);
    // At a quarter cycle the sphere is fully stretched but not yet bent.
    const Point3 q = bend.warp->apply(0.25 * kSteps, Point3{1, 0, 0});
    EXPECT_NEAR(distance(q, Point3{3, 0, 0}), 0, 1e-9);
}

TEST(Warp, LambdaBoundsTheDisplacementPerTimeUnit) {
    for (const std::string& key : all_cases()) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        const auto& p = s.reference.positions();
        double worst = 0;
        for (double t = 0; t <= s.time_units - 1 + 1e-9; t += 0.25) {
            for (const Point3& x : p)
                worst = std::max(worst, distance(s.warp->apply(t + 1, x), s.warp->apply(t, x)));
        }
        EXPECT_LE(worst, s.lambda);
        EXPECT_GT(worst, s.lambda / 1.25) << "lambda is far from tight";
    }
}

TEST(Warp, StaysEmbeddedAndOrientedOnTheReference) {
    for (const std::string& key : all_cases()) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        for (double f : {0.25, 0.5, 0.75}) {
            const SurfaceMesh m = warped_reference(s, f * s.time_units);
            EXPECT_EQ(count_self_intersections(m), 0u) << "t = " << f * s.time_units;
            EXPECT_GT(signed_volume(m), 0);
        }
    }
}

TEST(Warp, NormalsAndAreaScale) {
    const Scenario& pulse = cached("pulse");
    const double peak = 0.5 * kSteps;
    for (std::uint32_t i = 0; i < pulse.pool_size(); i += 101) {
        EXPECT_NEAR(area_scale(pulse, peak, i), 2.25, 1e-6);
        EXPECT_NEAR(area_scale(pulse, 0.0, i), 1.0, 1e-6);
        const Vec3 n = surface_normal(pulse, peak, i);
        EXPECT_NEAR(distance(n, normalized(pulse.reference.positions()[i])), 0, 1e-6);
    }
    // Stretch: the true normal of the ellipsoid at the image point.
    const Scenario& st = cached("stretch");
    for (std::uint32_t i = 0; i < st.pool_size(); i += 101) {
        const Point3 q = st.warp->apply(peak, st.reference.positions()[i]);
        const Vec3 exact = normalized(Vec3{q.x / 9, q.y, q.z});
        EXPECT_NEAR(distance(surface_normal(st, peak, i), exact), 0, 1e-6);
    }
    // Rotation: rigid, so area is preserved.
    const Scenario& rot = cached("rotate");
    for (std::uint32_t i = 0; i < rot.pool_size(); i += 101)
        EXPECT_NEAR(area_scale(rot, 3.7, i), 1.0, 1e-6);
}

TEST(Warp, DimpleMovesDisjointPatchesOutAndBack) {
    // Two centres on the unit sphere, 1 apart; radius 0.3; slides of 0.1 (L = 0.57).
    const std::vector<Point3> c{{1, 0, 0}, normalized(Point3{1, 1, 0})};
    const std::vector<Vec3> d{{0, 0.1, 0.02}, {0, 0, -0.1}};
    const double rate = 0.01;  // period 100
    const auto w = make_dimple_warp(c, d, 0.3, rate);
    EXPECT_EQ(w->name(), "dimple");
    EXPECT_EQ(w->apply(0.0, c[0]), c[0]);
    EXPECT_NEAR(distance(w->apply(50.0, c[0]), c[0] + d[0]), 0, 1e-15);  // the peak
    EXPECT_NEAR(distance(w->apply(50.0, c[1]), c[1] + d[1]), 0, 1e-15);
    EXPECT_NEAR(distance(w->apply(25.0, c[0]), c[0] + d[0] * 0.5), 0, 1e-15);
    EXPECT_NEAR(distance(w->apply(100.0, c[0]), c[0]), 0, 1e-15);  // back after one period
    // The bump: half way out at the peak, nothing at the rim and beyond.
    const Point3 mid = c[0] + Vec3{0, 0, 0.15};
    EXPECT_NEAR(distance(w->apply(50.0, mid), mid + d[0] * dimple_bump(0.5)), 0, 1e-15);
    EXPECT_DOUBLE_EQ(dimple_bump(0.5), 0.421875);
    EXPECT_EQ(dimple_bump(1.0), 0.0);
    EXPECT_EQ(dimple_bump(0.0), 1.0);
    for (const Point3 x : {Point3{-1, 0, 0}, Point3{0, 0, 1}, c[0] + Vec3{0, 0, 0.3},
                           Point3{0.7, -0.7, 0}})
        for (double t : {10.0, 50.0, 77.0}) EXPECT_EQ(w->apply(t, x), x);
    // The largest slope of the bump is kDimpleBumpSlope.
    double slope = 0;
    for (int i = 0; i < 10000; ++i) {
        const double r = i / 10000.0, e = 1e-7;
        slope = std::max(slope, std::abs(dimple_bump(r + e) - dimple_bump(r)) / e);
    }
    EXPECT_NEAR(slope, kDimpleBumpSlope, 1e-6);
    // Injective near the surface: distinct points of a grid around c[0] stay distinct and
    // keep their order along the slide direction (the field is a contraction, L < 1).
    for (double y = -0.35; y <= 0.35; y += 0.01) {
        const Point3 a = c[0] + Vec3{0, y, 0}, b = c[0] + Vec3{0, y + 0.01, 0};
        EXPECT_GT(w->apply(50.0, b).y - w->apply(50.0, a).y, 0.0) << y;
    }
}

TEST(Warp, DimpleScenarioFollowsSpecS4) {
    const Scenario& s = cached("dimple");
    EXPECT_EQ(s.name, "dimple");
    EXPECT_NE(s.description.find("dimples"), std::string::npos);
    EXPECT_FALSE(s.edits);
    ASSERT_TRUE(s.surface0 != nullptr);
    const double peak = 0.5 * s.time_units;
    const double reach = 1.0307764064044151 * s.h0;  // |h0 t_k + h0/4 c_k|
    std::size_t moved = 0;
    double largest = 0;
    for (const Point3& x : s.reference.positions()) {
        const double m = distance(s.warp->apply(peak, x), x);
        if (m > 0) ++moved;
        largest = std::max(largest, m);
    }
    // Several disjoint patches move by up to about h0, and the rest of the sphere stays put.
    EXPECT_LE(largest, reach * (1 + 1e-12));
    EXPECT_GT(largest, 0.97 * reach);
    EXPECT_GT(moved, s.pool_size() / 5);
    EXPECT_LT(moved, s.pool_size() * 4 / 5);
    // lambda is the speed at a centre, pi * rate * reach, with the 5% margin.
    EXPECT_NEAR(s.lambda, 1.05 * kPi * s.rate * reach, 0.02 * s.lambda);
    // Its own warp name is accepted, another one is not.
    ScenarioOptions o;
    o.samples = 500;
    o.steps = 10;
    o.warp = "dimple";
    EXPECT_EQ(make_scenario("dimple", o).name, "dimple");
    o.warp = "bend";
    expect_invalid([&] { (void)make_scenario("dimple", o); }, "own motion");
}

TEST(Warp, FibonacciSphere) {
    for (std::size_t n : {1u, 2u, 16u, 64u}) {
        const auto p = fibonacci_sphere(n);
        ASSERT_EQ(p.size(), n);
        for (std::size_t i = 0; i < n; ++i) {
            EXPECT_NEAR(norm(p[i]), 1.0, 1e-15);
            EXPECT_LT(std::abs(p[i].z), 1.0);  // never a pole
            if (i > 0) {
                EXPECT_LT(p[i].z, p[i - 1].z);
            }
        }
    }
    expect_invalid([] { (void)fibonacci_sphere(0); }, "n must be");
}

TEST(Warp, FactoriesRejectBadParameters) {
    expect_invalid([] { (void)make_pulse_warp({0, 0, 0}, 1.5, 0.0); }, "rate");
    expect_invalid([] { (void)make_stretch_warp({0, 0, 0}, {0, 0, 0}, 3, 1); }, "axis");
    expect_invalid([] { (void)make_twist_warp({0, 0, 0}, {1, 0, 0}, -1, 1, 1); }, "half_length");
    expect_invalid([] { (void)make_bend_warp({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, 1, 1, 1, 1); },
                   "parallel");
    expect_invalid([] { (void)make_bend_warp({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1, 7, 1, 1); },
                   "max_turn");
    const std::vector<Point3> two{{1, 0, 0}, {0, 1, 0}};  // sqrt 2 apart
    const std::vector<Vec3> small{{0, 0.1, 0}, {0, 0, 0.1}};
    expect_invalid([&] { (void)make_dimple_warp(two, small, 0.8, 1); }, "supports overlap");
    expect_invalid([&] { (void)make_dimple_warp(two, {{0, 0.5, 0}, {0, 0, 0}}, 0.5, 1); },
                   "Lipschitz");
    expect_invalid([&] { (void)make_dimple_warp(two, {{0, 0.1, 0}}, 0.5, 1); },
                   "2 centres but 1 displacements");
    expect_invalid([] { (void)make_dimple_warp({}, {}, 0.5, 1); }, "no centre");
    expect_invalid([&] { (void)make_dimple_warp(two, small, 0.0, 1); }, "radius");
    expect_invalid([&] { (void)make_dimple_warp(two, small, 0.5, -1); }, "rate");
    expect_invalid([&] { (void)make_dimple_warp(two, {{0, NAN, 0}, {0, 0, 0}}, 0.5, 1); },
                   "not finite");
}

}  // namespace
}  // namespace dynmesh
