#include "dynmesh/deform/scenario.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/deform/ground_truth.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/metrics/hausdorff.hpp"
#include "dynmesh/metrics/self_intersection.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

constexpr std::size_t kSamples = 2000;
constexpr int kSteps = 20;

std::string blobby() { return test::shared_data("meshes/blobby.off").string(); }

/// Every scenario the tests build, once each (small sizes).
std::vector<std::string> all_cases() {
    return {"pulse",     "stretch",   "twist",     "bend",      "rotate",
            "dimple",    "mesh+bend", "mesh+twist", "mesh+pulse"};
}

const Scenario& cached(const std::string& key) {
    static std::map<std::string, std::unique_ptr<Scenario>> cache;
    auto it = cache.find(key);
    if (it != cache.end()) return *it->second;
    ScenarioOptions o;
    o.samples = kSamples;
    o.steps = kSteps;
    std::string name = key;
    if (key.rfind("mesh+", 0) == 0) {
        name = blobby();
        o.warp = key.substr(5);
    }
    auto s = std::make_unique<Scenario>(make_scenario(name, o));
    return *cache.emplace(key, std::move(s)).first->second;
}

SurfaceMesh warped_reference(const Scenario& s, double t) {
    SurfaceMesh m = s.reference;
    warp_points(s, t, s.reference.positions(), m.positions());
    return m;
}

double signed_volume(const SurfaceMesh& m) {
    double v = 0;
    for (const Face f : m.faces()) {
        const auto x = m.face_vertices(f);
        v += dot(m.position(x[0]), cross(m.position(x[1]), m.position(x[2]))) / 6.0;
    }
    return v;
}

std::vector<std::uint32_t> all_pool(const Scenario& s) {
    std::vector<std::uint32_t> v(s.pool_size());
    std::iota(v.begin(), v.end(), 0u);
    return v;
}

std::vector<std::uint32_t> identity_vertex_pool(const SurfaceMesh& m) {
    std::vector<std::uint32_t> v(m.vertices_size());
    std::iota(v.begin(), v.end(), 0u);
    return v;
}

template <class F>
void expect_invalid(F&& f, const std::string& needle) {
    try {
        f();
        ADD_FAILURE() << "no InvalidInput thrown (expected a message with '" << needle << "')";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
            << "message: " << e.what() << "\nexpected to contain: " << needle;
    }
}

// ---- construction --------------------------------------------------------------------------

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

TEST(SampleEdits, MeshScenarioInsertsFromTheSubdividedPool) {
    const Scenario& s = cached("mesh+pulse");
    const double peak = 0.5 * kSteps;
    const SampleEdits e = plan_sample_edits(s, peak, s.initial, s.h0);
    EXPECT_GT(e.insert_pool.size(), 20u);
    std::vector<std::uint32_t> after = s.initial;
    after.insert(after.end(), e.insert_pool.begin(), e.insert_pool.end());
    EXPECT_GT(sampling_radius(s, peak, s.initial), 1.4 * s.h0);
    EXPECT_LT(sampling_radius(s, peak, after), 1.2 * s.h0);
}

// ---- warps ---------------------------------------------------------------------------------

TEST(Warp, IsExactlyTheIdentityAtTimeZeroAndCloses) {
    for (const std::string& key : all_cases()) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        const auto& p = s.reference.positions();
        double back = 0, moved = 0;
        for (const Point3& x : p) {
            ASSERT_EQ(s.warp->apply(0.0, x), x);
            back = std::max(back, distance(s.warp->apply(s.time_units, x), x));
            for (double f : {0.25, 0.5})  // the twist swings: straight again at 0.5
                moved = std::max(moved, distance(s.warp->apply(f * s.time_units, x), x));
        }
        EXPECT_LT(back, 1e-9 * s.length_scale);  // one full cycle
        // And it really moves (the dimples move locally, by about one sample spacing).
        EXPECT_GT(moved, key == "dimple" ? s.h0 : 0.05 * s.length_scale);
    }
}

TEST(Warp, AnalyticShapesAtThePeak) {
    // Pulse: radius 1.5 at half-cycle; stretch: the ellipsoid 3:1:1.
    const Scenario& pulse = cached("pulse");
    const Scenario& stretch = cached("stretch");
    const double t = 0.5 * kSteps;
    for (std::size_t i = 0; i < pulse.pool_size(); i += 13) {
        EXPECT_NEAR(norm(pulse.warp->apply(t, pulse.reference.positions()[i])), 1.5, 1e-12);
        const Point3 q = stretch.warp->apply(t, stretch.reference.positions()[i]);
        EXPECT_NEAR(q.x * q.x / 9 + q.y * q.y + q.z * q.z, 1.0, 1e-12);
    }
    // Bend: the stretched x axis becomes an arc turning by 2 pi / 3 at the peak.
    const Scenario& bend = cached("bend");
    const Point3 tip = bend.warp->apply(t, Point3{1, 0, 0});
    const double rho = 6.0 / (2 * kPi / 3);
    EXPECT_NEAR(tip.x, rho * std::sin(kPi / 3), 1e-9);
    EXPECT_NEAR(tip.y, rho * (1 - std::cos(kPi / 3)), 1e-9);
    // At a quarter cycle the sphere is fully stretched but not yet bent.
    const Point3 q = bend.warp->apply(0.25 * kSteps, Point3{1, 0, 0});
    EXPECT_NEAR(distance(q, Point3{3, 0, 0}), 0, 1e-9);
}

TEST(Warp, LambdaBoundsTheDisplacementPerTimeUnit) {
    for (const std::string& key : all_cases()) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        const auto& p = s.reference.positions();
        double worst = 0;
        for (double t = 0; t <= s.time_units - 1 + 1e-9; t += 0.25) {
            for (const Point3& x : p)
                worst = std::max(worst, distance(s.warp->apply(t + 1, x), s.warp->apply(t, x)));
        }
        EXPECT_LE(worst, s.lambda);
        EXPECT_GT(worst, s.lambda / 1.25) << "lambda is far from tight";
    }
}

TEST(Warp, StaysEmbeddedAndOrientedOnTheReference) {
    for (const std::string& key : all_cases()) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        for (double f : {0.25, 0.5, 0.75}) {
            const SurfaceMesh m = warped_reference(s, f * s.time_units);
            EXPECT_EQ(count_self_intersections(m), 0u) << "t = " << f * s.time_units;
            EXPECT_GT(signed_volume(m), 0);
        }
    }
}

TEST(Warp, NormalsAndAreaScale) {
    const Scenario& pulse = cached("pulse");
    const double peak = 0.5 * kSteps;
    for (std::uint32_t i = 0; i < pulse.pool_size(); i += 101) {
        EXPECT_NEAR(area_scale(pulse, peak, i), 2.25, 1e-6);
        EXPECT_NEAR(area_scale(pulse, 0.0, i), 1.0, 1e-6);
        const Vec3 n = surface_normal(pulse, peak, i);
        EXPECT_NEAR(distance(n, normalized(pulse.reference.positions()[i])), 0, 1e-6);
    }
    // Stretch: the true normal of the ellipsoid at the image point.
    const Scenario& st = cached("stretch");
    for (std::uint32_t i = 0; i < st.pool_size(); i += 101) {
        const Point3 q = st.warp->apply(peak, st.reference.positions()[i]);
        const Vec3 exact = normalized(Vec3{q.x / 9, q.y, q.z});
        EXPECT_NEAR(distance(surface_normal(st, peak, i), exact), 0, 1e-6);
    }
    // Rotation: rigid, so area is preserved.
    const Scenario& rot = cached("rotate");
    for (std::uint32_t i = 0; i < rot.pool_size(); i += 101)
        EXPECT_NEAR(area_scale(rot, 3.7, i), 1.0, 1e-6);
}

TEST(Warp, DimpleMovesDisjointPatchesOutAndBack) {
    // Two centres on the unit sphere, 1 apart; radius 0.3; slides of 0.1 (L = 0.57).
    const std::vector<Point3> c{{1, 0, 0}, normalized(Point3{1, 1, 0})};
    const std::vector<Vec3> d{{0, 0.1, 0.02}, {0, 0, -0.1}};
    const double rate = 0.01;  // period 100
    const auto w = make_dimple_warp(c, d, 0.3, rate);
    EXPECT_EQ(w->name(), "dimple");
    EXPECT_EQ(w->apply(0.0, c[0]), c[0]);
    EXPECT_NEAR(distance(w->apply(50.0, c[0]), c[0] + d[0]), 0, 1e-15);  // the peak
    EXPECT_NEAR(distance(w->apply(50.0, c[1]), c[1] + d[1]), 0, 1e-15);
    EXPECT_NEAR(distance(w->apply(25.0, c[0]), c[0] + d[0] * 0.5), 0, 1e-15);
    EXPECT_NEAR(distance(w->apply(100.0, c[0]), c[0]), 0, 1e-15);  // back after one period
    // The bump: half way out at the peak, nothing at the rim and beyond.
    const Point3 mid = c[0] + Vec3{0, 0, 0.15};
    EXPECT_NEAR(distance(w->apply(50.0, mid), mid + d[0] * dimple_bump(0.5)), 0, 1e-15);
    EXPECT_DOUBLE_EQ(dimple_bump(0.5), 0.421875);
    EXPECT_EQ(dimple_bump(1.0), 0.0);
    EXPECT_EQ(dimple_bump(0.0), 1.0);
    for (const Point3 x : {Point3{-1, 0, 0}, Point3{0, 0, 1}, c[0] + Vec3{0, 0, 0.3},
                           Point3{0.7, -0.7, 0}})
        for (double t : {10.0, 50.0, 77.0}) EXPECT_EQ(w->apply(t, x), x);
    // The largest slope of the bump is kDimpleBumpSlope.
    double slope = 0;
    for (int i = 0; i < 10000; ++i) {
        const double r = i / 10000.0, e = 1e-7;
        slope = std::max(slope, std::abs(dimple_bump(r + e) - dimple_bump(r)) / e);
    }
    EXPECT_NEAR(slope, kDimpleBumpSlope, 1e-6);
    // Injective near the surface: distinct points of a grid around c[0] stay distinct and
    // keep their order along the slide direction (the field is a contraction, L < 1).
    for (double y = -0.35; y <= 0.35; y += 0.01) {
        const Point3 a = c[0] + Vec3{0, y, 0}, b = c[0] + Vec3{0, y + 0.01, 0};
        EXPECT_GT(w->apply(50.0, b).y - w->apply(50.0, a).y, 0.0) << y;
    }
}

TEST(Warp, DimpleScenarioFollowsSpecS4) {
    const Scenario& s = cached("dimple");
    EXPECT_EQ(s.name, "dimple");
    EXPECT_NE(s.description.find("dimples"), std::string::npos);
    EXPECT_FALSE(s.edits);
    ASSERT_TRUE(s.surface0 != nullptr);
    const double peak = 0.5 * s.time_units;
    const double reach = 1.0307764064044151 * s.h0;  // |h0 t_k + h0/4 c_k|
    std::size_t moved = 0;
    double largest = 0;
    for (const Point3& x : s.reference.positions()) {
        const double m = distance(s.warp->apply(peak, x), x);
        if (m > 0) ++moved;
        largest = std::max(largest, m);
    }
    // Several disjoint patches move by up to about h0, and the rest of the sphere stays put.
    EXPECT_LE(largest, reach * (1 + 1e-12));
    EXPECT_GT(largest, 0.97 * reach);
    EXPECT_GT(moved, s.pool_size() / 5);
    EXPECT_LT(moved, s.pool_size() * 4 / 5);
    // lambda is the speed at a centre, pi * rate * reach, with the 5% margin.
    EXPECT_NEAR(s.lambda, 1.05 * kPi * s.rate * reach, 0.02 * s.lambda);
    // Its own warp name is accepted, another one is not.
    ScenarioOptions o;
    o.samples = 500;
    o.steps = 10;
    o.warp = "dimple";
    EXPECT_EQ(make_scenario("dimple", o).name, "dimple");
    o.warp = "bend";
    expect_invalid([&] { (void)make_scenario("dimple", o); }, "own motion");
}

TEST(Warp, FibonacciSphere) {
    for (std::size_t n : {1u, 2u, 16u, 64u}) {
        const auto p = fibonacci_sphere(n);
        ASSERT_EQ(p.size(), n);
        for (std::size_t i = 0; i < n; ++i) {
            EXPECT_NEAR(norm(p[i]), 1.0, 1e-15);
            EXPECT_LT(std::abs(p[i].z), 1.0);  // never a pole
            if (i > 0) {
                EXPECT_LT(p[i].z, p[i - 1].z);
            }
        }
    }
    expect_invalid([] { (void)fibonacci_sphere(0); }, "n must be");
}

TEST(Warp, FactoriesRejectBadParameters) {
    expect_invalid([] { (void)make_pulse_warp({0, 0, 0}, 1.5, 0.0); }, "rate");
    expect_invalid([] { (void)make_stretch_warp({0, 0, 0}, {0, 0, 0}, 3, 1); }, "axis");
    expect_invalid([] { (void)make_twist_warp({0, 0, 0}, {1, 0, 0}, -1, 1, 1); }, "half_length");
    expect_invalid([] { (void)make_bend_warp({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, 1, 1, 1, 1); },
                   "parallel");
    expect_invalid([] { (void)make_bend_warp({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1, 7, 1, 1); },
                   "max_turn");
    const std::vector<Point3> two{{1, 0, 0}, {0, 1, 0}};  // sqrt 2 apart
    const std::vector<Vec3> small{{0, 0.1, 0}, {0, 0, 0.1}};
    expect_invalid([&] { (void)make_dimple_warp(two, small, 0.8, 1); }, "supports overlap");
    expect_invalid([&] { (void)make_dimple_warp(two, {{0, 0.5, 0}, {0, 0, 0}}, 0.5, 1); },
                   "Lipschitz");
    expect_invalid([&] { (void)make_dimple_warp(two, {{0, 0.1, 0}}, 0.5, 1); },
                   "2 centres but 1 displacements");
    expect_invalid([] { (void)make_dimple_warp({}, {}, 0.5, 1); }, "no centre");
    expect_invalid([&] { (void)make_dimple_warp(two, small, 0.0, 1); }, "radius");
    expect_invalid([&] { (void)make_dimple_warp(two, small, 0.5, -1); }, "rate");
    expect_invalid([&] { (void)make_dimple_warp(two, {{0, NAN, 0}, {0, 0, 0}}, 0.5, 1); },
                   "not finite");
}

// ---- sample edits --------------------------------------------------------------------------

TEST(SampleEdits, NothingToDoAtTimeZero) {
    for (const std::string& key : all_cases()) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        const SampleEdits e = plan_sample_edits(s, 0.0, s.initial, s.h0);
        EXPECT_TRUE(e.insert_pool.empty());
        EXPECT_TRUE(e.delete_pool.empty());
    }
    // A rigid motion changes no density either.
    const Scenario& rot = cached("rotate");
    const SampleEdits e = plan_sample_edits(rot, 0.3 * kSteps, rot.initial, rot.h0);
    EXPECT_TRUE(e.insert_pool.empty());
    EXPECT_TRUE(e.delete_pool.empty());
}

TEST(SampleEdits, InsertsWhereTheSurfaceStretches) {
    const Scenario& s = cached("stretch");
    const double peak = 0.5 * kSteps;
    // A finer insertion radius inserts more.
    EXPECT_GT(plan_sample_edits(s, peak, s.initial, 0.5 * s.h0).insert_pool.size(),
              s.initial.size() / 4);
    const SampleEdits e = plan_sample_edits(s, peak, s.initial, s.h0);
    ASSERT_GT(e.insert_pool.size(), 20u);
    EXPECT_TRUE(e.delete_pool.empty());  // nothing is compressed at the peak
    EXPECT_TRUE(std::is_sorted(e.insert_pool.begin(), e.insert_pool.end()));
    std::vector<char> live(s.pool_size(), 0);
    for (auto i : s.initial) live[i] = 1;
    double scale_inserted = 0, scale_all = 0;
    for (auto i : e.insert_pool) {
        EXPECT_FALSE(live[i]);
        scale_inserted += area_scale(s, peak, i);
    }
    for (auto i : s.initial) scale_all += area_scale(s, peak, i);
    scale_inserted /= static_cast<double>(e.insert_pool.size());
    scale_all /= static_cast<double>(s.initial.size());
    EXPECT_GT(scale_inserted, scale_all);  // insertions go where the area grew
    // Afterwards the live set covers Sigma(t) about as well as P(0) covered Sigma(0).
    std::vector<std::uint32_t> after = s.initial;
    after.insert(after.end(), e.insert_pool.begin(), e.insert_pool.end());
    const double h_before = sampling_radius(s, peak, s.initial);
    const double h_after = sampling_radius(s, peak, after);
    EXPECT_GT(h_before, 1.2 * s.h0);
    EXPECT_LT(h_after, 1.3 * s.h0);
    // Inserted points are more than insert_radius apart from each other and from P(t).
    const auto pts = pool_positions(s, peak, e.insert_pool);
    const auto live_pts = pool_positions(s, peak, s.initial);
    for (std::size_t i = 0; i < std::min<std::size_t>(pts.size(), 200); ++i) {
        for (std::size_t j = 0; j < i; ++j) EXPECT_GT(distance(pts[i], pts[j]), s.h0);
        for (const Point3& q : live_pts) ASSERT_GT(distance(pts[i], q), s.h0);
    }
}

TEST(SampleEdits, DeletesWhereTheSurfaceShrinksBack) {
    for (const std::string key : {"stretch", "pulse"}) {
        SCOPED_TRACE(key);
        const Scenario& s = cached(key);
        const double peak = 0.5 * kSteps, end = kSteps;
        // Make the peak as dense as P(0) was, then come back.
        const SampleEdits grow = plan_sample_edits(s, peak, s.initial, 0.5 * s.h0);
        std::vector<std::uint32_t> live = s.initial;
        live.insert(live.end(), grow.insert_pool.begin(), grow.insert_pool.end());
        std::sort(live.begin(), live.end());
        const SampleEdits shrink = plan_sample_edits(s, end, live, s.h0);
        EXPECT_TRUE(shrink.insert_pool.empty());
        ASSERT_FALSE(shrink.delete_pool.empty());
        EXPECT_LE(shrink.delete_pool.size(), live.size() / 2);
        EXPECT_TRUE(std::is_sorted(shrink.delete_pool.begin(), shrink.delete_pool.end()));
        // Deleted samples come from where the peak had stretched the surface the most.
        double scale_deleted = 0, scale_live = 0;
        for (auto i : shrink.delete_pool) scale_deleted += area_scale(s, peak, i);
        for (auto i : live) scale_live += area_scale(s, peak, i);
        scale_deleted /= static_cast<double>(shrink.delete_pool.size());
        scale_live /= static_cast<double>(live.size());
        if (key == std::string("stretch")) {
            EXPECT_GT(scale_deleted, scale_live);
        }
        // No hole: every deleted sample keeps a surviving sample within h0.
        std::vector<char> gone(s.pool_size(), 0);
        for (auto i : shrink.delete_pool) gone[i] = 1;
        std::vector<std::uint32_t> kept;
        for (auto i : live)
            if (!gone[i]) kept.push_back(i);
        const auto kept_pts = pool_positions(s, end, kept);
        for (const Point3& p : pool_positions(s, end, shrink.delete_pool)) {
            double d = 1e300;
            for (const Point3& q : kept_pts) d = std::min(d, distance(p, q));
            ASSERT_LE(d, s.h0);
        }
        // The density drops, and the sampling radius stays below that of P(0) plus h0.
        EXPECT_LT(sampling_radius(s, end, kept), 2 * s.h0);
    }
}

TEST(SampleEdits, NeverDeletesMoreThanHalf) {
    const Scenario& s = cached("pulse");
    // The whole pool is four times denser than P(0) everywhere.
    const std::vector<std::uint32_t> live = all_pool(s);
    const SampleEdits e = plan_sample_edits(s, 0.0, live, s.h0);
    EXPECT_TRUE(e.insert_pool.empty());
    EXPECT_GT(e.delete_pool.size(), live.size() / 5);
    EXPECT_LE(e.delete_pool.size(), live.size() / 2);
    // Deterministic.
    EXPECT_EQ(plan_sample_edits(s, 0.0, live, s.h0).delete_pool, e.delete_pool);
}

TEST(SampleEdits, RejectsBadArguments) {
    const Scenario& s = cached("pulse");
    expect_invalid([&] { (void)plan_sample_edits(s, 1.0, s.initial, 0.0); }, "insert_radius");
    expect_invalid([&] { (void)plan_sample_edits(s, 1.0, s.initial, std::nan("")); },
                   "insert_radius");
    const std::vector<std::uint32_t> bad{0, static_cast<std::uint32_t>(s.pool_size())};
    expect_invalid([&] { (void)plan_sample_edits(s, 1.0, bad, s.h0); }, "pool size");
    const std::vector<std::uint32_t> twice{3, 5, 3};
    expect_invalid([&] { (void)plan_sample_edits(s, 1.0, twice, s.h0); }, "twice");
    SampleEditOptions o;
    o.insert_radius = s.h0;
    o.target_ratio = 3;
    expect_invalid([&] { (void)plan_sample_edits(s, 1.0, s.initial, o); }, "target_ratio");
}

// ---- ground truth --------------------------------------------------------------------------

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
    ASSERT_EQ(v.size(), 16u);
    EXPECT_EQ(v[0].first, "t");
    bool found = false;
    for (const auto& [k, x] : v)
        if (k == "R_over_h") found = (x == 1.5);
    EXPECT_TRUE(found);
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
