#include "dynmesh/io/simplex_mesh_io.hpp"

#include <cstdlib>
#include <limits>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/io/point_set_io.hpp"
#include "dynmesh/quadtree/oct_mesh.hpp"
#include "dynmesh/quadtree/quad_mesh.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A simple positively oriented tetrahedral mesh: the Kuhn subdivision of an n³ grid over
/// [0, 1]³ with a non-dyadic spacing (numbers that need all 17 digits).
struct TetGrid {
    std::vector<Point3> points;
    std::vector<std::array<std::uint32_t, 4>> tets;
};
TetGrid kuhn_grid(std::uint32_t n) {
    TetGrid g;
    const auto id = [n](std::uint32_t i, std::uint32_t j, std::uint32_t k) {
        return (k * (n + 1) + j) * (n + 1) + i;
    };
    for (std::uint32_t k = 0; k <= n; ++k)
        for (std::uint32_t j = 0; j <= n; ++j)
            for (std::uint32_t i = 0; i <= n; ++i)
                g.points.push_back({i / double(n), j / double(n) + 0.1, k / double(n) / 3});
    // The 6 tetrahedra of a cube along the main diagonal, one per permutation of the axes.
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (std::uint32_t k = 0; k < n; ++k)
        for (std::uint32_t j = 0; j < n; ++j)
            for (std::uint32_t i = 0; i < n; ++i)
                for (const auto& perm : perms) {
                    std::array<std::uint32_t, 3> c{i, j, k};
                    std::array<std::uint32_t, 4> t{};
                    t[0] = id(c[0], c[1], c[2]);
                    for (int s = 0; s < 3; ++s) {
                        ++c[static_cast<std::size_t>(perm[s])];
                        t[static_cast<std::size_t>(s) + 1] = id(c[0], c[1], c[2]);
                    }
                    if (orient3d(g.points[t[0]], g.points[t[1]], g.points[t[2]],
                                 g.points[t[3]]) != Sign::Positive)
                        std::swap(t[2], t[3]);
                    g.tets.push_back(t);
                }
    return g;
}

/// The first token after `key` in `text`, as a number.
long long number_after(const std::string& text, const std::string& key) {
    const auto at = text.find(key);
    if (at == std::string::npos) return -1;
    return std::strtoll(text.c_str() + at + key.size(), nullptr, 10);
}

TEST(SimplexMeshIo, FormatFollowsTheExtension) {
    EXPECT_EQ(simplex_mesh_format("a/out.node"), SimplexMeshFormat::NodeEle);
    EXPECT_EQ(simplex_mesh_format("out.ele"), SimplexMeshFormat::NodeEle);
    EXPECT_EQ(simplex_mesh_format("out.OFF"), SimplexMeshFormat::Off);
    EXPECT_EQ(simplex_mesh_format("out.vtu"), SimplexMeshFormat::Vtu);
    EXPECT_EQ(simplex_mesh_format("out.Mesh"), SimplexMeshFormat::Medit);
    for (const char* bad : {"out.xyz", "out", "out.vtk", "out.mesh.gz"}) {
        try {
            (void)simplex_mesh_format(bad);
            ADD_FAILURE() << bad << " accepted";
        } catch (const InvalidInput& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(bad), std::string::npos) << msg;
            EXPECT_NE(msg.find(".vtu"), std::string::npos) << msg;  // lists what is supported
        }
    }
}

TEST(SimplexMeshIo, NodeEleWritesBothFiles3D) {
    const auto dir = test::scratch_dir("simplex_mesh_io_node");
    const TetGrid g = kuhn_grid(2);
    const auto files = write_tet_mesh(dir / "out.node", g.points, g.tets);
    ASSERT_EQ(files.size(), 2u);
    EXPECT_EQ(files[0], dir / "out.node");
    EXPECT_EQ(files[1], dir / "out.ele");
    const PointSet back = read_point_set(dir / "out.node");
    EXPECT_EQ(back.dimension, 3);
    EXPECT_EQ(back.points, g.points);  // shortest round-trip numbers: exact
    const std::string ele = slurp(dir / "out.ele");
    std::istringstream in(ele);
    std::size_t count = 0, corners = 0, attributes = 1;
    in >> count >> corners >> attributes;
    EXPECT_EQ(count, g.tets.size());
    EXPECT_EQ(corners, 4u);
    EXPECT_EQ(attributes, 0u);
    std::size_t id = 0;
    std::array<std::uint32_t, 4> t{};
    in >> id >> t[0] >> t[1] >> t[2] >> t[3];  // first line after the header, 1-based
    in >> id >> t[0] >> t[1] >> t[2] >> t[3];
    EXPECT_EQ(id, 2u);
    for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(t[k], g.tets[1][k] + 1);
    // -o OUT.ele names the same pair.
    const auto again = write_tet_mesh(dir / "other.ele", g.points, g.tets);
    EXPECT_EQ(again[0], dir / "other.node");
    EXPECT_EQ(slurp(dir / "other.ele"), ele);
}

TEST(SimplexMeshIo, OffOfATetMeshIsItsClosedOutwardBoundary) {
    const auto dir = test::scratch_dir("simplex_mesh_io_off");
    const std::uint32_t n = 3;
    const TetGrid g = kuhn_grid(n);
    (void)write_tet_mesh(dir / "out.off", g.points, g.tets);
    const TriangleSoup soup = read_soup(dir / "out.off");
    EXPECT_EQ(soup.triangles.size(), 6u * 2 * n * n);         // 2 triangles per boundary square
    EXPECT_EQ(soup.points.size(), 6u * n * n + 2);            // boundary vertices only (χ = 2)
    const SurfaceMesh surface = read_mesh(dir / "out.off");   // oriented, closed 2-manifold
    EXPECT_EQ(surface.n_faces(), soup.triangles.size());
    // Outward: the signed volume enclosed equals the box volume (1 · 1 · 1/3).
    double volume6 = 0;
    for (const auto& t : soup.triangles)
        volume6 += dot(soup.points[t[0]], cross(soup.points[t[1]], soup.points[t[2]]));
    EXPECT_NEAR(volume6 / 6, 1.0 / 3, 1e-12);
}

TEST(SimplexMeshIo, OffOfATriangleMeshKeepsEveryTriangle) {
    const auto dir = test::scratch_dir("simplex_mesh_io_off2");
    const std::vector<Vec2> pts = {{0.4, 0.45}, {0.6, 0.58}};
    const QuadMesh2 mesh = quad_mesh(DynQuadtree<2>::build(pts));
    (void)write_triangle_mesh(dir / "out.off", mesh.points, mesh.triangles);
    const TriangleSoup soup = read_soup(dir / "out.off");
    ASSERT_EQ(soup.points.size(), mesh.points.size());
    ASSERT_EQ(soup.triangles.size(), mesh.triangles.size());
    for (std::size_t i = 0; i < soup.points.size(); ++i)
        EXPECT_EQ(soup.points[i], (Point3{mesh.points[i].x, mesh.points[i].y, 0.0}));
    EXPECT_EQ(soup.triangles, mesh.triangles);
}

TEST(SimplexMeshIo, VtuHasTheRightCountsAndCellTypes) {
    const auto dir = test::scratch_dir("simplex_mesh_io_vtu");
    const TetGrid g = kuhn_grid(2);
    (void)write_tet_mesh(dir / "out.vtu", g.points, g.tets);
    const std::string text = slurp(dir / "out.vtu");
    EXPECT_EQ(text.rfind("<?xml", 0), 0u);
    EXPECT_NE(text.find("type=\"UnstructuredGrid\""), std::string::npos);
    EXPECT_EQ(number_after(text, "NumberOfPoints=\""), static_cast<long long>(g.points.size()));
    EXPECT_EQ(number_after(text, "NumberOfCells=\""), static_cast<long long>(g.tets.size()));
    // Points round-trip exactly (%.17g).
    std::istringstream pts(text.substr(text.find("format=\"ascii\">") + 15));
    for (const Point3& p : g.points) {
        Point3 q;
        pts >> q.x >> q.y >> q.z;
        EXPECT_EQ(q, p);
    }
    // One type per cell, all 10 (tetra); last offset = 4 · cells.
    const auto types_at = text.find("Name=\"types\"");
    ASSERT_NE(types_at, std::string::npos);
    std::istringstream types(text.substr(text.find('>', types_at) + 1));
    for (std::size_t i = 0; i < g.tets.size(); ++i) {
        int t = 0;
        types >> t;
        EXPECT_EQ(t, 10);
    }
    std::string end;
    types >> end;
    EXPECT_EQ(end, "</DataArray>");
    EXPECT_NE(text.find(" " + std::to_string(4 * g.tets.size()) + "\n        </DataArray>"),
              std::string::npos);

    const std::vector<Vec2> p2 = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
    const std::vector<std::array<std::uint32_t, 3>> t2 = {{0, 1, 2}};
    (void)write_triangle_mesh(dir / "tri.vtu", p2, t2);
    const std::string tri = slurp(dir / "tri.vtu");
    EXPECT_NE(tri.find("          5\n"), std::string::npos);  // VTK_TRIANGLE
    EXPECT_NE(tri.find("          3\n"), std::string::npos);  // offset
}

TEST(SimplexMeshIo, MeditRoundTrips) {
    const auto dir = test::scratch_dir("simplex_mesh_io_medit");
    const TetGrid g = kuhn_grid(2);
    (void)write_tet_mesh(dir / "out.mesh", g.points, g.tets);
    std::istringstream in(slurp(dir / "out.mesh"));
    std::string word;
    int version = 0, dim = 0;
    in >> word >> version;
    EXPECT_EQ(word, "MeshVersionFormatted");
    EXPECT_EQ(version, 2);
    in >> word >> dim;
    EXPECT_EQ(word, "Dimension");
    EXPECT_EQ(dim, 3);
    std::size_t nv = 0, nt = 0;
    in >> word >> nv;
    EXPECT_EQ(word, "Vertices");
    ASSERT_EQ(nv, g.points.size());
    for (const Point3& p : g.points) {
        Point3 q;
        int ref = -1;
        in >> q.x >> q.y >> q.z >> ref;
        EXPECT_EQ(q, p);
        EXPECT_EQ(ref, 0);
    }
    in >> word >> nt;
    EXPECT_EQ(word, "Tetrahedra");
    ASSERT_EQ(nt, g.tets.size());
    for (const auto& t : g.tets) {
        std::array<std::uint32_t, 4> r{};
        int ref = -1;
        in >> r[0] >> r[1] >> r[2] >> r[3] >> ref;
        for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(r[k], t[k] + 1);
        EXPECT_EQ(ref, 0);
    }
    in >> word;
    EXPECT_EQ(word, "End");

    const std::vector<Vec2> p2 = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
    const std::vector<std::array<std::uint32_t, 3>> t2 = {{0, 1, 2}};
    (void)write_triangle_mesh(dir / "tri.mesh", p2, t2);
    EXPECT_EQ(slurp(dir / "tri.mesh"),
              "MeshVersionFormatted 2\n\nDimension 2\n\nVertices\n3\n0 0 0\n1 0 0\n0 1 0\n"
              "\nTriangles\n1\n1 2 3 0\n\nEnd\n");
}

TEST(SimplexMeshIo, RepeatedWritesAreByteIdentical) {
    const auto dir = test::scratch_dir("simplex_mesh_io_repeat");
    const std::vector<Vec3> pts = {{0.41, 0.47, 0.6}, {0.55, 0.52, 0.49}};
    const OctMesh3 mesh = oct_mesh(DynQuadtree<3>::build(pts));
    for (const char* ext : {".node", ".off", ".vtu", ".mesh"}) {
        const auto a = write_tet_mesh(dir / (std::string("a") + ext), mesh.points, mesh.tets);
        const auto b = write_tet_mesh(dir / (std::string("b") + ext), mesh.points, mesh.tets);
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t i = 0; i < a.size(); ++i) {
            const std::string bytes = slurp(a[i]);
            EXPECT_FALSE(bytes.empty()) << a[i];
            EXPECT_EQ(bytes, slurp(b[i])) << a[i];
        }
        if (std::string(ext) != ".node") {
            const SimplexMeshView view{
                .dimension = 3, .points = mesh.points, .simplices = mesh.tets};
            EXPECT_EQ(slurp(a[0]), simplex_mesh_text(simplex_mesh_format(a[0]), view));
        }
    }
    // Overwriting with equal data leaves equal bytes.
    const std::string before = slurp(dir / "a.vtu");
    (void)write_tet_mesh(dir / "a.vtu", mesh.points, mesh.tets);
    EXPECT_EQ(slurp(dir / "a.vtu"), before);
}

TEST(SimplexMeshIo, BadInputThrowsAndWritesNothing) {
    const auto dir = test::scratch_dir("simplex_mesh_io_bad");
    const TetGrid g = kuhn_grid(1);
    auto tets = g.tets;
    tets[2][3] = static_cast<std::uint32_t>(g.points.size());
    EXPECT_THROW((void)write_tet_mesh(dir / "x.vtu", g.points, tets), InvalidInput);
    auto pts = g.points;
    pts[1].y = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW((void)write_tet_mesh(dir / "x.mesh", pts, g.tets), InvalidInput);
    EXPECT_THROW((void)write_simplex_mesh(dir / "x.off",
                                          {.dimension = 4, .points = g.points, .simplices = g.tets}),
                 InvalidInput);
    EXPECT_THROW((void)write_tet_mesh(dir / "x.stl", g.points, g.tets), InvalidInput);
    EXPECT_THROW((void)simplex_mesh_text(SimplexMeshFormat::NodeEle,
                                         {.dimension = 3, .points = g.points, .simplices = g.tets}),
                 InvalidInput);
    EXPECT_TRUE(std::filesystem::is_empty(dir));
    EXPECT_THROW((void)write_tet_mesh(dir / "missing" / "x.vtu", g.points, g.tets), IoError);
}

}  // namespace
}  // namespace dynmesh
