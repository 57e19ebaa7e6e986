/// Flip smoothing of worsened sphere meshes (10K, 100K, 1M vertices) against one iteration of
/// CGAL's isotropic remeshing at the same size, in the same run.
///
/// Prints Google Benchmark's table, then a summary with time per vertex (linear scaling shows
/// as a flat column), flips per second and the ratio to CGAL.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>

#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/flips/worsen.hpp"
#include "dynmesh/geometry/spatial_sort.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "recording_reporter.hpp"

namespace {

using namespace dynmesh;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<K::Point_3>;

struct Fixture {
    SurfaceMesh worsened;
    CgalMesh cgal;  // the initial (unworsened) mesh for the remeshing reference
    double mean_edge = 0;
};

/// The mesh of n uniform samples of the unit sphere, vertices numbered along a Hilbert curve
/// (as scanned or generated meshes usually are), worsened with seed 1.
const Fixture& fixture(std::size_t n) {
    static std::map<std::size_t, Fixture> cache;
    auto it = cache.find(n);
    if (it != cache.end()) return it->second;
    const Sphere sphere({0, 0, 0}, 1.0);
    Fixture f;
    std::vector<Point3> samples = sphere.sample_uniform(n, 1);
    spatial_sort(samples);
    SurfaceMesh initial = restricted_delaunay(samples, sphere);
    f.worsened = initial;
    (void)worsen(f.worsened, {.seed = 1});
    std::vector<CgalMesh::Vertex_index> vs;
    for (Vertex v : initial.vertices()) {
        const Point3& p = initial.position(v);
        vs.push_back(f.cgal.add_vertex(K::Point_3(p.x, p.y, p.z)));
    }
    for (Face fc : initial.faces()) {
        const auto c = initial.face_vertices(fc);
        f.cgal.add_face(vs[c[0].idx()], vs[c[1].idx()], vs[c[2].idx()]);
    }
    for (Edge e : initial.edges())
        f.mean_edge += distance(initial.position(initial.vertex(e, 0)), initial.position(initial.vertex(e, 1)));
    f.mean_edge /= double(initial.n_edges());
    return cache.emplace(n, std::move(f)).first->second;
}

void BM_FlipSmooth(benchmark::State& state) {
    const Fixture& f = fixture(static_cast<std::size_t>(state.range(0)));
    std::size_t flips = 0;
    for (auto _ : state) {
        state.PauseTiming();
        SurfaceMesh mesh = f.worsened;
        state.ResumeTiming();
        const FlipReport r = flip_all(mesh);
        flips = r.flips;
        benchmark::DoNotOptimize(r);
    }
    const double n = double(f.worsened.n_vertices());
    state.counters["vertices"] = n;
    state.counters["flips"] = double(flips);
    state.counters["ns_per_vertex"] =
        benchmark::Counter(n * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["flips_per_s"] = benchmark::Counter(double(flips), benchmark::Counter::kIsIterationInvariantRate);
    state.SetComplexityN(state.range(0));
}

void BM_CgalIsotropicRemeshing1Iter(benchmark::State& state) {
    const Fixture& f = fixture(static_cast<std::size_t>(state.range(0)));
    for (auto _ : state) {
        state.PauseTiming();
        CgalMesh mesh = f.cgal;
        state.ResumeTiming();
        CGAL::Polygon_mesh_processing::isotropic_remeshing(
            faces(mesh), f.mean_edge, mesh, CGAL::parameters::number_of_iterations(1));
        benchmark::DoNotOptimize(mesh);
    }
    const double n = double(f.cgal.number_of_vertices());
    state.counters["vertices"] = n;
    state.counters["ns_per_vertex"] =
        benchmark::Counter(n * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.SetComplexityN(state.range(0));
}

BENCHMARK(BM_FlipSmooth)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oN);
BENCHMARK(BM_CgalIsotropicRemeshing1Iter)->Arg(10000)->Arg(100000)->Arg(1000000)
    ->Unit(benchmark::kMillisecond)->Iterations(1)->Complexity(benchmark::oN);

/// Time per vertex, flips per second and the ratio to CGAL, after Google Benchmark's table.
void print_summary(const dynmesh::bench::RecordingReporter& rep) {
    const auto& ours = rep.runs("BM_FlipSmooth");
    const auto& cgal = rep.runs("BM_CgalIsotropicRemeshing1Iter");
    if (ours.empty()) return;
    std::printf("\nSummary: flip smoothing of worsened unit-sphere meshes (one core)\n");
    std::printf("%10s %12s %14s %12s %14s %16s %12s\n", "samples", "vertices", "dynmesh [s]",
                "ns/vertex", "flips/vertex", "flips/s", "CGAL/dynmesh");
    for (const auto& [n, r] : ours) {
        const double t = r.seconds, v = r.counter("vertices", double(n)), fl = r.counter("flips");
        const double ratio = cgal.count(n) ? cgal.at(n).seconds / t : 0.0;
        std::printf("%10zu %12.0f %14.4f %12.1f %14.3f %16.3e %12.1f\n", n, v, t, t / v * 1e9,
                    fl / v, fl / t, ratio);
    }
    if (!cgal.empty()) {
        std::printf("CGAL isotropic_remeshing, 1 iteration, target = mean edge length:\n");
        for (const auto& [n, r] : cgal)
            std::printf("%10zu %14.4f s %10.1f ns/vertex\n", n, r.seconds,
                        r.seconds / r.counter("vertices", double(n)) * 1e9);
    }
}

}  // namespace

int main(int argc, char** argv) { return dynmesh::bench::run_benchmarks(argc, argv, print_summary); }
