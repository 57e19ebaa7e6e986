#include "dynmesh/quadtree/quadtree.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <limits>
#include <map>
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

template <int D>
using Tree = DynQuadtree<D>;

/// Calls f(o) for every offset o in {-1, 0, 1}^D.
template <int D, class F>
void for_offsets(F&& f) {
    std::array<int, D> o;
    o.fill(-1);
    while (true) {
        f(o);
        int i = 0;
        while (i < D && o[i] == 1) o[i++] = -1;
        if (i == D) return;
        ++o[i];
    }
}

/// Independent oracle: I(P) by brute force straight from the definition (spec §1.4; paper
/// mode k = 1, rules C, A, B; mesh mode k = 2 and rules U, R as well).
template <int D>
std::vector<CellId<D>> oracle_leaves(const std::vector<typename Tree<D>::GridPoint>& pts,
                                     QuadtreeMode mode = QuadtreeMode::Paper) {
    constexpr int K = Tree<D>::kLevels;
    const bool mesh = mode == QuadtreeMode::Mesh;
    const std::int64_t k = mesh ? 2 : 1;
    std::set<CellId<D>> in_i;
    for (int j = 0; j <= K; ++j) {
        for (const auto& p : pts) {
            std::size_t near = 0;
            for (const auto& q : pts) {
                bool ok = true;
                for (int i = 0; i < D; ++i) {
                    const auto a = static_cast<std::int64_t>(p[i] >> j);
                    const auto b = static_cast<std::int64_t>(q[i] >> j);
                    ok = ok && std::abs(a - b) <= k;
                }
                near += ok ? 1 : 0;
            }
            if (near >= 2) {
                CellId<D> x{j, {}};
                for (int i = 0; i < D; ++i) x.index[i] = p[i] >> j;
                in_i.insert(x);
            }
        }
    }
    if (mesh && !pts.empty()) in_i.insert({K, {}});  // rule R
    std::vector<CellId<D>> work(in_i.begin(), in_i.end());
    while (!work.empty()) {
        const CellId<D> x = work.back();
        work.pop_back();
        const bool holds = std::any_of(pts.begin(), pts.end(), [&](const auto& p) {
            for (int i = 0; i < D; ++i)
                if ((p[i] >> x.level) != x.index[i]) return false;
            return true;
        });
        if (mesh && holds) {  // rule U: every equal-size neighbour
            const std::int64_t n = std::int64_t{1} << (K - x.level);
            for_offsets<D>([&](const std::array<int, D>& o) {
                CellId<D> y{x.level, {}};
                for (int i = 0; i < D; ++i) {
                    const std::int64_t b = static_cast<std::int64_t>(x.index[i]) + o[i];
                    if (b < 0 || b >= n) return;
                    y.index[i] = static_cast<std::uint64_t>(b);
                }
                if (in_i.insert(y).second) work.push_back(y);
            });
        }
        if (x.level == K) continue;
        const std::int64_t n = std::int64_t{1} << (K - x.level - 1);
        // every cell of the next level whose closure meets x's closure
        for_offsets<D>([&](const std::array<int, D>& o) {
            CellId<D> y{x.level + 1, {}};
            for (int i = 0; i < D; ++i) {
                const auto a = static_cast<std::int64_t>(x.index[i]);
                const std::int64_t b = (a >> 1) + o[i];
                if (b < 0 || b >= n || 2 * b > a + 1 || a > 2 * b + 2) return;
                y.index[i] = static_cast<std::uint64_t>(b);
            }
            if (in_i.insert(y).second) work.push_back(y);
        });
    }
    std::vector<CellId<D>> leaves;
    if (in_i.empty()) leaves.push_back({K, {}});
    for (const auto& x : in_i)
        for (int mask = 0; mask < (1 << D); ++mask) {
            CellId<D> ch{x.level - 1, {}};
            for (int i = 0; i < D; ++i) ch.index[i] = 2 * x.index[i] + ((mask >> i) & 1);
            if (!in_i.contains(ch)) leaves.push_back(ch);
        }
    std::sort(leaves.begin(), leaves.end());
    return leaves;
}

/// The paper's oracle (spec §2.1, Figure 2, T3): QuadTreeRefine run literally, with FIFO work
/// buckets, rounds (split all cells of one size, then test the new children), crowding tested
/// against the current leaf neighbours (§1.3) and balance splits of neighbours >= 4x larger.
template <int D>
class PaperQtr {
public:
    using GP = typename Tree<D>::GridPoint;
    static constexpr int K = Tree<D>::kLevels;

    explicit PaperQtr(const std::vector<GP>& pts) {
        const CellId<D> root{K, {}};
        leaves_[root] = pts;
        std::vector<std::deque<CellId<D>>> w(K + 1);
        if (pts.size() >= 2) w[K].push_back(root);
        int l = K;
        auto any = [&] {
            return std::any_of(w.begin(), w.end(), [](const auto& q) { return !q.empty(); });
        };
        while (any()) {
            while (l >= 0 && w[l].empty()) --l;
            if (l < 0)  // guard: the lemma says this never happens
                for (l = 0; w[l].empty(); ++l) {
                }
            std::vector<CellId<D>> newcells;
            while (!w[l].empty()) {
                const CellId<D> c = w[l].front();
                w[l].pop_front();
                const auto it = leaves_.find(c);
                if (it == leaves_.end()) continue;  // no longer a leaf
                const std::vector<GP> pts_c = it->second;
                leaves_.erase(it);
                internal_.insert(c);
                for (int mask = 0; mask < (1 << D); ++mask) {
                    const CellId<D> ch = child(c, mask);
                    auto& v = leaves_[ch];
                    for (const GP& g : pts_c) {
                        bool in = true;
                        for (int i = 0; i < D; ++i) in = in && (g[i] >> ch.level) == ch.index[i];
                        if (in) v.push_back(g);
                    }
                    newcells.push_back(ch);
                }
            }
            for (const CellId<D>& ch : newcells) {
                const auto nb = neighbour_leaves(ch);
                const std::size_t own = leaves_.at(ch).size();
                bool crowded = own >= 2;
                if (own == 1)
                    for (const auto& c2 : nb) crowded = crowded || !leaves_.at(c2).empty();
                if (crowded) w[ch.level].push_back(ch);
                for (const auto& c2 : nb)
                    if (c2.level >= ch.level + 2) w[c2.level].push_back(c2);
            }
            l = std::min(l + 1, K);
        }
    }
    [[nodiscard]] std::vector<CellId<D>> leaves() const {
        std::vector<CellId<D>> out;
        for (const auto& [c, v] : leaves_) out.push_back(c);
        return out;  // std::map: already sorted
    }

private:
    static CellId<D> child(const CellId<D>& c, int mask) {
        CellId<D> ch{c.level - 1, {}};
        for (int i = 0; i < D; ++i) ch.index[i] = 2 * c.index[i] + ((mask >> i) & 1);
        return ch;
    }
    static bool touches(const CellId<D>& a, const CellId<D>& b) {
        for (int i = 0; i < D; ++i) {
            const std::uint64_t alo = a.index[i] << a.level, ahi = (a.index[i] + 1) << a.level;
            const std::uint64_t blo = b.index[i] << b.level, bhi = (b.index[i] + 1) << b.level;
            if (ahi < blo || bhi < alo) return false;
        }
        return true;
    }
    void collect(const CellId<D>& y, const CellId<D>& x, std::set<CellId<D>>& out) const {
        if (!touches(y, x)) return;
        if (leaves_.contains(y)) {
            out.insert(y);
        } else if (internal_.contains(y)) {
            for (int mask = 0; mask < (1 << D); ++mask) collect(child(y, mask), x, out);
        }
    }
    std::set<CellId<D>> neighbour_leaves(const CellId<D>& x) const {
        std::set<CellId<D>> out;
        const std::int64_t n = std::int64_t{1} << (K - x.level);
        std::array<int, D> o;
        o.fill(-1);
        while (true) {
            CellId<D> y{x.level, {}};
            bool ok = false;
            for (int i = 0; i < D; ++i) ok = ok || o[i] != 0;
            for (int i = 0; i < D && ok; ++i) {
                const std::int64_t v = static_cast<std::int64_t>(x.index[i]) + o[i];
                ok = v >= 0 && v < n;
                y.index[i] = static_cast<std::uint64_t>(v);
            }
            if (ok) {
                CellId<D> z = y;  // a leaf containing y, if any
                while (z.level < K && !leaves_.contains(z) && !internal_.contains(z)) {
                    for (auto& v : z.index) v >>= 1;
                    ++z.level;
                }
                if (leaves_.contains(z))
                    out.insert(z);
                else
                    collect(y, x, out);
            }
            int i = 0;
            while (i < D && o[i] == 1) o[i++] = -1;
            if (i == D) break;
            ++o[i];
        }
        return out;
    }

    std::map<CellId<D>, std::vector<GP>> leaves_;
    std::set<CellId<D>> internal_;
};

template <int D>
void check_paper_oracle(std::uint64_t seed, int sets) {
    Rng rng(seed);
    for (int s = 0; s < sets; ++s) {
        const auto pts = D == 2 ? point_pool<D>(rng, 2 + rng.below(24), /*max_exp=*/16)
                                : point_pool<D>(rng, 2 + rng.below(12), /*max_exp=*/8, 0.0);
        const Tree<D> built = Tree<D>::build(pts);
        std::vector<typename Tree<D>::GridPoint> grid;
        for (const auto& p : pts) grid.push_back(built.grid_point(p));
        ASSERT_EQ(PaperQtr<D>(grid).leaves(), built.leaves()) << "seed " << seed << " set " << s;
    }
}

TEST(DynQuadtree, PaperFigure2OrderGivesTheCanonicalTree2D) { check_paper_oracle<2>(31, 200); }
TEST(DynQuadtree, PaperFigure2OrderGivesTheCanonicalTree3D) { check_paper_oracle<3>(32, 60); }

/// Runs `sequences` random insert/erase sequences; after each, compares the dynamic tree with
/// a shuffled re-insertion, a sorted re-insertion and build() of the final set (and, for small
/// sets, with the brute-force oracle). Checks invariants after every operation if asked.
template <int D>
void run_history_independence(std::uint64_t seed, int sequences, bool check_every_op,
                              QuadtreeMode mode = QuadtreeMode::Paper) {
    Rng rng(seed);
    const QuadtreeOptions<D> options{.mode = mode};
    for (int s = 0; s < sequences; ++s) {
        const auto pool = D == 2 ? point_pool<D>(rng, 4 + rng.below(28), /*max_exp=*/24)
                                 : point_pool<D>(rng, 4 + rng.below(20), /*max_exp=*/12,
                                                 /*tiny=*/0.02);
        Tree<D> tree(options);
        std::set<std::size_t> present;
        const std::size_t ops = 10 + rng.below(50);
        for (std::size_t k = 0; k < ops; ++k) {
            const std::size_t i = rng.below(pool.size());
            if (rng.coin(0.62)) {
                const InsertResult r = tree.insert(pool[i]);
                ASSERT_EQ(r,
                          present.contains(i) ? InsertResult::Duplicate : InsertResult::Inserted);
                present.insert(i);
            } else {
                const EraseResult r = tree.erase(pool[i]);
                ASSERT_EQ(r, present.contains(i) ? EraseResult::Erased : EraseResult::NotFound);
                present.erase(i);
            }
            ASSERT_EQ(tree.size(), present.size());
            if (check_every_op) {
                const auto bad = tree.check_invariants();
                ASSERT_TRUE(bad.ok()) << "seed " << seed << " seq " << s << " op " << k << ":\n"
                                         << bad.summary();
            }
        }
        std::vector<PointD<D>> final_set;
        for (std::size_t i : present) final_set.push_back(pool[i]);
        const std::string dump = tree.canonical_dump();

        const Tree<D> built = Tree<D>::build(final_set, options);
        ASSERT_EQ(built.canonical_dump(), dump) << "seed " << seed << " seq " << s;

        auto shuffled = final_set;
        for (std::size_t i = shuffled.size(); i > 1; --i)
            std::swap(shuffled[i - 1], shuffled[rng.below(i)]);
        Tree<D> again(options);
        for (const auto& p : shuffled) ASSERT_EQ(again.insert(p), InsertResult::Inserted);
        ASSERT_EQ(again.canonical_dump(), dump) << "seed " << seed << " seq " << s;

        auto sorted = final_set;
        std::sort(sorted.begin(), sorted.end(), [](const PointD<D>& a, const PointD<D>& b) {
            for (int i = 0; i < D; ++i) {
                const auto ui = static_cast<std::size_t>(i);
                if (a[ui] != b[ui]) return a[ui] < b[ui];
            }
            return false;
        });
        Tree<D> ordered(options);
        for (const auto& p : sorted) ASSERT_EQ(ordered.insert(p), InsertResult::Inserted);
        ASSERT_EQ(ordered.canonical_dump(), dump) << "seed " << seed << " seq " << s;

        if (final_set.size() <= 24 && s % 4 == 0) {
            std::vector<typename Tree<D>::GridPoint> grid;
            for (const auto& p : final_set) grid.push_back(tree.grid_point(p));
            ASSERT_EQ(tree.leaves(), oracle_leaves<D>(grid, mode))
                << "seed " << seed << " seq " << s;
        }
        if (!check_every_op) {
            const auto bad = tree.check_invariants();
            ASSERT_TRUE(bad.ok()) << "seed " << seed << " seq " << s << ":\n" << bad.summary();
        }
    }
}

TEST(DynQuadtree, EmptyTreeIsTheRootLeaf) {
    const Tree<2> t2;
    EXPECT_EQ(t2.size(), 0u);
    EXPECT_EQ(t2.leaf_count(), 1u);
    EXPECT_TRUE(t2.check_invariants().ok()) << t2.check_invariants().summary();
    const Tree<3> t3;
    EXPECT_EQ(t3.leaf_count(), 1u);
    EXPECT_TRUE(t3.check_invariants().ok()) << t3.check_invariants().summary();
    EXPECT_EQ(Tree<2>::build({}).canonical_dump(), t2.canonical_dump());
}

TEST(DynQuadtree, OnePointDoesNotSplitTwoPointsDo) {
    Tree<2> t;
    ASSERT_EQ(t.insert({0.5, 0.5}), InsertResult::Inserted);
    EXPECT_EQ(t.leaf_count(), 1u);
    ASSERT_EQ(t.insert({0.4, 0.6}), InsertResult::Inserted);
    EXPECT_GT(t.leaf_count(), 1u);
    EXPECT_FALSE(t.last_update().split.empty());
    EXPECT_TRUE(t.check_invariants().ok()) << t.check_invariants().summary();
    ASSERT_EQ(t.erase({0.4, 0.6}), EraseResult::Erased);
    EXPECT_EQ(t.leaf_count(), 1u);
    EXPECT_FALSE(t.last_update().merged.empty());
}

TEST(DynQuadtree, HistoryIndependence2D) { run_history_independence<2>(11, 1000, false); }
TEST(DynQuadtree, HistoryIndependence3D) { run_history_independence<3>(12, 300, false); }
TEST(DynQuadtree, InvariantsAfterEveryOperation2D) { run_history_independence<2>(21, 80, true); }
TEST(DynQuadtree, InvariantsAfterEveryOperation3D) { run_history_independence<3>(22, 15, true); }
TEST(DynQuadtree, MeshModeHistoryIndependence2D) {
    run_history_independence<2>(13, 600, false, QuadtreeMode::Mesh);
}
TEST(DynQuadtree, MeshModeHistoryIndependence3D) {
    run_history_independence<3>(14, 120, false, QuadtreeMode::Mesh);
}
TEST(DynQuadtree, MeshModeInvariantsAfterEveryOperation2D) {
    run_history_independence<2>(23, 60, true, QuadtreeMode::Mesh);
}
TEST(DynQuadtree, MeshModeInvariantsAfterEveryOperation3D) {
    run_history_independence<3>(24, 10, true, QuadtreeMode::Mesh);
}

TEST(DynQuadtree, MeshModeRefinesThePaperTree) {
    // Every paper rule is implied by a mesh rule, so I_paper(P) ⊆ I_mesh(P): every paper leaf
    // is a union of mesh leaves.
    Rng rng(41);
    for (int s = 0; s < 50; ++s) {
        const auto pool = point_pool<2>(rng, 2 + rng.below(40), 20);
        const Tree<2> paper = Tree<2>::build(pool);
        const Tree<2> mesh = Tree<2>::build(pool, {.mode = QuadtreeMode::Mesh});
        for (const CellId<2>& c : mesh.leaves()) {
            CellId<2> a = c;  // walk up until a paper leaf or internal cell
            while (paper.cell_kind(a) == CellKind::Absent) {
                ++a.level;
                for (auto& v : a.index) v >>= 1;
            }
            EXPECT_EQ(paper.cell_kind(a), CellKind::Leaf)
                << "mesh leaf (level " << c.level << ") is not inside a paper leaf";
        }
        EXPECT_GE(mesh.leaf_count(), paper.leaf_count());
        EXPECT_TRUE(mesh.check_invariants().ok()) << mesh.check_invariants().summary();
    }
}

template <int D>
void check_bad_input_unchanged() {
    Rng rng(5);
    Tree<D> t;
    const auto pool = point_pool<D>(rng, 20);
    for (const auto& p : pool) ASSERT_EQ(t.insert(p), InsertResult::Inserted);
    const std::string before = t.canonical_dump();
    const auto report_splits = t.last_update().split;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();

    EXPECT_EQ(t.insert(pool[3]), InsertResult::Duplicate);
    PointD<D> near = pool[3];
    near[0] = std::nextafter(near[0], 1.0);  // snaps to the same grid point
    EXPECT_EQ(t.insert(near), InsertResult::Duplicate);
    PointD<D> out = pool[0];
    out[0] = 0.3;
    EXPECT_EQ(t.insert(out), InsertResult::OutsideDomain);
    out[0] = 0.7;
    EXPECT_EQ(t.insert(out), InsertResult::OutsideDomain);
    PointD<D> bad = pool[0];
    bad[D - 1] = nan;
    EXPECT_EQ(t.insert(bad), InsertResult::NotFinite);
    bad[D - 1] = -inf;
    EXPECT_EQ(t.insert(bad), InsertResult::NotFinite);
    EXPECT_EQ(t.erase(make_point<D>({0.5 + 1e-7, 0.5, 0.5})), EraseResult::NotFound);
    EXPECT_EQ(t.erase(out), EraseResult::NotFound);
    EXPECT_EQ(t.erase(bad), EraseResult::NotFound);

    EXPECT_EQ(t.canonical_dump(), before);
    EXPECT_EQ(t.size(), pool.size());
    EXPECT_EQ(t.last_update().split, report_splits);
    EXPECT_TRUE(t.check_invariants().ok()) << t.check_invariants().summary();

    // The middle third is closed.
    Tree<D> edge;
    EXPECT_EQ(edge.insert(make_point<D>({1.0 / 3.0, 2.0 / 3.0, 0.5})), InsertResult::Inserted);
}

TEST(DynQuadtree, BadInputLeavesStateUnchanged2D) { check_bad_input_unchanged<2>(); }
TEST(DynQuadtree, BadInputLeavesStateUnchanged3D) { check_bad_input_unchanged<3>(); }

TEST(DynQuadtree, BuildRejectsBadInput) {
    const std::vector<Vec2> dup{{0.5, 0.5}, {0.4, 0.4}, {0.5, 0.5}};
    EXPECT_THROW((void)Tree<2>::build(dup), InvalidInput);
    const std::vector<Vec2> outside{{0.5, 0.5}, {0.1, 0.5}};
    EXPECT_THROW((void)Tree<2>::build(outside), InvalidInput);
    const std::vector<Vec2> nan{{0.5, std::numeric_limits<double>::quiet_NaN()}};
    EXPECT_THROW((void)Tree<2>::build(nan), InvalidInput);
    EXPECT_THROW(Tree<2>({.origin = {0, 0}, .width = 0.0}), InvalidInput);
    EXPECT_THROW(Tree<3>({.origin = {0, std::nan(""), 0}, .width = 1.0}), InvalidInput);
    const Tree<2> t;
    EXPECT_THROW((void)t.grid_point({0.9, 0.5}), InvalidInput);
}

template <int D>
void check_clustered(double spacing) {
    Tree<D> t;
    std::vector<PointD<D>> pts;
    Rng rng(9);
    // A tight cluster at spacing `spacing`, one at 1e-9, plus a few far points.
    for (int i = 0; i < 12; ++i) {
        PointD<D> p = make_point<D>({0.5, 0.45, 0.55});
        p[0] += spacing * i;
        p[1] += spacing * (i % 3);
        pts.push_back(p);
    }
    for (int i = 0; i < 6; ++i) pts.push_back(make_point<D>({0.61 + 1e-9 * i, 0.4, 0.6}));
    for (int i = 0; i < 6; ++i)
        pts.push_back(make_point<D>(
            {rng.uniform(0.34, 0.66), rng.uniform(0.34, 0.66), rng.uniform(0.34, 0.66)}));
    for (const auto& p : pts) {
        ASSERT_EQ(t.insert(p), InsertResult::Inserted);
        const auto bad = t.check_invariants();
        ASSERT_TRUE(bad.ok()) << bad.summary();
    }
    EXPECT_EQ(Tree<D>::build(pts).canonical_dump(), t.canonical_dump());
    // Deep: the smallest leaf is far below the cluster spacing's level 0 of the domain.
    int min_level = Tree<D>::kLevels;
    for (const auto& c : t.leaves()) min_level = std::min(min_level, c.level);
    EXPECT_LT(min_level, 52 + static_cast<int>(std::log2(spacing)) + 2);
    for (std::size_t i = 0; i < pts.size(); i += 2) {
        ASSERT_EQ(t.erase(pts[i]), EraseResult::Erased);
        const auto bad = t.check_invariants();
        ASSERT_TRUE(bad.ok()) << bad.summary();
    }
    std::vector<PointD<D>> rest;
    for (std::size_t i = 1; i < pts.size(); i += 2) rest.push_back(pts[i]);
    EXPECT_EQ(Tree<D>::build(rest).canonical_dump(), t.canonical_dump());
}

TEST(DynQuadtree, ClusteredInputs2D) {
    for (double s : {1e-3, 1e-6, 1e-9, 1e-12}) check_clustered<2>(s);
}
TEST(DynQuadtree, ClusteredInputs3D) { check_clustered<3>(1e-9); }

template <int D>
void check_erase_all() {
    Rng rng(3);
    const std::string empty = Tree<D>().canonical_dump();
    for (int round = 0; round < 5; ++round) {
        auto pool = point_pool<D>(rng, 60);
        Tree<D> t;
        for (const auto& p : pool) ASSERT_EQ(t.insert(p), InsertResult::Inserted);
        for (std::size_t i = pool.size(); i > 1; --i) std::swap(pool[i - 1], pool[rng.below(i)]);
        for (const auto& p : pool) ASSERT_EQ(t.erase(p), EraseResult::Erased);
        EXPECT_EQ(t.size(), 0u);
        EXPECT_EQ(t.leaf_count(), 1u);
        EXPECT_EQ(t.internal_count(), 0u);
        EXPECT_EQ(t.canonical_dump(), empty);
        EXPECT_TRUE(t.check_invariants().ok()) << t.check_invariants().summary();
    }
}

TEST(DynQuadtree, EraseAllReturnsToEmptyTree2D) { check_erase_all<2>(); }
TEST(DynQuadtree, EraseAllReturnsToEmptyTree3D) { check_erase_all<3>(); }

TEST(DynQuadtree, EraseThenReinsertRestoresTheTree) {
    Rng rng(4);
    const auto pool = point_pool<2>(rng, 200);
    Tree<2> t;
    for (const auto& p : pool) ASSERT_EQ(t.insert(p), InsertResult::Inserted);
    const std::string dump = t.canonical_dump();
    for (std::size_t i = 0; i < pool.size(); i += 7) {
        ASSERT_EQ(t.erase(pool[i]), EraseResult::Erased);
        const auto merged = t.last_update().merged;
        ASSERT_EQ(t.insert(pool[i]), InsertResult::Inserted);
        // Insert undoes exactly what the erase did.
        auto resplit = t.last_update().split;
        auto m = merged;
        std::sort(m.begin(), m.end());
        std::sort(resplit.begin(), resplit.end());
        EXPECT_EQ(resplit, m);
        ASSERT_EQ(t.canonical_dump(), dump);
    }
}

TEST(DynQuadtree, CustomDomain) {
    const QuadtreeOptions<2> opt{.origin = {-30.0, 100.0}, .width = 300.0};
    Tree<2> t(opt);
    EXPECT_EQ(t.insert({0.0, 200.0}), InsertResult::OutsideDomain);
    std::vector<Vec2> pts{{80.0, 200.0}, {85.0, 201.0}, {100.0, 250.0}, {80.0, 200.001}};
    for (const auto& p : pts) ASSERT_EQ(t.insert(p), InsertResult::Inserted);
    EXPECT_TRUE(t.check_invariants().ok()) << t.check_invariants().summary();
    EXPECT_EQ(Tree<2>::build(pts, opt).canonical_dump(), t.canonical_dump());
    EXPECT_NE(Tree<2>::build(pts, opt).canonical_dump(), Tree<2>::build({}).canonical_dump());
}

/// Tree work of one update (support messages, crowding flips, splits, merges), averaged over
/// insert/erase pairs of the same query points at fixed density and growing n.
template <int D>
double mean_tree_work(std::size_t n, std::size_t n0, double side0, QuadtreeMode mode) {
    std::vector<PointD<D>> pts, queries;
    fixed_density_points<D>(n, n0, side0, 300, 91, pts, queries);
    QuadtreeOptions<D> options;
    options.mode = mode;
    Tree<D> t = Tree<D>::build(pts, options);
    return mean_update_work(
        t, queries,
        [](const Tree<D>& tree) {
            const auto& r = tree.last_update();
            return static_cast<double>(r.support_updates + r.crowding_changes + r.split.size() +
                                       r.merged.size());
        },
        400);
}

TEST(DynQuadtree, WorkPerUpdateDoesNotGrowWithN2D) {
    for (QuadtreeMode mode : {QuadtreeMode::Paper, QuadtreeMode::Mesh}) {
        const double w1 = mean_tree_work<2>(1000, 1000, 1.0 / 12, mode);
        const double w16 = mean_tree_work<2>(16000, 1000, 1.0 / 12, mode);
        EXPECT_GT(w1, 0);
        EXPECT_LT(w16, 1.25 * w1) << "n = 1000: " << w1 << ", n = 16000: " << w16;
    }
}

TEST(DynQuadtree, WorkPerUpdateDoesNotGrowWithN3D) {
    const double w1 = mean_tree_work<3>(500, 500, 1.0 / 12, QuadtreeMode::Paper);
    const double w8 = mean_tree_work<3>(4000, 500, 1.0 / 6, QuadtreeMode::Paper);
    EXPECT_GT(w1, 0);
    EXPECT_LT(w8, 1.25 * w1) << "n = 500: " << w1 << ", n = 4000: " << w8;
}

// ---- resolution (quadtree.hpp, "Resolution") ------------------------------------------------

TEST(DynQuadtree, DyadicDomains) {
    EXPECT_TRUE(Tree<2>().dyadic());
    EXPECT_TRUE(Tree<2>({.origin = {-0.25, 1.5}, .width = 2.0}).dyadic());
    EXPECT_TRUE(Tree<3>({.origin = {0.0, -3.0, 0.5}, .width = 4.0}).dyadic());
    EXPECT_FALSE(Tree<2>({.origin = {0.1, 0.0}, .width = 1.0}).dyadic());  // origin off W/8
    EXPECT_FALSE(Tree<2>({.origin = {0.0, 0.0}, .width = 3.0}).dyadic());  // not a power of 2
}

TEST(DynQuadtree, RejectsDomainsWithoutAGrid) {
    EXPECT_THROW(Tree<2>({.origin = {0, 0}, .width = 1e-300}), InvalidInput);  // unit subnormal
    EXPECT_THROW(Tree<2>({.origin = {1.7e308, 0}, .width = 1e308}), InvalidInput);  // overflow
    EXPECT_NO_THROW(Tree<2>({.origin = {0, 0}, .width = 1e-290}));
}

/// A refused insertion changes nothing: tree, counts, last_update(); in both modes.
template <int D>
void check_refusal_unchanged(QuadtreeMode mode) {
    QuadtreeOptions<D> o;
    for (int d = 0; d < D; ++d) o.origin[static_cast<std::size_t>(d)] = 0.1;
    o.width = 3.0;  // not dyadic: lattice positions are rounded
    o.mode = mode;
    Tree<D> t(o);
    const auto a = make_point<D>({1.5, 1.5, 1.5});
    ASSERT_EQ(t.insert(a), InsertResult::Inserted);
    ASSERT_EQ(t.insert(make_point<D>({1.2, 1.8, 1.4})), InsertResult::Inserted);
    const std::string dump = t.canonical_dump();
    const auto split = t.last_update().split;
    const std::size_t messages = t.last_update().support_updates;
    for (double d : {1e-14, 1e-12, 2e-12}) {
        PointD<D> b = a;
        b[0] += d;
        EXPECT_EQ(t.insert(b), InsertResult::BeyondPrecision) << d;
        EXPECT_FALSE(t.contains(b)) << d;
        EXPECT_EQ(t.size(), 2u);
        EXPECT_EQ(t.canonical_dump(), dump) << d;
        EXPECT_EQ(t.last_update().split, split) << d;
        EXPECT_EQ(t.last_update().support_updates, messages) << d;
        const auto bad = t.check_invariants();
        ASSERT_TRUE(bad.ok()) << bad.summary();
    }
    PointD<D> far = a;
    far[0] += 1e-8;
    EXPECT_EQ(t.insert(far), InsertResult::Inserted);
    EXPECT_TRUE(t.check_invariants().ok()) << t.check_invariants().summary();
}
TEST(DynQuadtree, RefusalLeavesTheTreeUnchanged2D) {
    check_refusal_unchanged<2>(QuadtreeMode::Paper);
    check_refusal_unchanged<2>(QuadtreeMode::Mesh);
}
TEST(DynQuadtree, RefusalLeavesTheTreeUnchanged3D) {
    check_refusal_unchanged<3>(QuadtreeMode::Paper);
    check_refusal_unchanged<3>(QuadtreeMode::Mesh);
}

/// Acceptance is a property of the point set: an insertion is refused exactly when build() of
/// the resulting set throws, over random walks with pairs around the resolution threshold.
template <int D>
void check_resolution_is_a_set_property(QuadtreeMode mode, std::uint64_t seed, int steps = 150) {
    QuadtreeOptions<D> o;
    for (int d = 0; d < D; ++d) o.origin[static_cast<std::size_t>(d)] = -0.7;
    o.width = 5.0;  // not dyadic
    o.mode = mode;
    Rng rng(seed);
    std::vector<PointD<D>> pool;
    for (int i = 0; i < 24; ++i) {
        PointD<D> p;
        for (int d = 0; d < D; ++d) p[static_cast<std::size_t>(d)] = rng.uniform(1.2, 2.6);
        pool.push_back(p);
        for (int k = 0; k < 2; ++k) {  // partners 10^-13 .. 10^-10 away (threshold ~1e-11)
            PointD<D> q = p;
            for (int d = 0; d < D; ++d)
                q[static_cast<std::size_t>(d)] += std::pow(10.0, -rng.uniform(10, 13)) *
                                                  rng.uniform(-1, 1);
            pool.push_back(q);
        }
    }
    Tree<D> t(o);
    std::vector<PointD<D>> present;
    std::size_t refused = 0, accepted = 0;
    for (int step = 0; step < steps; ++step) {
        const std::string what = "seed " + std::to_string(seed) + " step " + std::to_string(step);
        if (!present.empty() && rng.coin(0.3)) {
            const std::size_t k = rng.below(present.size());
            ASSERT_EQ(t.erase(present[k]), EraseResult::Erased) << what;
            present.erase(present.begin() + static_cast<std::ptrdiff_t>(k));
            continue;
        }
        const PointD<D> p = pool[rng.below(pool.size())];
        if (t.contains(p)) continue;
        std::vector<PointD<D>> with = present;
        with.push_back(p);
        bool builds = true;
        try {
            (void)Tree<D>::build(with, o);
        } catch (const InvalidInput&) {
            builds = false;
        }
        const InsertResult r = t.insert(p);
        if (r == InsertResult::Duplicate) continue;
        ASSERT_EQ(r == InsertResult::Inserted, builds) << what;
        ASSERT_TRUE(r == InsertResult::Inserted || r == InsertResult::BeyondPrecision) << what;
        if (r == InsertResult::Inserted) {
            present.push_back(p);
            ++accepted;
        } else {
            ++refused;
        }
        const auto bad = t.check_invariants();
        ASSERT_TRUE(bad.ok()) << what << ":\n" << bad.summary();
    }
    EXPECT_GT(refused, static_cast<std::size_t>(steps / 30)) << "the walk never reached the threshold";
    EXPECT_GT(accepted, static_cast<std::size_t>(steps / 8));
    EXPECT_EQ(t.canonical_dump(), Tree<D>::build(present, o).canonical_dump());
}
TEST(DynQuadtree, ResolutionIsAPropertyOfThePointSet2D) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        check_resolution_is_a_set_property<2>(QuadtreeMode::Paper, seed);
        check_resolution_is_a_set_property<2>(QuadtreeMode::Mesh, seed + 10);
    }
}
TEST(DynQuadtree, ResolutionIsAPropertyOfThePointSet3D) {
    check_resolution_is_a_set_property<3>(QuadtreeMode::Paper, 4, 60);
    check_resolution_is_a_set_property<3>(QuadtreeMode::Mesh, 5, 30);
}

TEST(DynQuadtree, BuildNamesTheUnresolvedPoint) {
    const QuadtreeOptions<2> o{.origin = {0.1, 0.1}, .width = 3.0};
    const std::vector<Vec2> pts{{1.2, 1.3}, {1.9, 1.9}, {1.5, 1.5}, {1.5 + 1e-13, 1.5}};
    try {
        (void)Tree<2>::build(pts, o);
        FAIL() << "build accepted points 1e-13 apart on a rounded lattice";
    } catch (const InvalidInput& e) {
        const std::string msg = e.what();
        EXPECT_TRUE(msg.find("point 2 ") != std::string::npos ||
                    msg.find("point 3 ") != std::string::npos)
            << msg;
        EXPECT_NE(msg.find("resolution"), std::string::npos) << msg;
    }
    // The unit box is dyadic: the same spacing is resolved there.
    EXPECT_NO_THROW((void)Tree<2>::build(std::vector<Vec2>{{0.5, 0.5}, {0.5 + 1e-13, 0.5}}));
}

TEST(DynQuadtree, LeafSizeTracksNearestNeighbourDistance) {
    // Two points at distance d: the leaves holding them have size Θ(d).
    for (int e = 5; e <= 45; e += 8) {
        Tree<2> t;
        const double d = std::ldexp(1.0, -e);
        ASSERT_EQ(t.insert({0.5, 0.5}), InsertResult::Inserted);
        ASSERT_EQ(t.insert({0.5 + d, 0.5}), InsertResult::Inserted);
        int min_level = 99;
        for (const auto& c : t.leaves()) min_level = std::min(min_level, c.level);
        const double leaf_size = std::ldexp(1.0, min_level - 52);
        EXPECT_GE(leaf_size, d / 8) << "e=" << e;
        EXPECT_LE(leaf_size, d) << "e=" << e;
        EXPECT_TRUE(t.check_invariants().ok()) << t.check_invariants().summary();
    }
}

}  // namespace
}  // namespace dynmesh
