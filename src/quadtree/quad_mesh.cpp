#include "dynmesh/quadtree/quad_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"

namespace dynmesh {

namespace {

constexpr int kLevels = DynQuadtree<2>::kLevels;

std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/// A dyadic cell: [ix·2^level, (ix+1)·2^level) × [iy·2^level, (iy+1)·2^level).
struct Cell {
    int level = 0;
    std::uint64_t ix = 0, iy = 0;
    auto operator<=>(const Cell&) const = default;
};
struct CellHash {
    std::size_t operator()(const Cell& c) const noexcept {
        return static_cast<std::size_t>(
            mix(mix(mix(static_cast<std::uint64_t>(c.level)) ^ c.ix) ^ c.iy));
    }
};
/// A lattice point in grid units (both coordinates in [0, 2^52]).
using Lattice = std::pair<std::uint64_t, std::uint64_t>;
struct LatticeHash {
    std::size_t operator()(const Lattice& v) const noexcept {
        return static_cast<std::size_t>(mix(mix(v.first) ^ v.second));
    }
};

using CellSet = std::unordered_set<Cell, CellHash>;

Cell cell_of(const std::array<std::uint64_t, 2>& g, int level) {
    return {level, g[0] >> level, g[1] >> level};
}

/// Number of cells per axis at `level`.
std::uint64_t cells_per_axis(int level) { return std::uint64_t{1} << (kLevels - level); }

/// The mesh-mode tree (spec §1.4, k = 2, rules C, A, B, U, R) of the tree's point set,
/// seeded with the tree's own internal cells. Returns the leaves, sorted.
class MeshModeRefiner {
public:
    explicit MeshModeRefiner(const DynQuadtree<2>& tree) : points_(tree.points()) {
        count_.reserve(points_.size() * (kLevels + 1));
        in_i_.reserve(2 * tree.leaf_count());
        for (const auto& [g, p] : points_)
            for (int j = 0; j <= kLevels; ++j) ++count_[cell_of(g, j)];
        for (const CellId<2>& leaf : tree.leaves())
            if (leaf.level < kLevels) add({leaf.level + 1, leaf.index[0] >> 1, leaf.index[1] >> 1});
        if (!points_.empty()) add({kLevels, 0, 0});  // rule R
        for (const auto& [g, p] : points_) {
            // crowded_2 is monotone upwards along p's ancestors: find the lowest crowded one.
            int lo = 0, hi = kLevels + 1;  // answer in [lo, hi); hi = none
            while (lo < hi) {
                const int mid = (lo + hi) / 2;
                if (block_count(cell_of(g, mid)) >= 2)
                    hi = mid;
                else
                    lo = mid + 1;
            }
            if (lo <= kLevels) add(cell_of(g, lo));  // rule C
        }
        close();
    }

    [[nodiscard]] const CellSet& internal() const { return in_i_; }
    [[nodiscard]] std::uint64_t count(const Cell& c) const {
        const auto it = count_.find(c);
        return it == count_.end() ? 0 : it->second;
    }
    [[nodiscard]] const std::vector<std::pair<DynQuadtree<2>::GridPoint, Vec2>>& points() const {
        return points_;
    }

private:
    /// |P ∩ N_2[x]| (the 5×5 block of equal-size cells centred on x, clipped to the domain).
    [[nodiscard]] std::uint64_t block_count(const Cell& x) const {
        const auto n = static_cast<std::int64_t>(cells_per_axis(x.level));
        std::uint64_t total = 0;
        for (std::int64_t dx = -2; dx <= 2; ++dx)
            for (std::int64_t dy = -2; dy <= 2; ++dy) {
                const std::int64_t i = static_cast<std::int64_t>(x.ix) + dx;
                const std::int64_t j = static_cast<std::int64_t>(x.iy) + dy;
                if (i < 0 || j < 0 || i >= n || j >= n) continue;
                total +=
                    count({x.level, static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j)});
            }
        return total;
    }
    void add(const Cell& c) {
        if (in_i_.insert(c).second) work_.push_back(c);
    }
    /// Closes I under A (parent), B (2:1 corner balance) and U (equal-size neighbours of a
    /// point-holding cell).
    void close() {
        while (!work_.empty()) {
            const Cell x = work_.back();
            work_.pop_back();
            if (x.level < kLevels) {
                const int up = x.level + 1;
                const auto n = static_cast<std::int64_t>(cells_per_axis(up));
                const auto ix = static_cast<std::int64_t>(x.ix),
                           iy = static_cast<std::int64_t>(x.iy);
                // Cells of size 2|x| whose closures meet x: indices (ix-1..ix+1) >> 1.
                for (std::int64_t i = std::max<std::int64_t>(ix - 1, 0) >> 1;
                     i <= std::min((ix + 1) >> 1, n - 1); ++i)
                    for (std::int64_t j = std::max<std::int64_t>(iy - 1, 0) >> 1;
                         j <= std::min((iy + 1) >> 1, n - 1); ++j)
                        add({up, static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j)});
                // (the parent is among them: rule A)
            }
            if (count(x) > 0) {
                const auto n = static_cast<std::int64_t>(cells_per_axis(x.level));
                for (std::int64_t dx = -1; dx <= 1; ++dx)
                    for (std::int64_t dy = -1; dy <= 1; ++dy) {
                        const std::int64_t i = static_cast<std::int64_t>(x.ix) + dx;
                        const std::int64_t j = static_cast<std::int64_t>(x.iy) + dy;
                        if (i < 0 || j < 0 || i >= n || j >= n) continue;
                        add({x.level, static_cast<std::uint64_t>(i),
                             static_cast<std::uint64_t>(j)});
                    }
            }
        }
    }

    std::vector<std::pair<DynQuadtree<2>::GridPoint, Vec2>> points_;
    std::unordered_map<Cell, std::uint64_t, CellHash> count_;
    CellSet in_i_;
    std::vector<Cell> work_;
};

/// 2·signed area of (a, b, c), in long double.
long double twice_area(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (static_cast<long double>(b.x) - a.x) * (static_cast<long double>(c.y) - a.y) -
           (static_cast<long double>(b.y) - a.y) * (static_cast<long double>(c.x) - a.x);
}

}  // namespace

QuadMesh2 quad_mesh(const DynQuadtree<2>& tree) {
    const MeshModeRefiner refiner(tree);
    const CellSet& in_i = refiner.internal();

    // Leaves: children of I-cells that are not in I (or the root alone).
    std::vector<Cell> leaves;
    for (const Cell& x : in_i) {
        if (x.level == 0) throw InternalError("quad_mesh: a cell of size 1 grid unit was split");
        for (std::uint64_t k = 0; k < 4; ++k) {
            const Cell ch{x.level - 1, 2 * x.ix + (k & 1), 2 * x.iy + (k >> 1)};
            if (!in_i.contains(ch)) leaves.push_back(ch);
        }
    }
    if (in_i.empty()) leaves.push_back({kLevels, 0, 0});
    std::sort(leaves.begin(), leaves.end());
    const CellSet leaf_set(leaves.begin(), leaves.end());

    std::unordered_set<Lattice, LatticeHash> corners;
    corners.reserve(2 * leaves.size());
    for (const Cell& c : leaves) {
        const std::uint64_t s = std::uint64_t{1} << c.level, x = c.ix * s, y = c.iy * s;
        corners.insert({x, y});
        corners.insert({x + s, y});
        corners.insert({x, y + s});
        corners.insert({x + s, y + s});
    }

    // Warping (§4.2) and stars (§4.1).
    struct Star {
        Lattice v;
        std::size_t point = 0;
        bool holds_point = false;
    };
    std::unordered_map<Cell, Star, CellHash> stars;
    std::unordered_map<Lattice, std::size_t, LatticeHash> warped;  // lattice key -> point index
    const auto& pts = refiner.points();
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const auto& g = pts[i].first;
        Cell c{};
        bool found = false;
        for (int j = 0; j <= kLevels && !found; ++j) {
            c = cell_of(g, j);
            found = leaf_set.contains(c);
        }
        if (!found) throw InternalError("quad_mesh: point without a leaf");
        const std::uint64_t s = std::uint64_t{1} << c.level, ax = c.ix * s, ay = c.iy * s;
        const Lattice v{g[0] - ax >= s / 2 ? ax + s : ax, g[1] - ay >= s / 2 ? ay + s : ay};
        if (!warped.emplace(v, i).second)
            throw InternalError("quad_mesh: two points warp to one corner");
        for (std::uint64_t k = 0; k < 4; ++k) {
            const std::uint64_t cx = (k & 1) ? v.first : v.first - s;
            const std::uint64_t cy = (k >> 1) ? v.second : v.second - s;
            const Cell sc{c.level, cx >> c.level, cy >> c.level};
            if (!leaf_set.contains(sc))
                throw InternalError(
                    "quad_mesh: star lemma violated (a star cell is not a leaf of "
                    "the point leaf's size)");
            if (!stars.emplace(sc, Star{v, i, sc == c}).second)
                throw InternalError("quad_mesh: two stars share a cell");
        }
    }

    // Triangles over lattice keys.
    std::vector<std::array<Lattice, 3>> tris;
    std::vector<Lattice> cycle;
    for (const Cell& c : leaves) {
        const std::uint64_t s = std::uint64_t{1} << c.level, h = s / 2, x = c.ix * s, y = c.iy * s;
        cycle.clear();
        bool hanging = false;
        const auto push_side = [&](Lattice corner, Lattice mid) {
            cycle.push_back(corner);
            if (h > 0 && corners.contains(mid)) {
                cycle.push_back(mid);
                hanging = true;
            }
        };
        push_side({x, y}, {x + h, y});
        push_side({x + s, y}, {x + s, y + h});
        push_side({x + s, y + s}, {x + h, y + s});
        push_side({x, y + s}, {x, y + h});
        const Lattice centre{x + h, y + h};
        const std::size_t m = cycle.size();
        const auto star = stars.find(c);
        if (star != stars.end() && star->second.holds_point) {
            const Lattice v = star->second.v;  // cone from the point (at v) over the far sides
            for (std::size_t k = 0; k < m; ++k) {
                const Lattice a = cycle[k], b = cycle[(k + 1) % m];
                if (a != v && b != v) tris.push_back({v, a, b});
            }
        } else if (star != stars.end() || hanging) {
            for (std::size_t k = 0; k < m; ++k)
                tris.push_back({centre, cycle[k], cycle[(k + 1) % m]});
        } else {
            tris.push_back({cycle[0], cycle[1], cycle[2]});
            tris.push_back({cycle[0], cycle[2], cycle[3]});
        }
    }

    // Vertices sorted by lattice key.
    std::vector<Lattice> keys;
    keys.reserve(3 * tris.size());
    for (const auto& t : tris) keys.insert(keys.end(), t.begin(), t.end());
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());

    QuadMesh2 mesh;
    mesh.origin = tree.options().origin;
    mesh.width = tree.options().width;
    mesh.leaves = leaves.size();
    const double unit = mesh.width * 0x1p-52;  // exact: a power-of-two scaling
    const auto index = [&keys](const Lattice& k) {
        return static_cast<std::uint32_t>(std::lower_bound(keys.begin(), keys.end(), k) -
                                          keys.begin());
    };
    mesh.points.reserve(keys.size());
    for (const Lattice& k : keys) {
        if (const auto w = warped.find(k); w != warped.end())
            mesh.points.push_back(pts[w->second].second);
        else
            mesh.points.push_back({mesh.origin.x + static_cast<double>(k.first) * unit,
                                   mesh.origin.y + static_cast<double>(k.second) * unit});
    }
    mesh.triangles.reserve(tris.size());
    for (const auto& t : tris) mesh.triangles.push_back({index(t[0]), index(t[1]), index(t[2])});
    mesh.input_vertices.resize(pts.size());
    for (const auto& [k, i] : warped) mesh.input_vertices[i] = index(k);
    return mesh;
}

std::vector<std::string> check_quad_mesh(const QuadMesh2& mesh) {
    std::vector<std::string> bad;
    const auto n = mesh.points.size();
    std::vector<bool> used(n, false);
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<bool>> edges;  // dir: a<b
    long double area2 = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        if (tri[0] >= n || tri[1] >= n || tri[2] >= n) {
            bad.push_back("triangle " + std::to_string(t) + ": index out of range");
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            used[tri[k]] = true;
            const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
            edges[{std::min(a, b), std::max(a, b)}].push_back(a < b);
        }
        const Vec2 &a = mesh.points[tri[0]], &b = mesh.points[tri[1]], &c = mesh.points[tri[2]];
        if (orient2d(a, b, c) != Sign::Positive)
            bad.push_back("triangle " + std::to_string(t) + " is not counter-clockwise");
        area2 += twice_area(a, b, c);
    }
    const long double want = static_cast<long double>(mesh.width) * mesh.width;
    if (std::fabs(area2 / 2 - want) > 1e-12L * want)
        bad.push_back("total area " + std::to_string(static_cast<double>(area2 / 2)) +
                      " differs from the domain area " + std::to_string(static_cast<double>(want)));
    const double x0 = mesh.origin.x, y0 = mesh.origin.y, x1 = x0 + mesh.width, y1 = y0 + mesh.width;
    for (const auto& [e, dirs] : edges) {
        const std::string name =
            "edge (" + std::to_string(e.first) + ", " + std::to_string(e.second) + ")";
        if (dirs.size() == 1) {
            const Vec2 &p = mesh.points[e.first], &q = mesh.points[e.second];
            const bool on_box = (p.x == x0 && q.x == x0) || (p.x == x1 && q.x == x1) ||
                                (p.y == y0 && q.y == y0) || (p.y == y1 && q.y == y1);
            if (!on_box)
                bad.push_back(name + " has one triangle but is not on the domain boundary");
        } else if (dirs.size() == 2) {
            if (dirs[0] == dirs[1])
                bad.push_back(name + ": its two triangles disagree in orientation");
        } else {
            bad.push_back(name + " is shared by " + std::to_string(dirs.size()) + " triangles");
        }
    }
    for (std::size_t v = 0; v < n; ++v)
        if (!used[v]) bad.push_back("vertex " + std::to_string(v) + " is unused");
    std::vector<std::pair<std::pair<double, double>, std::size_t>> sorted;
    sorted.reserve(n);
    for (std::size_t v = 0; v < n; ++v) sorted.push_back({{mesh.points[v].x, mesh.points[v].y}, v});
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 1; k < sorted.size(); ++k)
        if (sorted[k].first == sorted[k - 1].first)
            bad.push_back("vertices " + std::to_string(sorted[k - 1].second) + " and " +
                          std::to_string(sorted[k].second) + " coincide");
    return bad;
}

AngleRangeDeg angle_range_deg(const QuadMesh2& mesh) {
    AngleRangeDeg r;
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const Vec2& p = mesh.points[t[k]];
            const Vec2& a = mesh.points[t[(k + 1) % 3]];
            const Vec2& b = mesh.points[t[(k + 2) % 3]];
            const double ux = a.x - p.x, uy = a.y - p.y, vx = b.x - p.x, vy = b.y - p.y;
            const double deg = std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180.0 /
                               std::numbers::pi;
            r.min = std::min(r.min, deg);
            r.max = std::max(r.max, deg);
        }
    return r;
}

}  // namespace dynmesh
