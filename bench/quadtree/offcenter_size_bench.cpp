/// Output size of the off-center refinement (offcenter_mesh, spec §5.3 and §6.3–6.4) at the
/// smallest allowed radius-edge bound ρ = nextafter(√2) (≈ 20.7°), against
///   * CGAL's 2D Delaunay mesher (refine_Delaunay_mesh_2, Delaunay_mesh_size_criteria_2(0.125),
///     i.e. B = √2, no size bound) on the same box and points (box sides as constraints),
///   * the same refinement with circumcentres only (spec §6.4 ablation),
///   * the BEG-style quadtree postprocess quad_mesh() (its own angle bound, 18.4°),
/// for uniform and clustered inputs (n = 100, 1000, 10000) and every file of
/// shared/data/planar/ (vertices only; scaled into the middle third of the unit box).
/// Prints a table: vertices, Steiner points (vertices − inputs, box corners included) and the
/// measured minimum angle for each method, and the ratio off-center / CGAL.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/io/point_set_io.hpp"
#include "dynmesh/quadtree/offcenter.hpp"
#include "dynmesh/quadtree/quad_mesh.hpp"
#include "dynmesh/quadtree/quadtree.hpp"
#include "bench_inputs.hpp"
#include "recording_reporter.hpp"

#ifndef DYNMESH_PLANAR_DATA_DIR
#define DYNMESH_PLANAR_DATA_DIR "/work/shared/data/planar"
#endif

namespace {

using namespace dynmesh;

struct Case {
    std::string name;
    std::vector<Vec2> points;  // in the middle third of the unit box, distinct after snapping
};
std::vector<Case> g_cases;

const double kRho = std::nextafter(std::sqrt(2.0), 2.0);

double min_angle_deg(const Vec2& a, const Vec2& b, const Vec2& c) {
    double m = 180;
    const Vec2 p[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
        const Vec2 u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
        m = std::min(m, std::atan2(std::fabs(cross(u, v)), dot(u, v)) * 180 / std::numbers::pi);
    }
    return m;
}


/// The vertices of a planar file: read_point_set() for .node and one-point-per-line files; the
/// node section of a .poly, and the segment end points of an .edg, by a small parser.
std::vector<Vec2> read_planar(const std::filesystem::path& path) {
    std::vector<Vec2> out;
    try {
        for (const Point3& p : read_point_set(path).points) out.push_back({p.x, p.y});
        return out;
    } catch (const IoError&) {
    }
    std::ifstream in(path);
    std::vector<std::vector<double>> rows;
    for (std::string line; std::getline(in, line);) {
        if (const auto h = line.find('#'); h != std::string::npos) line.erase(h);
        std::istringstream ls(line);
        std::vector<double> row;
        for (double v; ls >> v;) row.push_back(v);
        if (!row.empty()) rows.push_back(row);
    }
    if (rows.empty()) return out;
    const auto count = static_cast<std::size_t>(rows[0][0]);
    if (path.extension() == ".poly") {
        for (std::size_t k = 1; k <= count && k < rows.size(); ++k)
            if (rows[k].size() >= 3) out.push_back({rows[k][1], rows[k][2]});
    } else {  // .edg: count, then x1 y1 x2 y2 per segment
        for (std::size_t k = 1; k <= count && k < rows.size(); ++k)
            if (rows[k].size() >= 4) {
                out.push_back({rows[k][0], rows[k][1]});
                out.push_back({rows[k][2], rows[k][3]});
            }
    }
    return out;
}

/// The points in order, without those that snap onto an earlier one.
std::vector<Vec2> distinct(const std::vector<Vec2>& in) {
    const DynQuadtree<2> probe;
    std::set<DynQuadtree<2>::GridPoint> seen;
    std::vector<Vec2> out;
    for (const Vec2& p : in)
        if (seen.insert(probe.grid_point(p)).second) out.push_back(p);
    return out;
}

/// Scales into [0.34, 0.66]^2 (aspect kept) and drops points that snap together.
std::vector<Vec2> into_middle_third(const std::vector<Vec2>& in) {
    Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
    for (const Vec2& p : in) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    const double ext = std::max({hi.x - lo.x, hi.y - lo.y, 1e-300});
    const double s = 0.32 / ext;
    const Vec2 shift{0.5 - 0.5 * s * (lo.x + hi.x), 0.5 - 0.5 * s * (lo.y + hi.y)};
    std::vector<Vec2> out;
    for (const Vec2& p : in) out.push_back({s * p.x + shift.x, s * p.y + shift.y});
    return distinct(out);
}

const DynQuadtree<2>& tree_of(std::size_t i) {
    static std::vector<std::unique_ptr<DynQuadtree<2>>> trees(g_cases.size());
    if (!trees[i]) trees[i] = std::make_unique<DynQuadtree<2>>(DynQuadtree<2>::build(g_cases[i].points));
    return *trees[i];
}

void set_counters(benchmark::State& state, std::size_t vertices, double min_angle) {
    const auto i = static_cast<std::size_t>(state.range(0));
    state.counters["n"] = double(g_cases[i].points.size());
    state.counters["vertices"] = double(vertices);
    state.counters["steiner"] = double(vertices - g_cases[i].points.size());
    state.counters["min_angle_deg"] = min_angle;
}

void BM_OffCenter(benchmark::State& state, bool use_offcenters) {
    const auto& tree = tree_of(static_cast<std::size_t>(state.range(0)));
    OffCenterMesh2 mesh;
    for (auto _ : state) {
        mesh = offcenter_mesh(tree, {.rho = kRho, .use_offcenters = use_offcenters});
        benchmark::DoNotOptimize(mesh.triangles.data());
    }
    set_counters(state, mesh.points.size(), mesh.min_angle_deg);
    state.counters["valid"] = check_offcenter_mesh(mesh).ok() ? 1 : 0;
}
void BM_OffCenterHPU(benchmark::State& s) { BM_OffCenter(s, true); }
void BM_CircumcentreOnly(benchmark::State& s) { BM_OffCenter(s, false); }

void BM_CgalMesher(benchmark::State& state) {
    const auto& tree = tree_of(static_cast<std::size_t>(state.range(0)));
    std::vector<Vec2> pts;
    for (const auto& e : tree.points()) pts.push_back(e.second);
    std::size_t vertices = 0;
    double min_angle = 180;
    for (auto _ : state) {
        const bench::CgalMeshCdt cdt =
            bench::cgal_refine_box(tree.options().origin, tree.options().width, pts);
        vertices = cdt.number_of_vertices();
        min_angle = 180;
        for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
            if (!f->is_in_domain()) continue;
            const auto& p = f->vertex(0)->point();
            const auto& q = f->vertex(1)->point();
            const auto& r = f->vertex(2)->point();
            min_angle = std::min(min_angle, min_angle_deg({p.x(), p.y()}, {q.x(), q.y()}, {r.x(), r.y()}));
        }
    }
    set_counters(state, vertices, min_angle);
}

void BM_QuadMesh(benchmark::State& state) {
    const auto& tree = tree_of(static_cast<std::size_t>(state.range(0)));
    QuadMesh2 mesh;
    for (auto _ : state) {
        mesh = quad_mesh(tree);
        benchmark::DoNotOptimize(mesh.triangles.data());
    }
    set_counters(state, mesh.points.size(), angle_range_deg(mesh).min);
}

void print_summary(const dynmesh::bench::RecordingReporter& rep) {
    const char* fns[] = {"BM_OffCenterHPU", "BM_CgalMesher", "BM_CircumcentreOnly", "BM_QuadMesh"};
    std::printf("\nOutput size at rho = %.17g (min angle %.6f deg); V = vertices, S = V - n "
                "(box corners included), min = measured min angle (deg)\n",
                kRho, offcenter_min_angle_deg(kRho));
    std::printf("%-16s %6s | %6s %6s %7s | %6s %6s %7s | %6s %6s %7s | %7s %7s %7s | %6s %6s %3s\n",
                "input", "n", "offV", "offS", "offMin", "cgalV", "cgalS", "cgalMin", "circV", "circS",
                "circMin", "quadV", "quadS", "quadMin", "S/cgal", "S/circ", "ok");
    for (std::size_t i = 0; i < g_cases.size(); ++i) {
        std::printf("%-16s %6zu |", g_cases[i].name.c_str(), g_cases[i].points.size());
        double s[4] = {0, 0, 0, 0};
        bool ok = false;  // off-center mesh valid (check_offcenter_mesh) and meets the angle bound
        for (int k = 0; k < 4; ++k) {
            const auto& runs = rep.runs(fns[k]);
            const auto it = runs.find(i);
            if (it == runs.end()) {
                std::printf(" %8s %8s %7s |", "-", "-", "-");
                continue;
            }
            s[k] = it->second.counter("steiner");
            const double width = k == 3 ? 7 : 6;
            std::printf(" %*.0f %*.0f %7.4f |", int(width), it->second.counter("vertices"), int(width),
                        s[k], it->second.counter("min_angle_deg"));
            if (k == 0)
                ok = it->second.counter("valid") == 1 &&
                     it->second.counter("min_angle_deg") >= offcenter_min_angle_deg(kRho) - 1e-9;
        }
        std::printf(" %6.3f %6.3f %3s\n", s[1] > 0 ? s[0] / s[1] : 0.0, s[2] > 0 ? s[0] / s[2] : 0.0,
                    ok ? "yes" : "NO");
    }
}

}  // namespace

int main(int argc, char** argv) {
    for (bool clustered : {false, true})
        for (std::size_t n : {100u, 1000u, 10000u}) {
            Case c{std::string(clustered ? "clustered" : "uniform") + "-" + std::to_string(n),
                   bench::make_points<2>(n, clustered, 1)};
            c.points = distinct(c.points);
            g_cases.push_back(std::move(c));
        }
    std::vector<std::filesystem::path> files;
    if (std::filesystem::is_directory(DYNMESH_PLANAR_DATA_DIR))
        for (const auto& e : std::filesystem::directory_iterator(DYNMESH_PLANAR_DATA_DIR))
            files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
        try {
            auto pts = read_planar(f);
            if (pts.size() < 2) continue;
            g_cases.push_back({f.filename().string(), into_middle_third(pts)});
        } catch (const std::exception& e) {
            std::fprintf(stderr, "skipping %s: %s\n", f.string().c_str(), e.what());
        }
    }
    for (std::size_t i = 0; i < g_cases.size(); ++i) {
        const auto arg = static_cast<std::int64_t>(i);
        benchmark::RegisterBenchmark("BM_OffCenterHPU", BM_OffCenterHPU)->Arg(arg)->Iterations(1)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark("BM_CgalMesher", BM_CgalMesher)->Arg(arg)->Iterations(1)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark("BM_CircumcentreOnly", BM_CircumcentreOnly)->Arg(arg)
            ->Iterations(1)->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark("BM_QuadMesh", BM_QuadMesh)->Arg(arg)->Iterations(1)
            ->Unit(benchmark::kMillisecond);
    }
    return dynmesh::bench::run_benchmarks(argc, argv, print_summary);
}
