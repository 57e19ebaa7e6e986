#include "dynmesh/deform/local_ops.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <unordered_set>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/metrics/self_intersection.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

// ---- helpers -----------------------------------------------------------------------------

SurfaceMesh sphere_mesh(std::size_t n, std::uint64_t seed) {
    const Sphere sphere({0, 0, 0}, 1.0);
    return sample_and_mesh(sphere, n, seed);
}

bool bit_equal(const Point3& a, const Point3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// check_mesh clean (closed, no duplicate edges, no degenerate triangles) with this Euler
/// characteristic; returns a description of what is wrong, empty when fine.
std::string mesh_problems(const SurfaceMesh& m, long long euler) {
    const CheckReport rep = check_mesh(m, {.require_closed = true});
    std::string out;
    if (!rep.ok()) out += rep.summary("  ");
    if (rep.integer("duplicate_edges") != 0) out += " duplicate edges;";
    if (!rep.flag("closed")) out += " not closed;";
    if (rep.integer("euler") != euler) out += " euler " + std::to_string(rep.integer("euler"));
    return out;
}

/// Snapshot for "mesh unchanged": the array sizes and the live soup.
struct Snapshot {
    std::size_t nv, ne, nf;
    TriangleSoup soup;
    explicit Snapshot(const SurfaceMesh& m)
        : nv(m.vertices_size()), ne(m.edges_size()), nf(m.faces_size()), soup(m.to_soup()) {}
    bool operator==(const Snapshot& o) const {
        if (nv != o.nv || ne != o.ne || nf != o.nf) return false;
        if (soup.triangles != o.soup.triangles || soup.points.size() != o.soup.points.size())
            return false;
        for (std::size_t i = 0; i < soup.points.size(); ++i)
            if (!bit_equal(soup.points[i], o.soup.points[i])) return false;
        return true;
    }
};

/// Vertices within `rings` hops of `centre` (written here independently of the library).
std::vector<Vertex> rings_around(const SurfaceMesh& m, const std::vector<Vertex>& centre,
                                 int rings) {
    std::set<Vertex> seen(centre.begin(), centre.end());
    std::vector<Vertex> frontier(seen.begin(), seen.end());
    for (int d = 0; d < rings; ++d) {
        std::vector<Vertex> next;
        for (Vertex v : frontier)
            for (Vertex w : m.neighbors(v))
                if (seen.insert(w).second) next.push_back(w);
        frontier.swap(next);
    }
    return {seen.begin(), seen.end()};
}

/// (triangle, vertex) pairs with a vertex within 2 rings of `centre` strictly inside the
/// diametric ball of a triangle incident to `centre`.
std::size_t star_ball_violations(const SurfaceMesh& m, const std::vector<Vertex>& centre) {
    const std::vector<Vertex> ring = rings_around(m, centre, 2);
    std::set<Face> faces;
    for (Vertex v : centre)
        for (Halfedge h : m.outgoing_halfedges(v))
            if (!m.is_boundary(h)) faces.insert(m.face(h));
    std::size_t bad = 0;
    for (Face f : faces) {
        const auto t = m.face_vertices(f);
        for (Vertex w : ring) {
            if (w == t[0] || w == t[1] || w == t[2]) continue;
            if (in_diametric_ball(m.position(t[0]), m.position(t[1]), m.position(t[2]),
                                  m.position(w)) == Sign::Positive)
                ++bad;
        }
    }
    return bad;
}

Face nearest_face_brute_force(const SurfaceMesh& m, const Point3& p) {
    Face best;
    double best_d = std::numeric_limits<double>::infinity();
    for (Face f : m.faces()) {
        const auto t = m.face_vertices(f);
        const double d =
            closest_point_on_triangle(p, m.position(t[0]), m.position(t[1]), m.position(t[2]))
                .distance;
        if (d < best_d) {
            best_d = d;
            best = f;
        }
    }
    return best;
}

double nearest_vertex_distance(const SurfaceMesh& m, const Point3& p) {
    double best = std::numeric_limits<double>::infinity();
    for (Vertex v : m.vertices()) best = std::min(best, distance(p, m.position(v)));
    return best;
}

Vec3 unit_face_normal(const SurfaceMesh& m, Face f) {
    const auto t = m.face_vertices(f);
    return triangle_normal(m.position(t[0]), m.position(t[1]), m.position(t[2]));
}

/// The link of a removed vertex projected onto the plane with normal n (right-handed basis,
/// so counter-clockwise seen from +n stays counter-clockwise).
std::vector<Point2> project_link(const SurfaceMesh& m, const std::vector<Vertex>& link,
                                 const Vec3& n) {
    const Vec3 axis = std::abs(n.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
    const Vec3 u = normalized(cross(n, axis));
    const Vec3 w = cross(n, u);
    std::vector<Point2> q;
    for (Vertex x : link) q.push_back({dot(m.position(x), u), dot(m.position(x), w)});
    return q;
}

/// Problems of `tris` as the CDT of the polygon q: wrong count, a clockwise triangle, a
/// polygon side not covered exactly once, or a link vertex strictly inside the circumcircle
/// of a triangle across an interior diagonal. Empty when it is a valid CDT.
std::string cdt_problems(const std::vector<Point2>& q,
                         const std::vector<std::array<std::uint32_t, 3>>& tris) {
    const std::size_t k = q.size();
    std::string out;
    if (tris.size() != k - 2) out += " " + std::to_string(tris.size()) + " triangles;";
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> opposite;
    for (const auto& t : tris) {
        if (orient2d(q[t[0]], q[t[1]], q[t[2]]) != Sign::Positive) out += " clockwise triangle;";
        for (int j = 0; j < 3; ++j)
            if (!opposite.emplace(std::pair{t[j], t[(j + 1) % 3]}, t[(j + 2) % 3]).second)
                out += " directed edge twice;";
    }
    for (std::uint32_t i = 0; i < k; ++i)
        if (opposite.count({i, static_cast<std::uint32_t>((i + 1) % k)}) != 1)
            out += " side " + std::to_string(i) + " missing;";
    for (const auto& [e, c] : opposite) {
        const auto [a, b] = e;
        const auto it = opposite.find({b, a});
        if (it == opposite.end()) continue;  // a polygon side
        if (incircle(q[a], q[b], q[c], q[it->second]) == Sign::Positive)
            out += " diagonal (" + std::to_string(a) + "," + std::to_string(b) + ") not Delaunay;";
    }
    return out;
}

/// The triangles of a removal are faces of the mesh (before any flip).
bool triangles_are_faces(const SurfaceMesh& m, const RemoveResult& r) {
    for (const auto& t : r.triangles) {
        const Halfedge h = m.find_halfedge(r.link[t[0]], r.link[t[1]]);
        if (!h.is_valid() || m.opposite_vertex(h) != r.link[t[2]]) return false;
    }
    return true;
}

/// A vertex v at `apex` over a random star-shaped polygon of k vertices near z = 0, closed by
/// a cone to (0, 0, -1) below. v is vertex 0, the polygon vertices 1..k, the bottom k + 1.
SurfaceMesh random_star(std::size_t k, std::uint64_t seed) {
    Rng rng(seed);
    TriangleSoup s;
    s.points.push_back({rng.uniform(-0.01, 0.01), rng.uniform(-0.01, 0.01), 0.25});
    for (std::size_t i = 0; i < k; ++i) {
        const double angle = 2 * kPi * (double(i) + rng.uniform(0.3, 0.7)) / double(k);
        const double radius = rng.uniform(0.3, 1.0);
        s.points.push_back(
            {radius * std::cos(angle), radius * std::sin(angle), rng.uniform(-0.03, 0.03)});
    }
    s.points.push_back({0, 0, -1});
    const auto kk = static_cast<std::uint32_t>(k);
    for (std::uint32_t i = 0; i < kk; ++i) {
        const std::uint32_t a = 1 + i, b = 1 + (i + 1) % kk;
        s.triangles.push_back({0, a, b});
        s.triangles.push_back({kk + 1, b, a});
    }
    return SurfaceMesh::from_soup(s);
}

// ---- closest point -----------------------------------------------------------------------

TEST(LocalOpsClosestPoint, MatchesDenseSamplingAndBarycentrics) {
    Rng rng(5);
    for (int trial = 0; trial < 200; ++trial) {
        const Point3 a = rng.unit_vector(), b = rng.unit_vector(), c = rng.unit_vector();
        const Point3 p = rng.unit_vector() * rng.uniform(0.0, 2.0);
        const ClosestPoint cp = closest_point_on_triangle(p, a, b, c);
        EXPECT_NEAR(cp.u + cp.v + cp.w, 1.0, 1e-12);
        EXPECT_GE(std::min({cp.u, cp.v, cp.w}), 0.0);
        EXPECT_LT(distance(cp.point, a * cp.u + b * cp.v + c * cp.w), 1e-12);
        EXPECT_NEAR(cp.distance, distance(p, cp.point), 1e-15);
        double sampled = std::numeric_limits<double>::infinity();
        const int n = 60;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) {
                const double u = double(i) / n, v = double(j) / n;
                sampled = std::min(sampled, distance(p, a * (1 - u - v) + b * u + c * v));
            }
        EXPECT_LE(cp.distance, sampled + 1e-12) << "trial " << trial;
    }
}

// ---- Add ---------------------------------------------------------------------------------

/// The common postconditions of a successful Add (spec §8 item 10).
void expect_added(const SurfaceMesh& m, const AddResult& r, const Point3& p, AddCase kind) {
    EXPECT_EQ(r.kind, kind);
    ASSERT_TRUE(r.vertex.is_valid());
    EXPECT_FALSE(m.is_deleted(r.vertex));
    EXPECT_TRUE(bit_equal(m.position(r.vertex), p)) << "p is not kept bit for bit";
    EXPECT_EQ(mesh_problems(m, 2), "");
    EXPECT_EQ(star_ball_violations(m, {r.vertex}), 0u);
    EXPECT_TRUE(r.balls_empty);
}

TEST(LocalOpsAdd, PointAboveTriangleInterior) {
    SurfaceMesh m = sphere_mesh(2000, 1);
    ASSERT_EQ(mesh_problems(m, 2), "");
    Rng rng(11);
    for (int trial = 0; trial < 20; ++trial) {
        Face f;
        do f = Face(static_cast<std::uint32_t>(rng.below(m.faces_size())));
        while (m.is_deleted(f));
        const auto t = m.face_vertices(f);
        const Point3 centroid = (m.position(t[0]) + m.position(t[1]) + m.position(t[2])) / 3.0;
        const Point3 p = centroid + unit_face_normal(m, f) * (trial % 2 == 0 ? 0.003 : -0.003);
        const std::size_t nv = m.n_vertices(), nf = m.n_faces();
        const AddResult r = add_point(m, p, f);
        expect_added(m, r, p, AddCase::Interior);
        EXPECT_EQ(m.n_vertices(), nv + 1);
        EXPECT_EQ(m.n_faces(), nf + 2);
        EXPECT_NEAR(r.offset, 0.003, 1e-12);
        EXPECT_LT(distance(r.projected, centroid), 1e-12);
    }
}

TEST(LocalOpsAdd, PointOnEdgeSplitsTheEdge) {
    SurfaceMesh m = sphere_mesh(2000, 2);
    Rng rng(12);
    for (int trial = 0; trial < 20; ++trial) {
        Edge e;
        do e = Edge(static_cast<std::uint32_t>(rng.below(m.edges_size())));
        while (m.is_deleted(e));
        const Halfedge h = SurfaceMesh::halfedge(e, 0);
        const Face f0 = m.face(h), f1 = m.face(SurfaceMesh::twin(h));
        const Point3 mid = (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1))) * 0.5;
        // Outside the convex mesh, in the normal cone of the edge: the closest point of
        // either triangle is (about) the midpoint, on the edge.
        const Point3 p = mid + normalized(unit_face_normal(m, f0) + unit_face_normal(m, f1)) * 0.002;
        const std::size_t nv = m.n_vertices(), nf = m.n_faces();
        const AddResult r = add_point(m, p, trial % 2 == 0 ? f0 : f1);
        expect_added(m, r, p, AddCase::Edge);
        EXPECT_EQ(m.n_vertices(), nv + 1);
        EXPECT_EQ(m.n_faces(), nf + 2);
        EXPECT_LT(distance(r.projected, mid), 1e-9);
    }
}

TEST(LocalOpsAdd, PointNearVertexIsRefusedAndMeshUnchanged) {
    SurfaceMesh m = sphere_mesh(2000, 3);
    Rng rng(13);
    for (int trial = 0; trial < 10; ++trial) {
        const Vertex x(static_cast<std::uint32_t>(rng.below(m.vertices_size())));
        // Radially out of a vertex of an inscribed convex mesh: in the vertex's normal cone.
        const Point3 p = m.position(x) * 1.002;
        const Face f = m.face(m.halfedge(x));
        const Snapshot before(m);
        const AddResult r = add_point(m, p, f);
        EXPECT_EQ(r.kind, AddCase::Vertex);
        EXPECT_FALSE(r.vertex.is_valid());
        EXPECT_EQ(r.near_vertex, x);
        EXPECT_EQ(r.flips, 0u);
        EXPECT_NEAR(r.offset, 0.002, 1e-12);
        EXPECT_TRUE(Snapshot(m) == before) << "the vertex case changed the mesh";
    }
}

TEST(LocalOpsAdd, InvalidFaceThrows) {
    SurfaceMesh m = test::octahedron();
    EXPECT_THROW((void)add_point(m, {0, 0, 2}, Face(1000)), InvalidInput);
    EXPECT_THROW((void)add_point(m, {std::numeric_limits<double>::quiet_NaN(), 0, 2}, Face(0)), InvalidInput);
}

TEST(LocalOpsAdd, ManyRandomAddsStayValid) {
    for (std::uint64_t seed : {4u, 5u}) {
        SurfaceMesh m = sphere_mesh(2000, seed);
        Rng rng(seed * 101);
        std::size_t added = 0, skipped = 0, conditional = 0, edges = 0, in_nearby_ball = 0;
        while (added < 300) {
            const Point3 p = rng.unit_vector() * (1.0 + rng.uniform(-0.005, 0.005));
            // The precondition of Add: p well away from every vertex.
            if (nearest_vertex_distance(m, p) < 0.02) {
                ++skipped;
                continue;
            }
            const Face f = nearest_face_brute_force(m, p);
            const AddResult r = add_point(m, p, f);
            ASSERT_NE(r.kind, AddCase::Vertex) << "seed " << seed << " add " << added;
            ++added;
            conditional += r.conditional_flip ? 1 : 0;
            edges += r.kind == AddCase::Edge ? 1 : 0;
            ASSERT_TRUE(bit_equal(m.position(r.vertex), p));
            ASSERT_EQ(star_ball_violations(m, {r.vertex}), 0u) << "seed " << seed << " add " << added;
            in_nearby_ball += r.nearby_balls_containing_p > 0 ? 1 : 0;
            ASSERT_TRUE(r.balls_empty);
            if (added % 50 == 0) {
                ASSERT_EQ(mesh_problems(m, 2), "") << "after " << added;
            }
        }
        EXPECT_EQ(mesh_problems(m, 2), "");
        EXPECT_EQ(m.n_vertices(), 2300u);
        EXPECT_EQ(count_self_intersections(m), 0u);
        EXPECT_LT(skipped, 300u);
        // Diagnostic only: on a uniform random (not well-spaced) sample the circumradius
        // guard sometimes refuses the flip that would take p out of a neighbour's ball.
        EXPECT_LT(in_nearby_ball, 30u);
        std::printf("seed %llu: %zu edge cases, %zu conditional flips, %zu adds with p in a "
                    "nearby ball, %zu points skipped\n",
                    static_cast<unsigned long long>(seed), edges, conditional, in_nearby_ball,
                    skipped);
    }
}

// ---- Remove ------------------------------------------------------------------------------

TEST(LocalOpsRemove, RandomStarsOfDegree3To12GiveAValidCdt) {
    std::size_t fans_rejected = 0;  // the checker itself must be able to fail
    for (std::size_t k = 3; k <= 12; ++k) {
        for (std::uint64_t seed = 1; seed <= 6; ++seed) {
            const SurfaceMesh initial = random_star(k, seed * 1000 + k);
            ASSERT_EQ(mesh_problems(initial, 2), "");
            const Vertex v(0);
            ASSERT_EQ(initial.valence(v), k);

            SurfaceMesh m = initial;
            const RemoveResult r = remove_point(m, v, {.flip_after = false});
            ASSERT_TRUE(r.removed) << "k " << k << " seed " << seed << ": " << r.reason;
            EXPECT_EQ(r.link, initial.neighbors(v));
            EXPECT_TRUE(m.is_deleted(v));
            EXPECT_EQ(m.n_vertices(), k + 1);
            EXPECT_EQ(mesh_problems(m, 2), "") << "k " << k << " seed " << seed;
            EXPECT_EQ(r.flips, 0u);
            EXPECT_TRUE(triangles_are_faces(m, r));
            EXPECT_NEAR(norm(r.plane_normal), 1.0, 1e-12);
            EXPECT_EQ(cdt_problems(project_link(m, r.link, r.plane_normal), r.triangles), "")
                << "k " << k << " seed " << seed;
            EXPECT_EQ(count_self_intersections(m), 0u);
            std::vector<std::array<std::uint32_t, 3>> fan;
            for (std::uint32_t i = 1; i + 1 < k; ++i) fan.push_back({0, i, i + 1});
            if (fan != r.triangles &&
                !cdt_problems(project_link(m, r.link, r.plane_normal), fan).empty())
                ++fans_rejected;

            SurfaceMesh m2 = initial;
            const RemoveResult r2 = remove_point(m2, v);
            ASSERT_TRUE(r2.removed) << r2.reason;
            EXPECT_EQ(r2.triangles, r.triangles);  // same plane, same CDT
            EXPECT_EQ(mesh_problems(m2, 2), "") << "k " << k << " seed " << seed;
        }
    }
    EXPECT_GT(fans_rejected, 10u);
}

TEST(LocalOpsRemove, SphereVerticesOfEveryDegree) {
    std::map<std::size_t, std::size_t> tested;  // degree -> count
    for (std::uint64_t seed : {6u, 7u}) {
        const SurfaceMesh initial = sphere_mesh(2000, seed);
        std::map<std::size_t, std::vector<Vertex>> by_degree;
        for (Vertex v : initial.vertices()) by_degree[initial.valence(v)].push_back(v);
        for (const auto& [deg, vs] : by_degree) {
            for (std::size_t i = 0; i < vs.size() && i < 4; ++i) {
                const Vertex v = vs[i * vs.size() / 4];
                SurfaceMesh m = initial;
                const RemoveResult r = remove_point(m, v, {.flip_after = false});
                ASSERT_TRUE(r.removed) << "degree " << deg << ": " << r.reason;
                EXPECT_EQ(r.planes_tried, 1u);
                EXPECT_EQ(mesh_problems(m, 2), "");
                EXPECT_TRUE(triangles_are_faces(m, r));
                EXPECT_EQ(cdt_problems(project_link(m, r.link, r.plane_normal), r.triangles), "")
                    << "degree " << deg;

                SurfaceMesh m2 = initial;
                const RemoveResult r2 = remove_point(m2, v);
                ASSERT_TRUE(r2.removed) << r2.reason;
                EXPECT_EQ(mesh_problems(m2, 2), "");
                EXPECT_TRUE(r2.balls_empty) << "degree " << deg;
                EXPECT_EQ(star_ball_violations(m2, r2.link), 0u) << "degree " << deg;
                ++tested[deg];
            }
        }
    }
    // A random sphere sample has degrees from 4 (or 3) to 9 or more.
    EXPECT_GE(tested.size(), 5u);
}

TEST(LocalOpsRemove, HalfOfASphereOneByOne) {
    SurfaceMesh m = sphere_mesh(2000, 8);
    std::vector<Vertex> order(m.vertices().begin(), m.vertices().end());
    Rng rng(88);
    for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.below(i)]);
    std::size_t removed = 0, refused = 0, attempts = 0, stuck = 0, flips = 0;
    for (Vertex v : order) {
        if (removed == 1000) break;
        ++attempts;
        const RemoveResult r = remove_point(m, v);
        if (!r.removed) {
            ++refused;
            EXPECT_FALSE(r.reason.empty());
            continue;
        }
        ++removed;
        flips += r.flips;
        if (!r.balls_empty) ++stuck;
        if (removed % 100 == 0) {
            ASSERT_EQ(mesh_problems(m, 2), "") << "after " << removed;
        }
    }
    EXPECT_EQ(removed, 1000u);
    EXPECT_EQ(m.n_vertices(), 1000u);
    EXPECT_LT(double(refused), 0.05 * double(attempts)) << refused << " of " << attempts;
    EXPECT_EQ(mesh_problems(m, 2), "");
    EXPECT_EQ(count_self_intersections(m), 0u);
    EXPECT_EQ(stuck, 0u) << "local flips left non-empty diametric balls";
    EXPECT_GT(flips, 0u) << "the local flip after Remove never did anything";
    std::printf("%zu removed, %zu refused of %zu attempts, %zu flips\n", removed, refused,
                attempts, flips);
}

TEST(LocalOpsRemove, InterleavedWithAddsOnAMeshWithGarbage) {
    SurfaceMesh m = sphere_mesh(1000, 9);
    Rng rng(99);
    std::size_t adds = 0, removes = 0;
    for (int step = 0; step < 300; ++step) {
        if (step % 2 == 0) {
            Vertex v;
            do v = Vertex(static_cast<std::uint32_t>(rng.below(m.vertices_size())));
            while (m.is_deleted(v));
            const RemoveResult r = remove_point(m, v);
            removes += r.removed ? 1 : 0;
        } else {
            const Point3 p = rng.unit_vector() * (1.0 + rng.uniform(-0.005, 0.005));
            if (nearest_vertex_distance(m, p) < 0.03) continue;
            const AddResult r = add_point(m, p, nearest_face_brute_force(m, p));
            ASSERT_NE(r.kind, AddCase::Vertex);
            ASSERT_EQ(star_ball_violations(m, {r.vertex}), 0u);
            ++adds;
        }
    }
    EXPECT_TRUE(m.has_garbage());
    EXPECT_GT(adds, 100u);
    EXPECT_GT(removes, 140u);
    EXPECT_EQ(mesh_problems(m, 2), "");
    EXPECT_EQ(count_self_intersections(m), 0u);
}

TEST(LocalOpsRemove, RefusesBoundaryVertex) {
    SurfaceMesh m = test::grid(3);
    const Snapshot before(m);
    const RemoveResult r = remove_point(m, Vertex(1));  // on the bottom row
    EXPECT_FALSE(r.removed);
    EXPECT_NE(r.reason.find("boundary"), std::string::npos) << r.reason;
    EXPECT_TRUE(Snapshot(m) == before);
    // An interior vertex of the open grid is removable.
    const RemoveResult r2 = remove_point(m, Vertex(5));
    EXPECT_TRUE(r2.removed) << r2.reason;
    EXPECT_TRUE(check_mesh(m).ok());
}

TEST(LocalOpsRemove, RefusesTetrahedronVertex) {
    TriangleSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    s.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    SurfaceMesh m = SurfaceMesh::from_soup(s);
    ASSERT_EQ(mesh_problems(m, 2), "");
    const Snapshot before(m);
    for (std::uint32_t i = 0; i < 4; ++i) {
        const RemoveResult r = remove_point(m, Vertex(i));
        EXPECT_FALSE(r.removed);
        EXPECT_NE(r.reason.find("fewer than 4"), std::string::npos) << r.reason;
    }
    EXPECT_TRUE(Snapshot(m) == before);
}

TEST(LocalOpsRemove, RefusesWhenEveryPlaneNeedsAnExistingDiagonal) {
    // v above a rhombus x0..x3 whose short (Delaunay) diagonal x0x2 is already an edge of
    // the two bottom triangles: every incident plane's CDT uses x0x2, so Remove must refuse.
    TriangleSoup s;
    s.points = {{0, 0, 0.1}, {0.3, 0, 0}, {0, 1, 0}, {-0.3, 0, 0}, {0, -1, 0}};
    s.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}, {3, 2, 1}, {4, 3, 1}};
    SurfaceMesh m = SurfaceMesh::from_soup(s);
    ASSERT_EQ(mesh_problems(m, 2), "");
    const Snapshot before(m);
    const RemoveResult r = remove_point(m, Vertex(0));
    EXPECT_FALSE(r.removed);
    EXPECT_EQ(r.planes_tried, 4u);
    EXPECT_NE(r.reason.find("already a mesh edge"), std::string::npos) << r.reason;
    EXPECT_TRUE(Snapshot(m) == before);
}

TEST(LocalOpsRemove, DeletedVertexThrows) {
    SurfaceMesh m = test::icosphere(1);
    ASSERT_TRUE(remove_point(m, Vertex(0)).removed);
    EXPECT_THROW((void)remove_point(m, Vertex(0)), InvalidInput);
    EXPECT_THROW((void)remove_point(m, Vertex(100000)), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
