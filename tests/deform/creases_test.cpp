// Creases (spec deforming-mesh.md §10.3, test F6): detection on the input, locked edges that
// no flip touches, Remove along a crease, Add that splits a crease edge only for a crease
// sample, and a cube whose twelve edges stay mesh-edge chains through a twist.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include "dynmesh/deform/creases.hpp"
#include "dynmesh/deform/deforming_mesh.hpp"
#include "dynmesh/deform/local_ops.hpp"
#include "dynmesh/deform/warp.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/metrics/self_intersection.hpp"

namespace dynmesh {
namespace {

/// The cube [-1, 1]^3 with an n x n grid of squares on each face, each cut into two
/// triangles along an alternating diagonal; closed, outward.
SurfaceMesh grid_cube(int n) {
    TriangleSoup soup;
    std::map<std::array<int, 3>, std::uint32_t> index;
    auto vertex = [&](std::array<int, 3> k) {
        const auto [it, fresh] = index.emplace(k, static_cast<std::uint32_t>(soup.points.size()));
        if (fresh)
            soup.points.push_back(Point3{-1 + 2.0 * k[0] / n, -1 + 2.0 * k[1] / n, -1 + 2.0 * k[2] / n});
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            Vec3 out{};
            out[static_cast<std::size_t>(axis)] = side ? 1 : -1;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    std::array<std::uint32_t, 4> q{};
                    const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
                    for (int c = 0; c < 4; ++c) {
                        std::array<int, 3> k{};
                        k[static_cast<std::size_t>(axis)] = side ? n : 0;
                        k[static_cast<std::size_t>(u)] = i + di[c];
                        k[static_cast<std::size_t>(w)] = j + dj[c];
                        q[static_cast<std::size_t>(c)] = vertex(k);
                    }
                    const bool alt = (i + j) % 2 == 0;
                    const std::array<std::array<std::uint32_t, 3>, 2> tris =
                        alt ? std::array<std::array<std::uint32_t, 3>, 2>{{{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}}
                            : std::array<std::array<std::uint32_t, 3>, 2>{{{q[0], q[1], q[3]}, {q[1], q[2], q[3]}}};
                    for (auto t : tris) {
                        const Vec3 nt = triangle_normal_raw(soup.points[t[0]], soup.points[t[1]], soup.points[t[2]]);
                        if (dot(nt, out) < 0) std::swap(t[1], t[2]);
                        soup.triangles.push_back(t);
                    }
                }
        }
    return SurfaceMesh::from_soup(soup);
}

/// Which of the cube's 12 edges a point lies on (-1: none, or a corner).
int cube_edge_of(const Point3& p) {
    auto at_face = [](double x) { return std::abs(std::abs(x) - 1) < 1e-12; };
    const bool fx = at_face(p.x), fy = at_face(p.y), fz = at_face(p.z);
    if (fx + fy + fz != 2) return -1;
    const int free_axis = !fx ? 0 : !fy ? 1 : 2;
    const int a = (free_axis + 1) % 3, b = (free_axis + 2) % 3;
    const std::array<double, 3> c{p.x, p.y, p.z};
    return free_axis * 4 + (c[static_cast<std::size_t>(a)] > 0 ? 2 : 0) + (c[static_cast<std::size_t>(b)] > 0 ? 1 : 0);
}
bool is_cube_corner(const Point3& p) {
    return std::abs(std::abs(p.x) - 1) < 1e-12 && std::abs(std::abs(p.y) - 1) < 1e-12 &&
           std::abs(std::abs(p.z) - 1) < 1e-12;
}

TEST(Creases, MarksTheTwelveEdgesOfACube) {
    SurfaceMesh cube = grid_cube(6);
    const Creases c = mark_creases(cube, {.feature_angle_deg = 45});
    EXPECT_EQ(c.lines.size(), 12u);
    EXPECT_EQ(c.corners.size(), 8u);
    EXPECT_EQ(c.edges, 12u * 6u);
    const auto locked = locked_edges(cube);
    ASSERT_TRUE(locked.is_valid());
    for (Edge e : cube.edges()) {
        const Point3 &a = cube.position(cube.vertex(e, 0)), &b = cube.position(cube.vertex(e, 1));
        const int ea = is_cube_corner(a) ? -2 : cube_edge_of(a), eb = is_cube_corner(b) ? -2 : cube_edge_of(b);
        // On a cube edge: both ends on it (a corner counts for its three edges).
        const bool on_edge = (ea != -1 && eb != -1) && (ea == eb || ea == -2 || eb == -2) &&
                             cube_edge_of(0.5 * (a + b)) != -1;
        EXPECT_EQ(locked[e] != 0, on_edge) << "edge " << e.idx();
    }
    for (const auto& line : c.lines) {
        EXPECT_EQ(line.size(), 7u);
        EXPECT_TRUE(is_cube_corner(cube.position(line.front())));
        EXPECT_TRUE(is_cube_corner(cube.position(line.back())));
    }
    // Above the cube's 90 degrees nothing is sharp; chains shorter than asked are dropped.
    SurfaceMesh again = grid_cube(6);
    EXPECT_EQ(mark_creases(again, {.feature_angle_deg = 95}).edges, 0u);
    EXPECT_EQ(mark_creases(again, {.feature_angle_deg = 45, .min_chain_edges = 7}).edges, 0u);
    EXPECT_THROW((void)mark_creases(again, {.feature_angle_deg = 180}), InvalidInput);
}

TEST(Creases, SmoothSurfaceHasNone) {
    SurfaceMesh m = grid_cube(8);  // pushed onto the unit sphere
    for (Vertex v : m.vertices()) m.position(v) = Point3{} + normalized(m.position(v) - Point3{});
    const Creases c = mark_creases(m, {.feature_angle_deg = 45});
    EXPECT_EQ(c.edges, 0u);
    EXPECT_TRUE(c.lines.empty());
}

TEST(Creases, NoFlipTouchesALockedEdge) {
    // Every edge locked: a global flip of a mesh that wants flips makes none. Every other
    // edge locked: the free ones flip, the locked ones keep their ends.
    SurfaceMesh cube = grid_cube(4);
    for (Vertex v : cube.vertices()) {  // push the grid off its squares so that flips are due
        Point3& p = cube.position(v);
        p = p + Vec3{0.05 * std::sin(7 * p.y), 0.05 * std::sin(5 * p.z), 0.05 * std::sin(3 * p.x)};
    }
    SurfaceMesh free_copy = cube;
    const FlipReport free_run = flip_all(free_copy, {});
    ASSERT_GT(free_run.flips, 0u);
    SurfaceMesh half = cube;
    auto locked = lock_edges_property(cube);
    for (Edge e : cube.edges()) locked[e] = 1;
    const FlipReport r = flip_all(cube, {});
    EXPECT_EQ(r.flips, 0u);
    EXPECT_GT(r.feature_locked, 0u);

    auto some = lock_edges_property(half);
    std::vector<std::pair<Edge, std::array<Vertex, 2>>> kept;
    for (Edge e : half.edges())
        if (e.idx() % 2 == 0) {
            some[e] = 1;
            kept.push_back({e, {half.vertex(e, 0), half.vertex(e, 1)}});
        }
    std::vector<Edge> all;
    for (Edge e : half.edges()) all.push_back(e);
    const FlipReport rh = flip_from(half, all, {});
    EXPECT_GT(rh.flips, 0u);
    for (const auto& [e, ends] : kept) {
        EXPECT_EQ(half.vertex(e, 0), ends[0]);
        EXPECT_EQ(half.vertex(e, 1), ends[1]);
    }
}

TEST(Creases, RemoveCollapsesAlongTheCreaseAndKeepsCorners) {
    SurfaceMesh cube = grid_cube(6);
    (void)mark_creases(cube, {.feature_angle_deg = 45});
    const auto locked = locked_edges(cube);
    Vertex mid, corner;
    for (Vertex v : cube.vertices()) {
        const Point3& p = cube.position(v);
        if (is_cube_corner(p)) corner = v;
        if (std::abs(p.x - 1) < 1e-12 && std::abs(p.y - 1) < 1e-12 && std::abs(p.z) < 1e-12) mid = v;
    }
    ASSERT_TRUE(mid.is_valid() && corner.is_valid());
    const std::vector<Vertex> link = cube.neighbors(mid);
    std::vector<Vertex> chain;
    for (Vertex w : link)
        if (locked[SurfaceMesh::edge(cube.find_halfedge(mid, w))]) chain.push_back(w);
    ASSERT_EQ(chain.size(), 2u);
    const RemoveResult r = remove_point(cube, mid);
    ASSERT_TRUE(r.removed) << r.reason;
    const Halfedge ab = cube.find_halfedge(chain[0], chain[1]);
    ASSERT_TRUE(ab.is_valid());
    EXPECT_TRUE(locked[SurfaceMesh::edge(ab)]);
    std::size_t marked = 0;
    for (Edge e : cube.edges()) marked += locked[e] != 0;
    EXPECT_EQ(marked, 12u * 6u - 1u);
    const RemoveResult rc = remove_point(cube, corner);
    EXPECT_FALSE(rc.removed);
    EXPECT_NE(rc.reason.find("corner"), std::string::npos) << rc.reason;
}

TEST(Creases, AddSplitsALockedEdgeOnlyWhenAsked) {
    SurfaceMesh cube = grid_cube(4);
    (void)mark_creases(cube, {.feature_angle_deg = 45});
    const auto locked = locked_edges(cube);
    Edge e;
    for (Edge x : cube.edges())
        if (locked[x]) e = x;
    const Vertex a = cube.vertex(e, 0), b = cube.vertex(e, 1);
    const Point3 p = 0.5 * (cube.position(a) + cube.position(b));
    const Face f = cube.face(SurfaceMesh::halfedge(e, 0));
    const std::size_t before = cube.n_vertices();
    const AddResult refused = add_point(cube, p, f);
    EXPECT_EQ(refused.kind, AddCase::LockedEdge);
    EXPECT_EQ(cube.n_vertices(), before);
    AddOptions o;
    o.split_edge = e;
    const AddResult r = add_point(cube, p, f, o);
    ASSERT_EQ(r.kind, AddCase::Edge);
    for (Vertex end : {a, b}) {
        const Halfedge h = cube.find_halfedge(r.vertex, end);
        ASSERT_TRUE(h.is_valid());
        EXPECT_TRUE(locked[SurfaceMesh::edge(h)]);
    }
    EXPECT_EQ(locked_degree(cube, locked, r.vertex), 2u);
}

TEST(DeformCreases, ASampleInsertedOnACreaseSplitsItsEdge) {
    // A sample queued after t = 0 at the midpoint of a crease edge joins that crease: the
    // next update makes it a vertex between the edge's two ends, with both halves crease
    // edges (a sample on no crease would have to stay dormant there).
    const SurfaceMesh cube = grid_cube(6);
    std::vector<Point3> pos = cube.positions();
    DeformOptions o;
    o.lambda = 0.01;
    o.feature_angle_deg = 45;
    InitialSurface init;
    init.reference = &cube;
    DeformingMesh dm(pos, o, init);
    const SurfaceMesh& m = dm.mesh();
    const auto locked = locked_edges(m);
    Edge e;
    for (Edge x : m.edges())
        if (locked[x] && !e.is_valid()) e = x;
    ASSERT_TRUE(e.is_valid());
    const SampleId a = dm.sample_of(m.vertex(e, 0)), b = dm.sample_of(m.vertex(e, 1));
    const Point3 mid = 0.5 * (pos[a] + pos[b]);
    const SampleId id = dm.queue_insertion(mid);
    pos.push_back(mid);
    const StepReport st = dm.advance(1, pos);
    (void)st;
    (void)dm.update();
    const Vertex v = dm.vertex_of(id);
    ASSERT_TRUE(v.is_valid()) << "the inserted sample stayed dormant";
    const auto lk = locked_edges(dm.mesh());
    EXPECT_EQ(locked_degree(dm.mesh(), lk, v), 2u);
    for (SampleId end : {a, b}) {
        const Halfedge h = dm.mesh().find_halfedge(v, dm.vertex_of(end));
        ASSERT_TRUE(h.is_valid());
        EXPECT_TRUE(lk[SurfaceMesh::edge(h)]);
    }
    const CheckReport inv = dm.check_invariants();
    EXPECT_EQ(inv.integer("crease_problems"), 0) << inv.summary();
}

/// Non-crease edges whose two triangles turn by 90 degrees or more.
std::size_t folds_off_creases(const SurfaceMesh& m) {
    const auto locked = locked_edges(m);
    std::size_t n = 0;
    for (Edge e : m.edges()) {
        if (locked.is_valid() && locked[e]) continue;
        const Halfedge h = SurfaceMesh::halfedge(e, 0);
        auto normal = [&](Halfedge x) {
            const auto v = m.face_vertices(m.face(x));
            return triangle_normal_raw(m.position(v[0]), m.position(v[1]), m.position(v[2]));
        };
        if (!(dot(normal(h), normal(SurfaceMesh::twin(h))) > 0)) ++n;
    }
    return n;
}

/// Runs a sheared 12 x 12 grid cube (every vertex a sample) through `warp` for T units with creases
/// at 45 degrees and checks, at every integer time, that its twelve edges are mesh-edge
/// chains (check_invariants' crease test, and each crease edge on one cube edge at t = 0),
/// the eight corners are vertices with three crease edges, no self-intersection, no fold off
/// the creases, and a min angle >= 10 degrees off them.
struct CubeRun {
    UpdateCounters totals;
    std::size_t crease_vertices_first = 0, crease_vertices_last = 0;  ///< at t = 0 and T
};
void run_cube(const Warp& warp, int T, CubeRun& out, bool init_refine = true) {
    // Sheared (x += 0.7 z), so that four of its edges are obtuse (125 degrees), where the
    // diametric rule would flip across them, and four acute (55 degrees).
    const SurfaceMesh unit = grid_cube(12);
    SurfaceMesh cube = unit;
    for (Vertex v : cube.vertices()) cube.position(v).x += 0.7 * cube.position(v).z;
    const std::vector<Point3>& at0 = unit.positions();  // sample i on the unsheared cube
    const std::vector<Point3> p0 = cube.positions();
    DeformOptions o;
    o.lambda = 0.1;
    o.feature_angle_deg = 45;
    o.init_refine = init_refine;
    if (!init_refine) {
        o.h0 = 0.3;  // a coarse net, the other samples dormant
        // The global R: the size field (small next to the sharp edges) would make the net
        // dense along the creases at once.
        o.size_factor = 0;
    }
    InitialSurface init;
    init.reference = &cube;
    DeformingMesh dm(p0, o, init);
    EXPECT_EQ(dm.init_report().crease_edges, 12u * 12u);
    EXPECT_EQ(dm.init_report().corners, 8u);
    EXPECT_EQ(dm.init_report().tri0, "decimated");
    std::vector<Point3> pos(p0.size());
    out.crease_vertices_first = 0;
    for (int t = 0; t <= T; ++t) {
        if (t > 0) {
            for (std::size_t i = 0; i < p0.size(); ++i) pos[i] = warp.apply(t, p0[i]);
            const StepReport st = dm.advance(t, pos);
            if (st.update_due) (void)dm.update();
        }
        SCOPED_TRACE("t = " + std::to_string(t));
        const SurfaceMesh& m = dm.mesh();
        const CheckReport inv = dm.check_invariants();
        ASSERT_EQ(inv.integer("crease_problems"), 0) << inv.summary();
        EXPECT_EQ(count_self_intersections(m), 0u);
        EXPECT_EQ(folds_off_creases(m), 0u);
        const auto locked = locked_edges(m);
        ASSERT_TRUE(locked.is_valid());
        std::size_t corners = 0;
        double min_angle_off = 180;
        std::vector<char> on_crease(m.vertices_size(), 0);
        for (Edge e : m.edges()) {
            if (!locked[e]) continue;
            // Both ends are samples of one cube edge (or corners), as placed at t = 0.
            const Point3 a = at0[dm.sample_of(m.vertex(e, 0))], b = at0[dm.sample_of(m.vertex(e, 1))];
            const int ea = is_cube_corner(a) ? -2 : cube_edge_of(a), eb = is_cube_corner(b) ? -2 : cube_edge_of(b);
            ASSERT_TRUE(ea != -1 && eb != -1 && (ea == eb || ea == -2 || eb == -2) && cube_edge_of(0.5 * (a + b)) != -1)
                << "a crease edge leaves the cube's edges";
            on_crease[m.vertex(e, 0).idx()] = on_crease[m.vertex(e, 1).idx()] = 1;
        }
        for (Vertex v : m.vertices()) {
            const Point3 a = at0[dm.sample_of(v)];
            if (is_cube_corner(a)) {
                ++corners;
                EXPECT_EQ(locked_degree(m, locked, v), 3u);
            }
            if (t == 0) out.crease_vertices_first += on_crease[v.idx()];
        }
        out.crease_vertices_last = 0;
        for (Vertex v : m.vertices()) out.crease_vertices_last += on_crease[v.idx()];
        EXPECT_EQ(corners, 8u);
        for (Face f : m.faces()) {
            const auto v = m.face_vertices(f);
            if (on_crease[v[0].idx()] || on_crease[v[1].idx()] || on_crease[v[2].idx()]) continue;
            min_angle_off = std::min(min_angle_off, min_angle(m.position(v[0]), m.position(v[1]), m.position(v[2])) * 180 / std::numbers::pi);
        }
        EXPECT_GE(min_angle_off, 10.0);
        if (::testing::Test::HasFailure()) break;
    }
    out.totals = dm.totals();
}

TEST(DeformCreases, CubeEdgesStayMeshEdgeChainsThroughATwist) {
    // One swing: +45 degrees at the top at T/4, back, -45 degrees, back.
    const int T = 40;
    const auto warp = make_twist_warp(Point3{0, 0, 0}, Vec3{0, 0, 1}, 1.0, std::numbers::pi / 4, 1.0 / T);
    CubeRun c;
    run_cube(*warp, T, c);
    EXPECT_GT(c.totals.flips, 0u);
}

TEST(DeformCreases, DormantCreaseSamplesSplitTheirCreaseEdges) {
    // Without RefineVert at t = 0 the run starts from the coarse net (crease vertices removed
    // along their creases); the first updates make the dormant crease samples vertices, each
    // by splitting the crease edge it lies on.
    const int T = 40;
    const auto warp = make_twist_warp(Point3{0, 0, 0}, Vec3{0, 0, 1}, 1.0, std::numbers::pi / 4, 1.0 / T);
    CubeRun c;
    run_cube(*warp, T, c, /*init_refine=*/false);
    EXPECT_GT(c.totals.insertions, 100u);
    // The crease gets its samples back (12 edges of 11 inner samples, 8 corners).
    EXPECT_LT(c.crease_vertices_first, 80u);
    EXPECT_GE(c.crease_vertices_last, 12u * 11u + 8u - 12u);
}

}  // namespace
}  // namespace dynmesh
