#include "dynmesh/reconstruct/restricted_delaunay.hpp"

#include <algorithm>
#include <chrono>
#include <utility>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "dynmesh/error.hpp"
#include "dynmesh/mesh/check.hpp"
#include "samples_common.hpp"

namespace dynmesh {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K>;  // sample index
using Cb = CGAL::Triangulation_cell_base_with_info_3<std::uint32_t, K,     // Voronoi vertex index
                                                     CGAL::Delaunay_triangulation_cell_base_3<K>>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, Tds>;
using detail::IndexTriangle;

Point3 to_point(const K::Point_3& p) { return {p.x(), p.y(), p.z()}; }

/// A point on a dual Voronoi edge with its signed distance to the surface.
struct Probe {
    Point3 p;
    double d;
};

/// Finds the restricted facets of one point set.
class RestrictedFacetFinder {
public:
    RestrictedFacetFinder(std::span<const Point3> samples, const ImplicitSurface& surface,
                          const RestrictedDelaunayOptions& options)
        : samples_(samples), surface_(surface), max_evaluations_(options.max_evaluations_per_edge) {
        const Bbox3 b = surface.bbox();
        box_center_ = 0.5 * (b.min + b.max);
        box_diagonal_ = b.diagonal();
    }

    /// The restricted facets (input indices, oriented outward) of the Delaunay triangulation
    /// of the samples, in a canonical order: each triangle starts at its smallest index and
    /// the list is sorted, so the result does not depend on CGAL's traversal order.
    std::vector<IndexTriangle> run(std::size_t& n_cells) const {
        std::vector<std::pair<K::Point_3, std::uint32_t>> points;
        points.reserve(samples_.size());
        for (std::size_t i = 0; i < samples_.size(); ++i) {
            const Point3& p = samples_[i];
            points.emplace_back(K::Point_3(p.x, p.y, p.z), static_cast<std::uint32_t>(i));
        }
        Delaunay dt(points.begin(), points.end());
        if (dt.dimension() < 3)
            throw InvalidInput(
                "restricted_delaunay: the samples are coplanar (the Delaunay "
                "triangulation has dimension " +
                std::to_string(dt.dimension()) + ")");
        n_cells = dt.number_of_finite_cells();

        // Voronoi vertices (circumcentres of the finite cells) with their signed distances;
        // each is shared by the four dual edges of its cell's facets.
        std::vector<Probe> voronoi;
        voronoi.reserve(n_cells);
        const auto circumcenter = dt.geom_traits().construct_circumcenter_3_object();
        for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
            c->info() = static_cast<std::uint32_t>(voronoi.size());
            const Point3 p = to_point(circumcenter(c->vertex(0)->point(), c->vertex(1)->point(),
                                                   c->vertex(2)->point(), c->vertex(3)->point()));
            voronoi.push_back({p, surface_.signed_distance(p)});
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
            const Point3 &pa = samples_[t[0]], &pb = samples_[t[1]], &pc = samples_[t[2]];
            // The dual Voronoi edge joins the circumcentres of the two cells; for a facet of
            // the convex hull it is a ray from the finite cell's circumcentre along the outward
            // facet normal, cut where it is surely past the surface's bounding box.
            const Probe& from = voronoi[cell->info()];
            Probe to;
            if (dt.is_infinite(other)) {
                Vec3 n = normalized(cross(pb - pa, pc - pa));
                if (dot(n, samples_[cell->vertex(i)->info()] - pa) > 0) n = -n;
                to.p = from.p + (distance(from.p, box_center_) + box_diagonal_) * n;
                to.d = surface_.signed_distance(to.p);
            } else {
                to = voronoi[other->info()];
            }
            if (!meets_surface(from, to)) continue;
            const Point3 centroid = (pa + pb + pc) / 3.0;
            if (dot(cross(pb - pa, pc - pa), surface_.normal(centroid)) < 0) std::swap(t[1], t[2]);
            std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
            kept.push_back(t);
        }
        std::sort(kept.begin(), kept.end());
        return kept;
    }

private:
    /// True when segment ab meets the surface. The signed distance is 1-Lipschitz, so a
    /// piece whose end distances have one sign and sum to more than its length cannot meet
    /// the surface; other pieces are halved until decided (at most max_evaluations_
    /// evaluations; an undecided edge grazes the surface and counts as not meeting it).
    [[nodiscard]] bool meets_surface(const Probe& a, const Probe& b) const {
        std::size_t budget = max_evaluations_;
        return meets_surface(a, b, budget, 0);
    }
    [[nodiscard]] bool meets_surface(const Probe& a, const Probe& b, std::size_t& budget,
                                     int depth) const {
        if ((a.d < 0) != (b.d < 0)) return true;
        if (std::abs(a.d) + std::abs(b.d) > distance(a.p, b.p)) return false;
        if (budget == 0 || depth == 60) return false;
        --budget;
        const Point3 m = 0.5 * (a.p + b.p);
        const Probe mid{m, surface_.signed_distance(m)};
        return meets_surface(a, mid, budget, depth + 1) || meets_surface(mid, b, budget, depth + 1);
    }

    std::span<const Point3> samples_;
    const ImplicitSurface& surface_;
    std::size_t max_evaluations_;
    Point3 box_center_;
    double box_diagonal_ = 0;
};

}  // namespace

RestrictedDelaunayResult restricted_delaunay_with_report(std::span<const Point3> samples,
                                                         const ImplicitSurface& surface,
                                                         const RestrictedDelaunayOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const std::string who = "restricted_delaunay";
    detail::check_samples(samples, who);

    RestrictedDelaunayResult result;
    RestrictedDelaunayReport& report = result.report;
    report.samples = samples.size();

    const RestrictedFacetFinder finder(samples, surface, options);
    const std::vector<IndexTriangle> facets = finder.run(report.delaunay_cells);
    const auto defects = detail::find_manifold_defects(facets, samples.size());
    if (facets.empty() || !defects.ok()) {
        throw InvalidInput(who + ": the restricted Delaunay triangulation is not a 2-manifold: " +
                           (facets.empty() ? std::string("no Delaunay facet meets the surface")
                                           : defects.describe()) +
                           "; the sample is too sparse for this surface");
    }

    auto compact = detail::compact_soup(samples, facets);
    result.mesh = SurfaceMesh::from_soup(compact.soup);
    const auto check = check_mesh(result.mesh, {.require_closed = true});
    if (!check.ok())
        throw InvalidInput(who +
                           ": the restricted Delaunay triangulation is not a closed "
                           "2-manifold; the sample is too sparse for this surface:\n" +
                           check.summary("  "));
    report.vertices_used = compact.vertex_sample.size();
    report.unused_samples = samples.size() - report.vertices_used;
    report.facets = facets.size();
    report.vertex_sample = std::move(compact.vertex_sample);
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

SurfaceMesh restricted_delaunay(std::span<const Point3> samples, const ImplicitSurface& surface,
                                const RestrictedDelaunayOptions& options) {
    return restricted_delaunay_with_report(samples, surface, options).mesh;
}

SurfaceMesh sample_and_mesh(const ImplicitSurface& surface, std::size_t n, std::uint64_t seed) {
    const std::vector<Point3> samples = surface.sample_uniform(n, seed);
    return restricted_delaunay(samples, surface);
}

}  // namespace dynmesh
