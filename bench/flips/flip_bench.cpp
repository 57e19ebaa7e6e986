/// Flip smoothing of worsened meshes, global mode:
/// - worsened unit-sphere meshes (10K, 100K, 1M vertices numbered along a space-filling
///   curve) against one iteration of CGAL's isotropic remeshing at the same size, in the
///   same run (the baseline);
/// - what the vertex numbering costs: the Armadillo scan subdivided three times (1-to-4
///   midpoints, 26,002 * 64 = 1.66M vertices) in its file's numbering and spatially sorted,
///   and the 1M sphere renumbered at random, each with flip_all's renumbering off (the
///   numbering as given) and on (FlipReorder::Auto / Always). Times include the renumbering.
///
/// Prints Google Benchmark's table, then a summary with time per vertex (linear scaling shows
/// as a flat column), flips per second, the ratio to CGAL, and the numbering table.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <map>

#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/flips/worsen.hpp"
#include "dynmesh/geometry/spatial_sort.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/mesh_order.hpp"
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

/// Flips a copy of `mesh` per iteration (the copy is not timed) and sets the counters.
void run_flip_all(benchmark::State& state, const SurfaceMesh& worsened, const FlipOptions& options) {
    std::size_t flips = 0;
    bool renumbered = false;
    SurfaceMesh mesh;  // outside the loop: freeing a copy is not timed
    for (auto _ : state) {
        state.PauseTiming();
        mesh = worsened;
        state.ResumeTiming();
        const FlipReport r = flip_all(mesh, options);
        flips = r.flips;
        renumbered = r.renumbered;
        benchmark::DoNotOptimize(r);
    }
    const double n = double(worsened.n_vertices());
    state.counters["vertices"] = n;
    state.counters["flips"] = double(flips);
    state.counters["renumbered"] = renumbered ? 1 : 0;
    state.counters["scattered"] = scattered_edge_fraction(worsened);
    state.counters["ns_per_vertex"] =
        benchmark::Counter(n * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["flips_per_s"] = benchmark::Counter(double(flips), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_FlipSmooth(benchmark::State& state) {
    run_flip_all(state, fixture(static_cast<std::size_t>(state.range(0))).worsened, {});
    state.SetComplexityN(state.range(0));
}

void BM_CgalIsotropicRemeshing1Iter(benchmark::State& state) {
    const Fixture& f = fixture(static_cast<std::size_t>(state.range(0)));
    CgalMesh mesh;
    for (auto _ : state) {
        state.PauseTiming();
        mesh = f.cgal;
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

// ---- vertex numbering ----------------------------------------------------------------------

/// The worsened numbering cases: 0 = subdivided Armadillo in file order, 1 = the same mesh
/// spatially sorted, 2 = the 1M sphere renumbered at random.
const SurfaceMesh& numbering_case(int which) {
    static std::map<int, SurfaceMesh> cache;
    auto it = cache.find(which);
    if (it != cache.end()) return it->second;
    SurfaceMesh m;
    if (which == 2) {
        m = fixture(1000000).worsened;
        permute(m, random_mesh_order(m, 1));
    } else {
        // make_scenario's reference mesh of a mesh file is the file's mesh after flat 1-to-4
        // midpoint subdivisions (input vertices first, midpoints after, in the order the
        // subdivision meets them): three levels here, 26,002 * 64 vertices.
        const std::string path = std::string(DYNMESH_SHARED_DATA_DIR) + "/meshes/armadillo.off";
        if (!std::filesystem::exists(path)) return cache[which];
        const Scenario s = make_scenario(path, {.samples = 26002, .pool_factor = 128});
        m = s.reference;
        (void)worsen(m, {.seed = 1});
        if (which == 1) permute(m, spatial_mesh_order(m));
    }
    return cache.emplace(which, std::move(m)).first->second;
}

BENCHMARK(BM_FlipSmooth)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oN);
BENCHMARK(BM_CgalIsotropicRemeshing1Iter)->Arg(10000)->Arg(100000)->Arg(1000000)
    ->Unit(benchmark::kMillisecond)->Iterations(1)->Complexity(benchmark::oN);
/// One argument, 10 * case + renumbering (0 = FlipReorder::Never, 1 = Auto, 2 = Always), so
/// that the summary can key the runs.
void BM_FlipNumberingCase(benchmark::State& state) {
    const auto code = state.range(0);
    const SurfaceMesh& m = numbering_case(static_cast<int>(code / 10));
    if (m.is_empty()) {
        state.SkipWithError("armadillo.off not found in the shared data");
        return;
    }
    const FlipReorder reorder[] = {FlipReorder::Never, FlipReorder::Auto, FlipReorder::Always};
    run_flip_all(state, m, {.reorder = reorder[code % 10]});
}
BENCHMARK(BM_FlipNumberingCase)->Arg(0)->Arg(1)->Arg(10)->Arg(11)->Arg(12)->Arg(20)->Arg(21)
    ->Unit(benchmark::kMillisecond)->Iterations(3);

/// Time per vertex, flips per second and the ratio to CGAL, after Google Benchmark's table.
void print_summary(const dynmesh::bench::RecordingReporter& rep) {
    const auto& ours = rep.runs("BM_FlipSmooth");
    const auto& cgal = rep.runs("BM_CgalIsotropicRemeshing1Iter");
    if (!ours.empty()) {
        std::printf("\nSummary: flip smoothing of worsened unit-sphere meshes (one core)\n");
        std::printf("%10s %12s %14s %12s %14s %16s %12s\n", "samples", "vertices", "dynmesh [s]",
                    "ns/vertex", "flips/vertex", "flips/s", "CGAL/dynmesh");
        for (const auto& [n, r] : ours) {
            const double t = r.seconds, v = r.counter("vertices", double(n)), fl = r.counter("flips");
            const double ratio = cgal.count(n) ? cgal.at(n).seconds / t : 0.0;
            std::printf("%10zu %12.0f %14.4f %12.1f %14.3f %16.3e %12.1f\n", n, v, t, t / v * 1e9,
                        fl / v, fl / t, ratio);
        }
    }
    if (!cgal.empty()) {
        std::printf("CGAL isotropic_remeshing, 1 iteration, target = mean edge length:\n");
        for (const auto& [n, r] : cgal)
            std::printf("%10zu %14.4f s %10.1f ns/vertex\n", n, r.seconds,
                        r.seconds / r.counter("vertices", double(n)) * 1e9);
    }
    const auto& num = rep.runs("BM_FlipNumberingCase");
    if (num.empty()) return;
    const char* cases[] = {"armadillo x64, file order", "armadillo x64, sorted", "sphere 1M, random order"};
    const char* modes[] = {"as given (Never)", "Auto", "Always"};
    std::printf("\nVertex numbering: flip_all on worsened meshes, times include renumbering\n");
    std::printf("%-28s %-18s %10s %10s %10s %12s %11s %14s\n", "mesh", "renumbering", "vertices", "scattered",
                "renumbered", "flip_all [s]", "s/M vertex", "vs. as given");
    for (const auto& [code, r] : num) {
        const double v = r.counter("vertices");
        const auto base = num.find(code - code % 10);
        std::printf("%-28s %-18s %10.0f %10.3f %10s %12.3f %11.3f %14.2f\n", cases[code / 10], modes[code % 10], v,
                    r.counter("scattered"), r.counter("renumbered") > 0 ? "yes" : "no", r.seconds, r.seconds / v * 1e6,
                    base != num.end() ? r.seconds / base->second.seconds : 0.0);
    }
    if (num.count(0) && num.count(1) && num.count(10) && num.count(11))
        std::printf("armadillo x64: file order / sorted (both Auto) = %.2f; without renumbering = %.2f\n",
                    num.at(1).seconds / num.at(11).seconds, num.at(0).seconds / num.at(10).seconds);
}

}  // namespace

int main(int argc, char** argv) { return dynmesh::bench::run_benchmarks(argc, argv, print_summary); }
