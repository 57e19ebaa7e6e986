#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "dynmesh/mesh/check.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/metrics/hausdorff.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "dynmesh/probing/refine.hpp"

namespace dynmesh {
namespace {

struct ProbeRun {
    ProbingResult result;
    MeshCheckReport check;
    double hausdorff = 0;
};

ProbeRun probe(const ProbeObject& object, const Point3& interior, double omega_radius, double eps,
          std::size_t check_every) {
    ProbingOptions o;
    o.eps = eps;
    o.eps_S = object.reach();
    o.omega_center = {0, 0, 0};
    o.omega_radius = omega_radius;
    o.interior_points = {interior};
    o.ground_truth = &object;
    o.check_every = check_every;
    ProbeRun run{probe_surface(object, o), {}, 0};
    const ProbingReport& p = run.result.report;
    std::printf("eps %.3f: %zu vertices, %zu probes, %zu cells, %zu retained, %zu detection / %zu "
                "positioning edges, path %.2f, exterior %.2f, %.2f s\n",
                eps, p.vertices, p.probes, p.cells_created, p.nodes_retained, p.detection_edges,
                p.positioning_edges, p.path_length, p.exterior_path_length, p.seconds);
    const SurfaceMesh m = SurfaceMesh::from_soup(run.result.mesh);
    run.check = check_mesh(m, {.require_closed = true});
    double to_s = 0;
    for (const Point3& p : mesh_sample_points(m, 2)) to_s = std::max(to_s, object.distance(p));
    run.hausdorff = std::max(to_s, max_distance_to_mesh(m, object.sample_surface(eps / 4)));
    return run;
}

/// Spec §7 test 5 with §10.5: the torus exercises the paths (detection, positioning, retained
/// nodes), the invariants hold after every 200th insertion, the topology is the torus's.
TEST(ProbeShapes, TorusHasGenusOneAndUsesPaths) {
    const TorusOracle torus(Torus({0, 0, 0}, 1, 0.35));
    const double eps = 0.03;
    const ProbeRun r = probe(torus, torus.shape().interior_point(), 1.5, eps, 200);
    EXPECT_TRUE(r.result.problems.empty()) << r.result.problems.front();
    EXPECT_TRUE(r.check.ok()) << r.check.summary();
    EXPECT_EQ(r.check.euler, 0);
    EXPECT_EQ(r.check.components, 1u);
    EXPECT_LE(r.result.report.max_ball_radius, eps);
    EXPECT_GT(r.result.report.detection_edges, 0u);
    EXPECT_GT(r.result.report.positioning_edges, 0u);
    EXPECT_GT(r.result.report.nodes_retained, 0u);
    EXPECT_GT(r.result.report.segments_checked, 0u);
    EXPECT_LE(r.hausdorff, 4.5 * 2.7 * eps * eps / (0.35 * 0.35));
    EXPECT_LE(r.hausdorff, eps * eps / 0.35);
}

TEST(ProbeShapes, EllipsoidIsASphereTopologically) {
    const EllipsoidOracle ell(Ellipsoid({0, 0, 0}, 1, 0.8, 0.6));
    const double eps = 0.03;
    const ProbeRun r = probe(ell, {0, 0, 0}, 1.2, eps, 500);
    EXPECT_TRUE(r.result.problems.empty()) << r.result.problems.front();
    EXPECT_TRUE(r.check.ok()) << r.check.summary();
    EXPECT_EQ(r.check.euler, 2);
    EXPECT_LE(r.result.report.max_ball_radius, eps);
    EXPECT_LE(r.hausdorff, eps * eps / ell.reach());
}

/// A real scan through the mesh oracle. Nearly flat cells put Voronoi vertices 1e11-1e12
/// away; their edges must be taken on the facet's dual line anchored inside Omega, or kept
/// hits drift off their edge and their balls hold samples (the invariant check fails).
TEST(ProbeShapes, BlobbyScanThroughTheMeshOracle) {
    const ProbeSetup setup = make_probe_object(std::string(DYNMESH_SHARED_DATA_DIR) + "/meshes/blobby.off");
    ProbingOptions o;
    o.eps = 0.008;
    o.eps_S = 0.1;
    o.omega_center = setup.omega.center;
    o.omega_radius = setup.omega.radius;
    o.interior_points = setup.interior_points;
    o.ground_truth = setup.object.get();
    const ProbingResult r = probe_surface(*setup.object, o);
    EXPECT_TRUE(r.problems.empty()) << r.problems.size() << ": " << r.problems.front();
    const MeshCheckReport check = check_mesh(SurfaceMesh::from_soup(r.mesh), {.require_closed = true});
    EXPECT_TRUE(check.ok()) << check.summary();
    EXPECT_EQ(check.euler, 2);
    EXPECT_LE(r.report.max_ball_radius, o.eps);
}

}  // namespace
}  // namespace dynmesh
