#include "dynmesh/system/hash.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>

namespace dynmesh {
namespace {

TEST(Hash, MixerAndFold) {
    // splitmix64 from state 0: its first output is mix64(0).
    EXPECT_EQ(mix64(0), 0xe220a8397b1dcdafULL);
    EXPECT_EQ(hash_ints(1, 2, 3), hash_combine(hash_combine(mix64(1), 2), 3));
    const std::array<std::int64_t, 2> a{-1, 7};
    EXPECT_EQ(hash_range(a, 5), hash_ints(5, std::int64_t{-1}, 7));
    EXPECT_NE(hash_ints(1, 2), hash_ints(2, 1));
}

}  // namespace
}  // namespace dynmesh
