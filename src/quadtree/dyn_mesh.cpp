#include "dynmesh/quadtree/dyn_mesh.hpp"

#include <algorithm>
#include <cstdio>
#include <unordered_map>
#include <utility>

#include "dynmesh/error.hpp"
#include "dynmesh/system/hash.hpp"
#include "leaf_mesh.hpp"

namespace dynmesh {

namespace {

template <int D>
constexpr int kLevels = DynQuadtree<D>::kLevels;

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
    return static_cast<std::size_t>(hash_range(c.index, static_cast<std::uint64_t>(c.level)));
}

template <int D>
std::size_t DynQuadMesh<D>::LatticeHash::operator()(const Lattice& k) const noexcept {
    return static_cast<std::size_t>(hash_range(k));
}

template <int D>
DynQuadMesh<D>::DynQuadMesh(const QuadtreeOptions<D>& domain)
    : tree_([&] {
          QuadtreeOptions<D> o = domain;
          o.mode = QuadtreeMode::Mesh;
          return o;
      }()) {
    rebuild_live();
}

template <int D>
DynQuadMesh<D> DynQuadMesh<D>::build(std::span<const Point> points,
                                     const QuadtreeOptions<D>& domain) {
    QuadtreeOptions<D> o = domain;
    o.mode = QuadtreeMode::Mesh;
    DynQuadMesh m(o);
    m.tree_ = DynQuadtree<D>::build(points, o);
    m.rebuild_live();
    return m;
}

template <int D>
void DynQuadMesh<D>::rebuild_live() {
    leaves_.clear();
    live_.reset();
    vertices_.clear();
    vertex_at_.clear();
    unused_.clear();
    const auto coded = detail::coded_leaves(tree_);
    leaves_.reserve(coded.size());
    for (const auto& [c, code] : coded) add_leaf(c, code);
    live_.recycle();
    delta_.clear();
}

template <int D>
std::uint32_t DynQuadMesh<D>::acquire_vertex(const Lattice& k, const Point& p) {
    if (const auto it = vertex_at_.find(k); it != vertex_at_.end()) {
        const std::uint32_t v = it->second;
        if (live_.point(v) == p) {
            ++vertices_[v].uses;
            return v;
        }
        // The corner was warped or unwarped by this update: its old vertex must be unused.
        if (vertices_[v].uses != 0)
            throw InternalError("DynQuadMesh: a lattice vertex with two positions");
        live_.remove_vertex(v, delta_);
        vertex_at_.erase(it);
    }
    const std::uint32_t v = live_.add_vertex(p, delta_);
    if (v >= vertices_.size()) vertices_.resize(v + 1);
    vertices_[v] = {k, 1};
    vertex_at_.emplace(k, v);
    return v;
}

template <int D>
void DynQuadMesh<D>::leaf_geometry(const CellId<D>& c, std::uint32_t code,
                                   std::vector<Lattice>& keys, std::vector<Point>& points) const {
    static thread_local std::vector<detail::LatticeSimplex<D>> lattice;
    lattice.clear();
    keys.clear();
    points.clear();
    detail::leaf_simplices<D>(c, code, lattice);
    const Point* warped = detail::star_point<D>(tree_, c, code);
    const Lattice apex = detail::code_apex<D>(c, code);
    for (auto& t : lattice) {
        detail::orient_lattice_simplex<D>(t);
        std::array<Point, D + 1> real;
        for (int i = 0; i <= D; ++i) {
            const auto ui = static_cast<std::size_t>(i);
            real[ui] = warped && t[ui] == apex ? *warped
                                               : detail::lattice_position<D>(tree_.options(), t[ui]);
            keys.push_back(t[ui]);
            points.push_back(real[ui]);
        }
        detail::check_warped_orientation<D>(real);
    }
}

template <int D>
void DynQuadMesh<D>::add_leaf(const CellId<D>& c, std::uint32_t code) {
    static thread_local std::vector<Lattice> keys;
    static thread_local std::vector<Point> points;
    static thread_local std::vector<typename LiveMesh<D>::Simplex> simplices;
    static thread_local std::vector<std::pair<Lattice, std::uint32_t>> seen;  // this leaf's
    leaf_geometry(c, code, keys, points);
    simplices.assign(keys.size() / (D + 1), {});
    seen.clear();
    for (std::size_t k = 0; k < keys.size(); ++k) {
        // A leaf has at most 3^D lattice vertices: look each up in the hash map once.
        std::uint32_t v = LiveMesh<D>::kNone;
        for (const auto& [key, id] : seen)
            if (key == keys[k]) {
                v = id;
                break;
            }
        if (v == LiveMesh<D>::kNone) {
            v = acquire_vertex(keys[k], points[k]);
            seen.emplace_back(keys[k], v);
        } else {
            ++vertices_[v].uses;
        }
        simplices[k / (D + 1)][k % (D + 1)] = v;
    }
    const std::uint32_t first = live_.add_simplices(simplices, delta_);
    leaves_[c] = {code, first, static_cast<std::uint32_t>(simplices.size())};
}

template <int D>
void DynQuadMesh<D>::remove_leaf(const LeafRecord& r) {
    for (std::uint32_t k = 0; k < r.count; ++k)
        for (std::uint32_t v : live_.simplex(r.first + k))
            if (--vertices_[v].uses == 0) unused_.push_back(v);
    live_.remove_simplices(r.first, r.count, delta_);
}

template <int D>
void DynQuadMesh<D>::drop_unused_vertices() {
    for (std::uint32_t v : unused_) {
        if (!live_.has_vertex(v) || vertices_[v].uses != 0) continue;  // revived or replaced
        vertex_at_.erase(vertices_[v].key);
        live_.remove_vertex(v, delta_);
    }
    unused_.clear();
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
    QuadMeshUpdateReport<D> rep;
    rep.tree = tree_.last_update();
    delta_.clear();
    const auto drop = [&](const CellId<D>& c) {
        if (const auto it = leaves_.find(c); it != leaves_.end()) {
            ++rep.leaves_removed;
            remove_leaf(it->second);
            leaves_.erase(it);
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

    // Remove every stale block first, then add the new ones, so that a corner that is warped
    // or unwarped by this update is seen unused before its new vertex is made.
    std::vector<std::pair<CellId<D>, detail::LeafCode>> fresh;
    for (const CellId<D>& c : near) {
        if (tree_.cell_kind(c) != CellKind::Leaf) continue;
        ++rep.leaves_examined;
        const detail::LeafCode code = detail::leaf_code(tree_, c);
        const auto it = leaves_.find(c);
        if (it == leaves_.end()) {
            ++rep.leaves_created;
        } else if (it->second.code != code) {
            ++rep.leaves_remeshed;
            remove_leaf(it->second);
        } else {
            continue;
        }
        fresh.emplace_back(c, code);
    }
    for (const auto& [c, code] : fresh) add_leaf(c, code);
    drop_unused_vertices();
    live_.recycle();
    rep.simplices_removed = delta_.removed_simplices.size();
    rep.simplices_added = delta_.added_simplices.size();
    rep.vertices_removed = delta_.removed_vertices.size();
    rep.vertices_added = delta_.added_vertices.size();
    last_update_ = std::move(rep);
}

template <int D>
typename DynQuadMesh<D>::Mesh DynQuadMesh<D>::mesh() const {
    std::vector<std::pair<CellId<D>, detail::LeafCode>> leaves;
    leaves.reserve(leaves_.size());
    for (const auto& [c, r] : leaves_) leaves.emplace_back(c, r.code);
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
CheckReport DynQuadMesh<D>::check_invariants() const {
    std::vector<std::string> bad = tree_.check_invariants().problems;
    const auto leaves = tree_.leaves();
    if (leaves_.size() != leaves.size())
        bad.push_back("mesh holds codes for " + std::to_string(leaves_.size()) +
                      " leaves, the tree has " + std::to_string(leaves.size()));
    std::size_t total = 0;
    for (const CellId<D>& c : leaves) {
        const std::string name = detail::cell_name(c);
        const auto it = leaves_.find(c);
        if (it == leaves_.end()) {
            bad.push_back(name + " has no mesh code");
            continue;
        }
        try {
            const detail::LeafCode want = detail::leaf_code(tree_, c);
            if (it->second.code != want) bad.push_back(name + ": stale mesh code");
        } catch (const InternalError& e) {
            bad.push_back(name + ": " + e.what());
        }
        // Its block holds the simplices its code gives, vertex for vertex.
        try {
            std::vector<Lattice> keys;
            std::vector<Point> points;
            leaf_geometry(c, it->second.code, keys, points);
            if (keys.size() != std::size_t{it->second.count} * (D + 1))
                bad.push_back(name + ": its block has " + std::to_string(it->second.count) +
                              " simplices, its code gives " + std::to_string(keys.size() / (D + 1)));
            for (std::size_t k = 0; k < keys.size() && k / (D + 1) < it->second.count; ++k) {
                const std::uint32_t s = it->second.first + static_cast<std::uint32_t>(k / (D + 1));
                if (!live_.has_simplex(s)) {
                    bad.push_back(name + ": simplex " + std::to_string(s) + " is not live");
                    break;
                }
                const std::uint32_t v = live_.simplex(s)[k % (D + 1)];
                if (!live_.has_vertex(v) || !(live_.point(v) == points[k]) ||
                    v >= vertices_.size() || vertices_[v].key != keys[k]) {
                    bad.push_back(name + ": live simplex " + std::to_string(s) +
                                  " differs from its code's");
                    break;
                }
            }
        } catch (const InternalError& e) {
            bad.push_back(name + ": " + e.what());
        }
        total += it->second.count;
    }
    if (total != live_.simplex_count())
        bad.push_back("live mesh has " + std::to_string(live_.simplex_count()) +
                      " simplices, the leaf blocks " + std::to_string(total));

    // Vertex use counts and positions.
    std::vector<std::uint32_t> uses(live_.vertex_slots(), 0);
    for (std::uint32_t s = 0; s < live_.simplex_slots(); ++s)
        if (live_.has_simplex(s))
            for (std::uint32_t v : live_.simplex(s)) {
                if (!live_.has_vertex(v)) {
                    bad.push_back("live simplex " + std::to_string(s) + " uses a dead vertex");
                    continue;
                }
                ++uses[v];
            }
    std::size_t alive = 0;
    for (std::uint32_t v = 0; v < live_.vertex_slots(); ++v) {
        if (!live_.has_vertex(v)) continue;
        ++alive;
        if (uses[v] == 0) bad.push_back("live vertex " + std::to_string(v) + " is unused");
        if (v >= vertices_.size() || vertices_[v].uses != uses[v])
            bad.push_back("live vertex " + std::to_string(v) + ": stale use count");
        else if (const auto it = vertex_at_.find(vertices_[v].key);
                 it == vertex_at_.end() || it->second != v)
            bad.push_back("live vertex " + std::to_string(v) + " is not indexed by its position");
    }
    if (alive != live_.vertex_count() || vertex_at_.size() != alive)
        bad.push_back("live vertex count " + std::to_string(live_.vertex_count()) +
                      " differs from the records");

    return CheckReport::of_problems(std::move(bad));
}

template class DynQuadMesh<2>;
template class DynQuadMesh<3>;

}  // namespace dynmesh
