// The local size field (spec deforming-mesh.md §10.2, test F5): the feature-size estimate on a
// mesh against the exact local feature size of a thin ellipsoid and a torus with a thin tube,
// the grading, and a start on a real mesh whose thin parts the field resolves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "dynmesh/deform/run.hpp"
#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/deform/size_field.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

constexpr double kPi = std::numbers::pi;

/// A closed latitude-longitude mesh of the ellipsoid with semi-axes (a, b, c): `rings`
/// latitude circles of `segments` vertices and the two poles.
SurfaceMesh ellipsoid_mesh(double a, double b, double c, int rings, int segments) {
    TriangleSoup s;
    s.points.push_back({0, 0, c});
    for (int i = 1; i <= rings; ++i) {
        const double th = kPi * i / (rings + 1);
        for (int j = 0; j < segments; ++j) {
            const double ph = 2 * kPi * j / segments;
            s.points.push_back({a * std::sin(th) * std::cos(ph), b * std::sin(th) * std::sin(ph), c * std::cos(th)});
        }
    }
    s.points.push_back({0, 0, -c});
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * segments + (j % segments)); };
    const auto south = static_cast<std::uint32_t>(s.points.size() - 1);
    for (int j = 0; j < segments; ++j) {
        s.triangles.push_back({0, at(1, j), at(1, j + 1)});
        for (int i = 1; i < rings; ++i) {
            s.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            s.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
        s.triangles.push_back({at(rings, j), south, at(rings, j + 1)});
    }
    return SurfaceMesh::from_soup(s);
}

/// A closed mesh of the torus (major radius R about z, tube radius r): a u x v grid.
SurfaceMesh torus_mesh(double R, double r, int nu, int nv) {
    TriangleSoup s;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
            s.points.push_back({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
        }
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>((i % nu) * nv + (j % nv)); };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            s.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            s.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return SurfaceMesh::from_soup(s);
}

/// Ratios estimate / exact at every vertex, sorted.
std::vector<double> ratios(const SurfaceMesh& m, const ImplicitSurface& exact) {
    const std::vector<double> lfs = mesh_feature_size(m);
    std::vector<double> out;
    for (Vertex v : m.vertices()) out.push_back(lfs[v.idx()] / exact.local_feature_size(m.position(v)));
    std::sort(out.begin(), out.end());
    return out;
}

void expect_close_to_exact(const std::vector<double>& r, const char* what) {
    ASSERT_FALSE(r.empty());
    const double median = r[r.size() / 2];
    EXPECT_GE(median, 0.7) << what;
    EXPECT_LE(median, 1.3) << what;
    const auto in = std::count_if(r.begin(), r.end(), [](double x) { return x >= 0.5 && x <= 2.0; });
    EXPECT_GE(static_cast<double>(in), 0.95 * static_cast<double>(r.size())) << what << ": median " << median;
}

TEST(SizeField, FeatureSizeOfAThinEllipsoid) {
    // Semi-axes (1, 1, 0.05): lfs is about the half-thickness over the flat sides, where the
    // curvature radius (up to 20) is no bound: only the inward ray sees it.
    const Ellipsoid e(Point3{0, 0, 0}, 1.0, 1.0, 0.05);
    expect_close_to_exact(ratios(ellipsoid_mesh(1.0, 1.0, 0.05, 120, 160), e), "thin ellipsoid");
}

TEST(SizeField, FeatureSizeOfAThinTorus) {
    // Tube radius 0.3 around a circle of radius 5: lfs = 0.3 everywhere (the core circle).
    const Torus t(Point3{0, 0, 0}, 5.0, 0.3);
    expect_close_to_exact(ratios(torus_mesh(5.0, 0.3, 400, 24), t), "torus (5, 0.3)");
}

TEST(SizeField, GradedSizeIsLipschitzAndBelowTheFeatureSize) {
    const SurfaceMesh m = ellipsoid_mesh(1.0, 1.0, 0.05, 60, 80);
    const std::vector<double> lfs = mesh_feature_size(m);
    const double rho = 0.4, L = 0.3, cap = 0.05;
    const std::vector<double> r = graded_size(m, lfs, rho, L, cap);
    std::size_t tight = 0;
    for (Vertex v : m.vertices()) {
        const double top = std::min(cap, rho * lfs[v.idx()]);
        EXPECT_LE(r[v.idx()], top);
        tight += r[v.idx()] == top;
    }
    EXPECT_GT(tight, 0u);
    for (Edge e : m.edges()) {
        const Halfedge h = SurfaceMesh::halfedge(e, 0);
        const Vertex a = m.from_vertex(h), b = m.to_vertex(h);
        EXPECT_LE(std::abs(r[a.idx()] - r[b.idx()]), L * distance(m.position(a), m.position(b)) * (1 + 1e-12));
    }
    // Without grading the size is min(cap, rho lfs) itself; with it, somewhere strictly less.
    const std::vector<double> raw = graded_size(m, lfs, rho, 1e9, cap);
    std::size_t lower = 0;
    for (Vertex v : m.vertices()) {
        EXPECT_DOUBLE_EQ(raw[v.idx()], std::min(cap, rho * lfs[v.idx()]));
        lower += r[v.idx()] < raw[v.idx()];
    }
    EXPECT_GT(lower, 0u);
}

TEST(SizeField, ElephantStartsWithItsThinPartsResolvedOnTheReference) {
    // elephant.off's trunk and ears are thinner than a third of the global R. With the size
    // field, the net and RefineVert's fixed point on the reference are as dense as r asks, so
    // Tri(0) resolves them before any Add: a start that refined by Adds on the global-R mesh
    // instead had Adds refused for folding it, self-intersections and inverted triangles at
    // t = 0.
    ScenarioOptions so;
    so.warp = "pulse";
    so.steps = 200;
    Scenario s = make_scenario(test::shared_data("meshes/elephant.off").string(), so);
    s.time_units = 0;
    DeformRunOptions ro;
    ro.params.size_factor = 0.4;
    ro.measure_every = 1;
    ro.check_invariants = true;
    const DeformRunReport r = run_deform(s, ro);
    ASSERT_EQ(r.log.size(), 1u);
    EXPECT_EQ(r.self_intersections, 0u);
    EXPECT_EQ(r.inverted, 0u);
    EXPECT_EQ(r.violations.count("add_folded"), 0u);
    EXPECT_EQ(r.invariant_failures, 0u);
    EXPECT_GE(r.worst_min_angle_deg, 10.0);
    // The field did refine: more vertices than the global-R start.
    DeformRunOptions global = ro;
    global.params.size_factor = 0;
    global.check_invariants = false;
    EXPECT_GT(r.init_vertices, run_deform(s, global).init_vertices);
}

}  // namespace
}  // namespace dynmesh
