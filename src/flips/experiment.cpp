#include "dynmesh/flips/experiment.hpp"

#include <algorithm>
#include <unordered_set>

namespace dynmesh {

double shared_edge_fraction(const SurfaceMesh& a, const SurfaceMesh& b) {
    auto key = [](Vertex x, Vertex y) {
        const auto lo = std::min(x.idx(), y.idx()), hi = std::max(x.idx(), y.idx());
        return (static_cast<std::uint64_t>(lo) << 32) | hi;
    };
    std::unordered_set<std::uint64_t> ea;
    ea.reserve(a.n_edges());
    for (Edge e : a.edges()) ea.insert(key(a.vertex(e, 0), a.vertex(e, 1)));
    std::size_t shared = 0;
    for (Edge e : b.edges()) shared += ea.count(key(b.vertex(e, 0), b.vertex(e, 1)));
    return b.n_edges() ? double(shared) / double(b.n_edges()) : 1.0;
}

SmoothingExperimentResult run_smoothing_experiment(const SurfaceMesh& mesh,
                                                   const SmoothingExperimentOptions& opt,
                                                   SurfaceMesh* worsened_out,
                                                   SurfaceMesh* smoothed_out) {
    QualityOptions q;
    q.surface = opt.surface;
    q.histogram_bins = opt.histogram_bins;
    q.histogram_max_deg = opt.histogram_max_deg;
    SmoothingExperimentResult r;
    r.initial = mesh_quality(mesh, q);
    SurfaceMesh m = mesh;
    r.worsen = worsen(m, opt.worsen);
    r.worsened = mesh_quality(m, q);
    if (worsened_out) *worsened_out = m;
    r.flip = flip_all(m, opt.flip);
    r.smoothed = mesh_quality(m, q);
    r.shared_edge_fraction = shared_edge_fraction(mesh, m);
    if (smoothed_out) *smoothed_out = std::move(m);
    return r;
}

}  // namespace dynmesh
