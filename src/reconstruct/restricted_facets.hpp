#pragma once
/// \file Private: the restricted facets of a point set's Delaunay triangulation, for any way
/// of deciding whether a dual Voronoi edge meets the surface (an implicit surface's signed
/// distance, or segment queries against a triangle mesh).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "samples_common.hpp"

namespace dynmesh::detail {

using RdtKernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// A point of a dual Voronoi edge with the oracle's value there (signed distance, or unused).
struct DualProbe {
    Point3 p;
    double d = 0;
};

/// The restricted facets of the Delaunay triangulation of `samples` (indices into samples,
/// oriented outward), in a canonical order: each triangle starts at its smallest index and the
/// list is sorted, so the result does not depend on CGAL's traversal order.
///
/// The Oracle provides
///   Bbox3 bbox() const                   -- a box holding the surface;
///   double value(const Point3&) const    -- stored with every Voronoi vertex (shared by the
///                                           four dual edges of its cell);
///   bool keep(const DualProbe& from, const DualProbe& to, IndexTriangle& t) -- whether the
///        dual edge from-to of facet t meets the surface; when it does, the oracle orients t
///        outward (swapping t[1] and t[2] if needed).
/// The dual edge of a convex-hull facet is the outward ray from the finite cell's
/// circumcentre, cut where it is surely past the oracle's box.
/// \throw InvalidInput when the samples are coplanar.
template <class Oracle>
std::vector<IndexTriangle> restricted_facets(std::span<const Point3> samples, Oracle& oracle,
                                             std::size_t& n_cells, const std::string& who) {
    using K = RdtKernel;
    using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K>;  // sample index
    using Cb = CGAL::Triangulation_cell_base_with_info_3<std::uint32_t, K,     // Voronoi vertex
                                                         CGAL::Delaunay_triangulation_cell_base_3<K>>;
    using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
    using Delaunay = CGAL::Delaunay_triangulation_3<K, Tds>;

    const Bbox3 box = oracle.bbox();
    const Point3 box_center = 0.5 * (box.min + box.max);
    const double box_diagonal = box.diagonal();

    std::vector<std::pair<K::Point_3, std::uint32_t>> points;
    points.reserve(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const Point3& p = samples[i];
        points.emplace_back(K::Point_3(p.x, p.y, p.z), static_cast<std::uint32_t>(i));
    }
    Delaunay dt(points.begin(), points.end());
    if (dt.dimension() < 3)
        throw InvalidInput(who + ": the samples are coplanar (the Delaunay triangulation has dimension " +
                           std::to_string(dt.dimension()) + ")");
    n_cells = dt.number_of_finite_cells();

    std::vector<DualProbe> voronoi;
    voronoi.reserve(n_cells);
    const auto circumcenter = dt.geom_traits().construct_circumcenter_3_object();
    for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
        c->info() = static_cast<std::uint32_t>(voronoi.size());
        const auto q = circumcenter(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                                    c->vertex(3)->point());
        const Point3 p{q.x(), q.y(), q.z()};
        voronoi.push_back({p, oracle.value(p)});
    }

    std::vector<IndexTriangle> kept;
    for (auto fit = dt.finite_facets_begin(); fit != dt.finite_facets_end(); ++fit) {
        auto cell = fit->first;
        int i = fit->second;
        if (dt.is_infinite(cell)) {  // look from the finite side
            const auto mirror = cell->neighbor(i);
            i = mirror->index(cell);
            cell = mirror;
        }
        const auto other = cell->neighbor(i);
        IndexTriangle t{cell->vertex((i + 1) & 3)->info(), cell->vertex((i + 2) & 3)->info(),
                        cell->vertex((i + 3) & 3)->info()};
        const DualProbe& from = voronoi[cell->info()];
        DualProbe to;
        if (dt.is_infinite(other)) {
            const Point3 &pa = samples[t[0]], &pb = samples[t[1]], &pc = samples[t[2]];
            Vec3 n = normalized(cross(pb - pa, pc - pa));
            if (dot(n, samples[cell->vertex(i)->info()] - pa) > 0) n = -n;
            to.p = from.p + (distance(from.p, box_center) + box_diagonal) * n;
            to.d = oracle.value(to.p);
        } else {
            to = voronoi[other->info()];
        }
        if (!oracle.keep(from, to, t)) continue;
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        kept.push_back(t);
    }
    std::sort(kept.begin(), kept.end());
    return kept;
}

}  // namespace dynmesh::detail
