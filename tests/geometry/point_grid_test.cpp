#include "dynmesh/geometry/point_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/system/hash.hpp"  // mix64: a deterministic subset

namespace dynmesh {
namespace {

/// Points in a cube of side `size` about `center`, every tenth one repeating an earlier one.
std::vector<Point3> cloud(Rng& rng, std::size_t n, const Point3& center, double size) {
    std::vector<Point3> pts(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 d{rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)};
        pts[i] = i % 10 == 9 ? pts[rng.below(i)] : center + d * size;
    }
    return pts;
}

/// The ids within distance r of q, with their squared distances, increasing.
std::vector<std::pair<std::uint32_t, double>> brute_within(const std::vector<Point3>& pts,
                                                           const std::vector<std::uint32_t>& ids,
                                                           const Point3& q, double r) {
    std::vector<std::pair<std::uint32_t, double>> out;
    for (std::uint32_t id : ids)
        if (sqdistance(pts[id], q) <= r * r) out.emplace_back(id, sqdistance(pts[id], q));
    std::sort(out.begin(), out.end());
    return out;
}

/// Every query of `g` (holding `ids` at pts[id]) against brute force, around `center`.
void expect_queries_exact(const PointGrid& g, const std::vector<Point3>& pts,
                          const std::vector<std::uint32_t>& ids, const Point3& center,
                          double size, Rng& rng) {
    auto pos = [&](std::uint32_t i) -> const Point3& { return pts[i]; };
    ASSERT_EQ(g.size(), ids.size());
    for (int k = 0; k < 400; ++k) {
        const double spread = k % 10 == 0 ? 4.0 : 1.2;  // some queries far outside
        const Point3 q = center + Vec3{rng.uniform(-spread, spread), rng.uniform(-spread, spread),
                                       rng.uniform(-spread, spread)} * (0.5 * size);
        const double r = size * (k % 7 == 0 ? 3.0 : rng.uniform(0.0, 0.2));
        const auto expected = brute_within(pts, ids, q, r);

        std::vector<std::pair<std::uint32_t, double>> got;
        g.for_each_within(q, r, pos, [&](std::uint32_t id, double d2) { got.emplace_back(id, d2); });
        std::sort(got.begin(), got.end());
        ASSERT_EQ(got, expected) << "query " << k;
        ASSERT_EQ(g.any_within(q, r, pos), !expected.empty());

        std::vector<std::uint32_t> cand;
        g.for_each_candidate(q, r, [&](std::uint32_t id) { cand.push_back(id); });
        std::sort(cand.begin(), cand.end());
        ASSERT_TRUE(std::adjacent_find(cand.begin(), cand.end()) == cand.end()) << "an id twice";
        for (const auto& [id, d2] : expected)
            ASSERT_TRUE(std::binary_search(cand.begin(), cand.end(), id));

        // Nearest with a filter (odd ids only); ties break on the smaller id.
        auto keep = [](std::uint32_t id) { return id % 2 == 1; };
        std::uint32_t bi = PointGrid::kNone;
        double bd2 = std::numeric_limits<double>::infinity();
        for (std::uint32_t id : ids)
            if (keep(id) && (sqdistance(pts[id], q) < bd2 || (sqdistance(pts[id], q) == bd2 && id < bi))) {
                bd2 = sqdistance(pts[id], q);
                bi = id;
            }
        const auto [id, d2] = g.nearest_sq(q, pos, keep);
        ASSERT_EQ(id, bi) << "query " << k;
        ASSERT_EQ(d2, bd2);
        const auto [id1, d1] = g.nearest(q, pos, keep);
        ASSERT_EQ(id1, bi);
        ASSERT_EQ(d1, std::sqrt(bd2));
        // Stopping early: exact above the bound, some accepted id within it otherwise.
        const double stop = rng.uniform(0.0, 2.0) * bd2;
        const auto [sid, sd] = g.nearest_sq(q, pos, keep, stop);
        if (bd2 > stop) {
            ASSERT_EQ(sid, bi);
            ASSERT_EQ(sd, bd2);
        } else {
            ASSERT_TRUE(keep(sid));
            ASSERT_LE(sd, stop);
            ASSERT_EQ(sd, sqdistance(pts[sid], q));
        }
    }
}

TEST(PointGrid, BulkAndDynamicGridsAnswerExactly) {
    Rng rng(7);
    // Near the origin, and far from it in small cells (cell coordinates ~7e7).
    for (const auto& [center, size] : {std::pair{Point3{0, 0, 0}, 2.0}, std::pair{Point3{1e6, -2e6, 5e5}, 1.0}}) {
        const std::vector<Point3> pts = cloud(rng, 2000, center, size);
        const double cell = 0.03 * size;
        std::vector<std::uint32_t> all(pts.size());
        for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
        const PointGrid b = PointGrid::bulk(cell, pts);
        EXPECT_TRUE(b.is_static());
        expect_queries_exact(b, pts, all, center, size, rng);

        std::vector<std::uint32_t> some;  // a subset, by id
        for (std::uint32_t i = 0; i < pts.size(); ++i)
            if (mix64(i) % 3 != 0) some.push_back(i);
        expect_queries_exact(PointGrid::bulk(cell, pts, some), pts, some, center, size, rng);

        PointGrid d(cell);
        for (std::uint32_t i : all) d.insert(i, pts[i]);
        for (std::uint32_t i : all) {
            if (mix64(i) % 3 == 0) {
                ASSERT_TRUE(d.erase(i, pts[i]));
            }
        }
        EXPECT_FALSE(d.is_static());
        expect_queries_exact(d, pts, some, center, size, rng);

        // A bulk grid of the first half, changed into the same set: the erased ids leave their
        // bulk cells, the second half goes in as inserted ids.
        std::vector<std::uint32_t> half(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(all.size() / 2));
        PointGrid m = PointGrid::bulk(cell, pts, half);
        for (std::uint32_t i = static_cast<std::uint32_t>(half.size()); i < pts.size(); ++i) m.insert(i, pts[i]);
        for (std::uint32_t i : all)
            if (mix64(i) % 3 == 0) {
                ASSERT_TRUE(m.erase(i, pts[i]));
                ASSERT_FALSE(m.erase(i, pts[i]));
            }
        EXPECT_TRUE(m.is_static());
        EXPECT_EQ(m.size(), some.size());
        expect_queries_exact(m, pts, some, center, size, rng);
    }
}

TEST(PointGrid, EmptyGridsAndResets) {
    auto pos = [](std::uint32_t) { return Point3{0, 0, 0}; };
    auto any = [](std::uint32_t) { return true; };
    const PointGrid e = PointGrid::bulk(1.0, std::vector<Point3>{});
    EXPECT_EQ(e.size(), 0u);
    EXPECT_FALSE(e.any_within({0, 0, 0}, 10, pos));
    EXPECT_EQ(e.nearest_sq({0, 0, 0}, pos, any).first, PointGrid::kNone);
    EXPECT_EQ(PointGrid(1.0).nearest({0, 0, 0}, pos, any).first, PointGrid::kNone);

    const std::vector<Point3> one{{1, 2, 3}};
    PointGrid g = PointGrid::bulk(0.5, one);
    EXPECT_FALSE(g.erase(0, Point3{9, 9, 9}));  // not where it was put
    EXPECT_TRUE(g.erase(0, one[0]));
    EXPECT_EQ(g.size(), 0u);
    EXPECT_EQ(g.nearest_sq({0, 0, 0}, PointGrid::positions(one), any).first, PointGrid::kNone);
    g.reset(0.5);  // empty, no bulk table
    EXPECT_FALSE(g.is_static());
    g.insert(0, one[0]);
    EXPECT_EQ(g.size(), 1u);
    EXPECT_THROW(PointGrid::bulk(0.0, one), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
