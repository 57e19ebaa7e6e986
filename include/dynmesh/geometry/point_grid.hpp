#pragma once
/// \file PointGrid: a uniform hash grid over ids with 3D positions, for fixed-radius and
/// nearest-neighbour queries in expected O(1) per query when the points are well spaced
/// relative to the cell size (the deforming-mesh paper's "uniform grid", §4.6, with a hash
/// map in place of the radix sort).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

/// A well-mixed 64-bit hash of integer cell coordinates (for hash tables of grid cells).
[[nodiscard]] inline std::uint64_t hash_cell(std::int64_t x, std::int64_t y, std::int64_t z) {
    std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    h ^= h >> 31;
    h *= 0xD6E8FEB86659FD93ull;
    h ^= h >> 32;
    return h;
}

class PointGrid {
public:
    /// \pre cell > 0 and finite.
    explicit PointGrid(double cell = 1.0) { reset(cell); }

    /// Empties the grid and sets a new cell size.
    void reset(double cell) {
        DYNMESH_CHECK(std::isfinite(cell) && cell > 0, "PointGrid: the cell size must be positive and finite");
        cell_ = cell;
        inv_ = 1.0 / cell;
        cells_.clear();
        std::fill(occupied_.begin(), occupied_.end(), 0);
        size_ = 0;
    }
    [[nodiscard]] double cell() const { return cell_; }
    [[nodiscard]] std::size_t size() const { return size_; }

    void insert(std::uint32_t id, const Point3& p) {
        const Key k = key(p);
        cells_[k].push_back(id);
        mark(k);
        ++size_;
    }
    /// Removes id, which must have been inserted at p. Returns false when it is not there.
    bool erase(std::uint32_t id, const Point3& p) {
        auto it = cells_.find(key(p));
        if (it == cells_.end()) return false;
        auto& v = it->second;
        for (std::size_t i = 0; i < v.size(); ++i)
            if (v[i] == id) {
                v[i] = v.back();
                v.pop_back();
                if (v.empty()) cells_.erase(it);
                --size_;
                return true;
            }
        return false;
    }

    /// Calls f(id) for every id whose cell meets the cube of half-width r around p (a
    /// superset of the ids within distance r; the caller measures the distance).
    template <class F>
    void for_each_candidate(const Point3& p, double r, F&& f) const {
        const std::int64_t x0 = coord(p.x - r), x1 = coord(p.x + r);
        const std::int64_t y0 = coord(p.y - r), y1 = coord(p.y + r);
        const std::int64_t z0 = coord(p.z - r), z1 = coord(p.z + r);
        if ((x1 - x0 + 1) * (y1 - y0 + 1) * (z1 - z0 + 1) > static_cast<std::int64_t>(cells_.size()) + 64) {
            for (const auto& [k, ids] : cells_)
                for (std::uint32_t id : ids) f(id);
            return;
        }
        for (std::int64_t x = x0; x <= x1; ++x)
            for (std::int64_t y = y0; y <= y1; ++y)
                for (std::int64_t z = z0; z <= z1; ++z) {
                    const Key k = pack(x, y, z);
                    if (!maybe_occupied(k)) continue;  // most cells of a query are empty
                    auto it = cells_.find(k);
                    if (it == cells_.end()) continue;
                    for (std::uint32_t id : it->second) f(id);
                }
    }

    /// The id nearest to p among those accepted by `keep(id)`, with its distance; searches
    /// rings of growing radius, so the cost is proportional to the distance found. Ties break
    /// on the smaller id. Returns {UINT32_MAX, inf} for an empty grid or no accepted id.
    /// `pos(id)` gives the position of an id.
    template <class Pos, class Keep>
    [[nodiscard]] std::pair<std::uint32_t, double> nearest(const Point3& p, Pos&& pos, Keep&& keep) const {
        std::uint32_t best = std::numeric_limits<std::uint32_t>::max();
        double bd2 = std::numeric_limits<double>::infinity();
        if (size_ == 0) return {best, bd2};
        for (double r = cell_;; r *= 2) {
            for_each_candidate(p, r, [&](std::uint32_t id) {
                if (!keep(id)) return;
                const double d2 = sqnorm(pos(id) - p);
                if (d2 < bd2 || (d2 == bd2 && id < best)) {
                    bd2 = d2;
                    best = id;
                }
            });
            // Everything within distance r has been seen (the cube of half-width r covers it).
            if (bd2 <= r * r) break;
            if (r > 1e300 || exhausted(p, r)) break;
        }
        return {best, std::sqrt(bd2)};
    }

private:
    using Key = std::uint64_t;
    [[nodiscard]] std::int64_t coord(double x) const {
        const double c = std::floor(x * inv_);
        return static_cast<std::int64_t>(std::clamp(c, -1e6, 1e6));
    }
    static Key pack(std::int64_t x, std::int64_t y, std::int64_t z) {
        constexpr std::int64_t off = 1 << 20;
        return (static_cast<Key>(x + off) << 42) | (static_cast<Key>(y + off) << 21) |
               static_cast<Key>(z + off);
    }
    [[nodiscard]] Key key(const Point3& p) const { return pack(coord(p.x), coord(p.y), coord(p.z)); }
    /// True when the cube of half-width r around p already covered every cell (the whole
    /// grid was scanned).
    [[nodiscard]] bool exhausted(const Point3& p, double r) const {
        const std::int64_t n = (coord(p.x + r) - coord(p.x - r) + 1) * (coord(p.y + r) - coord(p.y - r) + 1) *
                               (coord(p.z + r) - coord(p.z - r) + 1);
        return n > static_cast<std::int64_t>(cells_.size()) + 64;
    }

    /// A one-hash Bloom filter of the occupied cells: a clear bit proves a cell empty without a
    /// hash-map lookup. Erasing leaves bits set (they only cost a lookup); reset() clears them.
    static constexpr std::size_t kFilterBits = std::size_t{1} << 15;
    [[nodiscard]] static std::size_t filter_bit(Key k) { return hash_cell(std::int64_t(k), 0, 0) & (kFilterBits - 1); }
    void mark(Key k) { occupied_[filter_bit(k) >> 6] |= std::uint64_t{1} << (filter_bit(k) & 63); }
    [[nodiscard]] bool maybe_occupied(Key k) const {
        return (occupied_[filter_bit(k) >> 6] >> (filter_bit(k) & 63)) & 1u;
    }

    double cell_ = 1, inv_ = 1;
    std::unordered_map<Key, std::vector<std::uint32_t>> cells_;
    std::vector<std::uint64_t> occupied_ = std::vector<std::uint64_t>(kFilterBits / 64, 0);
    std::size_t size_ = 0;
};

}  // namespace dynmesh
