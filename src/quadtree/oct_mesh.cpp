#include "dynmesh/quadtree/oct_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"

namespace dynmesh {

namespace {

constexpr int kLevels = DynQuadtree<3>::kLevels;

std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/// A dyadic cell: ∏_i [a_i·2^level, (a_i+1)·2^level).
struct Cell {
    int level = 0;
    std::array<std::uint64_t, 3> a{};
    auto operator<=>(const Cell&) const = default;
};
struct CellHash {
    std::size_t operator()(const Cell& c) const noexcept {
        std::uint64_t h = mix(static_cast<std::uint64_t>(c.level));
        for (std::uint64_t v : c.a) h = mix(h ^ v);
        return static_cast<std::size_t>(h);
    }
};
/// A lattice point in grid units (coordinates in [0, 2^52]).
using Lattice = std::array<std::uint64_t, 3>;
struct LatticeHash {
    std::size_t operator()(const Lattice& v) const noexcept {
        return static_cast<std::size_t>(mix(mix(mix(v[0]) ^ v[1]) ^ v[2]));
    }
};

using CellSet = std::unordered_set<Cell, CellHash>;
using LatticeSet = std::unordered_set<Lattice, LatticeHash>;
using GridPoint = DynQuadtree<3>::GridPoint;

Cell cell_of(const GridPoint& g, int level) {
    return {level, {g[0] >> level, g[1] >> level, g[2] >> level}};
}

/// Number of cells per axis at `level`.
std::int64_t cells_per_axis(int level) { return std::int64_t{1} << (kLevels - level); }

/// The mesh-mode tree (spec §1.4, k = 2, rules C, A, B, U, R) of the tree's point set,
/// seeded with the tree's own internal cells (paper-mode I(P) ⊆ mesh-mode I(P)).
class MeshModeRefiner {
public:
    explicit MeshModeRefiner(const DynQuadtree<3>& tree) : points_(tree.points()) {
        count_.reserve(points_.size() * (kLevels + 1));
        in_i_.reserve(2 * tree.leaf_count());
        for (const auto& [g, p] : points_)
            for (int j = 0; j <= kLevels; ++j) ++count_[cell_of(g, j)];
        for (const CellId<3>& leaf : tree.leaves())
            if (leaf.level < kLevels)
                add({leaf.level + 1, {leaf.index[0] >> 1, leaf.index[1] >> 1, leaf.index[2] >> 1}});
        if (!points_.empty()) add({kLevels, {0, 0, 0}});  // rule R
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
    [[nodiscard]] const std::vector<std::pair<GridPoint, Vec3>>& points() const { return points_; }

private:
    [[nodiscard]] std::uint64_t count(const Cell& c) const {
        const auto it = count_.find(c);
        return it == count_.end() ? 0 : it->second;
    }
    /// Calls f(cell) for every cell of x's level with index in [x.a - r, x.a + r] per axis
    /// (clipped to the domain).
    template <class F>
    static void for_block(const Cell& x, std::int64_t r, F&& f) {
        const std::int64_t n = cells_per_axis(x.level);
        const auto ix = static_cast<std::int64_t>(x.a[0]), iy = static_cast<std::int64_t>(x.a[1]),
                   iz = static_cast<std::int64_t>(x.a[2]);
        for (std::int64_t i = std::max<std::int64_t>(ix - r, 0); i <= std::min(ix + r, n - 1); ++i)
            for (std::int64_t j = std::max<std::int64_t>(iy - r, 0); j <= std::min(iy + r, n - 1);
                 ++j)
                for (std::int64_t k = std::max<std::int64_t>(iz - r, 0);
                     k <= std::min(iz + r, n - 1); ++k)
                    f(Cell{x.level,
                           {static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j),
                            static_cast<std::uint64_t>(k)}});
    }
    /// |P ∩ N_2[x]| (the 5×5×5 block of equal-size cells centred on x, clipped to the domain).
    [[nodiscard]] std::uint64_t block_count(const Cell& x) const {
        std::uint64_t total = 0;
        for_block(x, 2, [&](const Cell& y) { total += count(y); });
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
                // Cells of size 2|x| whose closures meet x: indices (a-1..a+1) >> 1 per axis
                // (the parent is among them: rule A).
                const int up = x.level + 1;
                const std::int64_t n = cells_per_axis(up);
                std::array<std::int64_t, 3> lo{}, hi{};
                for (std::size_t d = 0; d < 3; ++d) {
                    const auto a = static_cast<std::int64_t>(x.a[d]);
                    lo[d] = std::max<std::int64_t>(a - 1, 0) >> 1;
                    hi[d] = std::min((a + 1) >> 1, n - 1);
                }
                for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
                    for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                        for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
                            add({up,
                                 {static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j),
                                  static_cast<std::uint64_t>(k)}});
            }
            if (count(x) > 0) for_block(x, 1, [&](const Cell& y) { add(y); });  // rule U
        }
    }

    std::vector<std::pair<GridPoint, Vec3>> points_;
    std::unordered_map<Cell, std::uint64_t, CellHash> count_;
    CellSet in_i_;
    std::vector<Cell> work_;
};

using Tri = std::array<Lattice, 3>;

/// Triangulates and cones the leaves (spec §4.3, §4.4) over lattice keys.
class Triangulator {
public:
    explicit Triangulator(const LatticeSet& corners) : corners_(corners) {}

    /// The facet triangles of face (axis, side) of the cell with lower corner x and size s.
    void face_triangles(const Lattice& x, std::uint64_t s, std::size_t axis, int side,
                        std::vector<Tri>& out) const {
        Lattice lo = x;
        lo[axis] += side == 1 ? s : 0;
        const std::size_t b = (axis + 1) % 3, c = (axis + 2) % 3;
        const std::uint64_t h = s / 2;
        Lattice centre = lo;
        centre[b] += h;
        centre[c] += h;
        if (s >= 2 && corners_.contains(centre)) {  // the leaf across is smaller
            for (int q = 0; q < 4; ++q) {
                Lattice sub = lo;
                sub[b] += (q & 1) ? h : 0;
                sub[c] += (q & 2) ? h : 0;
                square_triangles(sub, h, b, c, out);
            }
        } else {
            square_triangles(lo, s, b, c, out);
        }
    }

private:
    /// One facet: the square with lower corner lo and side s spanning axes b and c.
    void square_triangles(const Lattice& lo, std::uint64_t s, std::size_t b, std::size_t c,
                          std::vector<Tri>& out) const {
        const auto at = [&](std::uint64_t db, std::uint64_t dc) {
            Lattice p = lo;
            p[b] += db;
            p[c] += dc;
            return p;
        };
        const std::uint64_t h = s / 2;
        const bool even = s >= 2 && s % 2 == 0;
        std::array<Lattice, 8> cycle{};
        std::size_t m = 0;
        bool hanging = false;
        const auto push_side = [&](const Lattice& corner, const Lattice& mid) {
            cycle[m++] = corner;
            if (even && corners_.contains(mid)) {
                cycle[m++] = mid;
                hanging = true;
            }
        };
        push_side(at(0, 0), at(h, 0));
        push_side(at(s, 0), at(s, h));
        push_side(at(s, s), at(h, s));
        push_side(at(0, s), at(0, h));
        if (!hanging) {
            // Diagonal from the lexicographically smallest corner at(0, 0) to at(s, s).
            out.push_back({cycle[0], cycle[1], cycle[2]});
            out.push_back({cycle[0], cycle[2], cycle[3]});
            return;
        }
        const Lattice centre = at(h, h);
        for (std::size_t k = 0; k < m; ++k) out.push_back({centre, cycle[k], cycle[(k + 1) % m]});
    }

    const LatticeSet& corners_;
};

/// 6·signed volume of (a, b, c, d), in long double.
long double six_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const long double ux = static_cast<long double>(b.x) - a.x, uy = static_cast<long double>(b.y) - a.y,
                      uz = static_cast<long double>(b.z) - a.z;
    const long double vx = static_cast<long double>(c.x) - a.x, vy = static_cast<long double>(c.y) - a.y,
                      vz = static_cast<long double>(c.z) - a.z;
    const long double wx = static_cast<long double>(d.x) - a.x, wy = static_cast<long double>(d.y) - a.y,
                      wz = static_cast<long double>(d.z) - a.z;
    return ux * (vy * wz - vz * wy) - uy * (vx * wz - vz * wx) + uz * (vx * wy - vy * wx);
}

}  // namespace

OctMesh3 oct_mesh(const DynQuadtree<3>& tree) {
    const MeshModeRefiner refiner(tree);
    const CellSet& in_i = refiner.internal();

    // Leaves: children of I-cells that are not in I (or the root alone).
    std::vector<Cell> leaves;
    for (const Cell& x : in_i) {
        if (x.level == 0) throw InternalError("oct_mesh: a cell of size 1 grid unit was split");
        for (std::uint64_t k = 0; k < 8; ++k) {
            const Cell ch{x.level - 1,
                          {2 * x.a[0] + (k & 1), 2 * x.a[1] + ((k >> 1) & 1), 2 * x.a[2] + (k >> 2)}};
            if (!in_i.contains(ch)) leaves.push_back(ch);
        }
    }
    if (in_i.empty()) leaves.push_back({kLevels, {0, 0, 0}});
    std::sort(leaves.begin(), leaves.end());
    const CellSet leaf_set(leaves.begin(), leaves.end());

    LatticeSet corners;
    corners.reserve(4 * leaves.size());
    for (const Cell& c : leaves) {
        const std::uint64_t s = std::uint64_t{1} << c.level;
        for (std::uint64_t k = 0; k < 8; ++k)
            corners.insert({c.a[0] * s + ((k & 1) ? s : 0), c.a[1] * s + (((k >> 1) & 1) ? s : 0),
                            c.a[2] * s + ((k >> 2) ? s : 0)});
    }

    // Warping (§4.2) and stars (§4.1): star cell -> its warped corner.
    std::unordered_map<Cell, Lattice, CellHash> stars;
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
        if (!found) throw InternalError("oct_mesh: point without a leaf");
        const std::uint64_t s = std::uint64_t{1} << c.level;
        Lattice v{};
        for (std::size_t d = 0; d < 3; ++d) {
            const std::uint64_t a = c.a[d] * s;
            v[d] = g[d] - a >= s / 2 ? a + s : a;
        }
        if (!warped.emplace(v, i).second)
            throw InternalError("oct_mesh: two points warp to one corner");
        for (std::uint64_t k = 0; k < 8; ++k) {
            Cell sc{c.level, {}};
            for (std::size_t d = 0; d < 3; ++d) {
                const std::uint64_t lo = ((k >> d) & 1) ? v[d] : v[d] - s;
                sc.a[d] = lo >> c.level;
            }
            if (!leaf_set.contains(sc))
                throw InternalError(
                    "oct_mesh: star lemma violated (a star cell is not a leaf of the point "
                    "leaf's size)");
            if (!stars.emplace(sc, v).second)
                throw InternalError("oct_mesh: two stars share a cell");
        }
    }

    // Tetrahedra over lattice keys: (apex, facet triangle), oriented later.
    const Triangulator triangulator(corners);
    std::vector<std::array<Lattice, 4>> cones;
    cones.reserve(24 * leaves.size());
    std::vector<Tri> facets;
    for (const Cell& c : leaves) {
        const std::uint64_t s = std::uint64_t{1} << c.level;
        const Lattice x{c.a[0] * s, c.a[1] * s, c.a[2] * s};
        const auto star = stars.find(c);
        const bool is_star = star != stars.end();
        const Lattice apex = is_star ? star->second : Lattice{x[0] + s / 2, x[1] + s / 2, x[2] + s / 2};
        facets.clear();
        for (std::size_t axis = 0; axis < 3; ++axis)
            for (int side = 0; side < 2; ++side) {
                // A star cell's faces through v are interior to the star: skip them.
                if (is_star && apex[axis] == x[axis] + (side == 1 ? s : 0)) continue;
                triangulator.face_triangles(x, s, axis, side, facets);
            }
        for (const Tri& t : facets) cones.push_back({apex, t[0], t[1], t[2]});
    }

    // Vertices sorted by lattice key.
    std::unordered_map<Lattice, std::uint32_t, LatticeHash> index_of;
    index_of.reserve(cones.size() / 2);
    for (const auto& t : cones)
        for (const Lattice& k : t) index_of.emplace(k, 0);
    std::vector<Lattice> keys;
    keys.reserve(index_of.size());
    for (const auto& [k, i] : index_of) keys.push_back(k);
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 0; i < keys.size(); ++i)
        index_of[keys[i]] = static_cast<std::uint32_t>(i);

    OctMesh3 mesh;
    mesh.origin = tree.options().origin;
    mesh.width = tree.options().width;
    mesh.leaves = leaves.size();
    const double unit = mesh.width * 0x1p-52;  // exact: a power-of-two scaling
    const auto index = [&index_of](const Lattice& k) { return index_of.at(k); };
    mesh.points.reserve(keys.size());
    for (const Lattice& k : keys) {
        if (const auto w = warped.find(k); w != warped.end())
            mesh.points.push_back(pts[w->second].second);
        else
            mesh.points.push_back({mesh.origin.x + static_cast<double>(k[0]) * unit,
                                   mesh.origin.y + static_cast<double>(k[1]) * unit,
                                   mesh.origin.z + static_cast<double>(k[2]) * unit});
    }
    mesh.tets.reserve(cones.size());
    for (const auto& t : cones) {
        std::array<std::uint32_t, 4> tet{index(t[0]), index(t[1]), index(t[2]), index(t[3])};
        const Sign o = orient3d(mesh.points[tet[0]], mesh.points[tet[1]], mesh.points[tet[2]],
                                mesh.points[tet[3]]);
        if (o == Sign::Zero) throw InternalError("oct_mesh: a flat tetrahedron");
        if (o == Sign::Negative) std::swap(tet[2], tet[3]);
        mesh.tets.push_back(tet);
    }
    mesh.input_vertices.resize(pts.size());
    for (const auto& [k, i] : warped) mesh.input_vertices[i] = index(k);
    return mesh;
}

std::vector<std::string> check_oct_mesh(const OctMesh3& mesh) {
    std::vector<std::string> bad;
    const auto n = mesh.points.size();
    std::vector<bool> used(n, false);
    // Sorted face -> parities; the face of a positive tet opposite its vertex i is outward
    // when i is even, so parity = [i odd] xor parity of the sorting permutation.
    std::vector<std::pair<std::array<std::uint32_t, 3>, bool>> faces;
    faces.reserve(4 * mesh.tets.size());
    long double volume6 = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const auto& tet = mesh.tets[t];
        const std::string name = "tetrahedron " + std::to_string(t);
        if (tet[0] >= n || tet[1] >= n || tet[2] >= n || tet[3] >= n) {
            bad.push_back(name + ": index out of range");
            continue;
        }
        bool distinct = true;
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) distinct = distinct && tet[i] != tet[j];
        if (!distinct) {
            bad.push_back(name + ": repeated vertex");
            continue;
        }
        for (int i = 0; i < 4; ++i) {
            used[tet[i]] = true;
            std::array<std::uint32_t, 3> f{};
            for (int j = 0, m = 0; j < 4; ++j)
                if (j != i) f[m++] = tet[j];
            bool parity = (i % 2) == 1;
            // Sort three values, tracking the permutation parity.
            for (const auto& [x, y] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{0, 1}}) {
                if (f[x] > f[y]) {
                    std::swap(f[x], f[y]);
                    parity = !parity;
                }
            }
            faces.emplace_back(f, parity);
        }
        const Vec3 &a = mesh.points[tet[0]], &b = mesh.points[tet[1]], &c = mesh.points[tet[2]],
                   &d = mesh.points[tet[3]];
        if (orient3d(a, b, c, d) != Sign::Positive)
            bad.push_back(name + " is not positively oriented");
        volume6 += six_volume(a, b, c, d);
    }
    const long double want = static_cast<long double>(mesh.width) * mesh.width * mesh.width;
    if (std::fabs(volume6 / 6 - want) > 1e-12L * want)
        bad.push_back("total volume " + std::to_string(static_cast<double>(volume6 / 6)) +
                      " differs from the domain volume " + std::to_string(static_cast<double>(want)));
    const Vec3 lo = mesh.origin;
    const Vec3 hi{lo.x + mesh.width, lo.y + mesh.width, lo.z + mesh.width};
    std::sort(faces.begin(), faces.end());
    for (std::size_t i = 0; i < faces.size();) {
        std::size_t j = i + 1;
        while (j < faces.size() && faces[j].first == faces[i].first) ++j;
        const auto& f = faces[i].first;
        const std::string name = "triangle (" + std::to_string(f[0]) + ", " +
                                 std::to_string(f[1]) + ", " + std::to_string(f[2]) + ")";
        if (j - i == 1) {
            const Vec3 &p = mesh.points[f[0]], &q = mesh.points[f[1]], &r = mesh.points[f[2]];
            bool on_box = false;
            for (std::size_t d = 0; d < 3; ++d)
                on_box = on_box || (p[d] == lo[d] && q[d] == lo[d] && r[d] == lo[d]) ||
                         (p[d] == hi[d] && q[d] == hi[d] && r[d] == hi[d]);
            if (!on_box)
                bad.push_back(name + " has one tetrahedron but is not on the domain boundary");
        } else if (j - i == 2) {
            if (faces[i].second == faces[i + 1].second)
                bad.push_back(name + ": its two tetrahedra disagree in orientation");
        } else {
            bad.push_back(name + " is shared by " + std::to_string(j - i) + " tetrahedra");
        }
        i = j;
    }
    for (std::size_t v = 0; v < n; ++v)
        if (!used[v]) bad.push_back("vertex " + std::to_string(v) + " is unused");
    std::vector<std::pair<std::array<double, 3>, std::size_t>> sorted;
    sorted.reserve(n);
    for (std::size_t v = 0; v < n; ++v)
        sorted.push_back({{mesh.points[v].x, mesh.points[v].y, mesh.points[v].z}, v});
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 1; k < sorted.size(); ++k)
        if (sorted[k].first == sorted[k - 1].first)
            bad.push_back("vertices " + std::to_string(sorted[k - 1].second) + " and " +
                          std::to_string(sorted[k].second) + " coincide");
    return bad;
}

DihedralRangeDeg dihedral_range_deg(const OctMesh3& mesh) {
    DihedralRangeDeg r;
    constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                  {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    for (const auto& t : mesh.tets)
        for (const auto& e : kEdges) {
            // The dihedral angle at edge pq is the angle between the components of
            // (a - p) and (b - p) orthogonal to q - p.
            const Vec3& p = mesh.points[t[e[0]]];
            const Vec3 axis = normalized(mesh.points[t[e[1]]] - p);
            Vec3 u = mesh.points[t[e[2]]] - p, w = mesh.points[t[e[3]]] - p;
            u -= dot(u, axis) * axis;
            w -= dot(w, axis) * axis;
            const double deg =
                std::atan2(norm(cross(u, w)), dot(u, w)) * 180.0 / std::numbers::pi;
            r.min = std::min(r.min, deg);
            r.max = std::max(r.max, deg);
        }
    return r;
}

double min_dihedral_deg(const OctMesh3& mesh) { return dihedral_range_deg(mesh).min; }
double max_dihedral_deg(const OctMesh3& mesh) { return dihedral_range_deg(mesh).max; }

}  // namespace dynmesh
