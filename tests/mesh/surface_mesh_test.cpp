#include "dynmesh/mesh/surface_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/mesh/check.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

void expect_valid_closed(const SurfaceMesh& m, long long euler, const std::string& ctx) {
    const auto r = check_mesh(m, {.require_closed = true});
    EXPECT_TRUE(r.ok()) << ctx << "\n" << r.summary("  ");
    EXPECT_EQ(r.integer("euler"), euler) << ctx;
}

TEST(SurfaceMesh, BuildsClosedMeshes) {
    const SurfaceMesh oct = test::octahedron();
    EXPECT_EQ(oct.n_vertices(), 6u);
    EXPECT_EQ(oct.n_edges(), 12u);
    EXPECT_EQ(oct.n_faces(), 8u);
    expect_valid_closed(oct, 2, "octahedron");
    for (Vertex v : oct.vertices()) EXPECT_EQ(oct.valence(v), 4u);
    const SurfaceMesh ico = test::icosphere(2);
    expect_valid_closed(ico, 2, "icosphere");
}

TEST(SurfaceMesh, OpenGridHasBoundary) {
    const SurfaceMesh g = test::grid(3);
    const auto r = check_mesh(g);
    EXPECT_TRUE(r.ok()) << r.summary();
    EXPECT_FALSE(r.flag("closed"));
    EXPECT_EQ(r.integer("boundary_edges"), 12);
    EXPECT_FALSE(check_mesh(g, {.require_closed = true}).ok());
}

TEST(SurfaceMesh, FromSoupRejectsBadTopology) {
    TriangleSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    const auto expect_repeated_edge = [&](const std::string& triangle) {
        try {
            (void)SurfaceMesh::from_soup(s);
            ADD_FAILURE() << "a repeated edge direction was accepted";
        } catch (const TopologyError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(triangle + ": edge (0, 1) is used twice in the same direction"), std::string::npos)
                << what;
        }
    };
    s.triangles = {{0, 1, 2}, {0, 1, 3}};  // same direction twice
    expect_repeated_edge("triangle 1");
    s.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};  // a third triangle on the edge
    expect_repeated_edge("triangle 2");
    s.triangles = {{1, 0, 3}, {0, 1, 2}, {2, 1, 0}};  // the same, the third one reversed
    try {
        (void)SurfaceMesh::from_soup(s);
        ADD_FAILURE() << "an edge with three triangles was accepted";
    } catch (const TopologyError& e) {
        EXPECT_NE(std::string(e.what()).find("triangle 2: edge (1, 0) is used twice"), std::string::npos) << e.what();
    }
    s.triangles = {{0, 1, 7}};
    EXPECT_THROW((void)SurfaceMesh::from_soup(s), InvalidInput);
    s.triangles = {{0, 1, 1}};
    EXPECT_THROW((void)SurfaceMesh::from_soup(s), InvalidInput);
    // Two triangles sharing only vertex 0: a pinched (non-manifold) vertex.
    s.points.push_back({2, 2, 2});
    s.triangles = {{0, 1, 2}, {0, 3, 4}};
    try {
        (void)SurfaceMesh::from_soup(s);
        FAIL() << "pinched vertex accepted";
    } catch (const TopologyError& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 0"), std::string::npos) << e.what();
    }
    s.triangles = {{0, 1, 2}};
    s.points[0].x = std::nan("");
    EXPECT_THROW((void)SurfaceMesh::from_soup(s), InvalidInput);
}

/// The soup's triangles in a random order (Fisher-Yates with the seed).
void shuffle_triangles(TriangleSoup& s, std::uint64_t seed) {
    Rng rng(seed);
    for (std::size_t i = s.triangles.size(); i > 1; --i) std::swap(s.triangles[i - 1], s.triangles[rng.below(i)]);
}

/// Octahedra chained at single vertices: the first alone, then one more for each entry of
/// `at`, sharing its vertex 0 with that vertex of the soup so far (its others are new,
/// numbered after the soup's).
TriangleSoup glued_octahedra(std::initializer_list<std::uint32_t> at) {
    const TriangleSoup octahedron = test::octahedron().to_soup();
    TriangleSoup glued = octahedron;
    for (const std::uint32_t shared : at) {
        const auto base = std::uint32_t(glued.points.size()) - 1;  // octahedron vertex i > 0 -> base + i
        for (std::uint32_t i = 1; i < octahedron.points.size(); ++i)
            glued.points.push_back(octahedron.points[i] + Vec3{0, 0, 3.0 * (1 + base)});
        for (auto tri : octahedron.triangles) {
            for (auto& i : tri) i = i == 0 ? shared : base + i;
            glued.triangles.push_back(tri);
        }
    }
    return glued;
}

/// The triangles, each rotated to start at its smallest index (orientation kept).
std::vector<std::array<std::uint32_t, 3>> rotated_to_smallest(std::vector<std::array<std::uint32_t, 3>> ts) {
    for (auto& t : ts) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return ts;
}

/// A closed bipyramid over a k-gon: two apices of valence k.
SurfaceMesh bipyramid(std::uint32_t k) {
    TriangleSoup s;
    s.points = {{0, 0, 1}, {0, 0, -1}};
    for (std::uint32_t i = 0; i < k; ++i) {
        const double a = 6.283185307179586 * i / k;
        s.points.push_back({std::cos(a), std::sin(a), 0});
    }
    for (std::uint32_t i = 0; i < k; ++i) {
        const std::uint32_t r = 2 + i, q = 2 + (i + 1) % k;
        s.triangles.push_back({0, r, q});
        s.triangles.push_back({1, q, r});
    }
    return SurfaceMesh::from_soup(s);
}

// Whatever the triangle order and the corner each triangle starts at, the mesh is valid and
// reads back as the same soup (faces in input order, with their orientation), through either
// overload.
TEST(SurfaceMesh, FromSoupRoundTripsAnyTriangleOrder) {
    for (const SurfaceMesh& base : {test::icosphere(3), test::grid(9), bipyramid(300)}) {
        TriangleSoup s = base.to_soup();
        shuffle_triangles(s, 7);
        Rng rng(8);  // the corner each triangle starts at
        for (auto& t : s.triangles) std::rotate(t.begin(), t.begin() + rng.below(3), t.end());
        const SurfaceMesh m = SurfaceMesh::from_soup(s);
        const auto r = check_mesh(m);
        EXPECT_TRUE(r.ok()) << r.summary();
        EXPECT_EQ(m.n_edges(), base.n_edges());
        const TriangleSoup back = m.to_soup();
        EXPECT_EQ(back.points, s.points);
        EXPECT_EQ(rotated_to_smallest(back.triangles), rotated_to_smallest(s.triangles));
        TriangleSoup moved = s;
        const SurfaceMesh m2 = SurfaceMesh::from_soup(std::move(moved));
        EXPECT_EQ(m2.to_soup().triangles, back.triangles);
        for (Face f : m.faces()) EXPECT_EQ(m2.halfedge(f), m.halfedge(f));
    }
    // A soup it refuses keeps its points, even when handed over.
    TriangleSoup refused = test::octahedron().to_soup();
    refused.triangles.push_back(refused.triangles.front());
    const std::size_t points = refused.points.size();
    EXPECT_THROW((void)SurfaceMesh::from_soup(std::move(refused)), TopologyError);
    EXPECT_EQ(refused.points.size(), points);  // NOLINT(bugprone-use-after-move): the documented guarantee
}

/// Every connectivity array of the mesh, in handle order (for comparing two builds).
std::vector<std::uint32_t> connectivity(const SurfaceMesh& m) {
    std::vector<std::uint32_t> out;
    for (std::uint32_t h = 0; h < m.halfedges_size(); ++h) {
        out.push_back(m.to_vertex(Halfedge(h)).idx());
        out.push_back(m.next(Halfedge(h)).idx());
        out.push_back(m.prev(Halfedge(h)).idx());
        out.push_back(m.face(Halfedge(h)).idx());
    }
    for (Vertex v : m.vertices()) out.push_back(m.halfedge(v).idx());
    for (Face f : m.faces()) out.push_back(m.halfedge(f).idx());
    return out;
}

/// The arrays of connectivity() for a valid soup, by the documented rules applied one corner
/// at a time: an edge is numbered when its first corner in soup order comes, that corner takes
/// its even halfedge and the twin corner the odd one; a face's halfedge is its first corner's;
/// a vertex's is its last corner's in soup order, or its outgoing boundary halfedge; boundary
/// halfedges are linked to the boundary halfedge leaving their head.
std::vector<std::uint32_t> reference_connectivity(const TriangleSoup& s) {
    constexpr std::uint32_t none = 0xffffffffu;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge;
    std::vector<std::uint32_t> corner_h(3 * s.triangles.size());
    for (std::size_t j = 0; j < corner_h.size(); ++j) {
        const auto& t = s.triangles[j / 3];
        const std::uint32_t a = t[j % 3], b = t[(j + 1) % 3];
        const auto [it, fresh] = edge.try_emplace({std::min(a, b), std::max(a, b)}, std::uint32_t(edge.size()));
        corner_h[j] = 2 * it->second + (fresh ? 0 : 1);
    }
    const std::size_t nh = 2 * edge.size();
    std::vector<std::uint32_t> to(nh, none), next(nh, none), prev(nh, none), face(nh, none), vh(s.points.size(), none);
    for (std::size_t j = 0; j < corner_h.size(); ++j) {
        const auto& t = s.triangles[j / 3];
        const std::uint32_t h = corner_h[j];
        to[h] = t[(j + 1) % 3];
        if (to[h ^ 1u] == none) to[h ^ 1u] = t[j % 3];
        next[h] = corner_h[j - j % 3 + (j + 1) % 3];
        prev[h] = corner_h[j - j % 3 + (j + 2) % 3];
        face[h] = std::uint32_t(j / 3);
        vh[t[j % 3]] = h;
    }
    std::map<std::uint32_t, std::uint32_t> boundary_leaving;
    for (std::uint32_t h = 0; h < nh; ++h)
        if (face[h] == none) boundary_leaving[to[h ^ 1u]] = h;
    for (std::uint32_t h = 0; h < nh; ++h)
        if (face[h] == none) {
            next[h] = boundary_leaving.at(to[h]);
            prev[next[h]] = h;
            vh[to[h ^ 1u]] = h;
        }
    std::vector<std::uint32_t> out;
    for (std::size_t h = 0; h < nh; ++h) out.insert(out.end(), {to[h], next[h], prev[h], face[h]});
    out.insert(out.end(), vh.begin(), vh.end());
    for (std::size_t t = 0; t < s.triangles.size(); ++t) out.push_back(corner_h[3 * t]);
    return out;
}

/// from_soup's error message for the soup (or "accepted").
std::string from_soup_message(const TriangleSoup& soup, unsigned threads) {
    try {
        (void)SurfaceMesh::from_soup(soup, {.threads = threads});
    } catch (const Error& e) {
        return e.what();
    }
    return "accepted";
}

// The threads split the work, never the result: on closed and open shuffled soups, with
// isolated vertices, with no triangles, every connectivity array equals the one-corner-at-a-
// time model for 1, 2, 3 and 7 threads (and more threads than vertices).
TEST(SurfaceMesh, FromSoupFollowsItsRulesForEveryThreadCount) {
    std::vector<TriangleSoup> soups;
    for (const SurfaceMesh& base : {test::icosphere(4), test::grid(40)}) {
        TriangleSoup s = base.to_soup();
        shuffle_triangles(s, 11);
        soups.push_back(s);
    }
    soups.push_back(soups.back());
    for (int i = 0; i < 5; ++i) soups.back().points.push_back({10.0 + i, 0, 0});  // isolated
    soups.push_back({{{0, 0, 0}, {1, 0, 0}}, {}});                               // no triangles
    soups.push_back({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}});            // one
    for (const TriangleSoup& s : soups) {
        const std::vector<std::uint32_t> expected = reference_connectivity(s);
        for (unsigned threads : {1u, 2u, 3u, 7u, 1000u}) {
            const SurfaceMesh m = SurfaceMesh::from_soup(s, {.threads = threads});
            EXPECT_EQ(connectivity(m), expected) << threads << " threads, " << s.triangles.size() << " triangles";
        }
    }
}

// Errors in several parts: the first in soup order is named, whatever the split. The first
// bad element sits late in part 0 (or at the end of it), a later one at the start of part 1,
// where a thread finds it first.
TEST(SurfaceMesh, FromSoupNamesTheFirstErrorForEveryThreadCount) {
    const TriangleSoup s = test::icosphere(4).to_soup();
    const std::size_t n = s.triangles.size(), nv = s.points.size();
    std::vector<std::pair<TriangleSoup, std::string>> cases;
    TriangleSoup bad = s;
    for (std::size_t t : {n / 3 - 1, n / 2 - 1, n / 2}) bad.triangles[t][1] = std::uint32_t(nv + t);
    cases.push_back({bad, "triangle " + std::to_string(n / 3 - 1) + " uses vertex index"});
    bad = s;
    for (std::size_t t : {n / 3 - 1, n / 2}) bad.triangles[t][2] = bad.triangles[t][0];
    cases.push_back({bad, "triangle " + std::to_string(n / 3 - 1) + " repeats a vertex"});
    bad = s;
    for (std::size_t t : {n / 3 - 1, n / 2}) std::swap(bad.triangles[t][0], bad.triangles[t][1]);
    cases.push_back({bad, "is used twice in the same direction"});
    bad = s;
    bad.points[nv / 3 - 1].y = std::nan("");
    bad.points[nv / 2].z = INFINITY;
    cases.push_back({bad, "vertex " + std::to_string(nv / 3 - 1) + " has a non-finite coordinate"});
    // Topology found by the parallel passes: two boundary fans at a vertex, an edge of four
    // triangles, a vertex with two closed fans (two octahedra sharing their vertex 0).
    TriangleSoup bowtie{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}};
    cases.push_back({bowtie, "vertex 0 is non-manifold: it has two separate boundary fans"});
    TriangleSoup four{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                      {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {1, 0, 5}}};
    cases.push_back({four, "triangle 2: edge (0, 1) is used twice in the same direction"});
    // A chain of three octahedra: the second shares the first's vertex 0, the third shares the
    // second's last vertex (15 in all: 0 and 10 are pinched, in different parts).
    const TriangleSoup glued = glued_octahedra({0, 10});
    ASSERT_EQ(glued.points.size(), 16u);
    cases.push_back({glued, "vertex 0 is non-manifold: its triangles form more than one fan"});
    for (const auto& [soup, expected] : cases)
        for (unsigned threads : {1u, 2u, 3u, 7u}) {
            const std::string got = from_soup_message(soup, threads);
            EXPECT_NE(got.find(expected), std::string::npos) << threads << " threads: " << got;
        }
}

// Two closed octahedra glued at one vertex: every edge has two triangles and no boundary, but
// the shared vertex has two fans.
TEST(SurfaceMesh, FromSoupRejectsClosedPinchedVertex) {
    const TriangleSoup s = glued_octahedra({0});
    try {
        (void)SurfaceMesh::from_soup(s);
        FAIL() << "a vertex with two closed fans was accepted";
    } catch (const TopologyError& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 0 is non-manifold"), std::string::npos) << e.what();
    }
}

TEST(SurfaceMesh, FlipKeepsOrientationAndVertices) {
    // Planar quad p=(0,0), q=(1,0), r=(1/2,1), s=(1/2,-1): both new triangles CCW.
    TriangleSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}};
    s.triangles = {{0, 1, 2}, {1, 0, 3}};
    SurfaceMesh m = SurfaceMesh::from_soup(s);
    const Edge e = m.find_edge(Vertex(0), Vertex(1));
    ASSERT_TRUE(m.is_flip_ok(e));
    m.flip(e);
    EXPECT_TRUE(m.find_edge(Vertex(2), Vertex(3)).is_valid());
    EXPECT_FALSE(m.find_edge(Vertex(0), Vertex(1)).is_valid());
    for (Face f : m.faces()) {
        const auto v = m.face_vertices(f);
        const Vec3 n = cross(m.position(v[1]) - m.position(v[0]), m.position(v[2]) - m.position(v[0]));
        EXPECT_GT(n.z, 0) << "face " << f.idx() << " not CCW";
    }
    EXPECT_TRUE(check_mesh(m).ok()) << check_mesh(m).summary();
    EXPECT_EQ(m.positions(), s.points);
}

/// Operation `op` (0 flip, 1 face split, 2 edge split, 3 collapse, 4 vertex removal) on a
/// random element of a unit-sphere mesh; false when the element drawn is deleted (nothing
/// tried). A flip or collapse that is not allowed is skipped.
bool random_operation(SurfaceMesh& m, Rng& rng, int op) {
    if (op == 0) {
        const Edge e(static_cast<std::uint32_t>(rng.below(m.edges_size())));
        if (!m.is_deleted(e) && m.is_flip_ok(e)) m.flip(e);
    } else if (op == 1) {
        const Face f(static_cast<std::uint32_t>(rng.below(m.faces_size())));
        if (m.is_deleted(f)) return false;
        const auto v = m.face_vertices(f);
        m.split_face(f, normalized((m.position(v[0]) + m.position(v[1]) + m.position(v[2])) / 3.0));
    } else if (op == 2) {
        const Edge e(static_cast<std::uint32_t>(rng.below(m.edges_size())));
        if (m.is_deleted(e)) return false;
        m.split_edge(e, normalized((m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1))) * 0.5));
    } else if (op == 3) {
        const Halfedge h(static_cast<std::uint32_t>(rng.below(m.halfedges_size())));
        if (!m.is_deleted(h) && m.is_collapse_ok(h)) m.collapse(h);
    } else {
        const Vertex v(static_cast<std::uint32_t>(rng.below(m.vertices_size())));
        if (!m.is_deleted(v)) (void)m.remove_vertex(v);
    }
    return true;
}

TEST(SurfaceMesh, RandomOperationSequencesStayValid) {
    for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
        SurfaceMesh m = test::icosphere(2);
        Rng rng(seed);
        for (int step = 0; step < 400; ++step) {
            const int op = static_cast<int>(rng.below(5));
            const std::string ctx = "seed " + std::to_string(seed) + " step " + std::to_string(step) +
                                    " op " + std::to_string(op);
            if (!random_operation(m, rng, op)) continue;
            const auto r = check_mesh(m, {.require_closed = true, .check_degenerate = false});
            ASSERT_TRUE(r.ok()) << ctx << "\n" << r.summary("  ");
            ASSERT_EQ(r.integer("euler"), 2) << ctx;
            if (step % 50 == 49) {
                m.garbage_collection();
                const auto r2 = check_mesh(m, {.require_closed = true, .check_degenerate = false});
                ASSERT_TRUE(r2.ok()) << ctx << " after gc\n" << r2.summary("  ");
            }
        }
    }
}

TEST(SurfaceMesh, ReplaceFacesAddsJoinsAndRemovesComponents) {
    // Sphere A at the origin, its mirror image B at x = 3 (a second component added by
    // replace_faces with nothing removed), then a tube between the caps around A's +x pole
    // and B's -x pole: one sphere again. Then the whole component goes.
    SurfaceMesh m = test::icosphere(2);
    const std::size_t n = m.vertices_size();
    std::vector<std::array<Vertex, 3>> b_tris;
    for (std::size_t i = 0; i < n; ++i) {
        const Point3 p = m.position(Vertex(static_cast<std::uint32_t>(i)));
        (void)m.add_vertex({3.0 - p.x, p.y, p.z});
    }
    const auto mirror = [&](Vertex v) { return Vertex(static_cast<std::uint32_t>(v.idx() + n)); };
    for (Face f : m.faces()) {
        const auto v = m.face_vertices(f);
        b_tris.push_back({mirror(v[0]), mirror(v[2]), mirror(v[1])});
    }
    (void)m.replace_faces({}, b_tris);
    {
        const auto r = check_mesh(m, {.require_closed = true});
        ASSERT_TRUE(r.ok()) << r.summary("  ");
        EXPECT_EQ(r.integer("components"), 2);
        EXPECT_EQ(r.integer("euler"), 4);
    }
    Vertex pole = *m.vertices().begin();
    for (std::uint32_t i = 0; i < n; ++i)
        if (m.position(Vertex(i)).x > m.position(pole).x) pole = Vertex(i);
    const std::vector<Vertex> ring = m.neighbors(pole);  // counter-clockwise around the pole
    std::vector<Face> cut;
    for (Halfedge h : m.outgoing_halfedges(pole)) cut.push_back(m.face(h));
    for (Halfedge h : m.outgoing_halfedges(mirror(pole))) cut.push_back(m.face(h));
    const std::size_t k = ring.size();
    std::vector<std::array<Vertex, 3>> tube;
    for (std::size_t i = 0; i < k; ++i) {
        const Vertex l0 = ring[i], l1 = ring[(i + 1) % k];
        tube.push_back({l0, l1, mirror(l1)});
        tube.push_back({l0, mirror(l1), mirror(l0)});
    }
    // A tube missing one quad leaves the hole open: refused, mesh unchanged.
    std::vector<std::array<Vertex, 3>> short_tube(tube.begin(), tube.end() - 2);
    EXPECT_THROW((void)m.replace_faces(cut, short_tube), InvalidInput);
    EXPECT_EQ(m.n_faces(), 2 * 320u);
    // Removing the caps without filling them would leave a hole: refused too.
    EXPECT_THROW((void)m.replace_faces(cut, {}), InvalidInput);
    // Reversed triangles use the boundary edges the wrong way round: refused too.
    std::vector<std::array<Vertex, 3>> reversed;
    for (const auto& t : tube) reversed.push_back({t[0], t[2], t[1]});
    EXPECT_THROW((void)m.replace_faces(cut, reversed), InvalidInput);
    expect_valid_closed(m, 4, "after refused replacements");

    const auto added = m.replace_faces(cut, tube);
    EXPECT_EQ(added.size(), 2 * k);
    EXPECT_TRUE(m.is_deleted(pole));
    {
        const auto r = check_mesh(m, {.require_closed = true});
        ASSERT_TRUE(r.ok()) << r.summary("  ");
        EXPECT_EQ(r.integer("components"), 1);
        EXPECT_EQ(r.integer("euler"), 2);
    }
    // An unused vertex can go on its own; one in use cannot.
    const Vertex lone = m.add_vertex({9, 9, 9});
    EXPECT_THROW(m.remove_isolated_vertex(*m.vertices().begin()), InvalidInput);
    m.remove_isolated_vertex(lone);
    EXPECT_TRUE(m.is_deleted(lone));
    std::vector<Face> all(m.faces().begin(), m.faces().end());
    (void)m.replace_faces(all, {});
    EXPECT_EQ(m.n_faces(), 0u);
    EXPECT_EQ(m.n_vertices(), 0u);
    EXPECT_EQ(m.n_edges(), 0u);
}

TEST(SurfaceMesh, RefusesOperationsThatDegenerate) {
    // Removing a vertex of a tetrahedron would leave two copies of one triangle.
    TriangleSoup t;
    t.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    t.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    SurfaceMesh tet = SurfaceMesh::from_soup(t);
    EXPECT_FALSE(tet.remove_vertex(Vertex(0)));
    std::vector<std::array<std::uint32_t, 3>> one = {{0, 1, 2}};
    EXPECT_THROW(tet.remove_vertex(Vertex(0), one), InvalidInput);
    EXPECT_TRUE(check_mesh(tet, {.require_closed = true}).ok());
    // Collapsing an edge of a lone triangle would leave a dangling edge.
    TriangleSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    s.triangles = {{0, 1, 2}};
    SurfaceMesh tri = SurfaceMesh::from_soup(s);
    for (Edge e : tri.edges())
        for (int i = 0; i < 2; ++i) EXPECT_FALSE(tri.is_collapse_ok(SurfaceMesh::halfedge(e, i)));
    // check_mesh flags a folded pair (two triangles on the same three vertices).
    s.triangles = {{0, 1, 2}, {0, 2, 1}};
    const auto r = check_mesh(SurfaceMesh::from_soup(s));
    EXPECT_FALSE(r.ok());
}

TEST(SurfaceMesh, SplitEdgeOnBoundary) {
    SurfaceMesh g = test::grid(2);
    for (Edge e : g.edges())
        if (g.is_boundary(e)) {
            g.split_edge(e, (g.position(g.vertex(e, 0)) + g.position(g.vertex(e, 1))) * 0.5);
            break;
        }
    const auto r = check_mesh(g);
    EXPECT_TRUE(r.ok()) << r.summary();
    EXPECT_EQ(r.integer("euler"), 1);
}

TEST(SurfaceMesh, RemoveVertexWithGivenTriangulation) {
    SurfaceMesh m = test::icosphere(1);
    Vertex v(0);
    const std::size_t k = m.valence(v);
    ASSERT_EQ(k, 5u);
    std::vector<std::array<std::uint32_t, 3>> fan = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
    m.remove_vertex(v, fan);
    expect_valid_closed(m, 2, "after remove");
    // A bad triangulation is refused and leaves the mesh unchanged.
    SurfaceMesh m2 = test::icosphere(1);
    std::vector<std::array<std::uint32_t, 3>> bad = {{0, 2, 1}, {0, 2, 3}, {0, 3, 4}};
    EXPECT_THROW(m2.remove_vertex(Vertex(0), bad), InvalidInput);
    expect_valid_closed(m2, 2, "after refused remove");
    EXPECT_EQ(m2.n_vertices(), test::icosphere(1).n_vertices());
}

TEST(SurfaceMesh, PropertiesFollowGarbageCollection) {
    SurfaceMesh m = test::icosphere(1);
    auto tag = m.add_vertex_property<int>("v:tag", -1);
    for (Vertex v : m.vertices()) tag[v] = static_cast<int>(v.idx());
    ASSERT_TRUE(m.remove_vertex(Vertex(3)));
    m.garbage_collection();
    for (Vertex v : m.vertices()) EXPECT_NE(tag[v], 3);
    EXPECT_EQ(tag.vector().size(), m.n_vertices());
    SurfaceMesh copy = m;
    auto ctag = copy.get_vertex_property<int>("v:tag");
    ASSERT_TRUE(ctag.is_valid());
    ctag[Vertex(0)] = 1000;
    EXPECT_NE(tag[Vertex(0)], 1000);
}

TEST(SurfaceMesh, AddingAPropertyUnderAnExistingNameThrows) {
    SurfaceMesh m = test::icosphere(1);
    auto tag = m.add_vertex_property<int>("tag", 1);
    EXPECT_THROW(m.add_vertex_property<int>("tag", 2), InvalidInput);
    EXPECT_THROW(m.add_vertex_property<double>("tag"), InvalidInput);  // any type
    EXPECT_EQ(tag[Vertex(0)], 1) << "the first property is untouched";
    // Each element kind has its own names.
    auto ftag = m.add_face_property<char>("tag", 0);
    EXPECT_THROW(m.add_face_property<char>("tag"), InvalidInput);
    auto etag = m.add_edge_property<float>("tag");
    EXPECT_THROW(m.add_edge_property<float>("tag"), InvalidInput);
    EXPECT_TRUE(ftag.is_valid() && etag.is_valid());
    // A copy keeps the names taken; a removed property frees its name.
    SurfaceMesh copy = m;
    EXPECT_THROW(copy.add_vertex_property<int>("tag"), InvalidInput);
    m.remove_property(tag);
    EXPECT_TRUE(m.add_vertex_property<int>("tag", 3).is_valid());
}

TEST(SurfaceMesh, IsValidIsFalseForDeletedAndOutOfRangeElements) {
    SurfaceMesh m = test::icosphere(1);
    const auto nv = static_cast<std::uint32_t>(m.vertices_size()), ne = static_cast<std::uint32_t>(m.edges_size()),
               nf = static_cast<std::uint32_t>(m.faces_size());
    for (Vertex v : m.vertices()) EXPECT_TRUE(m.is_valid(v));
    for (Edge e : m.edges()) EXPECT_TRUE(m.is_valid(e) && m.is_valid(SurfaceMesh::halfedge(e, 1)));
    for (Face f : m.faces()) EXPECT_TRUE(m.is_valid(f));
    EXPECT_FALSE(m.is_valid(Vertex()));
    EXPECT_FALSE(m.is_valid(Vertex(nv)));
    EXPECT_FALSE(m.is_valid(Edge(ne)));
    EXPECT_FALSE(m.is_valid(Halfedge(2 * ne)));
    EXPECT_FALSE(m.is_valid(Face(nf)));
    EXPECT_FALSE(m.is_valid(Face()));

    ASSERT_TRUE(m.remove_vertex(Vertex(3)));
    ASSERT_TRUE(m.has_garbage());
    EXPECT_FALSE(m.is_valid(Vertex(3))) << "a deleted vertex is not usable";
    std::size_t deleted_edges = 0, deleted_faces = 0;
    for (std::uint32_t i = 0; i < m.edges_size(); ++i) {
        const Edge e(i);
        deleted_edges += m.is_deleted(e);
        EXPECT_EQ(m.is_valid(e), !m.is_deleted(e)) << "edge " << i;
        EXPECT_EQ(m.is_valid(SurfaceMesh::halfedge(e, 0)), !m.is_deleted(e)) << "edge " << i;
    }
    for (std::uint32_t i = 0; i < m.faces_size(); ++i) {
        deleted_faces += m.is_deleted(Face(i));
        EXPECT_EQ(m.is_valid(Face(i)), !m.is_deleted(Face(i))) << "face " << i;
    }
    EXPECT_GT(deleted_edges, 0u);
    EXPECT_GT(deleted_faces, 0u);
    // Deleted elements are refused where a usable one is required.
    Face dead;
    for (std::uint32_t i = 0; i < m.faces_size() && !dead.is_valid(); ++i)
        if (m.is_deleted(Face(i))) dead = Face(i);
    EXPECT_THROW(m.split_face(dead, Point3{0, 0, 0}), InvalidInput);

    m.garbage_collection();
    for (std::uint32_t i = 0; i < m.vertices_size(); ++i) EXPECT_TRUE(m.is_valid(Vertex(i)));
    for (std::uint32_t i = 0; i < m.edges_size(); ++i) EXPECT_TRUE(m.is_valid(Edge(i)));
    for (std::uint32_t i = 0; i < m.faces_size(); ++i) EXPECT_TRUE(m.is_valid(Face(i)));
    EXPECT_FALSE(m.is_valid(Vertex(static_cast<std::uint32_t>(m.vertices_size()))));
}


/// Every face whose vertices changed (made, relinked, deleted, a vertex replaced) since the log
/// was last cleared is in the face log; a renumbering empties it.
TEST(SurfaceMesh, FaceLogHoldsEveryFaceAnOperationChanged) {
    using Corners = std::array<std::uint32_t, 4>;  // vertices (rotated to the smallest), deleted
    auto corners = [](const SurfaceMesh& m) {
        std::vector<Corners> c(m.faces_size());
        for (std::uint32_t i = 0; i < m.faces_size(); ++i) {
            const Face f(i);
            if (m.is_deleted(f)) {
                c[i] = {0, 0, 0, 1};
                continue;
            }
            auto v = m.face_vertices(f);
            std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
            c[i] = {v[0].idx(), v[1].idx(), v[2].idx(), 0};
        }
        return c;
    };
    std::size_t logged_changes = 0;
    for (std::uint64_t seed : {5u, 6u, 7u}) {
        SurfaceMesh m = test::icosphere(2);
        m.enable_face_log();
        EXPECT_TRUE(m.face_log().empty());
        Rng rng(seed);
        for (int step = 0; step < 300; ++step) {
            const std::vector<Corners> before = corners(m);
            m.clear_face_log();
            const int op = static_cast<int>(rng.below(5));
            const std::string ctx = "seed " + std::to_string(seed) + " step " + std::to_string(step) + " op " +
                                    std::to_string(op);
            if (!random_operation(m, rng, op)) continue;
            const std::vector<Corners> after = corners(m);
            std::vector<char> logged(m.faces_size(), 0);
            for (std::uint32_t f : m.face_log()) {
                ASSERT_LT(f, m.faces_size()) << ctx;
                logged[f] = 1;
            }
            for (std::uint32_t i = 0; i < after.size(); ++i) {
                const bool changed = i >= before.size() || before[i] != after[i];
                if (changed) {
                    ++logged_changes;
                    EXPECT_TRUE(logged[i]) << ctx << ": face " << i << " changed and is not in the log";
                }
            }
        }
        m.garbage_collection();
        EXPECT_TRUE(m.face_log().empty()) << "a renumbering keeps stale indices in the log";
    }
    EXPECT_GT(logged_changes, 1000u);
}

}  // namespace
}  // namespace dynmesh
