#include "leaf_mesh.hpp"

#include <algorithm>
#include <bit>
#include <string>
#include <utility>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"

namespace dynmesh::detail {

namespace {

template <int D>
constexpr int kLevels = DynQuadtree<D>::kLevels;

constexpr int pow3(int d) { return d == 0 ? 1 : 3 * pow3(d - 1); }

/// The midpoint probes of a cell: offsets e in {0, 1, 2}^D (units of s/2) with between 1 and
/// D − 1 coordinates equal to 1, numbered in base-3 order (e[0] least significant).
template <int D>
struct Probes {
    std::array<int, pow3(D)> index{};  // base-3 number -> probe number, or -1
    std::vector<std::array<int, D>> offsets;
    /// Per probe: the block cells (base-3 numbers of offset + 1) other than the leaf itself
    /// whose closure contains the probe point.
    std::vector<std::vector<int>> sharing;
    /// Per corner (base-3 number of digits 0 / 2): the block cells having that corner.
    std::array<std::vector<int>, pow3(D)> around_corner;
    Probes() {
        const auto digits = [](int num) {
            std::array<int, D> e{};
            for (int d = 0; d < D; ++d, num /= 3) e[d] = num % 3;
            return e;
        };
        for (int num = 0; num < pow3(D); ++num) {
            const std::array<int, D> e = digits(num);
            int ones = 0;
            for (int d = 0; d < D; ++d) ones += e[d] == 1 ? 1 : 0;
            // Block cell with offset o (digit o + 1) contains point lo + (s/2)·e in its closure
            // iff per axis: e = 1 -> o = 0; e = 0 -> o in {-1, 0}; e = 2 -> o in {0, 1}.
            std::vector<int> cells;
            for (int c = 0; c < pow3(D); ++c) {
                const std::array<int, D> o = digits(c);
                bool ok = c != (pow3(D) - 1) / 2;
                for (int d = 0; d < D && ok; ++d)
                    ok = e[d] == 1 ? o[d] == 1 : e[d] == 0 ? o[d] <= 1 : o[d] >= 1;
                if (ok) cells.push_back(c);
            }
            if (ones == 0) {
                cells.push_back((pow3(D) - 1) / 2);
                around_corner[static_cast<std::size_t>(num)] = cells;
            }
            if (ones >= 1 && ones <= D - 1) {
                index[num] = static_cast<int>(offsets.size());
                offsets.push_back(e);
                sharing.push_back(cells);
            } else {
                index[num] = -1;
            }
        }
    }
};

template <int D>
const Probes<D>& probes() {
    static const Probes<D> p;
    return p;
}

/// Bit layout of a code after the probe bits.
template <int D>
int star_bit() {
    return static_cast<int>(probes<D>().offsets.size());
}
template <int D>
int apex_bit(int d) {
    return star_bit<D>() + 1 + d;
}
template <int D>
int holds_bit() {
    return star_bit<D>() + 1 + D;
}

/// Point leaves at or below this level (smaller than 2 input quanta) place their point at its
/// grid position instead of its input coordinates (see assemble()).
template <int D>
constexpr int kSnapLevel = DynQuadtree<D>::kGuardBits;


}  // namespace

template <int D>
std::string cell_name(const CellId<D>& c) {
    std::string s = "cell (level " + std::to_string(c.level) + ";";
    for (std::uint64_t v : c.index) {
        s += ' ';
        s += std::to_string(v);
    }
    return s + ")";
}

template <int D>
std::pair<Lattice<D>, std::uint64_t> cell_box(const CellId<D>& c) {
    Lattice<D> lo{};
    for (int d = 0; d < D; ++d) lo[d] = c.index[d] << c.level;
    return {lo, std::uint64_t{1} << c.level};
}

template <int D>
LeafCode leaf_code(const DynQuadtree<D>& tree, const CellId<D>& leaf) {
    // The 3^D block of equal-size cells around the leaf, numbered in base 3 (offset + 1).
    constexpr int kBlock = pow3(D);
    constexpr int kSelf = (pow3(D) - 1) / 2;
    const std::uint64_t n = std::uint64_t{1} << (kLevels<D> - leaf.level);
    std::array<typename DynQuadtree<D>::CellView, kBlock> block{};
    for (int num = 0; num < kBlock; ++num) {
        CellId<D> y{leaf.level, {}};
        bool ok = true;
        for (int d = 0, r = num; d < D && ok; ++d, r /= 3) {
            const std::uint64_t a = leaf.index[d] + static_cast<std::uint64_t>(r % 3);
            ok = a >= 1 && a - 1 < n;
            y.index[d] = a - 1;
        }
        if (ok) block[num] = tree.cell_view(y);
    }

    // A midpoint probe is a vertex iff one of the equal-size cells sharing its face/edge is
    // internal (its children have a corner there; in a balanced tree no smaller leaf does).
    LeafCode code = 0;
    const auto& pr = probes<D>();
    for (std::size_t i = 0; i < pr.offsets.size(); ++i)
        for (int num : pr.sharing[i])
            if (block[num].kind == CellKind::Internal) {
                code |= LeafCode{1} << i;
                break;
            }

    // Stars (§4.1): a point leaf of this size in the block whose warped corner (ties round up)
    // is a corner of this leaf.
    const auto [lo, s] = cell_box(leaf);
    const std::uint64_t h = s / 2;
    for (int num = 0; num < kBlock; ++num) {
        if (block[num].kind != CellKind::Leaf || block[num].points.empty()) continue;
        const auto& pts = block[num].points;
        if (pts.size() > 1) throw InternalError("quadtree mesh: a leaf holds two points");
        int apex_num = 0;  // the apex as a block offset from this leaf: digit 0 (lo) or 2 (lo + s)
        bool corner_of_leaf = true;
        for (int d = D - 1; d >= 0; --d) {
            const int od = (num / pow3(d)) % 3 - 1;  // the point leaf's offset along d
            const std::uint64_t ylo = lo[d] + static_cast<std::uint64_t>(od) * s;
            const int up = pts[0].grid[d] - ylo >= h ? 1 : 0;  // warped corner: ylo + up·s
            const int rel = od + up;                              // in units of s from lo
            corner_of_leaf = corner_of_leaf && (rel == 0 || rel == 1);
            apex_num = apex_num * 3 + 2 * rel;
        }
        if (!corner_of_leaf) continue;
        if (code & (LeafCode{1} << star_bit<D>()))
            throw InternalError("quadtree mesh: two stars share " + cell_name(leaf));
        code |= LeafCode{1} << star_bit<D>();
        for (int d = 0; d < D; ++d)
            if ((apex_num / pow3(d)) % 3 == 2) code |= LeafCode{1} << apex_bit<D>(d);
        if (num != kSelf) continue;
        code |= LeafCode{1} << holds_bit<D>();
        // The star lemma: the 2^D cells around the apex are leaves of this size.
        for (int star : pr.around_corner[static_cast<std::size_t>(apex_num)])
            if (block[star].kind != CellKind::Leaf)
                throw InternalError(
                    "quadtree mesh: star lemma violated (a star cell of the point in " +
                    cell_name(leaf) + " is not a leaf of its size)");
    }
    return code;
}

template <int D>
bool code_has_vertex(const CellId<D>& leaf, LeafCode code, const Lattice<D>& v) {
    const auto [lo, s] = cell_box(leaf);
    const std::uint64_t h = s / 2;
    int num = 0, ones = 0;
    for (int d = D - 1; d >= 0; --d) {
        const std::uint64_t r = v[d] - lo[d];  // wraps for v < lo: then no digit matches
        int digit;
        if (r == 0)
            digit = 0;
        else if (r == h)
            digit = 1;
        else if (r == s)
            digit = 2;
        else
            return false;
        ones += digit == 1 ? 1 : 0;
        num = num * 3 + digit;
    }
    if (ones == 0) return true;  // a corner of the leaf
    const int i = probes<D>().index[num];
    return i >= 0 && ((code >> i) & 1) != 0;
}

template <int D>
bool code_is_star(LeafCode code) {
    return ((code >> star_bit<D>()) & 1) != 0;
}

template <int D>
bool code_holds_point(LeafCode code) {
    return ((code >> holds_bit<D>()) & 1) != 0;
}

template <int D>
Lattice<D> code_apex(const CellId<D>& leaf, LeafCode code) {
    auto [v, s] = cell_box(leaf);
    for (int d = 0; d < D; ++d)
        if ((code >> apex_bit<D>(d)) & 1) v[d] += s;
    return v;
}

template <int D>
void orient_lattice_simplex(LatticeSimplex<D>& t) {
    // Exact: lattice coordinates are integers below 2^53.
    std::array<PointD<D>, D + 1> lat;
    for (int i = 0; i <= D; ++i)
        for (int d = 0; d < D; ++d)
            lat[static_cast<std::size_t>(i)][static_cast<std::size_t>(d)] =
                static_cast<double>(t[static_cast<std::size_t>(i)][static_cast<std::size_t>(d)]);
    Sign want;
    if constexpr (D == 2)
        want = orient2d(lat[0], lat[1], lat[2]);
    else
        want = orient3d(lat[0], lat[1], lat[2], lat[3]);
    if (want == Sign::Zero) throw InternalError("quadtree mesh: a flat simplex");
    if (D == 2 && want == Sign::Negative)
        throw InternalError("quadtree mesh: a clockwise triangle in the construction");
    if (want == Sign::Negative) std::swap(t[D - 1], t[D]);
}

template <int D>
void check_warped_orientation(const std::array<PointD<D>, D + 1>& p) {
    Sign s;
    if constexpr (D == 2)
        s = orient2d(p[0], p[1], p[2]);
    else
        s = orient3d(p[0], p[1], p[2], p[3]);
    if (s != Sign::Positive)
        throw InternalError("quadtree mesh: warping an input point inverted or flattened a simplex");
}

template <int D>
PointD<D> lattice_position(const QuadtreeOptions<D>& domain, const Lattice<D>& k) {
    const double unit = domain.width * 0x1p-52;  // exact: a power-of-two scaling
    PointD<D> p;
    for (int d = 0; d < D; ++d) {
        const auto ud = static_cast<std::size_t>(d);
        p[ud] = domain.origin[ud] + static_cast<double>(k[d]) * unit;
    }
    return p;
}

template <int D>
const PointD<D>* star_point(const DynQuadtree<D>& tree, const CellId<D>& leaf, LeafCode code) {
    if (!code_is_star<D>(code) || leaf.level <= kSnapLevel<D>) return nullptr;
    const Lattice<D> v = code_apex<D>(leaf, code);
    for (int mask = 0; mask < (1 << D); ++mask) {  // the 2^D star cells around the apex
        CellId<D> c{leaf.level, {}};
        for (int d = 0; d < D; ++d) c.index[d] = (v[d] >> leaf.level) - 1 + ((mask >> d) & 1);
        const auto pts = tree.leaf_points(c);
        if (!pts.empty()) return &pts[0].point;
    }
    throw InternalError("quadtree mesh: a star without its point at " + cell_name(leaf));
}

template <int D>
AssembledMesh<D> assemble(const DynQuadtree<D>& tree,
                          std::span<const std::pair<CellId<D>, LeafCode>> leaves) {
    using Point = PointD<D>;
    std::vector<LatticeSimplex<D>> simplices;
    simplices.reserve(leaves.size() * (D == 2 ? 3 : 24));
    std::vector<std::pair<Lattice<D>, Point>> warped;  // apex -> input point
    std::vector<std::pair<typename DynQuadtree<D>::GridPoint, Lattice<D>>> inputs;
    for (const auto& [leaf, code] : leaves) {
        leaf_simplices<D>(leaf, code, simplices);
        if (code_holds_point<D>(code)) {
            const auto pts = tree.leaf_points(leaf);
            DYNMESH_ASSERT(pts.size() == 1, "assemble: a point leaf without its point");
            const Lattice<D> v = code_apex<D>(leaf, code);
            // Inputs lie within one quantum (2^kGuardBits units) above their grid point. In a
            // leaf of at least 2 quanta that keeps the point in the leaf's half towards v, the
            // region the star analysis assumes; in a smaller leaf (points within about two
            // quanta of each other) the grid point equals v and is used instead.
            if (leaf.level > kSnapLevel<D>) warped.emplace_back(v, pts[0].point);
            inputs.emplace_back(pts[0].grid, v);
        }
    }
    std::sort(warped.begin(), warped.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 1; i < warped.size(); ++i)
        if (warped[i].first == warped[i - 1].first)
            throw InternalError("quadtree mesh: two points warp to one corner");

    std::vector<Lattice<D>> keys;
    keys.reserve(simplices.size() * (D + 1) / 2);
    for (const auto& t : simplices) keys.insert(keys.end(), t.begin(), t.end());
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    const auto index = [&keys](const Lattice<D>& k) {
        return static_cast<std::uint32_t>(std::lower_bound(keys.begin(), keys.end(), k) -
                                          keys.begin());
    };

    AssembledMesh<D> out;
    out.points.reserve(keys.size());
    auto w = warped.begin();
    for (const Lattice<D>& k : keys) {
        while (w != warped.end() && w->first < k) ++w;
        if (w != warped.end() && w->first == k)
            out.points.push_back(w->second);
        else
            out.points.push_back(lattice_position<D>(tree.options(), k));
    }
    // Orientation: the sign of each simplex at the lattice positions decides the vertex order;
    // the simplex at the real positions must have the same sign.
    out.simplices.reserve(simplices.size());
    for (auto& t : simplices) {
        orient_lattice_simplex<D>(t);
        std::array<std::uint32_t, D + 1> s{};
        std::array<Point, D + 1> real;
        for (int i = 0; i <= D; ++i) {
            s[i] = index(t[i]);
            real[i] = out.points[s[i]];
        }
        check_warped_orientation<D>(real);
        out.simplices.push_back(s);
    }
    std::sort(inputs.begin(), inputs.end());
    out.input_vertices.reserve(inputs.size());
    for (const auto& [g, v] : inputs) out.input_vertices.push_back(index(v));
    return out;
}

template <int D>
const DynQuadtree<D>& mesh_mode_tree(const DynQuadtree<D>& tree, DynQuadtree<D>& storage) {
    if (tree.options().mode == QuadtreeMode::Mesh) return tree;
    std::vector<PointD<D>> pts;
    pts.reserve(tree.size());
    for (const auto& [g, p] : tree.points()) pts.push_back(p);
    QuadtreeOptions<D> options = tree.options();
    options.mode = QuadtreeMode::Mesh;
    storage = DynQuadtree<D>::build(pts, options);
    return storage;
}

template <int D>
std::vector<std::pair<CellId<D>, LeafCode>> coded_leaves(const DynQuadtree<D>& tree) {
    std::vector<std::pair<CellId<D>, LeafCode>> out;
    const auto leaves = tree.leaves();
    out.reserve(leaves.size());
    for (const CellId<D>& c : leaves) out.emplace_back(c, leaf_code(tree, c));
    return out;
}

template <int D>
void append_vertex_problems(std::span<const PointD<D>> points, const std::vector<bool>& used,
                            std::vector<std::string>& bad) {
    const std::size_t n = points.size();
    for (std::size_t v = 0; v < n; ++v)
        if (!used[v]) bad.push_back("vertex " + std::to_string(v) + " is unused");
    std::vector<std::pair<std::array<double, D>, std::size_t>> sorted;
    sorted.reserve(n);
    for (std::size_t v = 0; v < n; ++v) {
        std::array<double, D> c{};
        for (int d = 0; d < D; ++d) c[d] = points[v][static_cast<std::size_t>(d)];
        sorted.push_back({c, v});
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 1; k < sorted.size(); ++k)
        if (sorted[k].first == sorted[k - 1].first)
            bad.push_back("vertices " + std::to_string(sorted[k - 1].second) + " and " +
                          std::to_string(sorted[k].second) + " coincide");
}

template <int D>
PublicMesh<D> mesh_from_leaves(const DynQuadtree<D>& tree,
                               std::span<const std::pair<CellId<D>, LeafCode>> leaves) {
    AssembledMesh<D> a = assemble<D>(tree, leaves);
    PublicMesh<D> mesh;
    mesh.origin = tree.options().origin;
    mesh.width = tree.options().width;
    mesh.leaves = leaves.size();
    mesh.points = std::move(a.points);
    if constexpr (D == 2)
        mesh.triangles = std::move(a.simplices);
    else
        mesh.tets = std::move(a.simplices);
    mesh.input_vertices = std::move(a.input_vertices);
    return mesh;
}

template <int D>
PublicMesh<D> mesh_of_tree(const DynQuadtree<D>& tree) {
    DynQuadtree<D> storage;
    const DynQuadtree<D>& mt = mesh_mode_tree(tree, storage);
    return mesh_from_leaves<D>(mt, coded_leaves(mt));
}

#define DYNMESH_LEAF_MESH(D)                                                                   \
    template LeafCode leaf_code<D>(const DynQuadtree<D>&, const CellId<D>&);                   \
    template bool code_has_vertex<D>(const CellId<D>&, LeafCode, const Lattice<D>&);           \
    template bool code_is_star<D>(LeafCode);                                                   \
    template bool code_holds_point<D>(LeafCode);                                               \
    template Lattice<D> code_apex<D>(const CellId<D>&, LeafCode);                              \
    template std::pair<Lattice<D>, std::uint64_t> cell_box<D>(const CellId<D>&);               \
    template void orient_lattice_simplex<D>(LatticeSimplex<D>&);                               \
    template void check_warped_orientation<D>(const std::array<PointD<D>, D + 1>&);            \
    template PointD<D> lattice_position<D>(const QuadtreeOptions<D>&, const Lattice<D>&);      \
    template const PointD<D>* star_point<D>(const DynQuadtree<D>&, const CellId<D>&, LeafCode); \
    template std::string cell_name<D>(const CellId<D>&);                                       \
    template AssembledMesh<D> assemble<D>(const DynQuadtree<D>&,                               \
                                          std::span<const std::pair<CellId<D>, LeafCode>>);    \
    template const DynQuadtree<D>& mesh_mode_tree<D>(const DynQuadtree<D>&, DynQuadtree<D>&); \
    template std::vector<std::pair<CellId<D>, LeafCode>> coded_leaves<D>(const DynQuadtree<D>&); \
    template PublicMesh<D> mesh_from_leaves<D>(const DynQuadtree<D>&,                          \
                                               std::span<const std::pair<CellId<D>, LeafCode>>); \
    template PublicMesh<D> mesh_of_tree<D>(const DynQuadtree<D>&);                             \
    template void append_vertex_problems<D>(std::span<const PointD<D>>, const std::vector<bool>&, \
                                            std::vector<std::string>&);
DYNMESH_LEAF_MESH(2)
DYNMESH_LEAF_MESH(3)
#undef DYNMESH_LEAF_MESH

}  // namespace dynmesh::detail
