#include "dynmesh/probing/oracles.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

constexpr Vec3 kX{1, 0, 0}, kY{0, 1, 0}, kZ{0, 0, 1};

TEST(SphereOracle, KnownHitsAndTmax) {
    const SphereOracle o(Sphere({1, 2, 3}, 2));
    EXPECT_DOUBLE_EQ(o.tolerance(), 2e-12);
    const auto h = o.cast({-4, 2, 3}, kX, 10);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 3, 1e-12);
    EXPECT_NEAR(distance(h->x, Point3{-1, 2, 3}), 0, 1e-12);
    EXPECT_FALSE(h->grazing);
    // Oblique: from (1, 2, 3) + (0, 1, 0) · 5 ... a ray at 60° to the normal.
    const Vec3 d = normalized(Vec3{1, -1, 0});
    const Point3 s = Point3{1, 2, 3} + 2 * normalized(Vec3{-1, 1, 0}) + 3 * (-d);
    const auto h2 = o.cast(s, d, 10);
    ASSERT_TRUE(h2);
    EXPECT_NEAR(h2->t, 3, 1e-12);
    // t_max is closed: exactly 3 hits, 3 - 1e-9 does not.
    EXPECT_TRUE(o.cast({-4, 2, 3}, kX, 3));
    EXPECT_FALSE(o.cast({-4, 2, 3}, kX, 3 - 1e-9));
    // Pointing away.
    EXPECT_FALSE(o.cast({-4, 2, 3}, -kX, 100));
}

TEST(SphereOracle, TangentRayIsGrazingOrIgnored) {
    const Sphere sphere({0, 0, 0}, 1);
    const SphereOracle o(sphere), strict(sphere, {.strict = true});
    const auto h = o.cast({-3, 1, 0}, kX, 10);  // touches (0, 1, 0)
    ASSERT_TRUE(h);
    EXPECT_TRUE(h->grazing);
    EXPECT_NEAR(distance(h->x, Point3{0, 1, 0}), 0, 1e-9);
    EXPECT_FALSE(strict.cast({-3, 1, 0}, kX, 10));
    EXPECT_FALSE(o.cast({-3, 1 + 1e-6, 0}, kX, 10));  // a clean miss
    const auto deep = o.cast({-3, 1 - 1e-6, 0}, kX, 10);
    ASSERT_TRUE(deep);
    EXPECT_FALSE(deep->grazing);
}

TEST(SphereOracle, StartOnAndInside) {
    const SphereOracle o(Sphere({0, 0, 0}, 1));
    EXPECT_THROW((void)o.cast({0.5, 0, 0}, kX, 1), InvalidInput);
    EXPECT_THROW((void)o.cast({3, 0, 0}, {2, 0, 0}, 1), InvalidInput);  // not unit
    // On S: entering is a hit at t = 0, leaving is no hit.
    const auto in = o.cast({1, 0, 0}, -kX, 5);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->t, 0);
    EXPECT_FALSE(o.cast({1 - 1e-13, 0, 0}, kX, 5));
}

TEST(EllipsoidOracle, KnownHits) {
    const EllipsoidOracle o(Ellipsoid({0, 0, 0}, 3, 2, 1));
    EXPECT_DOUBLE_EQ(o.tolerance(), 3e-12);
    for (const auto& [s, d, t] : {std::tuple{Point3{-5, 0, 0}, kX, 2.0},
                                  std::tuple{Point3{0, 7, 0}, -kY, 5.0},
                                  std::tuple{Point3{0, 0, -4}, kZ, 3.0}}) {
        const auto h = o.cast(s, d, 100);
        ASSERT_TRUE(h);
        EXPECT_NEAR(h->t, t, 1e-12);
        EXPECT_NEAR(o.shape().value(h->x), 0, 1e-12);
    }
    // An oblique ray hits where the implicit changes sign.
    const Vec3 d = normalized(Vec3{1, 1, 0.5});
    const Point3 s{-4, -4, -2};
    const auto h = o.cast(s, d, 100);
    ASSERT_TRUE(h);
    EXPECT_GT(o.shape().value(s + (h->t - 1e-6) * d), 0);
    EXPECT_LT(o.shape().value(s + (h->t + 1e-6) * d), 0);
    EXPECT_NEAR(o.reach(), 1.0 / 3, 1e-15);
    EXPECT_THROW((void)o.cast({0, 0, 0.5}, kX, 1), InvalidInput);
    // Tangent at the tip of the z axis: grazing (default) or nothing (strict).
    const EllipsoidOracle strict(o.shape(), {.strict = true});
    EXPECT_FALSE(strict.cast({-5, 0, 1}, kX, 10));
    const auto g = o.cast({-5, 0, 1}, kX, 10);
    ASSERT_TRUE(g);
    EXPECT_TRUE(g->grazing);
}

TEST(TorusOracle, KnownHits) {
    const TorusOracle o(Torus({0, 0, 0}, 2, 1));
    EXPECT_DOUBLE_EQ(o.tolerance(), 3e-12);
    const auto h = o.cast({5, 0, 0}, -kX, 100);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 2, 1e-12);
    // Down the axis: no hit (the hole); down at rho = 2: hits the top at z = 1.
    EXPECT_FALSE(o.cast({0, 0, 5}, -kZ, 100));
    const auto top = o.cast({0, 2, 5}, -kZ, 100);
    ASSERT_TRUE(top);
    EXPECT_NEAR(top->t, 4, 1e-12);
    // Through the hole along x from the inside equator: from (0,0,0) the ray hits rho = 1.
    const auto hole = o.cast({0, 0, 0}, kY, 100);
    ASSERT_TRUE(hole);
    EXPECT_NEAR(hole->t, 1, 1e-12);
    EXPECT_FALSE(o.cast({0, 0, 0}, kY, 1 - 1e-9));
    EXPECT_THROW((void)o.cast({2, 0, 0}, kX, 1), InvalidInput);
    // An unbounded ray: t_max = +infinity.
    EXPECT_FALSE(o.cast({5, 0, 0}, kX, INFINITY));
    ASSERT_TRUE(o.cast({5, 0, 0}, -kX, INFINITY));
    EXPECT_THROW((void)o.cast({5, 0, 0}, -kX, NAN), InvalidInput);
    // Oblique rays: the implicit changes sign at the hit, and the hit is the first one.
    const Vec3 d = normalized(Vec3{-1, 0.3, -0.4});
    const Point3 s{6, -1, 2.5};
    const auto o1 = o.cast(s, d, 100);
    ASSERT_TRUE(o1);
    EXPECT_GT(o.shape().value(s + (o1->t - 1e-6) * d), 0);
    EXPECT_LT(o.shape().value(s + (o1->t + 1e-6) * d), 0);
    for (int k = 0; k < 1000; ++k)
        EXPECT_GE(o.shape().signed_distance(s + (o1->t * k / 1000.0) * d), -1e-12);
}

TEST(TorusOracle, TangentRay) {
    const Torus torus({0, 0, 0}, 2, 1);
    const TorusOracle o(torus), strict(torus, {.strict = true});
    // Tangent to the top circle z = 1 along x at y = 2: touches (0, 2, 1).
    const auto h = o.cast({-5, 2, 1}, kX, 100);
    ASSERT_TRUE(h);
    EXPECT_TRUE(h->grazing);
    EXPECT_FALSE(strict.cast({-5, 2, 1}, kX, 100));
    // Tangent to the outer equator at (3, 0, 0) along y.
    EXPECT_FALSE(strict.cast({3, -5, 0}, kY, 100));
    const auto e = o.cast({3, -5, 0}, kY, 100);
    ASSERT_TRUE(e);
    EXPECT_TRUE(e->grazing);
}

TEST(BallsOracle, SmallestRootAndRefusals) {
    const BallsOracle o({{{0, 0, 0}, 1}, {{5, 0, 0}, 1}, {{-6, 0, 0}, 2}});
    const auto h = o.cast({2.5, 0, 0}, kX, 100);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 1.5, 1e-12);
    const auto l = o.cast({2.5, 0, 0}, -kX, 100);
    ASSERT_TRUE(l);
    EXPECT_NEAR(l->t, 1.5, 1e-12);
    const auto far = o.cast({-10, 0, 0}, kX, 100);
    ASSERT_TRUE(far);
    EXPECT_NEAR(far->t, 2, 1e-12);
    // Through the gap between ball 0 and ball 1 from above: no hit.
    EXPECT_FALSE(o.cast({2.5, 0, 5}, -kZ, 100));
    EXPECT_NEAR(o.reach(), 1, 1e-15);  // min r = 1, gaps 3 and 3 -> 1.5
    const BallsOracle close({{{0, 0, 0}, 1}, {{2.5, 0, 0}, 1}});
    EXPECT_NEAR(close.reach(), 0.25, 1e-15);
    EXPECT_EQ(o.components(), 3);
    EXPECT_EQ(o.euler_characteristic(), 6);
    EXPECT_NEAR(o.area(), 4 * std::numbers::pi * 6, 1e-12);
    EXPECT_THROW((void)o.cast({5.5, 0, 0}, kX, 1), InvalidInput);
    try {
        const BallsOracle bad({{{0, 0, 0}, 1}, {{5, 0, 0}, 1}, {{1.5, 0, 0}, 1}});
        FAIL() << "overlapping balls accepted";
    } catch (const InvalidInput& e) {
        EXPECT_EQ(e.element, 2u);
        EXPECT_NE(std::string(e.what()).find("overlap"), std::string::npos);
    }
    EXPECT_THROW(BallsOracle({{{0, 0, 0}, 1}, {{2, 0, 0}, 1}}), InvalidInput);  // touching
}

TEST(BallsOracle, StrictSkipsAGrazedBallForTheNextOne) {
    // The ray along x at y = 1 touches ball 0 at (0, 1, 0), then crosses ball 1 at x = 5 − √0.75.
    const std::vector<Ball> balls{{{0, 0, 0}, 1}, {{5, 0.5, 0}, 1}};
    const BallsOracle o(balls), strict(balls, {.strict = true});
    const auto g = o.cast({-3, 1, 0}, kX, 100);
    ASSERT_TRUE(g);
    EXPECT_TRUE(g->grazing);
    EXPECT_NEAR(g->t, 3, 1e-9);
    const auto s = strict.cast({-3, 1, 0}, kX, 100);
    ASSERT_TRUE(s);
    EXPECT_FALSE(s->grazing);
    EXPECT_NEAR(s->t, 8 - std::sqrt(0.75), 1e-12);
    // segment_is_free is conservative at the tangency.
    EXPECT_FALSE(o.segment_is_free({-3, 1, 0}, {2, 1, 0}));
    EXPECT_TRUE(o.segment_is_free({-3, 1.001, 0}, {2, 1.001, 0}));
}

TEST(EllipsoidOracle, StartOnS) {
    const EllipsoidOracle o(Ellipsoid({0, 0, 0}, 3, 2, 1));
    EXPECT_FALSE(o.cast({3, 0, 0}, kX, 10));  // leaving
    const auto in = o.cast({3, 0, 0}, -kX, 10);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->t, 0);
    EXPECT_FALSE(in->grazing);
}

TEST(Genus2Oracle, TopologyAndHitsAgreeWithTheImplicit) {
    const Genus2Oracle o;
    EXPECT_EQ(o.euler_characteristic(), -2);
    EXPECT_EQ(o.components(), 1);
    EXPECT_LT(o.value(Genus2Oracle::interior_point()), 0);
    // Down the z axis through the origin: the blended neck.
    const auto neck = o.cast({0, 0, 3}, -kZ, 10);
    ASSERT_TRUE(neck);
    // On the z axis a = b = sqrt(0.25² + z²) − 0.4 and f = a − k/4 = a − 0.15: z = sqrt(0.24).
    EXPECT_NEAR(neck->t, 3 - std::sqrt(0.24), 1e-12);
    EXPECT_GT(o.value({0, 0, 3 - neck->t + 1e-9}), 0);
    EXPECT_LT(o.value({0, 0, 3 - neck->t - 1e-9}), 0);
    // The two holes are free: down through (±1.25, 0).
    EXPECT_FALSE(o.cast({-1.25, 0, 3}, -kZ, 10));
    EXPECT_FALSE(o.cast({1.25, 0, 3}, -kZ, 10));
    // Along x from outside: hits the left torus's outer equator at x = -2.65.
    const auto side = o.cast({-5, 0, 0}, kX, 10);
    ASSERT_TRUE(side);
    EXPECT_NEAR(side->t, 5 - 2.65, 1e-12);
    // Random rays: a sign change at every hit, none before it.
    Rng rng(7);
    int hits = 0;
    for (int k = 0; k < 200; ++k) {
        const Point3 s = 4.0 * rng.unit_vector();
        const Vec3 d = normalized(Point3{rng.uniform(-1, 1), rng.uniform(-1, 1), 0} - s);
        const auto h = o.cast(s, d, 10);
        if (!h) continue;
        ++hits;
        EXPECT_GT(o.value(s + (h->t - 1e-7) * d), 0);
        EXPECT_LT(o.value(s + (h->t + 1e-7) * d), 0);
        for (int i = 0; i < 100; ++i) EXPECT_GE(o.value(s + (h->t * i / 100.0) * d), -1e-12);
    }
    EXPECT_GT(hits, 100);
    // The grid sample lies on S.
    for (const Point3& p : o.sample_surface(0.2)) EXPECT_NEAR(o.value(p), 0, 1e-12);
}

TEST(Genus2Oracle, ShallowChordsAreNotSkipped) {
    // Rays that cross S along a short chord (depth 0.01 below a surface point, tangentially):
    // the reported hit is the first crossing, with no interior sample before it.
    const Genus2Oracle o;
    Rng rng(11);
    const auto pts = o.sample_surface(0.25);
    int tested = 0;
    for (std::size_t k = 0; k < pts.size(); k += 7) {
        const Point3 p = pts[k];
        const Vec3 n = normalized(o.gradient(p));
        const Vec3 u = normalized(cross(n, rng.unit_vector()));
        const Point3 target = p - 0.01 * n;
        const Point3 s = target - 3.0 * u;
        if (o.value(s) <= 0) continue;
        ++tested;
        const auto h = o.cast(s, u, 6);
        ASSERT_TRUE(h) << "a ray through an interior point was declared free";
        EXPECT_LE(h->t, 3);
        for (int i = 0; i < 2000; ++i) EXPECT_GE(o.value(s + (h->t * i / 2000.0) * u), -1e-12);
    }
    EXPECT_GT(tested, 50);
}

/// Gauss–Bonnet on the implicit: ∫ K dA / 2π by the coarea formula on a grid (δ(f) smoothed
/// to a box of half-width w), K from the finite-difference Hessian of f.
double numeric_euler(const Genus2Oracle& o) {
    const Bbox3 b = Genus2Oracle::bbox();
    constexpr double g = 0.015, w = 0.015, e = 1e-5;
    double sum = 0;
    for (double x = b.min.x + g / 2; x < b.max.x; x += g)
        for (double y = b.min.y + g / 2; y < b.max.y; y += g)
            for (double z = b.min.z + g / 2; z < b.max.z; z += g) {
                const Point3 p{x, y, z};
                if (std::fabs(o.value(p)) >= w) continue;
                const Vec3 n = o.gradient(p);
                double H[3][3];
                for (std::size_t i = 0; i < 3; ++i) {
                    Vec3 dx{};
                    dx[i] = e;
                    const Vec3 gp = o.gradient(p + dx), gm = o.gradient(p - dx);
                    for (std::size_t j = 0; j < 3; ++j) H[j][i] = (gp[j] - gm[j]) / (2 * e);
                }
                // K = n^T adj(H) n / |n|^4.
                const double adj[3][3] = {
                    {H[1][1] * H[2][2] - H[1][2] * H[2][1], H[0][2] * H[2][1] - H[0][1] * H[2][2],
                     H[0][1] * H[1][2] - H[0][2] * H[1][1]},
                    {H[1][2] * H[2][0] - H[1][0] * H[2][2], H[0][0] * H[2][2] - H[0][2] * H[2][0],
                     H[0][2] * H[1][0] - H[0][0] * H[1][2]},
                    {H[1][0] * H[2][1] - H[1][1] * H[2][0], H[0][1] * H[2][0] - H[0][0] * H[2][1],
                     H[0][0] * H[1][1] - H[0][1] * H[1][0]}};
                double k = 0;
                for (std::size_t i = 0; i < 3; ++i)
                    for (std::size_t j = 0; j < 3; ++j) k += n[i] * adj[i][j] * n[j];
                const double nn = sqnorm(n);
                sum += k / (nn * nn) * std::sqrt(nn);
            }
    return sum * g * g * g / (2 * w) / (2 * std::numbers::pi);
}

TEST(Genus2Oracle, EulerCharacteristicByGaussBonnet) {
    const Genus2Oracle o;
    EXPECT_NEAR(numeric_euler(o), o.euler_characteristic(), 0.15);
}

TEST(Genus2Oracle, Area) {
    const Genus2Oracle o;
    // Two full tori would be 2 · 4π² · 1 · 0.4 = 31.58; the neck removes a little.
    EXPECT_LT(o.area(), 2 * 4 * std::numbers::pi * std::numbers::pi * 0.4);
    EXPECT_NEAR(o.area(), 30.2, 0.15);  // regression value of the grid integral
}

TriangleSoup unit_icosphere(int level) { return test::icosphere(level).to_soup(); }

TEST(MeshOracle, IcosphereAgreesWithTheSphere) {
    const MeshOracle mesh(unit_icosphere(4));
    const SphereOracle sphere(Sphere({0, 0, 0}, 1));
    // Level 4: edges ≈ 0.077, so the mesh lies within 1 − cos(edge) ≈ 1e-3 of the sphere.
    const double tol = 2e-3;
    Rng rng(3);
    for (int k = 0; k < 300; ++k) {
        const Point3 s = 3.0 * rng.unit_vector();
        const Vec3 d = normalized(0.8 * rng.unit_vector() - s);
        const auto a = mesh.cast(s, d, 10), b = sphere.cast(s, d, 10);
        ASSERT_TRUE(a && b);
        EXPECT_NEAR(a->t, b->t, tol / std::max(0.05, -dot(d, normalized(b->x))));
        EXPECT_NEAR(norm(a->x), 1, tol);
    }
    EXPECT_FALSE(mesh.cast({0, 0, 3}, kZ, 10));
    EXPECT_FALSE(mesh.cast({0, 0, 3}, -kZ, 1.5));
    EXPECT_THROW((void)mesh.cast({0, 0, 0.5}, kX, 1), InvalidInput);
    EXPECT_EQ(mesh.euler_characteristic(), 2);
    EXPECT_EQ(mesh.components(), 1);
    EXPECT_NEAR(mesh.area(), 4 * std::numbers::pi, 0.02);
    EXPECT_TRUE(mesh.is_free({0, 0, 1.01}));
    EXPECT_FALSE(mesh.is_free({0, 0, 0.9}));
    EXPECT_TRUE(mesh.segment_is_free({-2, 0, 1.5}, {2, 0, 1.5}));
    EXPECT_FALSE(mesh.segment_is_free({-2, 0, 0}, {2, 0, 0}));
    const auto inside = mesh.interior_points();
    ASSERT_EQ(inside.size(), 1u);
    EXPECT_FALSE(mesh.is_free(inside[0]));
}

TEST(MeshOracle, StartOnTheMeshLeaving) {
    const MeshOracle mesh(unit_icosphere(2));
    const auto h = mesh.cast({0, 0, 3}, -kZ, 10);
    ASSERT_TRUE(h);
    EXPECT_FALSE(mesh.cast(h->x, kZ, 10));  // leaving from S
    const auto again = mesh.cast(h->x, -kZ, 10);  // entering from S
    ASSERT_TRUE(again);
    EXPECT_NEAR(again->t, 0, 1e-9);
}

TEST(MeshOracle, ContactsAlongAnEdgeOrAtAVertexAreGrazing) {
    const TriangleSoup octa = test::octahedron().to_soup();
    const MeshOracle o(octa), strict(octa, {.strict = true});
    // Along the line of the edge (1,0,0)-(0,1,0): in the plane of both its faces.
    const Vec3 d = normalized(Vec3{-1, 1, 0});
    const auto e = o.cast({2, -1, 0}, d, 10);
    ASSERT_TRUE(e);
    EXPECT_TRUE(e->grazing);
    EXPECT_NEAR(e->t, std::sqrt(2.0), 1e-12);
    EXPECT_FALSE(strict.cast({2, -1, 0}, d, 10));
    // Touching the apex (0, 0, 1) from the side.
    const auto v = o.cast({-2, 0, 1}, kX, 10);
    ASSERT_TRUE(v);
    EXPECT_TRUE(v->grazing);
    EXPECT_NEAR(v->t, 2, 1e-12);
    EXPECT_FALSE(strict.cast({-2, 0, 1}, kX, 10));
    // A transverse crossing is not grazing.
    const auto t = o.cast({0.1, 0.1, 3}, -kZ, 10);
    ASSERT_TRUE(t);
    EXPECT_FALSE(t->grazing);
    EXPECT_NEAR(t->t, 2.2, 1e-12);
}

TEST(MeshOracle, RefusesOpenAndInconsistentMeshes) {
    TriangleSoup open = unit_icosphere(1);
    open.triangles.pop_back();
    try {
        const MeshOracle m(open);
        FAIL() << "open mesh accepted";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("not closed"), std::string::npos) << e.what();
    }
    TriangleSoup flipped = unit_icosphere(1);
    std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
    try {
        const MeshOracle m(flipped);
        FAIL() << "inconsistently oriented mesh accepted";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("oriented"), std::string::npos) << e.what();
    }
}

TEST(MeshOracle, GenusTwoFile) {
    const auto setup = make_probe_object(test::shared_data("meshes/eight.off").string());
    EXPECT_EQ(setup.object->euler_characteristic(), -2);
    ASSERT_EQ(setup.interior_points.size(), 1u);
    EXPECT_FALSE(setup.object->is_free(setup.interior_points[0]));
    // Ω contains S with margin: every vertex is well inside.
    for (const Point3& p : setup.object->sample_surface(1e9))
        EXPECT_LT(distance(p, setup.omega.center), setup.omega.radius * 0.95);
}

TEST(MakeProbeObject, DefectiveMeshFilesAreRefusedWithTheirName) {
    const auto border = test::shared_data("meshes/defective/mesh_with_border.off").string();
    try {
        (void)make_probe_object(border);
        FAIL();
    } catch (const InvalidInput& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("mesh_with_border.off"), std::string::npos) << m;
        EXPECT_NE(m.find("not closed"), std::string::npos) << m;
    }
    const auto pinched = test::shared_data("meshes/defective/cow_nonmanifold_vertex.obj").string();
    try {
        (void)make_probe_object(pinched);
        FAIL();
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("2-manifold"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)make_probe_object("/nonexistent/mesh.off"), IoError);
}

TEST(MakeProbeObject, Specs) {
    const auto t = make_probe_object("torus:2,0.5");
    EXPECT_NE(dynamic_cast<const TorusOracle*>(t.object.get()), nullptr);
    EXPECT_FALSE(t.object->is_free(t.interior_points.at(0)));
    EXPECT_GE(t.omega.radius, 2.5);
    const auto g = make_probe_object("genus2");
    EXPECT_EQ(g.object->euler_characteristic(), -2);
    EXPECT_THROW((void)make_probe_object("cube:1"), InvalidInput);
    EXPECT_THROW((void)make_probe_object("sphere:-1"), InvalidInput);
}

TEST(MakeProbeObject, BallsFile) {
    const auto dir = test::scratch_dir("probing_balls");
    const auto good = dir / "good.txt";
    std::ofstream(good) << "# two balls\n0 0 0 1\n\n4 0 0 0.5 # second\n";
    const auto s = make_probe_object("balls:" + good.string());
    EXPECT_EQ(s.object->components(), 2);
    ASSERT_EQ(s.interior_points.size(), 2u);
    for (const Point3& p : s.interior_points) EXPECT_FALSE(s.object->is_free(p));
    const auto bad = dir / "bad.txt";
    std::ofstream(bad) << "0 0 0 1\n# comment\n0.5 0 0 1\n";
    try {
        (void)make_probe_object("balls:" + bad.string());
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.txt:3:"), std::string::npos) << e.what();
    }
    const auto junk = dir / "junk.txt";
    std::ofstream(junk) << "0 0 0 1\n1 2 x 3\n";
    try {
        (void)make_probe_object("balls:" + junk.string());
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("junk.txt:2:"), std::string::npos) << e.what();
    }
}

TEST(GroundTruth, FreePointOfASegmentBetweenTwoComponents) {
    // Two unit spheres centred at x = ±1.5: the segment between their centres leaves O for
    // |x| < 0.5 (about, on the level-3 mesh).
    TriangleSoup two = unit_icosphere(3);
    const std::size_t n = two.points.size(), m = two.triangles.size();
    for (std::size_t i = 0; i < n; ++i) {
        two.points.push_back(two.points[i] + Vec3{1.5, 0, 0});
        two.points[i] = two.points[i] - Vec3{1.5, 0, 0};
    }
    for (std::size_t k = 0; k < m; ++k) {
        auto t = two.triangles[k];
        for (auto& v : t) v += std::uint32_t(n);
        two.triangles.push_back(t);
    }
    const MeshOracle mesh(two);
    const BallsOracle balls({{{-1.5, 0, 0}, 1}, {{1.5, 0, 0}, 1}});
    const Point3 a{-1.5, 0, 0}, b{1.5, 0, 0};
    for (const GroundTruth* g : {static_cast<const GroundTruth*>(&mesh), static_cast<const GroundTruth*>(&balls)}) {
        const auto t = g->free_point_on(a, b);
        ASSERT_TRUE(t);
        EXPECT_GT(*t, 0.9);
        EXPECT_LT(*t, 2.1);
        EXPECT_TRUE(g->is_free(a + *t * kX));
        // Within one component there is none; a free end is found at once.
        EXPECT_FALSE(g->free_point_on(a, a + 0.9 * kX));
        EXPECT_FALSE(g->free_point_on(a + 0.2 * kY, a + 0.3 * kZ));
        EXPECT_EQ(g->free_point_on({0, 0, 0}, a), 0.0);
    }
}

TEST(GroundTruth, SegmentsOfImplicitShapes) {
    const TorusOracle o(Torus({0, 0, 0}, 2, 1));
    EXPECT_TRUE(o.segment_is_free({0, 0, 5}, {0, 0, -5}));  // down the hole
    EXPECT_FALSE(o.segment_is_free({-5, 0, 0}, {5, 0, 0}));
    EXPECT_TRUE(o.segment_is_free({5, 0, 0}, {3, 0, 0}));  // ends on S
    EXPECT_FALSE(o.segment_is_free({5, 0, 0}, {2.9, 0, 0}));
    EXPECT_NEAR(o.distance({5, 0, 0}), 2, 1e-15);
}

}  // namespace
}  // namespace dynmesh
