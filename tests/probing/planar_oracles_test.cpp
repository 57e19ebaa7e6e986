#include "dynmesh/probing/oracles2.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"

namespace dynmesh {
namespace {

TEST(CircleOracle2, HitsTangentsAndStart) {
    const CircleOracle2 o({1, 1}, 2), strict({1, 1}, 2, {.strict = true});
    const auto h = o.cast({-4, 1, 0}, {1, 0, 0}, 10);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 3, 1e-12);
    EXPECT_FALSE(h->grazing);
    EXPECT_FALSE(o.cast({-4, 1, 0}, {1, 0, 0}, 3 - 1e-9));
    // Tangent at (1, 3): grazing, or nothing in strict mode.
    const auto g = o.cast({-4, 3, 0}, {1, 0, 0}, 10);
    ASSERT_TRUE(g);
    EXPECT_TRUE(g->grazing);
    EXPECT_FALSE(strict.cast({-4, 3, 0}, {1, 0, 0}, 10));
    EXPECT_THROW((void)o.cast({1, 1, 0}, {1, 0, 0}, 10), InvalidInput);
    EXPECT_NEAR(o.reach(), 2, 1e-9);
    EXPECT_NEAR(o.area(), 4 * std::numbers::pi, 1e-9);  // the length
    EXPECT_NEAR(o.distance({5, 1, 0}), 2, 1e-12);
}

TEST(StarOracle2, HitsAgreeWithTheCurve) {
    const StarOracle2 o({0, 0}, 1);
    // Peak at φ = 0 (r = 1.2), valley at φ = 60° (r = 0.8).
    const auto peak = o.cast({5, 0, 0}, {-1, 0, 0}, 10);
    ASSERT_TRUE(peak);
    EXPECT_NEAR(peak->t, 5 - 1.2, 1e-12);
    const Vec3 u{std::cos(std::numbers::pi / 3), std::sin(std::numbers::pi / 3), 0};
    const auto valley = o.cast(5.0 * u, -u, 10);
    ASSERT_TRUE(valley);
    EXPECT_NEAR(valley->t, 5 - 0.8, 1e-12);
    // Radius of curvature at the peaks: r²... = 1.728 / 3.6 = 0.48.
    EXPECT_NEAR(o.reach(), 0.48, 1e-6);
    Rng rng(5);
    int hits = 0;
    for (int k = 0; k < 300; ++k) {
        const double a = rng.uniform(0, 2 * std::numbers::pi);
        const Point3 s{3 * std::cos(a), 3 * std::sin(a), 0};
        const Point3 target{rng.uniform(-1.3, 1.3), rng.uniform(-1.3, 1.3), 0};
        const Vec3 d = normalized(target - s);
        const auto h = o.cast(s, d, 10);
        if (!h) continue;
        ++hits;
        EXPECT_GT(o.value(s + (h->t - 1e-7) * d), 0);
        EXPECT_LT(o.value(s + (h->t + 1e-7) * d), 0);
        EXPECT_NEAR(o.distance(h->x), 0, 1e-9);
        for (int i = 0; i < 500; ++i) EXPECT_GE(o.value(s + (h->t * i / 500.0) * d), -1e-12);
    }
    EXPECT_GT(hits, 150);
    for (const Point3& p : o.sample_surface(0.05)) EXPECT_NEAR(o.value(p), 0, 1e-12);
}

TEST(StarOracle2, FromSpec) {
    const auto s = make_probe_object("star2:2");
    ASSERT_NE(dynamic_cast<const StarOracle2*>(s.object.get()), nullptr);
    EXPECT_FALSE(s.object->is_free(s.interior_points.at(0)));
    EXPECT_GE(s.omega.radius, 2.4);
    EXPECT_THROW((void)make_probe_object("circle2:0"), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
