// run_deform(): scenarios end to end, measured against the ground truth at every time unit
// (spec §8.2-8.3: invariants at every update, quality at every unit).
#include <gtest/gtest.h>

#include <cmath>

#include "dynmesh/deform/run.hpp"
#include "dynmesh/error.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

DeformRunReport run(const std::string& name, std::size_t samples, int steps, double speed,
                    Schedule schedule = Schedule::Paper, int measure_every = 4, double kappa = kPracticalKappa) {
    ScenarioOptions so;
    so.samples = samples;
    so.steps = steps;
    so.speed = speed;
    const Scenario s = make_scenario(name, so);
    DeformRunOptions ro;
    ro.schedule = schedule;
    ro.check_invariants = true;
    ro.measure_every = measure_every;
    ro.params.kappa = kappa;
    return run_deform(s, ro);
}

void expect_good(const DeformRunReport& r) {
    EXPECT_EQ(r.invariant_failures, 0u) << (r.first_invariant_failures.empty() ? "" : r.first_invariant_failures[0]);
    EXPECT_EQ(r.self_intersections, 0u);
    EXPECT_EQ(r.inverted, 0u);
    EXPECT_GT(r.worst_min_angle_deg, 5.0);
    EXPECT_LT(r.worst_hausdorff_over_eps, 1.0);  // Hausdorff small relative to eps gamma
    EXPECT_LT(r.worst_normal_dev_deg, 45.0);
    EXPECT_GT(r.worst_min_edge_angle_deg, 90.0);  // every edge-angle > pi/2 (L3.7)
    ASSERT_EQ(r.log.size(), static_cast<std::size_t>(r.time_units) + 1);
    for (const DeformLogRow& row : r.log) {
        if (std::isnan(row.metrics.max_radius_edge)) continue;  // not measured (measure_every 0)
        // Invariant (ii) at every update: R <= 3 h; between steps L3.6 allows 12 h.
        if (row.measured && row.update) {
            EXPECT_LE(row.metrics.R_over_h, 3.0) << "t = " << row.metrics.t;
        }
        if (row.measured) {
            EXPECT_LE(row.metrics.R_over_h, 12.0) << "t = " << row.metrics.t;
        }
        EXPECT_LE(row.metrics.max_radius_edge, 12.0) << "t = " << row.metrics.t;
    }
}

TEST(DeformRun, StretchKeepsQualityAtEveryTimeUnit) {
    const auto r = run("stretch", 1500, 100, 0.5);
    expect_good(r);
    EXPECT_GT(r.insertions, 0u);
    EXPECT_GT(r.flips, 0u);
}

TEST(DeformRun, TwistedTorusKeepsQualityAtEveryTimeUnit) {
    const auto r = run("twist", 2000, 60, 0.5);
    expect_good(r);
}

TEST(DeformRun, BoomerangKeepsQualityAtEveryTimeUnit) {
    const auto r = run("bend", 1500, 80, 0.5);
    expect_good(r);
}

TEST(DeformRun, RigidRotationMakesNoChange) {
    const auto r = run("rotate", 1500, 60, 1.0);
    expect_good(r);
    EXPECT_EQ(r.flips + r.insertions + r.removals, 0u);
}

TEST(DeformRun, RealMeshWithInsertionsAndDeletions) {
    const std::string mesh = test::shared_data("meshes/blobby.off").string();
    ScenarioOptions so;
    so.samples = 100000;
    so.steps = 60;
    so.warp = "bend";
    const Scenario s = make_scenario(mesh, so);
    ASSERT_TRUE(s.edits);
    DeformRunOptions ro;
    ro.check_invariants = true;
    const auto r = run_deform(s, ro);
    EXPECT_GT(r.samples_inserted, 0u);
    EXPECT_GT(r.samples_deleted, 0u);
    EXPECT_EQ(r.invariant_failures, 0u) << (r.first_invariant_failures.empty() ? "" : r.first_invariant_failures[0]);
    EXPECT_EQ(r.self_intersections, 0u);
    EXPECT_EQ(r.inverted, 0u);
    EXPECT_LT(r.worst_hausdorff_over_eps, 1.0);
}

TEST(DeformRun, EveryStepScheduleUpdatesAtEveryUnit) {
    // Slow enough (kappa 8) that steps are several time units apart.
    const auto paper = run("stretch", 1500, 100, 0.1, Schedule::Paper, 0, 8);
    const auto every = run("stretch", 1500, 100, 0.1, Schedule::EveryStep, 0, 8);
    EXPECT_EQ(every.updates, static_cast<std::size_t>(every.time_units));
    EXPECT_LT(paper.updates, every.updates / 2);
    expect_good(paper);
    expect_good(every);
    EXPECT_EQ(parse_schedule("paper"), Schedule::Paper);
    EXPECT_EQ(parse_schedule("every-step"), Schedule::EveryStep);
    EXPECT_THROW((void)parse_schedule("sometimes"), InvalidInput);
}

TEST(DeformRun, LogCsvHasOneRowPerTimeUnit) {
    const auto r = run("pulse", 1500, 10, 1.0);
    const std::string csv = log_csv(r);
    std::size_t lines = 0;
    for (char c : csv) lines += c == '\n';
    EXPECT_EQ(lines, static_cast<std::size_t>(r.time_units) + 2);
    EXPECT_NE(csv.find("hausdorff_over_h"), std::string::npos);
    EXPECT_NE(csv.find("flips"), std::string::npos);
}

}  // namespace
}  // namespace dynmesh
