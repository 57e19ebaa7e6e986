// DeformingMesh: initialisation, scheduling, updates under motion, user edits, bad input
// (spec §8 acceptance checks 1-5, 8, 9, 12).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <numeric>

#include "dynmesh/deform/deforming_mesh.hpp"
#include "dynmesh/deform/run.hpp"
#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/metrics/self_intersection.hpp"
#include "dynmesh/shapes/analytic.hpp"

namespace dynmesh {
namespace {

std::vector<Point3> sphere_samples(std::size_t n, std::uint64_t seed) {
    return Sphere(Point3{0, 0, 0}, 1.0).sample_uniform(n, seed);
}

/// Points stretched along x by s (a sphere becoming an ellipsoid).
std::vector<Point3> stretched(const std::vector<Point3>& p0, double s) {
    std::vector<Point3> out(p0.size());
    for (std::size_t i = 0; i < p0.size(); ++i) out[i] = Point3{p0[i].x * s, p0[i].y, p0[i].z};
    return out;
}

/// Points scaled by s (a sphere pulsating about the origin).
std::vector<Point3> scaled(const std::vector<Point3>& p0, double s) {
    std::vector<Point3> out(p0.size());
    for (std::size_t i = 0; i < p0.size(); ++i) out[i] = p0[i] * s;
    return out;
}

/// Rotation about z by angle a.
std::vector<Point3> rotated(const std::vector<Point3>& p0, double a) {
    std::vector<Point3> out(p0.size());
    const double c = std::cos(a), s = std::sin(a);
    for (std::size_t i = 0; i < p0.size(); ++i)
        out[i] = Point3{c * p0[i].x - s * p0[i].y, s * p0[i].x + c * p0[i].y, p0[i].z};
    return out;
}

InvariantOptions cheap_checks() {
    InvariantOptions o;
    o.self_intersections = true;
    return o;
}

TEST(DeformInit, VertexNetDormantListsAndRestrictedDelaunayBound) {
    const auto P = sphere_samples(4000, 3);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformOptions params;
    params.lambda = 1e-4;
    params.h0_probes = 50000;
    params.init_refine = false;  // the paper's initialisation alone
    DeformingMesh dm(P, params, InitialSurface{.surface = &sphere});
    const auto& ir = dm.init_report();
    const double h0 = ir.h0;
    ASSERT_GT(h0, 0);
    EXPECT_TRUE(ir.h0_estimated);
    EXPECT_EQ(ir.samples, P.size());
    EXPECT_GT(ir.vertices, 100u);
    EXPECT_LT(ir.vertices, P.size());
    const SurfaceMesh& m = dm.mesh();
    // Vert(0) pairwise >= h0, every sample within h0 of Vert(0), owner = nearest vertex.
    std::vector<SampleId> verts;
    for (Vertex v : m.vertices()) verts.push_back(dm.sample_of(v));
    for (std::size_t i = 0; i < verts.size(); ++i)
        for (std::size_t j = i + 1; j < verts.size(); ++j)
            ASSERT_GE(distance(P[verts[i]], P[verts[j]]), h0) << verts[i] << " " << verts[j];
    for (SampleId s = 0; s < P.size(); ++s) {
        if (dm.vertex_of(s).is_valid()) continue;
        const SampleId o = dm.owner_of(s);
        ASSERT_NE(o, kNoSample) << s;
        const double d = distance(P[s], P[o]);
        EXPECT_LE(d, h0 * (1 + 1e-12)) << s;
        for (SampleId w : verts) ASSERT_GE(distance(P[s], P[w]), d) << "sample " << s << " not owned by nearest";
    }
    // Tri(0) is the RDT (then globally Delaunay-flipped): R(0) <= 2 h0.
    EXPECT_LE(ir.R0, 2 * h0);
    const auto inv = dm.check_invariants(cheap_checks());
    EXPECT_TRUE(inv.ok()) << inv.summary();
    EXPECT_EQ(inv.integer("samples"), std::ssize(P));
    // First step: floor(R / (kappa lambda)).
    EXPECT_EQ(dm.next_step(), static_cast<int>(std::floor(ir.R0 / (params.kappa * params.lambda))));
    EXPECT_EQ(ir.init_insertions, 0u);

    // With the default init_refine, RefineVert has run to a fixed point: every dormant
    // sample within R/3 of its owner, and the invariants hold.
    params.init_refine = true;
    DeformingMesh refined(P, params, InitialSurface{.surface = &sphere});
    InvariantOptions strict;
    strict.dormant_factor = 1.0 / 3.0;
    const auto inv2 = refined.check_invariants(strict);
    EXPECT_TRUE(inv2.ok()) << inv2.summary();
    EXPECT_GE(refined.init_report().vertices, ir.vertices);
}

TEST(DeformUpdate, RigidRotationNeedsNoChanges) {
    const auto P0 = sphere_samples(3000, 5);
    DeformOptions params;
    params.lambda = 0.002;
    params.kappa = 8;
    params.h0 = 0.08;
    DeformingMesh dm(P0, params, {.surface = nullptr, .mesh = nullptr, .vertex_samples = {}});
    std::size_t steps = 0;
    for (int t = 1; t <= 60; ++t) {
        const auto st = dm.advance(t, rotated(P0, 0.002 * t));
        EXPECT_TRUE(st.violations.empty()) << to_string(st.violations.front().kind) << " " << st.violations.front().detail;
        if (st.update_due) {
            const auto u = dm.update();
            ++steps;
            EXPECT_EQ(u.counters.flips, 0u) << "t = " << t;
            EXPECT_EQ(u.counters.insertions, 0u);
            EXPECT_EQ(u.counters.removals, 0u);
        }
    }
    EXPECT_GT(steps, 1u);
}

struct PulseRun {
    std::size_t updates = 0, changes = 0, refusals = 0, nonempty = 0;
    std::vector<std::string> failures;
};

/// Sphere stretched along x by 1 -> 1.6 -> 1 over T units; updates per the schedule, invariants checked at
/// every update and embedding at every unit.
PulseRun run_stretch(const std::vector<Point3>& P0, int T, bool every_step, double kappa) {
    DeformOptions params;
    params.kappa = kappa;
    params.h0 = 0.09;
    const double amp = 0.6;
    // |d/dt r(t)| <= amp * pi / T for r = 1 + amp sin^2(pi t / T)... bound per unit:
    params.lambda = amp * std::numbers::pi / T * 1.001;
    params.horizon = T;
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformingMesh dm(P0, params, {.surface = &sphere});
    PulseRun out;
    for (int t = 1; t <= T; ++t) {
        const double s = 1 + amp * std::pow(std::sin(std::numbers::pi * t / T), 2);
        const auto st = dm.advance(t, stretched(P0, s));
        for (const auto& v : st.violations) out.failures.push_back("t=" + std::to_string(t) + " " + std::string(to_string(v.kind)) + " " + v.detail);
        if (st.update_due || every_step) {
            const auto u = dm.update();
            ++out.updates;
            out.changes += u.counters.changes();
            InvariantOptions io;
            io.self_intersections = (t % 10 == 0);
            io.empty_balls = false;
            const auto inv = dm.check_invariants(io);
            if (!inv.ok()) out.failures.push_back("t=" + std::to_string(t) + " invariants: " + inv.problems.front());
            // A diametric ball can stay non-empty where a flip was refused (the circumradius
            // guard, an existing diagonal; spec §9 P9) at sparse spots: rare, never many.
            io.empty_balls = true;
            io.self_intersections = false;
            const auto balls = dm.check_invariants(io);
            const auto nonempty_balls = static_cast<std::size_t>(balls.integer("nonempty_balls"));
            if (nonempty_balls > 2)
                out.failures.push_back("t=" + std::to_string(t) + " " + std::to_string(nonempty_balls) +
                                       " non-empty diametric balls");
            out.nonempty += nonempty_balls;
            out.refusals += u.counters.flip_refusals;
            if (t < T) {
                EXPECT_EQ(u.next_step - t,
                          std::min(T - t, std::max(1, static_cast<int>(std::floor(u.R_after / (kappa * params.lambda))))))
                    << "t = " << t;
            }
        } else if (t % 10 == 0) {
            if (count_self_intersections(dm.mesh()) != 0) out.failures.push_back("t=" + std::to_string(t) + " self-intersection");
        }
    }
    return out;
}

TEST(DeformUpdate, StretchedSphereKeepsInvariantsAtEveryStep) {
    const auto P0 = sphere_samples(3000, 7);
    const PulseRun r = run_stretch(P0, 200, false, 8);
    for (const auto& f : r.failures) ADD_FAILURE() << f;
    EXPECT_GT(r.updates, 3u);
    EXPECT_LE(r.nonempty, r.updates / 10);  // rare
    EXPECT_GT(r.changes, 0u);  // stretching must promote dormant samples
}

TEST(DeformUpdate, ScheduledMakesFewerChangesThanEveryStep) {
    const auto P0 = sphere_samples(3000, 7);
    const PulseRun sched = run_stretch(P0, 400, false, 8);
    const PulseRun every = run_stretch(P0, 400, true, 8);
    for (const auto& f : sched.failures) ADD_FAILURE() << "scheduled: " << f;
    for (const auto& f : every.failures) ADD_FAILURE() << "every step: " << f;
    EXPECT_LT(sched.updates, every.updates);
    EXPECT_LE(sched.changes, every.changes);
}

TEST(DeformEdits, InsertionsFarAndNearAndDeletingHalfTheVertices) {
    const auto P0 = sphere_samples(3000, 11);
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformOptions params;
    params.lambda = 1e-3;
    params.h0 = 0.09;
    DeformingMesh dm(P0, params, {.surface = &sphere});
    std::vector<Point3> pos = P0;
    // Near: next to an existing vertex; far: on the sphere, in a fresh spot (not near any
    // sample is impossible on a dense sphere, so use points between samples).
    const Vertex v0 = *dm.mesh().vertices().begin();
    const Point3 vp = dm.mesh().position(v0);
    const Point3 near = normalized(vp + Vec3{1e-3, 0, 0});
    Rng rng(5);
    std::vector<SampleId> ids;
    ids.push_back(dm.queue_insertion(near));
    pos.push_back(near);
    for (const Point3& q : Sphere(Point3{0, 0, 0}, 1.0).sample_uniform(600, 99)) {
        ids.push_back(dm.queue_insertion(q));
        pos.push_back(q);
    }
    EXPECT_EQ(dm.id_capacity(), pos.size());
    // Queued, not yet applied.
    EXPECT_EQ(dm.owner_of(ids[0]), kNoSample);
    EXPECT_FALSE(dm.vertex_of(ids[0]).is_valid());
    dm.advance(1, pos);
    auto u = dm.update();
    EXPECT_EQ(u.counters.samples_inserted, ids.size());
    EXPECT_NE(dm.owner_of(ids[0]), kNoSample) << "a sample next to a vertex becomes dormant";
    auto inv = dm.check_invariants();
    EXPECT_TRUE(inv.ok()) << inv.summary();
    EXPECT_EQ(inv.integer("samples"), std::ssize(pos));

    // Delete half of the vertices (every other one by id) and some dormant samples.
    std::vector<SampleId> verts;
    for (Vertex v : dm.mesh().vertices()) verts.push_back(dm.sample_of(v));
    std::sort(verts.begin(), verts.end());
    const std::size_t nv = verts.size();
    std::size_t deleted = 0;
    for (std::size_t i = 0; i < verts.size(); i += 2, ++deleted) dm.queue_deletion(verts[i]);
    for (SampleId s = 0; s < 200; ++s)
        if (dm.owner_of(s) != kNoSample) {
            dm.queue_deletion(s);
            ++deleted;
        }
    dm.advance(2, pos);
    u = dm.update();
    EXPECT_EQ(u.counters.samples_deleted, deleted);
    for (std::size_t i = 0; i < verts.size(); i += 2) EXPECT_FALSE(dm.is_live(verts[i]));
    inv = dm.check_invariants();
    EXPECT_TRUE(inv.ok()) << inv.summary();
    EXPECT_EQ(inv.integer("samples"), std::ssize(pos) - static_cast<long long>(deleted));
    EXPECT_EQ(dm.live_samples(), pos.size() - deleted);
    EXPECT_GT(dm.mesh().n_vertices(), nv / 4);
}

TEST(DeformEdits, QueuedEditsWaitForTheNextStep) {
    const auto P0 = sphere_samples(2000, 13);
    DeformOptions params;
    params.lambda = 1e-5;
    params.h0 = 0.1;
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformingMesh dm(P0, params, {.surface = &sphere});
    ASSERT_GT(dm.next_step(), 2);
    const SampleId id = dm.queue_insertion(Point3{0, 0, 1});
    auto pos = P0;
    pos.push_back(Point3{0, 0, 1});
    const auto st = dm.advance(1, pos);
    EXPECT_FALSE(st.update_due);
    EXPECT_EQ(dm.owner_of(id), kNoSample);
    EXPECT_FALSE(dm.vertex_of(id).is_valid());
    EXPECT_TRUE(dm.is_live(id));
    EXPECT_THROW(dm.queue_deletion(id), InvalidInput);
    EXPECT_THROW(dm.queue_deletion(999999), InvalidInput);
}

TEST(DeformBadInput, ClearErrors) {
    const auto P0 = sphere_samples(2000, 17);
    DeformOptions params;
    params.lambda = 1e-3;
    params.h0 = 0.1;
    auto expect_msg = [](auto&& f, const std::string& needle) {
        try {
            f();
            ADD_FAILURE() << "no exception, expected one mentioning '" << needle << "'";
        } catch (const InvalidInput& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    DeformOptions bad = params;
    bad.lambda = 0;
    expect_msg([&] { DeformingMesh dm(P0, bad); }, "lambda");
    bad.lambda = std::nan("");
    expect_msg([&] { DeformingMesh dm(P0, bad); }, "lambda");
    auto nanP = P0;
    nanP[42].y = std::nan("");
    expect_msg([&] { DeformingMesh dm(nanP, params); }, "sample 42");
    auto dup = P0;
    dup[7] = dup[3];
    expect_msg([&] { DeformingMesh dm(dup, params); }, "coincide");
    // Too sparse: h0 as large as the sphere.
    DeformOptions sparse = params;
    sparse.h0 = 3.0;
    expect_msg([&] { DeformingMesh dm(P0, sparse); }, "sparse");
    // Advance: missing ids, NaN, time not increasing.
    DeformingMesh dm(P0, params);
    std::vector<Point3> shortP(P0.begin(), P0.end() - 1);
    expect_msg([&] { dm.advance(1, shortP); }, "position table");
    expect_msg([&] { dm.advance(1, nanP); }, "sample 42");
    dm.advance(1, P0);
    expect_msg([&] { dm.advance(1, P0); }, "time must increase");
}

TEST(DeformMonitors, TooFastMotionIsReportedAndRecovered) {
    const auto P0 = sphere_samples(3000, 19);
    DeformOptions params;
    params.lambda = 1e-4;  // the caller claims slow motion...
    params.h0 = 0.09;
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformingMesh dm(P0, params, {.surface = &sphere});
    // ... but inflates by 20 % in one unit.
    const auto st = dm.advance(1, scaled(P0, 1.2));
    bool saw = false;
    for (const auto& v : st.violations) saw |= v.kind == Violation::DisplacementExceedsLambda;
    EXPECT_TRUE(saw);
    EXPECT_TRUE(st.update_due);
    EXPECT_TRUE(st.emergency);
    dm.update();
    const auto inv = dm.check_invariants();
    EXPECT_TRUE(inv.ok()) << inv.summary();
}

TEST(DeformMonitors, InvertedTrianglesAreDetectedAndRepairedWithoutARebuild) {
    const auto P0 = sphere_samples(3000, 29);
    DeformOptions params;
    params.lambda = 1e-3;
    params.max_substeps = 1;  // the paper's monitors alone (sub-stepping would avoid the fold)
    params.h0 = 0.09;
    Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformingMesh dm(P0, params, {.surface = &sphere});
    // Move one vertex (that of the smallest sample id) along the sphere past a neighbour
    // (to its mirror image there): the triangles it drags over turn inside out.
    SampleId id = kNoSample;
    for (Vertex v : dm.mesh().vertices()) id = std::min(id, dm.sample_of(v));
    const Vertex v = dm.vertex_of(id);
    const SampleId w = dm.sample_of(dm.mesh().to_vertex(*dm.mesh().outgoing_halfedges(v).begin()));
    auto pos = P0;
    pos[id] = normalized(2.0 * P0[w] - P0[id]);
    const auto st = dm.advance(1, pos);
    bool inverted = false;
    for (const auto& x : st.violations) inverted |= x.kind == Violation::NormalInverted;
    EXPECT_TRUE(inverted);
    EXPECT_TRUE(st.emergency);
    ASSERT_TRUE(st.update_due);
    const auto u = dm.update();
    EXPECT_TRUE(u.emergency);
    // The emergency update mends it in place (spec §10.4: never a rebuild from scratch): a
    // valid embedded closed mesh again, the dented vertex no vertex or in a dent without
    // folds.
    for (const auto& x : u.violations) EXPECT_NE(x.kind, Violation::Rebuild);
    const auto mc = check_mesh(dm.mesh(), MeshCheckOptions{.require_closed = true});
    EXPECT_TRUE(mc.ok()) << mc.summary();
    EXPECT_EQ(count_self_intersections(dm.mesh()), 0u);
    for (Edge e : dm.mesh().edges()) {
        const auto& m = dm.mesh();
        const auto n0 = m.face_vertices(m.face(SurfaceMesh::halfedge(e, 0)));
        const auto n1 = m.face_vertices(m.face(SurfaceMesh::halfedge(e, 1)));
        const Vec3 a = triangle_normal_raw(m.position(n0[0]), m.position(n0[1]), m.position(n0[2]));
        const Vec3 b = triangle_normal_raw(m.position(n1[0]), m.position(n1[1]), m.position(n1[2]));
        ASSERT_GT(dot(a, b), 0.0) << "folded edge " << e.idx();
    }
}

TEST(DeformUpdate, LeavesNoEdgeForTheGlobalFlip) {
    // An update skips the global flip when the last one settled and only Adds and Removes
    // (which flip locally) changed the mesh since; the mesh it ends with must still have no
    // edge that the diametric-ball flip would take, after motion as after refinement.
    const auto P0 = sphere_samples(2500, 17);
    DeformOptions params;
    params.lambda = 0.01;
    DeformingMesh dm(P0, params, {.surface = nullptr});
    std::size_t checked = 0, changes = 0;
    for (int t = 1; t <= 12; ++t) {
        dm.advance(t, stretched(P0, 1 + 0.05 * t));
        const DeformUpdateReport u = dm.update();
        changes += u.counters.insertions + u.counters.removals;
        SurfaceMesh copy = dm.mesh();
        FlipOptions fo;
        fo.rule = FlipRule::DiametricBallNoFold;  // the rule of the update
        EXPECT_EQ(flip_all(copy, fo).flips, 0u) << "t = " << t;
        ++checked;
    }
    EXPECT_EQ(checked, 12u);
    EXPECT_GT(changes, 0u);  // the stretch refined: Adds ran between global flips
}

TEST(DeformSizeField, TheAnalyticScenariosRunAsWithTheGlobalR) {
    // Their features are all thicker than R (0.4 lfs >= R), so the default size field changes
    // nothing: the same updates and changes as the paper's global R.
    for (const char* name : {"stretch", "dimple", "bend"}) {
        ScenarioOptions so;
        so.samples = 1500;
        so.steps = 60;
        const Scenario s = make_scenario(name, so);
        DeformRunOptions ro;
        ro.measure_every = 0;
        ro.measure.self_intersections = false;
        ASSERT_GT(ro.params.size_factor, 0.0);
        const DeformRunReport with = run_deform(s, ro);
        ro.params.size_factor = 0;
        const DeformRunReport without = run_deform(s, ro);
        EXPECT_EQ(with.updates, without.updates) << name;
        EXPECT_EQ(with.flips, without.flips) << name;
        EXPECT_EQ(with.insertions, without.insertions) << name;
        EXPECT_EQ(with.removals, without.removals) << name;
        EXPECT_EQ(with.init_vertices, without.init_vertices) << name;
        EXPECT_GT(with.flips + with.insertions + with.removals, 0u) << name;
    }
}

TEST(DeformDeterminism, SameInputSameMesh) {
    const auto P0 = sphere_samples(2000, 23);
    auto run = [&] {
        DeformOptions params;
        params.lambda = 2e-3;
        params.kappa = 8;
        params.h0 = 0.1;
        DeformingMesh dm(P0, params);
        for (int t = 1; t <= 30; ++t) {
            const auto st = dm.advance(t, scaled(P0, 1 + 0.01 * t));
            if (st.update_due) dm.update();
        }
        return dm.mesh().to_soup();
    };
    const auto a = run();
    // A different heap layout (CGAL's advancing front, used without a surface, depends on it).
    std::vector<std::unique_ptr<char[]>> junk;
    for (int i = 0; i < 2000; ++i) junk.emplace_back(new char[static_cast<std::size_t>(97 * i + 1)]);
    for (std::size_t i = 0; i < junk.size(); i += 3) junk[i].reset();
    const auto b = run();
    EXPECT_EQ(a.triangles, b.triangles);
    ASSERT_EQ(a.points.size(), b.points.size());
    for (std::size_t i = 0; i < a.points.size(); ++i) EXPECT_EQ(a.points[i], b.points[i]);
}

TEST(DeformOrder, TheCallersNumberingDoesNotChangeTheResult) {
    // The same samples numbered two ways: the meshes (as triangles of the samples), the
    // dormant owners and the change counts agree after init and after every update.
    const auto P0 = sphere_samples(1500, 61);
    std::vector<SampleId> perm(P0.size());
    std::iota(perm.begin(), perm.end(), SampleId{0});
    Rng rng(5);
    for (std::size_t i = perm.size() - 1; i > 0; --i)
        std::swap(perm[i], perm[static_cast<std::size_t>(rng.below(i + 1))]);
    auto renumbered = [&](const std::vector<Point3>& p) {  // sample i of B is sample perm[i] of A
        std::vector<Point3> q(p.size());
        for (std::size_t i = 0; i < p.size(); ++i) q[i] = p[perm[i]];
        return q;
    };
    DeformOptions params;
    params.lambda = 0.004;
    params.h0 = 0.1;
    params.kappa = 8;
    const Sphere sphere(Point3{0, 0, 0}, 1.0);
    DeformingMesh a(P0, params, {.surface = &sphere}), b(renumbered(P0), params, {.surface = &sphere});
    auto triangles = [](const DeformingMesh& dm, const std::vector<SampleId>* map) {
        std::vector<std::array<SampleId, 3>> out;
        for (Face f : dm.mesh().faces()) {
            const auto vs = dm.mesh().face_vertices(f);
            std::array<SampleId, 3> t{};
            for (int k = 0; k < 3; ++k) {
                const SampleId s = dm.sample_of(vs[static_cast<std::size_t>(k)]);
                t[static_cast<std::size_t>(k)] = map ? (*map)[s] : s;
            }
            std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
            out.push_back(t);
        }
        std::sort(out.begin(), out.end());
        return out;
    };
    auto same = [&](const char* when) {
        ASSERT_EQ(triangles(a, nullptr), triangles(b, &perm)) << when;
        for (SampleId i = 0; i < P0.size(); ++i) {
            const SampleId ob = b.owner_of(i);
            ASSERT_EQ(a.owner_of(perm[i]), ob == kNoSample ? kNoSample : perm[ob]) << when << ", sample " << i;
        }
    };
    same("init");
    for (int step = 0; step < 3; ++step) {
        const int t = a.next_step();
        ASSERT_EQ(b.next_step(), t);
        const auto P = stretched(P0, 1.0 + 0.02 * t);
        a.advance(t, P);
        b.advance(t, renumbered(P));
        const DeformUpdateReport ua = a.update(), ub = b.update();
        EXPECT_EQ(ua.counters.changes(), ub.counters.changes());
        same("after an update");
    }
}

TEST(PointGrid, NearestAgreesWithBruteForce) {
    Rng rng(31);
    std::vector<Point3> pts(3000);
    for (auto& p : pts) p = Point3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    PointGrid g(0.05);
    for (std::uint32_t i = 0; i < pts.size(); ++i) g.insert(i, pts[i]);
    // erase a few to test erase
    for (std::uint32_t i = 0; i < pts.size(); i += 7) ASSERT_TRUE(g.erase(i, pts[i]));
    auto keep = [](std::uint32_t i) { return i % 7 != 0; };
    for (int q = 0; q < 100000; ++q) {
        const double r = q % 10 == 0 ? 3.0 : 1.2;
        const Point3 x{rng.uniform(-r, r), rng.uniform(-r, r), rng.uniform(-r, r)};
        const auto [id, d] = g.nearest(x, [&](std::uint32_t i) { return pts[i]; }, [](std::uint32_t) { return true; });
        double bd = 1e300;
        std::uint32_t bi = 0;
        for (std::uint32_t i = 0; i < pts.size(); ++i)
            if (keep(i) && (distance(pts[i], x) < bd)) {
                bd = distance(pts[i], x);
                bi = i;
            }
        ASSERT_EQ(id, bi) << "query " << q;
        ASSERT_EQ(d, bd);
    }
}

}  // namespace
}  // namespace dynmesh
