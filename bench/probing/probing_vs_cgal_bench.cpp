/// Meshing by probing against CGAL's surface mesher and against the omniscient baseline, in one
/// run, at the same ε (specs/probing.md §7): the unit sphere, the torus (1, 0.35) at about 10K
/// and 100K vertices, and a real mesh (blobby.off through the mesh oracle, ε_S 0.1).
///
/// - probe: probe_surface with the moving device (no safety monitor), wall time of the call,
///   which includes building the output soup;
/// - omniscient: the same refinement testing every Voronoi edge created, without moving;
/// - cgal: make_surface_mesh(Non_manifold_tag), criteria (0, ε, ε) on the object's signed
///   distance, wall time of the mesher plus extracting the oriented soup (cgal_baseline.hpp).
/// Every mesh is measured the same way afterwards (not timed): vertices, facets, Euler
/// characteristic, minimum angle, two-sided Hausdorff distance to the object. The summary
/// prints ours / CGAL for vertices and time, probes per vertex against CGAL's oracle queries
/// per vertex, and the device's path.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cgal_baseline.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/metrics/quality.hpp"
#include "dynmesh/probing/check.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "dynmesh/probing/refine.hpp"
#include "recording_reporter.hpp"

namespace {

using namespace dynmesh;
using Clock = std::chrono::steady_clock;

struct Case {
    const char* name;
    std::string spec;
    double eps;
    double eps_S;  ///< 0: the object's reach
};

const std::vector<Case>& cases() {
    static const std::vector<Case> c = {
        {"sphere:1", "sphere:1", 0.045, 0},
        {"torus:1,0.35", "torus:1,0.35", 0.03, 0},
        {"torus (100K)", "torus:1,0.35", 0.0096, 0},
        {"blobby.off", std::string(DYNMESH_SHARED_DATA_DIR) + "/meshes/blobby.off", 0.008, 0.1},
    };
    return c;
}

const ProbeSetup& setup(std::size_t k) {
    static std::vector<std::unique_ptr<ProbeSetup>> cache(cases().size());
    if (!cache[k]) cache[k] = std::make_unique<ProbeSetup>(make_probe_object(cases()[k].spec));
    return *cache[k];
}

/// The measures every method's mesh gets (not timed).
void measure(benchmark::State& state, std::size_t k, const TriangleSoup& mesh, double seconds) {
    const ProbeSetup& s = setup(k);
    const SurfaceMesh m = SurfaceMesh::from_soup(mesh);
    const QualityReport q = mesh_quality(m);
    const double eps = cases()[k].eps;
    state.counters["seconds"] = seconds;
    state.counters["vertices"] = double(m.n_vertices());
    state.counters["facets"] = double(m.n_faces());
    state.counters["euler"] = double(q.euler);
    state.counters["min_angle"] = q.angle_deg.min;
    state.counters["hausdorff"] =
        surface_hausdorff(mesh, *s.object, s.object->sample_surface(default_check_spacing(*s.object, eps, 3)));
}

void run_probe(benchmark::State& state, ProbingMode mode) {
    const std::size_t k = static_cast<std::size_t>(state.range(0));
    const ProbeSetup& s = setup(k);
    ProbingOptions o;
    o.eps = cases()[k].eps;
    o.eps_S = cases()[k].eps_S > 0 ? cases()[k].eps_S : s.object->reach();
    o.omega = s.omega;
    o.interior_points = s.interior_points;
    o.mode = mode;
    if (mode == ProbingMode::Omniscient) o.ground_truth = s.object.get();
    o.check_every = SIZE_MAX;
    ProbingResult r;
    double seconds = 0;
    for (auto _ : state) {
        const auto t0 = Clock::now();
        r = probe_surface(*s.object, o);
        seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    }
    measure(state, k, r.mesh, seconds);
    state.counters["probes"] = double(r.report.probes);
    state.counters["path_length"] = r.report.path_length;
    state.counters["exterior_path_length"] = r.report.exterior_path_length;
    state.counters["edges_travelled"] = double(r.report.voronoi_edges_travelled);
    state.counters["cells"] = double(r.report.cells_created);
}

void BM_Probe(benchmark::State& state) { run_probe(state, ProbingMode::Device); }
void BM_Omniscient(benchmark::State& state) { run_probe(state, ProbingMode::Omniscient); }

void BM_Cgal(benchmark::State& state) {
    const std::size_t k = static_cast<std::size_t>(state.range(0));
    const ProbeSetup& s = setup(k);
    bench::CgalSurfaceRun r;
    for (auto _ : state) r = bench::cgal_make_surface_mesh(*s.object, s.omega, s.interior_points.front(), cases()[k].eps);
    if (!r.manifold || !r.oriented) state.SkipWithError("CGAL's mesh is not an oriented manifold");
    measure(state, k, r.mesh, r.seconds);
    state.counters["probes"] = double(r.oracle_queries);
}

BENCHMARK(BM_Probe)->DenseRange(0, 3)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(BM_Omniscient)->DenseRange(0, 3)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(BM_Cgal)->DenseRange(0, 3)->Iterations(1)->Unit(benchmark::kSecond);

void summary(const bench::RecordingReporter& rep) {
    const auto& ours = rep.runs("BM_Probe");
    const auto& omni = rep.runs("BM_Omniscient");
    const auto& cgal = rep.runs("BM_Cgal");
    std::printf("\nMeshing by probing vs CGAL make_surface_mesh (radius criterion only) and the omniscient "
                "baseline, same eps, one run\n");
    std::printf("%-14s %-10s %8s %8s %6s %8s %10s %8s %10s %9s %10s\n", "surface", "method", "vertices", "facets",
                "euler", "min_ang", "hausdorff", "seconds", "probes", "probes/V", "path");
    for (std::size_t k = 0; k < cases().size(); ++k) {
        for (const auto& [label, runs] : {std::pair{"probe", &ours}, std::pair{"omniscient", &omni},
                                          std::pair{"cgal", &cgal}}) {
            const auto it = runs->find(k);
            if (it == runs->end()) continue;
            const auto& c = it->second;
            const double v = c.counter("vertices");
            std::printf("%-14s %-10s %8.0f %8.0f %6.0f %8.2f %10.2e %8.3f %10.0f %9.1f %10.4g\n", cases()[k].name,
                        label, v, c.counter("facets"), c.counter("euler"), c.counter("min_angle"),
                        c.counter("hausdorff"), c.counter("seconds"), c.counter("probes"),
                        c.counter("probes") / v, c.counter("path_length"));
        }
    }
    std::printf("\n%-14s %14s %14s %18s %20s %14s\n", "surface", "V ours/CGAL", "time ours/CGAL",
                "time ours/omnisc.", "probes/V ours/CGAL", "H ours/CGAL");
    for (std::size_t k = 0; k < cases().size(); ++k) {
        if (!ours.count(k) || !cgal.count(k)) continue;
        const auto &o = ours.at(k), &c = cgal.at(k);
        const double om = omni.count(k) ? omni.at(k).counter("seconds") : 0;
        std::printf("%-14s %14.3f %14.3f %18.3f %9.1f / %-8.1f %14.3f\n", cases()[k].name,
                    o.counter("vertices") / c.counter("vertices"), o.counter("seconds") / c.counter("seconds"),
                    om > 0 ? o.counter("seconds") / om : 0.0, o.counter("probes") / o.counter("vertices"),
                    c.counter("probes") / c.counter("vertices"), o.counter("hausdorff") / c.counter("hausdorff"));
    }
    std::printf("(CGAL's probes are its oracle's intersection queries, initial points included; ours are ray "
                "casts of the device.)\n");
}

}  // namespace

int main(int argc, char** argv) { return dynmesh::bench::run_benchmarks(argc, argv, summary); }
