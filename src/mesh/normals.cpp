#include "dynmesh/mesh/normals.hpp"

#include "dynmesh/geometry/triangle.hpp"

namespace dynmesh {

std::vector<Vec3> vertex_normals(const SurfaceMesh& mesh) {
    std::vector<Vec3> n(mesh.vertices_size(), Vec3{});
    for (const Face f : mesh.faces()) {
        const auto v = mesh.face_vertices(f);
        const Point3 &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
        const Vec3 fn = triangle_normal(a, b, c);
        n[v[0].idx()] += fn * angle_at(c, a, b);
        n[v[1].idx()] += fn * angle_at(a, b, c);
        n[v[2].idx()] += fn * angle_at(b, c, a);
    }
    for (Vec3& x : n) x = normalized(x);
    return n;
}

}  // namespace dynmesh
