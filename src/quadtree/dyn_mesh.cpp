#include "dynmesh/quadtree/dyn_mesh.hpp"

#include <algorithm>
#include <cstdio>
#include <unordered_map>
#include <utility>

#include "dynmesh/error.hpp"
#include "leaf_mesh.hpp"

namespace dynmesh {

namespace {

template <int D>
constexpr int kLevels = DynQuadtree<D>::kLevels;

/// Simplices of a leaf with this code: a function of the code alone (the leaf only places
/// them). Memoised per thread; codes have at most 2^(P + D + 2) values.
template <int D>
std::size_t simplices_of_code(detail::LeafCode code) {
    static thread_local std::unordered_map<detail::LeafCode, std::size_t> memo;
    static thread_local std::vector<detail::LatticeSimplex<D>> scratch;
    if (const auto it = memo.find(code); it != memo.end()) return it->second;
    scratch.clear();
    const CellId<D> probe{10, {}};  // any leaf of side >= 4 grid units
    detail::leaf_simplices<D>(probe, code, scratch);
    memo.emplace(code, scratch.size());
    return scratch.size();
}

/// Calls f(cell) for every cell of `level` with index in [lo_d, hi_d] per axis, clipped to the
/// domain.
template <int D, class F>
void for_cells(int level, std::array<std::int64_t, D> lo, std::array<std::int64_t, D> hi, F&& f) {
    if (level < 0 || level > kLevels<D>) return;
    const std::int64_t n = std::int64_t{1} << (kLevels<D> - level);
    for (int d = 0; d < D; ++d) {
        lo[d] = std::max<std::int64_t>(lo[d], 0);
        hi[d] = std::min<std::int64_t>(hi[d], n - 1);
        if (lo[d] > hi[d]) return;
    }
    std::array<std::int64_t, D> i = lo;
    while (true) {
        CellId<D> c{level, {}};
        for (int d = 0; d < D; ++d) c.index[d] = static_cast<std::uint64_t>(i[d]);
        f(c);
        int d = 0;
        while (d < D && i[d] == hi[d]) {
            i[d] = lo[d];
            ++d;
        }
        if (d == D) return;
        ++i[d];
    }
}

/// The cells of sizes |x|/2 and |x| whose closures meet x's closure: every cell whose 3^D
/// block (the cells its code reads) can contain x or one of x's children. A leaf of size 2|x|
/// reads cells of size 2|x| only, and x's change leaves their kinds and points alone unless
/// x's parent changed too (then the parent is a changed cell itself).
template <int D, class F>
void for_cells_near(const CellId<D>& x, F&& f) {
    std::array<std::int64_t, D> lo{}, hi{};
    for (int d = 0; d < D; ++d) {
        const auto a = static_cast<std::int64_t>(x.index[d]);
        lo[d] = 2 * a - 1;
        hi[d] = 2 * a + 2;
    }
    for_cells<D>(x.level - 1, lo, hi, f);
    for (int d = 0; d < D; ++d) {
        const auto a = static_cast<std::int64_t>(x.index[d]);
        lo[d] = a - 1;
        hi[d] = a + 1;
    }
    for_cells<D>(x.level, lo, hi, f);
}

}  // namespace

template <int D>
std::size_t DynQuadMesh<D>::CellHash::operator()(const CellId<D>& c) const noexcept {
    std::uint64_t h = static_cast<std::uint64_t>(c.level) * 0x9e3779b97f4a7c15ULL;
    for (std::uint64_t v : c.index) {
        h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
        h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
    }
    return static_cast<std::size_t>(h ^ (h >> 31));
}

template <int D>
DynQuadMesh<D>::DynQuadMesh(const QuadtreeOptions<D>& domain)
    : tree_([&] {
          QuadtreeOptions<D> o = domain;
          o.mode = QuadtreeMode::Mesh;
          return o;
      }()) {
    for (const auto& [c, code] : detail::coded_leaves(tree_)) {
        codes_.emplace(c, code);
        simplices_ += simplices_of_code<D>(code);
    }
}

template <int D>
DynQuadMesh<D> DynQuadMesh<D>::build(std::span<const Point> points,
                                     const QuadtreeOptions<D>& domain) {
    QuadtreeOptions<D> o = domain;
    o.mode = QuadtreeMode::Mesh;
    DynQuadMesh m(o);
    m.tree_ = DynQuadtree<D>::build(points, o);
    m.codes_.clear();
    m.simplices_ = 0;
    const auto leaves = detail::coded_leaves(m.tree_);
    m.codes_.reserve(leaves.size());
    for (const auto& [c, code] : leaves) {
        m.codes_.emplace(c, code);
        m.simplices_ += simplices_of_code<D>(code);
    }
    return m;
}

template <int D>
InsertResult DynQuadMesh<D>::insert(const Point& p) {
    const InsertResult r = tree_.insert(p);
    if (r == InsertResult::Inserted) refresh(tree_.grid_point(p));
    return r;
}

template <int D>
EraseResult DynQuadMesh<D>::erase(const Point& p) {
    const EraseResult r = tree_.erase(p);
    if (r == EraseResult::Erased) refresh(tree_.grid_point(p));
    return r;
}

template <int D>
void DynQuadMesh<D>::refresh(const typename DynQuadtree<D>::GridPoint& g) {
    MeshUpdateReport<D> rep;
    rep.tree = tree_.last_update();
    const auto drop = [&](const CellId<D>& c) {
        if (const auto it = codes_.find(c); it != codes_.end()) {
            ++rep.leaves_removed;
            rep.simplices_removed += simplices_of_code<D>(it->second);
            codes_.erase(it);
        }
    };
    for (const CellId<D>& x : rep.tree.split) drop(x);
    for (const CellId<D>& x : rep.tree.merged)
        for (int mask = 0; mask < (1 << D); ++mask) {
            CellId<D> ch{x.level - 1, {}};
            for (int d = 0; d < D; ++d) ch.index[d] = 2 * x.index[d] + ((mask >> d) & 1);
            drop(ch);
        }

    std::vector<CellId<D>> near;
    const auto collect = [&](const CellId<D>& c) { near.push_back(c); };
    for (const CellId<D>& x : rep.tree.split) for_cells_near<D>(x, collect);
    for (const CellId<D>& x : rep.tree.merged) for_cells_near<D>(x, collect);
    for_cells_near<D>(tree_.leaf_containing(g), collect);
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());

    for (const CellId<D>& c : near) {
        if (tree_.cell_kind(c) != CellKind::Leaf) continue;
        ++rep.leaves_examined;
        const detail::LeafCode code = detail::leaf_code(tree_, c);
        const auto [it, fresh] = codes_.try_emplace(c, code);
        if (fresh) {
            ++rep.leaves_created;
            rep.simplices_added += simplices_of_code<D>(code);
        } else if (it->second != code) {
            ++rep.leaves_remeshed;
            rep.simplices_removed += simplices_of_code<D>(it->second);
            rep.simplices_added += simplices_of_code<D>(code);
            it->second = code;
        }
    }
    simplices_ = simplices_ + rep.simplices_added - rep.simplices_removed;
    last_update_ = std::move(rep);
}

template <int D>
typename DynQuadMesh<D>::Mesh DynQuadMesh<D>::mesh() const {
    std::vector<std::pair<CellId<D>, detail::LeafCode>> leaves(codes_.begin(), codes_.end());
    std::sort(leaves.begin(), leaves.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    return detail::mesh_from_leaves<D>(tree_, leaves);
}

template <int D>
std::string DynQuadMesh<D>::canonical_dump() const {
    const Mesh m = mesh();
    const auto& simplices = [&]() -> const auto& {
        if constexpr (D == 2)
            return m.triangles;
        else
            return m.tets;
    }();
    std::string s = tree_.canonical_dump();
    s += "mesh vertices=" + std::to_string(m.points.size()) +
         " simplices=" + std::to_string(simplices.size()) + "\n";
    char buf[48];
    for (const auto& p : m.points) {
        for (int d = 0; d < D; ++d) {
            std::snprintf(buf, sizeof buf, d ? " %a" : "%a", p[static_cast<std::size_t>(d)]);
            s += buf;
        }
        s += '\n';
    }
    for (const auto& t : simplices) {
        for (int i = 0; i <= D; ++i) {
            if (i) s += ' ';
            s += std::to_string(t[static_cast<std::size_t>(i)]);
        }
        s += '\n';
    }
    return s;
}

template <int D>
std::vector<std::string> DynQuadMesh<D>::check_invariants() const {
    std::vector<std::string> bad = tree_.check_invariants();
    const auto leaves = tree_.leaves();
    if (codes_.size() != leaves.size())
        bad.push_back("mesh holds codes for " + std::to_string(codes_.size()) +
                      " leaves, the tree has " + std::to_string(leaves.size()));
    std::size_t total = 0;
    for (const CellId<D>& c : leaves) {
        const std::string name = detail::cell_name(c);
        const auto it = codes_.find(c);
        if (it == codes_.end()) {
            bad.push_back(name + " has no mesh code");
            continue;
        }
        try {
            const detail::LeafCode want = detail::leaf_code(tree_, c);
            if (it->second != want) bad.push_back(name + ": stale mesh code");
        } catch (const InternalError& e) {
            bad.push_back(name + ": " + e.what());
        }
        total += simplices_of_code<D>(it->second);
    }
    if (total != simplices_)
        bad.push_back("simplex count " + std::to_string(simplices_) + " != recomputed " +
                      std::to_string(total));
    return bad;
}

template class DynQuadMesh<2>;
template class DynQuadMesh<3>;

}  // namespace dynmesh
