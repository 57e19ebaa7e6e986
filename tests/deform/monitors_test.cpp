// Diagnostics that must never be silent, and repairs that must not change the topology: the
// elephant bent keeps its Euler characteristic without a rebuild from scratch (spec §10.4), a
// global flip that leaves a non-empty diametric ball says so, and an update that coarsens the
// mesh is reported (spec §8.2, §9 P5).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dynmesh/deform/deforming_mesh.hpp"
#include "dynmesh/deform/run.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "flat_sheets.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

std::size_t count_kind(const std::vector<ViolationRecord>& v, const std::string& kind) {
    return static_cast<std::size_t>(std::count_if(
        v.begin(), v.end(), [&](const ViolationRecord& r) { return std::string(to_string(r.kind)) == kind; }));
}

TEST(DeformMonitors, ElephantBendKeepsItsEulerCharacteristicWithoutARebuild) {
    // The bend of `dynmesh deform elephant.off` at 8x the default speed (steps 50): its
    // emergency rebuild from the advancing front once changed the Euler characteristic
    // -4 -> -6 at t = 7 and the run carried on; later such rebuilds were rolled back. The
    // first 16 time units fold the mesh (the monitors trip from t = 5 on); no update may
    // rebuild it now.
    ScenarioOptions so;
    so.warp = "bend";
    so.steps = 50;
    Scenario s = make_scenario(test::shared_data("meshes/elephant.off").string(), so);
    s.time_units = 16;
    MeshCheckOptions co;
    co.require_closed = true;
    co.check_degenerate = false;
    const long long euler = check_mesh(*s.input_mesh, co).integer("euler");
    ASSERT_EQ(euler, -4);
    DeformRunOptions ro;
    ro.measure_every = 0;
    ro.measure.self_intersections = false;
    ro.check_invariants = true;
    std::vector<long long> seen;
    ro.on_frame = [&](const DeformFrame& f) {
        const CheckReport mc = check_mesh(f.mesh->mesh(), co);
        EXPECT_TRUE(mc.ok()) << "t = " << f.t << ": " << mc.summary();
        seen.push_back(mc.integer("euler"));
    };
    const DeformRunReport r = run_deform(s, ro);
    ASSERT_EQ(seen.size(), 17u);
    for (std::size_t t = 0; t < seen.size(); ++t) EXPECT_EQ(seen[t], euler) << "t = " << t;
    // The motion did trip the monitors (the reproduction is still there), and nothing was
    // rebuilt or rolled back.
    EXPECT_GE(r.emergency_updates + r.violations.count("edge_angle_below_90"), 1u)
        << "no monitor tripped: the reproduction is gone";
    EXPECT_EQ(r.rebuilds, 0u);
    EXPECT_EQ(r.rollbacks, 0u);
    EXPECT_EQ(r.violations.count("rebuild"), 0u);
    EXPECT_EQ(r.violations.count("rollback"), 0u);
}

TEST(DeformMonitors, GlobalFlipReportsTheBallsItCannotEmpty) {
    // A sphere squashed to 2 % of its height: the diametric balls of the top triangles reach
    // the vertices of the bottom, which no flip can remove.
    SurfaceMesh m = test::icosphere(3);
    std::vector<Point3> pos;
    for (Vertex v : m.vertices()) {
        Point3& p = m.position(v);
        p.z *= 0.02;
        pos.push_back(p);
    }
    DeformOptions params;
    params.lambda = 1e-3;
    params.h0 = 0.1;
    params.init_refine = false;
    InitialSurface init;
    init.mesh = &m;
    for (Vertex v : m.vertices()) init.vertex_samples.push_back(static_cast<SampleId>(v.idx()));
    const DeformingMesh dm(pos, params, init);
    InvariantOptions io;
    io.empty_balls_soft = true;
    const CheckReport report = dm.check_invariants(io);
    const auto nonempty_balls = static_cast<std::size_t>(report.integer("nonempty_balls"));
    ASSERT_GT(nonempty_balls, 0u);
    ASSERT_EQ(report.notes.size(), 1u);  // the first such ball, as a note: the check is soft
    for (const std::string& p : report.problems) EXPECT_EQ(p.find("diametric ball"), std::string::npos) << p;
    ASSERT_EQ(count_kind(dm.violations(), "non_empty_ball"), 1u);  // one global flip at t = 0
    const ViolationRecord& v = *std::find_if(dm.violations().begin(), dm.violations().end(),
                                             [](const ViolationRecord& r) { return r.kind == Violation::NonEmptyBall; });
    EXPECT_EQ(v.t, 0);
    EXPECT_NE(v.detail.find(std::to_string(nonempty_balls) + " diametric balls"), std::string::npos) << v.detail;
    EXPECT_NE(v.detail.find("triangle ("), std::string::npos) << v.detail;
    EXPECT_EQ(dm.init_report().nonempty_balls, nonempty_balls);
    EXPECT_EQ(dm.init_report().first_nonempty_ball, report.notes.front());
    // The check can be turned off (only a flip loop at its cap is then reported).
    params.verify_balls = false;
    const DeformingMesh quiet(pos, params, init);
    EXPECT_EQ(count_kind(quiet.violations(), "non_empty_ball"), 0u);
    EXPECT_EQ(quiet.init_report().nonempty_balls, nonempty_balls);  // the t = 0 check still counts
}

TEST(DeformMonitors, TheUpdatesBallCountFollowsVerticesIntoBallsOfTrianglesThatDidNotMove) {
    // An update scans again only the diametric balls that may have changed since the last
    // scan. Here the middle of a flat ellipsoid's lower sheet is pushed up, over eight units,
    // to just under the upper sheet, which stays still: the balls of the upper triangles come
    // to hold vertices of the lower sheet although those triangles never changed; then, in
    // one unit, it goes back and leaves those balls again. The samples
    // are mirrored in x and in y, so that the motion has no best-fit turn (which would move
    // every sample). After every update, the count it reports is that of a scan of every
    // ball.
    const Ellipsoid flat(Point3{0, 0, 0}, 1.0, 1.0, 0.35);
    std::vector<Point3> P0;
    for (const Point3& p : flat.sample_uniform(1500, 29))
        for (const double sx : {1.0, -1.0})
            for (const double sy : {1.0, -1.0}) P0.push_back(Point3{sx * p.x, sy * p.y, p.z});
    DeformOptions params;
    params.lambda = 1e-9;
    params.h0 = 0.08;
    params.emergency_steps = false;
    DeformingMesh dm(P0, params, {.surface = &flat});
    InvariantOptions io;
    io.empty_balls_soft = true;
    std::size_t most = 0, last = 0;
    for (int t = 1; t <= 10; ++t) {
        const double f = t <= 8 ? t / 8.0 : 0.0;
        const std::vector<Point3> P = test::pushed_under(P0, f, 0.03);
        dm.advance(t, P);
        const DeformUpdateReport u = dm.update();
        std::size_t reported = 0;
        for (const ViolationRecord& v : u.violations)
            if (v.kind == Violation::NonEmptyBall && v.detail.find(" diametric balls hold a vertex") != std::string::npos)
                reported = std::stoul(v.detail);
        const auto full = static_cast<std::size_t>(dm.check_invariants(io).integer("nonempty_balls"));
        EXPECT_EQ(reported, full) << "t = " << t;
        most = std::max(most, full);
        last = full;
    }
    EXPECT_GT(most, 20u);
    EXPECT_LT(last, most / 4);
}

TEST(DeformMonitors, DeletingACapCoarsensTheMeshAndSaysSo) {
    // Deleting every sample of a cap leaves a hole that only large triangles can span: R
    // grows far beyond 2x and Decimation coarsens the whole sphere.
    const std::vector<Point3> P0 = Sphere(Point3{0, 0, 0}, 1.0).sample_uniform(4000, 41);
    DeformOptions params;
    params.lambda = 1e-4;
    params.h0 = 0.07;
    const Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformingMesh dm(P0, params, {.surface = &sphere});
    dm.advance(1, P0);
    for (SampleId id = 0; id < P0.size(); ++id)
        if (P0[id].z > 0.6) dm.queue_deletion(id);
    const std::size_t before = dm.mesh().n_vertices();
    const DeformUpdateReport u = dm.update();
    ASSERT_GT(u.R_after, 2 * u.R_before);
    EXPECT_EQ(u.vertices_before, before);
    ASSERT_EQ(count_kind(u.violations, "coarsened"), 1u);
    const auto it = std::find_if(u.violations.begin(), u.violations.end(),
                                 [](const ViolationRecord& r) { return r.kind == Violation::Coarsened; });
    EXPECT_EQ(it->t, 1);
    EXPECT_NE(it->detail.find("vertices " + std::to_string(before) + " -> " + std::to_string(u.vertices)),
              std::string::npos)
        << it->detail;
    // An update that changes nothing is not reported.
    dm.advance(2, P0);
    EXPECT_EQ(count_kind(dm.update().violations, "coarsened"), 0u);
}

}  // namespace
}  // namespace dynmesh
