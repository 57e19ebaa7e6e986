#include "dynmesh/metrics/self_intersection.hpp"

#include <climits>
#include <cstdint>
#include <optional>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <boost/function_output_iterator.hpp>

#include "dynmesh/error.hpp"

namespace dynmesh {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<K::Point_3>;
using CgalFace = CgalMesh::Face_index;
namespace PMP = CGAL::Polygon_mesh_processing;

/// A copy of the mesh's live faces as a CGAL::Surface_mesh; CGAL face i is faces[i].
struct CgalCopy {
    CgalMesh mesh;
    std::vector<Face> faces;
};

CgalCopy to_cgal(const SurfaceMesh& mesh) {
    CgalCopy out;
    out.mesh.reserve(static_cast<CgalMesh::size_type>(mesh.n_vertices()),
                     static_cast<CgalMesh::size_type>(mesh.n_edges()),
                     static_cast<CgalMesh::size_type>(mesh.n_faces()));
    std::vector<CgalMesh::Vertex_index> index(mesh.vertices_size());
    for (const Vertex v : mesh.vertices()) {
        const Point3& p = mesh.position(v);
        index[v.idx()] = out.mesh.add_vertex(K::Point_3(p.x, p.y, p.z));
    }
    out.faces.reserve(mesh.n_faces());
    for (const Face f : mesh.faces()) {
        const auto vs = mesh.face_vertices(f);
        const CgalFace cf =
            out.mesh.add_face(index[vs[0].idx()], index[vs[1].idx()], index[vs[2].idx()]);
        // Cannot fail for a valid SurfaceMesh (oriented manifold, same face order).
        if (cf == CgalMesh::null_face() || static_cast<std::size_t>(cf.idx()) != out.faces.size())
            throw InternalError("self_intersections: CGAL rejected face f" +
                                std::to_string(f.idx()));
        out.faces.push_back(f);
    }
    return out;
}

/// A copy of `faces` alone (live faces of the mesh, each once) with the vertices they use, or
/// nothing when CGAL cannot hold them as one surface (a vertex whose faces among them form
/// fans it cannot link).
std::optional<CgalCopy> to_cgal(const SurfaceMesh& mesh, std::span<const Face> faces) {
    CgalCopy out;
    std::vector<CgalMesh::Vertex_index> index(mesh.vertices_size(), CgalMesh::null_vertex());
    auto vertex = [&](Vertex v) {
        CgalMesh::Vertex_index& i = index[v.idx()];
        if (i == CgalMesh::null_vertex()) {
            const Point3& p = mesh.position(v);
            i = out.mesh.add_vertex(K::Point_3(p.x, p.y, p.z));
        }
        return i;
    };
    out.faces.reserve(faces.size());
    for (const Face f : faces) {
        DYNMESH_CHECK(mesh.is_valid(f) && !mesh.is_deleted(f),
                      "has_self_intersections: face f" + std::to_string(f.idx()) + " is not a live face");
        const auto vs = mesh.face_vertices(f);
        const CgalFace cf = out.mesh.add_face(vertex(vs[0]), vertex(vs[1]), vertex(vs[2]));
        if (cf == CgalMesh::null_face()) return std::nullopt;
        out.faces.push_back(f);
    }
    return out;
}

}  // namespace

std::size_t count_self_intersections(const SurfaceMesh& mesh) {
    if (mesh.n_faces() < 1) return 0;
    const CgalCopy copy = to_cgal(mesh);
    std::size_t n = 0;
    auto counter =
        boost::make_function_output_iterator([&n](const std::pair<CgalFace, CgalFace>&) { ++n; });
    PMP::self_intersections<CGAL::Sequential_tag>(copy.mesh, counter);
    return n;
}

std::vector<std::pair<Face, Face>> self_intersections(const SurfaceMesh& mesh,
                                                      std::size_t max_pairs) {
    std::vector<std::pair<Face, Face>> out;
    if (mesh.n_faces() < 1 || max_pairs == 0) return out;
    const CgalCopy copy = to_cgal(mesh);
    auto collect =
        boost::make_function_output_iterator([&](const std::pair<CgalFace, CgalFace>& p) {
            out.emplace_back(copy.faces[p.first.idx()], copy.faces[p.second.idx()]);
        });
    if (max_pairs < static_cast<std::size_t>(UINT_MAX)) {
        PMP::self_intersections<CGAL::Sequential_tag>(
            copy.mesh, collect,
            CGAL::parameters::maximum_number(static_cast<unsigned int>(max_pairs)));
    } else {
        PMP::self_intersections<CGAL::Sequential_tag>(copy.mesh, collect);
    }
    if (out.size() > max_pairs) out.resize(max_pairs);
    return out;
}

bool has_self_intersections(const SurfaceMesh& mesh) {
    if (mesh.n_faces() < 1) return false;
    const CgalCopy copy = to_cgal(mesh);
    return PMP::does_self_intersect<CGAL::Sequential_tag>(copy.mesh);
}

bool has_self_intersections(const SurfaceMesh& mesh, std::span<const Face> faces) {
    if (faces.empty()) return false;
    if (const std::optional<CgalCopy> part = to_cgal(mesh, faces))
        return PMP::does_self_intersect<CGAL::Sequential_tag>(part->mesh);
    const CgalCopy copy = to_cgal(mesh);
    std::vector<std::uint32_t> index(mesh.faces_size(), UINT32_MAX);  // our face -> CGAL face
    for (std::size_t i = 0; i < copy.faces.size(); ++i) index[copy.faces[i].idx()] = static_cast<std::uint32_t>(i);
    std::vector<CgalFace> range;
    range.reserve(faces.size());
    for (const Face f : faces) {
        DYNMESH_CHECK(f.idx() < index.size() && index[f.idx()] != UINT32_MAX,
                      "has_self_intersections: face f" + std::to_string(f.idx()) + " is not a live face");
        range.emplace_back(index[f.idx()]);
    }
    return PMP::does_self_intersect<CGAL::Sequential_tag>(range, copy.mesh);
}

}  // namespace dynmesh
