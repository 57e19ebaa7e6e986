#include "dynmesh/flips/worsen.hpp"

#include <algorithm>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/triangle.hpp"

namespace dynmesh {

namespace {
double edge_dihedral(const SurfaceMesh& m, Halfedge h) {
    const Halfedge o = SurfaceMesh::twin(h);
    if (m.is_boundary(h) || m.is_boundary(o)) return kPi;
    return dihedral_angle(m.position(m.from_vertex(h)), m.position(m.to_vertex(h)),
                          m.position(m.opposite_vertex(h)), m.position(m.opposite_vertex(o)));
}
}  // namespace

WorsenReport worsen(SurfaceMesh& mesh, const WorsenOptions& opt) {
    DYNMESH_CHECK(!mesh.has_garbage(), "worsen: the mesh has deleted elements; call garbage_collection() first");
    DYNMESH_CHECK(opt.probability >= 0 && opt.probability <= 1, "worsen: probability must lie in [0, 1]");
    WorsenReport rep;
    Rng rng(opt.seed);
    const double floor = deg_to_rad(opt.min_dihedral_deg);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (std::size_t round = 0; round < opt.rounds; ++round) {
        pairs.clear();
        for (Edge e : mesh.edges()) {
            const auto a = mesh.vertex(e, 0).idx(), b = mesh.vertex(e, 1).idx();
            pairs.emplace_back(std::min(a, b), std::max(a, b));
        }
        std::sort(pairs.begin(), pairs.end());
        for (const auto& [a, b] : pairs) {
            if (!rng.coin(opt.probability)) continue;
            const Edge e = mesh.find_edge(Vertex(a), Vertex(b));
            if (!e.is_valid() || !mesh.is_flip_ok(e) || (opt.only && !opt.only(mesh, e))) continue;
            const EdgeQuad k = edge_quad(mesh, e);
            if (is_degenerate_triangle(mesh.position(k.p), mesh.position(k.s), mesh.position(k.r)) ||
                is_degenerate_triangle(mesh.position(k.q), mesh.position(k.r), mesh.position(k.s)))
                continue;
            ++rep.attempts;
            const Halfedge h0 = SurfaceMesh::halfedge(e, 0), h1 = SurfaceMesh::halfedge(e, 1);
            mesh.flip(e);
            bool ok = edge_dihedral(mesh, h0) >= floor;
            for (Halfedge h : {mesh.next(h0), mesh.prev(h0), mesh.next(h1), mesh.prev(h1)})
                ok = ok && edge_dihedral(mesh, h) >= floor;
            if (ok) {
                ++rep.flips;
            } else {
                mesh.flip(e);  // flipping the new diagonal restores pq
                ++rep.rejected;
            }
        }
    }
    return rep;
}

}  // namespace dynmesh
