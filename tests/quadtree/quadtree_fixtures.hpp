#pragma once
/// \file Test fixtures shared by the quadtree test files: random point pools.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/geometry/random.hpp"
#include "dynmesh/quadtree/live_mesh.hpp"
#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh::testing_quadtree {

inline std::string joined(const std::vector<std::string>& v) {
    std::string s;
    for (std::size_t i = 0; i < v.size() && i < 5; ++i) s += v[i] + "\n";
    return s;
}

template <int D>
inline PointD<D> make_point(const std::array<double, 3>& c) {
    PointD<D> p;
    for (int i = 0; i < D; ++i) p[static_cast<std::size_t>(i)] = c[static_cast<std::size_t>(i)];
    return p;
}

/// A pool of distinct (after snapping) points in the middle third: uniform points mixed with
/// clusters of spacing 2^-3 .. 2^-max_exp and (with probability tiny) ~1e-9 of the domain.
/// Deep clusters make big trees (most of all in 3D), so the 3D suites use shallower ones.
template <int D>
inline std::vector<PointD<D>> point_pool(Rng& rng, std::size_t m, int max_exp = 30, double tiny = 0.1) {
    const DynQuadtree<D> probe;
    std::vector<PointD<D>> pool;
    std::set<typename DynQuadtree<D>::GridPoint> seen;
    PointD<D> centre{};
    while (pool.size() < m) {
        std::array<double, 3> c{};
        const double kind = rng.uniform();
        if (kind < 0.4 || pool.empty()) {
            for (auto& v : c) v = rng.uniform(1.0 / 3.0, 2.0 / 3.0);
        } else {
            if (rng.coin(0.3)) centre = pool[rng.below(pool.size())];
            const double scale =
                kind < 1.0 - tiny
                    ? std::ldexp(1.0, -static_cast<int>(
                                          3 + rng.below(static_cast<std::uint64_t>(max_exp - 2))))
                    : 1e-9;
            for (int i = 0; i < D; ++i) {
                const auto ui = static_cast<std::size_t>(i);
                c[ui] = std::clamp(centre[ui] + scale * rng.uniform(-2.0, 2.0), 0.34, 0.66);
            }
        }
        const PointD<D> p = make_point<D>(c);
        if (seen.insert(probe.grid_point(p)).second) {
            pool.push_back(p);
            centre = p;
        }
    }
    return pool;
}

/// Every tree point is a vertex of the mesh at its own coordinates (mesh.input_vertices is in
/// tree.points() order).
template <int D, class Mesh>
void expect_inputs_are_vertices(const DynQuadtree<D>& tree, const Mesh& mesh,
                                const std::string& what) {
    const auto pts = tree.points();
    ASSERT_EQ(mesh.input_vertices.size(), pts.size()) << what;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        ASSERT_LT(mesh.input_vertices[i], mesh.points.size()) << what;
        EXPECT_EQ(mesh.points[mesh.input_vertices[i]], pts[i].second) << what << " point " << i;
    }
}

/// `steps` random updates of `tree`: with probability 0.35 (and points present) an erase of a
/// present point, else an insert of a pool point (duplicates are skipped). After every step,
/// check(present, step) with the current point set.
template <int D, class Check>
void random_walk(DynQuadtree<D>& tree, const std::vector<PointD<D>>& pool, int steps, Rng& rng,
                 Check&& check) {
    std::vector<PointD<D>> present;
    for (int step = 0; step < steps; ++step) {
        if (!present.empty() && rng.coin(0.35)) {
            const std::size_t k = rng.below(present.size());
            ASSERT_EQ(tree.erase(present[k]), EraseResult::Erased);
            present.erase(present.begin() + static_cast<std::ptrdiff_t>(k));
        } else {
            const PointD<D> p = pool[rng.below(pool.size())];
            if (tree.insert(p) == InsertResult::Inserted) present.push_back(p);
        }
        check(present, step);
    }
}

/// A simplex as the coordinates of its vertices, in its vertex order.
template <int D>
using SimplexCoords = std::array<std::array<double, D>, D + 1>;

/// The simplices of a mesh (points + index simplices) as sorted coordinate tuples: two meshes
/// with different numbering hold the same oriented simplices iff these are equal.
template <int D, class Points, class Simplices>
std::vector<SimplexCoords<D>> simplex_coords(const Points& points, const Simplices& simplices) {
    std::vector<SimplexCoords<D>> out;
    for (const auto& s : simplices) {
        SimplexCoords<D> c{};
        for (int i = 0; i <= D; ++i)
            for (int d = 0; d < D; ++d)
                c[static_cast<std::size_t>(i)][static_cast<std::size_t>(d)] =
                    points[s[static_cast<std::size_t>(i)]][static_cast<std::size_t>(d)];
        out.push_back(c);
    }
    std::sort(out.begin(), out.end());
    return out;
}

/// The live simplices of a LiveMesh, as simplex_coords().
template <int D>
std::vector<SimplexCoords<D>> live_coords(const LiveMesh<D>& m) {
    std::vector<PointD<D>> points(m.vertex_slots());
    for (std::uint32_t v = 0; v < m.vertex_slots(); ++v) points[v] = m.point(v);
    std::vector<std::array<std::uint32_t, D + 1>> simplices;
    for (std::uint32_t s = 0; s < m.simplex_slots(); ++s)
        if (m.has_simplex(s)) simplices.push_back(m.simplex(s));
    return simplex_coords<D>(points, simplices);
}

/// A caller's copy of a LiveMesh that is only ever changed by applying MeshDelta's, as a GPU
/// buffer or a solver's arrays would be.
template <int D>
struct MeshMirror {
    std::map<std::uint32_t, PointD<D>> vertices;
    std::map<std::uint32_t, std::array<std::uint32_t, D + 1>> simplices;

    explicit MeshMirror(const LiveMesh<D>& m) {
        for (std::uint32_t v = 0; v < m.vertex_slots(); ++v)
            if (m.has_vertex(v)) vertices[v] = m.point(v);
        for (std::uint32_t s = 0; s < m.simplex_slots(); ++s)
            if (m.has_simplex(s)) simplices[s] = m.simplex(s);
    }
    /// Applies a delta in the documented order; every removed id must exist, every added id
    /// must be free, and every added simplex must use existing vertices.
    void apply(const MeshDelta<D>& d, const std::string& what) {
        for (std::uint32_t s : d.removed_simplices)
            ASSERT_EQ(simplices.erase(s), 1u) << what << ": removed simplex " << s << " unknown";
        for (std::uint32_t v : d.removed_vertices)
            ASSERT_EQ(vertices.erase(v), 1u) << what << ": removed vertex " << v << " unknown";
        for (const auto& a : d.added_vertices)
            ASSERT_TRUE(vertices.emplace(a.id, a.point).second)
                << what << ": added vertex " << a.id << " already there";
        for (const auto& a : d.added_simplices) {
            for (std::uint32_t v : a.vertices)
                ASSERT_TRUE(vertices.contains(v)) << what << ": simplex uses missing vertex " << v;
            ASSERT_TRUE(simplices.emplace(a.id, a.vertices).second)
                << what << ": added simplex " << a.id << " already there";
        }
    }
    /// Slot-for-slot equality with the mesher's LiveMesh (which also shows that no kept
    /// simplex lost a vertex: the LiveMesh's simplices use live vertices only).
    void expect_equals(const LiveMesh<D>& m, const std::string& what) const {
        std::size_t live_vertices = 0, live_simplices = 0;
        for (std::uint32_t v = 0; v < m.vertex_slots(); ++v) {
            if (!m.has_vertex(v)) continue;
            ++live_vertices;
            const auto it = vertices.find(v);
            ASSERT_TRUE(it != vertices.end()) << what << ": mirror misses vertex " << v;
            ASSERT_EQ(it->second, m.point(v)) << what << ": vertex " << v << " moved";
        }
        for (std::uint32_t s = 0; s < m.simplex_slots(); ++s) {
            if (!m.has_simplex(s)) continue;
            ++live_simplices;
            const auto it = simplices.find(s);
            ASSERT_TRUE(it != simplices.end()) << what << ": mirror misses simplex " << s;
            ASSERT_EQ(it->second, m.simplex(s)) << what << ": simplex " << s << " changed";
        }
        ASSERT_EQ(vertices.size(), live_vertices) << what;
        ASSERT_EQ(simplices.size(), live_simplices) << what;
        ASSERT_EQ(m.vertex_count(), live_vertices) << what;
        ASSERT_EQ(m.simplex_count(), live_simplices) << what;
    }
};

/// Uniform points at a fixed density: n points in the square (cube) of side
/// side0·(n / n0)^(1/D) centred at 0.5, so the local configuration around the centre has the
/// same distribution for every n; and `queries` more in the central part of side side0 / 2.
template <int D>
void fixed_density_points(std::size_t n, std::size_t n0, double side0, std::size_t queries,
                          std::uint64_t seed, std::vector<PointD<D>>& points,
                          std::vector<PointD<D>>& query_points) {
    Rng rng(seed), qrng(seed + 1);  // the queries are the same for every n
    const double side =
        side0 * std::pow(static_cast<double>(n) / static_cast<double>(n0), 1.0 / D);
    const auto draw = [](Rng& r, double s) {
        PointD<D> p;
        for (int d = 0; d < D; ++d) p[static_cast<std::size_t>(d)] = 0.5 + s * r.uniform(-0.5, 0.5);
        return p;
    };
    points.clear();
    query_points.clear();
    for (std::size_t i = 0; i < n; ++i) points.push_back(draw(rng, side));
    for (std::size_t i = 0; i < queries; ++i) query_points.push_back(draw(qrng, side0 / 2));
}

/// The mean of work(engine) over the updates of inserting each query point and erasing it
/// again (points the engine refuses are skipped); at least `min_updates` updates must happen.
template <class Engine, class Points, class Work>
double mean_update_work(Engine& engine, const Points& queries, Work&& work,
                        std::size_t min_updates) {
    double total = 0;
    std::size_t updates = 0;
    for (const auto& q : queries) {
        if (engine.insert(q) != InsertResult::Inserted) continue;
        total += work(engine);
        EXPECT_EQ(engine.erase(q), EraseResult::Erased);
        total += work(engine);
        updates += 2;
    }
    EXPECT_GE(updates, min_updates);
    return total / static_cast<double>(std::max<std::size_t>(updates, 1));
}

}  // namespace dynmesh::testing_quadtree
