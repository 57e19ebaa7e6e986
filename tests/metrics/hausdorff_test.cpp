#include "dynmesh/metrics/hausdorff.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/metrics/quality.hpp"
#include "dynmesh/shapes/surface.hpp"
#include "test_sphere.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

SurfaceMesh translated(SurfaceMesh mesh, const Vec3& t) {
    for (const Vertex v : mesh.vertices()) mesh.position(v) += t;
    return mesh;
}

TEST(MeshSamplePoints, CountsFollowTheGrid) {
    const SurfaceMesh mesh = test::icosphere(1);
    const std::size_t V = mesh.n_vertices(), E = mesh.n_edges(), F = mesh.n_faces();
    EXPECT_EQ(mesh_sample_points(mesh, 1).size(), V + F);          // vertices + barycentres
    EXPECT_EQ(mesh_sample_points(mesh, 2).size(), V + E + F);      // + edge midpoints
    EXPECT_EQ(mesh_sample_points(mesh, 3).size(), V + 2 * E + F);  // barycentre on the grid
    EXPECT_EQ(mesh_sample_points(mesh, 4).size(), V + 3 * E + 4 * F);
    EXPECT_THROW((void)mesh_sample_points(mesh, 0), InvalidInput);
}

TEST(MeshSamplePoints, LieOnTheMesh) {
    // Samples of an octahedron satisfy |x| + |y| + |z| = 1.
    for (std::size_t k : {1u, 2u, 5u})
        for (const Point3& p : mesh_sample_points(test::octahedron(), k))
            EXPECT_NEAR(std::abs(p.x) + std::abs(p.y) + std::abs(p.z), 1.0, 1e-12);
}

TEST(Hausdorff, MeshToItselfIsZero) {
    for (const SurfaceMesh& mesh : {test::icosphere(3), test::grid(5), test::octahedron()}) {
        const HausdorffResult r = hausdorff(mesh, mesh);
        EXPECT_NEAR(r.distance, 0.0, 1e-12);
        EXPECT_EQ(r.a_samples, r.b_samples);
        EXPECT_GT(r.a_samples, mesh.n_vertices());
    }
}

TEST(Hausdorff, TranslatedCopyIsTheTranslation) {
    // For a convex polytope P, H(P, P + t) = |t|: every point moves by |t|, and the extreme
    // vertex of P in direction t ends up |t| beyond P's supporting plane.
    for (const Vec3 t : {Vec3{0.3, 0, 0}, Vec3{0.3, -0.2, 0.1}, Vec3{0, 0, 0.05}}) {
        for (const SurfaceMesh& mesh : {test::octahedron(), test::icosphere(2)}) {
            const HausdorffResult r = hausdorff(mesh, translated(mesh, t));
            EXPECT_NEAR(r.distance, norm(t), 1e-12);
            EXPECT_NEAR(r.a_to_b, norm(t), 1e-12);
            EXPECT_NEAR(r.b_to_a, norm(t), 1e-12);
            EXPECT_DOUBLE_EQ(hausdorff_distance(mesh, translated(mesh, t)), r.distance);
        }
    }
    // A flat grid lifted off its plane.
    EXPECT_NEAR(hausdorff_distance(test::grid(4), translated(test::grid(4), {0, 0, 0.25})), 0.25,
                1e-12);
}

TEST(Hausdorff, IsSymmetricAndTwoSided) {
    // A small patch against a big grid: the patch is on the grid (0 one way), but most of
    // the grid is far from the patch.
    const SurfaceMesh big = test::grid(4), small = test::grid(1);
    const HausdorffResult r = hausdorff(small, big);
    EXPECT_NEAR(r.a_to_b, 0.0, 1e-12);
    EXPECT_NEAR(r.b_to_a, std::sqrt(3.0 * 3.0 + 3.0 * 3.0), 1e-12);  // corner (4,4) to (1,1)
    const HausdorffResult s = hausdorff(big, small);
    EXPECT_DOUBLE_EQ(s.a_to_b, r.b_to_a);
    EXPECT_DOUBLE_EQ(s.b_to_a, r.a_to_b);
    EXPECT_DOUBLE_EQ(s.distance, r.distance);
}

TEST(Hausdorff, CoarseAgainstFineSphere) {
    // Both icospheres are inscribed in the unit sphere, so their distance is about the
    // coarse one's sagitta.
    const SurfaceMesh coarse = test::icosphere(1), fine = test::icosphere(4);
    const test::TestSphere sphere;
    const double to_sphere = hausdorff_to_surface(coarse, sphere).a_to_b;
    const double d = hausdorff_distance(coarse, fine);
    EXPECT_GT(d, 0.8 * to_sphere);
    EXPECT_LT(d, 1.05 * to_sphere);
}

TEST(Hausdorff, ToSurfaceOfAShiftedSphere) {
    // The unit icosphere against a sphere shifted by 0.1 along x.
    const test::TestSphere shifted(1.0, {0.1, 0, 0});
    const HausdorffResult r =
        hausdorff_to_surface(test::icosphere(4), shifted, {.surface_samples = 5000, .seed = 3});
    EXPECT_GT(r.distance, 0.09);
    EXPECT_LT(r.distance, 0.11);
    EXPECT_EQ(r.b_samples, 5000u);
    // Same seed, same answer.
    const HausdorffResult again =
        hausdorff_to_surface(test::icosphere(4), shifted, {.surface_samples = 5000, .seed = 3});
    EXPECT_EQ(again.b_to_a, r.b_to_a);
}

TEST(Hausdorff, RejectsMeshesWithoutFaces) {
    const SurfaceMesh empty;
    const test::TestSphere sphere;
    EXPECT_THROW((void)hausdorff(empty, test::octahedron()), InvalidInput);
    EXPECT_THROW((void)hausdorff(test::octahedron(), empty), InvalidInput);
    EXPECT_THROW((void)hausdorff_to_surface(empty, sphere), InvalidInput);
    EXPECT_THROW((void)hausdorff(test::octahedron(), test::octahedron(), {.face_resolution = 0}),
                 InvalidInput);
}

}  // namespace
}  // namespace dynmesh

namespace dynmesh {
namespace {

TEST(Hausdorff, NearTheDoubleLimitsTheDistanceScalesExactly) {
    // An octahedron against the same octahedron shrunk by half: at unit size, at 1e300 (where
    // squared distances overflow) and at 1e-300 (where they underflow).
    const auto pair_at = [](double s) {
        SurfaceMesh a = test::octahedron(), b = test::octahedron();
        for (Point3& p : a.positions()) p = p * s;
        for (Point3& p : b.positions()) p = p * (0.5 * s);
        return hausdorff(a, b);
    };
    const HausdorffResult unit = pair_at(1.0);
    ASSERT_GT(unit.distance, 0.1);
    for (const double s : {1e300, 1e-300}) {
        const HausdorffResult r = pair_at(s);
        EXPECT_TRUE(std::isfinite(r.distance)) << s;
        EXPECT_NEAR(r.distance / s, unit.distance, 1e-12 * unit.distance) << s;
        EXPECT_NEAR(r.a_to_b / s, unit.a_to_b, 1e-12 * unit.distance) << s;
    }
}

TEST(Hausdorff, AnAnalyticSurfaceRefusesCoordinatesBeyondItsRange) {
    SurfaceMesh a = test::octahedron();
    for (Point3& p : a.positions()) p = p * 1e300;
    const auto sphere = make_surface("sphere:1");
    EXPECT_THROW((void)hausdorff_to_surface(a, *sphere), InvalidInput);
    EXPECT_THROW((void)mesh_quality(a, {.surface = sphere.get()}), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
