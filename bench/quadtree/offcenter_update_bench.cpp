/// Cost of one update of the dynamic off-center refinement (DynOffCenterMesh2, spec §5.4 and
/// §6.1) against recomputing from scratch, in the same run and on the same points:
///   * BM_DynUpdate: one iteration inserts a random point and erases it again (two updates,
///     state restored), each followed by reading its change as a caller would
///     (bench::read_delta: removed ids, added triangles with their vertex coordinates);
///     counters: microseconds per update, Steiner points and triangles changed per update,
///     evaluations re-run per update;
///   * BM_CanonicalMesh: DynOffCenterMesh2::mesh(), the whole canonical mesh (O(n + m)): what a
///     caller had to call to see the change before the live mesh existed;
///   * BM_StaticRecompute: offcenter_mesh() of the whole point set (the oracle mode, which is
///     what an update costs without the dynamic structure);
///   * BM_CgalRemesh: CGAL's 2D Delaunay mesher on the same points and box
///     (refine_Delaunay_mesh_2, Delaunay_mesh_size_criteria_2(0.125), i.e. about 20.7 degrees).
/// Inputs: n = 1e3, 1e4, 1e5 points, uniform and clustered (20 Gaussian blobs of sigma 0.01, as
/// quadtree_bench), in the middle third of the unit box, and the spread family of quadtree_bench
/// (n = 1e4, half the points in a cluster of side 1e-1 ... 1e-10, updates inside the cluster;
/// points closer than offcenter_min_separation() to an earlier one are dropped, and queries
/// the mesher refuses are skipped);
/// rho = 1.5. A summary table with the
/// ratios recompute / update follows Google Benchmark's output.
/// Options: --benchmark_filter etc. as usual; DYNMESH_OFFCENTER_UPDATE_MAX_N (default 100000)
/// caps n.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/quadtree/dyn_offcenter.hpp"
#include "dynmesh/quadtree/offcenter.hpp"
#include "dynmesh/quadtree/quadtree.hpp"
#include "bench_inputs.hpp"
#include "recording_reporter.hpp"

namespace {

using namespace dynmesh;

constexpr double kRho = 1.5;

struct Case {
    std::string name;
    std::size_t n = 0;
    bool clustered = false;
    int spread = 0;  // > 0: the spread family of bench_inputs.hpp with a cluster of side 10^-spread
};
std::vector<Case> g_cases;


/// The distinct points of a case (in the order generated), and their dynamic mesh.
struct Fixture {
    std::vector<Vec2> points;
    std::vector<Vec2> queries;  // same distribution, seed 2
    std::unique_ptr<DynOffCenterMesh2> dyn;
    double build_seconds = 0;
};

Fixture& fixture(std::size_t i) {
    static std::map<std::size_t, Fixture> cache;
    auto it = cache.find(i);
    if (it != cache.end()) return it->second;
    Fixture f;
    const Case& c = g_cases[i];
    DynQuadtree<2> probe;
    bench::SpreadSet set;
    if (c.spread > 0) set = bench::spread_set(c.spread);
    // Distinct after snapping, and no two closer than the refinement resolves (the deepest
    // spread cluster has random pairs below offcenter_min_separation()).
    const double sep = offcenter_min_separation({}, {.rho = kRho});
    PointGrid near(1e-3);
    for (const Vec2& p : c.spread > 0 ? set.points : bench::make_points<2>(c.n, c.clustered, 1)) {
        const Point3 p3{p.x, p.y, 0};
        bool close = false;
        near.for_each_candidate(p3, sep, [&](std::uint32_t id) {
            close = close || norm(f.points[id] - p) < sep;
        });
        if (close || probe.insert(p) != InsertResult::Inserted) continue;
        near.insert(static_cast<std::uint32_t>(f.points.size()), p3);
        f.points.push_back(p);
    }
    f.queries = c.spread > 0 ? set.queries : bench::make_points<2>(4096, c.clustered, 2);
    const auto t0 = std::chrono::steady_clock::now();
    f.dyn =
        std::make_unique<DynOffCenterMesh2>(DynOffCenterMesh2::build(f.points, {}, {.rho = kRho}));
    f.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // Warm-up (not timed): the first updates after a large build pay one-off allocator costs.
    for (std::size_t k = 0; k < 8; ++k) {
        const Vec2 q{0.34 + 0.04 * double(k), 0.5 + 1e-7 * double(k)};
        if (f.dyn->insert(q) == InsertResult::Inserted) (void)f.dyn->erase(q);
    }
    return cache.emplace(i, std::move(f)).first->second;
}

void BM_DynUpdate(benchmark::State& state) {
    Fixture& f = fixture(static_cast<std::size_t>(state.range(0)));
    std::size_t i = 0, updates = 0, changed = 0, evaluations = 0, rounds = 0, queries = 0;
    std::size_t triangles = 0;
    double checksum = 0;
    for (auto _ : state) {
        const Vec2& q = f.queries[i++ % f.queries.size()];
        if (f.dyn->insert(q) != InsertResult::Inserted) continue;
        checksum += bench::read_delta<2>(f.dyn->current_mesh(), f.dyn->last_change());
        const OffCenterUpdateReport a = f.dyn->last_update();
        if (f.dyn->erase(q) != EraseResult::Erased) state.SkipWithError("erase failed");
        checksum += bench::read_delta<2>(f.dyn->current_mesh(), f.dyn->last_change());
        const OffCenterUpdateReport& b = f.dyn->last_update();
        updates += 2;
        triangles += a.simplices_added + a.simplices_removed + b.simplices_added +
                     b.simplices_removed;
        changed += a.steiner_added + a.steiner_removed + b.steiner_added + b.steiner_removed;
        evaluations += a.evaluations + b.evaluations;
        rounds += a.rounds_visited + b.rounds_visited;
        queries += a.queries + b.queries;
    }
    benchmark::DoNotOptimize(checksum);
    const double u = double(std::max<std::size_t>(updates, 1));
    state.counters["triangles_changed_per_update"] = double(triangles) / u;
    state.counters["updates_per_iteration"] =
        double(updates) / double(std::max<std::size_t>(state.iterations(), 1));
    state.counters["steiner_changed_per_update"] = double(changed) / u;
    state.counters["evaluations_per_update"] = double(evaluations) / u;
    state.counters["rounds_per_update"] = double(rounds) / u;
    state.counters["queries_per_update"] = double(queries) / u;
    state.counters["vertices"] = double(f.dyn->vertex_count());
    state.counters["n"] = double(f.points.size());
    state.counters["build_s"] = f.build_seconds;
}

void BM_StaticRecompute(benchmark::State& state) {
    Fixture& f = fixture(static_cast<std::size_t>(state.range(0)));
    std::size_t vertices = 0;
    for (auto _ : state) {
        const OffCenterMesh2 mesh = offcenter_mesh(f.dyn->tree(), {.rho = kRho});
        vertices = mesh.points.size();
        benchmark::DoNotOptimize(mesh.triangles.data());
    }
    state.counters["vertices"] = double(vertices);
}

void BM_CanonicalMesh(benchmark::State& state) {
    Fixture& f = fixture(static_cast<std::size_t>(state.range(0)));
    std::size_t triangles = 0;
    for (auto _ : state) {
        const OffCenterMesh2 mesh = f.dyn->mesh();
        triangles = mesh.triangles.size();
        benchmark::DoNotOptimize(mesh.triangles.data());
    }
    state.counters["triangles"] = double(triangles);
}

void BM_CgalRemesh(benchmark::State& state) {
    Fixture& f = fixture(static_cast<std::size_t>(state.range(0)));
    std::size_t vertices = 0;
    for (auto _ : state) {
        vertices = bench::cgal_refine_box({0, 0}, 1.0, f.points).number_of_vertices();
        benchmark::DoNotOptimize(vertices);
    }
    state.counters["vertices"] = double(vertices);
}

void print_summary(const dynmesh::bench::RecordingReporter& rep) {
    const auto& dyn = rep.runs("BM_DynUpdate");
    const auto& stat = rep.runs("BM_StaticRecompute");
    const auto& canon = rep.runs("BM_CanonicalMesh");
    const auto& cgal = rep.runs("BM_CgalRemesh");
    std::printf(
        "\nOne update of DynOffCenterMesh2 (rho = %.3g), reading its change included, vs "
        "recomputing: static offcenter_mesh(), CGAL refine_Delaunay_mesh_2 (B = sqrt 2), and "
        "DynOffCenterMesh2::mesh()\n",
        kRho);
    std::printf("%-16s %7s %8s | %10s %9s %8s %9s %7s | %10s %9s %9s | %8s %8s %8s | %7s\n",
                "input", "n", "verts", "us/update", "steiner/u", "tris/u", "evals/u", "rnds/u",
                "static ms", "cgal ms", "mesh() ms", "static/u", "cgal/u", "mesh()/u",
                "build s");
    for (std::size_t i = 0; i < g_cases.size(); ++i) {
        const auto d = dyn.find(i);
        if (d == dyn.end()) continue;
        const double per =
            d->second.seconds / std::max(d->second.counter("updates_per_iteration", 2.0), 1e-300);
        std::printf("%-16s %7.0f %8.0f | %10.2f %9.2f %8.1f %9.1f %7.1f |", g_cases[i].name.c_str(),
                    d->second.counter("n"), d->second.counter("vertices"), per * 1e6,
                    d->second.counter("steiner_changed_per_update"),
                    d->second.counter("triangles_changed_per_update"),
                    d->second.counter("evaluations_per_update"),
                    d->second.counter("rounds_per_update"));
        const auto seconds = [&](const auto& runs) {
            const auto r = runs.find(i);
            return r != runs.end() ? r->second.seconds : 0.0;
        };
        std::printf(" %10.2f %9.2f %9.2f |", seconds(stat) * 1e3, seconds(cgal) * 1e3,
                    seconds(canon) * 1e3);
        std::printf(" %8.0f %8.0f %8.0f | %7.2f\n", seconds(stat) / per, seconds(cgal) / per,
                    seconds(canon) / per, d->second.counter("build_s"));
    }
    std::printf(
        "static/u, cgal/u, mesh()/u: recompute time / one dynamic update (the speed-up of the "
        "dynamic update; every column is a full quality mesh or its update).\n");
}

}  // namespace

int main(int argc, char** argv) {
    std::size_t max_n = 100000;
    if (const char* e = std::getenv("DYNMESH_OFFCENTER_UPDATE_MAX_N"))
        max_n = std::strtoull(e, nullptr, 10);
    for (bool clustered : {false, true})
        for (std::size_t n : {1000u, 10000u, 100000u})
            if (n <= max_n)
                g_cases.push_back(
                    {std::string(clustered ? "clustered" : "uniform") + "-" + std::to_string(n), n,
                     clustered});
    for (int k : {1, 4, 7, 10})
        g_cases.push_back({"spread-1e-" + std::to_string(k), 10000, false, k});
    for (std::size_t i = 0; i < g_cases.size(); ++i) {
        const auto arg = static_cast<std::int64_t>(i);
        benchmark::RegisterBenchmark("BM_DynUpdate", BM_DynUpdate)
            ->Arg(arg)
            ->MinTime(0.3)
            ->Unit(benchmark::kMicrosecond);
        const int reps = g_cases[i].n >= 100000 ? 1 : 3;
        benchmark::RegisterBenchmark("BM_StaticRecompute", BM_StaticRecompute)
            ->Arg(arg)
            ->Iterations(reps)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark("BM_CgalRemesh", BM_CgalRemesh)
            ->Arg(arg)
            ->Iterations(reps)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark("BM_CanonicalMesh", BM_CanonicalMesh)
            ->Arg(arg)
            ->Iterations(reps)
            ->Unit(benchmark::kMillisecond);
    }
    return dynmesh::bench::run_benchmarks(argc, argv, print_summary);
}
