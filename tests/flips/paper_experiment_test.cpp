// Acceptance checks of the edge-flip digest (§7) on the paper's inputs: 10K uniform samples
// of the unit sphere and of the torus R = 5, r = 3, meshed by restricted Delaunay, worsened
// and smoothed; and real meshes from ../shared/data.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>

#include "dynmesh/deform/snapshot.hpp"
#include "dynmesh/flips/diagnostics.hpp"
#include "dynmesh/flips/experiment.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/metrics/self_intersection.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

struct PaperCase {
    std::unique_ptr<ImplicitSurface> surface;
    double normal_mean, dihedral_mean, normal_max, dihedral_max, tolerance;
    long long euler;
};

std::vector<PaperCase> paper_cases() {
    std::vector<PaperCase> v;
    v.push_back({std::make_unique<Sphere>(Point3{0, 0, 0}, 1.0), 1.5, 1.4, 3.8, 5.3, 0.3, 2});
    v.push_back({std::make_unique<Torus>(Point3{0, 0, 0}, 5.0, 3.0), 2.6, 2.6, 15.8, 16.0, 0.5, 0});
    return v;
}

TEST(PaperExperiment, TablesWithinTolerance) {
    for (const PaperCase& c : paper_cases()) {
        for (std::uint64_t seed : {1u, 2u}) {
            const std::string ctx = c.surface->spec() + " seed " + std::to_string(seed);
            const SurfaceMesh mesh = restricted_delaunay(c.surface->sample_uniform(10000, seed), *c.surface);
            SmoothingExperimentOptions opt;
            opt.surface = c.surface.get();
            opt.worsen.seed = seed;
            SurfaceMesh smoothed;
            const auto r = run_smoothing_experiment(mesh, opt, nullptr, &smoothed);
            ASSERT_TRUE(r.flip.converged) << ctx;
            // Check 8: smoothed rows near the paper's; worsened rows clearly worse.
            EXPECT_NEAR(r.smoothed.normal_dev_deg->mean, c.normal_mean, c.tolerance) << ctx;
            EXPECT_NEAR(r.smoothed.dihedral_dev_deg.mean, c.dihedral_mean, c.tolerance) << ctx;
            EXPECT_NEAR(r.smoothed.normal_dev_deg->max, c.normal_max, 0.5 * c.normal_max) << ctx;
            EXPECT_NEAR(r.smoothed.dihedral_dev_deg.max, c.dihedral_max, 0.5 * c.dihedral_max) << ctx;
            EXPECT_LE(r.worsened.dihedral_dev_deg.max, 60.0 + 1e-9) << ctx;
            EXPECT_GE(r.worsened.dihedral_dev_deg.mean, 2.0 * r.smoothed.dihedral_dev_deg.mean) << ctx;
            EXPECT_GE(r.worsened.normal_dev_deg->mean, 2.0 * r.smoothed.normal_dev_deg->mean) << ctx;
            EXPECT_LE(r.smoothed.dihedral_dev_deg.mean, 1.05 * r.initial.dihedral_dev_deg.mean) << ctx;
            EXPECT_LE(r.smoothed.normal_dev_deg->mean, 1.05 * r.initial.normal_dev_deg->mean) << ctx;
            // P10: the flips essentially undo the worsening.
            EXPECT_GE(r.shared_edge_fraction, 0.99) << ctx;
            // Check 5: integrity, no self-intersection.
            const auto chk = check_mesh(smoothed, {.require_closed = true});
            EXPECT_TRUE(chk.ok()) << ctx << chk.summary();
            EXPECT_EQ(chk.integer("euler"), c.euler) << ctx;
            EXPECT_EQ(count_self_intersections(smoothed), 0u) << ctx;
            // Check 6: post-conditions; check 10: the two rules nearly agree.
            const auto d = flip_diagnostics(smoothed, FlipRule::AngleDef3);
            EXPECT_EQ(d.flippable, 0u) << ctx;
            EXPECT_LE(double(d.illegal), 0.001 * double(d.edges)) << ctx;
            if (c.euler == 2) {
                EXPECT_EQ(d.illegal, 0u) << ctx;
            }
            EXPECT_LE(double(d.nonempty_balls), 0.01 * double(d.faces)) << ctx;
            const auto dd = flip_diagnostics(smoothed, FlipRule::DiametricBall);
            EXPECT_LE(double(dd.flippable), 0.01 * double(dd.edges)) << ctx;
        }
    }
}

// Table 3: a snapshot of the boomerang deformation (at its most bent time) worsened and
// smoothed; dihedral statistics only (no true normals). The paper's shape is not available,
// so the check is the digest's §7.8 in relative form: the smoothed row within 5% of the
// snapshot's, the worsened row capped at 60 degrees and at least twice as bad. The test uses
// a smaller snapshot (2000 samples, about 1.2K vertices) than `dynmesh experiment`
// (kBoomerangSamples, about 5.7K).
TEST(PaperExperiment, Table3BoomerangWithinTolerance) {
    const SurfaceMesh snapshot = boomerang_snapshot(2000);
    const auto before = check_mesh(snapshot, {.require_closed = true});
    ASSERT_TRUE(before.ok()) << before.summary();
    ASSERT_EQ(before.integer("euler"), 2);
    ASSERT_GT(snapshot.n_vertices(), 1000u);
    // Stretched to 6 x 2 x 2 and bent by 120 degrees towards +y: shorter than 6 along x,
    // and its ends rise above the middle (1.4 for the axis), so wider than 2 along y.
    Bbox3 box;
    for (Vertex v : snapshot.vertices()) box.extend(snapshot.position(v));
    EXPECT_GT(box.max.x - box.min.x, 5.0) << "stretched";
    EXPECT_LT(box.max.x - box.min.x, 5.6) << "bent";
    EXPECT_GT(box.max.y - box.min.y, 2.3) << "bent";
    EXPECT_NEAR(box.max.z - box.min.z, 2.0, 0.1);
    for (std::uint64_t seed : {1u, 2u}) {
        SmoothingExperimentOptions opt;
        opt.worsen.seed = seed;
        SurfaceMesh smoothed;
        const auto r = run_smoothing_experiment(snapshot, opt, nullptr, &smoothed);
        ASSERT_TRUE(r.flip.converged);
        EXPECT_FALSE(r.initial.normal_dev_deg.has_value());
        const Summary &i = r.initial.dihedral_dev_deg, &w = r.worsened.dihedral_dev_deg, &s = r.smoothed.dihedral_dev_deg;
        EXPECT_LE(s.mean, 1.05 * i.mean) << "seed " << seed;
        EXPECT_LE(s.sd, 1.05 * i.sd) << "seed " << seed;
        EXPECT_LE(s.max, 1.05 * i.max) << "seed " << seed;
        EXPECT_LE(w.max, 60.0 + 1e-9) << "seed " << seed;
        EXPECT_GE(w.mean, 2.0 * s.mean) << "seed " << seed;
        EXPECT_GE(r.shared_edge_fraction, 0.99) << "seed " << seed;
        const auto chk = check_mesh(smoothed, {.require_closed = true});
        EXPECT_TRUE(chk.ok()) << chk.summary();
        EXPECT_EQ(count_self_intersections(smoothed), 0u);
        std::printf("Table 3 (seed %zu, %zu vertices): initial %.2f/%.2f/%.1f, worsened %.2f/%.2f/%.1f, smoothed %.2f/%.2f/%.1f\n",
                    std::size_t(seed), snapshot.n_vertices(), i.mean, i.sd, i.max, w.mean, w.sd, w.max, s.mean, s.sd, s.max);
    }
}

// Check 7: flips per vertex stay in a constant band as n grows.
TEST(PaperExperiment, FlipCountLinearInSize) {
    const Sphere sphere({0, 0, 0}, 1.0);
    std::vector<double> ratio;
    for (std::size_t n : {2500u, 5000u, 10000u, 20000u, 40000u}) {
        SurfaceMesh m = restricted_delaunay(sphere.sample_uniform(n, 3), sphere);
        (void)worsen(m, {.seed = 3});
        const FlipReport r = flip_all(m);
        ASSERT_TRUE(r.converged) << n;
        ratio.push_back(double(r.flips) / double(n));
    }
    const double lo = *std::min_element(ratio.begin(), ratio.end());
    const double hi = *std::max_element(ratio.begin(), ratio.end());
    EXPECT_GT(lo, 0.5);
    EXPECT_LE(hi / lo, 1.5);
}

TEST(RealMeshes, WorsenAndSmoothKeepTopology) {
    for (const char* name : {"meshes/armadillo.off", "meshes/elephant.off", "meshes/knot1.off"}) {
        const SurfaceMesh mesh = read_mesh(test::shared_data(name));
        const auto before = check_mesh(mesh, {.require_closed = true});
        ASSERT_TRUE(before.ok()) << name << before.summary();
        SmoothingExperimentOptions opt;
        SurfaceMesh smoothed;
        const auto r = run_smoothing_experiment(mesh, opt, nullptr, &smoothed);
        EXPECT_TRUE(r.flip.converged) << name;
        const auto after = check_mesh(smoothed, {.require_closed = true});
        EXPECT_TRUE(after.ok()) << name << after.summary();
        EXPECT_EQ(after.integer("euler"), before.integer("euler")) << name;
        EXPECT_EQ(smoothed.positions(), mesh.positions()) << name;
        EXPECT_LT(r.smoothed.dihedral_dev_deg.mean, 0.8 * r.worsened.dihedral_dev_deg.mean) << name;
        EXPECT_GT(r.smoothed.angle_deg.min, r.worsened.angle_deg.min) << name;
    }
}

std::set<std::pair<std::uint32_t, std::uint32_t>> sharp_edges(const SurfaceMesh& m, double deg) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> out;
    for (Edge e : m.edges()) {
        const EdgeQuad k = edge_quad(m, e);
        const double dev = 180.0 - rad_to_deg(dihedral_angle(m.position(k.p), m.position(k.q),
                                                             m.position(k.r), m.position(k.s)));
        if (dev > deg) out.emplace(std::min(k.p.idx(), k.q.idx()), std::max(k.p.idx(), k.q.idx()));
    }
    return out;
}

TEST(RealMeshes, FeatureAngleKeepsCreases) {
    const SurfaceMesh fandisk = read_mesh(test::shared_data("meshes/fandisk.off"));
    const auto creases = sharp_edges(fandisk, 45.0);
    ASSERT_GT(creases.size(), 600u);
    SurfaceMesh guarded = fandisk, free = fandisk;
    const FlipReport g = flip_all(guarded, {.feature_angle_deg = 45.0});
    const FlipReport f = flip_all(free);
    EXPECT_GT(g.flips, 0u);
    EXPECT_EQ(sharp_edges(guarded, 45.0), creases);
    // Without the guard the paper's rule does flip across a crease.
    EXPECT_NE(sharp_edges(free, 45.0), creases);
    EXPECT_GT(g.feature_locked + (f.flips > g.flips ? 1 : 0), 0u);
}

}  // namespace
}  // namespace dynmesh
