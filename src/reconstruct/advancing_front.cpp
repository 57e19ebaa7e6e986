#include "dynmesh/reconstruct/advancing_front.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <utility>

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_3.h>

#include "dynmesh/error.hpp"
#include "dynmesh/mesh/check.hpp"
#include "samples_common.hpp"

namespace dynmesh {
namespace {

// The same types as CGAL::advancing_front_surface_reconstruction(); building the triangulation
// here lets us reject coplanar input before CGAL would print "not 3D" and return nothing.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Advancing_front_surface_reconstruction_vertex_base_3<K>;
using Cb = CGAL::Advancing_front_surface_reconstruction_cell_base_3<K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, Tds>;
using Reconstruction = CGAL::Advancing_front_surface_reconstruction<Delaunay>;
using detail::IndexTriangle;

}  // namespace

AdvancingFrontResult reconstruct_advancing_front_with_report(std::span<const Point3> samples,
                                                             const AdvancingFrontOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const std::string who = "reconstruct_advancing_front";
    detail::check_samples(samples, who);
    if (!(options.radius_ratio_bound > 0) || !std::isfinite(options.radius_ratio_bound))
        throw InvalidInput(who + ": radius_ratio_bound must be positive and finite");
    if (!(options.beta_rad > 0 && options.beta_rad < 3.14159265358979))
        throw InvalidInput(who + ": beta_rad must be in (0, pi)");

    std::vector<std::pair<K::Point_3, std::size_t>> points;
    points.reserve(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i)
        points.emplace_back(K::Point_3(samples[i].x, samples[i].y, samples[i].z), i);
    Delaunay dt(points.begin(), points.end());
    if (dt.dimension() < 3)
        throw InvalidInput(who +
                           ": the samples are coplanar (the Delaunay triangulation has "
                           "dimension " +
                           std::to_string(dt.dimension()) + ")");

    Reconstruction reconstruction(dt);
    reconstruction.run(options.radius_ratio_bound, options.beta_rad);
    std::vector<std::array<std::size_t, 3>> raw;
    CGAL::write_triple_indices(std::back_inserter(raw), reconstruction);
    if (raw.empty()) throw InvalidInput(who + ": the reconstruction is empty");

    std::vector<IndexTriangle> triangles;
    triangles.reserve(raw.size());
    for (const auto& t : raw) {
        IndexTriangle tri{static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                          static_cast<std::uint32_t>(t[2])};
        std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
        triangles.push_back(tri);
    }
    std::sort(triangles.begin(), triangles.end());  // canonical order
    const auto defects = detail::find_manifold_defects(triangles, samples.size());
    if (defects.overused_edges + defects.misoriented_edges + defects.pinched_vertices > 0)
        throw InvalidInput(who + ": the reconstruction is not a 2-manifold: " + defects.describe());
    if (options.require_closed && defects.boundary_edges > 0)
        throw InvalidInput(
            who + ": the reconstruction is not closed: " + std::to_string(defects.boundary_edges) +
            " boundary edges among " + std::to_string(defects.edges) + " edges, " +
            std::to_string(triangles.size()) +
            " triangles (set require_closed "
            "= false to accept open surfaces)");

    AdvancingFrontResult result;
    AdvancingFrontReport& report = result.report;
    auto compact = detail::compact_soup(samples, triangles);
    report.closed = defects.boundary_edges == 0;
    if (report.closed && detail::signed_volume(compact.soup) < 0) {
        for (auto& t : compact.soup.triangles) std::swap(t[1], t[2]);
        report.flipped = true;
    }
    result.mesh = SurfaceMesh::from_soup(compact.soup);
    report.samples = samples.size();
    report.vertices_used = compact.vertex_sample.size();
    report.unused_samples = samples.size() - report.vertices_used;
    report.facets = triangles.size();
    report.boundary_edges = defects.boundary_edges;
    report.vertex_sample = std::move(compact.vertex_sample);
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

SurfaceMesh reconstruct_advancing_front(std::span<const Point3> samples,
                                        const AdvancingFrontOptions& options) {
    return reconstruct_advancing_front_with_report(samples, options).mesh;
}

}  // namespace dynmesh
