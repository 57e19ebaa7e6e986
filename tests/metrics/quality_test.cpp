#include "dynmesh/metrics/quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/check.hpp"
#include "test_sphere.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

/// The same mesh with every triangle reversed (inward normals).
SurfaceMesh reversed(const SurfaceMesh& mesh) {
    TriangleSoup soup = mesh.to_soup();
    for (auto& t : soup.triangles) std::swap(t[1], t[2]);
    return SurfaceMesh::from_soup(soup);
}

std::vector<std::string> names(const std::vector<std::pair<std::string, double>>& flat) {
    std::vector<std::string> out;
    for (const auto& [name, value] : flat) out.push_back(name);
    return out;
}

double lookup(const std::vector<std::pair<std::string, double>>& flat, const std::string& name) {
    for (const auto& [n, v] : flat)
        if (n == name) return v;
    ADD_FAILURE() << "no entry " << name;
    return NAN;
}

TEST(MeshQuality, IcosphereIsNearlyEquilateral) {
    for (int level : {0, 2, 4}) {
        const SurfaceMesh mesh = test::icosphere(level);
        const QualityReport r = mesh_quality(mesh);
        EXPECT_EQ(r.vertices, mesh.n_vertices());
        EXPECT_EQ(r.faces, mesh.n_faces());
        EXPECT_EQ(r.edges, mesh.n_edges());
        EXPECT_EQ(r.euler, 2);
        EXPECT_TRUE(r.closed);
        EXPECT_EQ(r.boundary_edges, 0u);
        EXPECT_EQ(r.degenerate_faces, 0u);
        EXPECT_EQ(r.angle_deg.count, 3 * mesh.n_faces());
        EXPECT_NEAR(r.angle_deg.mean, 60.0, 1e-9);
        EXPECT_GT(r.angle_deg.min, 50.0) << "level " << level;
        EXPECT_LT(r.angle_deg.max, 75.0) << "level " << level;
        EXPECT_LT(r.angle_deg.sd, 6.0);
        EXPECT_EQ(r.radius_edge.count, mesh.n_faces());
        EXPECT_GE(r.radius_edge.min, 1.0 / std::sqrt(3.0) - 1e-12);
        EXPECT_LT(r.radius_edge.max, 0.7);
        EXPECT_EQ(r.dihedral_dev_deg.count, mesh.n_edges());
        EXPECT_FALSE(r.normal_dev_deg.has_value());
        EXPECT_FALSE(r.hausdorff_to_surface.has_value());
        EXPECT_FALSE(r.self_intersecting_pairs.has_value());
    }
    // Level 0 is the regular icosahedron: every angle 60, every dihedral 138.19 degrees.
    const QualityReport r0 = mesh_quality(test::icosphere(0));
    EXPECT_NEAR(r0.angle_deg.min, 60.0, 1e-9);
    EXPECT_NEAR(r0.angle_deg.max, 60.0, 1e-9);
    EXPECT_NEAR(r0.dihedral_dev_deg.mean, 180.0 - 138.18968510422140, 1e-9);
    EXPECT_NEAR(r0.dihedral_dev_deg.sd, 0.0, 1e-9);
}

TEST(MeshQuality, DihedralDeviationShrinksWithRefinement) {
    double previous = 180;
    for (int level = 1; level <= 4; ++level) {
        const QualityReport r = mesh_quality(test::icosphere(level));
        EXPECT_LT(r.dihedral_dev_deg.max, previous * 0.6) << "level " << level;
        EXPECT_GT(r.dihedral_dev_deg.min, 0.0);
        previous = r.dihedral_dev_deg.max;
    }
}

TEST(MeshQuality, FlatGridHasZeroDihedralDeviation) {
    const int n = 6;
    const QualityReport r = mesh_quality(test::grid(n));
    EXPECT_FALSE(r.closed);
    EXPECT_EQ(r.euler, 1);
    EXPECT_EQ(r.boundary_edges, static_cast<std::size_t>(4 * n));
    EXPECT_EQ(r.dihedral_dev_deg.count, r.edges - r.boundary_edges);
    EXPECT_NEAR(r.dihedral_dev_deg.max, 0.0, 1e-9);
    EXPECT_NEAR(r.dihedral_dev_deg.mean, 0.0, 1e-9);
    EXPECT_NEAR(r.angle_deg.min, 45.0, 1e-9);
    EXPECT_NEAR(r.angle_deg.max, 90.0, 1e-9);
    // Right isosceles triangles with unit legs: R = sqrt(2)/2, shortest edge 1.
    EXPECT_NEAR(r.circumradius.mean, std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(r.circumradius.sd, 0.0, 1e-12);
    EXPECT_NEAR(r.radius_edge.max, std::sqrt(0.5), 1e-12);
    EXPECT_EQ(r.dihedral_dev_hist.bins.size(), 18u);
    EXPECT_EQ(r.dihedral_dev_hist.bins[0], r.dihedral_dev_deg.count);
}

TEST(MeshQuality, Octahedron) {
    const QualityReport r = mesh_quality(test::octahedron());
    EXPECT_EQ(r.vertices, 6u);
    EXPECT_EQ(r.edges, 12u);
    EXPECT_EQ(r.faces, 8u);
    EXPECT_EQ(r.euler, 2);
    EXPECT_TRUE(r.closed);
    // Dihedral angle of the regular octahedron: acos(-1/3) = 109.4712 degrees.
    const double expected = 180.0 - rad_to_deg(std::acos(-1.0 / 3.0));
    EXPECT_NEAR(expected, 70.5288, 1e-4);
    EXPECT_EQ(r.dihedral_dev_deg.count, 12u);
    EXPECT_NEAR(r.dihedral_dev_deg.mean, expected, 1e-9);
    EXPECT_NEAR(r.dihedral_dev_deg.min, expected, 1e-9);
    EXPECT_NEAR(r.dihedral_dev_deg.max, expected, 1e-9);
    EXPECT_NEAR(r.dihedral_dev_deg.sd, 0.0, 1e-9);
    EXPECT_EQ(r.dihedral_dev_hist.bins[7], 12u);  // [70, 80)
    EXPECT_NEAR(r.angle_deg.min, 60.0, 1e-9);
    EXPECT_NEAR(r.radius_edge.mean, 1.0 / std::sqrt(3.0), 1e-12);
    EXPECT_NEAR(r.circumradius.mean, std::sqrt(2.0 / 3.0), 1e-12);  // edge sqrt(2)
}

TEST(MeshQuality, DihedralDeviationIgnoresOrientation) {
    const SurfaceMesh mesh = test::icosphere(2);
    const QualityReport a = mesh_quality(mesh), b = mesh_quality(reversed(mesh));
    EXPECT_NEAR(a.dihedral_dev_deg.mean, b.dihedral_dev_deg.mean, 1e-9);
    EXPECT_NEAR(a.dihedral_dev_deg.max, b.dihedral_dev_deg.max, 1e-9);
}

TEST(MeshQuality, NormalDeviationAgainstTheSphereShrinksWithLevel) {
    const test::TestSphere sphere;
    double previous_mean = 90, previous_max = 90;
    for (int level = 1; level <= 5; ++level) {
        const SurfaceMesh mesh = test::icosphere(level);
        const QualityReport r = mesh_quality(mesh, {.surface = &sphere});
        ASSERT_TRUE(r.normal_dev_deg && r.normal_dev_abs_deg && r.normal_dev_hist);
        EXPECT_EQ(r.normal_dev_deg->count, 3 * mesh.n_faces());
        EXPECT_EQ(r.normal_dev_hist->total(), 3 * mesh.n_faces());
        EXPECT_GT(r.normal_dev_deg->min, 0.0);
        // A face inscribed in the unit sphere has its plane at distance sqrt(1 - R^2) from
        // the centre, so at each of its vertices the deviation is exactly asin(R).
        SummaryAccumulator expected;
        for (const Face f : mesh.faces()) {
            const auto vs = mesh.face_vertices(f);
            const double R =
                circumradius(mesh.position(vs[0]), mesh.position(vs[1]), mesh.position(vs[2]));
            for (int i = 0; i < 3; ++i) expected.add(rad_to_deg(std::asin(R)));
        }
        EXPECT_NEAR(r.normal_dev_deg->mean, expected.summary().mean, 1e-9);
        EXPECT_NEAR(r.normal_dev_deg->sd, expected.summary().sd, 1e-9);
        EXPECT_NEAR(r.normal_dev_deg->max, expected.summary().max, 1e-9);
        EXPECT_LT(r.normal_dev_deg->max, 25.0 / std::pow(2.0, level - 1)) << "level " << level;
        EXPECT_LT(r.normal_dev_deg->mean, previous_mean * 0.6) << "level " << level;
        EXPECT_LT(r.normal_dev_deg->max, previous_max * 0.6) << "level " << level;
        // Below 90 degrees the non-obtuse variant is the same.
        EXPECT_NEAR(r.normal_dev_abs_deg->mean, r.normal_dev_deg->mean, 1e-12);
        EXPECT_NEAR(r.normal_dev_abs_deg->max, r.normal_dev_deg->max, 1e-12);
        previous_mean = r.normal_dev_deg->mean;
        previous_max = r.normal_dev_deg->max;
    }
}

TEST(MeshQuality, NormalDeviationUsesOutwardFaceNormals) {
    const test::TestSphere sphere;
    const SurfaceMesh mesh = test::icosphere(3);
    const QualityReport out = mesh_quality(mesh, {.surface = &sphere});
    const QualityReport in = mesh_quality(reversed(mesh), {.surface = &sphere});
    // Inward faces deviate by 180 - a; the non-obtuse variant does not see the difference.
    EXPECT_NEAR(in.normal_dev_deg->mean, 180.0 - out.normal_dev_deg->mean, 1e-9);
    EXPECT_NEAR(in.normal_dev_deg->min, 180.0 - out.normal_dev_deg->max, 1e-9);
    EXPECT_NEAR(in.normal_dev_abs_deg->mean, out.normal_dev_abs_deg->mean, 1e-9);
    EXPECT_NEAR(in.normal_dev_abs_deg->max, out.normal_dev_abs_deg->max, 1e-9);
    EXPECT_EQ(in.normal_dev_hist->bins.back(), 3 * mesh.n_faces());
}

/// The exact mesh-to-sphere Hausdorff distance of an icosphere: every face is acute and
/// inscribed in the unit sphere, so its farthest point from the sphere is its circumcentre,
/// at depth 1 - sqrt(1 - R^2) (the sagitta).
double max_sagitta(const SurfaceMesh& mesh) {
    double m = 0;
    for (const Face f : mesh.faces()) {
        const auto vs = mesh.face_vertices(f);
        const double R =
            circumradius(mesh.position(vs[0]), mesh.position(vs[1]), mesh.position(vs[2]));
        m = std::max(m, 1.0 - std::sqrt(1.0 - R * R));
    }
    return m;
}

TEST(MeshQuality, HausdorffToSphereIsTheSagitta) {
    const test::TestSphere sphere;
    double previous = 1;
    for (int level = 1; level <= 4; ++level) {
        const SurfaceMesh mesh = test::icosphere(level);
        const QualityReport r =
            mesh_quality(mesh, {.surface = &sphere,
                                .hausdorff = true,
                                .hausdorff_sampling = {.surface_samples = 20000}});
        ASSERT_TRUE(r.hausdorff_to_surface.has_value());
        const HausdorffResult& h = *r.hausdorff_to_surface;
        const double exact = max_sagitta(mesh);
        EXPECT_NEAR(h.distance, exact, 0.2 * exact) << "level " << level;
        // Sampling never overestimates either side.
        EXPECT_LE(h.a_to_b, exact * (1 + 1e-9));
        EXPECT_LE(h.b_to_a, exact * (1 + 1e-9));
        EXPECT_EQ(h.distance, std::max(h.a_to_b, h.b_to_a));
        EXPECT_EQ(h.b_samples, 20000u);
        EXPECT_LT(h.distance, previous / 3) << "level " << level;
        previous = h.distance;
    }
}

TEST(MeshQuality, FinerSamplingApproachesTheSagitta) {
    const test::TestSphere sphere;
    const SurfaceMesh mesh = test::icosphere(2);
    const double exact = max_sagitta(mesh);
    const HausdorffResult coarse =
        hausdorff_to_surface(mesh, sphere, {.face_resolution = 1, .surface_samples = 0});
    const HausdorffResult fine =
        hausdorff_to_surface(mesh, sphere, {.face_resolution = 12, .surface_samples = 0});
    EXPECT_EQ(fine.b_to_a, 0.0);  // direction skipped
    EXPECT_EQ(fine.b_samples, 0u);
    EXPECT_LE(coarse.a_to_b, fine.a_to_b + 1e-15);
    EXPECT_NEAR(fine.a_to_b, exact, 0.02 * exact);
}

TEST(MeshQuality, SelfIntersectionsOnRequest) {
    SurfaceMesh mesh = test::icosphere(2);
    QualityReport r = mesh_quality(mesh, {.self_intersections = true});
    ASSERT_TRUE(r.self_intersecting_pairs.has_value());
    EXPECT_EQ(*r.self_intersecting_pairs, 0u);
    const Vertex v(0);
    mesh.position(v) = mesh.position(v) * -1.3;  // through the opposite side
    r = mesh_quality(mesh, {.self_intersections = true});
    EXPECT_GT(*r.self_intersecting_pairs, 0u);
}

TEST(MeshQuality, SkipsDeletedElements) {
    SurfaceMesh mesh = test::icosphere(2);
    const std::size_t v0 = mesh.n_vertices(), f0 = mesh.n_faces();
    for (const Edge e : mesh.edges()) {
        const Halfedge h = SurfaceMesh::halfedge(e, 0);
        if (mesh.is_collapse_ok(h)) {
            mesh.collapse(h);
            break;
        }
    }
    ASSERT_TRUE(mesh.has_garbage());
    const test::TestSphere sphere;
    const QualityReport r = mesh_quality(mesh, {.surface = &sphere,
                                                .hausdorff = true,
                                                .hausdorff_sampling = {.surface_samples = 2000},
                                                .self_intersections = true});
    EXPECT_EQ(r.vertices, v0 - 1);
    EXPECT_EQ(r.faces, f0 - 2);
    EXPECT_EQ(r.euler, 2);
    EXPECT_TRUE(r.closed);
    EXPECT_EQ(r.angle_deg.count, 3 * r.faces);
    EXPECT_EQ(r.dihedral_dev_deg.count, r.edges);
    EXPECT_EQ(*r.self_intersecting_pairs, 0u);
    EXPECT_LT(r.hausdorff_to_surface->distance, 0.2);
}

TEST(MeshQuality, CountsDegenerateFaces) {
    TriangleSoup soup;
    soup.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 1, 0}};
    soup.triangles = {{0, 1, 3}, {1, 2, 3}, {0, 2, 1}};  // the last one is collinear
    const QualityReport r = mesh_quality(SurfaceMesh::from_soup(soup));
    EXPECT_EQ(r.degenerate_faces, 1u);
    EXPECT_EQ(r.circumradius.count, 2u);
    EXPECT_EQ(r.angle_deg.count, 9u);
    EXPECT_NEAR(r.angle_deg.min, 0.0, 1e-12);
    EXPECT_NEAR(r.angle_deg.max, 180.0, 1e-12);
}

TEST(MeshQuality, ADegenerateFaceHasAnInfiniteRadiusEdgeRatio) {
    // The octahedron with one corner moved onto the midpoint of two others: one zero-area
    // face, found by the same exact test as check_mesh().
    SurfaceMesh mesh = test::octahedron();
    const auto f0 = mesh.face_vertices(*mesh.faces().begin());
    mesh.position(f0[2]) = 0.5 * (mesh.position(f0[0]) + mesh.position(f0[1]));
    const QualityReport r = mesh_quality(mesh);
    EXPECT_EQ(static_cast<long long>(r.degenerate_faces), check_mesh(mesh).integer("degenerate_faces"));
    EXPECT_GE(r.degenerate_faces, 1u);
    EXPECT_EQ(r.radius_edge.max, std::numeric_limits<double>::infinity());
    EXPECT_EQ(r.circumradius.max, std::numeric_limits<double>::infinity());
    EXPECT_TRUE(std::isfinite(r.radius_edge.mean));
}

/// The octahedron with every coordinate multiplied by `s`.
SurfaceMesh scaled_octahedron(double s) {
    SurfaceMesh mesh = test::octahedron();
    for (const Vertex v : mesh.vertices()) mesh.position(v) = mesh.position(v) * s;
    return mesh;
}

TEST(MeshQuality, CoordinatesNearTheDoubleLimitsGiveTheUnitMeasures) {
    const QualityReport unit = mesh_quality(test::octahedron());
    // 1e308: squares overflow; 1e-310: subnormal, squares underflow to zero.
    for (const double s : {1e308, 1e-310, 1e-300, 1e300}) {
        SCOPED_TRACE(s);
        const SurfaceMesh mesh = scaled_octahedron(s);
        const QualityReport r = mesh_quality(mesh);
        EXPECT_EQ(r.degenerate_faces, 0u);
        EXPECT_NEAR(r.angle_deg.min, unit.angle_deg.min, 1e-9);
        EXPECT_NEAR(r.angle_deg.max, unit.angle_deg.max, 1e-9);
        EXPECT_NEAR(r.radius_edge.min, unit.radius_edge.min, 1e-12);
        EXPECT_NEAR(r.radius_edge.max, unit.radius_edge.max, 1e-12);
        EXPECT_NEAR(r.dihedral_dev_deg.max, unit.dihedral_dev_deg.max, 1e-9);
        EXPECT_NEAR(r.dihedral_dev_deg.min, unit.dihedral_dev_deg.min, 1e-9);
        EXPECT_TRUE(std::isfinite(r.circumradius.max));
        EXPECT_NEAR(r.circumradius.max / s, unit.circumradius.max, 1e-12 * unit.circumradius.max);
    }
}

TEST(MeshQuality, TrianglesFarSmallerThanTheirNeighboursAreMeasuredExactly) {
    // Two octahedra in one mesh: one at 1e308 (or unit size) and one 1e-170 or 1e-10 across;
    // each triangle is measured in its own frame, so neither looks degenerate.
    const QualityReport unit = mesh_quality(test::octahedron());
    for (const auto& [big, small] : {std::pair{1.0, 1e-170}, std::pair{1e308, 1e-10}, std::pair{1e300, 1e-300}}) {
        SCOPED_TRACE(std::to_string(big) + " and " + std::to_string(small));
        TriangleSoup soup = scaled_octahedron(big).to_soup();
        const TriangleSoup tiny = scaled_octahedron(small).to_soup();
        const auto offset = static_cast<std::uint32_t>(soup.points.size());
        soup.points.insert(soup.points.end(), tiny.points.begin(), tiny.points.end());
        for (auto t : tiny.triangles) soup.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
        const QualityReport r = mesh_quality(SurfaceMesh::from_soup(soup));
        EXPECT_EQ(r.degenerate_faces, 0u);
        EXPECT_NEAR(r.angle_deg.min, unit.angle_deg.min, 1e-9);
        EXPECT_NEAR(r.angle_deg.max, unit.angle_deg.max, 1e-9);
        EXPECT_NEAR(r.radius_edge.max, unit.radius_edge.max, 1e-12);
        EXPECT_NEAR(r.dihedral_dev_deg.max, unit.dihedral_dev_deg.max, 1e-9);
        EXPECT_NEAR(r.circumradius.max / big, unit.circumradius.max, 1e-12);
    }
}

TEST(MeshQuality, EmptyMesh) {
    const QualityReport r = mesh_quality(SurfaceMesh());
    EXPECT_EQ(r.vertices, 0u);
    EXPECT_EQ(r.faces, 0u);
    EXPECT_FALSE(r.closed);
    EXPECT_EQ(r.angle_deg.count, 0u);
    EXPECT_EQ(r.dihedral_dev_deg.count, 0u);
}

TEST(MeshQuality, RejectsBadOptions) {
    const SurfaceMesh mesh = test::octahedron();
    EXPECT_THROW((void)mesh_quality(mesh, {.hausdorff = true}), InvalidInput);
    EXPECT_THROW((void)mesh_quality(mesh, {.histogram_bins = 0}), InvalidInput);
    EXPECT_THROW((void)mesh_quality(mesh, {.histogram_max_deg = 0}), InvalidInput);
}

TEST(Flatten, NamesWithoutSurface) {
    const auto flat = flatten(mesh_quality(test::octahedron()));
    const std::vector<std::string> expected = {"vertices",
                                               "faces",
                                               "edges",
                                               "euler",
                                               "closed",
                                               "boundary_edges",
                                               "degenerate_faces",
                                               "min_angle_deg",
                                               "max_angle_deg",
                                               "mean_angle_deg",
                                               "radius_edge_max",
                                               "radius_edge_mean",
                                               "circumradius_max",
                                               "circumradius_mean",
                                               "dihedral_dev_mean_deg",
                                               "dihedral_dev_sd_deg",
                                               "dihedral_dev_max_deg"};
    EXPECT_EQ(names(flat), expected);
    EXPECT_EQ(lookup(flat, "vertices"), 6.0);
    EXPECT_EQ(lookup(flat, "euler"), 2.0);
    EXPECT_EQ(lookup(flat, "closed"), 1.0);
    EXPECT_NEAR(lookup(flat, "dihedral_dev_max_deg"), 70.5288, 1e-4);
}

TEST(Flatten, NamesWithEverything) {
    const test::TestSphere sphere;
    const QualityReport r =
        mesh_quality(test::icosphere(2), {.surface = &sphere,
                                          .hausdorff = true,
                                          .hausdorff_sampling = {.surface_samples = 2000},
                                          .self_intersections = true});
    const auto flat = flatten(r);
    const auto n = names(flat);
    for (const char* name : {"normal_dev_mean_deg", "normal_dev_sd_deg", "normal_dev_max_deg",
                             "normal_dev_abs_mean_deg", "hausdorff", "hausdorff_mesh_to_surface",
                             "hausdorff_surface_to_mesh", "self_intersections"})
        EXPECT_NE(std::find(n.begin(), n.end(), name), n.end()) << name;
    EXPECT_EQ(lookup(flat, "normal_dev_mean_deg"), r.normal_dev_deg->mean);
    EXPECT_EQ(lookup(flat, "hausdorff"), r.hausdorff_to_surface->distance);
    EXPECT_EQ(lookup(flat, "self_intersections"), 0.0);
    EXPECT_EQ(lookup(flat, "closed"), 1.0);
    // Names are unique.
    auto sorted = n;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
}

}  // namespace
}  // namespace dynmesh
