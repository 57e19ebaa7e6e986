#pragma once
/// \file Test fixtures shared by the quadtree test files: random point pools.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

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

}  // namespace dynmesh::testing_quadtree
