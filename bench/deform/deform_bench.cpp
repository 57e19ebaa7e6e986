/// One MeshUpdate of a deforming sphere (|P| = 10K, 100K, 1M random samples; the sphere is
/// stretched along x, the samples moving lambda per time unit, and the update runs at the
/// scheduled step, after floor(R / (kappa lambda)) units of motion), against rebuilding the
/// mesh from the same samples at the same positions with CGAL's advancing-front
/// reconstruction in the same run. Prints seconds per update, ns per sample (flat = linear
/// time) and the rebuild / update ratio.
///
/// The caller's numbering: BM_DeformUpdate numbers the samples randomly (as sample_uniform
/// draws them), BM_DeformUpdateSorted gives the same samples numbered along a Morton curve;
/// the summary prints the random / sorted ratio of the update time (1 when the numbering
/// does not matter). The timed update includes advance() (every cost the caller pays at a
/// step: the motion of all samples, then MeshUpdate).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <tuple>

#include "dynmesh/deform/deforming_mesh.hpp"
#include "dynmesh/geometry/spatial_sort.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/reconstruct/advancing_front.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "recording_reporter.hpp"

namespace {

using namespace dynmesh;
using Clock = std::chrono::steady_clock;

/// x stretched by 1 + A (1 - cos(w t)) / 2: |d/dt| <= A w / 2 for |x| <= 1.
struct Motion {
    double A = 0.5;
    double lambda = 2e-4;
    [[nodiscard]] double w() const { return 2 * lambda / A; }
    [[nodiscard]] double scale(int t) const { return 1 + A * (1 - std::cos(w() * t)) / 2; }
    void at(int t, const std::vector<Point3>& p0, std::vector<Point3>& out) const {
        const double s = scale(t);
        out.resize(p0.size());
        for (std::size_t i = 0; i < p0.size(); ++i) out[i] = Point3{p0[i].x * s, p0[i].y, p0[i].z};
    }
};

struct Fixture {
    std::vector<Point3> p0, pos;
    std::unique_ptr<DeformingMesh> dm;
    Motion motion;
    double init_seconds = 0;
};

/// `sorted`: the samples renumbered along a Morton curve (same points).
Fixture& fixture(std::size_t n, bool sorted = false) {
    static std::map<std::pair<std::size_t, bool>, Fixture> cache;
    auto it = cache.find({n, sorted});
    if (it != cache.end()) return it->second;
    Fixture f;
    const Sphere sphere(Point3{0, 0, 0}, 1.0);
    f.p0 = sphere.sample_uniform(n, 1);
    if (sorted) spatial_sort(f.p0);
    DeformOptions params;
    params.lambda = f.motion.lambda * 1.001;
    params.h0_probes = std::max<std::size_t>(n, 100000);
    const auto t0 = Clock::now();
    f.dm = std::make_unique<DeformingMesh>(f.p0, params, InitialSurface{.surface = &sphere});
    f.init_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    // Warm up: the first steps of the motion.
    for (int k = 0; k < 2; ++k) {
        const int t = f.dm->next_step();
        f.motion.at(t, f.p0, f.pos);
        f.dm->advance(t, f.pos);
        f.dm->update();
    }
    return cache.emplace(std::make_pair(n, sorted), std::move(f)).first->second;
}

/// One iteration = compute the sample positions at the next scheduled step (not timed), then
/// advance() and update() (timed).
void update_bench(benchmark::State& state, bool sorted) {
    Fixture& f = fixture(static_cast<std::size_t>(state.range(0)), sorted);
    UpdateCounters total;
    std::size_t updates = 0, units = 0;
    double advance_s = 0;
    for (auto _ : state) {
        const int t0 = f.dm->time();
        const int t = f.dm->next_step();
        f.motion.at(t, f.p0, f.pos);
        const auto start = Clock::now();
        f.dm->advance(t, f.pos);
        const auto mid = Clock::now();
        const DeformUpdateReport u = f.dm->update();
        const auto end = Clock::now();
        state.SetIterationTime(std::chrono::duration<double>(end - start).count());
        advance_s += std::chrono::duration<double>(mid - start).count();
        total += u.counters;
        ++updates;
        units += static_cast<std::size_t>(t - t0);
    }
    const double n = double(f.p0.size());
    state.counters["samples"] = n;
    state.counters["vertices"] = double(f.dm->mesh().n_vertices());
    state.counters["init_s"] = f.init_seconds;
    state.counters["units_per_step"] = double(units) / double(updates);
    state.counters["changes_per_update"] = double(total.changes()) / double(updates);
    state.counters["advance_s"] = advance_s / double(updates);
    state.counters["flips_per_update"] = double(total.flips) / double(updates);
    state.counters["ns_per_sample"] =
        benchmark::Counter(n * double(updates) * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
void BM_DeformUpdate(benchmark::State& state) { update_bench(state, false); }
void BM_DeformUpdateSorted(benchmark::State& state) { update_bench(state, true); }

/// Fast frames (issue "Deforming real meshes": one update with all its sub-steps): at every
/// unit t, `move(t, p0, pos)` places the sphere's samples, advance() cuts the unit into
/// sub-steps with updates between them and tests the mesh for self-intersections, and
/// update() follows. Timed: advance() + update(), against the CGAL rebuild. One mesh per
/// (motion, size, local) lives across the iterations.
template <class Move>
void fast_frames(benchmark::State& state, int motion, bool local, Move&& move) {
    const auto n = static_cast<std::size_t>(state.range(0));
    static std::map<std::tuple<int, std::size_t, bool>, std::unique_ptr<DeformingMesh>> cache;
    const Sphere sphere(Point3{0, 0, 0}, 1.0);
    const std::vector<Point3> p0 = sphere.sample_uniform(n, 1);
    auto& dm = cache[{motion, n, local}];
    if (!dm) {
        DeformOptions params;
        params.lambda = 2e-4;
        params.h0_probes = std::max<std::size_t>(n, 100000);
        params.local_updates = local;
        dm = std::make_unique<DeformingMesh>(p0, params, InitialSurface{.surface = &sphere});
    }
    std::vector<Point3> pos(p0.size());
    std::size_t substeps = 0, internal = 0, retries = 0, local_updates = 0, region = 0, frames = 0, changes = 0;
    for (auto _ : state) {
        const int t = dm->time() + 1;
        move(t, p0, pos);
        const auto start = Clock::now();
        const StepReport st = dm->advance(t, pos);
        const DeformUpdateReport u = dm->update();
        state.SetIterationTime(std::chrono::duration<double>(Clock::now() - start).count());
        substeps += st.substeps;
        internal += st.internal_updates;
        retries += st.retries;
        changes += st.internal.changes() + u.counters.changes();
        local_updates += st.local_updates;
        region += st.region_vertices;
        ++frames;
    }
    state.counters["samples"] = double(n);
    state.counters["vertices"] = double(dm->mesh().n_vertices());
    state.counters["substeps"] = double(substeps) / double(frames);
    state.counters["internal_updates"] = double(internal) / double(frames);
    state.counters["retries"] = double(retries) / double(frames);
    state.counters["local_updates"] = double(local_updates) / double(frames);
    state.counters["changes"] = double(changes) / double(frames);
    state.counters["region_share"] =
        local_updates > 0 ? double(region) / double(local_updates) / double(dm->mesh().n_vertices()) : 1.0;
}

/// Every unit stretches x by 1.25 or back, so edges move relative to each other by about
/// four budgets 2 R / kappa: every pair is over its budget at once.
void BM_DeformFastFrame(benchmark::State& state) {
    fast_frames(state, 0, true, [](int t, const std::vector<Point3>& p0, std::vector<Point3>& pos) {
        const double s = t % 2 == 1 ? 1.25 : 1.0;
        for (std::size_t i = 0; i < p0.size(); ++i) pos[i] = Point3{p0[i].x * s, p0[i].y, p0[i].z};
    });
}

/// A fast local frame: a dimple of radius 0.3 about the pole (0, 0, 1) is pushed in by 0.15
/// at odd units and released at even ones (the rest of the sphere still), so the pairs over
/// their budget sit in the cap; the updates between sub-steps local (spec §10.1, the
/// default) or global (BM_DeformLocalFastFrameGlobal).
void local_fast_frame(benchmark::State& state, bool local) {
    fast_frames(state, 1, local, [](int t, const std::vector<Point3>& p0, std::vector<Point3>& pos) {
        const double depth = t % 2 == 1 ? 0.15 : 0.0;
        for (std::size_t i = 0; i < p0.size(); ++i) {
            const double d = distance(p0[i], Point3{0, 0, 1});
            const double w = d < 0.3 ? 0.5 * (1 + std::cos(kPi * d / 0.3)) : 0.0;
            pos[i] = p0[i] * (1 - depth * w);
        }
    });
}
void BM_DeformLocalFastFrame(benchmark::State& state) { local_fast_frame(state, true); }
void BM_DeformLocalFastFrameGlobal(benchmark::State& state) { local_fast_frame(state, false); }

/// The baseline: a from-scratch advancing-front reconstruction of the same samples at the
/// positions of the last update.
void BM_CgalAdvancingFrontRebuild(benchmark::State& state) {
    Fixture& f = fixture(static_cast<std::size_t>(state.range(0)));
    f.motion.at(f.dm->time(), f.p0, f.pos);
    std::size_t faces = 0;
    for (auto _ : state) {
        const auto start = Clock::now();
        const SurfaceMesh m = reconstruct_advancing_front(f.pos);
        state.SetIterationTime(std::chrono::duration<double>(Clock::now() - start).count());
        faces = m.n_faces();
    }
    state.counters["samples"] = double(f.p0.size());
    state.counters["faces"] = double(faces);
}

BENCHMARK(BM_DeformUpdate)->RangeMultiplier(10)->Range(10000, 1000000)->UseManualTime()
    ->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_DeformUpdateSorted)->RangeMultiplier(10)->Range(10000, 1000000)->UseManualTime()
    ->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_DeformFastFrame)->RangeMultiplier(10)->Range(10000, 1000000)->UseManualTime()
    ->Unit(benchmark::kMillisecond)->Iterations(4);
BENCHMARK(BM_DeformLocalFastFrame)->RangeMultiplier(10)->Range(10000, 1000000)->UseManualTime()
    ->Unit(benchmark::kMillisecond)->Iterations(4);
BENCHMARK(BM_DeformLocalFastFrameGlobal)->RangeMultiplier(10)->Range(10000, 1000000)->UseManualTime()
    ->Unit(benchmark::kMillisecond)->Iterations(4);
BENCHMARK(BM_CgalAdvancingFrontRebuild)->RangeMultiplier(10)->Range(10000, 1000000)->UseManualTime()
    ->Unit(benchmark::kMillisecond)->Iterations(1);

void print_summary(const dynmesh::bench::RecordingReporter& rep) {
    std::printf("\nSummary: one scheduled update vs. CGAL advancing-front rebuild of the same samples\n");
    std::printf("%10s %10s %12s %12s %12s %14s %10s %12s %12s\n", "samples", "vertices", "update s", "ns/sample",
                "changes", "CGAL rebuild s", "ratio", "sorted s", "rand/sorted");
    const auto& upd = rep.runs("BM_DeformUpdate");
    const auto& sorted = rep.runs("BM_DeformUpdateSorted");
    const auto& cgal = rep.runs("BM_CgalAdvancingFrontRebuild");
    for (const auto& [n, r] : upd) {
        std::printf("%10zu %10.0f %12.4f %12.1f %12.0f", n, r.counter("vertices", 0), r.seconds,
                    r.seconds / double(n) * 1e9, r.counter("changes_per_update", 0));
        if (cgal.count(n))
            std::printf(" %14.3f %10.1f", cgal.at(n).seconds, cgal.at(n).seconds / r.seconds);
        else
            std::printf(" %14s %10s", "-", "-");
        if (sorted.count(n)) std::printf(" %12.4f %12.2f", sorted.at(n).seconds, r.seconds / sorted.at(n).seconds);
        std::printf("\n");
    }
    const auto& fast = rep.runs("BM_DeformFastFrame");
    std::printf("\nSummary: one fast frame (advance with its sub-steps, updates and intersection check, then "
                "update) vs. the CGAL rebuild\n");
    std::printf("%10s %10s %10s %10s %8s %12s %12s %14s %10s\n", "samples", "vertices", "substeps", "internal", "retries",
                "frame s", "ns/sample", "CGAL rebuild s", "frame/CGAL");
    for (const auto& [n, r] : fast) {
        std::printf("%10zu %10.0f %10.1f %10.1f %8.2f %12.4f %12.1f", n, r.counter("vertices", 0), r.counter("substeps", 0),
                    r.counter("internal_updates", 0), r.counter("retries", 0), r.seconds, r.seconds / double(n) * 1e9);
        if (cgal.count(n))
            std::printf(" %14.3f %10.3f", cgal.at(n).seconds, r.seconds / cgal.at(n).seconds);
        std::printf("\n");
    }
    const auto& dimple = rep.runs("BM_DeformLocalFastFrame");
    const auto& g = rep.runs("BM_DeformLocalFastFrameGlobal");
    std::printf("\nSummary: one fast local frame (a dimple pushed in or released at the pole), updates between "
                "sub-steps local (U) or global, vs. the CGAL rebuild\n");
    std::printf("%10s %10s %10s %10s %10s %12s %12s %12s %12s %12s\n", "samples", "vertices", "substeps", "internal",
                "|U|/V", "local s", "global s", "global/local", "local/CGAL", "global/CGAL");
    for (const auto& [n, r] : dimple) {
        std::printf("%10zu %10.0f %10.1f %10.1f %10.3f %12.4f", n, r.counter("vertices", 0), r.counter("substeps", 0),
                    r.counter("internal_updates", 0), r.counter("region_share", 1), r.seconds);
        if (g.count(n))
            std::printf(" %12.4f %12.2f", g.at(n).seconds, g.at(n).seconds / r.seconds);
        else
            std::printf(" %12s %12s", "-", "-");
        if (cgal.count(n)) {
            std::printf(" %12.3f", r.seconds / cgal.at(n).seconds);
            if (g.count(n)) std::printf(" %12.3f", g.at(n).seconds / cgal.at(n).seconds);
        }
        std::printf("\n");
    }
}

}  // namespace

int main(int argc, char** argv) { return dynmesh::bench::run_benchmarks(argc, argv, print_summary); }
