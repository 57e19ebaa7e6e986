/// Single insert/erase updates of the dynamic balanced quadtree (2D: n = 1e3 ... 1e6; 3D:
/// 1e3 ... 1e5) and of the maintained simplicial mesh (DynQuadMesh: tree + mesh + reading the
/// change; 2D 1e3 ... 1e5, 3D 1e3 ... 1e4), uniform and clustered inputs, and versus spread at
/// n = 1e4. Baselines in the same run, on the same points: rebuilding a quality mesh with CGAL's
/// 2D Delaunay mesher (refine_Delaunay_mesh_2, B = sqrt(2), about 20.7 degrees), and
/// DynQuadMesh::mesh() (the canonical mesh, O(n log n): what a caller had to call to see the
/// change before the live mesh existed). A mesh update includes what a caller pays to consume
/// the change (bench::read_delta: every removed id, every added simplex's vertex coordinates).
/// Prints per-update times, simplices changed per update, and the ratios rebuild / mesh update
/// (the tree-only updates are reported without a ratio: they do not produce a mesh).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "dynmesh/geometry/random.hpp"
#include "dynmesh/quadtree/dyn_mesh.hpp"
#include "dynmesh/quadtree/quadtree.hpp"
#include "bench_inputs.hpp"
#include "recording_reporter.hpp"

namespace {

using namespace dynmesh;
using bench::make_points;

/// A structure built over n points, and points not in it to insert and erase again.
template <class Engine>
struct Fixture {
    Engine engine;
    std::vector<typename Engine::Point> queries;
};

/// Engine = DynQuadtree<D> (the tree alone) or DynQuadMesh<D> (tree and simplicial mesh).
template <class Engine, int D>
Fixture<Engine>& fixture(std::size_t n, bool clustered) {
    static std::map<std::pair<std::size_t, bool>, Fixture<Engine>> cache;
    auto it = cache.find({n, clustered});
    if (it != cache.end()) return it->second;
    const auto pts = make_points<D>(n, clustered, 1);
    Fixture<Engine> f{Engine::build(pts), make_points<D>(4096, clustered, 2)};
    return cache.emplace(std::make_pair(n, clustered), std::move(f)).first->second;
}

/// Simplices removed + added by the last update (0 for the tree alone).
template <int D>
std::size_t simplices_changed(const DynQuadtree<D>&) { return 0; }
template <int D>
std::size_t simplices_changed(const DynQuadMesh<D>& m) {
    return m.last_update().simplices_added + m.last_update().simplices_removed;
}
/// Consumes the last change as a caller would (nothing for the tree alone).
template <int D>
double consume(const DynQuadtree<D>&) { return 0; }
template <int D>
double consume(const DynQuadMesh<D>& m) {
    return bench::read_delta<D>(m.current_mesh(), m.last_change());
}
template <int D>
std::size_t leaves_of(const DynQuadtree<D>& t) { return t.leaf_count(); }
template <int D>
std::size_t leaves_of(const DynQuadMesh<D>& m) { return m.tree().leaf_count(); }

/// One iteration = insert a new point, then erase it again (two updates), each followed by
/// reading its change.
template <class Engine>
void run_updates(benchmark::State& state, Engine& engine,
                 const std::vector<typename Engine::Point>& queries) {
    std::size_t i = 0, updates = 0, changed = 0;
    double checksum = 0;
    for (auto _ : state) {
        const auto& q = queries[i++ % queries.size()];
        if (engine.insert(q) == InsertResult::Inserted) {
            checksum += consume(engine);
            changed += simplices_changed(engine);
            benchmark::DoNotOptimize(engine.erase(q));
            checksum += consume(engine);
            changed += simplices_changed(engine);
            updates += 2;
        }
    }
    benchmark::DoNotOptimize(checksum);
    const double its = double(std::max<benchmark::IterationCount>(state.iterations(), 1));
    state.counters["updates_per_iteration"] = double(updates) / its;
    state.counters["leaves"] = double(leaves_of(engine));
    state.counters["simplices_changed_per_update"] = double(changed) / std::max(1.0, double(updates));
}

template <class Engine, int D>
void BM_Update(benchmark::State& state, bool clustered) {
    auto& f = fixture<Engine, D>(static_cast<std::size_t>(state.range(0)), clustered);
    run_updates(state, f.engine, f.queries);
}

/// Spread L/s at fixed n = 10^4: half the points uniform in the middle third, half in a
/// square cluster of side 10^-k (k = state.range(0)), so the spread grows like 10^k. One
/// iteration inserts and erases a point inside the cluster (the deepest part of the tree).
template <class Engine>
void BM_Spread(benchmark::State& state) {
    static std::map<long, Fixture<Engine>> cache;
    const long k = static_cast<long>(state.range(0));
    auto it = cache.find(k);
    if (it == cache.end()) {
        bench::SpreadSet set = bench::spread_set(static_cast<int>(k));
        it = cache.emplace(k, Fixture<Engine>{Engine::build(set.points), std::move(set.queries)}).first;
    }
    run_updates(state, it->second.engine, it->second.queries);
    state.counters["log10_spread"] = double(k) + 2.0;  // cluster spacing ~ side / 70, box ~ 1
}

void BM_Update2D_Spread(benchmark::State& s) { BM_Spread<DynQuadtree<2>>(s); }
void BM_MeshUpdate2D_Spread(benchmark::State& s) { BM_Spread<DynQuadMesh<2>>(s); }
void BM_Update2D_Uniform(benchmark::State& s) { BM_Update<DynQuadtree<2>, 2>(s, false); }
void BM_Update2D_Clustered(benchmark::State& s) { BM_Update<DynQuadtree<2>, 2>(s, true); }
void BM_Update3D_Uniform(benchmark::State& s) { BM_Update<DynQuadtree<3>, 3>(s, false); }
void BM_MeshUpdate2D_Uniform(benchmark::State& s) { BM_Update<DynQuadMesh<2>, 2>(s, false); }
void BM_MeshUpdate2D_Clustered(benchmark::State& s) { BM_Update<DynQuadMesh<2>, 2>(s, true); }
void BM_MeshUpdate3D_Uniform(benchmark::State& s) { BM_Update<DynQuadMesh<3>, 3>(s, false); }
void BM_MeshUpdate3D_Clustered(benchmark::State& s) { BM_Update<DynQuadMesh<3>, 3>(s, true); }

/// The canonical mesh of the same structure as BM_MeshUpdate2D_Uniform's (2D uniform).
void BM_CanonicalMesh2D(benchmark::State& state) {
    auto& f = fixture<DynQuadMesh<2>, 2>(static_cast<std::size_t>(state.range(0)), false);
    std::size_t simplices = 0;
    for (auto _ : state) {
        const QuadMesh2 m = f.engine.mesh();
        simplices = m.triangles.size();
        benchmark::DoNotOptimize(m.points.data());
    }
    state.counters["simplices"] = double(simplices);
}

void BM_CgalMesher2D_Rebuild(benchmark::State& state) {
    const auto pts = make_points<2>(static_cast<std::size_t>(state.range(0)), false, 1);
    std::size_t vertices = 0;
    for (auto _ : state) {
        vertices = bench::cgal_refine_box({0, 0}, 1.0, pts).number_of_vertices();
        benchmark::DoNotOptimize(vertices);
    }
    state.counters["mesh_vertices"] = double(vertices);
}

BENCHMARK(BM_Update2D_Uniform)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Update2D_Clustered)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Update3D_Uniform)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Update2D_Spread)->DenseRange(1, 10, 3)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MeshUpdate2D_Uniform)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MeshUpdate2D_Clustered)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MeshUpdate3D_Uniform)->RangeMultiplier(10)->Range(1000, 10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MeshUpdate3D_Clustered)->RangeMultiplier(10)->Range(1000, 10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MeshUpdate2D_Spread)->DenseRange(1, 10, 3)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CgalMesher2D_Rebuild)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(BM_CanonicalMesh2D)->RangeMultiplier(10)->Range(1000, 100000)->Unit(benchmark::kMillisecond)
    ->Iterations(3);

/// Per-update times; for the mesh updates also the ratios rebuild / one update (CGAL quality
/// mesher, and DynQuadMesh::mesh()), and the scaling of each series with n.
void print_summary(const dynmesh::bench::RecordingReporter& rep) {
    std::printf(
        "\nSummary: seconds per single update (mesh updates include reading the change); "
        "for 2D uniform mesh updates, CGAL mesher rebuild and DynQuadMesh::mesh() / one update\n");
    const auto& cgal = rep.runs("BM_CgalMesher2D_Rebuild");
    const auto& canon = rep.runs("BM_CanonicalMesh2D");
    for (const auto& [fn, by_n] : rep.all()) {
        if (fn == "BM_CgalMesher2D_Rebuild" || fn == "BM_CanonicalMesh2D") continue;
        double first = 0;
        std::size_t first_n = 0;
        for (const auto& [n, r] : by_n) {
            // One iteration is an insert and an erase of the same point (two updates).
            const double per = r.seconds / std::max(r.counter("updates_per_iteration", 1.0), 1e-300);
            if (fn.ends_with("_Spread"))
                std::printf("%-26s n=   10000 cluster side 1e-%zu  %10.2f us/update", fn.c_str(), n, per * 1e6);
            else
                std::printf("%-26s n=%8zu  %10.2f us/update", fn.c_str(), n, per * 1e6);
            if (first_n == 0) {
                first = per;
                first_n = n;
            } else {
                std::printf("  (%5.2f x the first)", per / first);
            }
            if (const double c = r.counter("simplices_changed_per_update", 0.0); c > 0)
                std::printf("  %7.1f simplices changed", c);
            if (fn == "BM_MeshUpdate2D_Uniform" && cgal.count(n))
                std::printf("   CGAL rebuild %9.4f s = %8.0f x", cgal.at(n).seconds, cgal.at(n).seconds / per);
            if (fn == "BM_MeshUpdate2D_Uniform" && canon.count(n))
                std::printf("   mesh() %9.4f s = %8.0f x", canon.at(n).seconds, canon.at(n).seconds / per);
            std::printf("\n");
        }
    }
}

}  // namespace

int main(int argc, char** argv) { return dynmesh::bench::run_benchmarks(argc, argv, print_summary); }
