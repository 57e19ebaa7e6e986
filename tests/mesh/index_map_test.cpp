#include "dynmesh/mesh/index_map.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "dynmesh/geometry/random.hpp"

namespace dynmesh {
namespace {

// Random insertions, look-ups and erasures against std::map, with keys from a small range
// (long probe runs, many collisions, erasures inside runs) and from the whole range.
TEST(IndexMap, AgreesWithStdMapUnderRandomOperations) {
    for (std::uint64_t range : {64ull, 5000ull, 4000000000ull}) {
        Rng rng(range);
        IndexMap<int> map;
        std::map<std::uint32_t, int> ref;
        for (int step = 0; step < 200000; ++step) {
            const auto key = static_cast<std::uint32_t>(rng.below(range));
            const int op = static_cast<int>(rng.below(10));
            if (op < 5) {
                const auto [value, inserted] = map.try_emplace(key, step);
                const auto [it, ref_inserted] = ref.try_emplace(key, step);
                ASSERT_EQ(inserted, ref_inserted) << "step " << step;
                ASSERT_EQ(*value, it->second);
            } else if (op < 8) {
                ASSERT_EQ(map.erase(key), ref.erase(key) == 1) << "step " << step;
            } else {
                const int* v = map.find(key);
                const auto it = ref.find(key);
                ASSERT_EQ(v != nullptr, it != ref.end()) << "step " << step;
                if (v) {
                    ASSERT_EQ(*v, it->second);
                }
            }
            ASSERT_EQ(map.size(), ref.size());
        }
        std::map<std::uint32_t, int> listed;
        map.for_each([&](std::uint32_t k, int v) { listed.emplace(k, v); });
        EXPECT_EQ(listed, ref);
        map.clear();
        EXPECT_EQ(map.size(), 0u);
        for (const auto& [k, v] : ref) EXPECT_FALSE(map.contains(k));
    }
}

// A small table (16 slots, at most 7 keys) filled with random keys and emptied in random
// order, many times: probe runs often wrap around the end of the table, and erasing inside
// them must keep every remaining key reachable.
TEST(IndexMap, EraseInsideWrappedProbeRuns) {
    Rng rng(3);
    IndexMap<std::uint32_t> map;
    for (int round = 0; round < 20000; ++round) {
        map.clear();
        std::vector<std::uint32_t> keys;
        while (keys.size() < 7) {
            const auto k = static_cast<std::uint32_t>(rng.below(4000000000ull));
            if (map.try_emplace(k, k ^ 0x5555u).second) keys.push_back(k);
        }
        for (std::size_t i = keys.size(); i > 1; --i) std::swap(keys[i - 1], keys[rng.below(i)]);
        for (std::size_t e = 0; e < keys.size(); ++e) {
            ASSERT_TRUE(map.erase(keys[e]));
            ASSERT_FALSE(map.contains(keys[e]));
            for (std::size_t k = e + 1; k < keys.size(); ++k) {
                const std::uint32_t* v = map.find(keys[k]);
                ASSERT_NE(v, nullptr) << "round " << round << ": key lost after an erasure";
                ASSERT_EQ(*v, keys[k] ^ 0x5555u);
            }
        }
        ASSERT_EQ(map.size(), 0u);
    }
}

TEST(IndexSet, InsertEraseContains) {
    IndexSet s;
    EXPECT_TRUE(s.insert(7));
    EXPECT_FALSE(s.insert(7));
    EXPECT_TRUE(s.insert(0));
    EXPECT_TRUE(s.contains(0));
    EXPECT_FALSE(s.contains(1));
    EXPECT_TRUE(s.erase(7));
    EXPECT_FALSE(s.erase(7));
    std::set<std::uint32_t> seen;
    s.for_each([&](std::uint32_t k) { seen.insert(k); });
    EXPECT_EQ(seen, std::set<std::uint32_t>{0});
}

}  // namespace
}  // namespace dynmesh
