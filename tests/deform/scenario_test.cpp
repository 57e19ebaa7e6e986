#include "dynmesh/deform/scenario.hpp"

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/metrics/hausdorff.hpp"
#include "scenario_cases.hpp"

namespace dynmesh {
namespace {

using namespace test;

TEST(Scenario, EveryScenarioBuildsWithConsistentFields) {
    for (const std::string& key : all_cases()) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        EXPECT_FALSE(s.name.empty());
        EXPECT_FALSE(s.description.empty());
        ASSERT_TRUE(s.warp != nullptr);
        EXPECT_TRUE(s.reference.is_closed());
        EXPECT_FALSE(s.reference.has_garbage());
        EXPECT_EQ(s.pool_size(), s.reference.n_vertices());
        EXPECT_EQ(s.initial_density.size(), s.pool_size());
        EXPECT_EQ(s.time_units, kSteps);
        EXPECT_DOUBLE_EQ(s.rate, 1.0 / kSteps);
        EXPECT_GT(s.lambda, 0);
        EXPECT_GT(s.h0, 0);
        EXPECT_GT(s.spacing0, 0);
        EXPECT_LT(s.spacing0, s.h0);
        EXPECT_DOUBLE_EQ(s.density_radius, 4 * s.spacing0);
        // P(0): sorted, distinct pool indices; analytic pools keep (almost) every sample.
        ASSERT_FALSE(s.initial.empty());
        EXPECT_TRUE(std::is_sorted(s.initial.begin(), s.initial.end()));
        EXPECT_EQ(std::adjacent_find(s.initial.begin(), s.initial.end()), s.initial.end());
        EXPECT_LT(s.initial.back(), s.pool_size());
        EXPECT_GE(s.initial.size(), kSamples * 99 / 100);
        EXPECT_LE(s.initial.size(), kSamples);
        // Normals: unit, outward (positive enclosed volume means outward orientation).
        EXPECT_GT(signed_volume(s.reference), 0);
        for (std::size_t i = 0; i < s.pool_size(); i += 97)
            EXPECT_NEAR(norm(s.normals0[i]), 1.0, 1e-12);
        if (s.surface0) {
            EXPECT_EQ(s.initial.size(), kSamples);  // a dense RDT drops nothing
            for (std::size_t i = 0; i < s.pool_size(); i += 97)
                EXPECT_NEAR(s.surface0->signed_distance(s.reference.positions()[i]), 0, 1e-9);
        }
    }
    EXPECT_EQ(cached("mesh+bend").name, "mesh:blobby.off+bend");
    EXPECT_TRUE(cached("mesh+bend").edits);
    EXPECT_FALSE(cached("pulse").edits);
    EXPECT_EQ(cached("twist").reference.n_vertices() + cached("twist").reference.n_faces(),
              cached("twist").reference.n_edges());  // Euler characteristic 0
}

TEST(Scenario, InitialSamplesAreReferenceVerticesAndH0IsTheirCoveringRadius) {
    for (const std::string& key : all_cases()) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        const auto p0 = pool_positions(s, 0.0, s.initial);
        for (std::size_t i = 0; i < p0.size(); ++i)
            ASSERT_EQ(p0[i], s.reference.position(Vertex(s.initial[i])));
        EXPECT_DOUBLE_EQ(sampling_radius(s, 0.0, s.initial), s.h0);
        // Every pool point (itself a probe) lies within h0 of P(0).
        EXPECT_LE(covering_radius(s.reference.positions(), p0), s.h0);
        // The full pool covers at least as well as P(0) (strictly better on an analytic
        // surface, where the pool is four times denser).
        if (s.surface0) {
            EXPECT_LT(sampling_radius(s, 0.0, all_pool(s)), s.h0);
        } else {
            EXPECT_LE(sampling_radius(s, 0.0, all_pool(s)), s.h0);
        }
    }
}

TEST(Scenario, BoomerangIsBend) {
    ScenarioOptions o;
    o.samples = 500;
    o.steps = 10;
    const Scenario a = make_scenario("boomerang", o), b = make_scenario("bend", o);
    EXPECT_EQ(a.name, "bend");
    EXPECT_EQ(a.lambda, b.lambda);
}

TEST(Scenario, SameOptionsGiveIdenticalScenarios) {
    ScenarioOptions o;
    o.samples = 800;
    o.steps = 10;
    o.seed = 7;
    for (const std::string& name : {std::string("stretch"), blobby()}) {
        SCOPED_TRACE(name);
        const Scenario a = make_scenario(name, o), b = make_scenario(name, o);
        EXPECT_EQ(a.initial, b.initial);
        EXPECT_EQ(a.reference.positions(), b.reference.positions());
        EXPECT_EQ(a.lambda, b.lambda);
        EXPECT_EQ(a.h0, b.h0);
        EXPECT_EQ(a.initial_density, b.initial_density);
        o.seed = 8;
        const Scenario c = make_scenario(name, o);
        EXPECT_NE(pool_positions(a, 0.0, a.initial), pool_positions(c, 0.0, c.initial));
        o.seed = 7;
    }
}

TEST(Scenario, SpeedRescalesHorizonAndLambda) {
    ScenarioOptions o;
    o.samples = 500;
    o.steps = 40;
    const Scenario slow = make_scenario("stretch", o);
    o.speed = 4;
    const Scenario fast = make_scenario("stretch", o);
    o.speed = 0.1;
    const Scenario slower = make_scenario("stretch", o);
    EXPECT_EQ(slow.time_units, 40);
    EXPECT_EQ(fast.time_units, 10);
    EXPECT_EQ(slower.time_units, 400);
    EXPECT_NEAR(fast.lambda / slow.lambda, 4.0, 4e-3);
    EXPECT_NEAR(slow.lambda / slower.lambda, 10.0, 1e-2);
    // The same path: the shape at the peak is the same.
    const Point3 x{1, 0, 0};
    EXPECT_NEAR(distance(slow.warp->apply(20, x), fast.warp->apply(5, x)), 0, 1e-12);
    EXPECT_NEAR(distance(slow.warp->apply(20, x), Point3{3, 0, 0}), 0, 1e-12);
}

TEST(Scenario, MeshFileUsesEveryVertexWhenSamplesExceedTheVertexCount) {
    ScenarioOptions o;
    o.samples = 100000;
    o.steps = 10;
    o.warp = "twist";
    const Scenario s = make_scenario(blobby(), o);
    ASSERT_EQ(s.initial.size(), 2027u);  // every input vertex: pool indices 0..2026
    EXPECT_EQ(s.initial.back(), 2026u);
    EXPECT_EQ(s.surface0, nullptr);
    EXPECT_EQ(s.name, "mesh:blobby.off+twist");
    // One midpoint subdivision: V + E pool points, four times the faces, same geometry.
    EXPECT_EQ(s.pool_size(), 2027u + 6075u);
    EXPECT_EQ(s.reference.n_faces(), 4u * 4050u);
    const SurfaceMesh input = read_mesh(blobby());
    for (std::uint32_t i = 0; i < 2027; ++i)
        ASSERT_EQ(s.reference.position(Vertex(i)), input.position(Vertex(i)));
    HausdorffOptions ho;
    ho.face_resolution = 1;
    EXPECT_LT(hausdorff_distance(s.reference, input, ho), 1e-12);
    // No subdivision with pool_factor 1: the pool is the input.
    o.pool_factor = 1;
    EXPECT_EQ(make_scenario(blobby(), o).pool_size(), 2027u);
}


// ---- bad input -----------------------------------------------------------------------------

TEST(Scenario, BadInputsThrowNamingTheProblem) {
    ScenarioOptions o;
    o.samples = 500;
    o.steps = 10;
    expect_invalid([&] { (void)make_scenario("wobble", o); }, "unknown scenario 'wobble'");
    expect_invalid([&] { (void)make_scenario("wobble", o); }, "pulse, stretch, twist, bend");
    expect_invalid([&] { (void)make_scenario("", o); }, "unknown scenario");
    auto with = [&](auto change) {
        ScenarioOptions x = o;
        change(x);
        return x;
    };
    expect_invalid([&] { (void)make_scenario("pulse", with([](auto& x) { x.samples = 99; })); },
                   "samples must be >= 100");
    expect_invalid([&] { (void)make_scenario("pulse", with([](auto& x) { x.steps = 0; })); },
                   "steps");
    expect_invalid([&] { (void)make_scenario("pulse", with([](auto& x) { x.speed = 0; })); },
                   "speed");
    expect_invalid([&] { (void)make_scenario("pulse", with([](auto& x) { x.speed = -1; })); },
                   "speed");
    expect_invalid(
        [&] { (void)make_scenario("pulse", with([](auto& x) { x.speed = std::nan(""); })); },
        "speed");
    expect_invalid(
        [&] { (void)make_scenario("pulse", with([](auto& x) { x.speed = INFINITY; })); },
        "speed");
    expect_invalid(
        [&] { (void)make_scenario("pulse", with([](auto& x) { x.pool_factor = 0; })); },
        "pool_factor");
    expect_invalid([&] { (void)make_scenario("pulse", with([](auto& x) { x.warp = "twist"; })); },
                   "mesh files only");
    expect_invalid([&] { (void)make_scenario(blobby(), with([](auto& x) { x.warp = "wobble"; })); },
                   "unknown warp 'wobble'");
    const std::string border = test::shared_data("meshes/defective/mesh_with_border.off").string();
    expect_invalid([&] { (void)make_scenario(border, o); }, "not a closed");
    const std::string pinched =
        test::shared_data("meshes/defective/cow_nonmanifold_vertex.obj").string();
    expect_invalid([&] { (void)make_scenario(pinched, o); }, "cow_nonmanifold_vertex.obj");
    const std::string empty = test::shared_data("meshes/invalid/empty.off").string();
    expect_invalid([&] { (void)make_scenario(empty, o); }, "cannot use mesh file");
    const std::string dir = test::shared_data("meshes").string();
    expect_invalid([&] { (void)make_scenario(dir, o); }, "cannot use mesh file");
}

}  // namespace
}  // namespace dynmesh
