/// The costs of meshing by probing against the paper's bounds (specs/probing.md §5.3, §5.4),
/// on a sweep of ε over a decade (8 values, ε_k = ε_0 · 10^(−k/7)) for the sphere, the
/// ellipsoid (1, 0.8, 0.6), the torus (1, 0.35) and the genus-2 surface, from about 1K to
/// about 100K output vertices. ε_0 is chosen per surface for about 1K vertices; values with
/// ε ≥ 0.091·ε_S are outside the theorem's range and marked `guaranteed = 0` (the costs are
/// measured all the same).
///
/// Per run: N (output vertices), probes, cells created, retained nodes, detection and
/// positioning edges, path lengths, Hausdorff distance with its bound, wall time. The summary
/// prints probes/N, cells/(N log N), time per vertex and the exponents fitted on log–log axes
/// (probes ~ N^a, cells ~ N^b, displacement ~ N^c, time ~ N^d). With DYNMESH_SWEEP_CSV=FILE the
/// table is written as CSV for scripts/plot_probe_sweep.py. An ablation reruns the torus and the
/// genus-2 surface at three ε with positioning via ∂Ω (ProbingPositioning::Boundary).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "dynmesh/probing/check.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "dynmesh/probing/refine.hpp"
#include "recording_reporter.hpp"

namespace {

using namespace dynmesh;
using Clock = std::chrono::steady_clock;

struct Surface {
    const char* name;
    const char* spec;
    double eps0;
};

const std::vector<Surface>& surfaces() {
    static const std::vector<Surface> s = {
        {"sphere", "sphere:1", 0.09},
        {"ellipsoid", "ellipsoid:1,0.8,0.6", 0.074},
        {"torus", "torus:1,0.35", 0.096},
        {"genus2", "genus2", 0.12},
    };
    return s;
}
constexpr int kSteps = 8;  // ε_0 · 10^(−k/7), k = 0..7: a decade

const ProbeSetup& setup(std::size_t s) {
    static std::vector<std::unique_ptr<ProbeSetup>> cache(surfaces().size());
    if (!cache[s]) cache[s] = std::make_unique<ProbeSetup>(make_probe_object(surfaces()[s].spec));
    return *cache[s];
}

double eps_of(std::size_t s, int k) { return surfaces()[s].eps0 * std::pow(10.0, -k / 7.0); }

struct Row {
    std::string surface;
    double eps = 0;
    bool guaranteed = false;
    ProbingReport report;
    double hausdorff = 0, bound = 0, seconds = 0;
};
std::vector<Row>& rows() {
    static std::vector<Row> r;
    return r;
}

ProbingOptions sweep_options(const ProbeSetup& set, double eps) {
    ProbingOptions o;
    o.eps = eps;
    o.eps_S = set.object->reach();
    o.allow_unguaranteed = true;
    o.omega = set.omega;
    o.interior_points = set.interior_points;
    o.check_every = SIZE_MAX;
    return o;
}

ProbingResult timed_probe(const ProbeObject& object, const ProbingOptions& o, double& seconds) {
    const auto t0 = Clock::now();
    ProbingResult r = probe_surface(object, o);
    seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return r;
}

void BM_Sweep(benchmark::State& state) {
    const std::size_t s = static_cast<std::size_t>(state.range(0)) / kSteps;
    const int k = static_cast<int>(state.range(0) % kSteps);
    const ProbeSetup& set = setup(s);
    const ProbingOptions o = sweep_options(set, eps_of(s, k));
    ProbingResult r;
    double seconds = 0;
    for (auto _ : state) r = timed_probe(*set.object, o, seconds);
    const CheckReport c = check_probing(r, *set.object, o, 3);
    if (!c.flag("closed_manifold") || c.integer("euler") != set.object->euler_characteristic())
        state.SkipWithError("the output does not have the object's topology");
    Row row{surfaces()[s].name, o.eps, o.eps < 0.091 * o.eps_S, r.report, c.figure("hausdorff"), c.figure("hausdorff_bound"), seconds};
    rows().push_back(row);
    const double n = double(r.report.vertices);
    state.counters["N"] = n;
    state.counters["probes_per_N"] = double(r.report.probes) / n;
    state.counters["cells_per_NlogN"] = double(r.report.cells_created) / (n * std::log(n));
    state.counters["us_per_vertex"] = 1e6 * seconds / n;
}
BENCHMARK(BM_Sweep)->DenseRange(0, 4 * kSteps - 1)->Iterations(1)->Unit(benchmark::kSecond);

/// Ablation (spec §5.4): the same runs of the torus and the genus-2 surface at ε_0, ε_3, ε_6
/// with positioning via ∂Ω instead of through lowest common ancestors.
struct AblationRow {
    std::string surface;
    double eps = 0;
    ProbingReport report;
    double seconds = 0;
};
std::vector<AblationRow>& ablation() {
    static std::vector<AblationRow> r;
    return r;
}
void BM_BoundaryPositioning(benchmark::State& state) {
    const std::size_t s = 2 + static_cast<std::size_t>(state.range(0)) / 3;
    const int k = 3 * static_cast<int>(state.range(0) % 3);
    const ProbeSetup& set = setup(s);
    ProbingOptions o = sweep_options(set, eps_of(s, k));
    o.positioning = ProbingPositioning::Boundary;
    ProbingResult r;
    double seconds = 0;
    for (auto _ : state) r = timed_probe(*set.object, o, seconds);
    ablation().push_back({surfaces()[s].name, o.eps, r.report, seconds});
    state.counters["N"] = double(r.report.vertices);
}
BENCHMARK(BM_BoundaryPositioning)->DenseRange(0, 5)->Iterations(1)->Unit(benchmark::kSecond);

/// Least-squares slope of log y against log x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double n = double(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double a = std::log(x[i]), b = std::log(y[i]);
        sx += a, sy += b, sxx += a * a, sxy += a * b;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

void summary(const bench::RecordingReporter&) {
    std::printf("\nMeshing by probing, sweep of eps (one run; no safety monitor)\n");
    std::printf("%-10s %9s %3s %8s %9s %8s %11s %9s %9s %11s %10s %9s %9s %8s\n", "surface", "eps", "g", "N", "probes",
                "probes/N", "cells/NlogN", "retained", "detect", "position", "hausdorff", "bound", "us/vertex",
                "us/cell");
    for (const Row& r : rows()) {
        const double n = double(r.report.vertices);
        std::printf("%-10s %9.5f %3d %8.0f %9zu %8.2f %11.3f %9zu %9zu %11zu %10.2e %9.2e %9.1f %8.2f\n",
                    r.surface.c_str(), r.eps, r.guaranteed, n, r.report.probes, double(r.report.probes) / n,
                    double(r.report.cells_created) / (n * std::log(n)), r.report.nodes_retained,
                    r.report.detection_edges, r.report.positioning_edges, r.hausdorff, r.bound, 1e6 * r.seconds / n,
                    1e6 * r.seconds / double(r.report.cells_created));
    }
    std::printf("\nFitted exponents on log-log axes (y ~ N^a), per surface\n");
    std::printf("%-10s %8s %8s %10s %12s %10s %8s %12s\n", "surface", "probes", "cells", "detection", "positioning",
                "path_len", "time", "H vs eps");
    std::map<std::string, std::vector<const Row*>> by;
    for (const Row& r : rows()) by[r.surface].push_back(&r);
    for (const auto& [name, rs] : by) {
        std::vector<double> n, probes, cells, det, pos, len, t, eps, h;
        for (const Row* r : rs) {
            n.push_back(double(r->report.vertices));
            probes.push_back(double(r->report.probes));
            cells.push_back(double(r->report.cells_created));
            det.push_back(double(std::max<std::size_t>(r->report.detection_edges, 1)));
            pos.push_back(double(std::max<std::size_t>(r->report.positioning_edges, 1)));
            len.push_back(std::max(r->report.path_length, 1e-9));
            t.push_back(r->seconds);
            eps.push_back(r->eps);
            h.push_back(r->hausdorff);
        }
        if (n.size() < 2) continue;
        std::printf("%-10s %8.3f %8.3f %10.3f %12.3f %10.3f %8.3f %12.3f\n", name.c_str(), slope(n, probes),
                    slope(n, cells), slope(n, det), slope(n, pos), slope(n, len), slope(n, t), slope(eps, h));
    }
    std::printf("(N log N has exponent about 1.1 over this range; the paper: probes O(N log N), cells O(N log N), "
                "detection O(N log N), positioning O(N^2 log N), Hausdorff O(eps^2).)\n");
    std::printf("\nPositioning through lowest common ancestors (the sweep's runs) vs via the boundary of Omega\n");
    std::printf("%-10s %9s %8s %14s %14s %12s %12s %10s\n", "surface", "eps", "N", "pos. edges lca", "pos. edges bnd",
                "path lca/bnd", "ext. lca/bnd", "time ratio");
    for (const AblationRow& b : ablation())
        for (const Row& r : rows())
            if (r.surface == b.surface && r.eps == b.eps)
                std::printf("%-10s %9.5f %8zu %14zu %14zu %12.3f %12.3f %10.3f\n", r.surface.c_str(), r.eps,
                            r.report.vertices, r.report.positioning_edges, b.report.positioning_edges,
                            r.report.path_length / b.report.path_length,
                            r.report.exterior_path_length / b.report.exterior_path_length, r.seconds / b.seconds);
    if (const char* csv = std::getenv("DYNMESH_SWEEP_CSV")) {
        std::ofstream out(csv);
        out << "surface,eps,guaranteed,vertices,probes,probes_bootstrap,cells_created,nodes_retained,"
               "detection_edges,positioning_edges,path_length,exterior_path_length,hausdorff,hausdorff_bound,seconds\n";
        out.precision(10);
        for (const Row& r : rows())
            out << r.surface << ',' << r.eps << ',' << int(r.guaranteed) << ',' << r.report.vertices << ','
                << r.report.probes << ',' << r.report.probes_bootstrap << ',' << r.report.cells_created << ','
                << r.report.nodes_retained << ',' << r.report.detection_edges << ',' << r.report.positioning_edges
                << ',' << r.report.path_length << ',' << r.report.exterior_path_length << ',' << r.hausdorff << ','
                << r.bound << ',' << r.seconds << '\n';
        std::printf("wrote %s\n", csv);
    }
}

}  // namespace

int main(int argc, char** argv) { return dynmesh::bench::run_benchmarks(argc, argv, summary); }
