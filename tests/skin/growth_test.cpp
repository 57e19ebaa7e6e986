#include "dynmesh/skin/growth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dynmesh/error.hpp"
#include "skin_inputs.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/skin/check.hpp"
#include "dynmesh/skin/critical_events.hpp"

namespace dynmesh {
namespace {

using test::four_balls;
using test::ring;

TEST(SkinGrowth, InradiusBallLiesInTheMixedCell) {
    // Every critical simplex of a random set: points within the inradius of z_δ are in μ_δ,
    // and some point a little beyond it is not (the bound is tight).
    Rng rng(7);
    std::vector<WeightedPoint> B;
    for (int i = 0; i < 30; ++i) B.push_back({{rng.uniform(0, 6), rng.uniform(0, 6), rng.uniform(0, 6)}, rng.uniform(1, 3)});
    const SkinFunction phi(B, 0.5);
    std::size_t tested = 0;
    for (const SkinEvent& ev : critical_events(phi, -10, 10)) {
        const double r = mixed_cell_inradius(phi, ev.simplex);
        ASSERT_GT(r, 0) << "simplex " << ev.simplex;
        bool outside_found = false;
        for (int k = 0; k < 400; ++k) {
            const Vec3 d = normalized(Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
            EXPECT_TRUE(phi.in_mixed_cell(ev.simplex, ev.where + 0.999 * r * d)) << "simplex " << ev.simplex;
            outside_found |= !phi.in_mixed_cell(ev.simplex, ev.where + 1.3 * r * d);
        }
        EXPECT_TRUE(outside_found) << "simplex " << ev.simplex << " dim " << int(ev.kind);
        ++tested;
    }
    EXPECT_GT(tested, 30u);
}

struct GrowthCase {
    std::string name;
    std::vector<WeightedPoint> balls;
};

/// Grows the skin with the auditor on and checks every snapshot (§6.2, §6.3): a closed
/// oriented manifold with the alpha complex's components and Euler characteristic, vertices on
/// the skin, every non-exempt triangle above the angle floor; zero misses.
SkinGrowthReport grow_and_check(const GrowthCase& c, SkinSchedule schedule, std::size_t snapshots = 12) {
    const SkinFunction phi(c.balls, 0.5);
    SkinGrowthOptions o;
    o.schedule = schedule;
    o.snapshots = snapshots;
    o.audit = true;
    std::size_t seen = 0;
    o.on_snapshot = [&](const SkinSnapshot& snap) {
        ++seen;
        if (snap.mesh.n_faces() == 0) return;
        SkinMeshCheckOptions co;
        co.time = snap.time;
        co.exempt = snap.exempt;
        co.rho_floor = 0;
        co.max_normal_deviation_deg = 60;
        const CheckReport chk = check_skin_mesh(phi, snap.mesh, co);
        std::string problems;
        for (const auto& p : chk.problems) problems += "\n  " + p;
        EXPECT_TRUE(chk.ok()) << c.name << " at t = " << snap.time << problems;
    };
    const SkinGrowthResult r = grow_skin(phi, o);
    EXPECT_EQ(seen, snapshots) << c.name;
    std::string examples;
    for (const auto& e : r.report.violation_examples) examples += "\n  " + e;
    EXPECT_EQ(r.report.counters.violations, 0u) << c.name << examples;
    EXPECT_GT(r.report.counters.audit_samples, 0u) << c.name;
    return r.report;
}

TEST(SkinGrowth, OneBallNeedsNoOperation) {
    // A growing sphere is scale-invariant: born as an icosphere, it is never touched again.
    const auto rep = grow_and_check({"one ball", {{{0, 0, 0}, 2.0}}}, SkinSchedule::Relaxed);
    EXPECT_EQ(rep.counters.births, 1u);
    EXPECT_EQ(rep.counters.contractions + rep.counters.insertions, 0u);
    EXPECT_GT(rep.counters.checks(), 0u);
}

TEST(SkinGrowth, TwoBallsMergeThroughANeck) {
    const auto rep = grow_and_check({"two balls", {{{0, 0, 0}, 2.0}, {{2.2, 0.1, 0}, 1.8}}}, SkinSchedule::Relaxed);
    EXPECT_EQ(rep.counters.births, 2u);
    EXPECT_EQ(rep.counters.necks, 1u);
    EXPECT_EQ(rep.counters.fallbacks, 0u);
}

TEST(SkinGrowth, FourBallsOpenAndCloseAVoid) {
    const auto rep = grow_and_check({"four balls w=3.5", four_balls(3.5)}, SkinSchedule::Relaxed);
    EXPECT_EQ(rep.counters.births, 4u);
    EXPECT_EQ(rep.counters.necks, 6u);
    EXPECT_EQ(rep.counters.tunnels, 4u);
    EXPECT_EQ(rep.counters.deaths, 1u);
}

TEST(SkinGrowth, RingOfEightMakesATorus) {
    const auto rep = grow_and_check({"ring of 8", ring(8, 3.0, 2.0, 0.01)}, SkinSchedule::Relaxed);
    EXPECT_EQ(rep.counters.births, 8u);
    EXPECT_EQ(rep.counters.necks, 8u);
}

TEST(SkinGrowth, EveryStepChecksMoreForTheSameMesh) {
    const GrowthCase c{"two balls", {{{0, 0, 0}, 2.0}, {{2.2, 0.1, 0}, 1.8}}};
    const auto relaxed = grow_and_check(c, SkinSchedule::Relaxed, 4);
    const auto every = grow_and_check(c, SkinSchedule::EveryStep, 4);
    EXPECT_GT(every.counters.checks(), relaxed.counters.checks());
    EXPECT_GT(every.counters.steps, 1u);
}

/// §4.6: a fixed global step instead of the adaptive one is checked at that pace, and a coarse
/// one lets misses through that the auditor sees (the adaptive step and relaxed scheduling have
/// none on the same growth, above).
TEST(SkinGrowth, FixedStepIsTakenAndItsMissesCounted) {
    const SkinFunction phi({{{0, 0, 0}, 2.0}, {{2.2, 0.1, 0}, 1.8}}, 0.5);
    SkinGrowthOptions o;
    o.schedule = SkinSchedule::EveryStep;
    o.audit = true;
    const double start = skin_growth_start(phi, o);
    const double h = -start / 6;
    o.fixed_step = h;
    const SkinGrowthResult r = grow_skin(phi, o);
    // One step at the first birth, then one every h up to t = 0.
    EXPECT_GE(double(r.report.counters.steps), -start / h);
    EXPECT_LE(double(r.report.counters.steps), -start / h + 1);
    EXPECT_GT(r.report.counters.violations, 0u);
    SkinGrowthOptions relaxed;
    relaxed.fixed_step = h;
    EXPECT_THROW((void)grow_skin(phi, relaxed), InvalidInput);
    o.fixed_step = -1;
    EXPECT_THROW((void)grow_skin(phi, o), InvalidInput);
    o.fixed_step = 1e-12 * -start;  // would stop the clock
    EXPECT_THROW((void)grow_skin(phi, o), InvalidInput);
}

TEST(SkinGrowth, RejectsOtherShrinkFactors) {
    const SkinFunction phi({{{0, 0, 0}, 2.0}}, 0.3);
    EXPECT_THROW((void)grow_skin(phi), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
