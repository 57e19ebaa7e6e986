/// Spec §7 tests 3, 5, 6, 8 and the shapes: every run is checked by check_probing
/// against the object's ground truth (closed 2-manifold, the object's Euler characteristic and
/// components, every ball ≤ ε, a 2ε-sample, Hausdorff within 4.5·diam·ε²/ε_S²), with the safety
/// monitor on (zero unsafe moves: a violation would throw) and the invariants checked during
/// the run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "dynmesh/probing/check.hpp"
#include "dynmesh/probing/device.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "dynmesh/probing/refine.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

struct ProbeRun {
    ProbingOptions options;
    ProbingResult result;
    CheckReport check;
};

ProbeRun probe(const ProbeObject& object, const std::vector<Point3>& interior, const Ball& omega, double eps,
               double eps_S, std::size_t check_every, ProbingMode mode = ProbingMode::Device,
               bool allow_unguaranteed = false) {
    ProbeRun run;
    ProbingOptions& o = run.options;
    o.allow_unguaranteed = allow_unguaranteed;
    o.eps = eps;
    o.eps_S = eps_S;
    o.omega = omega;
    o.interior_points = interior;
    o.ground_truth = &object;
    o.check_every = check_every;
    o.mode = mode;
    run.result = probe_surface(object, o);
    run.check = check_probing(run.result, object, o, 3);
    const ProbingReport& p = run.result.report;
    std::printf("eps %.4f: %zu vertices, %zu probes (%.1f per vertex, %zu inferred), %zu cells, %zu retained, "
                "%zu detection / %zu positioning edges, path %.2f, exterior %.2f, Hausdorff %.2e (bound %.2e), "
                "%.2f s\n",
                eps, p.vertices, p.probes, double(p.probes) / double(std::max<std::size_t>(p.vertices, 1)),
                p.probes_inferred, p.cells_created, p.nodes_retained, p.detection_edges, p.positioning_edges,
                p.path_length, p.exterior_path_length, run.check.figure("hausdorff"), run.check.figure("hausdorff_bound"), p.seconds);
    return run;
}

/// The checks every run must pass, and the cost identities of spec §7 test 6.
void expect_guarantees(const ProbeRun& r) {
    EXPECT_TRUE(r.check.ok()) << r.check.problems.size() << " problems, first: " << r.check.problems.front();
    EXPECT_TRUE(r.check.flag("closed_manifold"));
    EXPECT_LE(r.check.figure("max_ball_radius"), r.options.eps);
    EXPECT_LE(r.check.figure("sample_gap"), 2 * r.options.eps);
    EXPECT_LE(r.check.figure("hausdorff"), r.check.figure("hausdorff_bound"));
    const ProbingReport& p = r.result.report;
    EXPECT_EQ(p.grazing_hits, 0u);
    // Each directed edge is probed at most once: probes ≤ 2 × edges created + bootstrap.
    EXPECT_LE(p.probes, 2 * p.voronoi_edges_created + p.probes_bootstrap);
    // Detection walks each activated node's edge forward and back.
    EXPECT_EQ(p.detection_edges, 2 * p.activations);
    if (r.options.mode == ProbingMode::Device) {
        // Every Voronoi edge travelled is at least one move the safety monitor verified.
        EXPECT_GE(p.segments_checked, p.detection_edges + p.positioning_edges);
    }
    // Angles: a refined sample is more than eps from every other (its ball was empty and
    // larger than eps) and every facet's circumradius is at most its ball's radius <= eps, so
    // a triangle whose shortest edge is not between two bootstrap samples has no angle below
    // asin(1/2) = 30 degrees.
    if (p.reinitialisations == 0) {
        const auto& m = r.result.mesh;
        const auto& E = r.result.sample;
        const auto bootstrap = [&](const Point3& q) {
            return std::find(E.begin(), E.begin() + std::ptrdiff_t(p.bootstrap_samples), q) !=
                   E.begin() + std::ptrdiff_t(p.bootstrap_samples);
        };
        double worst = 180;
        for (const auto& t : m.triangles) {
            const Point3 v[3] = {m.points[t[0]], m.points[t[1]], m.points[t[2]]};
            int shortest = 0;
            for (int k = 1; k < 3; ++k)
                if (distance(v[k], v[(k + 1) % 3]) < distance(v[shortest], v[(shortest + 1) % 3])) shortest = k;
            if (bootstrap(v[shortest]) && bootstrap(v[(shortest + 1) % 3])) continue;
            for (int k = 0; k < 3; ++k) {
                const Vec3 e1 = v[(k + 1) % 3] - v[k], e2 = v[(k + 2) % 3] - v[k];
                worst = std::min(worst, std::atan2(norm(cross(e1, e2)), dot(e1, e2)) * 180 / 3.14159265358979323846);
            }
        }
        EXPECT_GE(worst, 30 - 1e-6);
    }
}

/// Spec §7 test 5 with §10.5: the torus exercises the paths (detection, positioning, retained
/// nodes); the invariants hold after every 250th insertion; the topology is the torus's.
TEST(ProbeShapes, TorusHasGenusOneAndUsesPaths) {
    const TorusOracle torus(Torus({0, 0, 0}, 1, 0.35), {.strict = true});
    const ProbeRun r = probe(torus, {torus.shape().interior_point()}, {{0, 0, 0}, 1.5}, 0.03, 0.35, 250);
    expect_guarantees(r);
    EXPECT_EQ(r.check.integer("euler"), 0);
    EXPECT_GT(r.result.report.detection_edges, 0u);
    EXPECT_GT(r.result.report.positioning_edges, 0u);
    EXPECT_GT(r.result.report.nodes_retained, 0u);
    // The empirical regression bound of §10.5 (CGAL's Chew gives 0.00127 here).
    EXPECT_LE(r.check.figure("hausdorff"), 0.03 * 0.03 / 0.35);
}

TEST(ProbeShapes, EllipsoidIsASphereTopologically) {
    const EllipsoidOracle ell(Ellipsoid({0, 0, 0}, 1, 0.8, 0.6), {.strict = true});
    const ProbeRun r = probe(ell, {{0, 0, 0}}, {{0, 0, 0}, 1.2}, 0.03, ell.reach(), 500);
    expect_guarantees(r);
    EXPECT_EQ(r.check.integer("euler"), 2);
    EXPECT_LE(r.check.figure("hausdorff"), 0.03 * 0.03 / ell.reach());
}

TEST(ProbeShapes, GenusTwoSurface) {
    const Genus2Oracle g({.strict = true});
    const ProbeRun r = probe(g, {Genus2Oracle::interior_point()}, {{0, 0, 0}, 3.2}, 0.0225, g.reach(), SIZE_MAX);
    expect_guarantees(r);
    EXPECT_EQ(r.check.integer("euler"), -2);
    EXPECT_GT(r.result.report.detection_edges, 0u);
}

/// Spec §8.3: two components, one interior point each, each component a sphere.
TEST(ProbeShapes, TwoDisjointBalls) {
    const BallsOracle balls({{{-0.8, 0, 0}, 0.5}, {{0.8, 0.1, 0}, 0.5}}, {.strict = true});
    const ProbeRun r = probe(balls, {{-0.8, 0, 0}, {0.8, 0.1, 0}}, {{0, 0, 0}, 1.6}, 0.025, balls.reach(), 1000);
    expect_guarantees(r);
    EXPECT_EQ(r.check.integer("components"), 2);
    EXPECT_EQ(r.check.integer("euler"), 4);
    EXPECT_EQ(r.result.report.reinitialisations, 0u);
}

/// Spec §8.3's recovery: seen from the boundary of Omega, the big ball hides the small one,
/// so the first probe toward the small ball's interior point hits the big ball and its seed
/// repeats the big ball's (dropped). The small ball, which no Voronoi edge of the big ball's
/// sample happens to cross, is found by bootstrapping again from other directions.
TEST(ProbeShapes, AComponentHiddenBehindAnotherIsFoundAgain) {
    const BallsOracle balls({{{0, 0, 0}, 0.3}, {{1.3, 0, 0}, 0.1}}, {.strict = true});
    ProbingOptions o;
    o.eps = 0.03;
    o.eps_S = balls.reach();
    o.allow_unguaranteed = true;  // reach 0.1: a coarse run suffices to see the components
    o.omega = {{2, 0, 0}, 2.5};
    o.interior_points = {{0, 0, 0}, {1.3, 0, 0}};
    o.ground_truth = &balls;
    const ProbingResult r = probe_surface(balls, o);
    const CheckReport c = check_probing(r, balls, o, 3);
    EXPECT_GE(r.report.reinitialisations, 1u);
    EXPECT_EQ(c.integer("components"), 2);
    EXPECT_EQ(c.integer("euler"), 4);
    EXPECT_TRUE(c.flag("closed_manifold"));
    EXPECT_TRUE(r.problems.empty()) << r.problems.front();
}

/// A real scan through the mesh oracle (CGAL AABB tree). Nearly flat cells put Voronoi
/// vertices 1e11-1e12 away; their edges must be taken on the facet's dual line anchored inside
/// Omega, or kept hits drift off their edge and their balls hold samples.
TEST(ProbeShapes, RealMeshesThroughTheMeshOracle) {
    struct Case {
        const char* file;
        double eps_S, eps;
    };
    for (const Case& c : {Case{"meshes/blobby.off", 0.1, 0.008}, Case{"meshes/eight.off", 0.1, 0.009}}) {
        SCOPED_TRACE(c.file);
        const ProbeSetup setup = make_probe_object(test::shared_data(c.file).string(), {.strict = true});
        const ProbeRun r = probe(*setup.object, setup.interior_points, setup.omega, c.eps, c.eps_S, 2000);
        expect_guarantees(r);
        EXPECT_EQ(r.check.integer("euler"), setup.object->euler_characteristic());
    }
}

/// A quick run on the torus (1, 0.35): eps 0.06, outside the guarantee.
ProbingOptions coarse_torus_options(const TorusOracle& torus) {
    ProbingOptions o;
    o.eps = 0.06;
    o.eps_S = 0.35;
    o.allow_unguaranteed = true;
    o.omega = {{0, 0, 0}, 1.5};
    o.interior_points = {torus.shape().interior_point()};
    return o;
}

/// Spec §3.5, §5.4: positioning through the lowest common ancestor and via ∂Ω move the device
/// differently (both checked by the safety monitor, which walks every segment) but probe the
/// same edges from the same places, so they give the same sample; the LCA travels less.
TEST(ProbeShapes, LcaAndBoundaryPositioningGiveTheSameMesh) {
    const TorusOracle torus(Torus({0, 0, 0}, 1, 0.35));
    ProbingOptions o = coarse_torus_options(torus);
    o.ground_truth = &torus;
    const ProbingResult lca = probe_surface(torus, o);
    o.positioning = ProbingPositioning::Boundary;
    const ProbingResult boundary = probe_surface(torus, o);
    EXPECT_TRUE(lca.problems.empty()) << lca.problems.front();
    EXPECT_TRUE(boundary.problems.empty()) << boundary.problems.front();
    EXPECT_EQ(lca.sample, boundary.sample);
    EXPECT_EQ(lca.mesh.triangles, boundary.mesh.triangles);
    EXPECT_EQ(lca.report.probes, boundary.report.probes);
    EXPECT_EQ(lca.report.detection_edges, boundary.report.detection_edges);
    EXPECT_LT(lca.report.positioning_edges, boundary.report.positioning_edges);
    EXPECT_LT(lca.report.path_length, boundary.report.path_length);
    EXPECT_LE(lca.report.exterior_path_length, boundary.report.exterior_path_length);
    EXPECT_GT(lca.report.segments_checked, 0u);
}

/// Spec §7 test 7: two runs give the same sample, facets and counters.
TEST(ProbeShapes, RunsAreDeterministic) {
    const TorusOracle torus(Torus({0, 0, 0}, 1, 0.35));
    ProbingOptions o = coarse_torus_options(torus);
    const ProbingResult a = probe_surface(torus, o), b = probe_surface(torus, o);
    EXPECT_EQ(a.sample, b.sample);
    EXPECT_EQ(a.mesh.points, b.mesh.points);
    EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
    EXPECT_EQ(a.report.probes, b.report.probes);
    EXPECT_EQ(a.report.cells_created, b.report.cells_created);
    EXPECT_EQ(a.report.path_length, b.report.path_length);
    EXPECT_EQ(a.report.exterior_path_length, b.report.exterior_path_length);
}

/// The omniscient baseline: the same refinement without a device gives the same guarantees
/// and a mesh of the same size; it never moves.
TEST(ProbeShapes, OmniscientBaselineMeshesTheSameSurface) {
    const TorusOracle torus(Torus({0, 0, 0}, 1, 0.35), {.strict = true});
    const ProbeRun dev = probe(torus, {torus.shape().interior_point()}, {{0, 0, 0}, 1.5}, 0.04, 0.35, SIZE_MAX,
                               ProbingMode::Device, true);
    const ProbeRun omni = probe(torus, {torus.shape().interior_point()}, {{0, 0, 0}, 1.5}, 0.04, 0.35, SIZE_MAX,
                                ProbingMode::Omniscient, true);
    EXPECT_TRUE(omni.check.ok()) << omni.check.problems.front();
    EXPECT_EQ(omni.check.integer("euler"), 0);
    EXPECT_EQ(omni.result.report.path_length, 0);
    EXPECT_EQ(omni.result.report.exterior_path_length, 0);
    EXPECT_EQ(omni.result.report.detection_edges + omni.result.report.positioning_edges, 0u);
    const double ratio = double(omni.result.report.vertices) / double(dev.result.report.vertices);
    EXPECT_NEAR(ratio, 1.0, 0.1);
}

/// Safety: a monitor that believes a part of free space is solid makes the run stop with an
/// UnsafeMove naming the segment (the device does travel through that region).
TEST(ProbeShapes, TheMonitorStopsTheRunAtAnUnsafeMove) {
    class LyingTruth final : public GroundTruth {
    public:
        explicit LyingTruth(const TorusOracle& t) : t_(t) {}
        bool is_free(const Point3& p) const override { return t_.is_free(p); }
        bool segment_is_free(const Point3& a, const Point3& b) const override {
            // The torus's hole (|x|, |y| < 0.3 near z = 0) declared solid.
            const auto in_hole = [](const Point3& p) {
                return std::fabs(p.x) < 0.3 && std::fabs(p.y) < 0.3 && std::fabs(p.z) < 0.1;
            };
            for (int k = 0; k <= 16; ++k)
                if (in_hole(a + (k / 16.0) * (b - a))) return false;
            return t_.segment_is_free(a, b);
        }
        double distance(const Point3& p) const override { return t_.distance(p); }
        std::vector<Point3> sample_surface(double s) const override { return t_.sample_surface(s); }
        double reach() const override { return t_.reach(); }
        double diameter() const override { return t_.diameter(); }
        double area() const override { return t_.area(); }
        int components() const override { return 1; }
        int euler_characteristic() const override { return 0; }

    private:
        const TorusOracle& t_;
    };
    const TorusOracle torus(Torus({0, 0, 0}, 1, 0.35));
    const LyingTruth lying(torus);
    ProbingOptions o = coarse_torus_options(torus);
    o.ground_truth = &lying;
    try {
        (void)probe_surface(torus, o);
        FAIL() << "the run did not stop";
    } catch (const UnsafeMove& e) {
        EXPECT_NE(std::string(e.what()).find(" - "), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace dynmesh
