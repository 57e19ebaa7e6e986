#include "dynmesh/deform/ground_truth.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/metrics/hausdorff.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "scenario_cases.hpp"

namespace dynmesh {
namespace {

using namespace test;

TEST(GroundTruth, TheReferenceMeasuresAsExact) {
    for (const std::string& key : all_cases()) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        GroundTruth g(s);
        for (double t : {0.0, 0.3 * kSteps, 0.5 * kSteps}) {
            g.set_time(t);
            const SurfaceMesh& m = g.reference();
            MeasureOptions mo;
            mo.self_intersections = true;
            const FrameMetrics f =
                g.measure(m, identity_vertex_pool(m), all_pool(s), mo);
            EXPECT_EQ(f.t, t);
            EXPECT_EQ(f.vertices, s.pool_size());
            EXPECT_EQ(f.faces, s.reference.n_faces());
            EXPECT_EQ(f.samples, s.pool_size());
            EXPECT_LT(f.hausdorff, 1e-12 * s.length_scale);
            EXPECT_LT(f.hausdorff_over_h, 1e-9);
            EXPECT_EQ(f.inverted, 0u);
            EXPECT_EQ(f.self_intersections, 0u);
            EXPECT_LT(f.normal_dev_mean_deg, 6.0);
            EXPECT_LT(f.normal_dev_max_deg, 60.0);
            EXPECT_GT(f.h, 0);
            EXPECT_GT(f.R_over_h, 0.5);
            EXPECT_GT(f.min_edge_angle_deg, 90.0);
            EXPECT_GT(f.min_angle_deg, 0.0);
            EXPECT_GE(f.max_radius_edge, 1 / std::sqrt(3.0));
        }
    }
}

TEST(GroundTruth, MeshOfTheInitialSampleIsCloseToSigma) {
    const Scenario& s = cached("stretch");
    const auto p0 = pool_positions(s, 0.0, s.initial);
    SurfaceMesh mesh = restricted_delaunay(p0, *s.surface0);
    ASSERT_EQ(mesh.n_vertices(), s.initial.size());
    const std::vector<std::uint32_t> vertex_pool = s.initial;  // RDT keeps the input order
    GroundTruth g(s);
    for (double t : {0.0, 0.25 * kSteps, 0.5 * kSteps}) {
        SCOPED_TRACE(t);
        g.set_time(t);
        const auto pt = pool_positions(s, t, s.initial);
        for (const Vertex v : mesh.vertices()) mesh.position(v) = pt[v.idx()];
        const FrameMetrics f = g.measure(mesh, vertex_pool, s.initial);
        EXPECT_GT(f.hausdorff, 0);
        EXPECT_LT(f.hausdorff_over_h, 1.0);
        EXPECT_EQ(f.inverted, 0u);
        EXPECT_LT(f.normal_dev_mean_deg, 10.0);
        if (t == 0.0) {
            // Restricted Delaunay triangles have circumradius <= h (up to the probing).
            EXPECT_LT(f.R_over_h, 1.2);
            EXPECT_NEAR(f.h, s.h0, 1e-12);
        }
        EXPECT_EQ(measure_frame(s, t, mesh, vertex_pool, s.initial).hausdorff, f.hausdorff);
    }
    // An inverted mesh is reported as such.
    TriangleSoup soup = mesh.to_soup();
    for (auto& tr : soup.triangles) std::swap(tr[1], tr[2]);
    const FrameMetrics f =
        measure_frame(s, 0.0, SurfaceMesh::from_soup(soup), vertex_pool, s.initial);
    EXPECT_EQ(f.inverted, f.faces);
    EXPECT_GT(f.normal_dev_mean_deg, 150.0);
}

TEST(GroundTruth, InvertedMeansFacingAwayAtTheCornersAndAtTheNearestSurface) {
    // fandisk.off stretched x3: at sharp edges the true normals of the vertices are averages of
    // their faces', and stretched 3:1 some faces of Sigma(t) itself point away from the
    // averages at their corners (a test against the vertex normals counts 2 faces of the
    // carried reference). Counted only where a face also points away from the surface nearest
    // to its middle, neither the reference nor the carried input has an inverted face, and the
    // input with its orientation reversed has nothing else.
    ScenarioOptions o;
    o.steps = 200;
    o.warp = "stretch";
    const Scenario s = make_scenario(shared_data("meshes/fandisk.off").string(), o);
    ASSERT_TRUE(s.input_mesh.has_value());
    GroundTruth g(s);
    g.set_time(100);  // the peak of the stretch
    const SurfaceMesh& ref = g.reference();
    const FrameMetrics fr = g.measure(ref, identity_vertex_pool(ref), all_pool(s));
    EXPECT_EQ(fr.inverted, 0u);
    EXPECT_FALSE(fr.first_inverted.is_valid());  // nor names one (the report's first_inverted)
    SurfaceMesh input = *s.input_mesh;  // its vertex i is pool point i
    for (const Vertex v : input.vertices()) input.position(v) = ref.position(Vertex(v.idx()));
    const FrameMetrics f = g.measure(input, identity_vertex_pool(input), all_pool(s));
    EXPECT_EQ(f.inverted, 0u);
    EXPECT_FALSE(f.first_inverted.is_valid());
    EXPECT_GT(f.normal_dev_max_deg, 90.0);  // the vertex normals disagree with some faces
    TriangleSoup soup = input.to_soup();
    for (auto& tr : soup.triangles) std::swap(tr[1], tr[2]);
    const SurfaceMesh reversed = SurfaceMesh::from_soup(soup);
    const FrameMetrics r = g.measure(reversed, identity_vertex_pool(reversed), all_pool(s));
    EXPECT_EQ(r.inverted, reversed.n_faces());
    EXPECT_EQ(r.first_inverted, *reversed.faces().begin());
}

TEST(GroundTruth, HausdorffEqualsTheAabbTreeImplementation) {
    // The local search of measure() against metrics/hausdorff.hpp at face resolution 1 (the
    // same sample points), on meshes of a subset carried to several times, including a
    // bad one (the P(0) mesh carried to the peak of the bend).
    for (const std::string key : {"bend", "twist", "mesh+bend"}) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        SurfaceMesh mesh;
        std::vector<std::uint32_t> vertex_pool;
        if (s.surface0) {
            mesh = restricted_delaunay(pool_positions(s, 0.0, s.initial), *s.surface0);
            vertex_pool = s.initial;
        } else {  // the reference itself, with every 50th vertex pushed off the surface
            mesh = s.reference;
            vertex_pool = identity_vertex_pool(mesh);
        }
        GroundTruth g(s);
        for (double t : {0.0, 0.25 * kSteps, 0.5 * kSteps}) {
            SCOPED_TRACE(t);
            g.set_time(t);
            SurfaceMesh m = mesh;
            for (const Vertex v : m.vertices())
                m.position(v) = g.reference().position(Vertex(vertex_pool[v.idx()]));
            if (!s.surface0) {
                for (std::uint32_t i = 0; i < m.vertices_size(); i += 50)
                    m.position(Vertex(i)) += s.normals0[i] * (0.01 * s.length_scale);
            }
            const FrameMetrics f = g.measure(m, vertex_pool, s.initial);
            HausdorffOptions ho;
            ho.face_resolution = 1;
            const double expected = hausdorff_distance(m, g.reference(), ho);
            EXPECT_GT(expected, 0);
            EXPECT_NEAR(f.hausdorff, expected, 1e-9 * expected);
        }
    }
}

TEST(GroundTruth, RejectsBadArguments) {
    const Scenario& s = cached("pulse");
    const SurfaceMesh& m = s.reference;
    std::vector<std::uint32_t> short_pool(m.vertices_size() - 1, 0);
    expect_invalid([&] { (void)measure_frame(s, 0.0, m, short_pool, s.initial); }, "vertex_pool");
    std::vector<std::uint32_t> bad = identity_vertex_pool(m);
    bad[5] = static_cast<std::uint32_t>(s.pool_size() + 3);
    expect_invalid([&] { (void)measure_frame(s, 0.0, m, bad, s.initial); }, "pool index");
    const std::vector<std::uint32_t> bad_live{static_cast<std::uint32_t>(s.pool_size())};
    expect_invalid(
        [&] { (void)measure_frame(s, 0.0, m, identity_vertex_pool(m), bad_live); },
        "live pool index");
}

TEST(GroundTruth, FlattenNamesMatchThePlotScript) {
    FrameMetrics f;
    f.R_over_h = 1.5;
    const auto v = flatten(f);
    ASSERT_EQ(v.size(), 17u);
    EXPECT_EQ(v[0].first, "t");
    bool found = false;
    for (const auto& [k, x] : v)
        if (k == "R_over_h") found = (x == 1.5);
    EXPECT_TRUE(found);
}

}  // namespace
}  // namespace dynmesh
