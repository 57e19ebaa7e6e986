// The real files of shared/data/meshes: valid ones load with their exact sizes, invalid ones
// throw a precise IoError, defective ones are reported for what they are.

#include <chrono>
#include <iostream>
#include <set>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/mesh/check.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

namespace fs = std::filesystem;

struct Expected {
    const char* file;
    std::size_t vertices, faces;
};
const Expected kValid[] = {
    {"eight.off", 315, 634},         {"blobby.off", 2027, 4050},   {"elephant.off", 2775, 5558},
    {"knot1.off", 3200, 6400},       {"spot.obj", 2930, 5856},     {"fandisk.off", 6475, 12946},
    {"armadillo.off", 26002, 52000}, {"igea.ply", 134345, 268686}, {"blob.stl", 1538, 3072},
    {"cube_binary.ply", 8, 12},
};

TEST(MeshFiles, ValidMeshesLoadClosedWithExactSizes) {
    std::set<std::string> covered;
    for (const Expected& e : kValid) {
        SCOPED_TRACE(e.file);
        const fs::path path = test::shared_data(std::string("meshes/") + e.file);
        const SurfaceMesh mesh = read_mesh(path);
        EXPECT_EQ(mesh.n_vertices(), e.vertices);
        EXPECT_EQ(mesh.n_faces(), e.faces);
        const CheckReport report = check_mesh(mesh, {.require_closed = true});
        EXPECT_TRUE(report.ok()) << report.summary("  ");
        covered.insert(e.file);
    }
    // Every mesh file of the folder is in the table (a new file needs an entry).
    for (const auto& entry : fs::directory_iterator(test::shared_data("meshes"))) {
        if (entry.is_regular_file()) {
            EXPECT_TRUE(covered.count(entry.path().filename().string()))
                << entry.path() << " has no expected size in this test";
        }
    }
}

TEST(MeshFiles, IgeaTristripsReadFast) {
    const fs::path path = test::shared_data("meshes/igea.ply");
    (void)read_soup(path);  // warm the page cache
    const auto start = std::chrono::steady_clock::now();
    const TriangleSoup soup = read_soup(path);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(soup.points.size(), 134345u);
    EXPECT_EQ(soup.triangles.size(), 268686u);
    // Typically ~0.02 s; the bound is loose because the machine is shared.
    EXPECT_LT(seconds, 1.0);
    std::cout << "[ info ] read_soup(igea.ply): " << seconds << " s\n";
}

TEST(MeshFiles, StlWeldsIdenticalCorners) {
    const TriangleSoup soup = read_soup(test::shared_data("meshes/blob.stl"));
    EXPECT_EQ(soup.points.size(), 1538u);
    EXPECT_EQ(soup.triangles.size(), 3072u);
    // No two points are identical after welding.
    std::set<std::array<double, 3>> distinct;
    for (const Point3& p : soup.points) distinct.insert({p.x, p.y, p.z});
    EXPECT_EQ(distinct.size(), soup.points.size());
}

// ---- invalid files ------------------------------------------------------------------------

TEST(MeshFiles, EveryInvalidFileThrowsIoErrorNamingIt) {
    std::size_t n = 0;
    for (const auto& entry : fs::directory_iterator(test::shared_data("meshes/invalid"))) {
        test::expect_read_error(entry.path(), {});
        const std::string msg = test::io_error_of([&] { (void)read_mesh(entry.path()); });
        EXPECT_NE(msg.find(entry.path().filename().string()), std::string::npos) << msg;
        ++n;
    }
    EXPECT_GE(n, 8u);
}

TEST(MeshFiles, InvalidFilesGetPreciseMessages) {
    const auto invalid = [](const char* name) {
        return test::shared_data(std::string("meshes/invalid/") + name);
    };
    test::expect_read_error(invalid("empty.off"), {"empty file"});
    test::expect_read_error(invalid("OutOfMemory.off"),
                            {"OutOfMemory.off:2:", "353535235358 vertices", "cannot fit"});
    test::expect_read_error(invalid("bad_face_lines.off"),
                            {"bad_face_lines.off:6:", "face 0 has 0 vertices"});
    test::expect_read_error(invalid("malformed.obj"),
                            {"malformed.obj:23:", "face 0", "'12'", "out of range"});
    test::expect_read_error(invalid("unparseable.stl"),
                            {"unparseable.stl:4:", "invalid coordinate '\\x10'"});
    test::expect_read_error(invalid("invalidvertex.stl"),
                            {"invalidvertex.stl:89:", "facet 12", "'blah'"});
    test::expect_read_error(invalid("toomanyvertices.stl"),
                            {"toomanyvertices.stl:91:", "facet 12 has more than 3 vertices"});
    test::expect_read_error(invalid("empty2.stl"), {"no facets"});
}

// ---- defective files --------------------------------------------------------------------

fs::path defective(const char* name) {
    return test::shared_data(std::string("meshes/defective/") + name);
}

TEST(MeshFiles, QuadsAreNotTriangulated) {
    test::expect_read_error(defective("cube_quad.off"),
                            {"cube_quad.off:11:",
                             "face 0 has 4 vertices; only triangles are "
                             "supported"});
}

template <class F>
std::string topology_error_of(F&& f) {
    try {
        f();
    } catch (const TopologyError& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected TopologyError, got: " << e.what();
        return {};
    }
    ADD_FAILURE() << "expected TopologyError, nothing thrown";
    return {};
}

TEST(MeshFiles, TopologyProblemsAreReportedByReadMesh) {
    // The soups are fine; the surfaces are not.
    EXPECT_EQ(read_soup(defective("cube-shuffled.off")).triangles.size(), 12u);
    std::string msg = topology_error_of([] { (void)read_mesh(defective("cube-shuffled.off")); });
    EXPECT_NE(msg.find("cube-shuffled.off: "), std::string::npos) << msg;
    EXPECT_NE(msg.find("same direction"), std::string::npos) << msg;

    EXPECT_EQ(read_soup(defective("cow_nonmanifold_vertex.obj")).points.size(), 2903u);
    msg = topology_error_of([] { (void)read_mesh(defective("cow_nonmanifold_vertex.obj")); });
    EXPECT_NE(msg.find("cow_nonmanifold_vertex.obj: "), std::string::npos) << msg;
    EXPECT_NE(msg.find("non-manifold"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST(MeshFiles, MeshWithBorderLoadsButIsOpen) {
    const SurfaceMesh mesh = read_mesh(defective("mesh_with_border.off"));
    EXPECT_EQ(mesh.n_vertices(), 548u);
    EXPECT_EQ(mesh.n_faces(), 1014u);
    const CheckReport closed = check_mesh(mesh, {.require_closed = true});
    EXPECT_FALSE(closed.ok());
    EXPECT_FALSE(closed.flag("closed"));
    EXPECT_GT(closed.integer("boundary_edges"), 0);
}

TEST(MeshFiles, IntersectingTetraLoadsAsSoup) {
    const TriangleSoup soup = read_soup(defective("tetra_intersected_by_triangle.off"));
    EXPECT_EQ(soup.points.size(), 7u);
    EXPECT_EQ(soup.triangles.size(), 5u);
}

}  // namespace
}  // namespace dynmesh
