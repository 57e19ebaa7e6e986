#include "dynmesh/quadtree/quadtree.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <tuple>
#include <unordered_set>
#include <utility>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/format.hpp"

namespace dynmesh {

namespace {

/// All offsets in [-r, r]^D, in lexicographic order.
template <int D>
std::vector<std::array<int, D>> offsets(int r) {
    std::vector<std::array<int, D>> out;
    std::array<int, D> o;
    o.fill(-r);
    while (true) {
        out.push_back(o);
        int i = 0;
        while (i < D && o[i] == r) o[i++] = -r;
        if (i == D) break;
        ++o[i];
    }
    return out;
}

template <int D>
const std::vector<std::array<int, D>>& block3() {
    static const auto v = offsets<D>(1);
    return v;
}

/// Z-order (Morton order) of grid points without forming the interleaved key: compare along
/// the axis whose coordinates differ in the most significant bit.
template <int D>
bool z_less(const std::array<std::uint64_t, D>& a, const std::array<std::uint64_t, D>& b) {
    int axis = 0;
    std::uint64_t best = 0;
    for (int i = 0; i < D; ++i) {
        const std::uint64_t x = a[i] ^ b[i];
        if (best < x && best < (best ^ x)) {  // msb(best) < msb(x)
            axis = i;
            best = x;
        }
    }
    return a[axis] < b[axis];
}

/// The (2k+1)^D block offsets for isolation radius k = 1 or 2.
template <int D>
const std::vector<std::array<int, D>>& block_k(int k) {
    static const auto v1 = offsets<D>(1);
    static const auto v2 = offsets<D>(2);
    return k == 2 ? v2 : v1;
}

}  // namespace

// ---- cells ----------------------------------------------------------------------------------

template <int D>
typename DynQuadtree<D>::Key DynQuadtree<D>::root_key() {
    Key k;
    k.level = kLevels;
    return k;
}

template <int D>
typename DynQuadtree<D>::Key DynQuadtree<D>::cell_of(const GridPoint& g, int level) {
    Key k;
    k.level = level;
    for (int i = 0; i < D; ++i) k.a[i] = g[i] >> level;
    return k;
}

template <int D>
bool DynQuadtree<D>::offset_cell(const Key& c, const std::array<int, D>& o, Key& out) {
    const std::int64_t n = std::int64_t{1} << (kLevels - c.level);  // cells per axis
    out.level = c.level;
    for (int i = 0; i < D; ++i) {
        const std::int64_t v = static_cast<std::int64_t>(c.a[i]) + o[i];
        if (v < 0 || v >= n) return false;
        out.a[i] = static_cast<std::uint64_t>(v);
    }
    return true;
}

/// The 2^D cells of size 2|x| whose closures meet x's closure (parent included). Per axis the
/// parent index m = a >> 1 and its neighbour on the side of x (m - 1 if a is even, else m + 1).
template <int D>
std::vector<typename DynQuadtree<D>::Key> DynQuadtree<D>::up_neighbours(const Key& x) {
    std::vector<Key> out;
    if (x.level >= kLevels) return out;
    const std::int64_t n = std::int64_t{1} << (kLevels - x.level - 1);
    std::array<std::array<std::int64_t, 2>, D> choice;
    for (int i = 0; i < D; ++i) {
        const auto m = static_cast<std::int64_t>(x.a[i] >> 1);
        choice[i] = {m, (x.a[i] & 1) ? m + 1 : m - 1};
    }
    for (int mask = 0; mask < (1 << D); ++mask) {
        Key y;
        y.level = x.level + 1;
        bool ok = true;
        for (int i = 0; i < D && ok; ++i) {
            const std::int64_t v = choice[i][(mask >> i) & 1];
            ok = v >= 0 && v < n;
            y.a[i] = static_cast<std::uint64_t>(v);
        }
        if (ok) out.push_back(y);
    }
    return out;
}

// ---- construction, snapping ----------------------------------------------------------------

template <int D>
DynQuadtree<D>::DynQuadtree(const QuadtreeOptions<D>& options) : options_(options) {
    for (int i = 0; i < D; ++i)
        DYNMESH_CHECK(
            std::isfinite(options.origin[static_cast<std::size_t>(i)]),
            "DynQuadtree: domain origin " + format_point(options.origin) + " is not finite");
    DYNMESH_CHECK(
        std::isfinite(options.width) && options.width > 0,
        "DynQuadtree: domain width " + format_number(options.width) + " must be finite and > 0");
    for (int i = 0; i < D; ++i)
        DYNMESH_CHECK(std::isfinite(options.origin[static_cast<std::size_t>(i)] + options.width),
                      "DynQuadtree: the domain box at " + format_point(options.origin) +
                          " of width " + format_number(options.width) + " overflows");
    DYNMESH_CHECK(std::ldexp(options.width, -kLevels) >= DBL_MIN,
                  "DynQuadtree: domain width " + format_number(options.width) +
                      " is too small for the quadtree grid (needs W >= 2^52 * DBL_MIN)");
    int e = 0;
    dyadic_ = std::frexp(options.width, &e) == 0.5;
    for (int i = 0; i < D && dyadic_; ++i) {
        const double k = options.origin[static_cast<std::size_t>(i)] / (options.width / 8);
        dyadic_ = std::floor(k) == k;
    }
    nodes_.emplace(root_key(), Node{});
}

// ---- resolution -----------------------------------------------------------------------------

template <int D>
double DynQuadtree<D>::box_extent(const std::array<std::uint64_t, D>& lo,
                                  const std::array<std::uint64_t, D>& hi) const {
    const double unit = std::ldexp(options_.width, -kLevels);
    double x = 0;
    for (int i = 0; i < D; ++i) {
        const double o = options_.origin[static_cast<std::size_t>(i)];
        x = std::max({x, std::fabs(o + static_cast<double>(lo[i]) * unit),
                      std::fabs(o + static_cast<double>(hi[i]) * unit)});
    }
    return x;
}

template <int D>
bool DynQuadtree<D>::resolved(int level, double x) const {
    if (level < 1) return false;
    const double h = std::ldexp(options_.width, level - 1 - kLevels);
    if (dyadic_) return x <= std::ldexp(std::min(h, options_.width / 8), 53);
    const double ulp = std::nextafter(x, INFINITY) - x;
    return h >= 0x1p13 * ulp;
}

template <int D>
bool DynQuadtree<D>::is_resolved(const CellId<D>& c) const {
    if (c.level < 0 || c.level > kLevels) return false;
    std::array<std::uint64_t, D> lo{}, hi{};
    for (int i = 0; i < D; ++i) {
        lo[i] = c.index[i] << c.level;
        hi[i] = (c.index[i] + 1) << c.level;
    }
    return resolved(c.level, box_extent(lo, hi));
}

template <int D>
InsertResult DynQuadtree<D>::snap(const Point& p, GridPoint& g) const {
    for (int i = 0; i < D; ++i)
        if (!std::isfinite(p[static_cast<std::size_t>(i)])) return InsertResult::NotFinite;
    for (int i = 0; i < D; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        const double t = (p[ui] - options_.origin[ui]) / options_.width;
        if (!(t >= 1.0 / 3.0 && t <= 2.0 / 3.0)) return InsertResult::OutsideDomain;
        g[ui] = static_cast<std::uint64_t>(std::floor(t * 0x1p49)) << kGuardBits;
    }
    return InsertResult::Inserted;
}

template <int D>
bool DynQuadtree<D>::is_admissible(const Point& p) const {
    GridPoint g;
    return snap(p, g) == InsertResult::Inserted;
}

template <int D>
typename DynQuadtree<D>::GridPoint DynQuadtree<D>::grid_point(const Point& p) const {
    GridPoint g;
    DYNMESH_CHECK(snap(p, g) == InsertResult::Inserted,
                  "DynQuadtree::grid_point: point " + format_point(p) +
                      " is not finite or not in the middle third of the domain");
    return g;
}

// ---- lookups --------------------------------------------------------------------------------

template <int D>
typename DynQuadtree<D>::Node& DynQuadtree<D>::find_leaf(const GridPoint& g,
                                                         std::vector<Node*>* path) {
    Key k = root_key();
    while (true) {
        Node& node = nodes_.at(k);
        if (path) path->push_back(&node);
        if (node.is_leaf) return node;
        k = cell_of(g, k.level - 1);
    }
}

template <int D>
const typename DynQuadtree<D>::Node& DynQuadtree<D>::find_leaf(const GridPoint& g) const {
    Key k = root_key();
    while (true) {
        const Node& node = nodes_.at(k);
        if (node.is_leaf) return node;
        k = cell_of(g, k.level - 1);
    }
}

template <int D>
std::uint64_t DynQuadtree<D>::count_in(const Key& x) const {
    Key y = x;
    while (true) {
        if (const auto it = nodes_.find(y); it != nodes_.end()) {
            if (y.level == x.level) return it->second.count;
            DYNMESH_ASSERT(it->second.is_leaf, "count_in: deepest stored ancestor is internal");
            std::uint64_t c = 0;
            for (const Entry& e : it->second.points)
                if (cell_of(e.grid, x.level) == x) ++c;
            return c;
        }
        DYNMESH_ASSERT(y.level < kLevels, "count_in: root missing");
        for (int i = 0; i < D; ++i) y.a[i] >>= 1;
        ++y.level;
    }
}

template <int D>
bool DynQuadtree<D>::is_crowded(const Key& x) const {
    if (count_in(x) == 0) return false;
    std::uint64_t sum = 0;
    for (const auto& o : block_k<D>(isolation_radius())) {
        Key y;
        if (offset_cell(x, o, y)) sum += count_in(y);
        if (sum >= 2) return true;
    }
    return false;
}

template <int D>
bool DynQuadtree<D>::contains(const Point& p) const {
    GridPoint g;
    if (snap(p, g) != InsertResult::Inserted) return false;
    const Node& leaf = find_leaf(g);
    return std::any_of(leaf.points.begin(), leaf.points.end(),
                       [&](const Entry& e) { return e.grid == g; });
}

// ---- updates --------------------------------------------------------------------------------

template <int D>
InsertResult DynQuadtree<D>::insert(const Point& p) {
    GridPoint g;
    if (const InsertResult r = snap(p, g); r != InsertResult::Inserted) return r;
    std::vector<Node*> path;
    Node& leaf = find_leaf(g, &path);
    for (const Entry& e : leaf.points)
        if (e.grid == g) return InsertResult::Duplicate;
    for (Node* n : path) ++n->count;
    leaf.points.push_back({g, p});
    ++size_;
    QuadtreeUpdateReport<D> before = std::move(last_update_);
    const auto flips = settle(g, +1, path);
    // Resolution: an insertion only splits cells; their children are the new leaves.
    const bool refuse = std::any_of(flips.begin(), flips.end(), [&](const auto& f) {
        for (int mask = 0; mask < (1 << D); ++mask) {
            CellId<D> ch{f.first.level - 1, {}};
            for (int i = 0; i < D; ++i) ch.index[i] = 2 * f.first.a[i] + ((mask >> i) & 1);
            if (!is_resolved(ch)) return true;
        }
        return false;
    });
    if (refuse) {
        // Undo: the exact mirror of the update restores every support (no cell was split).
        leaf.points.pop_back();
        for (Node* n : path) --n->count;
        --size_;
        [[maybe_unused]] const auto undone = settle(g, -1, path);
        DYNMESH_ASSERT(undone.size() == flips.size(), "insert: rollback is not the mirror");
        last_update_ = std::move(before);
        return InsertResult::BeyondPrecision;
    }
    apply_flips(flips);
    return InsertResult::Inserted;
}

template <int D>
EraseResult DynQuadtree<D>::erase(const Point& p) {
    GridPoint g;
    if (snap(p, g) != InsertResult::Inserted) return EraseResult::NotFound;
    std::vector<Node*> path;
    Node& leaf = find_leaf(g, &path);
    const auto it = std::find_if(leaf.points.begin(), leaf.points.end(),
                                 [&](const Entry& e) { return e.grid == g; });
    if (it == leaf.points.end()) return EraseResult::NotFound;
    leaf.points.erase(it);
    for (Node* n : path) --n->count;
    --size_;
    apply_flips(settle(g, -1, path));
    return EraseResult::Erased;
}

template <int D>
void DynQuadtree<D>::push_u_support(const Key& x, int delta, std::vector<Key>& bucket) {
    for (const auto& o : block3<D>()) {
        Key y;
        if (!offset_cell(x, o, y) || y == x) continue;
        auto yt = state_.find(y);
        if (yt == state_.end()) yt = state_.emplace(y, CellState{}).first;
        yt->second.support += delta;
        DYNMESH_ASSERT(yt->second.support >= 0, "negative support from rule U");
        ++last_update_.support_updates;
        bucket.push_back(y);
    }
}

template <int D>
std::vector<std::pair<typename DynQuadtree<D>::Key, bool>> DynQuadtree<D>::settle(
    const GridPoint& g, int sign, const std::vector<Node*>& path) {
    last_update_ = {};
    const bool mesh = options_.mode == QuadtreeMode::Mesh;
    const int k = isolation_radius();
    std::vector<std::vector<Key>> buckets(kLevels + 1);

    // Step 1 (mesh mode): rule R follows |P| > 0, rule U follows the counts of the I-cells on
    // p's path (counts already updated). These are the internal nodes of the path, and, when
    // insert() rolls back a refused insertion, also the cells settle() had just put in I
    // (no leaf was split for them yet), found through their state.
    if (mesh) {
        const std::uint64_t now = sign > 0 ? 1 : 0;  // the count that means "crossed 0 <-> 1"
        if (size_ == now) {
            const Key root = root_key();
            auto it = state_.find(root);
            if (it == state_.end()) it = state_.emplace(root, CellState{}).first;
            it->second.support += sign;
            DYNMESH_ASSERT(it->second.support >= 0, "negative support from rule R");
            ++last_update_.support_updates;
            buckets[kLevels].push_back(root);
        }
        for (int j = kLevels; j >= 0; --j) {
            const auto depth = static_cast<std::size_t>(kLevels - j);
            const Key x = cell_of(g, j);
            std::uint64_t c = 0;
            if (depth < path.size() && !path[depth]->is_leaf) {
                c = path[depth]->count;
            } else {
                const auto it = state_.find(x);
                if (it == state_.end() || !it->second.in_i) break;
                c = count_in(x);
            }
            if (c == now) push_u_support(x, sign, buckets[x.level]);
        }
    }

    // Step 2: crowding flags of the cells whose N_k block contains p, level by level downwards.
    // Counts of the (4k+1)^D cells around p's cell are cached per level (index by offset + 2k).
    const int side = 4 * k + 1;
    int cache_size = 1;
    for (int i = 0; i < D; ++i) cache_size *= side;
    std::vector<std::int64_t> cache(static_cast<std::size_t>(cache_size));
    const auto& block = block_k<D>(k);
    for (int j = kLevels; j >= 0; --j) {
        // If p's cell holds >= 2 points besides p, every cell of this level whose block holds
        // p is crowded before and after iff it holds a point: nothing to do at this level.
        if (const auto depth = static_cast<std::size_t>(kLevels - j); depth < path.size()) {
            const std::uint64_t besides_p = path[depth]->count - (sign > 0 ? 1 : 0);
            if (besides_p >= 2) continue;
        }
        const Key c = cell_of(g, j);
        std::fill(cache.begin(), cache.end(), -1);
        auto cnt = [&](const std::array<int, D>& o) -> std::uint64_t {
            int idx = 0;
            for (int i = D - 1; i >= 0; --i) idx = idx * side + (o[i] + 2 * k);
            auto& slot = cache[static_cast<std::size_t>(idx)];
            if (slot < 0) {
                Key y;
                slot = offset_cell(c, o, y) ? static_cast<std::int64_t>(count_in(y)) : 0;
            }
            return static_cast<std::uint64_t>(slot);
        };
        std::uint64_t others = 0;
        for (const auto& o : block) others += cnt(o);
        if (sign > 0) --others;  // p itself, in cell c
        if (others == 0) break;  // nothing near p at this level, hence none below (spec §3.2)
        for (const auto& o : block) {
            Key x;
            if (!offset_cell(c, o, x)) continue;
            bool now = false;
            if (cnt(o) >= 1) {
                std::uint64_t sum = 0;
                for (const auto& o2 : block) {
                    std::array<int, D> oo;
                    for (int i = 0; i < D; ++i) oo[i] = o[i] + o2[i];
                    sum += cnt(oo);
                    if (sum >= 2) break;
                }
                now = sum >= 2;
            }
            auto it = state_.find(x);
            const bool was = it != state_.end() && it->second.crowded;
            if (now == was) continue;
            if (it == state_.end()) it = state_.emplace(x, CellState{}).first;
            it->second.crowded = now;
            it->second.support += now ? 1 : -1;
            DYNMESH_ASSERT(it->second.support >= 0, "negative support after crowding change");
            ++last_update_.crowding_changes;
            buckets[j].push_back(x);
        }
    }

    // Step 3: settle membership in I, smallest level first. Support flows from level j to
    // level j + 1 (rules A, B) or within level j (rule U, queued in the bucket being drained),
    // so each cell is final when its level is done. Supports move monotonically (up on an
    // insert, down on an erase), so no cell flips twice.
    std::vector<std::pair<Key, bool>> flips;
    for (int j = 0; j <= kLevels; ++j) {
        for (std::size_t q = 0; q < buckets[j].size(); ++q) {
            const Key x = buckets[j][q];
            auto it = state_.find(x);
            if (it == state_.end()) continue;  // support 0 and not in I: nothing to do
            const bool want = it->second.support > 0;
            if (want != it->second.in_i) {
                it->second.in_i = want;
                flips.emplace_back(x, want);
                const int delta = want ? 1 : -1;
                for (const Key& y : up_neighbours(x)) {
                    auto yt = state_.find(y);
                    if (yt == state_.end()) yt = state_.emplace(y, CellState{}).first;
                    yt->second.support += delta;
                    DYNMESH_ASSERT(yt->second.support >= 0, "negative support in propagation");
                    ++last_update_.support_updates;
                    buckets[j + 1].push_back(y);
                }
                if (mesh && count_in(x) > 0) push_u_support(x, delta, buckets[j]);
                it = state_.find(x);  // emplace may rehash; iterators, not references, die
            }
            if (it->second.support == 0 && !it->second.in_i) state_.erase(it);
        }
    }
    return flips;
}

template <int D>
void DynQuadtree<D>::apply_flips(const std::vector<std::pair<Key, bool>>& flips) {
    // Step 4: apply the flips to the leaf structure, splits top-down, merges bottom-up.
    std::vector<Key> splits, merges;
    for (const auto& [x, in] : flips) (in ? splits : merges).push_back(x);
    auto key_less = [](const Key& a, const Key& b) {
        return std::tie(a.level, a.a) < std::tie(b.level, b.a);
    };
    std::sort(splits.begin(), splits.end(), [&](const Key& a, const Key& b) {
        return a.level != b.level ? a.level > b.level : a.a < b.a;
    });
    std::sort(merges.begin(), merges.end(), key_less);
    for (const Key& x : splits) {
        split(x);
        last_update_.split.push_back({x.level, x.a});
    }
    for (const Key& x : merges) {
        merge(x);
        last_update_.merged.push_back({x.level, x.a});
    }
}

template <int D>
void DynQuadtree<D>::split(const Key& x) {
    Node& node = nodes_.at(x);
    DYNMESH_ASSERT(node.is_leaf, "split: cell is not a leaf");
    node.is_leaf = false;
    std::vector<Entry> pts = std::move(node.points);
    node.points.clear();
    for (int mask = 0; mask < (1 << D); ++mask) {
        Key ch;
        ch.level = x.level - 1;
        for (int i = 0; i < D; ++i) ch.a[i] = 2 * x.a[i] + ((mask >> i) & 1);
        Node child;
        for (const Entry& e : pts)
            if (cell_of(e.grid, ch.level) == ch) child.points.push_back(e);
        child.count = child.points.size();
        nodes_.emplace(ch, std::move(child));
    }
}

template <int D>
void DynQuadtree<D>::merge(const Key& x) {
    Node& node = nodes_.at(x);
    DYNMESH_ASSERT(!node.is_leaf, "merge: cell is already a leaf");
    for (int mask = 0; mask < (1 << D); ++mask) {
        Key ch;
        ch.level = x.level - 1;
        for (int i = 0; i < D; ++i) ch.a[i] = 2 * x.a[i] + ((mask >> i) & 1);
        const auto it = nodes_.find(ch);
        DYNMESH_ASSERT(it != nodes_.end() && it->second.is_leaf, "merge: child not a leaf");
        for (const Entry& e : it->second.points) node.points.push_back(e);
        nodes_.erase(it);
    }
    node.is_leaf = true;
    DYNMESH_ASSERT(node.count == node.points.size(), "merge: count mismatch");
}

// ---- static build ---------------------------------------------------------------------------

template <int D>
DynQuadtree<D> DynQuadtree<D>::build(std::span<const Point> points,
                                     const QuadtreeOptions<D>& options) {
    DynQuadtree tree(options);
    std::vector<Entry> entries(points.size());
    {
        std::unordered_map<Key, std::size_t, KeyHash> seen;
        for (std::size_t i = 0; i < points.size(); ++i) {
            GridPoint g;
            const InsertResult r = tree.snap(points[i], g);
            const auto bad = [&](const std::string& what) {
                return InvalidInput("DynQuadtree::build: point " + std::to_string(i) + " " +
                                        format_point(points[i]) + " " + what,
                                    i);
            };
            if (r == InsertResult::NotFinite) throw bad("is not finite");
            if (r == InsertResult::OutsideDomain)
                throw bad("is outside the middle third of the domain");
            const auto [it, fresh] = seen.emplace(cell_of(g, 0), i);
            if (!fresh) throw bad("duplicates point " + std::to_string(it->second));
            entries[i] = {g, points[i]};
        }
    }

    // Rule C, top-down by level over the points that still have a neighbour: a point whose
    // cell sees no other point in its N_k block at level j sees none below (blocks nest), and
    // a dropped point never lies in the block of an active point's cell (symmetry).
    const bool mesh = options.mode == QuadtreeMode::Mesh;
    const auto& block = block_k<D>(tree.isolation_radius());
    std::vector<Key> crowded;
    std::vector<std::size_t> active(entries.size());
    for (std::size_t i = 0; i < active.size(); ++i) active[i] = i;
    for (int j = kLevels; j >= 0 && active.size() >= 2; --j) {
        std::unordered_map<Key, std::uint64_t, KeyHash> occ;
        for (std::size_t i : active) ++occ[cell_of(entries[i].grid, j)];
        std::unordered_set<Key, KeyHash> marked;
        std::vector<std::size_t> next;
        for (std::size_t i : active) {
            const Key x = cell_of(entries[i].grid, j);
            std::uint64_t sum = 0;
            for (const auto& o : block) {
                Key y;
                if (!offset_cell(x, o, y)) continue;
                if (const auto it = occ.find(y); it != occ.end()) sum += it->second;
            }
            if (sum >= 2) {
                next.push_back(i);
                if (marked.insert(x).second) crowded.push_back(x);
            }
        }
        active = std::move(next);
    }

    // "Does cell x hold a point?" (rule U): the points of a cell are contiguous in Z-order and
    // its lower corner is the cell's Z-order minimum.
    std::vector<GridPoint> zsorted;
    if (mesh) {
        zsorted.reserve(entries.size());
        for (const Entry& e : entries) zsorted.push_back(e.grid);
        std::sort(zsorted.begin(), zsorted.end(), z_less<D>);
    }
    const auto holds_point = [&](const Key& x) {
        GridPoint lo;
        for (int i = 0; i < D; ++i) lo[i] = x.a[i] << x.level;
        const auto it = std::lower_bound(zsorted.begin(), zsorted.end(), lo, z_less<D>);
        return it != zsorted.end() && cell_of(*it, x.level) == x;
    };

    // Close under rules A and B ("x in I => every size-2|x| cell touching x is in I") and, in
    // mesh mode, U and R.
    std::vector<Key> work;
    const auto add = [&](const Key& y) {
        CellState& s = tree.state_[y];
        if (!s.in_i) {
            s.in_i = true;
            work.push_back(y);
        }
    };
    for (const Key& x : crowded) tree.state_[x].crowded = true;
    for (const Key& x : crowded) add(x);
    if (mesh && !entries.empty()) add(root_key());
    std::vector<Key> holders;  // mesh mode: the I-cells holding a point
    while (!work.empty()) {
        const Key x = work.back();
        work.pop_back();
        for (const Key& y : up_neighbours(x)) add(y);
        if (mesh && holds_point(x)) {
            holders.push_back(x);
            for (const auto& o : block3<D>()) {
                Key y;
                if (offset_cell(x, o, y) && y != x) add(y);
            }
        }
    }
    for (auto& [x, s] : tree.state_) {
        s.support += s.crowded ? 1 : 0;
        for (const Key& y : up_neighbours(x)) ++tree.state_.at(y).support;
    }
    for (const Key& x : holders)
        for (const auto& o : block3<D>()) {
            Key y;
            if (offset_cell(x, o, y) && y != x) ++tree.state_.at(y).support;
        }
    if (mesh && !entries.empty()) ++tree.state_.at(root_key()).support;

    // Nodes: every I cell is internal; its children not in I are leaves.
    tree.nodes_.clear();
    if (tree.state_.empty()) tree.nodes_.emplace(root_key(), Node{});
    for (const auto& [x, s] : tree.state_) {
        tree.nodes_[x].is_leaf = false;
        for (int mask = 0; mask < (1 << D); ++mask) {
            Key ch;
            ch.level = x.level - 1;
            for (int i = 0; i < D; ++i) ch.a[i] = 2 * x.a[i] + ((mask >> i) & 1);
            if (!tree.state_.contains(ch)) tree.nodes_[ch].is_leaf = true;
        }
    }
    for (const Entry& e : entries) {
        std::vector<Node*> path;
        Node& leaf = tree.find_leaf(e.grid, &path);
        for (Node* n : path) ++n->count;
        leaf.points.push_back(e);
    }
    tree.size_ = entries.size();

    // Resolution: name the point nearest to the smallest unresolved leaf (deterministic).
    std::optional<CellId<D>> bad;
    for (const auto& [k, n] : tree.nodes_) {
        const CellId<D> c{k.level, k.a};
        if (n.is_leaf && !tree.is_resolved(c) && (!bad || c < *bad)) bad = c;
    }
    if (bad) {
        std::size_t best = 0;
        std::uint64_t best_d = std::numeric_limits<std::uint64_t>::max();
        for (std::size_t i = 0; i < entries.size(); ++i) {
            std::uint64_t d = 0;  // L∞ distance in grid units from the point to the leaf
            for (int a = 0; a < D; ++a) {
                const std::uint64_t lo = bad->index[a] << bad->level;
                const std::uint64_t hi = lo + (std::uint64_t{1} << bad->level);
                const std::uint64_t v = entries[i].grid[a];
                d = std::max(d, v < lo ? lo - v : v >= hi ? v - hi + 1 : 0);
            }
            if (d < best_d) {
                best_d = d;
                best = i;
            }
        }
        PointD<D> corner{};
        for (int a = 0; a < D; ++a) {
            const auto ua = static_cast<std::size_t>(a);
            corner[ua] = options.origin[ua] + static_cast<double>(bad->index[a] << bad->level) *
                                                  std::ldexp(options.width, -kLevels);
        }
        throw InvalidInput(
            "DynQuadtree::build: point " + std::to_string(best) + " " +
            format_point(points[best]) +
            " is too close to other points for double precision at its coordinates: its tree "
            "needs a cell of size " +
            format_number(std::ldexp(options.width, bad->level - kLevels)) + " at " +
            format_point(corner) + ", below the coordinate resolution there" +
            (tree.dyadic() ? "" : " (a dyadic domain, e.g. auto_domain(), resolves finer)"),
            best);
    }
    return tree;
}

// ---- output and checks ----------------------------------------------------------------------

template <int D>
std::vector<CellId<D>> DynQuadtree<D>::leaves() const {
    std::vector<CellId<D>> out;
    out.reserve(leaf_count());
    for (const auto& [k, n] : nodes_)
        if (n.is_leaf) out.push_back({k.level, k.a});
    std::sort(out.begin(), out.end());
    return out;
}

template <int D>
typename DynQuadtree<D>::CellView DynQuadtree<D>::cell_view(const CellId<D>& c) const {
    const auto it = nodes_.find(Key{c.index, c.level});
    if (it == nodes_.end()) return {};
    if (!it->second.is_leaf) return {CellKind::Internal, {}};
    return {CellKind::Leaf, it->second.points};
}

template <int D>
CellId<D> DynQuadtree<D>::leaf_containing(const GridPoint& g) const {
    Key k = root_key();
    while (!nodes_.at(k).is_leaf) k = cell_of(g, k.level - 1);
    return {k.level, k.a};
}

template <int D>
std::vector<std::pair<typename DynQuadtree<D>::GridPoint, typename DynQuadtree<D>::Point>>
DynQuadtree<D>::points() const {
    std::vector<std::pair<GridPoint, Point>> out;
    out.reserve(size_);
    for (const auto& [k, n] : nodes_)
        if (n.is_leaf)
            for (const Entry& e : n.points) out.emplace_back(e.grid, e.point);
    std::sort(out.begin(), out.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    return out;
}

template <int D>
std::string DynQuadtree<D>::canonical_dump() const {
    std::vector<std::pair<CellId<D>, const Node*>> ls;
    for (const auto& [k, n] : nodes_)
        if (n.is_leaf) ls.emplace_back(CellId<D>{k.level, k.a}, &n);
    std::sort(ls.begin(), ls.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    char buf[64];
    std::string s =
        "dynquadtree D=" + std::to_string(D) + " K=" + std::to_string(kLevels) + " origin=";
    for (int i = 0; i < D; ++i) {
        std::snprintf(buf, sizeof buf, "%a", options_.origin[static_cast<std::size_t>(i)]);
        if (i) s += ",";
        s += buf;
    }
    std::snprintf(buf, sizeof buf, "%a", options_.width);
    s += " width=" + std::string(buf);
    if (options_.mode == QuadtreeMode::Mesh) s += " mode=mesh";
    s += " points=" + std::to_string(size_) +
         " leaves=" + std::to_string(ls.size()) + "\n";
    for (const auto& [id, n] : ls) {
        s += std::to_string(id.level);
        for (std::uint64_t v : id.index) {
            s += ' ';
            s += std::to_string(v);
        }
        std::vector<GridPoint> gs;
        for (const Entry& e : n->points) gs.push_back(e.grid);
        std::sort(gs.begin(), gs.end());
        for (const GridPoint& g : gs) {
            s += " |";
            for (std::uint64_t v : g) {
                s += ' ';
                s += std::to_string(v);
            }
        }
        s += "\n";
    }
    return s;
}

template <int D>
CheckReport DynQuadtree<D>::check_invariants() const {
    std::vector<std::string> bad;
    auto name = [](const Key& k) {
        std::string s = "cell (level " + std::to_string(k.level) + ";";
        for (std::uint64_t v : k.a) {
            s += ' ';
            s += std::to_string(v);
        }
        return s + ")";
    };
    auto child = [](const Key& x, int mask) {
        Key ch;
        ch.level = x.level - 1;
        for (int i = 0; i < D; ++i) ch.a[i] = 2 * x.a[i] + ((mask >> i) & 1);
        return ch;
    };
    // Deepest stored cell containing-or-equal y.
    auto deepest = [&](Key y) -> std::pair<Key, const Node*> {
        while (true) {
            if (const auto it = nodes_.find(y); it != nodes_.end()) return {y, &it->second};
            if (y.level >= kLevels) return {y, nullptr};
            for (int i = 0; i < D; ++i) y.a[i] >>= 1;
            ++y.level;
        }
    };

    if (!nodes_.contains(root_key())) bad.push_back("root missing");
    std::size_t leaf_points = 0, internal = 0;
    for (const auto& [x, n] : nodes_) {
        if (x.level < 0 || x.level > kLevels) {
            bad.push_back(name(x) + ": level out of range");
            continue;
        }
        if (x.level < kLevels) {
            Key par = x;
            for (int i = 0; i < D; ++i) par.a[i] >>= 1;
            ++par.level;
            const auto it = nodes_.find(par);
            if (it == nodes_.end() || it->second.is_leaf)
                bad.push_back(name(x) + ": parent missing or a leaf");
        }
        if (n.is_leaf) {
            leaf_points += n.points.size();
            if (n.count != n.points.size()) bad.push_back(name(x) + ": leaf count mismatch");
            for (const Entry& e : n.points)
                if (cell_of(e.grid, x.level) != x) bad.push_back(name(x) + ": point outside leaf");
            if (n.points.size() >= 2) bad.push_back(name(x) + ": self-crowded leaf");
            if (x.level < 1) bad.push_back(name(x) + ": leaf smaller than 2 grid units");
            if (!is_resolved({x.level, x.a}))
                bad.push_back(name(x) + ": leaf below the coordinate resolution");
        } else {
            ++internal;
            if (!n.points.empty()) bad.push_back(name(x) + ": internal cell holds points");
            std::uint64_t sum = 0;
            for (int mask = 0; mask < (1 << D); ++mask) {
                const auto it = nodes_.find(child(x, mask));
                if (it == nodes_.end()) {
                    bad.push_back(name(x) + ": child missing");
                } else {
                    sum += it->second.count;
                }
            }
            if (sum != n.count) bad.push_back(name(x) + ": count != sum of children");
        }
    }
    if (leaf_points != size_)
        bad.push_back("leaves hold " + std::to_string(leaf_points) + " points, size() is " +
                      std::to_string(size_));

    // Leaves: balanced (touching leaves differ < 4x) and not crowded by a neighbour (§1.3).
    for (const auto& [x, n] : nodes_) {
        if (!n.is_leaf) continue;
        for (const auto& o : block3<D>()) {
            Key y;
            if (!offset_cell(x, o, y) || y == x) continue;
            const auto [z, zn] = deepest(y);
            if (!zn) continue;
            if (zn->is_leaf) {
                if (z.level >= x.level + 2)
                    bad.push_back(name(x) + ": unbalanced against leaf " + name(z));
                if (n.points.size() == 1 && !zn->points.empty())
                    bad.push_back(name(x) + ": crowded by neighbour leaf " + name(z));
            } else if (n.points.size() == 1) {
                // y is internal: its children touching x are leaves when balanced.
                for (int mask = 0; mask < (1 << D); ++mask) {
                    const Key ch = child(y, mask);
                    bool touches = true;
                    for (int i = 0; i < D; ++i) {
                        // closures of ch (size s/2) and x (size s) meet along axis i
                        const std::uint64_t lo = ch.a[i], xlo = 2 * x.a[i];
                        touches = touches && lo + 1 >= xlo && lo <= xlo + 2;
                    }
                    if (!touches) continue;
                    const auto it = nodes_.find(ch);
                    if (it != nodes_.end() && it->second.is_leaf && !it->second.points.empty())
                        bad.push_back(name(x) + ": crowded by neighbour leaf " + name(ch));
                }
            }
        }
    }

    // Local certificate (§3.4): state = internal cells, closure under C, A, B, supports.
    if (state_.size() != internal)
        bad.push_back("state holds " + std::to_string(state_.size()) + " cells, tree has " +
                      std::to_string(internal) + " internal cells");
    const bool mesh = options_.mode == QuadtreeMode::Mesh;
    std::unordered_map<Key, int, KeyHash> support;
    for (const auto& [x, s] : state_) {
        const auto it = nodes_.find(x);
        if (!s.in_i || it == nodes_.end() || it->second.is_leaf)
            bad.push_back(name(x) + ": state entry is not an internal cell");
        if (s.crowded != is_crowded(x)) bad.push_back(name(x) + ": stale crowded flag");
        support[x] += s.crowded ? 1 : 0;
        for (const Key& y : up_neighbours(x)) {
            if (!state_.contains(y)) bad.push_back(name(x) + ": rule B/A violated at " + name(y));
            ++support[y];
        }
        if (mesh && count_in(x) > 0)
            for (const auto& o : block3<D>()) {
                Key y;
                if (!offset_cell(x, o, y) || y == x) continue;
                if (!state_.contains(y)) bad.push_back(name(x) + ": rule U violated at " + name(y));
                ++support[y];
            }
    }
    if (mesh && size_ > 0) {
        if (!state_.contains(root_key())) bad.push_back("rule R violated: the root is a leaf");
        ++support[root_key()];
    }
    // Mesh mode: every leaf touching a point leaf has its size (spec §1.4).
    if (mesh)
        for (const auto& [x, n] : nodes_) {
            if (!n.is_leaf || n.points.empty()) continue;
            for (const auto& o : block3<D>()) {
                Key y;
                if (!offset_cell(x, o, y) || y == x) continue;
                const auto it = nodes_.find(y);
                if (it == nodes_.end() || !it->second.is_leaf)
                    bad.push_back(name(x) + ": point leaf whose neighbour " + name(y) +
                                  " is not a leaf of its size");
            }
        }
    for (const auto& [x, s] : state_) {
        if (s.support != support[x])
            bad.push_back(name(x) + ": stored support " + std::to_string(s.support) +
                          " != recomputed " + std::to_string(support[x]));
        if (support[x] <= 0) bad.push_back(name(x) + ": internal cell without support");
    }
    for (const auto& [x, n] : nodes_)
        if (n.is_leaf && is_crowded(x)) bad.push_back(name(x) + ": crowded leaf (rule C)");
    return CheckReport::of_problems(std::move(bad));
}

template class DynQuadtree<2>;
template class DynQuadtree<3>;

}  // namespace dynmesh
