// Tri(0) on the input mesh (spec §10.5, §4.1): every closed mesh of shared/data initialises
// with the defaults of `dynmesh deform MESH`, with the input's topology, and the state at
// t = 0 is checked against the invariants.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "dynmesh/deform/deforming_mesh.hpp"
#include "dynmesh/deform/initial_mesh.hpp"
#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

CheckReport topology(const SurfaceMesh& m) {
    MeshCheckOptions o;
    o.require_closed = true;
    o.check_degenerate = false;
    return check_mesh(m, o);
}

/// The scenario and DeformingMesh exactly as `dynmesh deform MESH` builds them (run_deform).
struct MeshStart {
    Scenario s;
    std::unique_ptr<DeformingMesh> dm;
};
MeshStart start_on(const std::string& file, double size_factor = DeformOptions{}.size_factor) {
    MeshStart m{make_scenario(test::shared_data("meshes/" + file).string(), ScenarioOptions{}), nullptr};
    std::vector<Point3> x0;
    for (std::uint32_t q : m.s.initial) x0.push_back(m.s.reference.position(Vertex(q)));
    DeformOptions params;
    params.lambda = m.s.lambda;
    params.h0 = m.s.h0;
    params.horizon = m.s.time_units;
    params.size_factor = size_factor;
    InitialSurface init;
    init.reference = &*m.s.input_mesh;
    m.dm = std::make_unique<DeformingMesh>(x0, params, init);
    return m;
}

class InitOnMeshFile : public testing::TestWithParam<std::string> {};

/// Tri(0) of `file` has the input's topology, the init report agrees with check_invariants(),
/// and every invariant holds unless the file is in `outside_model`; in `balls_only`, every
/// invariant but the empty diametric balls (reported, not asserted).
void expect_good_start(const std::string& file, double size_factor, const std::vector<std::string>& outside_model,
                       const std::vector<std::string>& balls_only) {
    auto listed = [&](const std::vector<std::string>& l) { return std::find(l.begin(), l.end(), file) != l.end(); };
    MeshStart m;
    ASSERT_NO_THROW(m = start_on(file, size_factor)) << file;
    const SurfaceMesh& mesh = m.dm->mesh();
    const CheckReport in = topology(*m.s.input_mesh), out = topology(mesh);
    ASSERT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(out.integer("euler"), in.integer("euler"));
    EXPECT_EQ(out.integer("components"), in.integer("components"));
    EXPECT_EQ(m.dm->init_report().euler, in.integer("euler"));
    EXPECT_NE(m.dm->init_report().tri0, "advancing_front");
    const CheckReport inv = m.dm->check_invariants();  // with the self-intersection test
    EXPECT_EQ(inv.integer("self_intersections"), 0);
    // The init report carries the same verdict (without the self-intersection test).
    const InitReport& ir = m.dm->init_report();
    EXPECT_EQ(inv.ok(), ir.invariant_failures.empty() && ir.nonempty_balls == 0) << inv.summary();
    EXPECT_EQ(inv.integer("nonempty_balls"), static_cast<long long>(ir.nonempty_balls));
    if (listed(balls_only)) {
        EXPECT_TRUE(ir.invariant_failures.empty()) << file << ": " << inv.summary();
    } else if (!listed(outside_model)) {
        EXPECT_TRUE(inv.ok()) << file << ": " << inv.summary();
    }
}

TEST_P(InitOnMeshFile, HasTheInputTopologyAndIsChecked) {
    // The default, with the local size field: the elephant's thin parts are resolved. On spot
    // and fandisk one or two diametric balls near thin parts hold a vertex that no flip can
    // take out; the armadillo's scan wrinkles and a few places of igea are thinner than the
    // samples are dense (docs/deform/RESULTS.md, sections C and D).
    expect_good_start(GetParam(), DeformOptions{}.size_factor, {"armadillo.off", "igea.ply"},
                      {"spot.obj", "fandisk.off"});
}

TEST_P(InitOnMeshFile, WithTheGlobalRHasTheInputTopologyAndIsChecked) {
    // The paper's global R: features smaller than a third of R (a thin part of the elephant,
    // the armadillo's scan wrinkles, a few places of igea) need vertices closer than R/3 or
    // leave balls that no flip can empty: outside the paper's global-reach model, and
    // reported, not silent. On fandisk's sharp edges the flips that would empty a few balls
    // would fold a neighbour and are refused.
    expect_good_start(GetParam(), 0.0, {"elephant.off", "armadillo.off", "igea.ply"}, {"fandisk.off"});
}

std::vector<std::string> mesh_files() {
    std::vector<std::string> f{"eight.off",   "blobby.off",    "elephant.off", "knot1.off", "spot.obj",
                               "fandisk.off", "armadillo.off", "blob.stl",     "cube_binary.ply"};
    // igea (134K vertices, 20,000 samples) takes about 4 s in Release.
    if (std::getenv("DYNMESH_HEAVY_TESTS") != nullptr) f.push_back("igea.ply");
    return f;
}

INSTANTIATE_TEST_SUITE_P(SharedData, InitOnMeshFile, testing::ValuesIn(mesh_files()),
                         [](const testing::TestParamInfo<std::string>& i) {
                             std::string n = i.param;
                             for (char& c : n)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return n;
                         });

TEST(MeshRestrictedDelaunay, SphereSamplesOnAFineSphereMesh) {
    // The reference: a fine mesh of the unit sphere; the net: a uniform sample of it.
    const Sphere sphere(Point3{0, 0, 0}, 1.0);
    const SurfaceMesh reference = sample_and_mesh(sphere, 20000, 7);
    const std::vector<Point3> pts = sphere.sample_uniform(600, 3);
    std::vector<std::uint32_t> net(pts.size());
    for (std::uint32_t i = 0; i < net.size(); ++i) net[i] = i;
    const auto r = restricted_delaunay_on_mesh(pts, net, reference);
    const CheckReport c = topology(r.mesh);
    ASSERT_TRUE(c.ok()) << c.summary();
    EXPECT_EQ(c.integer("euler"), 2);
    EXPECT_EQ(r.report.euler, 2);
    EXPECT_TRUE(r.report.correct);
    EXPECT_EQ(r.report.vertex_sample.size(), pts.size());  // every sample is a vertex
    EXPECT_EQ(r.report.added, 0u);
    // Outward: positive volume; and every vertex keeps its sample's coordinates.
    EXPECT_GT(test::signed_volume(r.mesh), 0.0);
    for (Vertex v : r.mesh.vertices()) EXPECT_EQ(r.mesh.position(v), pts[r.report.vertex_sample[v.idx()]]);
    // The same facets as the restricted Delaunay triangulation on the sphere itself, but
    // for dual edges that pass between the sphere and its inscribed mesh.
    const auto exact = restricted_delaunay_with_report(pts, sphere);
    EXPECT_NEAR(static_cast<double>(r.report.facets), static_cast<double>(exact.report.facets),
                0.01 * static_cast<double>(exact.report.facets));
}

TEST(MeshRestrictedDelaunay, AddsSamplesWhereTheNetIsTooSparseForTheTopology) {
    // Four samples of a torus cannot mesh it; the rounds add pool samples until the result
    // has genus 1.
    const Torus torus(Point3{0, 0, 0}, 2.0, 0.7);
    const SurfaceMesh reference = sample_and_mesh(torus, 20000, 5);
    const std::vector<Point3> pool = torus.sample_uniform(3000, 9);
    const std::vector<std::uint32_t> net{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    MeshRestrictedDelaunayOptions o;
    o.max_rounds = 16;
    const auto r = restricted_delaunay_on_mesh(pool, net, reference, o);
    EXPECT_EQ(topology(r.mesh).integer("euler"), 0);
    EXPECT_GT(r.report.added, 0u);
    EXPECT_GT(r.report.rounds, 1u);
    // Without the rounds it fails, naming the problem.
    o.max_rounds = 1;
    try {
        (void)restricted_delaunay_on_mesh(pool, net, reference, o);
        ADD_FAILURE() << "a 10-sample net of a torus was accepted";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("too sparse"), std::string::npos) << e.what();
    }
    o.throw_on_failure = false;
    const auto f = restricted_delaunay_on_mesh(pool, net, reference, o);
    EXPECT_FALSE(f.report.correct);
}

TEST(InitialMeshOnReference, DecimatesTheReferenceWhenNoRestrictedDelaunayHasItsTopology) {
    // Every vertex of fandisk as the net: its restricted Delaunay triangulation against
    // itself is not a manifold at a crease corner, and no sample is left to add; the
    // fallback keeps the input mesh (nothing to remove).
    const SurfaceMesh fandisk = read_mesh(test::shared_data("meshes/fandisk.off"));
    const std::vector<Point3> pts(fandisk.positions().begin(), fandisk.positions().end());
    std::vector<std::uint32_t> net(pts.size());
    for (std::uint32_t i = 0; i < net.size(); ++i) net[i] = i;
    const ReferenceMesh r = initial_mesh_on_reference(pts, net, fandisk, {.refine = false});
    EXPECT_EQ(r.path, ReferenceMeshPath::Decimated);
    EXPECT_FALSE(r.fallback_reason.empty());
    EXPECT_EQ(r.mesh.n_faces(), fandisk.n_faces());
    EXPECT_EQ(topology(r.mesh).integer("euler"), 2);
}

}  // namespace
}  // namespace dynmesh
