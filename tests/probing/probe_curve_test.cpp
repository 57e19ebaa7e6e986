/// The 2D variant (spec §4.6, §7 test 9): closed planar curves give simple closed polygons,
/// every vertex with one edge in and one out, counter-clockwise around the object, checked by
/// check_probing against the curve.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/probing/check.hpp"
#include "dynmesh/probing/oracles2.hpp"
#include "dynmesh/probing/refine.hpp"

namespace dynmesh {
namespace {

ProbingOptions curve_options(const PlanarStarOracle& curve, double eps, double omega_radius) {
    ProbingOptions o;
    o.eps = eps;
    o.eps_S = curve.reach();
    o.omega = {{0, 0, 0}, omega_radius};
    o.interior_points = {curve.interior_point()};
    o.ground_truth = &curve;
    o.check_every = 50;
    return o;
}

double signed_area(const ProbingResult& r, const std::vector<std::uint32_t>& loop) {
    double a = 0;
    for (std::size_t k = 0; k + 1 < loop.size(); ++k) {
        const Point3 &p = r.mesh.points[loop[k]], &q = r.mesh.points[loop[k + 1]];
        a += p.x * q.y - q.x * p.y;
    }
    return a / 2;
}

/// The structure the polygons must have, measured here on the raw indices.
void expect_one_closed_loop(const ProbingResult& r) {
    ASSERT_EQ(r.polygons.size(), 1u);
    const auto& loop = r.polygons.front();
    ASSERT_GE(loop.size(), 4u);
    EXPECT_EQ(loop.front(), loop.back());
    const std::set<std::uint32_t> distinct(loop.begin(), loop.end() - 1);
    EXPECT_EQ(distinct.size(), loop.size() - 1);          // no vertex twice
    EXPECT_EQ(distinct.size(), r.mesh.points.size());     // every vertex on it
    EXPECT_TRUE(r.mesh.triangles.empty());
    for (const Point3& p : r.mesh.points) EXPECT_EQ(p.z, 0);
    EXPECT_GT(signed_area(r, loop), 0);  // counter-clockwise around O
}

TEST(ProbeCurve, CircleIsOneClosedPolygonWithChordsWithinTheBound) {
    const CircleOracle2 circle({0, 0}, 1, {.strict = true});
    const double eps = 0.05;
    const ProbingOptions o = curve_options(circle, eps, 1.5);
    const ProbingResult r = probe_curve(circle, o);
    expect_one_closed_loop(r);
    const CheckReport c = check_probing(r, circle, o, 2);
    EXPECT_TRUE(c.ok()) << c.problems.front();
    EXPECT_EQ(c.integer("euler"), 0);
    // Each edge is a chord with a disk of radius <= eps centred on the circle: it stays within
    // 1 - sqrt(1 - eps^2) of the circle.
    EXPECT_LE(c.figure("hausdorff"), 1 - std::sqrt(1 - eps * eps) + 1e-9);
    EXPECT_LE(c.figure("max_ball_radius"), eps);
    EXPECT_LE(c.figure("sample_gap"), 2 * eps);
    // Samples inserted by refinement are more than eps from the earlier ones.
    for (std::size_t i = 3; i < r.sample.size(); ++i)
        for (std::size_t j = 0; j < i; ++j) ASSERT_GT(distance(r.sample[i], r.sample[j]), eps) << i << " " << j;
    std::printf("circle eps %.3f: %zu vertices, %zu probes, %zu cells\n", eps, r.report.vertices, r.report.probes,
                r.report.cells_created);
}

/// With Omega wide enough to hold the outer medial axis of the star's concave parts, Voronoi
/// vertices outside the curve lie inside Omega: the device must reach them by detection.
TEST(ProbeCurve, StarUsesDetectionPathsAndKeepsTheInvariants) {
    const StarOracle2 star({0, 0}, 1, {.strict = true});
    const double eps = 0.02;
    const ProbingOptions o = curve_options(star, eps, 3);
    const ProbingResult r = probe_curve(star, o);
    expect_one_closed_loop(r);
    const CheckReport c = check_probing(r, star, o, 2);
    EXPECT_TRUE(c.ok()) << c.problems.front();
    EXPECT_LE(c.figure("hausdorff"), c.figure("hausdorff_bound"));
    EXPECT_GT(r.report.activations, 0u);
    EXPECT_EQ(r.report.detection_edges, 2 * r.report.activations);
    EXPECT_GT(r.report.segments_checked, 0u);
    EXPECT_LE(r.report.probes, 2 * r.report.voronoi_edges_created + r.report.probes_bootstrap);
    std::printf("star eps %.3f: %zu vertices, %zu probes, %zu activations, path %.3f\n", eps, r.report.vertices,
                r.report.probes, r.report.activations, r.report.path_length);
}

TEST(ProbeCurve, RunsAreDeterministicAndOmniscientAgrees) {
    const StarOracle2 star({0, 0}, 1);
    ProbingOptions o = curve_options(star, 0.03, 3);
    o.ground_truth = nullptr;
    const ProbingResult a = probe_curve(star, o), b = probe_curve(star, o);
    EXPECT_EQ(a.sample, b.sample);
    EXPECT_EQ(a.polygons, b.polygons);
    EXPECT_EQ(a.report.path_length, b.report.path_length);
    o.mode = ProbingMode::Omniscient;
    o.ground_truth = &star;
    const ProbingResult omni = probe_curve(star, o);
    expect_one_closed_loop(omni);
    EXPECT_NEAR(double(omni.report.vertices) / double(a.report.vertices), 1, 0.1);
}

TEST(ProbeCurve, RefusesPointsOffThePlane) {
    const CircleOracle2 circle({0, 0}, 1);
    ProbingOptions o = curve_options(circle, 0.05, 1.5);
    o.interior_points = {{0, 0, 0.1}};
    EXPECT_THROW((void)probe_curve(circle, o), InvalidInput);
    o = curve_options(circle, 0.05, 1.5);
    o.omega.center.z = 1;
    EXPECT_THROW((void)probe_curve(circle, o), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
