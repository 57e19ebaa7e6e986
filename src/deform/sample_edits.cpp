#include "dynmesh/deform/sample_edits.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/geometry/point_grid.hpp"
#include "scenario_common.hpp"

namespace dynmesh {

using detail::check_positive;
using detail::fmt;
using detail::kNone;

SampleEdits plan_sample_edits(const Scenario& s, double t, std::span<const std::uint32_t> live_pool,
                              double insert_radius) {
    SampleEditOptions o;
    o.insert_radius = insert_radius;
    return plan_sample_edits(s, t, live_pool, o);
}

SampleEdits plan_sample_edits(const Scenario& s, double t, std::span<const std::uint32_t> live_pool,
                              const SampleEditOptions& o) {
    const char* who = "plan_sample_edits";
    check_positive(who, "insert_radius", o.insert_radius);
    check_positive(who, "compress_ratio", o.compress_ratio);
    check_positive(who, "target_ratio", o.target_ratio);
    if (o.target_ratio > o.compress_ratio)
        throw InvalidInput("plan_sample_edits: target_ratio (" + fmt(o.target_ratio) +
                           ") must not exceed compress_ratio (" + fmt(o.compress_ratio) + ")");
    const std::size_t m = s.pool_size();
    std::vector<std::uint32_t> live(live_pool.begin(), live_pool.end());
    std::sort(live.begin(), live.end());
    for (std::size_t i = 0; i < live.size(); ++i) {
        if (live[i] >= m)
            throw InvalidInput("plan_sample_edits: live pool index " + std::to_string(live[i]) +
                               " >= pool size " + std::to_string(m));
        if (i > 0 && live[i] == live[i - 1])
            throw InvalidInput("plan_sample_edits: live pool index " + std::to_string(live[i]) +
                               " is listed twice");
    }
    const std::vector<Point3> pt = pool_positions(s, t);
    enum : char { kAbsent = 0, kLive = 1, kInserted = 2 };
    std::vector<char> state(m, kAbsent);
    for (std::uint32_t i : live) state[i] = kLive;

    const auto pos = PointGrid::positions(pt);
    SampleEdits out;
    // 1. Insertions: greedy in index order (the live samples in one grid made at once, the
    // few insertions in another that grows).
    {
        const PointGrid g = PointGrid::bulk(o.insert_radius, pt, live);
        PointGrid inserted(o.insert_radius);
        for (std::uint32_t i = 0; i < m; ++i) {
            if (state[i] != kAbsent) continue;
            if (!g.any_within(pt[i], o.insert_radius, pos) &&
                !inserted.any_within(pt[i], o.insert_radius, pos)) {
                out.insert_pool.push_back(i);
                state[i] = kInserted;
                inserted.insert(i, pt[i]);
            }
        }
    }
    if (!o.deletions || live.size() < 2) return out;

    // 2. Density ratios over live samples and planned insertions.
    const double rd = s.density_radius;
    std::vector<std::uint32_t> present = live;
    present.insert(present.end(), out.insert_pool.begin(), out.insert_pool.end());
    const PointGrid gd = PointGrid::bulk(rd, pt, present);
    std::vector<std::uint32_t> count(m, 0);
    std::vector<std::uint32_t> candidates;
    auto ratio = [&](std::uint32_t p) {
        return static_cast<double>(count[p]) /
               static_cast<double>(std::max<std::uint32_t>(1, s.initial_density[p]));
    };
    for (std::uint32_t p : live) {
        std::uint32_t n = 0;
        gd.for_each_within(pt[p], rd, pos, [&](std::uint32_t, double) { ++n; });
        count[p] = n;
        if (ratio(p) >= o.compress_ratio) candidates.push_back(p);
    }
    if (candidates.empty()) return out;
    for (std::uint32_t i : out.insert_pool) {  // running counts are kept for insertions too
        std::uint32_t n = 0;
        gd.for_each_within(pt[i], rd, pos, [&](std::uint32_t, double) { ++n; });
        count[i] = n;
    }

    // 3. Deletions: greedy in index order, with protected keepers.
    const double keep_r = std::min(s.spacing0, s.h0);
    const std::size_t max_deleted = live.size() / 2;
    std::vector<char> gone(m, 0), keep(m, 0);
    for (std::uint32_t p : candidates) {
        if (out.delete_pool.size() >= max_deleted) break;
        if (keep[p] || !(ratio(p) > o.target_ratio)) continue;
        std::uint32_t q = kNone;
        double qd = std::numeric_limits<double>::infinity();
        gd.for_each_within(pt[p], keep_r, pos, [&](std::uint32_t id, double d2) {
            if (id == p || gone[id]) return;
            if (d2 < qd || (d2 == qd && id < q)) {
                qd = d2;
                q = id;
            }
        });
        if (q == kNone || !(qd < keep_r * keep_r)) continue;
        gone[p] = 1;
        keep[q] = 1;
        out.delete_pool.push_back(p);
        gd.for_each_within(pt[p], rd, pos, [&](std::uint32_t id, double) {
            if (count[id] > 0) --count[id];
        });
    }
    return out;
}

}  // namespace dynmesh
