#include "dynmesh/quadtree/dyn_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "quadtree_fixtures.hpp"

namespace dynmesh {
namespace {
using namespace testing_quadtree;

/// The simplex list of a mesh of either dimension.
const auto& simplices_of(const QuadMesh2& m) { return m.triangles; }
const auto& simplices_of(const OctMesh3& m) { return m.tets; }

SimplexMeshD<2> static_mesh(const DynQuadtree<2>& t) { return quad_mesh(t); }
SimplexMeshD<3> static_mesh(const DynQuadtree<3>& t) { return oct_mesh(t); }
std::vector<std::string> check_mesh(const QuadMesh2& m) { return check_quad_mesh(m).problems; }
std::vector<std::string> check_mesh(const OctMesh3& m) { return check_oct_mesh(m).problems; }

/// Field-by-field equality (the canonical output files are a function of these).
template <class M>
void expect_same_mesh(const M& a, const M& b, const std::string& what) {
    ASSERT_EQ(a.points.size(), b.points.size()) << what;
    EXPECT_EQ(a.points, b.points) << what;
    EXPECT_EQ(simplices_of(a), simplices_of(b)) << what;
    EXPECT_EQ(a.input_vertices, b.input_vertices) << what;
    EXPECT_EQ(a.leaves, b.leaves) << what;
}

/// Every input point is a vertex: at its own coordinates, or at its grid position when its
/// leaf is smaller than two input quanta (points within about two quanta of another).
template <int D, class M>
void expect_input_vertices(const DynQuadtree<D>& tree, const M& mesh, const std::string& what) {
    const auto pts = tree.points();
    ASSERT_EQ(mesh.input_vertices.size(), pts.size()) << what;
    const double unit = tree.options().width * 0x1p-52;
    for (std::size_t j = 0; j < pts.size(); ++j) {
        const auto& [g, p] = pts[j];
        PointD<D> want = p;
        if (tree.leaf_containing(g).level <= DynQuadtree<D>::kGuardBits)
            for (int d = 0; d < D; ++d) {
                const auto ud = static_cast<std::size_t>(d);
                want[ud] = tree.options().origin[ud] + static_cast<double>(g[ud]) * unit;
            }
        ASSERT_EQ(mesh.points[mesh.input_vertices[j]], want) << what << " input " << j;
    }
}

/// Random insert/erase sequences. After every `every`-th operation: the dynamic mesh equals
/// the from-scratch mesh of the current point set (paper-mode tree → quad_mesh / oct_mesh,
/// an independent path through DynQuadtree::build), its invariants hold, the maintained
/// simplex count and the report's delta are right, and the mesh is valid.
template <int D>
void run_sequences(std::uint64_t seed, int sequences, int every) {
    Rng rng(seed);
    for (int s = 0; s < sequences; ++s) {
        const auto pool = D == 2 ? point_pool<D>(rng, 4 + rng.below(40), /*max_exp=*/24)
                                 : point_pool<D>(rng, 3 + rng.below(10), /*max_exp=*/10,
                                                 /*tiny=*/0.0);
        DynQuadMesh<D> dm;
        MeshMirror<D> mirror(dm.current_mesh());
        std::set<std::size_t> present;
        const std::size_t ops = 10 + rng.below(40);
        for (std::size_t k = 0; k < ops; ++k) {
            const std::size_t i = rng.below(pool.size());
            const std::size_t before = dm.simplex_count();
            if (rng.coin(0.65)) {
                const InsertResult r = dm.insert(pool[i]);
                ASSERT_EQ(r,
                          present.contains(i) ? InsertResult::Duplicate : InsertResult::Inserted);
                if (r != InsertResult::Inserted) continue;
                present.insert(i);
            } else {
                const EraseResult r = dm.erase(pool[i]);
                ASSERT_EQ(r, present.contains(i) ? EraseResult::Erased : EraseResult::NotFound);
                if (r != EraseResult::Erased) continue;
                present.erase(i);
            }
            const std::string what = "seed " + std::to_string(seed) + " seq " +
                                     std::to_string(s) + " op " + std::to_string(k);
            const auto& rep = dm.last_update();
            ASSERT_EQ(dm.simplex_count() + rep.simplices_removed,
                      before + rep.simplices_added);
            ASSERT_EQ(rep.simplices_added, dm.last_change().added_simplices.size());
            ASSERT_EQ(rep.simplices_removed, dm.last_change().removed_simplices.size());
            // A copy fed only with the deltas stays equal to the live mesh, slot for slot.
            mirror.apply(dm.last_change(), what);
            if (::testing::Test::HasFatalFailure()) return;
            if (k % 8 == 0 || k + 1 == ops) mirror.expect_equals(dm.current_mesh(), what);
            if (::testing::Test::HasFatalFailure()) return;
            if (k % static_cast<std::size_t>(every) != 0 && k + 1 != ops) continue;
            const auto bad = dm.check_invariants();
            ASSERT_TRUE(bad.ok()) << what << ":\n" << bad.summary();
            std::vector<PointD<D>> current;
            for (std::size_t j : present) current.push_back(pool[j]);
            const auto want = static_mesh(DynQuadtree<D>::build(current));
            const auto got = dm.mesh();
            expect_same_mesh(got, want, what);
            // The live mesh holds the from-scratch mesh's simplices (as a set); at the end of
            // each sequence (check_invariants() compares it with mesh() at every checkpoint).
            if (k + 1 == ops) {
                ASSERT_EQ(live_coords<D>(dm.current_mesh()),
                          simplex_coords<D>(want.points, simplices_of(want)))
                    << what;
            }
            if (k + 1 == ops) {  // the dump of tree and mesh equals a from-scratch build's
                ASSERT_EQ(dm.canonical_dump(), DynQuadMesh<D>::build(current).canonical_dump())
                    << what;
            }
            ASSERT_EQ(simplices_of(got).size(), dm.simplex_count()) << what;
            const auto invalid = check_mesh(got);
            ASSERT_TRUE(invalid.empty()) << what << ":\n" << joined(invalid);
            expect_input_vertices(dm.tree(), got, what);
        }
    }
}

TEST(DynQuadMesh, MatchesFromScratchAfterEveryUpdate2D) { run_sequences<2>(51, 80, 1); }
TEST(DynQuadMesh, MatchesFromScratchAfterEveryUpdate3D) { run_sequences<3>(52, 6, 1); }
TEST(DynQuadMesh, MatchesFromScratchManySequences2D) { run_sequences<2>(53, 500, 8); }
TEST(DynQuadMesh, MatchesFromScratchManySequences3D) { run_sequences<3>(54, 50, 10); }

/// Points a few input quanta apart (the finest the grid resolves): leaves down to a quarter
/// of a quantum, inputs up to a quantum away from their grid point. Static and dynamic meshes
/// agree, are valid and keep the angle bounds.
template <int D>
void check_quantum_clusters(std::uint64_t seed, int clusters) {
    Rng rng(seed);
    const double q = std::ldexp(1.0, -49) * 1.0000001;  // just over one quantum (unit domain)
    std::size_t small_leaves = 0;
    for (int t = 0; t < clusters; ++t) {
        PointD<D> c;
        for (int d = 0; d < D; ++d) c[static_cast<std::size_t>(d)] = rng.uniform(0.4, 0.6);
        const auto spread = static_cast<std::int64_t>(3 + rng.below(40));
        std::vector<PointD<D>> pts;
        std::set<typename DynQuadtree<D>::GridPoint> seen;
        const DynQuadtree<D> probe;
        const std::size_t n = 2 + rng.below(5);
        while (pts.size() < n) {
            PointD<D> p = c;
            for (int d = 0; d < D; ++d)
                p[static_cast<std::size_t>(d)] +=
                    static_cast<double>(static_cast<std::int64_t>(rng.below(spread)) - spread / 2) * q;
            if (seen.insert(probe.grid_point(p)).second) pts.push_back(p);
        }
        DynQuadMesh<D> dm;
        for (const auto& p : pts) ASSERT_EQ(dm.insert(p), InsertResult::Inserted);
        ASSERT_EQ(dm.erase(pts[0]), EraseResult::Erased);
        ASSERT_EQ(dm.insert(pts[0]), InsertResult::Inserted);
        const std::string what = "cluster " + std::to_string(t);
        const auto got = dm.mesh();
        expect_same_mesh(got, static_mesh(DynQuadtree<D>::build(pts)), what);
        const auto invalid = check_mesh(got);
        ASSERT_TRUE(invalid.empty()) << what << ":\n" << joined(invalid);
        expect_input_vertices(dm.tree(), got, what);
        if constexpr (D == 2) {
            const AngleRangeDeg a = angle_range_deg(got);
            EXPECT_GE(a.min, kQuadMeshMinAngleDeg - 1e-6) << what;
            EXPECT_LE(a.max, kQuadMeshMaxAngleDeg + 1e-6) << what;
        } else {
            const DihedralRangeDeg a = dihedral_range_deg(got);
            EXPECT_GE(a.min, kOctMeshMinDihedralDeg) << what;
            EXPECT_LE(a.max, kOctMeshMaxDihedralDeg) << what;
        }
        for (const auto& [g, p] : dm.tree().points())
            small_leaves += dm.tree().leaf_containing(g).level <= DynQuadtree<D>::kGuardBits;
    }
    EXPECT_GT(small_leaves, 0u) << "the family never reached leaves below two quanta";
}
TEST(DynQuadMesh, PointsAFewQuantaApart2D) { check_quantum_clusters<2>(71, 400); }
TEST(DynQuadMesh, PointsAFewQuantaApart3D) { check_quantum_clusters<3>(72, 15); }

TEST(DynQuadMesh, EmptyMeshCoversTheDomain) {
    const DynQuadMesh<2> m2;
    EXPECT_EQ(m2.simplex_count(), 2u);
    EXPECT_TRUE(check_quad_mesh(m2.mesh()).ok());
    const DynQuadMesh<3> m3;
    EXPECT_EQ(m3.simplex_count(), 12u);  // the root cube: 6 faces × 2 triangles, coned
    EXPECT_TRUE(check_oct_mesh(m3.mesh()).ok());
}

TEST(DynQuadMesh, InsertThenEraseRestoresTheMesh) {
    Rng rng(61);
    const auto pool = point_pool<2>(rng, 300, 30);
    const std::vector<Vec2> base(pool.begin(), pool.begin() + 250);
    DynQuadMesh<2> dm = DynQuadMesh<2>::build(base);
    const QuadMesh2 before = dm.mesh();
    const std::size_t count = dm.simplex_count();
    for (std::size_t i = 250; i < pool.size(); ++i) {
        ASSERT_EQ(dm.insert(pool[i]), InsertResult::Inserted);
        const std::size_t added = dm.last_update().simplices_added;
        const std::size_t removed = dm.last_update().simplices_removed;
        ASSERT_EQ(dm.erase(pool[i]), EraseResult::Erased);
        // The erase undoes exactly what the insert did.
        EXPECT_EQ(dm.last_update().simplices_added, removed);
        EXPECT_EQ(dm.last_update().simplices_removed, added);
        ASSERT_EQ(dm.simplex_count(), count);
    }
    expect_same_mesh(dm.mesh(), before, "after insert/erase pairs");
    EXPECT_TRUE(dm.check_invariants().ok()) << dm.check_invariants().summary();
}

/// Work of one update = tree cells touched (support messages, crowding flips, splits and
/// merges) + leaves recoded + simplices changed, averaged over insert/erase pairs of the same
/// query points, at fixed point density and growing n (fixed_density_points). The work must
/// stay flat: only the point set far from the queries grows. (3D: the tree alone, in
/// quadtree_test.cpp; a 3D mesh of thousands of points is too slow for a unit test.)
template <int D>
double mean_mesh_work(std::size_t n, std::size_t n0, double side0) {
    std::vector<PointD<D>> pts, queries;
    fixed_density_points<D>(n, n0, side0, 150, 81, pts, queries);
    DynQuadMesh<D> dm = DynQuadMesh<D>::build(pts);
    return mean_update_work(
        dm, queries,
        [](const DynQuadMesh<D>& m) {
            const auto& r = m.last_update();
            return static_cast<double>(r.tree.support_updates + r.tree.crowding_changes +
                                       r.tree.split.size() + r.tree.merged.size() +
                                       r.leaves_examined + r.simplices_added + r.simplices_removed);
        },
        200);
}

TEST(DynQuadMesh, WorkPerUpdateDoesNotGrowWithN2D) {
    const double w1 = mean_mesh_work<2>(250, 250, 1.0 / 12);
    const double w16 = mean_mesh_work<2>(4000, 250, 1.0 / 12);  // side 1/3: the middle third
    EXPECT_GT(w1, 0);
    EXPECT_LT(w16, 1.25 * w1) << "n = 250: " << w1 << ", n = 4000: " << w16;
}

/// A point so close to another that its leaves would be finer than the rounded lattice of a
/// non-dyadic domain resolves: refused, nothing changes (mesh, live mesh, report). On the
/// unit (dyadic) domain the lattice is exact and the same configuration is accepted.
TEST(DynQuadMesh, RefusesPointsBeyondPrecision) {
    const QuadtreeOptions<2> rounded{.origin = {0.1, 0.1}, .width = 3.0};
    DynQuadMesh<2> dm(rounded);
    ASSERT_EQ(dm.insert({1.5, 1.5}), InsertResult::Inserted);
    ASSERT_EQ(dm.insert({1.25, 1.75}), InsertResult::Inserted);
    const std::string dump = dm.canonical_dump();
    const QuadMeshUpdateReport<2> rep = dm.last_update();
    const std::size_t change = dm.last_change().added_simplices.size();
    const std::vector<SimplexCoords<2>> live = live_coords<2>(dm.current_mesh());
    for (double d : {1e-14, 1e-13, 1e-12}) {
        EXPECT_EQ(dm.insert({1.5 + d, 1.5}), InsertResult::BeyondPrecision) << d;
        EXPECT_EQ(dm.canonical_dump(), dump) << d;
        EXPECT_EQ(dm.last_update().simplices_added, rep.simplices_added) << d;
        EXPECT_EQ(dm.last_update().tree.split, rep.tree.split) << d;
        EXPECT_EQ(dm.last_change().added_simplices.size(), change) << d;
        EXPECT_EQ(live_coords<2>(dm.current_mesh()), live) << d;
    }
    EXPECT_TRUE(dm.check_invariants().ok()) << dm.check_invariants().summary();
    // Far enough for the rounded lattice (a leaf spans > 2^14 ulps): accepted and valid.
    ASSERT_EQ(dm.insert({1.5 + 1e-8, 1.5}), InsertResult::Inserted);
    EXPECT_TRUE(check_quad_mesh(dm.mesh()).ok());
    EXPECT_TRUE(dm.check_invariants().ok()) << dm.check_invariants().summary();

    DynQuadMesh<2> exact;  // the unit box: dyadic
    ASSERT_EQ(exact.insert({0.5, 0.5}), InsertResult::Inserted);
    ASSERT_EQ(exact.insert({0.5 + 1e-14, 0.5}), InsertResult::Inserted);
    EXPECT_TRUE(check_quad_mesh(exact.mesh()).ok());
    EXPECT_TRUE(exact.check_invariants().ok()) << exact.check_invariants().summary();
}

template <int D>
void check_bad_input() {
    Rng rng(63);
    const auto pool = point_pool<D>(rng, 12, 12);
    DynQuadMesh<D> dm = DynQuadMesh<D>::build(pool);
    const auto before = dm.mesh();
    const std::size_t count = dm.simplex_count();
    PointD<D> nan = pool[0];
    nan[0] = std::numeric_limits<double>::quiet_NaN();
    PointD<D> outside = pool[0];
    outside[0] = 0.9;
    EXPECT_EQ(dm.insert(pool[3]), InsertResult::Duplicate);
    EXPECT_EQ(dm.insert(nan), InsertResult::NotFinite);
    EXPECT_EQ(dm.insert(outside), InsertResult::OutsideDomain);
    EXPECT_EQ(dm.erase(outside), EraseResult::NotFound);
    EXPECT_EQ(dm.erase(nan), EraseResult::NotFound);
    PointD<D> absent = pool[0];
    absent[0] += 1e-3;
    if (!dm.tree().contains(absent)) {
        EXPECT_EQ(dm.erase(absent), EraseResult::NotFound);
    }
    EXPECT_EQ(dm.simplex_count(), count);
    expect_same_mesh(dm.mesh(), before, "after rejected updates");
    EXPECT_TRUE(dm.check_invariants().ok()) << dm.check_invariants().summary();
    std::vector<PointD<D>> dup = pool;
    dup.push_back(pool[5]);
    EXPECT_THROW((void)DynQuadMesh<D>::build(dup), InvalidInput);
}
TEST(DynQuadMesh, BadInputLeavesStateUnchanged2D) { check_bad_input<2>(); }
TEST(DynQuadMesh, BadInputLeavesStateUnchanged3D) { check_bad_input<3>(); }

TEST(DynQuadMesh, CustomDomain) {
    const QuadtreeOptions<2> domain{.origin = {-3.0, 10.0}, .width = 6.0};
    DynQuadMesh<2> dm(domain);
    Rng rng(64);
    for (int i = 0; i < 50; ++i)
        ASSERT_EQ(dm.insert({rng.uniform(-1.0, 1.0), rng.uniform(12.0, 14.0)}),
                  InsertResult::Inserted);
    EXPECT_EQ(dm.tree().options().mode, QuadtreeMode::Mesh);
    const QuadMesh2 m = dm.mesh();
    EXPECT_EQ(m.origin.x, -3.0);
    EXPECT_TRUE(check_quad_mesh(m).ok());
    const AngleRangeDeg a = angle_range_deg(m);
    EXPECT_GE(a.min, kQuadMeshMinAngleDeg - 1e-6);
    EXPECT_LE(a.max, kQuadMeshMaxAngleDeg + 1e-6);
}

}  // namespace
}  // namespace dynmesh
