#pragma once
/// \file Inputs and the CGAL baseline shared by the quadtree benchmarks.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "dynmesh/geometry/random.hpp"
#include "dynmesh/quadtree/live_mesh.hpp"
#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh::bench {

/// n points in the middle third [0.34, 0.66]^D of the unit box; clustered = 20 Gaussian blobs
/// of sigma 0.01 centred in [0.4, 0.6]^D.
template <int D>
std::vector<PointD<D>> make_points(std::size_t n, bool clustered, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<PointD<D>> centres(20);
    for (auto& c : centres)
        for (int k = 0; k < D; ++k) c[k] = rng.uniform(0.4, 0.6);
    std::vector<PointD<D>> pts(n);
    for (auto& p : pts) {
        const auto& c = centres[rng.below(centres.size())];
        for (int k = 0; k < D; ++k)
            p[k] = clustered ? std::clamp(c[k] + 0.01 * rng.normal(), 0.34, 0.66)
                             : rng.uniform(0.34, 0.66);
    }
    return pts;
}

/// The spread family at n = 10^4 (2D): 5000 points uniform in the middle third and 5000 in a
/// square cluster of side 10^-k at (0.5, 0.5), so the spread grows like 10^k; `queries` are
/// 4096 more points of the cluster (the deepest part of the tree).
struct SpreadSet {
    std::vector<Vec2> points, queries;
};
inline SpreadSet spread_set(int k) {
    Rng rng(7);
    const double side = std::pow(10.0, -static_cast<double>(k));
    SpreadSet s;
    for (int i = 0; i < 5000; ++i) s.points.push_back({rng.uniform(0.34, 0.66), rng.uniform(0.34, 0.66)});
    for (int i = 0; i < 5000; ++i) s.points.push_back({0.5 + side * rng.uniform(), 0.5 + side * rng.uniform()});
    for (int i = 0; i < 4096; ++i) s.queries.push_back({0.5 + side * rng.uniform(), 0.5 + side * rng.uniform()});
    return s;
}

/// What a caller pays to consume one update's change, as a GPU buffer or a solver mirror
/// would: every removed simplex and vertex id, and every added simplex with the coordinates of
/// its vertices read from the live mesh. Returns a checksum so the reads are not optimised out.
template <int D>
double read_delta(const LiveMesh<D>& mesh, const MeshDelta<D>& delta) {
    double sum = 0;
    for (std::uint32_t s : delta.removed_simplices) sum += s;
    for (std::uint32_t v : delta.removed_vertices) sum += v;
    for (const auto& a : delta.added_vertices) sum += a.point[0];
    for (const auto& a : delta.added_simplices)
        for (std::uint32_t v : a.vertices)
            for (int d = 0; d < D; ++d) sum += mesh.point(v)[static_cast<std::size_t>(d)];
    return sum;
}

using CgalKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMeshCdt = CGAL::Constrained_Delaunay_triangulation_2<
    CgalKernel, CGAL::Triangulation_data_structure_2<CGAL::Triangulation_vertex_base_2<CgalKernel>,
                                                     CGAL::Delaunay_mesh_face_base_2<CgalKernel>>>;

/// The baseline: CGAL's 2D Delaunay mesher (refine_Delaunay_mesh_2 with
/// Delaunay_mesh_size_criteria_2(0.125), i.e. B = √2, about 20.7°, no size bound) on the box
/// [origin, origin + width]^2 with its sides as constraints and the points inserted.
template <class Points>
CgalMeshCdt cgal_refine_box(const Vec2& origin, double width, const Points& points) {
    CgalMeshCdt cdt;
    using P = CgalKernel::Point_2;
    const auto a = cdt.insert(P(origin.x, origin.y)), b = cdt.insert(P(origin.x + width, origin.y)),
               c = cdt.insert(P(origin.x + width, origin.y + width)),
               d = cdt.insert(P(origin.x, origin.y + width));
    cdt.insert_constraint(a, b);
    cdt.insert_constraint(b, c);
    cdt.insert_constraint(c, d);
    cdt.insert_constraint(d, a);
    for (const Vec2& p : points) cdt.insert(P(p.x, p.y));
    CGAL::refine_Delaunay_mesh_2(cdt, CGAL::Delaunay_mesh_size_criteria_2<CgalMeshCdt>(0.125));
    return cdt;
}

}  // namespace dynmesh::bench
