#include "dynmesh/quadtree/domain.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/quadtree/dyn_mesh.hpp"
#include "quadtree_fixtures.hpp"

namespace dynmesh {
namespace {
using namespace testing_quadtree;

template <int D>
bool same_box(const QuadtreeOptions<D>& a, const QuadtreeOptions<D>& b) {
    return a.origin == b.origin && a.width == b.width;
}

/// n random points around centre c with spread e per axis.
template <int D>
std::vector<PointD<D>> cloud(Rng& rng, std::size_t n, double c, double e) {
    std::vector<PointD<D>> pts(n);
    for (auto& p : pts)
        for (int d = 0; d < D; ++d) p[static_cast<std::size_t>(d)] = c + e * rng.uniform(-1, 1);
    return pts;
}

/// Every point lies in the middle third; for well-resolved sets (spread above 2^-40 of the
/// coordinates) with the documented margin W/48 on every side; the box is dyadic.
template <int D>
void check_holds(const std::vector<PointD<D>>& pts, const std::string& what) {
    const QuadtreeOptions<D> box = auto_domain<D>(pts);
    const DynQuadtree<D> tree(box);
    EXPECT_TRUE(tree.dyadic()) << what;
    double lo = INFINITY, hi = -INFINITY, mag = 0;
    for (const auto& p : pts) {
        ASSERT_TRUE(tree.is_admissible(p)) << what;
        for (int d = 0; d < D; ++d) {
            const double v = p[static_cast<std::size_t>(d)];
            mag = std::max(mag, std::fabs(v));
            const double o = box.origin[static_cast<std::size_t>(d)];
            lo = std::min(lo, (v - o) / box.width);
            hi = std::max(hi, (v - o) / box.width);
        }
    }
    if (!pts.empty() && (hi - lo) * box.width > std::ldexp(mag, -40)) {
        EXPECT_GE(lo, 1.0 / 3 + 1.0 / 48 - 1e-9) << what;
        EXPECT_LE(hi, 2.0 / 3 - 1.0 / 48 + 1e-9) << what;
    }
}

TEST(AutoDomain, HoldsEveryPointInTheMiddleThird) {
    Rng rng(1);
    const double centres[] = {0.0, 1e-300, -3e-10, 0.5, -7.25, 1e10, -1e200, 1e300};
    const double spreads[] = {0.0, 1e-300, 1e-12, 1e-3, 1.0, 1e3, 1e150, 1e300};
    for (double c : centres)
        for (double e : spreads) {
            const std::string what = "centre " + std::to_string(c) + " spread " + std::to_string(e);
            if (e > 0 && e < std::fabs(c) * 1e-13) continue;  // below the coordinate resolution
            check_holds<2>(cloud<2>(rng, 50, c, e), what + " 2D");
            check_holds<3>(cloud<3>(rng, 20, c, e), what + " 3D");
            check_holds<2>(cloud<2>(rng, 2, c, e), what + " two points");
        }
}

TEST(AutoDomain, DegenerateSets) {
    const QuadtreeOptions<2> unit;
    EXPECT_TRUE(same_box<2>(auto_domain<2>(std::vector<Vec2>{}), unit));
    // One position (repeated or not): a box of its own magnitude, at least 1 wide.
    const auto one = auto_domain<2>(std::vector<Vec2>{{0, 0}});
    EXPECT_EQ(one.width, 8.0);
    EXPECT_TRUE(same_box<2>(auto_domain<2>(std::vector<Vec2>{{0, 0}, {0, 0}, {0, 0}}), one));
    check_holds<2>({{0, 0}}, "origin");
    check_holds<2>({{3, -4}, {3, -4}}, "repeated point");
    check_holds<2>({{1e300, -1e300}}, "huge point");
    check_holds<3>({{1e-310, 0, -1e-310}, {2e-310, 0, -1e-310}}, "subnormal spread");
    check_holds<2>({{-1e300, 1e300}, {1e300, -1e300}}, "huge spread");
    // Points one ulp apart at 1e16: the box holds them (the tree then judges resolution).
    check_holds<2>({{1e16, 1e16}, {1e16 + 2, 1e16}}, "one ulp apart");
}

TEST(AutoDomain, RejectsWhatNoBoxHolds) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW((void)auto_domain<2>(std::vector<Vec2>{{0, 0}, {nan, 1}}), InvalidInput);
    EXPECT_THROW((void)auto_domain<2>(std::vector<Vec2>{{1.7e308, 0}}), InvalidInput);
    EXPECT_THROW((void)auto_domain<2>(std::vector<Vec2>{{-1.7e308, 0}, {1.7e308, 0}}),
                 InvalidInput);
    try {
        (void)auto_domain<3>(std::vector<Vec3>{{0, 0, 0}, {1, 2, std::numeric_limits<double>::infinity()}});
        FAIL() << "accepted an infinite coordinate";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("point 1"), std::string::npos) << e.what();
    }
}

/// The fraction of random sets whose box moves when the bounding box grows by `rel` of its
/// extent on one side (the maximum point moved outwards).
template <int D>
double moved_fraction(double rel, std::uint64_t seed) {
    Rng rng(seed);
    int moved = 0;
    const int trials = 2000;
    for (int t = 0; t < trials; ++t) {
        const double c = rng.uniform(-100, 100);
        const double e = std::ldexp(1.0, static_cast<int>(rng.below(40)) - 20) * rng.uniform(0.5, 1);
        auto pts = cloud<D>(rng, 30, c, e);
        const QuadtreeOptions<D> a = auto_domain<D>(pts);
        const std::size_t axis = rng.below(D);
        auto top = std::max_element(pts.begin(), pts.end(), [&](const auto& p, const auto& q) {
            return p[axis] < q[axis];
        });
        (*top)[axis] += rel * 2 * e;
        moved += same_box<D>(a, auto_domain<D>(pts)) ? 0 : 1;
    }
    return static_cast<double>(moved) / trials;
}

TEST(AutoDomain, SmallBoundingBoxChangesDoNotMoveIt) {
    // A change of 1e-7 of the extent crosses a threshold with probability ~1e-6.
    EXPECT_EQ(moved_fraction<2>(1e-7, 3), 0.0);
    EXPECT_EQ(moved_fraction<3>(1e-7, 4), 0.0);
    // A change of 1e-3 of the extent: a fraction of a percent (thresholds of the width and
    // of one or two origin coordinates).
    EXPECT_LT(moved_fraction<2>(1e-3, 5), 0.01);
}

TEST(AutoDomain, ForUpdatesPrefersTheFinalBox) {
    Rng rng(7);
    const auto initial = cloud<2>(rng, 60, 3.0, 0.5);
    std::vector<Vec2> all = initial;
    // Inserted then erased again, inside the final box's middle third.
    all.push_back({3.2, 3.1});
    std::vector<Vec2> final_points = initial;
    const auto box = auto_domain_for_updates<2>(final_points, all);
    EXPECT_TRUE(same_box<2>(box, auto_domain<2>(final_points)));
    // An erased point far outside: the box must hold it, so it is the box of all points.
    all.push_back({30.0, 3.0});
    const auto wide = auto_domain_for_updates<2>(final_points, all);
    EXPECT_TRUE(same_box<2>(wide, auto_domain<2>(all)));
    EXPECT_TRUE(DynQuadtree<2>(wide).is_admissible({30.0, 3.0}));
}

/// An update run over the box of auto_domain_for_updates() and a from-scratch run over
/// auto_domain() of the final points give byte-identical dumps (tree and mesh), although the
/// run held points the final set does not have, some on the final bounding box's edge.
template <int D>
void check_update_run_matches_scratch(std::uint64_t seed) {
    Rng rng(seed);
    const auto initial = cloud<D>(rng, D == 2 ? 120 : 25, -4.0, 0.75);
    auto inserted = cloud<D>(rng, D == 2 ? 60 : 12, -4.0, 0.8);  // a bit wider than initial
    std::vector<PointD<D>> all = initial;
    all.insert(all.end(), inserted.begin(), inserted.end());
    // The script: insert everything, then erase every third inserted point and one initial.
    std::vector<PointD<D>> final_points = initial;
    final_points.erase(final_points.begin());
    for (std::size_t i = 0; i < inserted.size(); ++i)
        if (i % 3 != 0) final_points.push_back(inserted[i]);
    QuadtreeOptions<D> box = auto_domain_for_updates<D>(final_points, all);
    ASSERT_TRUE(same_box<D>(box, auto_domain<D>(final_points)));
    DynQuadMesh<D> run = DynQuadMesh<D>::build(initial, box);
    for (const auto& p : inserted) ASSERT_EQ(run.insert(p), InsertResult::Inserted);
    ASSERT_EQ(run.erase(initial.front()), EraseResult::Erased);
    for (std::size_t i = 0; i < inserted.size(); i += 3)
        ASSERT_EQ(run.erase(inserted[i]), EraseResult::Erased);
    const auto scratch = DynQuadMesh<D>::build(final_points, auto_domain<D>(final_points));
    EXPECT_EQ(run.canonical_dump(), scratch.canonical_dump());
}
TEST(AutoDomain, UpdateRunMatchesFromScratch2D) {
    for (std::uint64_t seed : {8u, 9u, 10u}) check_update_run_matches_scratch<2>(seed);
}
TEST(AutoDomain, UpdateRunMatchesFromScratch3D) { check_update_run_matches_scratch<3>(11); }

}  // namespace
}  // namespace dynmesh
