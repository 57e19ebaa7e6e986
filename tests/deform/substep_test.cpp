// Sub-stepping (spec deforming-mesh.md §10.1, tests F2 and F3): a time unit is cut into
// ceil(max D / B) sub-steps, the cut run equals the slow motion it stands for, a rigid motion
// needs none at any speed, and a jump that folds the mesh in one unit is followed without a
// fold.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "dynmesh/deform/deforming_mesh.hpp"
#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/metrics/self_intersection.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "flat_sheets.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

std::vector<Point3> sphere_samples(std::size_t n, std::uint64_t seed) {
    return Sphere(Point3{0, 0, 0}, 1.0).sample_uniform(n, seed);
}

/// The largest relative displacement over the budget 2 R / kappa, over the mesh edges and the
/// dormant samples with their owners, when every sample goes from `from` to `to`: the
/// sub-step count's definition for a motion without rotation (the size field is no bound on
/// the unit sphere: 0.4 lfs > R), computed here from the public accessors.
double strain_over_budget(const DeformingMesh& dm, const std::vector<Point3>& from, const std::vector<Point3>& to) {
    const double B = 2 * dm.max_circumradius() / dm.params().kappa;
    auto rel = [&](SampleId a, SampleId b) { return norm((to[b] - from[b]) - (to[a] - from[a])); };
    double worst = 0;
    const SurfaceMesh& m = dm.mesh();
    for (Edge e : m.edges()) {
        const Halfedge h = SurfaceMesh::halfedge(e, 0);
        worst = std::max(worst, rel(dm.sample_of(m.from_vertex(h)), dm.sample_of(m.to_vertex(h))) / B);
    }
    for (SampleId s = 0; s < dm.id_capacity(); ++s)
        if (dm.owner_of(s) != kNoSample) worst = std::max(worst, rel(s, dm.owner_of(s)) / B);
    return worst;
}

/// A smooth non-rigid motion of the unit sphere's samples: a twist about z by amplitude a.
std::vector<Point3> twisted(const std::vector<Point3>& p0, double a) {
    std::vector<Point3> out(p0.size());
    for (std::size_t i = 0; i < p0.size(); ++i) {
        const double th = a * p0[i].z, c = std::cos(th), s = std::sin(th);
        out[i] = Point3{c * p0[i].x - s * p0[i].y, s * p0[i].x + c * p0[i].y, p0[i].z};
    }
    return out;
}

/// The sample of the mesh vertex with the smallest sample id.
SampleId smallest_vertex_sample(const DeformingMesh& dm) {
    SampleId id = kNoSample;
    for (Vertex v : dm.mesh().vertices()) id = std::min(id, dm.sample_of(v));
    return id;
}

/// The triangles of d's mesh as sample triples (smallest first), sorted.
std::vector<std::array<SampleId, 3>> faces(const DeformingMesh& d) {
    std::vector<std::array<SampleId, 3>> out;
    for (Face f : d.mesh().faces()) {
        const auto v = d.mesh().face_vertices(f);
        std::array<SampleId, 3> s{d.sample_of(v[0]), d.sample_of(v[1]), d.sample_of(v[2])};
        std::rotate(s.begin(), std::min_element(s.begin(), s.end()), s.end());
        out.push_back(s);
    }
    std::sort(out.begin(), out.end());
    return out;
}

DeformOptions options(double h0) {
    DeformOptions o;
    o.lambda = 1e-9;  // the schedule never calls: only the budget decides
    o.h0 = h0;
    o.emergency_steps = false;
    return o;
}

TEST(Substep, CountIsTheStrainOverTheBudgetRoundedUp) {
    const auto P0 = sphere_samples(2000, 3);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    for (const double a : {0.001, 0.01, 0.05, 0.2}) {
        // A stretch along x by 1 + a: its best-fit rotation is the identity, so the strain is
        // the plain relative displacement.
        DeformingMesh dm(P0, options(0.12), {.surface = &sphere});
        std::vector<Point3> P1 = P0;
        for (Point3& p : P1) p.x *= 1 + a;
        const double ratio = strain_over_budget(dm, P0, P1);
        const StepReport st = dm.advance(1, P1);
        EXPECT_EQ(st.substeps, static_cast<std::size_t>(std::max(1.0, std::ceil(ratio)))) << "a = " << a;
        EXPECT_LE(st.max_strain_ratio, 1.0 + 1e-9) << "a = " << a;
        if (ratio > 1) {
            EXPECT_GT(st.internal_updates, 0u) << "a = " << a;
        }
    }
}

TEST(Substep, RigidMotionNeedsOneSubStepAtAnySpeed) {
    const auto P0 = sphere_samples(2000, 5);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformingMesh dm(P0, options(0.12), {.surface = &sphere});
    const std::size_t flips0 = dm.totals().flips;
    std::vector<Point3> P = P0;
    for (int t = 1; t <= 5; ++t) {
        // Translation by 100 h0 and a turn by 0.5 rad per unit.
        const double c = std::cos(0.5 * t), s = std::sin(0.5 * t);
        for (std::size_t i = 0; i < P.size(); ++i)
            P[i] = Point3{c * P0[i].x - s * P0[i].y + 12.0 * t, s * P0[i].x + c * P0[i].y, P0[i].z};
        const StepReport st = dm.advance(t, P);
        EXPECT_EQ(st.substeps, 1u) << "t = " << t;
        EXPECT_EQ(st.internal_updates, 0u);
        EXPECT_LT(st.max_strain_ratio, 1e-6);
    }
    EXPECT_EQ(dm.totals().flips, flips0);
}

TEST(Substep, EqualsTheSlowMotionItStandsFor) {
    // Run A: a fast twist, one frame per unit, cut into sub-steps inside the library.
    // Run B: the same sub-step positions handed in as frames of their own.
    const auto P0 = sphere_samples(1500, 7);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformingMesh a(P0, options(0.14), {.surface = &sphere});
    DeformingMesh b(P0, options(0.14), {.surface = &sphere});
    std::vector<Point3> from = P0;
    int tb = 0;
    std::size_t cut = 0;
    for (int t = 1; t <= 4; ++t) {
        const auto to = twisted(P0, 0.25 * t);
        const StepReport st = a.advance(t, to);
        cut += st.substeps > 1;
        for (std::size_t k = 1; k <= st.substeps; ++k) {
            std::vector<Point3> at(to.size());
            const double f = static_cast<double>(k) / static_cast<double>(st.substeps);
            for (std::size_t i = 0; i < at.size(); ++i) at[i] = k == st.substeps ? to[i] : from[i] + (to[i] - from[i]) * f;
            const StepReport sb = b.advance(++tb, at);
            EXPECT_EQ(sb.substeps, 1u) << "t = " << t << ", k = " << k;
        }
        from = to;
    }
    EXPECT_GT(cut, 0u) << "the motion is too slow to test sub-stepping";
    EXPECT_GT(a.updates(), 0u);
    EXPECT_EQ(a.updates(), b.updates());
    EXPECT_EQ(a.totals().flips, b.totals().flips);
    EXPECT_EQ(a.totals().insertions, b.totals().insertions);
    EXPECT_EQ(a.totals().removals, b.totals().removals);
    ASSERT_EQ(a.mesh().n_faces(), b.mesh().n_faces());
    EXPECT_EQ(faces(a), faces(b));
    // The invariants hold after an update (between updates only up to the L3.6 constants).
    a.update();
    const auto inv = a.check_invariants();
    EXPECT_TRUE(inv.ok()) << inv.summary();
}

/// A dimple of radius 0.3 about the pole (0, 0, 1), pushed in by `depth`.
std::vector<Point3> dimpled(const std::vector<Point3>& p0, double depth) {
    std::vector<Point3> out(p0.size());
    for (std::size_t i = 0; i < p0.size(); ++i) {
        const double d = distance(p0[i], Point3{0, 0, 1});
        const double w = d < 0.3 ? 0.5 * (1 + std::cos(kPi * d / 0.3)) : 0.0;
        out[i] = p0[i] * (1 - depth * w);
    }
    return out;
}

/// The largest circumradius of m's triangles, face by face.
double largest_circumradius_of(const SurfaceMesh& m) {
    double r = 0;
    for (Face f : m.faces()) {
        const auto v = m.face_vertices(f);
        r = std::max(r, circumradius(m.position(v[0]), m.position(v[1]), m.position(v[2])));
    }
    return r;
}

TEST(Substep, TheIncrementalSpacingScanRemovesWhatAScanOfEveryVertexRemoves) {
    // A dimple pushed in and released, again and again: the compression brings vertex pairs
    // below R/3, and the spacing repair of each update at an integer time removes one vertex
    // of each pair. Looking only around the vertices changed since the last full scan (and at
    // the pairs it left) must give the same removals, flips and mesh as looking at every vertex.
    // A budget so large that no unit is cut: the updates at integer times do all the work.
    const auto P0 = sphere_samples(3000, 5);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformOptions o = options(0.1);
    o.kappa = 2;
    DeformingMesh inc(P0, o, {.surface = &sphere});
    o.incremental_spacing = false;
    DeformingMesh full(P0, o, {.surface = &sphere});
    std::size_t removals = 0;
    for (int t = 1; t <= 24; ++t) {
        const int k = t % 12;
        const auto at = dimpled(P0, 0.03 * (k <= 6 ? k : 12 - k));
        (void)inc.advance(t, at);
        (void)full.advance(t, at);
        const DeformUpdateReport a = inc.update(), b = full.update();
        removals += a.counters.removals;
        EXPECT_EQ(a.counters.removals, b.counters.removals) << "t = " << t;
        EXPECT_EQ(a.counters.spacing_repairs, b.counters.spacing_repairs) << "t = " << t;
        ASSERT_EQ(faces(inc), faces(full)) << "t = " << t;
    }
    EXPECT_GT(removals, 0u) << "no spacing repair to compare";
    EXPECT_EQ(inc.totals().flips, full.totals().flips);
}

TEST(Substep, TheIncrementalSpacingScanFindsAStillSheetThatAMovedSheetCameClose) {
    // A flat ellipsoid's lower sheet is pushed up to 0.01 under its upper sheet, which stays
    // still (the samples mirrored in x and y: no best-fit turn), with a budget so large that
    // no unit is cut. The close pairs join a moved vertex to a vertex that never changed and
    // is no neighbour of it; which one of the pair goes depends on their order, so the scan
    // must look at both. No samples near the rims at x = +-1: the triangles there are the
    // largest, so that R (and the threshold R/3) stays put while the lower sheet moves.
    const Ellipsoid flat(Point3{0, 0, 0}, 1.0, 1.0, 0.35);
    std::vector<Point3> P0;
    for (const Point3& p : flat.sample_uniform(1500, 29))
        if (std::abs(p.x) < 0.85 || std::abs(p.y) > 0.2)
            for (const double sx : {1.0, -1.0})
                for (const double sy : {1.0, -1.0}) P0.push_back(Point3{sx * p.x, sy * p.y, p.z});
    DeformOptions o;
    o.lambda = 1e-9;
    o.h0 = 0.08;
    o.kappa = 2;
    o.emergency_steps = false;
    DeformingMesh inc(P0, o, {.surface = &flat});
    o.incremental_spacing = false;
    DeformingMesh full(P0, o, {.surface = &flat});
    std::size_t removals = 0;
    for (int t = 1; t <= 8; ++t) {
        const std::vector<Point3> P = test::pushed_under(P0, t / 8.0, 0.01);
        (void)inc.advance(t, P);
        (void)full.advance(t, P);
        const DeformUpdateReport a = inc.update(), b = full.update();
        removals += a.counters.removals;
        EXPECT_EQ(a.counters.removals, b.counters.removals) << "t = " << t;
        ASSERT_EQ(faces(inc), faces(full)) << "t = " << t;
    }
    EXPECT_GT(removals, 0u) << "no spacing repair to compare";
}

TEST(Substep, UpdatesBetweenSubStepsStayInTheMovingRegion) {
    // Spec §10.1: a fast dimple at the pole, pushed in and released, the rest of the sphere
    // still. The updates between sub-steps work on the pairs over their budget and their
    // 2-ring: a small part of the mesh. Each unit ends with no fold and no self-intersection,
    // and after its update every invariant holds; the same run with global updates between
    // sub-steps, too.
    const auto P0 = sphere_samples(4000, 13);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    for (const bool local : {true, false}) {
        DeformOptions o = options(0.1);
        o.local_updates = local;
        DeformingMesh dm(P0, o, {.surface = &sphere});
        std::size_t internal = 0, local_updates = 0, region = 0;
        for (int t = 1; t <= 4; ++t) {
            const StepReport st = dm.advance(t, dimpled(P0, t % 2 == 1 ? 0.15 : 0.0));
            EXPECT_GT(st.substeps, 1u);
            EXPECT_EQ(st.inverted_triangles, 0u) << "t = " << t;
            EXPECT_EQ(st.new_folds, 0u) << "t = " << t;
            EXPECT_FALSE(st.self_intersecting) << "t = " << t;
            EXPECT_EQ(st.self_intersecting, count_self_intersections(dm.mesh()) > 0) << "t = " << t;
            // R is kept from the faces each sub-step and update changed: it is the mesh's.
            EXPECT_NEAR(st.R, largest_circumradius_of(dm.mesh()), 1e-9 * st.R) << "t = " << t;
            internal += st.internal_updates;
            local_updates += st.local_updates;
            region += st.region_vertices;
            dm.update();
            EXPECT_NEAR(dm.max_circumradius(), largest_circumradius_of(dm.mesh()), 1e-9 * dm.max_circumradius());
            const auto inv = dm.check_invariants();
            EXPECT_TRUE(inv.ok()) << "local " << local << ", t = " << t << ": " << inv.summary();
            EXPECT_EQ(count_self_intersections(dm.mesh()), 0u);
        }
        ASSERT_GT(internal, 0u);
        if (local) {
            EXPECT_EQ(local_updates, internal);
            // The cap holds some 2 % of the sphere's area; its regions stay well below a tenth.
            EXPECT_LT(static_cast<double>(region) / static_cast<double>(local_updates),
                      0.1 * static_cast<double>(dm.mesh().n_vertices()));
        } else {
            EXPECT_EQ(local_updates, 0u);
            EXPECT_EQ(region, 0u);
        }
    }
}

TEST(Substep, TheLargestCircumradiusFollowsEveryMovedTriangle) {
    // R is kept from the triangles that each sub-step moves and each update changes. A bump
    // grown at the pole, a unit at a time, stretches the triangles on its flank until they
    // are the largest; at the end of every unit R is the mesh's, whether or not the unit
    // needed an update.
    const auto P0 = sphere_samples(3000, 17);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformingMesh dm(P0, options(0.12), {.surface = &sphere});
    const double R0 = dm.max_circumradius();
    double R = R0;
    for (int t = 1; t <= 12; ++t) {
        std::vector<Point3> P(P0.size());
        for (std::size_t i = 0; i < P0.size(); ++i) {
            const double d = distance(P0[i], Point3{0, 0, 1});
            const double w = d < 0.8 ? 0.5 * (1 + std::cos(kPi * d / 0.8)) : 0.0;
            P[i] = P0[i] * (1 + 0.05 * t * w);
        }
        const StepReport st = dm.advance(t, P);
        R = largest_circumradius_of(dm.mesh());
        EXPECT_NEAR(st.R, R, 1e-9 * R) << "t = " << t;
    }
    EXPECT_GT(R, 1.1 * R0);  // the flank's triangles grew past the others
}

TEST(Substep, ALocalMotionIsSubSteppedAsTheSameMotionCarriedByATranslation) {
    // A sub-step moves only the samples its unit moves and measures only the pairs with an
    // end among them (spec §10.1: a frame costs O(n |U| + |Vert|)). A fast dimple leaves most
    // of the sphere in place; the same dimple on a sphere that also slides by (8, 0, 0) per
    // unit moves every sample, with the same relative motion. Both runs must take the same
    // sub-steps and updates and end with the same triangles.
    // Also a cap lifted by 0.02 with a sharp rim, where the dormant samples just outside it
    // stay while their owners inside move.
    const auto P0 = sphere_samples(4000, 13);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    const auto lifted = [&](double h) {
        std::vector<Point3> out = P0;
        for (Point3& p : out)
            if (distance(p, Point3{0, 0, 1}) < 0.3) p = p * (1 + h);
        return out;
    };
    for (const bool sharp : {false, true}) {
        SCOPED_TRACE(sharp ? "lifted cap" : "dimple");
        DeformingMesh still(P0, options(0.1), {.surface = &sphere});
        DeformingMesh slid(P0, options(0.1), {.surface = &sphere});
        std::size_t internal = 0;
        for (int t = 1; t <= 4; ++t) {
            const auto to =
                sharp ? lifted(t % 2 == 1 ? 0.02 : 0.0) : dimpled(P0, t % 2 == 1 ? 0.15 : 0.0);
            std::vector<Point3> moved = to;
            for (Point3& p : moved) p.x += 8.0 * t;
            const StepReport a = still.advance(t, to), b = slid.advance(t, moved);
            EXPECT_GT(a.substeps, 1u) << "t = " << t;
            EXPECT_EQ(a.substeps, b.substeps) << "t = " << t;
            EXPECT_EQ(a.internal_updates, b.internal_updates) << "t = " << t;
            EXPECT_EQ(a.region_vertices, b.region_vertices) << "t = " << t;
            EXPECT_NEAR(a.max_strain_ratio, b.max_strain_ratio, 1e-9) << "t = " << t;
            internal += a.internal_updates;
            still.update();
            slid.update();
        }
        ASSERT_GT(internal, 0u);
        EXPECT_EQ(still.totals().flips, slid.totals().flips);
        EXPECT_EQ(still.totals().insertions, slid.totals().insertions);
        EXPECT_EQ(still.totals().removals, slid.totals().removals);
        EXPECT_EQ(faces(still), faces(slid));
    }
}

TEST(Substep, AJumpThatWouldFoldTheMeshIsFollowedWithoutAFold) {
    // One vertex moved along the sphere past a neighbour in one unit: without sub-stepping
    // its triangles turn inside out (DeformMonitors.InvertedTrianglesAreDetected...).
    const auto P0 = sphere_samples(3000, 29);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformOptions o;
    o.lambda = 1e-3;
    o.h0 = 0.09;
    DeformingMesh dm(P0, o, {.surface = &sphere});
    const SampleId id = smallest_vertex_sample(dm);
    const Vertex v = dm.vertex_of(id);
    const SampleId w = dm.sample_of(dm.mesh().to_vertex(*dm.mesh().outgoing_halfedges(v).begin()));
    auto pos = P0;
    // Along the great circle (a chord would leave the sphere at the midpoint).
    const Point3 target = normalized(2.0 * P0[w] - P0[id]);
    pos[id] = target;
    const SurfaceMesh* before = &dm.mesh();
    const StepReport st = dm.advance(1, pos);
    EXPECT_GT(st.substeps, 1u);
    EXPECT_EQ(&dm.mesh(), before) << "a retry (" << st.retries << " here) must keep references valid";
    for (const auto& x : st.violations) {
        EXPECT_NE(x.kind, Violation::NormalInverted) << x.detail;
        EXPECT_NE(x.kind, Violation::EdgeAngleBelow90) << x.detail;
    }
    if (st.update_due) dm.update();
    const auto mc = check_mesh(dm.mesh(), MeshCheckOptions{.require_closed = true});
    EXPECT_TRUE(mc.ok()) << mc.summary();
    EXPECT_EQ(count_self_intersections(dm.mesh()), 0u);
    const auto inv = dm.check_invariants();
    EXPECT_TRUE(inv.ok()) << inv.summary();
}


/// A unit sphere A (icosphere of level 3) and a sphere B of radius 0.5 (level 2) centred at
/// (bx, 0, 0): the soup, A's vertices first (B's from `offset` on).
struct TwoSpheres {
    TriangleSoup soup;
    std::uint32_t offset = 0;
};
TwoSpheres two_spheres(double bx) {
    TwoSpheres out{test::icosphere(3).to_soup()};
    const SurfaceMesh small = test::icosphere(2);
    out.offset = static_cast<std::uint32_t>(out.soup.points.size());
    const std::uint32_t o = out.offset;
    for (Vertex v : small.vertices()) out.soup.points.push_back(Point3{bx, 0, 0} + small.position(v) * 0.5);
    for (const auto& t : small.to_soup().triangles) out.soup.triangles.push_back({t[0] + o, t[1] + o, t[2] + o});
    return out;
}
/// A deforming mesh started on `m` as given, every vertex its sample, no refinement at t = 0.
DeformingMesh on_given_mesh(const SurfaceMesh& m, const std::vector<Point3>& P0) {
    InitialSurface init;
    init.mesh = &m;
    for (Vertex v : m.vertices()) init.vertex_samples.push_back(static_cast<SampleId>(v.idx()));
    DeformOptions o = options(0.1);
    o.init_refine = false;
    return DeformingMesh(P0, o, init);
}

TEST(Substep, TheStartTestsTheWholeMeshAndAnIntersectionThereIsFoundByTheFirstUnit) {
    // The whole mesh is tested once at t = 0; the tests of the units look at what changed
    // since an embedded test, so after a start that intersects itself the first unit's test
    // must still find the intersection, away from what the unit moved. A unit sphere A and a
    // small sphere B, beside it (embedded) or cutting into it (not).
    for (const double bx : {3.0, 1.0}) {
        const auto [soup, offset] = two_spheres(bx);
        const SurfaceMesh m = SurfaceMesh::from_soup(soup);
        const std::vector<Point3> P0 = soup.points;
        DeformingMesh dm = on_given_mesh(m, P0);
        const bool cut = bx < 2;
        EXPECT_EQ(dm.init_report().self_intersecting, cut) << "B at x = " << bx;
        EXPECT_EQ(count_self_intersections(dm.mesh()) > 0, cut);
        // Unit 1 dimples A's far side, at x = -1, fast enough to be cut (so tested).
        std::vector<Point3> p = P0;
        for (std::size_t i = 0; i < offset; ++i) {
            const double d = distance(P0[i], Point3{-1, 0, 0});
            p[i] = P0[i] * (1 - 0.2 * (d < 0.5 ? 0.5 * (1 + std::cos(kPi * d / 0.5)) : 0.0));
        }
        const StepReport s1 = dm.advance(1, p);
        ASSERT_GT(s1.substeps, 1u);
        EXPECT_EQ(s1.self_intersecting, cut) << "B at x = " << bx;
    }
}

TEST(Substep, AnIntersectionMadeByAnUncheckedUnitIsFoundByTheNextCheck) {
    // Spec §10.4: each test covers every face changed since the last embedded one, across the
    // updates (and their renumberings) between them. Two spheres: a small one B beside a unit
    // sphere A. Unit 1 dimples A's far side (sub-stepped, so tested: embedded). Unit 2 slides
    // B rigidly into A: one sub-step, no fold, so untested; its update deletes a sample and
    // renumbers the mesh. Unit 3 releases the dimple: its test must find B inside A although
    // B did not move in it.
    const auto [soup, offset] = two_spheres(3);
    const SurfaceMesh m = SurfaceMesh::from_soup(soup);
    const std::vector<Point3> P0 = soup.points;
    DeformingMesh dm = on_given_mesh(m, P0);
    auto at = [&](double depth, double slide) {
        std::vector<Point3> p = P0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            if (i >= offset) {
                p[i].x -= slide;
                continue;
            }
            const double d = distance(P0[i], Point3{-1, 0, 0});
            p[i] = P0[i] * (1 - depth * (d < 0.5 ? 0.5 * (1 + std::cos(kPi * d / 0.5)) : 0.0));
        }
        return p;
    };
    const StepReport s1 = dm.advance(1, at(0.2, 0));
    ASSERT_GT(s1.substeps, 1u);
    ASSERT_FALSE(s1.self_intersecting);
    dm.update();
    const StepReport s2 = dm.advance(2, at(0.2, 2.2));
    ASSERT_EQ(s2.substeps, 1u);
    ASSERT_EQ(s2.new_folds + s2.inverted_triangles, 0u);
    ASSERT_GT(count_self_intersections(dm.mesh()), 0u);  // B is in A
    SampleId top = 0;  // a sample of A far from the dimple and from B
    for (SampleId i = 0; i < offset; ++i)
        if (P0[i].z > P0[top].z) top = i;
    dm.queue_deletion(top);
    const DeformUpdateReport u = dm.update();
    ASSERT_GT(u.counters.samples_deleted, 0u);
    const StepReport s3 = dm.advance(3, at(0, 2.2));
    ASSERT_GT(s3.substeps, 1u);
    EXPECT_TRUE(s3.self_intersecting);
}

TEST(Substep, AVertexSentThroughTheOppositeWallIsDetected) {
    // F7a: one sample's input position jumps through the sphere and out of the far side in
    // one unit. No sub-stepping can keep that embedded: the unit needs more sub-steps than
    // the cap (no retry can double them), and it ends reporting the intersection.
    const auto P0 = sphere_samples(2000, 11);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformOptions o;
    o.lambda = 1e-3;
    o.h0 = 0.12;
    o.max_substeps = 64;
    DeformingMesh dm(P0, o, {.surface = &sphere});
    const SampleId id = smallest_vertex_sample(dm);
    auto pos = P0;
    pos[id] = P0[id] * -1.2;
    const StepReport st = dm.advance(1, pos);
    EXPECT_TRUE(st.self_intersecting);
    EXPECT_EQ(st.substeps, o.max_substeps);
    EXPECT_EQ(st.retries, 0u);
    EXPECT_TRUE(std::any_of(st.violations.begin(), st.violations.end(),
                            [](const ViolationRecord& v) { return v.kind == Violation::SubstepCapHit; }));
    EXPECT_GT(count_self_intersections(dm.mesh()), 0u);
}

TEST(Substep, AnInducedSelfIntersectionIsReportedInOnePieceAndAvoidedWhenSubStepped) {
    // One vertex slides along the sphere over three of its neighbours' spacing in one unit.
    // Moved in one piece (max_substeps = 1) its star folds over the triangles beyond: the
    // mesh intersects itself, and the unit's report says so (the fold monitors trip and the
    // whole-mesh test runs). Sub-stepped, the updates between the sub-steps re-triangulate
    // around it as it goes: no intersection, no fold.
    const auto P0 = sphere_samples(3000, 29);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    auto jump = [&](std::size_t max_substeps, StepReport& st) {
        DeformOptions o;
        o.lambda = 1e-3;
        o.h0 = 0.09;
        o.max_substeps = max_substeps;
        auto dm = std::make_unique<DeformingMesh>(P0, o, InitialSurface{.surface = &sphere});
        const SampleId id = smallest_vertex_sample(*dm);
        const Vertex v = dm->vertex_of(id);
        const SampleId w = dm->sample_of(dm->mesh().to_vertex(*dm->mesh().outgoing_halfedges(v).begin()));
        auto pos = P0;
        pos[id] = normalized(P0[id] + 3.0 * (P0[w] - P0[id]));  // along the sphere, past w
        st = dm->advance(1, pos);
        return dm;
    };
    StepReport one, cut;
    const auto a = jump(1, one);
    EXPECT_EQ(one.substeps, 1u);
    EXPECT_GT(count_self_intersections(a->mesh()), 0u) << "the jump does not induce an intersection";
    EXPECT_TRUE(one.self_intersecting);
    EXPECT_TRUE(std::any_of(one.violations.begin(), one.violations.end(), [](const ViolationRecord& v) {
        return v.kind == Violation::NormalInverted || v.kind == Violation::EdgeAngleBelow90;
    })) << "the intersection went unreported";
    const auto b = jump(DeformOptions{}.max_substeps, cut);
    if (cut.update_due) (void)b->update();
    EXPECT_GT(cut.substeps, 1u);
    EXPECT_GT(cut.internal_updates, 0u);
    EXPECT_EQ(count_self_intersections(b->mesh()), 0u);
    EXPECT_FALSE(cut.self_intersecting);
    const auto inv = b->check_invariants();
    EXPECT_TRUE(inv.ok()) << inv.summary();
}

}  // namespace
}  // namespace dynmesh
