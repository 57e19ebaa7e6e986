#include "dynmesh/reconstruct/restricted_delaunay.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "dynmesh/error.hpp"
#include "dynmesh/mesh/check.hpp"
#include "restricted_facets.hpp"
#include "samples_common.hpp"

namespace dynmesh {
namespace {

using detail::DualProbe;
using detail::IndexTriangle;

/// The restricted_facets() oracle of an implicit surface: a dual edge meets the surface when
/// the 1-Lipschitz signed distance proves a crossing on it (see restricted_delaunay()).
class ImplicitOracle {
public:
    ImplicitOracle(std::span<const Point3> samples, const ImplicitSurface& surface,
                   const RestrictedDelaunayOptions& options)
        : samples_(samples), surface_(surface), max_evaluations_(options.max_evaluations_per_edge) {}

    [[nodiscard]] Bbox3 bbox() const { return surface_.bbox(); }
    [[nodiscard]] double value(const Point3& p) const { return surface_.signed_distance(p); }
    bool keep(const DualProbe& from, const DualProbe& to, IndexTriangle& t) const {
        std::size_t budget = max_evaluations_;
        if (!meets_surface(from, to, budget, 0)) return false;
        const Point3 &pa = samples_[t[0]], &pb = samples_[t[1]], &pc = samples_[t[2]];
        const Point3 centroid = (pa + pb + pc) / 3.0;
        if (dot(cross(pb - pa, pc - pa), surface_.normal(centroid)) < 0) std::swap(t[1], t[2]);
        return true;
    }

private:
    /// True when segment ab meets the surface. The signed distance is 1-Lipschitz, so a
    /// piece whose end distances have one sign and sum to more than its length cannot meet
    /// the surface; other pieces are halved until decided (at most max_evaluations_
    /// evaluations; an undecided edge grazes the surface and counts as not meeting it).
    [[nodiscard]] bool meets_surface(const DualProbe& a, const DualProbe& b, std::size_t& budget,
                                     int depth) const {
        if ((a.d < 0) != (b.d < 0)) return true;
        if (std::abs(a.d) + std::abs(b.d) > distance(a.p, b.p)) return false;
        if (budget == 0 || depth == 60) return false;
        --budget;
        const Point3 m = 0.5 * (a.p + b.p);
        const DualProbe mid{m, surface_.signed_distance(m)};
        return meets_surface(a, mid, budget, depth + 1) || meets_surface(mid, b, budget, depth + 1);
    }

    std::span<const Point3> samples_;
    const ImplicitSurface& surface_;
    std::size_t max_evaluations_;
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

    ImplicitOracle oracle(samples, surface, options);
    const std::vector<IndexTriangle> facets =
        detail::restricted_facets(samples, oracle, report.delaunay_cells, who);
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
