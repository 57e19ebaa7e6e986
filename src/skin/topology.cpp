#include "dynmesh/skin/topology.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <utility>

#include <CGAL/Alpha_shape_3.h>
#include <CGAL/Alpha_shape_cell_base_3.h>
#include <CGAL/Alpha_shape_vertex_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>

#include "dynmesh/error.hpp"

namespace dynmesh {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using RVb = CGAL::Regular_triangulation_vertex_base_3<K>;
using Vb = CGAL::Alpha_shape_vertex_base_3<K, RVb>;
using RCb = CGAL::Regular_triangulation_cell_base_3<K>;
using Cb = CGAL::Alpha_shape_cell_base_3<K, RCb>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using RT = CGAL::Regular_triangulation_3<K, Tds>;
using AlphaShape = CGAL::Alpha_shape_3<RT>;

struct UnionFind {
    std::vector<std::size_t> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t(0)); }
    std::size_t find(std::size_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    bool join(std::size_t a, std::size_t b) {
        a = find(a);
        b = find(b);
        if (a == b) return false;
        parent[a] = b;
        return true;
    }
};

}  // namespace

SkinTopology skin_topology(const std::vector<WeightedPoint>& balls, double t) {
    DYNMESH_CHECK(!balls.empty(), "skin_topology: no ball");
    std::vector<K::Weighted_point_3> points;
    points.reserve(balls.size());
    for (const WeightedPoint& b : balls) {
        DYNMESH_CHECK(is_finite(b.center) && std::isfinite(b.weight), "skin_topology: a centre or a weight is not finite");
        points.emplace_back(K::Point_3(b.center.x, b.center.y, b.center.z), b.weight);
    }
    // Six far points that are never in the complex (weight + t < 0, far beyond every ball)
    // make any input (one ball, collinear or coplanar centres) a 3D triangulation without
    // changing the simplices among the balls or their alpha values.
    Point3 lo = balls[0].center, hi = lo;
    double w_max = 0;
    for (const WeightedPoint& b : balls) {
        lo = {std::min(lo.x, b.center.x), std::min(lo.y, b.center.y), std::min(lo.z, b.center.z)};
        hi = {std::max(hi.x, b.center.x), std::max(hi.y, b.center.y), std::max(hi.z, b.center.z)};
        w_max = std::max(w_max, b.weight);
    }
    const double far_weight = -std::fabs(t) - 1;
    const double D = 2 * norm(hi - lo) + 4 * std::sqrt(std::max(0.0, w_max + t)) + 10;
    const Point3 mid = lo + 0.5 * (hi - lo);
    std::vector<K::Point_3> far;
    for (int k = 0; k < 3; ++k)
        for (double sign : {-1.0, 1.0}) {
            Vec3 e{0, 0, 0};
            (k == 0 ? e.x : k == 1 ? e.y : e.z) = sign * D;
            const Point3 p = mid + e;
            far.emplace_back(p.x, p.y, p.z);
            points.emplace_back(far.back(), far_weight);
        }
    AlphaShape as(points.begin(), points.end(), t, AlphaShape::GENERAL);
    DYNMESH_CHECK(as.dimension() == 3, "skin_topology: the triangulation is not 3-dimensional");
    const auto in = [&](auto classification) { return classification != AlphaShape::EXTERIOR; };

    SkinTopology topo;
    long long V = 0, E = 0, F = 0, T = 0;
    std::unordered_map<AlphaShape::Vertex_handle, std::size_t> vindex;
    for (auto v = as.finite_vertices_begin(); v != as.finite_vertices_end(); ++v)
        if (in(as.classify(v))) vindex.emplace(v, std::size_t(V++));
    UnionFind vertices{std::size_t(V)};
    long long merged = 0;
    for (auto e = as.finite_edges_begin(); e != as.finite_edges_end(); ++e) {
        if (!in(as.classify(*e))) continue;
        ++E;
        const auto a = e->first->vertex(e->second), b = e->first->vertex(e->third);
        if (vertices.join(vindex.at(a), vindex.at(b))) ++merged;
    }
    topo.b0 = V - merged;

    // Cells outside the complex, the unbounded part (every infinite cell) as one.
    std::unordered_map<AlphaShape::Cell_handle, std::size_t> cindex;
    std::size_t outside = 1;  // index 0: the unbounded part
    for (auto c = as.all_cells_begin(); c != as.all_cells_end(); ++c) {
        if (as.is_infinite(c)) {
            cindex.emplace(c, 0);
        } else if (in(as.classify(c))) {
            ++T;
        } else {
            cindex.emplace(c, outside++);
        }
    }
    UnionFind cells{outside};
    long long joined = 0;
    for (auto f = as.all_facets_begin(); f != as.all_facets_end(); ++f) {
        const auto c = f->first, n = c->neighbor(f->second);
        if (!as.is_infinite(*f) && in(as.classify(*f))) {
            ++F;
            continue;
        }
        const auto ic = cindex.find(c), in_ = cindex.find(n);
        if (ic != cindex.end() && in_ != cindex.end() && cells.join(ic->second, in_->second)) ++joined;
    }
    topo.b2 = (long long)(outside) - joined - 1;
    topo.b1 = topo.b0 + topo.b2 - (V - E + F - T);
    return topo;
}

}  // namespace dynmesh
