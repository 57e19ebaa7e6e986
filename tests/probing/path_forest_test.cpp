#include "probing/path_forest.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "dynmesh/geometry/random.hpp"

namespace dynmesh {
namespace {

struct TreeNode {
    std::uint32_t prev = 0, depth = 0, jump = 0;
};

/// A random tree: node 0 is the top; node k's parent is drawn among the earlier nodes, biased
/// toward recent ones so that long chains (depth in the hundreds) occur.
std::vector<TreeNode> random_tree(std::size_t n, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<TreeNode> t(n);
    t[0] = {0, 1, 0};
    for (std::uint32_t k = 1; k < n; ++k) {
        const double u = rng.uniform(0, 1);
        const std::uint32_t back = static_cast<std::uint32_t>(u * u * u * std::min<double>(k, 40));
        const std::uint32_t p = k - 1 - std::min(back, k - 1);
        t[k].prev = p;
        t[k].depth = t[p].depth + 1;
        t[k].jump = detail::skew_jump(t, p);
    }
    return t;
}

std::uint32_t naive_lca(const std::vector<TreeNode>& t, std::uint32_t a, std::uint32_t b) {
    while (t[a].depth > t[b].depth) a = t[a].prev;
    while (t[b].depth > t[a].depth) b = t[b].prev;
    while (a != b) {
        a = t[a].prev;
        b = t[b].prev;
    }
    return a;
}

TEST(PathForest, JumpsPointToAncestorsAndLcaMatchesTheNaiveClimb) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        const std::vector<TreeNode> t = random_tree(3000, seed);
        std::uint32_t deepest = 0;
        for (std::uint32_t k = 0; k < t.size(); ++k) {
            deepest = std::max(deepest, t[k].depth);
            // The jump is an ancestor: climbing prev from k reaches it.
            std::uint32_t x = k;
            while (x != t[k].jump && x != 0) x = t[x].prev;
            ASSERT_EQ(x, t[k].jump) << k;
        }
        EXPECT_GT(deepest, 100u);
        Rng rng(seed + 10);
        for (int q = 0; q < 20000; ++q) {
            const auto a = static_cast<std::uint32_t>(rng.uniform(0, 1) * double(t.size() - 1));
            const auto b = static_cast<std::uint32_t>(rng.uniform(0, 1) * double(t.size() - 1));
            ASSERT_EQ(detail::lowest_common_ancestor(t, a, b), naive_lca(t, a, b)) << a << " " << b;
        }
    }
}

/// The jumps give logarithmic climbs: reaching the top from the deepest node takes O(log depth)
/// jumps (at most 3 log2(depth) in Myers' scheme).
TEST(PathForest, ClimbsAreLogarithmic) {
    std::vector<TreeNode> chain(1 << 14);
    chain[0] = {0, 1, 0};
    for (std::uint32_t k = 1; k < chain.size(); ++k) {
        chain[k].prev = k - 1;
        chain[k].depth = k + 1;
        chain[k].jump = detail::skew_jump(chain, k - 1);
    }
    int steps = 0;
    for (std::uint32_t x = std::uint32_t(chain.size() - 1); x != 0; ++steps)
        x = chain[x].jump != x ? chain[x].jump : chain[x].prev;
    EXPECT_LE(steps, 3 * 14);
    EXPECT_EQ(detail::lowest_common_ancestor(chain, std::uint32_t(chain.size() - 1), 5), 5u);
}

}  // namespace
}  // namespace dynmesh
