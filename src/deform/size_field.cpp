#include "dynmesh/deform/size_field.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <utility>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/normals.hpp"

namespace dynmesh {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

K::Point_3 to_cgal(const Point3& p) { return {p.x, p.y, p.z}; }

}  // namespace

std::vector<double> mesh_feature_size(const SurfaceMesh& m) {
    if (m.n_faces() == 0) throw InvalidInput("size field: the mesh has no face");
    for (Edge e : m.edges())
        if (m.is_boundary(e)) throw InvalidInput("size field: the mesh is not closed");
    const double inf = std::numeric_limits<double>::infinity();
    const std::vector<Vec3> n = vertex_normals(m);
    Triangles tris;
    std::vector<std::uint32_t> face_of;  // triangle index -> face index
    tris.reserve(m.n_faces());
    for (Face f : m.faces()) {
        const auto v = m.face_vertices(f);
        tris.emplace_back(to_cgal(m.position(v[0])), to_cgal(m.position(v[1])), to_cgal(m.position(v[2])));
        face_of.push_back(static_cast<std::uint32_t>(f.idx()));
    }
    Tree tree(tris.cbegin(), tris.cend());
    tree.build();
    std::vector<double> lfs(m.vertices_size(), inf);
    std::vector<char> own(m.faces_size(), 0);
    for (Vertex v : m.vertices()) {
        const Point3 p = m.position(v);
        double best = inf;
        // Curvature radius from the turn of the normal towards each neighbour.
        for (Halfedge h : m.outgoing_halfedges(v)) {
            const Vertex u = m.to_vertex(h);
            const double a = angle_between(n[v.idx()], n[u.idx()]);
            const double s = std::sin(a / 2);
            if (s > 0) best = std::min(best, distance(p, m.position(u)) / (2 * s));
            if (const Face f = m.face(h); f.is_valid()) own[f.idx()] = 1;
        }
        // Thickness behind v and gap in front of it.
        const auto skip = [&](Triangles::const_iterator it) {
            return own[face_of[static_cast<std::size_t>(it - tris.cbegin())]] != 0;
        };
        for (const double sign : {-1.0, 1.0}) {
            const Vec3 d = n[v.idx()] * sign;
            if (!(norm(d) > 0)) continue;
            const K::Ray_3 ray(to_cgal(p), K::Vector_3(d.x, d.y, d.z));
            const auto hit = tree.first_intersection(ray, skip);
            if (!hit) continue;
            if (const K::Point_3* q = boost::get<K::Point_3>(&hit->first)) {
                const double dist = distance(p, Point3{q->x(), q->y(), q->z()});
                best = std::min(best, dist / 2);
            }
        }
        for (Halfedge h : m.outgoing_halfedges(v))
            if (const Face f = m.face(h); f.is_valid()) own[f.idx()] = 0;
        lfs[v.idx()] = best;
    }
    return lfs;
}

std::vector<double> graded_size(const SurfaceMesh& m, std::span<const double> lfs, double rho, double grading,
                                double cap) {
    DYNMESH_CHECK(lfs.size() == m.vertices_size(), "graded_size: one lfs value per vertex");
    DYNMESH_CHECK(rho > 0 && grading >= 0, "graded_size: rho > 0 and grading >= 0");
    std::vector<double> r(m.vertices_size(), std::numeric_limits<double>::infinity());
    using Item = std::pair<double, std::uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    for (Vertex v : m.vertices()) {
        r[v.idx()] = std::min(cap, rho * lfs[v.idx()]);
        if (std::isfinite(r[v.idx()])) queue.emplace(r[v.idx()], static_cast<std::uint32_t>(v.idx()));
    }
    while (!queue.empty()) {
        const auto [d, i] = queue.top();
        queue.pop();
        if (d > r[i]) continue;
        const Vertex v(i);
        for (Halfedge h : m.outgoing_halfedges(v)) {
            const Vertex u = m.to_vertex(h);
            const double c = d + grading * distance(m.position(v), m.position(u));
            if (c < r[u.idx()]) {
                r[u.idx()] = c;
                queue.emplace(c, static_cast<std::uint32_t>(u.idx()));
            }
        }
    }
    return r;
}

}  // namespace dynmesh
