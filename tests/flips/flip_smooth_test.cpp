#include "dynmesh/flips/flip_smooth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "dynmesh/error.hpp"
#include "dynmesh/flips/diagnostics.hpp"
#include "dynmesh/flips/planar.hpp"
#include "dynmesh/flips/worsen.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/mesh/mesh_order.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

/// An icosphere whose vertices are moved randomly along the sphere, then flipped to the
/// Delaunay (convex hull) connectivity: a good mesh of random-ish samples.
SurfaceMesh jittered_sphere(int level, std::uint64_t seed) {
    SurfaceMesh m = test::icosphere(level);
    Rng rng(seed);
    double h = 0;
    for (Edge e : m.edges()) h += distance(m.position(m.vertex(e, 0)), m.position(m.vertex(e, 1)));
    h /= double(m.n_edges());
    for (Vertex v : m.vertices())
        m.position(v) = normalized(m.position(v) + rng.unit_vector() * (0.3 * h));
    (void)flip_all(m, {.rule = FlipRule::DiametricBall});
    return m;
}

std::set<std::pair<std::uint32_t, std::uint32_t>> edge_set(const SurfaceMesh& m) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> s;
    for (Edge e : m.edges()) {
        const auto a = m.vertex(e, 0).idx(), b = m.vertex(e, 1).idx();
        s.emplace(std::min(a, b), std::max(a, b));
    }
    return s;
}

double max_dihedral_dev_deg(const SurfaceMesh& m) {
    double worst = 0;
    for (Edge e : m.edges()) {
        const EdgeQuad k = edge_quad(m, e);
        worst = std::max(worst, 180.0 - rad_to_deg(dihedral_angle(m.position(k.p), m.position(k.q),
                                                                  m.position(k.r), m.position(k.s))));
    }
    return worst;
}

TEST(FlipAll, WorsenThenSmoothRestoresTheMesh) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        SurfaceMesh initial = jittered_sphere(4, seed);
        SurfaceMesh m = initial;
        const auto w = worsen(m, {.seed = seed});
        EXPECT_GT(w.flips, m.n_edges() / 20) << "worsening did nothing";
        EXPECT_LE(max_dihedral_dev_deg(m), 60.0 + 1e-9);
        const auto before = edge_set(m);
        EXPECT_NE(before, edge_set(initial));

        const FlipReport r = flip_all(m);
        EXPECT_TRUE(r.converged);
        EXPECT_GT(r.flips, 0u);
        // Integrity (acceptance check 5).
        const auto chk = check_mesh(m, {.require_closed = true});
        EXPECT_TRUE(chk.ok()) << chk.summary();
        EXPECT_EQ(chk.integer("euler"), 2);
        EXPECT_EQ(m.positions(), initial.positions()) << "a flip moved a vertex";
        // Idempotence (check 4).
        const FlipReport again = flip_all(m);
        EXPECT_EQ(again.flips, 0u);
        // The smoothed mesh equals the initial one up to a handful of edges (P10).
        const auto init_edges = edge_set(initial), final_edges = edge_set(m);
        std::size_t shared = 0;
        for (const auto& e : final_edges) shared += init_edges.count(e);
        EXPECT_GE(double(shared), 0.99 * double(final_edges.size())) << "seed " << seed;
        // Post-conditions (check 6).
        const auto d = flip_diagnostics(m, FlipRule::AngleDef3);
        EXPECT_EQ(d.flippable, 0u);
        EXPECT_LE(double(d.illegal), 0.001 * double(d.edges));
        EXPECT_LE(double(d.nonempty_balls), 0.01 * double(d.faces));
        // Rule cross-check (check 10).
        const auto dd = flip_diagnostics(m, FlipRule::DiametricBall);
        EXPECT_LE(double(dd.flippable), 0.01 * double(dd.edges));
    }
}

/// `m` with every position multiplied by `s`, followed by a regular tetrahedron at 1e308.
SurfaceMesh scaled_with_a_giant(const SurfaceMesh& m, double s) {
    TriangleSoup soup = m.to_soup();
    for (Point3& p : soup.points) p = p * s;
    const auto o = static_cast<std::uint32_t>(soup.points.size());
    for (const Point3& p : {Point3{1, 1, 1}, Point3{1, -1, -1}, Point3{-1, 1, -1}, Point3{-1, -1, 1}})
        soup.points.push_back(p * 1e308);
    for (const auto& t : std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}})
        soup.triangles.push_back({t[0] + o, t[1] + o, t[2] + o});
    return SurfaceMesh::from_soup(soup);
}

/// jittered_sphere with coordinates rounded to multiples of 2^-40, so that scaling by any
/// power of two down to 2^-1030 (subnormal) is exact.
SurfaceMesh quantized_sphere() {
    SurfaceMesh m = jittered_sphere(3, 5);
    for (Point3& p : m.positions()) p = {std::ldexp(std::round(std::ldexp(p.x, 40)), -40),
                                         std::ldexp(std::round(std::ldexp(p.y, 40)), -40),
                                         std::ldexp(std::round(std::ldexp(p.z, 40)), -40)};
    return m;
}

TEST(FlipAll, DecisionsDoNotDependOnTheMagnitudeOfTheCoordinates) {
    // A worsened sphere smoothed at unit size, and the same sphere scaled by 2^-40, 2^1000
    // (squares overflow) or 2^-1030 (subnormal), sharing its mesh with a tetrahedron at
    // 1e308: the same flips, triangle for triangle.
    SurfaceMesh unit = quantized_sphere();
    (void)worsen(unit, {.seed = 2});
    const std::size_t faces = unit.n_faces();
    SurfaceMesh smoothed = scaled_with_a_giant(unit, 1.0);  // the same numbering as below
    const FlipReport ref = flip_all(smoothed, {});
    ASSERT_GT(ref.flips, 50u);
    const auto triangles = [&](const SurfaceMesh& m) {
        auto t = m.to_soup().triangles;
        t.resize(faces);  // the sphere's faces come first
        return t;
    };
    for (const double s : {0x1p-40, 0x1p1000, 0x1p-1030}) {
        SCOPED_TRACE(s);
        SurfaceMesh mixed = scaled_with_a_giant(unit, s);
        const FlipReport r = flip_all(mixed, {});
        EXPECT_EQ(r.flips, ref.flips);
        EXPECT_EQ(triangles(mixed), triangles(smoothed));
        // And worsening decides the same at every magnitude too.
        SurfaceMesh w1 = scaled_with_a_giant(quantized_sphere(), 1.0);
        SurfaceMesh w2 = scaled_with_a_giant(quantized_sphere(), s);
        EXPECT_EQ(worsen(w1, {.seed = 9}).flips, worsen(w2, {.seed = 9}).flips);
        EXPECT_EQ(triangles(w2), triangles(w1));
    }
}

TEST(FlipAll, FlipCountIsLinear) {
    std::vector<double> ratio;
    for (int level : {3, 4, 5}) {
        SurfaceMesh m = jittered_sphere(level, 11);
        (void)worsen(m, {.seed = 5});
        const FlipReport r = flip_all(m);
        ASSERT_TRUE(r.converged);
        ratio.push_back(double(r.flips) / double(m.n_vertices()));
    }
    const double lo = *std::min_element(ratio.begin(), ratio.end());
    const double hi = *std::max_element(ratio.begin(), ratio.end());
    EXPECT_GT(lo, 0.0);
    EXPECT_LE(hi / lo, 1.5) << ratio[0] << " " << ratio[1] << " " << ratio[2];
}

TEST(FlipAll, DiametricRuleEmptiesBalls) {
    SurfaceMesh m = jittered_sphere(4, 3);
    (void)worsen(m, {.seed = 9});
    const FlipReport r = flip_all(m, {.rule = FlipRule::DiametricBall});
    EXPECT_TRUE(r.converged);
    const auto d = flip_diagnostics(m, FlipRule::DiametricBall, 1.0 - 1e-9);
    EXPECT_EQ(d.flippable, 0u);
    EXPECT_EQ(d.illegal, 0u);
    EXPECT_EQ(d.nonempty_balls, 0u);
}

TEST(FlipAll, RefusesGarbage) {
    SurfaceMesh m = test::icosphere(1);
    ASSERT_TRUE(m.remove_vertex(Vertex(0)));
    EXPECT_THROW((void)flip_all(m), InvalidInput);
}

TEST(Planar, FlipsToCgalDelaunay) {
    std::vector<double> ratio;
    for (std::size_t n : {32u, 100u, 320u}) {
        SurfaceMesh m = jittered_grid_triangulation(n, 0.1, n);
        double min_deg = 180;
        for (Face f : m.faces()) {
            const auto v = m.face_vertices(f);
            min_deg = std::min(min_deg, rad_to_deg(min_angle(m.position(v[0]), m.position(v[1]), m.position(v[2]))));
        }
        EXPECT_GT(min_deg, 15.0);
        EXPECT_GT(count_non_locally_delaunay(m), 0u);
        const FlipReport r = flip_all(m, {.rule = FlipRule::PlanarIncircle});
        EXPECT_TRUE(r.converged);
        EXPECT_EQ(count_non_locally_delaunay(m), 0u);
        const auto cmp = compare_with_cgal_delaunay_2(m);
        EXPECT_TRUE(cmp.identical()) << "n=" << n << " only_here=" << cmp.only_here
                                     << " only_cgal=" << cmp.only_delaunay;
        ratio.push_back(double(r.flips) / double(m.n_vertices()));
        // Definition 3 agrees in the plane: nothing left to flip.
        const FlipReport d3 = flip_all(m, {.rule = FlipRule::AngleDef3});
        EXPECT_EQ(d3.flips, 0u);
    }
    EXPECT_LE(*std::max_element(ratio.begin(), ratio.end()) /
                  *std::min_element(ratio.begin(), ratio.end()), 1.5);
}

/// Worsens the cap z > 0.9 of a sphere mesh with the paper's procedure (random flips that
/// keep every dihedral angle >= 120 degrees) restricted to edges with both ends above
/// z = 0.92; returns the cap's vertices.
std::vector<Vertex> worsen_cap(SurfaceMesh& m, std::uint64_t seed) {
    std::vector<Vertex> cap;
    for (Vertex v : m.vertices())
        if (m.position(v).z > 0.9) cap.push_back(v);
    const WorsenReport w = worsen(m, {.seed = seed, .only = [](const SurfaceMesh& mesh, Edge e) {
        return mesh.position(mesh.vertex(e, 0)).z > 0.92 && mesh.position(mesh.vertex(e, 1)).z > 0.92;
    }});
    EXPECT_GT(w.flips, 20u);
    return cap;
}

// Acceptance check 9 (digest §7): after flip_local, F (the triangles within 1 hop of V) has
// no flippable or illegal edge and no non-empty shrunken ball, and every triangle more than
// final m + 1 hops away is bit-identical to before.
TEST(FlipLocal, RepairsAWorsenedCapAndLeavesTheRestAlone) {
    for (std::uint64_t seed : {3u, 4u}) {
        SurfaceMesh m = jittered_sphere(5, 21);
        const std::vector<Vertex> cap = worsen_cap(m, seed);
        ASSERT_GT(cap.size(), 20u);
        const SurfaceMesh worsened = m;
        const CheckReport bad = check_local_flip(worsened, worsened, cap, {.final_m = 3, .converged = true});
        ASSERT_GT(bad.integer("flippable_edges"), 0) << "the cap is not worsened";
        ASSERT_GT(bad.integer("illegal_edges"), 0);

        const LocalFlipReport r = flip_local(m, cap);
        EXPECT_TRUE(r.converged);
        EXPECT_GT(r.flips.flips, 0u);
        EXPECT_GE(r.window_vertices, cap.size());
        const auto chk = check_mesh(m, {.require_closed = true});
        EXPECT_TRUE(chk.ok()) << chk.summary();
        const CheckReport c = check_local_flip(worsened, m, cap, r);
        EXPECT_TRUE(c.ok()) << ::testing::PrintToString(c.problems);
        EXPECT_GT(c.figure("near_faces"), 2 * cap.size());
        EXPECT_GT(c.figure("far_faces"), m.n_faces() / 2) << "most of the sphere is far from the cap";
        EXPECT_EQ(c.integer("unchecked_balls"), 0);
        std::printf("flip_local: %zu cap vertices, %zu rounds, final m %zu, %zu flips, window %zu vertices\n",
                    cap.size(), r.rounds, r.final_m, r.flips.flips, r.window_vertices);
    }
}

TEST(FlipLocal, CheckFindsChangesFarAwayAndMovedVertices) {
    SurfaceMesh m = jittered_sphere(4, 5);
    const std::vector<Vertex> cap = worsen_cap(m, 1);
    const SurfaceMesh worsened = m;
    const LocalFlipReport r = flip_local(m, cap);
    ASSERT_TRUE(check_local_flip(worsened, m, cap, r).ok());
    // A flip near the south pole is beyond final_m + 1 hops of the cap.
    SurfaceMesh far = m;
    Edge south;
    for (Edge e : far.edges())
        if (far.position(far.vertex(e, 0)).z < -0.95 && far.is_flip_ok(e)) south = e;
    ASSERT_TRUE(south.is_valid());
    far.flip(south);
    const CheckReport c = check_local_flip(worsened, far, cap, r);
    EXPECT_EQ(c.integer("far_faces_changed"), 2);
    EXPECT_FALSE(c.ok());
    SurfaceMesh moved = m;
    moved.position(Vertex(0)).x = std::nextafter(moved.position(Vertex(0)).x, 2.0);
    const CheckReport d = check_local_flip(worsened, moved, cap, r);
    EXPECT_EQ(d.integer("moved_vertices"), 1);
    EXPECT_FALSE(d.ok());
    EXPECT_FALSE(check_local_flip(worsened, m, cap, {.final_m = r.final_m, .converged = false}).ok());
}

// The ball test searches the whole mesh: a sheet of the surface that folds back over F is
// caught even though it is topologically far. Two parallel grids 0.1 apart, joined
// nowhere: the far one's vertices lie inside the balls of the near one's triangles.
TEST(FlipLocal, CheckCatchesAFoldFromElsewhere) {
    TriangleSoup soup;
    const SurfaceMesh a = test::grid(6);
    const TriangleSoup sa = a.to_soup();
    soup = sa;
    for (Point3 p : sa.points) soup.points.push_back({p.x + 0.5, p.y + 0.5, 0.1});
    const auto n = static_cast<std::uint32_t>(sa.points.size());
    for (auto t : sa.triangles) soup.triangles.push_back({t[0] + n, t[2] + n, t[1] + n});
    const SurfaceMesh two = SurfaceMesh::from_soup(soup);
    const std::vector<Vertex> V = {Vertex(3 * 7 + 3)};  // the middle of the first grid
    const CheckReport c = check_local_flip(two, two, V, {.final_m = 3, .converged = true});
    EXPECT_GT(c.integer("nonempty_balls"), 0);
    EXPECT_EQ(c.integer("illegal_edges"), 0) << "the near sheet itself is Delaunay";
    // Without the other sheet, the same triangles have empty balls.
    const CheckReport alone = check_local_flip(a, a, V, {.final_m = 3, .converged = true});
    EXPECT_EQ(alone.integer("nonempty_balls"), 0);
}

// The stop test (LocalFlipReport) against an all-pairs version written here: on a mesh that
// is already flipped, flip_local makes no flip, so its final m is the first m0 * 2^k at
// which no diametric ball of F meets a ring triangle.
TEST(FlipLocal, StopTestMatchesAnAllPairsSearch) {
    const Sphere sphere({0, 0, 0}, 1.0);
    SurfaceMesh m = restricted_delaunay(sphere.sample_uniform(3000, 4), sphere);
    ASSERT_TRUE(flip_all(m).converged);
    auto all_pairs_pass = [&](std::span<const Vertex> V, std::size_t mm) {
        IndexMap<std::uint32_t> hops;
        hop_distances(m, V, mm + 1, hops);
        auto hop = [&](Vertex v) { return hops.contains(v.idx()) ? std::size_t(*hops.find(v.idx())) : mm + 2; };
        std::vector<Face> F, ring;
        for (Face f : m.faces()) {
            const auto c = m.face_vertices(f);
            const std::size_t lo = std::min({hop(c[0]), hop(c[1]), hop(c[2])});
            const std::size_t hi = std::max({hop(c[0]), hop(c[1]), hop(c[2])});
            if (lo <= 1) F.push_back(f);
            if (hi > mm && lo <= mm + 1) ring.push_back(f);
        }
        for (Face f : F) {
            const auto c = m.face_vertices(f);
            const Point3 cc = circumcenter(m.position(c[0]), m.position(c[1]), m.position(c[2]));
            const double rad = distance(cc, m.position(c[0]));
            for (Face g : ring) {
                const auto d = m.face_vertices(g);
                if (closest_point_on_triangle(cc, m.position(d[0]), m.position(d[1]), m.position(d[2])).distance < rad)
                    return false;
            }
        }
        return true;
    };
    Rng rng(2);
    std::set<std::pair<std::size_t, std::size_t>> seen;  // (m0, final m)
    for (int trial = 0; trial < 60; ++trial) {
        std::vector<Vertex> V;
        for (int k = 0; k < 1 + trial % 5; ++k) V.push_back(Vertex(static_cast<std::uint32_t>(rng.below(m.n_vertices()))));
        const std::size_t m0 = trial % 2 ? 1 : 3;
        SurfaceMesh c = m;
        const LocalFlipReport r = flip_local(c, V, {.m0 = m0});
        ASSERT_EQ(r.flips.flips, 0u);
        std::size_t expect = m0;
        while (!all_pairs_pass(V, expect)) expect *= 2;
        EXPECT_EQ(r.final_m, expect) << "trial " << trial;
        seen.emplace(m0, r.final_m);
    }
    // Both outcomes of the test occur: windows that had to grow and first windows that pass.
    EXPECT_TRUE(seen.count({1, 4}) || seen.count({1, 8}));
    EXPECT_TRUE(seen.count({3, 3}));
    for (const auto& [m0, fm] : seen) std::printf("m0 %zu -> final m %zu\n", m0, fm);
}

// The whole sphere is worsened, but only the cap is repaired: flips stay inside the window,
// although the queue would find flippable edges everywhere beyond it.
TEST(FlipLocal, LeavesAWorsenedRestAlone) {
    SurfaceMesh m = jittered_sphere(5, 8);
    (void)worsen(m, {.seed = 8});
    std::vector<Vertex> cap;
    for (Vertex v : m.vertices())
        if (m.position(v).z > 0.95) cap.push_back(v);
    const SurfaceMesh worsened = m;
    const LocalFlipReport r = flip_local(m, cap);
    EXPECT_TRUE(r.converged);
    const CheckReport c = check_local_flip(worsened, m, cap, r);
    EXPECT_TRUE(c.ok()) << ::testing::PrintToString(c.problems);
    EXPECT_GT(c.figure("far_faces"), m.n_faces() / 2);
    EXPECT_GT(flip_diagnostics(m, FlipRule::AngleDef3).flippable, 100u) << "the rest is still worsened";
    // One round with a one-hop window: it flips only edges with both ends within 1 hop of V
    // in the input, so every triangle it changes has its three corners within 2 hops there,
    // although the queue would find flippable edges farther out.
    std::size_t changed = 0;
    for (std::uint32_t v = 5; v < m.n_vertices(); v += 97) {
        SurfaceMesh one = worsened;
        const std::vector<Vertex> V = {Vertex(v)};
        const LocalFlipReport r1 = flip_local(one, V, {.m0 = 1, .max_rounds = 1});
        IndexMap<std::uint32_t> hops;
        hop_distances(worsened, V, 2, hops);
        for (Face f : one.faces()) {
            const auto c = one.face_vertices(f);
            if (c == worsened.face_vertices(f)) continue;
            ++changed;
            for (Vertex x : c) EXPECT_TRUE(hops.contains(x.idx())) << "vertex " << v << ": a flip outside the window";
        }
        EXPECT_EQ(check_local_flip(worsened, one, V, r1).integer("far_faces_changed"), 0);
    }
    EXPECT_GT(changed, 100u);
}

// With a first window of one hop, the edges of F reach outside it, so the stop test must
// grow the window before F can be repaired.
TEST(FlipLocal, WindowGrowsUntilFIsRepaired) {
    SurfaceMesh m = jittered_sphere(5, 21);
    const std::vector<Vertex> cap = worsen_cap(m, 3);
    const SurfaceMesh worsened = m;
    const LocalFlipReport r = flip_local(m, cap, {.m0 = 1});
    EXPECT_TRUE(r.converged);
    EXPECT_GE(r.rounds, 2u);
    const CheckReport c = check_local_flip(worsened, m, cap, r);
    EXPECT_TRUE(c.ok()) << ::testing::PrintToString(c.problems);
}

// flip_all in a spatially renumbered mesh: the same result as renumbering by hand, flipping
// in that numbering and numbering back; the caller's vertices untouched.
TEST(FlipAll, RenumberedRunKeepsTheCallersNumbering) {
    const SurfaceMesh initial = test::shuffled(jittered_sphere(4, 2), 3);
    SurfaceMesh worsened = initial;
    (void)worsen(worsened, {.seed = 2});
    SurfaceMesh a = worsened;
    const FlipReport ra = flip_all(a, {.reorder = FlipReorder::Always});
    EXPECT_TRUE(ra.renumbered);
    EXPECT_TRUE(ra.converged);
    EXPECT_EQ(a.positions(), worsened.positions());
    const auto chk = check_mesh(a, {.require_closed = true});
    EXPECT_TRUE(chk.ok()) << chk.summary();
    EXPECT_EQ(flip_diagnostics(a, FlipRule::AngleDef3).flippable, 0u);
    SurfaceMesh b = worsened;
    const MeshOrder order = spatial_mesh_order(b);
    permute(b, order);
    const FlipReport rb = flip_all(b, {.reorder = FlipReorder::Never});
    EXPECT_FALSE(rb.renumbered);
    permute(b, inverse(order));
    EXPECT_EQ(test::mesh_difference(a, b), "");
    EXPECT_EQ(ra.flips, rb.flips);
    // In the caller's numbering the run is a different (non-spatial) order of the same rule.
    SurfaceMesh c = worsened;
    const FlipReport rc = flip_all(c, {.reorder = FlipReorder::Never});
    EXPECT_TRUE(rc.converged);
    EXPECT_EQ(flip_diagnostics(c, FlipRule::AngleDef3).flippable, 0u);
}

TEST(FlipAll, AutoRenumbersLargeScatteredMeshesOnly) {
    const SurfaceMesh big = test::icosphere(6);  // 40962 vertices
    ASSERT_LT(big.n_vertices(), kReorderMinVertices);
    SurfaceMesh small_shuffled = test::shuffled(big, 1);
    EXPECT_FALSE(flip_all(small_shuffled).renumbered) << "fits in cache: not worth it";
    TriangleSoup s = big.to_soup();
    // Four shifted copies: 163848 vertices.
    const std::size_t n = s.points.size(), t = s.triangles.size();
    for (int k = 1; k < 4; ++k) {
        for (std::size_t i = 0; i < n; ++i) s.points.push_back(s.points[i] + Vec3{3.0 * k, 0, 0});
        for (std::size_t i = 0; i < t; ++i) {
            auto tr = s.triangles[i];
            for (auto& v : tr) v += static_cast<std::uint32_t>(k * n);
            s.triangles.push_back(tr);
        }
    }
    SurfaceMesh four = SurfaceMesh::from_soup(s);
    ASSERT_GE(four.n_vertices(), kReorderMinVertices);
    SurfaceMesh sorted = four;
    permute(sorted, spatial_mesh_order(sorted));
    EXPECT_FALSE(flip_all(sorted).renumbered);
    SurfaceMesh scattered = test::shuffled(four, 2);
    const SurfaceMesh before = scattered;
    const FlipReport r = flip_all(scattered);
    EXPECT_TRUE(r.renumbered);
    EXPECT_EQ(scattered.positions(), before.positions());
}

}  // namespace
}  // namespace dynmesh
