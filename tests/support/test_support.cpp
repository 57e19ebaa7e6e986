#include "test_support.hpp"

#include <cstring>
#include <map>

#include "dynmesh/mesh/mesh_order.hpp"

namespace dynmesh::test {

std::filesystem::path shared_data(const std::string& relative) {
    return std::filesystem::path(DYNMESH_SHARED_DATA_DIR) / relative;
}

std::filesystem::path scratch_dir(const std::string& name) {
    const auto p = std::filesystem::path(DYNMESH_TEST_TMP_DIR) / name;
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    return p;
}

SurfaceMesh octahedron() {
    TriangleSoup s;
    s.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return SurfaceMesh::from_soup(s);
}

SurfaceMesh icosphere(int level) { return SurfaceMesh::from_soup(unit_icosphere(level)); }

double signed_volume(const SurfaceMesh& m) {
    double v = 0;
    for (Face f : m.faces()) {
        const auto c = m.face_vertices(f);
        v += dot(m.position(c[0]), cross(m.position(c[1]), m.position(c[2])));
    }
    return v / 6;
}

SurfaceMesh grid(int n) {
    TriangleSoup s;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) s.points.push_back({double(i), double(j), 0.0});
    auto id = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return SurfaceMesh::from_soup(s);
}

std::string mesh_difference(const SurfaceMesh& a, const SurfaceMesh& b) {
    if (a.vertices_size() != b.vertices_size() || a.edges_size() != b.edges_size() ||
        a.faces_size() != b.faces_size())
        return "sizes differ";
    for (std::uint32_t i = 0; i < a.vertices_size(); ++i) {
        const Vertex v(i);
        if (a.is_deleted(v) != b.is_deleted(v) || a.halfedge(v) != b.halfedge(v) ||
            std::memcmp(&a.position(v), &b.position(v), sizeof(Point3)) != 0)
            return "vertex " + std::to_string(i) + " differs";
    }
    for (std::uint32_t i = 0; i < a.halfedges_size(); ++i) {
        const Halfedge h(i);
        if (a.is_deleted(h) != b.is_deleted(h) || a.to_vertex(h) != b.to_vertex(h) || a.next(h) != b.next(h) ||
            a.prev(h) != b.prev(h) || a.face(h) != b.face(h))
            return "halfedge " + std::to_string(i) + " differs";
    }
    for (std::uint32_t i = 0; i < a.faces_size(); ++i) {
        const Face f(i);
        if (a.is_deleted(f) != b.is_deleted(f) || a.halfedge(f) != b.halfedge(f))
            return "face " + std::to_string(i) + " differs";
    }
    return "";
}

SurfaceMesh shuffled(SurfaceMesh mesh, std::uint64_t seed) {
    permute(mesh, random_mesh_order(mesh, seed));
    return mesh;
}

}  // namespace dynmesh::test
