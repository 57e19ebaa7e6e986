#include "dynmesh/deform/sample_edits.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/error.hpp"
#include "scenario_cases.hpp"

namespace dynmesh {
namespace {

using namespace test;

TEST(SampleEdits, MeshScenarioInsertsFromTheSubdividedPool) {
    const Scenario& s = cached("mesh+pulse");
    const double peak = 0.5 * kSteps;
    const SampleEdits e = plan_sample_edits(s, peak, s.initial, s.h0);
    EXPECT_GT(e.insert_pool.size(), 20u);
    std::vector<std::uint32_t> after = s.initial;
    after.insert(after.end(), e.insert_pool.begin(), e.insert_pool.end());
    EXPECT_GT(sampling_radius(s, peak, s.initial), 1.4 * s.h0);
    EXPECT_LT(sampling_radius(s, peak, after), 1.2 * s.h0);
}

TEST(SampleEdits, NothingToDoAtTimeZero) {
    for (const std::string& key : all_cases()) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        const SampleEdits e = plan_sample_edits(s, 0.0, s.initial, s.h0);
        EXPECT_TRUE(e.insert_pool.empty());
        EXPECT_TRUE(e.delete_pool.empty());
    }
    // A rigid motion changes no density either.
    const Scenario& rot = cached("rotate");
    const SampleEdits e = plan_sample_edits(rot, 0.3 * kSteps, rot.initial, rot.h0);
    EXPECT_TRUE(e.insert_pool.empty());
    EXPECT_TRUE(e.delete_pool.empty());
}

TEST(SampleEdits, InsertsWhereTheSurfaceStretches) {
    const Scenario& s = cached("stretch");
    const double peak = 0.5 * kSteps;
    // A finer insertion radius inserts more.
    EXPECT_GT(plan_sample_edits(s, peak, s.initial, 0.5 * s.h0).insert_pool.size(),
              s.initial.size() / 4);
    const SampleEdits e = plan_sample_edits(s, peak, s.initial, s.h0);
    ASSERT_GT(e.insert_pool.size(), 20u);
    EXPECT_TRUE(e.delete_pool.empty());  // nothing is compressed at the peak
    EXPECT_TRUE(std::is_sorted(e.insert_pool.begin(), e.insert_pool.end()));
    std::vector<char> live(s.pool_size(), 0);
    for (auto i : s.initial) live[i] = 1;
    double scale_inserted = 0, scale_all = 0;
    for (auto i : e.insert_pool) {
        EXPECT_FALSE(live[i]);
        scale_inserted += area_scale(s, peak, i);
    }
    for (auto i : s.initial) scale_all += area_scale(s, peak, i);
    scale_inserted /= static_cast<double>(e.insert_pool.size());
    scale_all /= static_cast<double>(s.initial.size());
    EXPECT_GT(scale_inserted, scale_all);  // insertions go where the area grew
    // Afterwards the live set covers Sigma(t) about as well as P(0) covered Sigma(0).
    std::vector<std::uint32_t> after = s.initial;
    after.insert(after.end(), e.insert_pool.begin(), e.insert_pool.end());
    const double h_before = sampling_radius(s, peak, s.initial);
    const double h_after = sampling_radius(s, peak, after);
    EXPECT_GT(h_before, 1.2 * s.h0);
    EXPECT_LT(h_after, 1.3 * s.h0);
    // Inserted points are more than insert_radius apart from each other and from P(t).
    const auto pts = pool_positions(s, peak, e.insert_pool);
    const auto live_pts = pool_positions(s, peak, s.initial);
    for (std::size_t i = 0; i < std::min<std::size_t>(pts.size(), 200); ++i) {
        for (std::size_t j = 0; j < i; ++j) EXPECT_GT(distance(pts[i], pts[j]), s.h0);
        for (const Point3& q : live_pts) ASSERT_GT(distance(pts[i], q), s.h0);
    }
}

TEST(SampleEdits, DeletesWhereTheSurfaceShrinksBack) {
    for (const std::string key : {"stretch", "pulse"}) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        const double peak = 0.5 * kSteps, end = kSteps;
        // Make the peak as dense as P(0) was, then come back.
        const SampleEdits grow = plan_sample_edits(s, peak, s.initial, 0.5 * s.h0);
        std::vector<std::uint32_t> live = s.initial;
        live.insert(live.end(), grow.insert_pool.begin(), grow.insert_pool.end());
        std::sort(live.begin(), live.end());
        const SampleEdits shrink = plan_sample_edits(s, end, live, s.h0);
        EXPECT_TRUE(shrink.insert_pool.empty());
        ASSERT_FALSE(shrink.delete_pool.empty());
        EXPECT_LE(shrink.delete_pool.size(), live.size() / 2);
        EXPECT_TRUE(std::is_sorted(shrink.delete_pool.begin(), shrink.delete_pool.end()));
        // Deleted samples come from where the peak had stretched the surface the most.
        double scale_deleted = 0, scale_live = 0;
        for (auto i : shrink.delete_pool) scale_deleted += area_scale(s, peak, i);
        for (auto i : live) scale_live += area_scale(s, peak, i);
        scale_deleted /= static_cast<double>(shrink.delete_pool.size());
        scale_live /= static_cast<double>(live.size());
        if (key == std::string("stretch")) {
            EXPECT_GT(scale_deleted, scale_live);
        }
        // No hole: every deleted sample keeps a surviving sample within h0.
        std::vector<char> gone(s.pool_size(), 0);
        for (auto i : shrink.delete_pool) gone[i] = 1;
        std::vector<std::uint32_t> kept;
        for (auto i : live)
            if (!gone[i]) kept.push_back(i);
        const auto kept_pts = pool_positions(s, end, kept);
        for (const Point3& p : pool_positions(s, end, shrink.delete_pool)) {
            double d = 1e300;
            for (const Point3& q : kept_pts) d = std::min(d, distance(p, q));
            ASSERT_LE(d, s.h0);
        }
        // The density drops, and the sampling radius stays below that of P(0) plus h0.
        EXPECT_LT(sampling_radius(s, end, kept), 2 * s.h0);
    }
}

TEST(SampleEdits, NeverDeletesMoreThanHalf) {
    const Scenario& s = cached("pulse");
    // The whole pool is four times denser than P(0) everywhere.
    const std::vector<std::uint32_t> live = all_pool(s);
    const SampleEdits e = plan_sample_edits(s, 0.0, live, s.h0);
    EXPECT_TRUE(e.insert_pool.empty());
    EXPECT_GT(e.delete_pool.size(), live.size() / 5);
    EXPECT_LE(e.delete_pool.size(), live.size() / 2);
    // Deterministic.
    EXPECT_EQ(plan_sample_edits(s, 0.0, live, s.h0).delete_pool, e.delete_pool);
}

TEST(SampleEdits, RejectsBadArguments) {
    const Scenario& s = cached("pulse");
    expect_invalid([&] { (void)plan_sample_edits(s, 1.0, s.initial, 0.0); }, "insert_radius");
    expect_invalid([&] { (void)plan_sample_edits(s, 1.0, s.initial, std::nan("")); },
                   "insert_radius");
    const std::vector<std::uint32_t> bad{0, static_cast<std::uint32_t>(s.pool_size())};
    expect_invalid([&] { (void)plan_sample_edits(s, 1.0, bad, s.h0); }, "pool size");
    const std::vector<std::uint32_t> twice{3, 5, 3};
    expect_invalid([&] { (void)plan_sample_edits(s, 1.0, twice, s.h0); }, "twice");
    SampleEditOptions o;
    o.insert_radius = s.h0;
    o.target_ratio = 3;
    expect_invalid([&] { (void)plan_sample_edits(s, 1.0, s.initial, o); }, "target_ratio");
}

}  // namespace
}  // namespace dynmesh
