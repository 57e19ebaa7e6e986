#include "dynmesh/skin/static_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dynmesh/error.hpp"
#include "skin_inputs.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/metrics/quality.hpp"
#include "dynmesh/skin/critical_events.hpp"
#include "dynmesh/skin/topology.hpp"

namespace dynmesh {
namespace {

using test::four_balls;
using test::ring;

/// The properties every static skin mesh must have (§6.3 M1, M4, M5 and the size bound [U]):
/// a closed oriented manifold with the alpha complex's topology, vertices on the skin,
/// triangles oriented along ∇Φ, within C·Q0 of the length scale, with angles ≥ 30° (the
/// radius-edge bound 1), and close to the skin at their centroids.
void expect_good_mesh(const std::vector<WeightedPoint>& balls, const SkinMeshResult& r, const SkinFunction& phi) {
    MeshCheckOptions mo;
    mo.require_closed = true;
    const CheckReport check = check_mesh(r.mesh, mo);
    ASSERT_TRUE(check.ok()) << check.summary();
    const SkinTopology topo = skin_topology(balls, 0);
    EXPECT_EQ(check.integer("euler"), topo.euler());
    EXPECT_EQ((long long)(check.integer("components")), topo.components());
    ASSERT_EQ(r.rho.size(), r.mesh.n_vertices());
    const SkinQuality q;
    std::size_t hint = 0;
    for (Vertex v : r.mesh.vertices()) {
        const SkinEvaluation ev = phi.evaluate(r.mesh.position(v), hint);
        hint = ev.simplex;
        EXPECT_LE(std::fabs(ev.value) / norm(ev.gradient), 1e-9) << v.idx();
        EXPECT_NEAR(ev.rho, r.rho[v.idx()], 1e-6 * ev.rho);
    }
    double min_angle = 180;
    for (Face f : r.mesh.faces()) {
        const auto fv = r.mesh.face_vertices(f);
        const Point3 a = r.mesh.position(fv[0]), b = r.mesh.position(fv[1]), c = r.mesh.position(fv[2]);
        const Point3 g = a + (1.0 / 3) * ((b - a) + (c - a));
        const SkinEvaluation ev = phi.evaluate(g, hint);
        hint = ev.simplex;
        EXPECT_GT(dot(cross(b - a, c - a), ev.gradient), 0) << "face " << f.idx() << " is turned inward";
        // The centroid lies within (C·Q1)²·ϱ of the skin (M4), measured along the gradient.
        const double lambda = std::min({phi.evaluate(a, hint).rho, phi.evaluate(b, hint).rho, phi.evaluate(c, hint).rho});
        std::size_t h2 = hint;
        const Point3 foot = project_to_skin(phi, g, 0, h2);
        EXPECT_LE(norm(foot - g) / std::max(lambda, r.report.rho_floor), (q.C * q.Q1) * (q.C * q.Q1)) << f.idx();
        // [U] at Q0: circumradius over the smallest length scale.
        const double la = norm(b - c), lb = norm(c - a), lc = norm(a - b);
        const double area2 = norm(cross(b - a, c - a));
        const double R = la * lb * lc / (2 * area2);
        EXPECT_LE(R / std::max(lambda, r.report.rho_floor), q.C * q.Q0 * (1 + 1e-6)) << f.idx();
        const double angle = std::asin(std::min(1.0, std::min({la, lb, lc}) / (2 * R))) * 180 / M_PI;
        min_angle = std::min(min_angle, angle);
    }
    EXPECT_GE(min_angle, 30 - 1e-6);
}

TEST(SkinStaticMesh, OneBall) {
    const double r = 1.7;
    const std::vector<WeightedPoint> B{{{0.3, -0.2, 0.1}, r * r / 0.5}};
    const SkinFunction phi(B, 0.5);
    const SkinMeshResult m = mesh_skin(phi);
    expect_good_mesh(B, m, phi);
    for (Vertex v : m.mesh.vertices()) EXPECT_NEAR(norm(m.mesh.position(v) - Point3{0.3, -0.2, 0.1}), r, 1e-9);
}

TEST(SkinStaticMesh, TwoBallsApartAndJoined) {
    for (double d : {1.0, 4.0}) {
        const std::vector<WeightedPoint> B{{{-d, 0, 0}, 3.0}, {{d, 0.1, 0}, 3.0}};
        const SkinFunction phi(B, 0.5);
        const SkinMeshResult m = mesh_skin(phi);
        SCOPED_TRACE(d);
        expect_good_mesh(B, m, phi);
    }
}

/// §8 correction 5: the four-ball example has genus 3 at w = 2.5, a sphere and a void at 2.9,
/// one sphere at 3.5.
TEST(SkinStaticMesh, FourBallExample) {
    const std::vector<std::pair<double, long long>> cases{{2.5, -4}, {2.9, 4}, {3.5, 2}};
    for (const auto& [w, chi] : cases) {
        SCOPED_TRACE(w);
        const auto B = four_balls(w);
        const SkinFunction phi(B, 0.5);
        const SkinMeshResult m = mesh_skin(phi);
        expect_good_mesh(B, m, phi);
        const CheckReport check = check_mesh(m.mesh);
        EXPECT_EQ(check.integer("euler"), chi);
    }
}

TEST(SkinStaticMesh, RingIsATorus) {
    const auto B = ring(8, 3.0, 2.2);
    const SkinFunction phi(B, 0.5);
    const SkinMeshResult m = mesh_skin(phi);
    expect_good_mesh(B, m, phi);
    EXPECT_EQ(check_mesh(m.mesh).integer("euler"), 0);
}

/// The mesh is a function of the input: the same in every call, wherever the allocator puts
/// the triangulation (earlier results are kept alive so that each call's cells land elsewhere).
TEST(SkinStaticMesh, SameMeshInEveryCall) {
    const auto B = ring(8, 3.0, 2.2, 0.3);
    const SkinFunction phi(B, 0.5);
    std::vector<SkinMeshResult> kept;
    for (int call = 0; call < 4; ++call) {
        kept.push_back(mesh_skin(phi));
        std::vector<std::vector<char>> ballast(64 * (call + 1), std::vector<char>(4096 + 64 * call));
        if (call == 0) continue;
        const SurfaceMesh& a = kept.front().mesh;
        const SurfaceMesh& b = kept.back().mesh;
        ASSERT_EQ(a.n_vertices(), b.n_vertices()) << "call " << call;
        ASSERT_EQ(a.n_faces(), b.n_faces()) << "call " << call;
        for (Vertex v : a.vertices()) {
            ASSERT_EQ(a.position(v).x, b.position(v).x) << "call " << call << ", vertex " << v.idx();
            ASSERT_EQ(a.position(v).y, b.position(v).y) << "call " << call << ", vertex " << v.idx();
            ASSERT_EQ(a.position(v).z, b.position(v).z) << "call " << call << ", vertex " << v.idx();
        }
        for (Face f : a.faces()) {
            const auto fa = a.face_vertices(f), fb = b.face_vertices(f);
            for (int i = 0; i < 3; ++i) ASSERT_EQ(fa[i].idx(), fb[i].idx()) << "call " << call << ", face " << f.idx();
        }
    }
}

TEST(SkinStaticMesh, EmptySkinIsRefused) {
    const SkinFunction phi({{{0, 0, 0}, 1.0}}, 0.5);
    SkinMeshOptions o;
    o.time = -2;
    EXPECT_THROW((void)mesh_skin(phi, o), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
