#pragma once
/// \file Test fixtures shared by the quadtree test files: random point pools.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/geometry/random.hpp"
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

}  // namespace dynmesh::testing_quadtree
