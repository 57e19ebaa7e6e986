#pragma once
/// \file Hashes of integer keys (grid cells, lattice points, directed edges, bit patterns of
/// coordinates) for the library's hash tables: one 64-bit mixer and a fold over several
/// integers, so that every table hashes its keys the same way.
///
/// Usage
/// \code
///   struct CellKeyHash {
///       std::size_t operator()(const CellKey& k) const noexcept {
///           return static_cast<std::size_t>(hash_ints(k.level, k.ix, k.iy));
///       }
///   };
/// \endcode

#include <concepts>
#include <cstdint>

namespace dynmesh {

/// The splitmix64 finaliser (Steele, Lea and Flood, "Fast splittable pseudorandom number
/// generators", 2014) applied to x plus the golden-ratio increment: a bijection of 64-bit
/// integers in which every output bit depends on every input bit.
[[nodiscard]] constexpr std::uint64_t mix64(std::uint64_t x) noexcept {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/// Folds the integer v into the running hash h.
[[nodiscard]] constexpr std::uint64_t hash_combine(std::uint64_t h, std::uint64_t v) noexcept {
    return mix64(h ^ v);
}

/// The hash of a sequence of integers: mix64 of the first, then hash_combine with each next
/// one (signed values taken modulo 2^64).
template <std::integral T, std::integral... U>
[[nodiscard]] constexpr std::uint64_t hash_ints(T first, U... rest) noexcept {
    std::uint64_t h = mix64(static_cast<std::uint64_t>(first));
    ((h = hash_combine(h, static_cast<std::uint64_t>(rest))), ...);
    return h;
}

/// The hash of `head` followed by the integers of a range (an array of coordinates):
/// hash_ints(head, r[0], r[1], ...).
template <class Range>
[[nodiscard]] constexpr std::uint64_t hash_range(const Range& r, std::uint64_t head = 0) noexcept {
    std::uint64_t h = mix64(head);
    for (const auto v : r) h = hash_combine(h, static_cast<std::uint64_t>(v));
    return h;
}

}  // namespace dynmesh
