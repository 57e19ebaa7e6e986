#include "dynmesh/skin/safe_duration.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dynmesh {
namespace {

/// specs/skin-surfaces.md §4.4 tables, with the values of §8 correction 8 (Δt in units of ϱ0²,
/// triangle durations before κ_t), at the defaults Q0 = 1.75, Q1 = 2.25.
TEST(SafeDuration, TheDigestsTables) {
    const SkinQuality q;
    const double edge_gamma[] = {1.0, 1.1, 1.25, 1.5, 2.0, 3.0};
    const double eps_e[] = {0.1250, 0.1716, 0.2329, 0.3171, 0.4400, 0.5882};
    const double dt_e[] = {0.4688, 0.6275, 0.8230, 1.0672, 1.3728, 1.6609};
    for (int i = 0; i < 6; ++i) {
        EXPECT_NEAR(edge_epsilon(edge_gamma[i], q), eps_e[i], 5e-5) << edge_gamma[i];
        EXPECT_NEAR(edge_safe_duration(edge_gamma[i], 1, q), dt_e[i], 5e-5) << edge_gamma[i];
        // Δt scales with ϱ0².
        EXPECT_NEAR(edge_safe_duration(edge_gamma[i], 3, q), 9 * dt_e[i], 9 * 5e-5);
    }
    const double tri_gamma[] = {1.0, 0.9, 0.8, 0.7, 0.5, 0.25};
    const double eps_t[] = {0.0609, 0.0853, 0.1118, 0.1410, 0.2103, 0.3360};
    const double dt_t[] = {0.2362, 0.3267, 0.4224, 0.5243, 0.7528, 1.1181};
    for (int i = 0; i < 6; ++i) {
        EXPECT_NEAR(triangle_epsilon(tri_gamma[i], q), eps_t[i], 5e-5) << tri_gamma[i];
        EXPECT_NEAR(triangle_safe_duration(tri_gamma[i], 1, q), q.kappa_t * dt_t[i], 5e-5) << tri_gamma[i];
    }
    // Other buffer widths at γ = 1: (ε_e, ε_t) for Q0/Q1 = 0.9, 0.8, 0.7.
    const double ratio[] = {0.9, 0.8, 0.7}, e[] = {0.053, 0.111, 0.176}, t[] = {0.026, 0.054, 0.085};
    for (int i = 0; i < 3; ++i) {
        const SkinQuality w{.Q0 = ratio[i] * 2.25, .Q1 = 2.25};
        EXPECT_NEAR(edge_epsilon(1, w), e[i], 5e-4);
        EXPECT_NEAR(triangle_epsilon(1, w), t[i], 5e-4);
    }
}

TEST(SafeDuration, ElementsAtOrBeyondTheQ1ThresholdGetNoTime) {
    const SkinQuality q;
    EXPECT_EQ(edge_safe_duration(q.Q0 / q.Q1, 1, q), 0);
    EXPECT_EQ(edge_safe_duration(0.5, 1, q), 0);
    EXPECT_GT(edge_safe_duration(q.Q0 / q.Q1 + 1e-6, 1, q), 0);
    EXPECT_EQ(triangle_safe_duration(q.Q1 / q.Q0, 1, q), 0);
    EXPECT_GT(triangle_safe_duration(q.Q1 / q.Q0 - 1e-6, 1, q), 0);
}

/// §4.2: over travel_duration(ε, ϱ0) the extreme case, a point on a void sphere heading for its
/// centre (ϱ² falling at rate exactly 1/2), ends with ϱ = (1 − ε)ϱ0.
TEST(SafeDuration, TravelDurationIsTheVoidSpheresTime) {
    for (double eps : {0.05, 0.125, 0.3, 0.6})
        for (double rho0 : {0.1, 1.0, 7.0}) {
            const double dt = travel_duration(eps, rho0);
            EXPECT_NEAR(std::sqrt(rho0 * rho0 - dt / 2), (1 - eps) * rho0, 1e-12 * rho0);
        }
}

/// §8 correction 2: only an element that was in range at its previous check is a miss.
TEST(SafeDuration, BeyondTheThresholdIsAMissOnlyAfterAnInRangeCheck) {
    for (bool floored : {false, true}) {
        EXPECT_EQ(classify_beyond(false, false, floored), BeyondCount::BornBad);
        EXPECT_EQ(classify_beyond(false, true, floored), BeyondCount::BornBad);  // a stale state of another element
        // In range before, under the floor or not: the schedule should have caught it.
        EXPECT_EQ(classify_beyond(true, false, floored), BeyondCount::Miss);
    }
    EXPECT_EQ(classify_beyond(true, true, false), BeyondCount::StillBad);
    // Beyond but excluded by the floor before: its exclusion cleared, born bad (not still bad).
    EXPECT_EQ(classify_beyond(true, true, true), BeyondCount::LeftFloor);
}

TEST(SafeDuration, MinimumAngleFloorAndFeasibility) {
    EXPECT_NEAR(min_angle_floor_deg(2.25), 11.39, 0.005);
    EXPECT_NEAR(min_angle_floor_deg(1.75), 19.0, 0.1);  // "about 11.4° and 19°" (§5)
    EXPECT_TRUE(feasibility_problems({}).empty());
    const auto f1 = feasibility_problems({.C = 0.12, .Q0 = 1.6, .Q1 = 2.25});
    ASSERT_FALSE(f1.empty());
    EXPECT_EQ(f1.front().rfind("F1", 0), 0u) << f1.front();
    const auto f3 = feasibility_problems({.C = 0.12, .Q0 = 1.75, .Q1 = 1.9});
    ASSERT_EQ(f3.size(), 1u);
    EXPECT_EQ(f3.front().rfind("F3", 0), 0u) << f3.front();
    const auto f4 = feasibility_problems({.C = 0.2, .Q0 = 1.9, .Q1 = 2.25});
    ASSERT_FALSE(f4.empty());
    EXPECT_EQ(f4.back().rfind("F4", 0), 0u) << f4.back();
    EXPECT_FALSE(feasibility_problems({.C = 0.12, .Q0 = 2.25, .Q1 = 1.75}).empty());
    EXPECT_FALSE(feasibility_problems({.kappa_t = 0}).empty());
}

}  // namespace
}  // namespace dynmesh
