#pragma once
/// \file PointGrid: a uniform hash grid over ids with 3D positions, for fixed-radius and
/// nearest-neighbour queries in expected O(1) per query when the points are well spaced
/// relative to the cell size (the deforming-mesh paper's "uniform grid", §4.6, with a hash
/// table in place of the radix sort).
///
/// Two ways to fill it, one set of queries:
/// - bulk: PointGrid::bulk(cell, points[, ids]) buckets every point at once (two linear
///   passes into one open-addressing table of cells over one array, each cell's ids
///   contiguous): the fast way to index a set known in advance;
/// - dynamic: insert() and erase() in any order, on an empty PointGrid(cell) or on a bulk
///   grid (an erased id leaves its cell's range; an inserted one goes to a hash map of
///   extra cells, looked up after the bulk cells).
/// Cell coordinates are kept whole (clamped to +-4e15, where doubles are still exact
/// integers; clamping merges the outermost cells and never loses a point).
/// The grid stores ids only: queries that measure distances take `pos(id)`, the position of
/// an id (the position it was inserted at).
///
/// Usage
/// \code
///   PointGrid g = PointGrid::bulk(h, pts);                     // ids 0 .. pts.size() - 1
///   const auto pos = PointGrid::positions(pts);                 // pos(i) = pts[i]
///   g.for_each_within(q, r, pos, [&](std::uint32_t id, double d2) { ... });
///   const auto [id, d] = g.nearest(q, pos, [](std::uint32_t) { return true; });
///   g.erase(3, pts[3]);                                          // and insert(id, p)
/// \endcode

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/system/hash.hpp"

namespace dynmesh {

class PointGrid {
public:
    static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

    /// An empty dynamic grid. \pre cell > 0 and finite.
    explicit PointGrid(double cell = 1.0) { reset(cell); }

    /// A bulk grid of n ids: id(k) at at(k), k = 0 .. n - 1 (ids need not be dense).
    template <class At, class Id>
    [[nodiscard]] static PointGrid bulk(double cell, std::size_t n, At&& at, Id&& id) {
        PointGrid g(cell);
        g.build(n, at, id);
        return g;
    }
    /// A bulk grid of the ids 0 .. points.size() - 1 at `points`.
    [[nodiscard]] static PointGrid bulk(double cell, std::span<const Point3> points) {
        return bulk(cell, points.size(), [&](std::size_t i) { return points[i]; },
                    [](std::size_t i) { return static_cast<std::uint32_t>(i); });
    }
    /// A bulk grid of `ids`, id i at points[i]. \pre every id < points.size().
    [[nodiscard]] static PointGrid bulk(double cell, std::span<const Point3> points,
                                        std::span<const std::uint32_t> ids) {
        return bulk(cell, ids.size(), [&](std::size_t k) { return points[ids[k]]; },
                    [&](std::size_t k) { return ids[k]; });
    }

    /// pos(id) = points[id]: the `pos` of the queries below for positions held in an array.
    [[nodiscard]] static auto positions(std::span<const Point3> points) {
        return [points](std::uint32_t id) -> const Point3& { return points[id]; };
    }

    /// Empties the grid and sets a new cell size.
    void reset(double cell) {
        DYNMESH_CHECK(std::isfinite(cell) && cell > 0, "PointGrid: the cell size must be positive and finite");
        cell_ = cell;
        inv_ = 1.0 / cell;
        extra_.clear();
        std::fill(occupied_.begin(), occupied_.end(), 0);
        table_.clear();
        ids_.clear();
        mask_ = 0;
        n_cells_ = 0;
        size_ = 0;
    }
    [[nodiscard]] double cell() const { return cell_; }
    [[nodiscard]] std::size_t size() const { return size_; }
    /// True for a grid made by bulk() (its ids are in the bulk table, plus any inserted since).
    [[nodiscard]] bool is_static() const { return !table_.empty(); }

    /// Adds id at p (the same id may be added twice, at two places).
    void insert(std::uint32_t id, const Point3& p) {
        const CellKey k = key(p);
        extra_[k].push_back(id);
        mark(hash(k));
        ++size_;
    }
    /// Removes id, which must have been inserted at p. Returns false when it is not there.
    bool erase(std::uint32_t id, const Point3& p) {
        const CellKey k = key(p);
        const std::uint64_t h = hash(k);
        if (!table_.empty()) {
            Cell& c = table_[slot(k, h)];
            if (c.begin != kNone)
                for (std::uint32_t i = c.begin; i < c.end; ++i)
                    if (ids_[i] == id) {
                        ids_[i] = ids_[--c.end];
                        --size_;
                        return true;
                    }
        }
        if (extra_.empty() || !maybe_occupied(h)) return false;
        auto it = extra_.find(k);
        if (it == extra_.end()) return false;
        auto& v = it->second;
        for (std::size_t i = 0; i < v.size(); ++i)
            if (v[i] == id) {
                v[i] = v.back();
                v.pop_back();
                if (v.empty()) extra_.erase(it);
                --size_;
                return true;
            }
        return false;
    }

    /// Calls f(id) for every id whose cell meets the cube of half-width r around p (a
    /// superset of the ids within distance r; the caller measures the distance).
    template <class F>
    void for_each_candidate(const Point3& p, double r, F&& f) const {
        visit_cube(p, r, [&](std::uint32_t id) {
            f(id);
            return false;
        });
    }
    /// Calls f(id, squared distance) for every id within distance r of p (closed ball).
    template <class Pos, class F>
    void for_each_within(const Point3& p, double r, Pos&& pos, F&& f) const {
        const double r2 = r * r;
        visit_cube(p, r, [&](std::uint32_t id) {
            const double d2 = sqdistance(pos(id), p);
            if (d2 <= r2) f(id, d2);
            return false;
        });
    }
    /// True when some id lies within distance r of p (closed ball); stops at the first.
    template <class Pos>
    [[nodiscard]] bool any_within(const Point3& p, double r, Pos&& pos) const {
        const double r2 = r * r;
        return visit_cube(p, r, [&](std::uint32_t id) { return sqdistance(pos(id), p) <= r2; });
    }

    /// The id nearest to p among those accepted by `keep(id)`, with its distance. Ties break
    /// on the smaller id. Returns {kNone, inf} for an empty grid or no accepted id.
    template <class Pos, class Keep>
    [[nodiscard]] std::pair<std::uint32_t, double> nearest(const Point3& p, Pos&& pos, Keep&& keep) const {
        const auto [id, d2] = nearest_sq(p, pos, keep);
        return {id, std::sqrt(d2)};
    }
    /// As nearest, with the squared distance, and allowed to stop early: once some accepted id
    /// within sqrt(stop_sq) of p is found, it returns one such id (not necessarily the
    /// nearest). The answer is exact when the nearest squared distance exceeds stop_sq. The
    /// search visits shells of cells around p's cell, so the cost grows with the distance
    /// found, and is at most one pass over the grid.
    template <class Pos, class Keep>
    [[nodiscard]] std::pair<std::uint32_t, double> nearest_sq(const Point3& p, Pos&& pos, Keep&& keep,
                                                              double stop_sq = -1.0) const {
        std::uint32_t best = kNone;
        double bd2 = std::numeric_limits<double>::infinity();
        auto consider = [&](std::uint32_t id) {
            if (!keep(id)) return;
            const double d2 = sqdistance(pos(id), p);
            if (d2 < bd2 || (d2 == bd2 && id < best)) {
                bd2 = d2;
                best = id;
            }
        };
        if (size_ == 0) return {best, bd2};
        const std::int64_t cx = coord(p.x), cy = coord(p.y), cz = coord(p.z);
        for (std::int64_t k = 0;; ++k) {
            const double side = static_cast<double>(2 * k + 1);
            if (side * side * side > static_cast<double>(n_cells()) + 64) {
                // The cube of shells 0..k has more cells than the grid: look at every id.
                for_each_id([&](std::uint32_t id) {
                    consider(id);
                    return false;
                });
                return {best, bd2};
            }
            // The cells at Chebyshev distance exactly k from p's cell.
            for (std::int64_t dx = -k; dx <= k; ++dx)
                for (std::int64_t dy = -k; dy <= k; ++dy) {
                    const bool face = dx == -k || dx == k || dy == -k || dy == k;
                    const std::int64_t step = face ? 1 : std::max<std::int64_t>(2 * k, 1);
                    for (std::int64_t dz = -k; dz <= k; dz += step)
                        visit_cell(cx + dx, cy + dy, cz + dz, [&](std::uint32_t id) {
                            consider(id);
                            return false;
                        });
                }
            // Every id not seen yet is at distance >= k * cell from p.
            const double seen = static_cast<double>(k) * cell_;
            if (bd2 <= seen * seen || bd2 <= stop_sq) return {best, bd2};
        }
    }

private:
    struct CellKey {
        std::int64_t x = 0, y = 0, z = 0;
        friend bool operator==(const CellKey&, const CellKey&) = default;
    };
    struct CellKeyHash {
        std::size_t operator()(const CellKey& k) const noexcept { return static_cast<std::size_t>(hash(k)); }
    };

    // ---- cell coordinates ------------------------------------------------------------------
    /// Clamped to +-4e15, where doubles are still exact integers.
    static constexpr double kLimit = 4e15;
    [[nodiscard]] std::int64_t coord(double x) const {
        return static_cast<std::int64_t>(std::clamp(std::floor(x * inv_), -kLimit, kLimit));
    }
    [[nodiscard]] CellKey key(const Point3& p) const { return {coord(p.x), coord(p.y), coord(p.z)}; }
    [[nodiscard]] std::size_t n_cells() const { return n_cells_ + extra_.size(); }

    // ---- visiting ids; f(id) returns true to stop -------------------------------------------
    /// The ids of every cell meeting the cube of half-width r around p, cell by cell in
    /// (x, y, z) order, or of the whole grid when the cube has more cells than the grid.
    /// Returns true when f stopped the visit.
    template <class F>
    bool visit_cube(const Point3& p, double r, F&& f) const {
        const std::int64_t x0 = coord(p.x - r), x1 = coord(p.x + r);
        const std::int64_t y0 = coord(p.y - r), y1 = coord(p.y + r);
        const std::int64_t z0 = coord(p.z - r), z1 = coord(p.z + r);
        const double n = static_cast<double>(x1 - x0 + 1) * static_cast<double>(y1 - y0 + 1) *
                         static_cast<double>(z1 - z0 + 1);
        if (n > static_cast<double>(n_cells()) + 64) return for_each_id(f);
        for (std::int64_t x = x0; x <= x1; ++x)
            for (std::int64_t y = y0; y <= y1; ++y)
                for (std::int64_t z = z0; z <= z1; ++z)
                    if (visit_cell(x, y, z, f)) return true;
        return false;
    }
    /// The ids of the cell (x, y, z): its bulk ids, then those inserted since.
    template <class F>
    bool visit_cell(std::int64_t x, std::int64_t y, std::int64_t z, F&& f) const {
        const CellKey k{x, y, z};
        const std::uint64_t h = hash(k);  // once, for the table and the filter
        if (!table_.empty()) {
            const Cell& c = table_[slot(k, h)];
            if (c.begin != kNone)
                for (std::uint32_t i = c.begin; i < c.end; ++i)
                    if (f(ids_[i])) return true;
        }
        if (extra_.empty() || !maybe_occupied(h)) return false;  // most cells of a query are empty
        const auto it = extra_.find(k);
        if (it == extra_.end()) return false;
        for (std::uint32_t id : it->second)
            if (f(id)) return true;
        return false;
    }
    /// Every id of the grid.
    template <class F>
    bool for_each_id(F&& f) const {
        for (const Cell& c : table_)
            if (c.begin != kNone)
                for (std::uint32_t i = c.begin; i < c.end; ++i)
                    if (f(ids_[i])) return true;
        for (const auto& [k, ids] : extra_)
            for (std::uint32_t id : ids)
                if (f(id)) return true;
        return false;
    }

    // ---- inserted ids: a hash map of extra cells ----------------------------------------------
    /// A one-hash Bloom filter of the extra cells: a clear bit proves a cell has no inserted id
    /// without a hash-map lookup. Erasing leaves bits set (they only cost a lookup); reset()
    /// clears them.
    static constexpr std::size_t kFilterBits = std::size_t{1} << 15;
    /// h: the cell's hash_ints(x, y, z).
    void mark(std::uint64_t h) {
        const std::size_t b = h & (kFilterBits - 1);
        occupied_[b >> 6] |= std::uint64_t{1} << (b & 63);
    }
    [[nodiscard]] bool maybe_occupied(std::uint64_t h) const {
        const std::size_t b = h & (kFilterBits - 1);
        return (occupied_[b >> 6] >> (b & 63)) & 1u;
    }
    [[nodiscard]] static std::uint64_t hash(const CellKey& k) { return hash_ints(k.x, k.y, k.z); }

    // ---- bulk storage: an open-addressing table of cells over one array of ids --------------
    struct Cell {
        CellKey k;
        std::uint32_t begin = kNone, end = 0;  // ids_[begin, end); begin == kNone: a free slot
    };
    /// The slot of cell k (hash h) in the table (a free slot when k has none). \pre a bulk
    /// table.
    [[nodiscard]] std::size_t slot(const CellKey& k, std::uint64_t h) const {
        std::size_t i = static_cast<std::size_t>(h) & mask_;
        while (table_[i].begin != kNone && !(table_[i].k == k)) i = (i + 1) & mask_;
        return i;
    }
    /// Buckets n ids (id(k) at at(k)): a first pass counts the ids of each cell, a second
    /// places them, each cell's ids contiguous and in the order given.
    template <class At, class Id>
    void build(std::size_t n, At&& at, Id&& id) {
        DYNMESH_CHECK(n < kNone, "PointGrid::bulk: too many points");
        std::size_t slots = 16;
        while (slots < 2 * n) slots *= 2;
        table_.assign(slots, Cell{});
        mask_ = slots - 1;
        std::vector<std::uint32_t> where(n);  // the slot of each id's cell
        for (std::size_t k = 0; k < n; ++k) {
            const CellKey ck = key(at(k));
            const std::size_t s = slot(ck, hash(ck));
            Cell& c = table_[s];
            if (c.begin == kNone) {
                c = Cell{ck, 0, 0};
                ++n_cells_;
            }
            ++c.end;  // the count, for now
            where[k] = static_cast<std::uint32_t>(s);
        }
        std::uint32_t start = 0;
        for (Cell& c : table_)
            if (c.begin != kNone) {
                c.begin = start;
                start += c.end;
                c.end = c.begin;  // the fill position, the end once every id is placed
            }
        ids_.resize(n);
        for (std::size_t k = 0; k < n; ++k) ids_[table_[where[k]].end++] = id(k);
        size_ = n;
    }

    double cell_ = 1, inv_ = 1;
    std::size_t size_ = 0;
    std::size_t n_cells_ = 0;  // cells of the bulk table (a cell emptied by erase() still counts)
    // inserted ids
    std::unordered_map<CellKey, std::vector<std::uint32_t>, CellKeyHash> extra_;
    std::vector<std::uint64_t> occupied_ = std::vector<std::uint64_t>(kFilterBits / 64, 0);
    // bulk
    std::vector<Cell> table_;
    std::size_t mask_ = 0;
    std::vector<std::uint32_t> ids_;
};

}  // namespace dynmesh
