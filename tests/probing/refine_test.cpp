#include "dynmesh/probing/refine.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>

#include <gtest/gtest.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <array>
#include <map>
#include <set>

#include "dynmesh/error.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/shapes/analytic.hpp"

namespace dynmesh {
namespace {

/// The unit sphere as a probing oracle (first crossing of a ray from outside).
class UnitSphereOracle final : public Oracle {
public:
    std::optional<ProbeHit> cast(const Point3& s, const Vec3& d, double t_max) const override {
        ++casts;
        const double b = dot(s, d), c = dot(s, s) - 1;
        const double disc = b * b - c;
        if (!(disc > 0)) return std::nullopt;
        const double t = -b - std::sqrt(disc);
        if (t < -1e-12 || t > t_max + 1e-12) return std::nullopt;
        return ProbeHit{s + std::max(t, 0.0) * d, std::max(t, 0.0), false};
    }
    double tolerance() const override { return 1e-12; }
    mutable std::size_t casts = 0;
};

/// The unit ball's ground truth, as much as the safety monitor needs.
class UnitSphereTruth final : public GroundTruth {
public:
    bool is_free(const Point3& p) const override { return norm(p) >= 1 - 1e-12; }
    bool segment_is_free(const Point3& a, const Point3& b) const override {
        const Vec3 d = b - a;
        const double len2 = dot(d, d);
        const double t = len2 > 0 ? std::clamp(-dot(a, d) / len2, 0.0, 1.0) : 0.0;
        return norm(a + t * d) >= 1 - 1e-9;
    }
    double distance(const Point3& p) const override { return std::fabs(norm(p) - 1); }
    std::vector<Point3> sample_surface(double) const override { return {}; }
    double reach() const override { return 1; }
    double diameter() const override { return 2; }
    double area() const override { return 4 * std::numbers::pi; }
    int components() const override { return 1; }
    int euler_characteristic() const override { return 2; }
};

ProbingOptions sphere_options(double eps) {
    ProbingOptions o;
    o.eps = eps;
    o.eps_S = 1;
    o.omega = {{0, 0, 0}, 1.5};
    o.interior_points = {{0, 0, 0}};
    return o;
}

/// Spec §7 test 3 with the §10.5 bound: a closed oriented sphere mesh, every ball ≤ ε, a
/// 2ε-sample, Hausdorff within 1 − sqrt(1 − ε²).
TEST(ProbeSurface, SphereIsAClosedManifoldWithSmallBalls) {
    const double eps = 0.08;
    const UnitSphereOracle oracle;
    const UnitSphereTruth truth;
    ProbingOptions o = sphere_options(eps);
    o.ground_truth = &truth;
    o.check_every = 100;
    const ProbingResult r = probe_surface(oracle, o);
    ASSERT_GT(r.mesh.triangles.size(), 100u);
    EXPECT_TRUE(r.problems.empty()) << r.problems.front();
    const SurfaceMesh m = SurfaceMesh::from_soup(r.mesh);
    const CheckReport check = check_mesh(m, {.require_closed = true, .require_connected = true});
    EXPECT_TRUE(check.ok()) << check.summary();
    EXPECT_EQ(check.integer("euler"), 2);
    EXPECT_LE(r.report.max_ball_radius, eps);
    std::printf("sphere eps %.3f: %zu vertices, %zu facets, %zu probes (%zu bootstrap), %zu cells, "
                "%zu retained, %zu detection / %zu positioning edges, path %.3f, exterior %.3f\n",
                eps, r.report.vertices, r.report.facets, r.report.probes, r.report.probes_bootstrap,
                r.report.cells_created, r.report.nodes_retained, r.report.detection_edges,
                r.report.positioning_edges, r.report.path_length, r.report.exterior_path_length);
    EXPECT_EQ(r.report.probes, oracle.casts);
    // Outward orientation: every facet's normal points away from the centre.
    for (const auto& t : r.mesh.triangles) {
        const Point3 &a = r.mesh.points[t[0]], &b = r.mesh.points[t[1]], &c = r.mesh.points[t[2]];
        ASSERT_GT(dot(cross(b - a, c - a), a + b + c), 0);
    }
    // Vertices on S; facets within 1 - sqrt(1 - eps^2) of S (their planes cut the ball).
    double dev = 0;
    for (const Point3& p : r.mesh.points) EXPECT_NEAR(norm(p), 1.0, 1e-12);
    for (const auto& t : r.mesh.triangles) {
        const Point3 g = (r.mesh.points[t[0]] + r.mesh.points[t[1]] + r.mesh.points[t[2]]) / 3.0;
        dev = std::max(dev, 1 - norm(g));
    }
    EXPECT_LE(dev, 1 - std::sqrt(1 - eps * eps) + 1e-9);
    // A 2ε-sample of the sphere.
    const Sphere sphere({0, 0, 0}, 1);
    for (const Point3& q : sphere.sample_uniform(2000, 3)) {
        double best = INFINITY;
        for (const Point3& p : r.sample) best = std::min(best, norm(p - q));
        ASSERT_LE(best, 2 * eps) << q.x << " " << q.y << " " << q.z;
    }
    // Termination argument: inserted samples are more than ε apart... up to the bootstrap
    // triangle, which is ε/8-small by construction.
    for (std::size_t i = 3; i < r.sample.size(); ++i)
        for (std::size_t j = 0; j < i; ++j) ASSERT_GT(norm(r.sample[i] - r.sample[j]), eps) << i << " " << j;
    // Costs: every probe is of a Voronoi edge end, at most two per edge created.
    EXPECT_GT(r.report.cells_created, r.mesh.triangles.size());
    EXPECT_LE(r.report.probes - r.report.probes_bootstrap, 2 * 4 * r.report.cells_created);
}

/// Spec §7 test 4: with eps < 0.05 eps_S the output is the whole restricted Delaunay
/// triangulation Del_|S(E). Computed here independently: CGAL's Delaunay triangulation of the
/// sample, every Voronoi edge (segment between circumcentres, or ray of a hull facet) tested
/// against the unit sphere exactly as a quadratic, and the facets whose edge crosses it
/// compared with the output's.
TEST(ProbeSurface, VisibleEqualsFullRestrictedDelaunayBelowTheThreshold) {
    const UnitSphereOracle oracle;
    const ProbingResult r = probe_surface(oracle, sphere_options(0.045));
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::size_t, K>;
    using Cb = CGAL::Delaunay_triangulation_cell_base_3<K>;
    using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
    using DT = CGAL::Delaunay_triangulation_3<K, Tds>;
    std::vector<std::pair<K::Point_3, std::size_t>> pts;
    for (std::size_t i = 0; i < r.sample.size(); ++i)
        pts.push_back({{r.sample[i].x, r.sample[i].y, r.sample[i].z}, i});
    const DT dt(pts.begin(), pts.end());
    // Does the segment a + t (b - a), t in [0, t_end], meet the unit sphere?
    const auto crosses = [](const K::Point_3& a, const K::Vector_3& d, double t_end) {
        const double A = d.squared_length(), B = 2 * (a - CGAL::ORIGIN) * d, C = (a - CGAL::ORIGIN).squared_length() - 1;
        const double disc = B * B - 4 * A * C;
        if (disc < 0) return false;
        const double t1 = (-B - std::sqrt(disc)) / (2 * A), t2 = (-B + std::sqrt(disc)) / (2 * A);
        return (t1 >= 0 && t1 <= t_end) || (t2 >= 0 && t2 <= t_end);
    };
    std::set<std::array<std::size_t, 3>> restricted;
    for (auto f = dt.finite_facets_begin(); f != dt.finite_facets_end(); ++f) {
        const auto c = f->first;
        const int i = f->second;
        const auto n = c->neighbor(i);
        bool hit = false;
        if (!dt.is_infinite(c) && !dt.is_infinite(n)) {
            const K::Point_3 a = dt.dual(c), b = dt.dual(n);
            hit = crosses(a, b - a, 1);
        } else {
            const auto fin = dt.is_infinite(c) ? n : c;
            const int j = dt.is_infinite(c) ? n->index(c) : i;
            const K::Point_3 a = dt.dual(fin);
            const K::Point_3& p = fin->vertex((j + 1) & 3)->point();
            const K::Point_3& q = fin->vertex((j + 2) & 3)->point();
            const K::Point_3& s = fin->vertex((j + 3) & 3)->point();
            K::Vector_3 normal = CGAL::cross_product(q - p, s - p);
            if (normal * (fin->vertex(j)->point() - p) > 0) normal = -normal;  // away from the cell
            hit = crosses(a, normal, 1e300);
        }
        if (!hit) continue;
        std::array<std::size_t, 3> t{c->vertex((i + 1) & 3)->info(), c->vertex((i + 2) & 3)->info(),
                                     c->vertex((i + 3) & 3)->info()};
        std::sort(t.begin(), t.end());
        restricted.insert(t);
    }
    std::map<std::array<double, 3>, std::size_t> index;
    for (std::size_t i = 0; i < r.sample.size(); ++i) index[{r.sample[i].x, r.sample[i].y, r.sample[i].z}] = i;
    std::set<std::array<std::size_t, 3>> visible;
    for (const auto& tri : r.mesh.triangles) {
        std::array<std::size_t, 3> t{};
        for (int k = 0; k < 3; ++k) {
            const Point3& p = r.mesh.points[tri[k]];
            t[k] = index.at({p.x, p.y, p.z});
        }
        std::sort(t.begin(), t.end());
        visible.insert(t);
    }
    EXPECT_GT(visible.size(), 1000u);
    EXPECT_EQ(visible, restricted);
}

TEST(ProbeSurface, RunsAreDeterministic) {
    const UnitSphereOracle oracle;
    const ProbingResult a = probe_surface(oracle, sphere_options(0.06));
    const ProbingResult b = probe_surface(oracle, sphere_options(0.06));
    EXPECT_EQ(a.sample, b.sample);
    EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
    EXPECT_EQ(a.report.probes, b.report.probes);
    EXPECT_EQ(a.report.cells_created, b.report.cells_created);
}

TEST(ProbeSurface, RefusesBadOptions) {
    const UnitSphereOracle oracle;
    ProbingOptions o = sphere_options(0.1);
    o.eps = 0.095;  // >= 0.091 eps_S
    EXPECT_THROW((void)probe_surface(oracle, o), InvalidInput);
    o = sphere_options(NAN);
    EXPECT_THROW((void)probe_surface(oracle, o), InvalidInput);
    o = sphere_options(0.05);
    o.interior_points.clear();
    EXPECT_THROW((void)probe_surface(oracle, o), InvalidInput);
    o = sphere_options(0.05);
    o.interior_points = {{2, 0, 0}};  // outside Omega
    EXPECT_THROW((void)probe_surface(oracle, o), InvalidInput);
    o = sphere_options(0.05);
    o.interior_points = {{0, 0, 1.2}};  // inside Omega, outside the object: the probe misses
    EXPECT_THROW((void)probe_surface(oracle, o), InvalidInput);
    o = sphere_options(0.05);
    o.omega.radius = 1.0 + 1e-9;  // S touches the boundary of Omega
    EXPECT_THROW((void)probe_surface(oracle, o), InvalidInput);
}

TEST(ProbeSurface, EpsFromDelta) {
    // The unit-sphere example of spec §2: eps_S = 1, R_Omega = 1.5, delta = 0.01 -> 0.0272.
    EXPECT_NEAR(probing_eps_from_delta(0.01, 1, 1.5), std::sqrt(0.01 / 13.5), 1e-15);
    EXPECT_THROW((void)probing_eps_from_delta(-1, 1, 1.5), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
