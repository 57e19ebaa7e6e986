#include "dynmesh/skin/critical_events.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

namespace dynmesh {
namespace {

using Kind = SkinEvent::Kind;

std::map<Kind, int> count_by_kind(const std::vector<SkinEvent>& ev) {
    std::map<Kind, int> n;
    for (const SkinEvent& e : ev) ++n[e.kind];
    return n;
}

/// Two equal balls (±1, 0, 0), weight w: both born at −w, the neck forms at the midpoint when
/// the grown weights reach the half-distance squared, t = 1 − w.
TEST(CriticalEvents, TwoBalls) {
    const double w = 2.0;
    const SkinFunction phi({{{-1, 0, 0}, w}, {{1, 0, 0}, w}}, 0.5);
    const auto ev = critical_events(phi, -10);
    ASSERT_EQ(ev.size(), 3u);
    EXPECT_EQ(ev[0].kind, Kind::Birth);
    EXPECT_EQ(ev[1].kind, Kind::Birth);
    EXPECT_NEAR(ev[0].time, -w, 1e-12);
    EXPECT_EQ(ev[2].kind, Kind::Neck);
    EXPECT_NEAR(ev[2].time, 1 - w, 1e-12);
    EXPECT_NEAR(norm(ev[2].where), 0, 1e-12);
    // Far apart (no neck by t = 0): only the births.
    const SkinFunction far({{{-3, 0, 0}, w}, {{3, 0, 0}, w}}, 0.5);
    EXPECT_EQ(critical_events(far, -10).size(), 2u);
}

/// §8 correction 5: four balls at the even-parity cube corners, weight 3.5: 4 births at −3.5,
/// 6 necks at 2 − w = −1.5, 4 tunnel closures at 8/3 − w, the void's death at 3 − w = −0.5.
TEST(CriticalEvents, TheFourBallExample) {
    const double w = 3.5;
    std::vector<WeightedPoint> B;
    for (const Point3& p : {Point3{1, -1, -1}, Point3{1, 1, 1}, Point3{-1, 1, -1}, Point3{-1, -1, 1}}) B.push_back({p, w});
    const SkinFunction phi(B, 0.5);
    const auto ev = critical_events(phi, -10);
    const auto n = count_by_kind(ev);
    EXPECT_EQ(n.at(Kind::Birth), 4);
    EXPECT_EQ(n.at(Kind::Neck), 6);
    EXPECT_EQ(n.at(Kind::TunnelClose), 4);
    EXPECT_EQ(n.at(Kind::Death), 1);
    for (const SkinEvent& e : ev) {
        const double expect = e.kind == Kind::Birth ? -w : e.kind == Kind::Neck ? 2 - w
                            : e.kind == Kind::TunnelClose ? 8.0 / 3 - w : 3 - w;
        EXPECT_NEAR(e.time, expect, 1e-12) << int(e.kind);
    }
    EXPECT_NEAR(norm(ev.back().where), 0, 1e-12);  // the void dies at the centre
    // The Euler characteristic after all events: births +1... each event changes χ of the body by
    // (−1)^dim, so χ(skin) = 2·Σ(−1)^dim over the events up to t (a sphere: 2).
    int chi = 0;
    for (const SkinEvent& e : ev) chi += 2 * ((int(e.kind) % 2 == 0) ? 1 : -1);
    EXPECT_EQ(chi, 2);
    // CGAL's example (w = 2.5, §8 correction 5): at t = 0 genus 3, χ = −4, no void yet.
    std::vector<WeightedPoint> C = B;
    for (auto& b : C) b.weight = 2.5;
    int chi_c = 0;
    for (const SkinEvent& e : critical_events(SkinFunction(C, 0.5), -10)) chi_c += 2 * ((int(e.kind) % 2 == 0) ? 1 : -1);
    EXPECT_EQ(chi_c, -4);
}

/// Three equal balls, one just off the middle of the segment between the other two: the long
/// edge (its midpoint is covered by the third ball) and the obtuse triangle (its orthocentre lies
/// outside it) are attached, not critical, though their W is below 0: 3 births, 2 necks, χ = 2.
TEST(CriticalEvents, AttachedSimplicesAreNotEvents) {
    const double w = 20;
    const SkinFunction phi({{{-2, 0, 0}, w}, {{2, 0, 0}, w}, {{0, 0.5, 0}, w}}, 0.5);
    int uncritical_below_zero = 0;
    for (const SkinSimplex& sx : phi.simplices())
        if (sx.W <= 0 && sx.dim > 0 && std::size_t(sx.vertices[std::size_t(sx.dim)]) < 3) ++uncritical_below_zero;
    EXPECT_EQ(uncritical_below_zero, 4);  // three edges and the triangle have W <= 0
    const auto ev = critical_events(phi, -100);
    const auto n = count_by_kind(ev);
    EXPECT_EQ(n.at(Kind::Birth), 3);
    EXPECT_EQ(n.at(Kind::Neck), 2);
    EXPECT_EQ(n.count(Kind::TunnelClose), 0u);
    for (const SkinEvent& e : ev) {
        if (e.kind == Kind::Neck) {
            EXPECT_NEAR(e.time, 4.25 / 4 - w, 1e-12);
        }
    }
}

/// A ring of 8 balls: 8 births, 8 necks, and no tunnel closure by t = 0: a torus (χ 0).
TEST(CriticalEvents, RingIsATorus) {
    std::vector<WeightedPoint> B;
    for (int i = 0; i < 8; ++i) {
        const double a = 2 * M_PI * i / 8;
        B.push_back({{3 * std::cos(a), 3 * std::sin(a), 0}, 1.6});
    }
    const auto ev = critical_events(SkinFunction(B, 0.5), -10);
    const auto n = count_by_kind(ev);
    EXPECT_EQ(n.at(Kind::Birth), 8);
    EXPECT_EQ(n.at(Kind::Neck), 8);
    EXPECT_EQ(n.count(Kind::TunnelClose), 0u);
    int chi = 0;
    for (const SkinEvent& e : ev) chi += 2 * ((int(e.kind) % 2 == 0) ? 1 : -1);
    EXPECT_EQ(chi, 0);
}

}  // namespace
}  // namespace dynmesh
