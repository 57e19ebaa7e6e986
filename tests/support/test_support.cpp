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

SurfaceMesh icosphere(int level) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    TriangleSoup s;
    s.points = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : s.points) p = normalized(p);
    s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                   {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                   {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                   {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto k = std::minmax(a, b);
            auto it = mid.find(k);
            if (it != mid.end()) return it->second;
            s.points.push_back(normalized((s.points[a] + s.points[b]) * 0.5));
            const auto i = static_cast<std::uint32_t>(s.points.size() - 1);
            mid.emplace(k, i);
            return i;
        };
        std::vector<std::array<std::uint32_t, 3>> next;
        for (const auto& tr : s.triangles) {
            const auto a = midpoint(tr[0], tr[1]), b = midpoint(tr[1], tr[2]),
                       c = midpoint(tr[2], tr[0]);
            next.push_back({tr[0], a, c});
            next.push_back({tr[1], b, a});
            next.push_back({tr[2], c, b});
            next.push_back({a, b, c});
        }
        s.triangles.swap(next);
    }
    return SurfaceMesh::from_soup(s);
}

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
