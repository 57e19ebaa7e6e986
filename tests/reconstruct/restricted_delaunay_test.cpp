#include "dynmesh/reconstruct/restricted_delaunay.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

/// Closed, with Euler characteristic `euler`, enclosing a positive volume, every face facing
/// along the surface normal, and every vertex bit-identical to the sample the report names, in
/// input order.
void expect_valid_rdt(const RestrictedDelaunayResult& r, std::span<const Point3> samples,
                      const ImplicitSurface& surface, long long euler, const std::string& ctx) {
    const auto check = check_mesh(r.mesh, {.require_closed = true});
    EXPECT_TRUE(check.ok()) << ctx << "\n" << check.summary("  ");
    EXPECT_EQ(check.integer("euler"), euler) << ctx;
    EXPECT_EQ(check.integer("components"), 1) << ctx;
    EXPECT_GT(test::signed_volume(r.mesh), 0) << ctx;
    std::size_t inward = 0;
    for (Face f : r.mesh.faces()) {
        const auto c = r.mesh.face_vertices(f);
        const Point3 &a = r.mesh.position(c[0]), &b = r.mesh.position(c[1]),
                     &d = r.mesh.position(c[2]);
        if (dot(triangle_normal(a, b, d), surface.normal((a + b + d) / 3.0)) <= 0) ++inward;
    }
    EXPECT_EQ(inward, 0u) << ctx;
    ASSERT_EQ(r.report.vertex_sample.size(), r.mesh.n_vertices()) << ctx;
    EXPECT_TRUE(std::is_sorted(r.report.vertex_sample.begin(), r.report.vertex_sample.end()));
    for (Vertex v : r.mesh.vertices()) {
        const Point3& p = r.mesh.position(v);
        const Point3& s = samples[r.report.vertex_sample[v.idx()]];
        ASSERT_TRUE(p.x == s.x && p.y == s.y && p.z == s.z) << ctx << " vertex " << v.idx();
    }
    EXPECT_EQ(r.report.samples, samples.size());
    EXPECT_EQ(r.report.vertices_used + r.report.unused_samples, samples.size());
    EXPECT_EQ(r.report.facets, r.mesh.n_faces());
}

TEST(RestrictedDelaunay, UnitSphereGivesTheConvexHull) {
    const Sphere sphere({0, 0, 0}, 1);
    const auto samples = sphere.sample_uniform(10000, 1);
    const auto r = restricted_delaunay_with_report(samples, sphere);
    expect_valid_rdt(r, samples, sphere, 2, "sphere");
    // Every sample of a sphere is a hull vertex, and the hull of n points has 2n - 4 faces.
    EXPECT_EQ(r.report.unused_samples, 0u);
    EXPECT_EQ(r.mesh.n_faces(), 2 * samples.size() - 4);
    EXPECT_NEAR(test::signed_volume(r.mesh), 4 * kPi / 3, 0.01);
    // Each face is a hull face: no sample lies outside its plane (checked on every 7th face).
    std::size_t k = 0;
    for (Face f : r.mesh.faces()) {
        if (k++ % 7 != 0) continue;
        const auto c = r.mesh.face_vertices(f);
        const Point3 &a = r.mesh.position(c[0]), &b = r.mesh.position(c[1]),
                     &d = r.mesh.position(c[2]);
        const Vec3 n = triangle_normal(a, b, d);
        double outside = -1;
        for (const Point3& p : samples) outside = std::max(outside, dot(n, p - a));
        ASSERT_LT(outside, 1e-12) << "face " << f.idx() << " is not on the hull";
    }
}

TEST(RestrictedDelaunay, TorusIsAClosedGenusOneSurface) {
    const Torus torus({0.5, -0.25, 1}, 5, 3);
    for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
        const auto samples = torus.sample_uniform(10000, seed);
        const auto r = restricted_delaunay_with_report(samples, torus);
        expect_valid_rdt(r, samples, torus, 0, "torus seed " + std::to_string(seed));
        const double volume = 2 * kPi * kPi * 5 * 9;
        EXPECT_NEAR(test::signed_volume(r.mesh) / volume, 1, 0.02) << "seed " << seed;
        EXPECT_EQ(r.report.unused_samples, 0u);
    }
}

TEST(RestrictedDelaunay, OffCentreEllipsoid) {
    const Ellipsoid e({10, -20, 5}, 3, 1, 2);
    const auto samples = e.sample_uniform(6000, 9);
    const auto r = restricted_delaunay_with_report(samples, e);
    expect_valid_rdt(r, samples, e, 2, "ellipsoid");
    // The volume about the origin is the enclosed volume for a closed surface.
    EXPECT_NEAR(test::signed_volume(r.mesh) / (4 * kPi / 3 * 6), 1, 0.02);
}

TEST(RestrictedDelaunay, PlainCallAndSampleAndMeshAgree) {
    const Torus torus({0, 0, 0}, 5, 3);
    const auto samples = torus.sample_uniform(10000, 2);
    const SurfaceMesh a = restricted_delaunay(samples, torus);
    const SurfaceMesh b = sample_and_mesh(torus, 10000, 2);
    const auto sa = a.to_soup(), sb = b.to_soup();
    EXPECT_TRUE(sa.points == sb.points);
    EXPECT_TRUE(sa.triangles == sb.triangles);
    EXPECT_EQ(check_mesh(b, {.require_closed = true}).integer("euler"), 0);
}

std::string message_of(std::span<const Point3> samples, const ImplicitSurface& s,
                       const RestrictedDelaunayOptions& o = RestrictedDelaunayOptions{}) {
    try {
        (void)restricted_delaunay(samples, s, o);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "no exception";
}

TEST(RestrictedDelaunay, RejectsBadSamples) {
    const Sphere sphere({0, 0, 0}, 1);
    auto samples = sphere.sample_uniform(200, 3);
    samples[17] = samples[3];
    samples[150] = samples[40];
    const std::string dup = message_of(samples, sphere);
    EXPECT_NE(dup.find("3 and 17"), std::string::npos) << dup;
    EXPECT_NE(dup.find("40 and 150"), std::string::npos) << dup;

    samples = sphere.sample_uniform(200, 3);
    samples[5].y = std::nan("");
    EXPECT_NE(message_of(samples, sphere).find("sample 5"), std::string::npos);

    const std::vector<Point3> three{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    EXPECT_NE(message_of(three, sphere).find("at least 4"), std::string::npos);
    std::vector<Point3> flat;
    for (int k = 0; k < 20; ++k) flat.push_back({std::cos(k * 0.3), std::sin(k * 0.3), 0});
    EXPECT_NE(message_of(flat, sphere).find("coplanar"), std::string::npos);
}

TEST(RestrictedDelaunay, ThinTorus) {
    // Reach 1, tube circumference 2 pi: long thin Voronoi cells around the tube.
    const Torus torus({0, 0, 0}, 5, 1);
    for (std::uint64_t seed : {1u, 2u}) {
        const auto samples = torus.sample_uniform(10000, seed);
        expect_valid_rdt(restricted_delaunay_with_report(samples, torus), samples, torus, 0,
                         "thin torus seed " + std::to_string(seed));
    }
}

TEST(RestrictedDelaunay, DualEdgeThatEntersAndLeavesTheSurfaceCounts) {
    // Two tetrahedra on a big triangle around a unit sphere: their circumcentres (0, 0, +-7.5)
    // are both outside the sphere, but the Voronoi edge between them passes through it, so
    // the big triangle is a restricted facet (and alone, so not a closed surface).
    const Sphere unit({0, 0, 0}, 1);
    const double s3 = std::sqrt(3.0);
    const std::vector<Point3> points{
        {10, 0, 0}, {-5, 5 * s3, 0}, {-5, -5 * s3, 0}, {0, 0, 20}, {0, 0, -20}};
    const std::string found = message_of(points, unit);
    EXPECT_NE(found.find("3 non-manifold edges (3 with one facet"), std::string::npos) << found;
    // With no evaluations beyond the ends, only the sign change would count: nothing is kept.
    const std::string ends_only = message_of(points, unit, {.max_evaluations_per_edge = 0});
    EXPECT_NE(ends_only.find("no Delaunay facet meets the surface"), std::string::npos)
        << ends_only;
}

TEST(RestrictedDelaunay, SparseSampleIsRejected) {
    // (These tiny samples of torus:5,3 give non-manifold RDTs; from about 50 points on, most
    // seeds already give a closed genus-1 surface.)
    const Torus torus({0, 0, 0}, 5, 3);
    for (std::size_t n : {10u, 20u, 30u}) {
        const auto samples = torus.sample_uniform(n, 1);
        const std::string what = message_of(samples, torus);
        EXPECT_NE(what.find("is not a 2-manifold"), std::string::npos) << what;
        EXPECT_NE(what.find("too sparse"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace dynmesh
