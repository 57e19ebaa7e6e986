#include "star_intersection.hpp"

#include <algorithm>
#include <array>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

namespace dynmesh::detail {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Point_3 cg(const Point3& p) { return {p.x, p.y, p.z}; }

bool faces_meet(const SurfaceMesh& m, Face f, Face g) {
    const auto a = m.face_vertices(f), b = m.face_vertices(g);
    int shared = 0, ia = -1, ib = -1;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (a[i] == b[j]) {
                ++shared;
                ia = i;
                ib = j;
            }
    if (shared >= 2) return false;  // neighbours across an edge (a fold is not this test's)
    const K::Triangle_3 ta(cg(m.position(a[0])), cg(m.position(a[1])), cg(m.position(a[2])));
    const K::Triangle_3 tb(cg(m.position(b[0])), cg(m.position(b[1])), cg(m.position(b[2])));
    if (shared == 0) return CGAL::do_intersect(ta, tb);
    const K::Segment_3 ea(cg(m.position(a[(ia + 1) % 3])), cg(m.position(a[(ia + 2) % 3])));
    const K::Segment_3 eb(cg(m.position(b[(ib + 1) % 3])), cg(m.position(b[(ib + 2) % 3])));
    return CGAL::do_intersect(ea, tb) || CGAL::do_intersect(eb, ta);
}

}  // namespace

bool star_intersects(const SurfaceMesh& m, Vertex v, const PointGrid& grid, double radius,
                     const std::function<Vertex(std::uint32_t)>& vertex_of) {
    std::vector<Face> star;
    Bbox3 box;  // of the star: a face that meets it overlaps this box (closed)
    box.extend(m.position(v));
    for (Halfedge h : m.outgoing_halfedges(v)) {
        if (const Face f = m.face(h); f.is_valid()) star.push_back(f);
        box.extend(m.position(m.to_vertex(h)));
    }
    // Faces met before (each face is seen from up to three of its vertices).
    std::vector<Face> tested;
    bool hit = false;
    for_each_face_meeting(m, grid, m.position(v), radius, box, vertex_of, [&](Face g) {
        if (std::find(star.begin(), star.end(), g) != star.end()) return false;
        if (std::find(tested.begin(), tested.end(), g) != tested.end()) return false;
        tested.push_back(g);
        for (Face f : star)
            if (faces_meet(m, f, g)) return hit = true;
        return false;
    });
    return hit;
}

}  // namespace dynmesh::detail
