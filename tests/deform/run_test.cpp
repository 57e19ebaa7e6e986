// run_deform(): scenarios end to end, measured against the ground truth at every time unit
// (spec §8.2-8.3: invariants at every update, quality at every unit).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dynmesh/deform/run.hpp"
#include "dynmesh/error.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

DeformRunReport run(const std::string& name, std::size_t samples, int steps, double speed,
                    Schedule schedule = Schedule::Paper, int measure_every = 4, double kappa = kPracticalKappa,
                    std::size_t max_substeps = DeformOptions{}.max_substeps) {
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
    ro.params.max_substeps = max_substeps;
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

TEST(DeformRun, SubSteppingLeavesARunWithinTheModelUnchanged) {
    // Spec §10.6 F1: when the motion meets the paper's model (floor(R / (kappa lambda)) >= 1,
    // no monitor), sub-stepping never fires and the run is the paper's, change for change.
    for (const char* name : {"stretch", "dimple"}) {
        const auto paper = run(name, 1000, 100, 0.05, Schedule::Paper, 0, kPracticalKappa, 1);
        ASSERT_EQ(paper.violations.count("step_too_short"), 0u) << name << ": not within the model";
        ASSERT_GT(paper.updates, 2u) << name;
        const auto cut = run(name, 1000, 100, 0.05, Schedule::Paper, 0);
        EXPECT_EQ(cut.substeps, static_cast<std::size_t>(cut.time_units)) << name;
        EXPECT_EQ(cut.internal_updates, 0u) << name;
        EXPECT_EQ(cut.substep_retries, 0u) << name;
        EXPECT_EQ(cut.updates, paper.updates) << name;
        EXPECT_EQ(cut.flips, paper.flips) << name;
        EXPECT_EQ(cut.insertions, paper.insertions) << name;
        EXPECT_EQ(cut.removals, paper.removals) << name;
        EXPECT_EQ(cut.violations, paper.violations) << name;
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

TEST(DeformRun, SpacingRepairMakesTheRemovesOfTheAnalyticScenarios) {
    // The analytic scenarios delete no sample, so every Remove comes from the spacing repair
    // (spec §9 P7, not in the paper, on by default). Without it there is no Remove, and
    // compression brings old vertex pairs below R/3: the spacing invariant fails.
    ScenarioOptions so;
    so.samples = 1500;
    so.steps = 100;
    so.speed = 0.5;
    const Scenario s = make_scenario("stretch", so);
    ASSERT_FALSE(s.edits);
    DeformRunOptions ro;
    ro.check_invariants = true;
    ro.measure_every = 0;
    const auto on = run_deform(s, ro);
    std::size_t repairs = 0;
    for (const DeformLogRow& row : on.log) repairs += row.counters.spacing_repairs;
    EXPECT_GT(on.removals, 0u);
    EXPECT_GT(repairs, 0u);
    EXPECT_EQ(on.invariant_failures, 0u) << (on.first_invariant_failures.empty() ? "" : on.first_invariant_failures[0]);
    ro.params.spacing_repair = false;
    const auto off = run_deform(s, ro);
    EXPECT_EQ(off.removals, 0u);
    EXPECT_GT(off.insertions, 0u);
    EXPECT_GT(off.invariant_failures, 0u);
    ASSERT_FALSE(off.first_invariant_failures.empty());
    EXPECT_NE(off.first_invariant_failures[0].find(" R apart"), std::string::npos) << off.first_invariant_failures[0];
}

TEST(DeformCheck, EveryReasonIsListedWithItsTime) {
    DeformRunReport r;
    EXPECT_TRUE(check_failures(r, CheckLevel::Invariants).ok());
    EXPECT_TRUE(check_failures(r, CheckLevel::Strict).ok());
    r.invariant_failures = 2;
    r.first_invariant_failures = {"t=3: vertices sample 1 and sample 2 are 0.2 R apart", "t=4: x"};
    r.self_intersections = 4;
    r.first_self_intersection_t = 7;
    r.inverted = 1;
    r.first_inverted_t = 9;
    r.updates_with_nonempty_balls = 1;
    r.nonempty_balls_max = 3;
    r.first_nonempty_balls = {"t=2: the diametric ball of triangle (1, 2, 3) holds 1 vertices"};
    r.violations = {{"rollback", 3}, {"step_too_short", 1}};
    r.violation_examples = {{5, Violation::TopologyRollback, "the rebuild is undone"},
                            {6, Violation::StepTooShort, "floor(R / (kappa lambda)) = 0"}};
    const auto inv = check_failures(r, CheckLevel::Invariants).problems;
    auto has = [](const std::vector<std::string>& lines, const std::string& start, const std::string& part) {
        return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) {
            return l.rfind(start, 0) == 0 && l.find(part) != std::string::npos;
        });
    };
    EXPECT_TRUE(has(inv, "2 updates", "invariant"));
    EXPECT_TRUE(has(inv, "t=3: ", "R apart"));
    EXPECT_TRUE(has(inv, "t=4: ", "x"));
    EXPECT_TRUE(has(inv, "t=7: ", "self-intersections (4"));
    EXPECT_TRUE(has(inv, "t=9: ", "inverted"));
    EXPECT_TRUE(has(inv, "t=5: rollback: ", "undone"));
    EXPECT_TRUE(has(inv, "rollback: 2 more", ""));
    EXPECT_FALSE(has(inv, "", "step_too_short"));
    EXPECT_FALSE(has(inv, "", "diametric ball"));
    const auto strict = check_failures(r, CheckLevel::Strict).problems;
    for (const std::string& l : inv) EXPECT_NE(std::find(strict.begin(), strict.end(), l), strict.end()) << l;
    EXPECT_TRUE(has(strict, "t=6: step_too_short: ", "kappa"));
    EXPECT_TRUE(has(strict, "t=2: ", "diametric ball of triangle (1, 2, 3)"));
    EXPECT_TRUE(check_failures(r, CheckLevel::Off).ok());
    EXPECT_EQ(parse_check_level("strict"), CheckLevel::Strict);
    EXPECT_EQ(parse_check_level("on"), CheckLevel::Invariants);
    EXPECT_EQ(parse_check_level(to_string(CheckLevel::Invariants)), CheckLevel::Invariants);
    EXPECT_THROW((void)parse_check_level("sometimes"), InvalidInput);
}

TEST(DeformCheck, StrictFailsOnTheMonitorsOfAValidRun) {
    // Too fast for its sampling (steps 100 at 1500 samples): floor(R / (kappa lambda)) = 0 at
    // every step. Without sub-stepping (which would follow the motion within the budget) the
    // mesh stays valid, so --check passes, but --check=strict lists each step_too_short with
    // its time unit.
    const auto r = run("stretch", 1500, 100, 0.5, Schedule::Paper, 0, kPracticalKappa, 1);
    ASSERT_GT(r.violations.count("step_too_short"), 0u);
    EXPECT_TRUE(check_failures(r, CheckLevel::Invariants).ok())
        << check_failures(r, CheckLevel::Invariants).problems.front();
    const auto strict = check_failures(r, CheckLevel::Strict).problems;
    EXPECT_TRUE(std::any_of(strict.begin(), strict.end(),
                            [](const std::string& l) { return l.rfind("t=0: step_too_short: ", 0) == 0; }));
    EXPECT_TRUE(std::any_of(strict.begin(), strict.end(), [](const std::string& l) {
        return l.rfind("step_too_short: ", 0) == 0 && l.find(" more") != std::string::npos;
    }));
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
