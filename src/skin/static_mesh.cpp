#include "dynmesh/skin/static_mesh.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include <CGAL/Cartesian_converter.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "../geometry/circumcenter_accuracy.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/geometry/spatial_sort.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/mesh/soup.hpp"

namespace dynmesh {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using EK = CGAL::Exact_predicates_exact_constructions_kernel;

struct VertexInfo {
    double rho = 0;                 ///< ϱ at the sample
    std::size_t hint = 0;           ///< a mixed cell near it
    std::uint32_t mesh_index = ~0u; ///< its index in the output (while extracting)
};
inline constexpr std::uint8_t kUntested = 255;

struct CellInfo {
    Point3 cc{};       ///< circumcentre (a Voronoi vertex)
    double f = 0;      ///< Φ(cc) − t
    double clear = 0;  ///< a radius around cc free of the skin (Sample::clear)
    bool ready = false;
    std::uint32_t simplex = 0;  ///< the mixed cell that holds cc
    /// Per facet i, as last judged from this cell (the side it is looked at from): the
    /// crossings of its dual edge, capped at 254; kUntested before the first judgement.
    std::array<std::uint8_t, 4> hits{kUntested, kUntested, kUntested, kUntested};
    std::uint64_t id = 0;  ///< a number no other cell of this run has (0 until first asked)
};
using Vb = CGAL::Triangulation_vertex_base_with_info_3<VertexInfo, K>;
using Cb = CGAL::Triangulation_cell_base_with_info_3<CellInfo, K, CGAL::Delaunay_triangulation_cell_base_3<K>>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using DT = CGAL::Delaunay_triangulation_3<K, Tds>;
using Cell = DT::Cell_handle;
using Vertex = DT::Vertex_handle;

Point3 to_p(const K::Point_3& p) { return {p.x(), p.y(), p.z()}; }
K::Point_3 to_k(const Point3& p) { return {p.x, p.y, p.z}; }

/// Why a restricted facet is refined.
enum class Defect : std::uint8_t { None, Size, Shape, Topology };

struct Crossing {
    int hits = 0;    ///< sign changes of Φ − t seen along the dual edge
    Point3 p{};      ///< the first crossing from the finite end: the surface Delaunay ball's centre
    std::uint64_t from = 0, to = 0;  ///< the ids of the cells the dual edge joins (looked from `from`)
};

struct BadFacet {
    double priority = 0;
    Vertex a, b, c;
    /// The facet's corners in lexicographic order: ties in priority (symmetric inputs) are
    /// broken by where the facet is, not by the order in which facets were queued (which
    /// follows the cells' addresses).
    std::array<std::array<double, 3>, 3> key{};
    /// The judgement when queued: still valid at the pop when the facet joins the same cells.
    Crossing x;
    Defect defect = Defect::None;
    bool operator<(const BadFacet& o) const { return priority != o.priority ? priority < o.priority : key < o.key; }
};

class Mesher {
public:
    Mesher(const SkinFunction& phi, const SkinMeshOptions& options) : phi_(phi), opt_(options), t_(options.time) {
        DYNMESH_CHECK(std::isfinite(t_), "mesh_skin: the time must be finite");
        DYNMESH_CHECK(options.quality.C > 0 && options.quality.Q0 > 1, "mesh_skin: C must be positive and Q0 above 1");
        DYNMESH_CHECK(options.radius_edge_bound >= 0.6, "mesh_skin: the radius-edge bound must be at least 0.6");
        DYNMESH_CHECK(options.rho_floor_factor > 0 && options.rho_floor_factor < 1,
                      "mesh_skin: the floor factor must be in (0, 1)");
        const double s = phi.shrink();
        bool any = false;
        double radius_sum = 0;
        std::size_t counted = 0;
        for (std::size_t i = 0; i < phi.input_balls(); ++i) {
            const WeightedPoint& b = phi.balls()[i];
            if (b.weight > 0) {
                radius_sum += std::sqrt(s * b.weight);
                ++counted;
            }
            if (b.weight + t_ <= 0) continue;
            const double r = std::sqrt(b.weight + t_);
            box_.extend(b.center - Vec3{r, r, r});
            box_.extend(b.center + Vec3{r, r, r});
            any = true;
        }
        DYNMESH_CHECK(any, "mesh_skin: the skin is empty at this time (no ball has a positive weight + t)");
        rho_floor_ = options.rho_floor_factor * (counted ? radius_sum / double(counted) : box_.diagonal());
        scale2_ = sqnorm(box_.max - box_.min);
    }

    SkinMeshResult run() {
        const auto start = std::chrono::steady_clock::now();
        seed();
        for (Cell c : dt_.finite_cell_handles()) prepare(c);
        for (auto f = dt_.finite_facets_begin(); f != dt_.finite_facets_end(); ++f) test_facet(f->first, f->second);
        refine();
        SkinMeshResult result = extract();
        report_.delaunay_vertices = dt_.number_of_vertices();
        report_.locate_fallbacks = phi_.locate_fallbacks();
        report_.rho_floor = rho_floor_;
        report_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        result.report = report_;
        return result;
    }

private:
    double f_at(const Point3& x, std::size_t& hint) const {
        const std::size_t k = phi_.locate(x, hint);
        hint = k;
        return phi_.value_in(k, x) - t_;
    }

    /// Φ − t at x and a radius around x that the skin does not enter: along any path
    /// |∇Φ| ≤ c·g with g = ‖y − z_δ(y)‖ (c = 2/min(s, 1 − s)) and g 1-Lipschitz (§1.6), so
    /// |Φ(y) − Φ(x)| ≤ c(g·d + d²/2) within distance d, which stays below |Φ(x) − t| for
    /// d < −g + √(g² + 2|Φ(x) − t|/c).
    struct Sample {
        double f = 0;
        double clear = 0;
    };
    Sample sample_at(const Point3& x, std::size_t& hint) const {
        const std::size_t k = phi_.locate(x, hint);
        hint = k;
        const double g = norm(x - phi_.simplices()[k].z);
        const double f = phi_.value_in(k, x) - t_;
        const double c = 2 / std::min(phi_.shrink(), 1 - phi_.shrink());
        return {f, std::max(0.0, 0.999 * (std::sqrt(g * g + 2 * std::fabs(f) / c) - g))};
    }

    /// A root of Φ = t on the segment [a, b] inside the mixed cell of simplex k, from that
    /// cell's quadric restricted to the line (exact up to rounding), if it has one there.
    std::optional<Point3> root_in_cell(std::size_t k, const Point3& a, const Point3& b) const {
        const double f0 = phi_.value_in(k, a) - t_;
        const double f1 = phi_.value_in(k, b) - t_;
        const double fm = phi_.value_in(k, a + 0.5 * (b - a)) - t_;
        // f(τ) = f0 + β τ + α τ², τ in [0, 1].
        const double alpha = 2 * (f1 + f0 - 2 * fm), beta = f1 - f0 - alpha;
        double roots[2];
        int n = 0;
        if (std::fabs(alpha) <= 1e-14 * (std::fabs(beta) + std::fabs(f0))) {
            if (beta != 0) roots[n++] = -f0 / beta;
        } else {
            const double disc = beta * beta - 4 * alpha * f0;
            if (disc >= 0) {
                const double q = -0.5 * (beta + std::copysign(std::sqrt(disc), beta));
                if (q != 0) roots[n++] = f0 / q;
                roots[n++] = q / alpha;
            }
        }
        for (int i = 0; i < n; ++i) {
            if (!(roots[i] >= -1e-12 && roots[i] <= 1 + 1e-12)) continue;
            const Point3 x = a + std::clamp(roots[i], 0.0, 1.0) * (b - a);
            if (phi_.in_mixed_cell(k, x)) return x;
        }
        return std::nullopt;
    }

    /// The crossing of Φ = t between a (f(a) = fa) and b (f(b) = fb, opposite signs), by the
    /// Illinois variant of regula falsi (Φ is piecewise quadratic along a line).
    Point3 root_between(Point3 a, double fa, Point3 b, double fb, std::size_t& hint) const {
        int side = 0;
        const double tol = 1e-13 * scale2_;
        for (int it = 0; it < 200; ++it) {
            const double w = fa / (fa - fb);
            const Point3 m = a + w * (b - a);
            const double fm = f_at(m, hint);
            if (auto x = root_in_cell(hint, a, b)) return *x;
            if (std::fabs(fm) <= tol || sqnorm(b - a) <= 1e-30 * scale2_) return m;
            if ((fm < 0) == (fa < 0)) {
                a = m;
                fa = fm;
                if (side == -1) fb *= 0.5;
                side = -1;
            } else {
                b = m;
                fb = fm;
                if (side == 1) fa *= 0.5;
                side = 1;
            }
        }
        return a + (fa / (fa - fb)) * (b - a);
    }

    /// Inserts a sample; the null handle when it coincides with one already there.
    Vertex add_sample(const Point3& p, std::size_t hint, Cell near = Cell()) {
        const std::size_t before = dt_.number_of_vertices();
        Vertex v = dt_.insert(to_k(p), near);
        if (dt_.number_of_vertices() == before) {
            ++report_.refused;
            return Vertex();
        }
        const SkinEvaluation ev = phi_.evaluate(p, hint);
        v->info().rho = ev.rho;
        v->info().hint = ev.simplex;
        return v;
    }

    /// Rays from each local minimum of Φ below t (born atoms) and each local maximum above t
    /// (living voids) to the skin: every component of the skin gets points.
    void seed() {
        // Eight directions spread over the sphere by the golden-angle spiral, turned per seed
        // centre so that no two centres' seeds are translates (no cospherical and coplanar
        // quadruples of samples).
        const auto directions = [](std::size_t k) {
            std::vector<Vec3> dirs;
            const double turn = 0.61803398874989485 * double(k % 997);
            for (int i = 0; i < 8; ++i) {
                const double z = 1 - (2 * i + 1) / 8.0, r = std::sqrt(1 - z * z);
                const double a = 2.399963229728653 * i + turn;
                dirs.push_back({r * std::cos(a), r * std::sin(a), z});
            }
            return dirs;
        };
        const double s = phi_.shrink();
        std::vector<Point3> seeds;
        std::vector<std::size_t> seed_hints;  // a mixed cell at or near each seed
        for (std::size_t k = 0; k < phi_.simplices().size(); ++k) {
            const SkinSimplex& sx = phi_.simplices()[k];
            const bool birth = sx.dim == 0 && std::size_t(sx.vertices[0]) < phi_.input_balls() && sx.W < t_;
            const bool void_centre = sx.dim == 3 && sx.W > t_;
            if (!birth && !void_centre) continue;
            if (!phi_.in_mixed_cell(k, sx.z)) continue;  // not a critical point of Φ
            // The patch around z is a sphere of radius √(s(t − W)) or √((1 − s)(W − t)).
            const double r = birth ? std::sqrt(s * (t_ - sx.W)) : std::sqrt((1 - s) * (sx.W - t_));
            for (const Vec3& d : directions(k)) {
                // Steps of r/2, or longer where the skin-free radius of the last sample
                // allows (through the inside of a blob of atoms): the first crossing is kept.
                std::size_t hint = k;
                Sample sa{sx.W - t_, 0.0};
                Point3 a = sx.z;
                double along = 0;
                for (int step = 1; step < 100000; ++step) {
                    along += std::max(0.5 * r, sa.clear);
                    const Point3 b = sx.z + along * d;
                    const Sample sb = sample_at(b, hint);
                    if ((sb.f < 0) != (sa.f < 0)) {
                        seeds.push_back(root_between(a, sa.f, b, sb.f, hint));
                        seed_hints.push_back(hint);
                        break;
                    }
                    if (!box_.contains(b)) break;  // the skin lies in the box: a ray that left it misses
                    a = b;
                    sa = sb;
                }
            }
        }
        report_.seeds = seeds.size();
        DYNMESH_CHECK(seeds.size() >= 4, "mesh_skin: the skin has too few seed points");
        // Inserted along a space-filling curve, each from the cell of the one before: the
        // walks of the triangulation stay short.
        Cell near;
        for (const std::uint32_t s : spatial_order(seeds))
            if (const Vertex v = add_sample(seeds[s], seed_hints[s], near); v != Vertex()) near = v->cell();
        DYNMESH_CHECK(dt_.dimension() == 3, "mesh_skin: the seed points are coplanar");
    }

    void prepare(Cell c) {
        if (c->info().ready || dt_.is_infinite(c)) return;
        const K::Point_3& a = c->vertex(0)->point();
        const K::Point_3& b = c->vertex(1)->point();
        const K::Point_3& d = c->vertex(2)->point();
        const K::Point_3& e = c->vertex(3)->point();
        K::Point_3 x = CGAL::circumcenter(a, b, d, e);
        if (!detail::circumcenter_is_accurate(x, std::array{&a, &b, &d, &e})) {
            const CGAL::Cartesian_converter<K, EK> to_exact;
            const EK::Point_3 ex = CGAL::circumcenter(to_exact(a), to_exact(b), to_exact(d), to_exact(e));
            x = K::Point_3(CGAL::to_double(ex.x()), CGAL::to_double(ex.y()), CGAL::to_double(ex.z()));
        }
        c->info().cc = to_p(x);
        if (!is_finite(c->info().cc)) {
            // A flat cell (four cospherical and coplanar samples): its Voronoi vertex is at
            // infinity; its centroid stands in, so that the facets around it are still judged.
            ++report_.flat_cells;
            c->info().cc = to_p(CGAL::centroid(a, b, d, e));
        }
        std::size_t hint = c->vertex(0)->info().hint;
        for (int k = 0; k < 4; ++k) {
            const Cell n = c->neighbor(k);
            if (n->info().ready && !dt_.is_infinite(n)) {
                hint = n->info().simplex;
                break;
            }
        }
        const Sample smp = sample_at(c->info().cc, hint);
        c->info().simplex = std::uint32_t(hint);
        c->info().f = smp.f;
        c->info().clear = smp.clear;
        c->info().ready = true;
    }

    /// Of the two cells on a facet, the one the facet is looked at from: the finite one, or
    /// the one whose vertex opposite the facet is lexicographically smaller. Not the handles'
    /// addresses: the mesh must not depend on where the allocator put the cells.
    bool looked_from(Cell c, int i) const {
        const Cell n = c->neighbor(i);
        if (dt_.is_infinite(c) != dt_.is_infinite(n)) return !dt_.is_infinite(c);
        return c->vertex(i)->point() < n->vertex(n->index(c))->point();
    }

    std::uint64_t id_of(Cell c) {
        if (c->info().id == 0) c->info().id = ++cells_seen_;
        return c->info().id;
    }

    /// The facet (c, i) as seen from the cell it is looked at from.
    void canonical(Cell& c, int& i) const {
        if (looked_from(c, i)) return;
        const Cell n = c->neighbor(i);
        i = n->index(c);
        c = n;
    }

    /// Pieces of a dual edge are halved until each either changes sign (a crossing) or is
    /// covered by the skin-free balls of its ends (none); a piece still undecided after 8
    /// halvings only grazes the skin and counts as no crossing. The near half is searched first.
    void search(const Point3& a, const Sample& sa, const Point3& b, const Sample& sb, int depth, Crossing& out,
                std::size_t& hint) const {
        if ((sa.f < 0) != (sb.f < 0)) {
            if (out.hits == 0) out.p = root_between(a, sa.f, b, sb.f, hint);
            ++out.hits;
            return;
        }
        if (sa.clear + sb.clear >= norm(b - a) || depth >= 8) return;
        const Point3 m = a + 0.5 * (b - a);
        const Sample sm = sample_at(m, hint);
        search(a, sa, m, sm, depth + 1, out, hint);
        search(m, sm, b, sb, depth + 1, out, hint);
    }

    /// The crossings of the facet's dual Voronoi edge with the skin (the same from both sides).
    Crossing dual_crossing(Cell c, int i) {
        canonical(c, i);
        const Cell n = c->neighbor(i);
        prepare(c);
        const Point3 a = c->info().cc;
        const Sample sa{c->info().f, c->info().clear};
        Point3 b;
        Sample sb;
        std::size_t hint = c->vertex(0)->info().hint;
        if (dt_.is_infinite(n)) {
            // The outward ray of a hull facet, cut beyond the box that holds the skin.
            const Point3 p0 = to_p(c->vertex((i + 1) & 3)->point());
            const Point3 p1 = to_p(c->vertex((i + 2) & 3)->point());
            const Point3 p2 = to_p(c->vertex((i + 3) & 3)->point());
            Vec3 nrm = normalized(cross(p1 - p0, p2 - p0));
            if (dot(nrm, to_p(c->vertex(i)->point()) - p0) > 0) nrm = -1.0 * nrm;
            const Point3 mid = box_.min + 0.5 * (box_.max - box_.min);
            const double len = norm(a - mid) + box_.diagonal() + 1e-9;
            b = a + len * nrm;
            sb = sample_at(b, hint);
        } else {
            prepare(n);
            b = n->info().cc;
            sb = {n->info().f, n->info().clear};
        }
        Crossing out;
        out.from = id_of(c);
        out.to = id_of(n);
        search(a, sa, b, sb, 0, out, hint);
        c->info().hits[std::size_t(i)] = std::uint8_t(std::min(out.hits, 254));
        return out;
    }

    /// Why the facet (c, i) must be refined (None when it is not restricted, or good).
    Defect judge(Cell c, int i, Crossing& x, double& priority) {
        canonical(c, i);
        x = dual_crossing(c, i);
        if (x.hits == 0) return Defect::None;
        const Vertex v0 = c->vertex((i + 1) & 3), v1 = c->vertex((i + 2) & 3), v2 = c->vertex((i + 3) & 3);
        const Point3 p0 = to_p(v0->point()), p1 = to_p(v1->point()), p2 = to_p(v2->point());
        const double r = norm(x.p - p0);
        const double lambda = std::max({std::min({v0->info().rho, v1->info().rho, v2->info().rho}), rho_floor_});
        const double shortest = std::sqrt(std::min({sqnorm(p1 - p0), sqnorm(p2 - p1), sqnorm(p0 - p2)}));
        priority = r / lambda;
        if (r > opt_.quality.C * opt_.quality.Q0 * lambda) return Defect::Size;
        if (x.hits > 1) return Defect::Topology;
        if (r > opt_.radius_edge_bound * shortest && shortest > 0.05 * rho_floor_) return Defect::Shape;
        return Defect::None;
    }

    void test_facet(Cell c, int i) {
        if (dt_.is_infinite(c->vertex((i + 1) & 3)) || dt_.is_infinite(c->vertex((i + 2) & 3)) ||
            dt_.is_infinite(c->vertex((i + 3) & 3)))
            return;
        Crossing x;
        double priority = 0;
        const Defect defect = judge(c, i, x, priority);
        if (defect == Defect::None) return;
        BadFacet bad{priority, c->vertex((i + 1) & 3), c->vertex((i + 2) & 3), c->vertex((i + 3) & 3), {}, x, defect};
        for (int k = 0; k < 3; ++k) {
            const K::Point_3& p = c->vertex((i + 1 + k) & 3)->point();
            bad.key[k] = {p.x(), p.y(), p.z()};
        }
        std::sort(bad.key.begin(), bad.key.end());
        queue_.push(bad);
    }

    void refine() {
        std::vector<Cell> star;
        std::size_t next_progress = 0;
        while (!queue_.empty()) {
            const BadFacet bad = queue_.top();
            queue_.pop();
            Cell c;
            int i0 = 0, i1 = 0, i2 = 0;
            if (!dt_.is_facet(bad.a, bad.b, bad.c, c, i0, i1, i2)) continue;
            const int i = 6 - i0 - i1 - i2;
            // The judgement made when the facet was queued holds while it joins the same two
            // cells (the same dual edge); otherwise it is judged again.
            Cell from = c;
            int j = i;
            canonical(from, j);
            Crossing x = bad.x;
            Defect defect = bad.defect;
            if (id_of(from) != x.from || id_of(from->neighbor(j)) != x.to) {
                double priority = 0;
                defect = judge(c, i, x, priority);
            }
            if (defect == Defect::None) continue;
            DYNMESH_CHECK(dt_.number_of_vertices() < opt_.max_vertices,
                          "mesh_skin: more than max_vertices = " + std::to_string(opt_.max_vertices) +
                              " samples; raise the limit or the floor under the length scale");
            const Vertex v = add_sample(x.p, c->vertex(i0)->info().hint, c);
            if (v == Vertex()) continue;
            (defect == Defect::Size ? report_.refined_size
                                    : defect == Defect::Shape ? report_.refined_shape : report_.refined_topology)++;
            star.clear();
            dt_.incident_cells(v, std::back_inserter(star));
            for (Cell s : star) {
                for (int k = 0; k < 4; ++k) {
                    const Cell n = s->neighbor(k);
                    if (n->has_vertex(v) && !looked_from(s, k)) continue;  // shared facet, tested once
                    test_facet(s, k);
                }
            }
            if (opt_.progress && dt_.number_of_vertices() >= next_progress) {
                opt_.progress(dt_.number_of_vertices(), queue_.size());
                next_progress = dt_.number_of_vertices() + std::max<std::size_t>(1000, dt_.number_of_vertices() / 100);
            }
        }
    }

    SkinMeshResult extract() {
        TriangleSoup soup;
        SkinMeshResult result;
        // The facets are visited in an order that depends on where the cells lie in memory:
        // the vertices are numbered in the triangulation's own (allocation) order and the
        // triangles sorted, so that the mesh is the same in every run.
        for (auto v = dt_.finite_vertices_begin(); v != dt_.finite_vertices_end(); ++v) v->info().mesh_index = ~0u;
        std::vector<std::array<Vertex, 3>> restricted;
        for (auto f = dt_.finite_facets_begin(); f != dt_.finite_facets_end(); ++f) {
            Cell c = f->first;
            int i = f->second;
            // Every facet was judged after its two cells last changed (at seeding or as part
            // of an insertion's star): only those whose dual edge crossed the skin are searched
            // again, for the crossing point.
            canonical(c, i);
            if (c->info().hits[std::size_t(i)] == 0) continue;
            const Crossing x = dual_crossing(c, i);
            if (x.hits == 0) continue;
            std::array<Vertex, 3> v{c->vertex((i + 1) & 3), c->vertex((i + 2) & 3), c->vertex((i + 3) & 3)};
            const Point3 p0 = to_p(v[0]->point()), p1 = to_p(v[1]->point()), p2 = to_p(v[2]->point());
            std::size_t hint = v[0]->info().hint;
            const Vec3 g = phi_.evaluate(x.p, hint).gradient;
            if (dot(cross(p1 - p0, p2 - p0), g) < 0) std::swap(v[1], v[2]);
            for (Vertex w : v) w->info().mesh_index = 0;  // used
            restricted.push_back(v);
        }
        for (auto v = dt_.finite_vertices_begin(); v != dt_.finite_vertices_end(); ++v) {
            if (v->info().mesh_index == ~0u) continue;
            std::size_t hint = v->info().hint;
            v->info().mesh_index = std::uint32_t(soup.points.size());
            soup.points.push_back(project_to_skin(phi_, to_p(v->point()), t_, hint));
            result.rho.push_back(v->info().rho);
        }
        for (const auto& v : restricted) {
            std::array<std::uint32_t, 3> t{v[0]->info().mesh_index, v[1]->info().mesh_index, v[2]->info().mesh_index};
            std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // orientation kept
            soup.triangles.push_back(t);
        }
        std::sort(soup.triangles.begin(), soup.triangles.end());
        result.mesh = SurfaceMesh::from_soup(soup);
        return result;
    }

    const SkinFunction& phi_;
    SkinMeshOptions opt_;
    double t_;
    Bbox3 box_;  ///< holds every ball of radius √(w + t), and so the skin
    double rho_floor_ = 0;
    double scale2_ = 1;
    DT dt_;
    std::priority_queue<BadFacet> queue_;
    std::uint64_t cells_seen_ = 0;
    SkinMeshReport report_;
};

}  // namespace

Point3 project_to_skin(const SkinFunction& phi, const Point3& x0, double t, std::size_t& hint) {
    Point3 x = x0;
    for (int it = 0; it < 50; ++it) {
        const SkinEvaluation ev = phi.evaluate(x, hint);
        hint = ev.simplex;
        const double f = ev.value - t;
        const double g2 = sqnorm(ev.gradient);
        if (!(g2 > 0)) break;
        const Point3 next = x - (f / g2) * ev.gradient;
        const double moved2 = sqnorm(next - x);
        x = next;
        if (moved2 <= 1e-28 * (sqnorm(x - Point3{0, 0, 0}) + ev.rho * ev.rho) || moved2 == 0) break;
    }
    return x;
}

SkinMeshResult mesh_skin(const SkinFunction& phi, const SkinMeshOptions& options) {
    Mesher mesher(phi, options);
    return mesher.run();
}

}  // namespace dynmesh
