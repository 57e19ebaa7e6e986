#include "dynmesh/probing/device.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dynmesh/probing/oracles.hpp"

namespace dynmesh {
namespace {

struct Fixture {
    SphereOracle sphere{Sphere({0, 0, 0}, 1)};
    Ball omega{{0, 0, 0}, 2};
};

TEST(ProbingDevice, PlaceOutsideOmegaOnly) {
    Fixture f;
    ProbingDevice dev(f.sphere, f.omega, &f.sphere);
    EXPECT_THROW((void)dev.cast({1, 0, 0}, 1), InvalidInput);  // not placed
    EXPECT_THROW(dev.place({1.5, 0, 0}), InvalidInput);
    EXPECT_FALSE(dev.placed());
    dev.place({2, 0, 0});
    EXPECT_TRUE(dev.placed());
    dev.place({0, 0, 2 - 1e-7});  // within the margin 1e-6 R of ∂Ω
}

TEST(ProbingDevice, MonitorRefusesAMoveThroughTheObject) {
    Fixture f;
    ProbingDevice dev(f.sphere, f.omega, &f.sphere);
    dev.place({-2, 0, 0});
    try {
        dev.move_to({2, 0, 0});
        FAIL() << "a move through the sphere was accepted";
    } catch (const UnsafeMove& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("(-2, 0, 0)"), std::string::npos) << m;
        EXPECT_NE(m.find("(2, 0, 0)"), std::string::npos) << m;
    }
    EXPECT_EQ(dev.position(), (Point3{-2, 0, 0}));
    EXPECT_EQ(dev.counters().segments, 0u);
    dev.move_to({-1.5, 0, 0});  // free
    EXPECT_EQ(dev.counters().segments, 1u);
    EXPECT_THROW(dev.move_to({-0.5, 0, 0}), UnsafeMove);  // into O
}

TEST(ProbingDevice, WithoutMonitorTheMoveIsCounted) {
    Fixture f;
    ProbingDevice dev(f.sphere, f.omega);
    dev.place({-3, 0, 0});
    dev.move_to({3, 0, 0});
    EXPECT_EQ(dev.counters().segments, 1u);
    EXPECT_NEAR(dev.counters().inside_length, 4, 1e-12);
    EXPECT_NEAR(dev.counters().exterior_length, 2, 1e-12);
}

TEST(ProbingDevice, ExteriorMoveLengthIsTheArcFormula) {
    Fixture f;
    ProbingDevice dev(f.sphere, f.omega, &f.sphere);
    dev.set_recording(true);
    dev.place({3, 0, 0});
    dev.move_exterior({0, 2.5, 0});  // 1 + 2 · π/2 + 0.5
    EXPECT_NEAR(dev.counters().exterior_length, 1.5 + std::numbers::pi, 1e-12);
    dev.move_exterior({0, -2, 0});  // antipodal on ∂Ω: 0.5 + 2π
    EXPECT_NEAR(dev.counters().exterior_length, 2 + 3 * std::numbers::pi, 1e-12);
    EXPECT_EQ(dev.counters().exterior_moves, 2u);
    EXPECT_EQ(dev.counters().segments, 0u);
    EXPECT_EQ(dev.counters().inside_length, 0);
    EXPECT_THROW(dev.move_exterior({0, 0, 1.5}), InvalidInput);  // inside Ω
    // The recorded path stays on or outside ∂Ω and ends at the position.
    ASSERT_EQ(dev.recorded_paths().size(), 1u);
    const auto& path = dev.recorded_paths()[0];
    // Arcs recorded every 10° (90° then 180°), with the radial ends.
    EXPECT_GE(path.size(), 1 + 9 + 18u);
    for (const Point3& p : path) EXPECT_GE(norm(p), 2 - 1e-12);
    EXPECT_EQ(path.back(), dev.position());
}

TEST(ProbingDevice, MonitorChecksTheExteriorPath) {
    // An Ω whose boundary cuts through the object: the arc from angle 0 to 120° in the xy
    // plane passes through the ball's centre (0, 1.2, 0), while both ends are free.
    const SphereOracle ball(Sphere({0, 1.2, 0}, 0.5));
    const Ball omega{{0, 0, 0}, 1.2};
    const Point3 a{1.2, 0, 0}, b{-0.6, 1.2 * std::sqrt(0.75), 0};
    ASSERT_TRUE(ball.is_free(a) && ball.is_free(b));
    ProbingDevice dev(ball, omega, &ball);
    dev.place(a);
    EXPECT_THROW(dev.move_exterior(b), UnsafeMove);
    EXPECT_EQ(dev.position(), a);
    EXPECT_EQ(dev.counters().exterior_moves, 0u);
    ProbingDevice blind(ball, omega);
    blind.place(a);
    blind.move_exterior(b);
    EXPECT_NEAR(blind.counters().exterior_length, 1.2 * 2 * std::numbers::pi / 3, 1e-12);
}

TEST(ProbingDevice, CastCountsProbes) {
    Fixture f;
    ProbingDevice dev(f.sphere, f.omega, &f.sphere);
    dev.place({0, 0, 2});
    const auto h = dev.cast({0, 0, -1}, 4);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 1, 1e-12);
    EXPECT_FALSE(dev.cast({0, 0, 1}, 4));
    EXPECT_EQ(dev.counters().probes, 2u);
    dev.move_to({0, 0, 1.5});
    EXPECT_NEAR(dev.cast({0, 0, -1}, 4)->t, 0.5, 1e-12);
    EXPECT_EQ(dev.counters().probes, 3u);
    EXPECT_NEAR(dev.counters().inside_length, 0.5, 1e-12);
}

TEST(LengthInside, Cases) {
    const Ball b{{0, 0, 0}, 1};
    EXPECT_NEAR(length_inside(b, {-2, 0, 0}, {2, 0, 0}), 2, 1e-15);
    EXPECT_NEAR(length_inside(b, {0, 0, 0}, {2, 0, 0}), 1, 1e-15);
    EXPECT_EQ(length_inside(b, {-2, 2, 0}, {2, 2, 0}), 0);
}

}  // namespace
}  // namespace dynmesh
