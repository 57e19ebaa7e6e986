/// Local flipping (flip_local, the doubling-window method) around |V| scattered vertices of a
/// converged unit-sphere mesh whose edges near V were worsened, against the user's
/// alternative, flip_all on the same mesh, in the same run:
/// - |V| sweep (10 .. 10,000) on a 100K-vertex mesh;
/// - mesh-size sweep (10K .. 1M vertices) at |V| = 100.
/// The cost of flip_local should follow its window (the vertices within the final m hops of
/// V), not the mesh: the summary prints the time per window vertex, which should stay flat
/// in both sweeps, and the ratio flip_all / flip_local. Every run starts with cold caches
/// (evict_caches).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <algorithm>
#include <map>
#include <tuple>
#include <unordered_set>

#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/flips/worsen.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/spatial_sort.hpp"
#include "dynmesh/mesh/mesh_order.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "recording_reporter.hpp"

namespace {

using namespace dynmesh;

/// n uniform samples of the unit sphere (numbered along the curve), meshed and flipped to
/// convergence under Definition 3.
const SurfaceMesh& converged_sphere(std::size_t n) {
    static std::map<std::size_t, SurfaceMesh> cache;
    auto it = cache.find(n);
    if (it != cache.end()) return it->second;
    const Sphere sphere({0, 0, 0}, 1.0);
    std::vector<Point3> samples = sphere.sample_uniform(n, 1);
    spatial_sort(samples);
    SurfaceMesh m = restricted_delaunay(samples, sphere);
    (void)flip_all(m);
    permute(m, spatial_mesh_order(m));  // edges and faces in the vertices' curve order too
    return cache.emplace(n, std::move(m)).first->second;
}

struct LocalCase {
    SurfaceMesh worsened;
    std::vector<Vertex> V;
};

/// k distinct vertices of the converged n-vertex sphere, scattered at random or (cap) the k
/// nearest to one point, and the mesh with the paper's worsening applied to the edges with
/// both ends within one hop of them.
const LocalCase& local_case(std::size_t n, std::size_t k, bool cap) {
    static std::map<std::tuple<std::size_t, std::size_t, bool>, LocalCase> cache;
    auto it = cache.find({n, k, cap});
    if (it != cache.end()) return it->second;
    LocalCase c;
    c.worsened = converged_sphere(n);
    Rng rng(k);
    std::unordered_set<std::uint32_t> picked;
    if (cap) {
        std::vector<std::pair<double, std::uint32_t>> by_distance;
        for (Vertex v : c.worsened.vertices())
            by_distance.emplace_back(sqdistance(c.worsened.position(v), Point3{0.6, 0.48, 0.64}), v.idx());
        std::partial_sort(by_distance.begin(), by_distance.begin() + std::ptrdiff_t(k), by_distance.end());
        for (std::size_t i = 0; i < k; ++i) picked.insert(by_distance[i].second);
    }
    while (picked.size() < k) picked.insert(static_cast<std::uint32_t>(rng.below(c.worsened.n_vertices())));
    for (std::uint32_t v : picked) c.V.push_back(Vertex(v));
    std::sort(c.V.begin(), c.V.end());
    std::unordered_set<std::uint32_t> near(picked);
    for (Vertex v : c.V)
        for (Halfedge h : c.worsened.outgoing_halfedges(v)) near.insert(c.worsened.to_vertex(h).idx());
    (void)worsen(c.worsened, {.seed = 1, .only = [&](const SurfaceMesh& m, Edge e) {
                                  return near.count(m.vertex(e, 0).idx()) && near.count(m.vertex(e, 1).idx());
                              }});
    return cache.emplace(std::tuple{n, k, cap}, std::move(c)).first->second;
}

/// Streams through 64 MB (twice the last-level cache) so that every run starts with the mesh
/// out of the caches, as a mesh edited some time ago would be. Without it a 10K-vertex mesh
/// (1 MB) stays in L2 after its copy and a 1M-vertex one (100 MB) does not, and the sweep
/// would measure the cache hierarchy instead of the algorithm.
void evict_caches() {
    static std::vector<std::uint64_t> junk(std::size_t(8) << 20, 1);
    std::uint64_t sum = 0;
    for (std::uint64_t& x : junk) sum += x++;
    benchmark::DoNotOptimize(sum);
}

/// Runs flip_local (or flip_all) on a copy per iteration; the copy, its destruction and the
/// cache eviction are not timed.
void run(benchmark::State& state, std::size_t n, std::size_t k, bool local, bool cap = false) {
    const LocalCase& c = local_case(n, k, cap);
    LocalFlipReport last;
    FlipReport all;
    SurfaceMesh mesh;  // outside the loop: freeing a copy (100 MB at 1M vertices) is not timed
    for (auto _ : state) {
        state.PauseTiming();
        mesh = c.worsened;  // reuses the buffers of the previous copy
        evict_caches();
        state.ResumeTiming();
        if (local)
            last = flip_local(mesh, c.V);
        else
            all = flip_all(mesh);
        benchmark::DoNotOptimize(mesh);
    }
    state.counters["vertices"] = double(c.worsened.n_vertices());
    state.counters["V"] = double(k);
    if (local) {
        state.counters["window"] = double(last.window_vertices);
        state.counters["rounds"] = double(last.rounds);
        state.counters["final_m"] = double(last.final_m);
        state.counters["flips"] = double(last.flips.flips);
        state.counters["checks"] = double(last.flips.checks);
        state.counters["converged"] = last.converged ? 1 : 0;
        state.counters["ns_per_window_vertex"] = benchmark::Counter(
            double(last.window_vertices) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    } else {
        state.counters["flips"] = double(all.flips);
    }
}

constexpr std::size_t kSweepMesh = 100000;
constexpr std::size_t kSweepV = 100;

void BM_FlipLocalVSweep(benchmark::State& s) { run(s, kSweepMesh, std::size_t(s.range(0)), true); }
void BM_FlipAllVSweep(benchmark::State& s) { run(s, kSweepMesh, std::size_t(s.range(0)), false); }
void BM_FlipLocalSizeSweep(benchmark::State& s) { run(s, std::size_t(s.range(0)), kSweepV, true); }
void BM_FlipAllSizeSweep(benchmark::State& s) { run(s, std::size_t(s.range(0)), kSweepV, false); }
void BM_FlipLocalCapSweep(benchmark::State& s) { run(s, std::size_t(s.range(0)), kSweepV, true, true); }
void BM_FlipAllCapSweep(benchmark::State& s) { run(s, std::size_t(s.range(0)), kSweepV, false, true); }

BENCHMARK(BM_FlipLocalVSweep)->Arg(10)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond)->Iterations(20);
BENCHMARK(BM_FlipAllVSweep)->Arg(10)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FlipLocalSizeSweep)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMicrosecond)->Iterations(20);
BENCHMARK(BM_FlipAllSizeSweep)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FlipLocalCapSweep)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMicrosecond)->Iterations(20);
BENCHMARK(BM_FlipAllCapSweep)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(3);

void print_table(const dynmesh::bench::RecordingReporter& rep, const char* local_name, const char* all_name,
                 const char* title) {
    const auto& local = rep.runs(local_name);
    const auto& all = rep.runs(all_name);
    if (local.empty()) return;
    std::printf("\n%s\n", title);
    std::printf("%10s %8s %8s %7s %8s %8s %15s %14s %16s %14s %12s\n", "vertices", "|V|", "window", "rounds", "final_m",
                "flips", "checks/window v", "flip_local [s]", "ns/window vertex", "flip_all [s]", "all / local");
    for (const auto& [arg, r] : local) {
        const double w = r.counter("window");
        const auto a = all.find(arg);
        const double ta = a != all.end() ? a->second.seconds : 0.0;
        std::printf("%10.0f %8.0f %8.0f %7.0f %8.0f %8.0f %15.2f %14.6f %16.1f %14.4f %12.1f%s\n", r.counter("vertices"),
                    r.counter("V"), w, r.counter("rounds"), r.counter("final_m"), r.counter("flips"), r.counter("checks") / w,
                    r.seconds, r.seconds / w * 1e9, ta, ta / r.seconds, r.counter("converged") > 0 ? "" : "  (not converged)");
    }
}

void print_summary(const dynmesh::bench::RecordingReporter& rep) {
    print_table(rep, "BM_FlipLocalVSweep", "BM_FlipAllVSweep",
                "|V| sweep on a 100K-vertex sphere (time per window vertex should stay flat)");
    print_table(rep, "BM_FlipLocalSizeSweep", "BM_FlipAllSizeSweep",
                "Mesh-size sweep at |V| = 100 scattered vertices (time per window vertex should stay flat)");
    print_table(rep, "BM_FlipLocalCapSweep", "BM_FlipAllCapSweep",
                "Mesh-size sweep at |V| = 100 vertices of one cap (time per window vertex should stay flat)");
}

}  // namespace

int main(int argc, char** argv) { return dynmesh::bench::run_benchmarks(argc, argv, print_summary); }
