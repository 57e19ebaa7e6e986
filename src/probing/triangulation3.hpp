#pragma once
/// \file The 3D Delaunay triangulation behind a probing run (private): CGAL's
/// Delaunay_triangulation_3 with a record per directed Voronoi edge in each cell, behind the
/// small interface the dimension-independent refiner (refiner.hpp) uses. A cell is a Voronoi
/// vertex; facet (c, i), opposite c's vertex i, is dual to the Voronoi edge from c toward
/// c->neighbor(i).

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Cartesian_converter.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "../geometry/circumcenter_accuracy.hpp"
#include "refiner_types.hpp"

namespace dynmesh::detail {

class Triangulation3 {
public:
    static constexpr int kDim = 3;
    static constexpr int kFacets = 4;  ///< facets per cell = edges per Voronoi vertex
    using Info = SimplexInfo<kFacets>;

private:
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K>;  // sample index
    using Cb = CGAL::Triangulation_cell_base_with_info_3<Info, K,
                                                         CGAL::Delaunay_triangulation_cell_base_3<K>>;
    using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
    using DT = CGAL::Delaunay_triangulation_3<K, Tds>;
    using KPoint = K::Point_3;
    using EK = CGAL::Exact_predicates_exact_constructions_kernel;
    static KPoint to_k(const Point3& p) { return {p.x, p.y, p.z}; }
    static Point3 to_p(const KPoint& p) { return {p.x(), p.y(), p.z()}; }

public:
    using Cell = DT::Cell_handle;

    [[nodiscard]] int dimension() const { return dt_.dimension(); }
    void insert(const Point3& p, std::uint32_t sample) { dt_.insert(to_k(p))->info() = sample; }
    [[nodiscard]] std::vector<Cell> all_cells() const {
        std::vector<Cell> out;
        for (Cell c : dt_.all_cell_handles()) out.push_back(c);
        return out;
    }
    [[nodiscard]] bool is_infinite(Cell c) const { return dt_.is_infinite(c); }
    [[nodiscard]] static Cell neighbor(Cell c, int i) { return c->neighbor(i); }
    [[nodiscard]] static int index(Cell c, Cell n) { return c->index(n); }
    [[nodiscard]] static Info& info(Cell c) { return c->info(); }
    /// The circumcentre of a finite cell, accurate to about 1e-12 of its radius: computed in
    /// double, and again exactly (EPECK, then rounded) when the double result's distances to
    /// the four vertices differ by more than that, or when the cell is nearly flat (radius over
    /// 1e3 times its longest edge), so that a node lies on the dual lines of its four facets,
    /// on the right side of them, and a certified segment is the edge it stands for.
    [[nodiscard]] static Point3 circumcenter(Cell c) {
        const KPoint& a = c->vertex(0)->point();
        const KPoint& b = c->vertex(1)->point();
        const KPoint& d = c->vertex(2)->point();
        const KPoint& e = c->vertex(3)->point();
        const KPoint x = CGAL::circumcenter(a, b, d, e);
        if (circumcenter_is_accurate(x, std::array{&a, &b, &d, &e})) return to_p(x);
        const CGAL::Cartesian_converter<K, EK> to_exact;
        const EK::Point_3 ex = CGAL::circumcenter(to_exact(a), to_exact(b), to_exact(d), to_exact(e));
        return {CGAL::to_double(ex.x()), CGAL::to_double(ex.y()), CGAL::to_double(ex.z())};
    }
    /// The vertices of facet (c, i) (finite facets only), in an order whose normal
    /// cross(b − a, c − a) points away from c's vertex i when c is positively oriented.
    [[nodiscard]] static std::array<Point3, 3> facet_points(Cell c, int i) {
        return {to_p(c->vertex((i + 1) & 3)->point()), to_p(c->vertex((i + 2) & 3)->point()),
                to_p(c->vertex((i + 3) & 3)->point())};
    }
    [[nodiscard]] static std::array<std::uint32_t, 3> facet_samples(Cell c, int i) {
        return {c->vertex((i + 1) & 3)->info(), c->vertex((i + 2) & 3)->info(),
                c->vertex((i + 3) & 3)->info()};
    }
    /// c's vertex opposite facet i (finite when the facet is finite and c is not infinite).
    [[nodiscard]] static Point3 apex(Cell c, int i) { return to_p(c->vertex(i)->point()); }
    [[nodiscard]] bool apex_is_infinite(Cell c, int i) const {
        return dt_.is_infinite(c->vertex(i));
    }
    /// The unit direction of the Voronoi edge dual to facet (c, i), from c's end toward the
    /// neighbour's: the facet's normal turned away from c's vertex opposite the facet (toward
    /// the neighbour's when c is infinite). The side is decided by the exact orientation
    /// predicate, so it holds for nearly flat cells whose circumcentres are far and rounded.
    [[nodiscard]] Vec3 edge_direction(Cell c, int i) const {
        const Vec3 n = facet_normal(facet_points(c, i));
        const KPoint& a = c->vertex((i + 1) & 3)->point();
        const KPoint& b = c->vertex((i + 2) & 3)->point();
        const KPoint& d = c->vertex((i + 3) & 3)->point();
        if (!dt_.is_infinite(c->vertex(i)))
            return CGAL::orientation(a, b, d, c->vertex(i)->point()) == CGAL::POSITIVE ? -n : n;
        const Cell w = c->neighbor(i);
        return CGAL::orientation(a, b, d, w->vertex(w->index(c))->point()) == CGAL::POSITIVE ? n : -n;
    }
    /// A unit normal of the facet's plane, cross(f1 − f0, f2 − f0) normalised; computed exactly
    /// when the facet is so thin (sine of its angle at f0 below 1e-4) that the double cross
    /// product loses digits.
    [[nodiscard]] static Vec3 facet_normal(const std::array<Point3, 3>& f) {
        const Vec3 u = f[1] - f[0], v = f[2] - f[0], n = cross(u, v);
        if (norm(n) > 1e-4 * norm(u) * norm(v)) return normalized(n);
        const EK::Vector_3 eu = EK::Point_3(f[1].x, f[1].y, f[1].z) - EK::Point_3(f[0].x, f[0].y, f[0].z);
        const EK::Vector_3 ev = EK::Point_3(f[2].x, f[2].y, f[2].z) - EK::Point_3(f[0].x, f[0].y, f[0].z);
        const EK::Vector_3 en = CGAL::cross_product(eu, ev);
        return normalized(Vec3{CGAL::to_double(en.x()), CGAL::to_double(en.y()), CGAL::to_double(en.z())});
    }
    /// The circumcentre of the facet, exact when the double one is off by more than about
    /// 1e-12 of the radius (thin facets).
    [[nodiscard]] static Point3 facet_circumcenter(const std::array<Point3, 3>& f) {
        const KPoint x = CGAL::circumcenter(to_k(f[0]), to_k(f[1]), to_k(f[2]));
        const double ra = CGAL::squared_distance(x, to_k(f[0])), rb = CGAL::squared_distance(x, to_k(f[1])),
                     rc = CGAL::squared_distance(x, to_k(f[2]));
        const double lo = std::min({ra, rb, rc}), hi = std::max({ra, rb, rc});
        if (std::isfinite(hi) && hi - lo <= 2e-12 * hi) return to_p(x);
        const EK::Point_3 ex = CGAL::circumcenter(EK::Point_3(f[0].x, f[0].y, f[0].z), EK::Point_3(f[1].x, f[1].y, f[1].z),
                                                  EK::Point_3(f[2].x, f[2].y, f[2].z));
        return {CGAL::to_double(ex.x()), CGAL::to_double(ex.y()), CGAL::to_double(ex.z())};
    }
    /// Distance from x to the nearest sample (hint: a cell near x).
    [[nodiscard]] double nearest_sample_distance(const Point3& x, Cell hint) const {
        return distance(to_p(dt_.nearest_vertex(to_k(x), hint)->point()), x);
    }

    /// Inserts x (sample index `sample`) by the cavity of the cells in conflict with it,
    /// searched from `c` or `c->neighbor(i)` (whichever has x strictly inside its circumsphere;
    /// else located from c). `retire(cell)` is called for every cavity cell before it is
    /// destroyed; the new cells (infinite ones included) are appended to `fresh`; the new
    /// vertex is opposite facet fresh_index(n) of each new cell n.
    template <class Retire>
    void insert_in_cavity(const Point3& x, std::uint32_t sample, Cell c, int i, Retire&& retire,
                          std::vector<Cell>& fresh) {
        const KPoint kx = to_k(x);
        Cell seed = c;
        if (dt_.side_of_sphere(c, kx, true) != CGAL::ON_BOUNDED_SIDE) {
            seed = i >= 0 ? c->neighbor(i) : c;
            if (dt_.side_of_sphere(seed, kx, true) != CGAL::ON_BOUNDED_SIDE)
                seed = dt_.locate(kx, c);
        }
        cavity_.clear();
        boundary_.clear();
        dt_.find_conflicts(kx, seed, std::back_inserter(boundary_), std::back_inserter(cavity_));
        for (Cell k : cavity_) retire(k);
        const auto v = dt_.insert_in_hole(kx, cavity_.begin(), cavity_.end(),
                                          boundary_.front().first, boundary_.front().second);
        v->info() = sample;
        new_vertex_ = v;
        fresh.clear();
        dt_.incident_cells(v, std::back_inserter(fresh));
    }
    /// In a cell made by the last insert_in_cavity: the facet opposite the new vertex.
    [[nodiscard]] int fresh_index(Cell n) const { return n->index(new_vertex_); }
    /// Calls f(c, i) once for every finite facet.
    template <class F>
    void for_each_finite_facet(F&& f) const {
        for (auto it = dt_.finite_facets_begin(); it != dt_.finite_facets_end(); ++it)
            f(it->first, it->second);
    }
    [[nodiscard]] std::size_t number_of_samples() const { return dt_.number_of_vertices(); }

private:
    DT dt_;
    std::vector<Cell> cavity_;
    std::vector<DT::Facet> boundary_;
    DT::Vertex_handle new_vertex_;
};

}  // namespace dynmesh::detail
