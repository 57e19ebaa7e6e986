#pragma once
/// \file The 2D Delaunay triangulation behind a probing run of a closed curve (private):
/// CGAL's Delaunay_triangulation_2 with the interface of Triangulation3 (triangulation3.hpp),
/// one dimension down. Points are Point3 with z = 0. A face is a Voronoi vertex; edge (f, i),
/// opposite f's vertex i, is dual to the Voronoi edge from f toward f->neighbor(i).

#include <CGAL/Cartesian_converter.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

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

class Triangulation2 {
public:
    static constexpr int kDim = 2;
    static constexpr int kFacets = 3;
    using Info = SimplexInfo<kFacets>;

private:
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
    using Fb = CGAL::Triangulation_face_base_with_info_2<Info, K>;
    using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
    using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
    using KPoint = K::Point_2;
    static KPoint to_k(const Point3& p) { return {p.x, p.y}; }
    static Point3 to_p(const KPoint& p) { return {p.x(), p.y(), 0}; }

public:
    using Cell = DT::Face_handle;

    [[nodiscard]] int dimension() const { return dt_.dimension(); }
    void insert(const Point3& p, std::uint32_t sample) { dt_.insert(to_k(p))->info() = sample; }
    [[nodiscard]] std::vector<Cell> all_cells() const {
        std::vector<Cell> out;
        for (auto it = dt_.all_faces_begin(); it != dt_.all_faces_end(); ++it) out.push_back(it);
        return out;
    }
    [[nodiscard]] bool is_infinite(Cell c) const { return dt_.is_infinite(c); }
    [[nodiscard]] static Cell neighbor(Cell c, int i) { return c->neighbor(i); }
    [[nodiscard]] static int index(Cell c, Cell n) { return c->index(n); }
    [[nodiscard]] static Info& info(Cell c) { return c->info(); }
    /// As Triangulation3::circumcenter: exact when the double result is off by more than
    /// about 1e-12 of the radius or the face is nearly flat.
    [[nodiscard]] static Point3 circumcenter(Cell c) {
        const KPoint& a = c->vertex(0)->point();
        const KPoint& b = c->vertex(1)->point();
        const KPoint& d = c->vertex(2)->point();
        const KPoint x = CGAL::circumcenter(a, b, d);
        if (circumcenter_is_accurate(x, std::array{&a, &b, &d})) return to_p(x);
        using EK = CGAL::Exact_predicates_exact_constructions_kernel;
        const CGAL::Cartesian_converter<K, EK> to_exact;
        const EK::Point_2 ex = CGAL::circumcenter(to_exact(a), to_exact(b), to_exact(d));
        return {CGAL::to_double(ex.x()), CGAL::to_double(ex.y()), 0};
    }
    [[nodiscard]] static std::array<Point3, 2> facet_points(Cell c, int i) {
        return {to_p(c->vertex(DT::ccw(i))->point()), to_p(c->vertex(DT::cw(i))->point())};
    }
    [[nodiscard]] static std::array<std::uint32_t, 2> facet_samples(Cell c, int i) {
        return {c->vertex(DT::ccw(i))->info(), c->vertex(DT::cw(i))->info()};
    }
    [[nodiscard]] static Point3 apex(Cell c, int i) { return to_p(c->vertex(i)->point()); }
    [[nodiscard]] bool apex_is_infinite(Cell c, int i) const {
        return dt_.is_infinite(c->vertex(i));
    }
    /// As Triangulation3::edge_direction: the edge's normal in the plane, turned away from c's
    /// vertex opposite it (toward the neighbour's when c is infinite), by the exact predicate.
    [[nodiscard]] Vec3 edge_direction(Cell c, int i) const {
        const Vec3 n = facet_normal(facet_points(c, i));
        const KPoint& a = c->vertex(DT::ccw(i))->point();
        const KPoint& b = c->vertex(DT::cw(i))->point();
        if (!dt_.is_infinite(c->vertex(i)))
            return CGAL::orientation(a, b, c->vertex(i)->point()) == CGAL::LEFT_TURN ? -n : n;
        const Cell w = c->neighbor(i);
        return CGAL::orientation(a, b, w->vertex(w->index(c))->point()) == CGAL::LEFT_TURN ? n : -n;
    }
    /// A unit normal of the edge within the plane z = 0.
    [[nodiscard]] static Vec3 facet_normal(const std::array<Point3, 2>& f) {
        const Vec3 e = f[1] - f[0];
        return normalized(Vec3{-e.y, e.x, 0});
    }
    [[nodiscard]] static Point3 facet_circumcenter(const std::array<Point3, 2>& f) {
        return 0.5 * (f[0] + f[1]);
    }
    [[nodiscard]] double nearest_sample_distance(const Point3& x, Cell hint) const {
        return distance(to_p(dt_.nearest_vertex(to_k(x), hint)->point()), x);
    }

    /// As Triangulation3::insert_in_cavity: the faces in conflict with x are found from c
    /// (CGAL's get_conflicts_and_boundary locates x first), retired, and replaced by the star
    /// of x over the boundary of their union.
    template <class Retire>
    void insert_in_cavity(const Point3& x, std::uint32_t sample, Cell c, int /*i*/,
                          Retire&& retire, std::vector<Cell>& fresh) {
        const KPoint kx = to_k(x);
        cavity_.clear();
        boundary_.clear();
        dt_.get_conflicts_and_boundary(kx, std::back_inserter(cavity_),
                                       std::back_inserter(boundary_), c);
        if (cavity_.empty() || boundary_.empty())
            throw InternalError("probe: a 2D insertion found no face in conflict");
        for (Cell k : cavity_) retire(k);
        const auto v = dt_.star_hole(kx, boundary_.begin(), boundary_.end(), cavity_.begin(),
                                     cavity_.end());
        v->info() = sample;
        new_vertex_ = v;
        fresh.clear();
        auto fc = dt_.incident_faces(v), done = fc;
        do {
            fresh.push_back(fc);
        } while (++fc != done);
    }
    [[nodiscard]] int fresh_index(Cell n) const { return n->index(new_vertex_); }
    template <class F>
    void for_each_finite_facet(F&& f) const {
        for (auto it = dt_.finite_edges_begin(); it != dt_.finite_edges_end(); ++it)
            f(it->first, it->second);
    }
    [[nodiscard]] std::size_t number_of_samples() const { return dt_.number_of_vertices(); }

private:
    DT dt_;
    std::vector<Cell> cavity_;
    std::vector<DT::Edge> boundary_;
    DT::Vertex_handle new_vertex_;
};

}  // namespace dynmesh::detail
