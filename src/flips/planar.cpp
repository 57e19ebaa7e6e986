#include "dynmesh/flips/planar.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <set>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/geometry/random.hpp"

namespace dynmesh {

SurfaceMesh jittered_grid_triangulation(std::size_t n, double jitter, std::uint64_t seed) {
    DYNMESH_CHECK(n >= 1, "jittered_grid_triangulation: n must be at least 1");
    DYNMESH_CHECK(jitter >= 0 && jitter < 0.5, "jittered_grid_triangulation: jitter must lie in [0, 0.5)");
    Rng rng(seed);
    TriangleSoup s;
    const double h = 1.0 / double(n);
    for (std::size_t j = 0; j <= n; ++j)
        for (std::size_t i = 0; i <= n; ++i) {
            double x = double(i) * h, y = double(j) * h;
            if (i > 0 && i < n) x += rng.uniform(-jitter, jitter) * h;
            if (j > 0 && j < n) y += rng.uniform(-jitter, jitter) * h;
            s.points.push_back({x, y, 0.0});
        }
    auto id = [n](std::size_t i, std::size_t j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < n; ++i) {
            const auto a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if (rng.coin()) {
                s.triangles.push_back({a, b, c});
                s.triangles.push_back({a, c, d});
            } else {
                s.triangles.push_back({a, b, d});
                s.triangles.push_back({b, c, d});
            }
        }
    return SurfaceMesh::from_soup(s);
}

DelaunayComparison compare_with_cgal_delaunay_2(const SurfaceMesh& m) {
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
    using Tds = CGAL::Triangulation_data_structure_2<Vb>;
    using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
    std::vector<std::pair<K::Point_2, std::uint32_t>> pts;
    for (Vertex v : m.vertices()) pts.emplace_back(K::Point_2(m.position(v).x, m.position(v).y), v.idx());
    DT dt(pts.begin(), pts.end());
    std::set<std::pair<std::uint32_t, std::uint32_t>> ours, theirs;
    for (Edge e : m.edges()) {
        const auto a = m.vertex(e, 0).idx(), b = m.vertex(e, 1).idx();
        ours.emplace(std::min(a, b), std::max(a, b));
    }
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
        const auto a = e->first->vertex(DT::cw(e->second))->info();
        const auto b = e->first->vertex(DT::ccw(e->second))->info();
        theirs.emplace(std::min(a, b), std::max(a, b));
    }
    DelaunayComparison c;
    c.edges_here = ours.size();
    c.edges_delaunay = theirs.size();
    for (const auto& e : ours) c.only_here += theirs.count(e) == 0;
    for (const auto& e : theirs) c.only_delaunay += ours.count(e) == 0;
    return c;
}

std::size_t count_non_locally_delaunay(const SurfaceMesh& m) {
    std::size_t n = 0;
    for (Edge e : m.edges())
        if (!m.is_boundary(e)) {
            const EdgeQuad k = edge_quad(m, e);
            n += planar_condition(m.position(k.p), m.position(k.q), m.position(k.r), m.position(k.s));
        }
    return n;
}

}  // namespace dynmesh
