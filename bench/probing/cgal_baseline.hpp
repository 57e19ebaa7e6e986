#pragma once
/// \file The CGAL baseline of the "meshing by probing" benchmark (specs/probing.md §7 "CGAL
/// comparison", §10 item 9): CGAL's Surface_mesher (Boissonnat–Oudot / Chew refinement of the
/// restricted Delaunay triangulation) run on the implicit function of a probing object.
///
/// Setup, as the spec prescribes:
///     make_surface_mesh(c2t3, Implicit_surface_3(f, Sphere_3(inside, R²), error_bound),
///                       traits, Surface_mesh_default_criteria_3(0, ε, ε),
///                       Non_manifold_tag() | Manifold_tag(), 20 initial points)
/// - f = object.signed_distance (negative inside O).
/// - The bounding sphere is centred at `inside` (CGAL requires f < 0 there), with radius
///   R = |inside − bounding.center| + bounding.radius, so it contains the caller's ball
///   `bounding` (which must contain S, as ProbeSetup::omega does). CGAL 5.5 takes R², and its
///   bisection stops at |p1 − p2| < error_bound · R (the bound is relative to R).
/// - Angle bound 0 disables the aspect-ratio criterion and a distance bound ε never acts when
///   the radius bound is ε, so only "surface Delaunay ball radius ≤ ε" drives refinement.
/// - The triangulation is Surface_mesh_default_triangulation_3 (EPICK with robust
///   circumcentres, CGAL's surface-mesh vertex and cell bases) with one addition, a creation
///   time stamp in every vertex and cell (see Determinism); the complex is
///   Surface_mesh_complex_2_in_triangulation_3.
///
/// Counts (exact; CGAL itself is unchanged, the counting is done by wrappers):
/// - oracle_queries: calls of the oracle's Intersect_3 functor, i.e. segment / ray / line vs
///   surface intersection tests, successful or not. make_surface_mesh is given a traits object
///   (CountingImplicitOracle below) derived from Surface_mesher::Implicit_surface_oracle_3 whose
///   intersect_3_object() returns a counting wrapper of the base functor; the mesher asks it
///   once per restricted-Delaunay test of a facet (Surface_mesher_base::is_facet_on_surface:
///   every facet of every new cell, and the facets opposite the new vertex). Facets whose dual
///   is degenerate are rejected by CGAL before any query and are not counted.
///   The initial points are found by the base class's Construct_initial_points, which calls
///   the base functor directly (it holds a reference to the base object), so those queries are
///   not seen by the wrapper; they are counted as initial_point_queries = the number of initial
///   points (20): CGAL shoots segments from the sphere centre to random points of the sphere
///   and retries (moving the centre) only when a segment shows no sign change. With f < 0 at
///   the centre and the whole sphere outside `bounding`, i.e. outside O, every segment has one,
///   so there are no retries (checked on every object of the benchmark by building with
///   CGAL_SURFACE_MESHER_DEBUG_INITIAL_POINTS, which logs each of these queries).
///   oracle_queries includes initial_point_queries.
/// - oracle_hits: the queries that returned a point of S (a non-empty CGAL::Object), the
///   initial points included. The others found no sign change (most often: both ends of a
///   Voronoi edge on the same side, two evaluations of f and no bisection).
/// - function_evaluations: calls of f by CGAL (through the std::function held by
///   Implicit_surface_3): two signs per query, the ends of the clipped segment, then one per
///   bisection step; the initial points included. Evaluations made while orienting the
///   output (below) are not counted.
///
/// Output: the facets of the complex as a TriangleSoup, vertices numbered in the order they
/// are first met by the complex's facet iterator (deterministic). Orientation: every facet of
/// the complex is dual to a Voronoi edge along which sign(f) changes (that is how CGAL's
/// oracle detects it). Label each Delaunay cell by sign(f) at its circumcentre, with +1 for
/// infinite cells and for circumcentres not strictly inside the bounding sphere (CGAL clips
/// there, and f > 0 there); each facet is oriented so that its normal (right-hand rule) points
/// from the lower-labelled cell to the higher-labelled one, i.e. out of O. The complex is then
/// the oriented boundary of the union of the cells labelled −1, so the orientation is
/// consistent at every edge with two facets; that holds for a manifold complex and also
/// around the manifold parts of a non-manifold one. This costs one evaluation of f per facet
/// (two when f is exactly 0 at a circumcentre), included in seconds_total.
///
/// Timing: seconds_mesh is the wall time (steady_clock) of make_surface_mesh alone (initial
/// points included); seconds = seconds_total adds the extraction of the oriented soup and the
/// topology checks (manifold, oriented, Euler characteristic).
///
/// Determinism: two runs with the same arguments give the same mesh and counts, in one
/// process or in several. Two things had to be fixed for that.
/// - The initial points come from CGAL::Random_points_on_sphere_3 / Random_points_in_sphere_3
///   drawing from CGAL::get_default_random() (a thread-local CGAL::Random seeded from the
///   clock by default). Each run replaces it by CGAL::Random(seed) and restores the previous
///   generator afterwards, leaving the caller's random stream untouched.
/// - Handle comparisons. By default, Cell_handle / Vertex_handle compare by address. The TDS
///   facet iterator reports each facet from the side whose cell has the smaller address, and
///   Surface_mesher measures the radius criterion from that side's first vertex and bisects
///   the dual segment in that side's direction. The last bits of the radii, hence the order
///   of the refinement queue and the output, then depend on where malloc put the cell blocks.
///   A fresh process repeats itself, but later runs in the same process did not: the sphere at
///   ε = 0.08 gave 1312, 1310 and 1305 vertices. With time-stamped vertices and cells (the
///   mechanism Mesh_3 uses, CGAL/Time_stamper.h), handles compare by creation order.

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_with_circumcenter_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Implicit_surface_3.h>
#include <CGAL/Random.h>
#include <CGAL/Robust_circumcenter_traits_3.h>
#include <CGAL/Surface_mesh_cell_base_3.h>
#include <CGAL/Surface_mesh_complex_2_in_triangulation_3.h>
#include <CGAL/Surface_mesh_default_criteria_3.h>
#include <CGAL/Surface_mesh_default_triangulation_3.h>
#include <CGAL/Surface_mesh_vertex_base_3.h>
#include <CGAL/Surface_mesher/Implicit_surface_oracle_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/make_surface_mesh.h>
#include <CGAL/tags.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/probing/oracle.hpp"
#include "dynmesh/probing/oracles.hpp"

namespace dynmesh::bench {

/// The result of one CGAL run (see the file comment for the definitions).
struct CgalSurfaceRun {
    /// The facets of the complex, oriented outward (consistently wherever the complex is a
    /// manifold); only vertices incident to a facet.
    TriangleSoup mesh;
    double seconds = 0;       ///< seconds_total: seconds_mesh + extracting and checking the soup
    double seconds_mesh = 0;  ///< make_surface_mesh only (initial points included)
    std::size_t oracle_queries = 0;          ///< Intersect_3 calls, initial points included
    std::size_t initial_point_queries = 0;   ///< the part of oracle_queries spent on them
    std::size_t oracle_hits = 0;             ///< queries that returned a point of S
    std::size_t function_evaluations = 0;    ///< calls of f made by CGAL
    std::size_t triangulation_vertices = 0;  ///< vertices of the Delaunay triangulation
    /// Closed 2-manifold: every edge in exactly two facets, every vertex's facets one cycle.
    bool manifold = false;
    /// Every edge in exactly two facets, traversed once in each direction.
    bool oriented = false;
    long long euler_characteristic = 0;  ///< V − E + F of the soup (E: distinct edges)
};

namespace cgal_baseline_detail {

/// Adds CGAL's time-stamp interface to a vertex or cell base (as Mesh_3's bases have it):
/// Compact_container then stamps elements in creation order and handles compare by stamp
/// instead of by address (file comment, Determinism).
template <class Base>
class TimeStamped : public Base {
public:
    using Has_timestamp = CGAL::Tag_true;
    template <class Tds2>
    struct Rebind_TDS {
        using Other = TimeStamped<typename Base::template Rebind_TDS<Tds2>::Other>;
    };
    using Base::Base;
    [[nodiscard]] std::size_t time_stamp() const { return time_stamp_; }
    void set_time_stamp(const std::size_t& ts) { time_stamp_ = ts; }

private:
    std::size_t time_stamp_ = static_cast<std::size_t>(-1);  // "unset" for Time_stamper
};

/// CGAL::Surface_mesh_default_triangulation_3 (same kernel, vertex and cell bases), with
/// time-stamped vertices and cells.
using Kernel = CGAL::Robust_circumcenter_traits_3<CGAL::Epick>;
using Tr = CGAL::Delaunay_triangulation_3<
    Kernel, CGAL::Triangulation_data_structure_3<
                TimeStamped<CGAL::Surface_mesh_vertex_base_3<Kernel>>,
                TimeStamped<CGAL::Delaunay_triangulation_cell_base_with_circumcenter_3<
                    Kernel, CGAL::Surface_mesh_cell_base_3<Kernel>>>>>;
static_assert(
    std::is_same_v<Tr::Geom_traits, CGAL::Surface_mesh_default_triangulation_3::Geom_traits>);
using C2t3 = CGAL::Surface_mesh_complex_2_in_triangulation_3<Tr>;
using GT = Tr::Geom_traits;
using FT = GT::FT;
using CPoint = GT::Point_3;
using Function = std::function<FT(CPoint)>;
using Surface = CGAL::Implicit_surface_3<GT, Function>;
using Sign_of = CGAL::Real_embeddable_traits<FT>::Sgn;  // the oracle's default transform

/// The oracle's surface-identifier generator: the smaller of the two signs, as CGAL's default
/// (Surface_mesher::Return_min). That one lives in an anonymous namespace of a CGAL header,
/// which makes GCC warn (-Wsubobject-linkage) about any class in a header deriving from the
/// oracle. The identifier only matters for points with set_on_surface(), which EPICK points
/// lack, so this changes nothing.
struct MinSign {
    using result_type = CGAL::Sign;
    CGAL::Sign operator()(CGAL::Sign a, CGAL::Sign b) const { return (std::min)(a, b); }
};

/// CGAL's oracle for Implicit_surface_3 (its Surface_mesher_traits_3, up to MinSign).
using BaseOracle = CGAL::Surface_mesher::Implicit_surface_oracle_3<GT, Surface, Sign_of, MinSign>;

/// Traits for make_surface_mesh: CGAL's implicit-surface oracle with a counting Intersect_3.
/// Everything else (types, Construct_initial_points, is_in_volume) is inherited unchanged.
class CountingImplicitOracle : public BaseOracle {
public:
    /// Where the counts go: queries, and those that returned a point.
    struct Counters {
        std::size_t queries = 0;
        std::size_t hits = 0;
    };

    explicit CountingImplicitOracle(Counters* counters) : counters_(counters) {}

    /// Forwards every query (Segment_3, Ray_3, Line_3) to the base functor, counting it.
    class Intersect_3 {
    public:
        Intersect_3(BaseOracle::Intersect_3 base, Counters* counters)
            : base_(std::move(base)), counters_(counters) {}
        template <class Query>
        CGAL::Object operator()(const Surface& surface, const Query& query) {
            ++counters_->queries;
            CGAL::Object result = base_(surface, query);
            if (!result.empty()) ++counters_->hits;
            return result;
        }

    private:
        BaseOracle::Intersect_3 base_;
        Counters* counters_;
    };

    [[nodiscard]] Intersect_3 intersect_3_object() const {
        return Intersect_3(BaseOracle::intersect_3_object(), counters_);
    }

private:
    Counters* counters_;
};

/// Replaces CGAL's default random generator for the lifetime of the guard.
class DefaultRandomGuard {
public:
    explicit DefaultRandomGuard(unsigned int seed) : saved_(CGAL::get_default_random()) {
        CGAL::get_default_random() = CGAL::Random(seed);
    }
    ~DefaultRandomGuard() { CGAL::get_default_random() = saved_; }
    DefaultRandomGuard(const DefaultRandomGuard&) = delete;
    DefaultRandomGuard& operator=(const DefaultRandomGuard&) = delete;

private:
    CGAL::Random saved_;
};

inline Point3 to_point3(const CPoint& p) { return {p.x(), p.y(), p.z()}; }

/// Orients the facets of the complex outward (file comment) and numbers their vertices.
inline TriangleSoup extract_soup(const C2t3& c2t3, const Surface& surface,
                                 const ProbeObject& object) {
    const Tr& tr = c2t3.triangulation();
    const GT::Sphere_3& sphere = surface.bounding_sphere();
    const auto label = [&](Tr::Cell_handle c) -> int {
        if (tr.is_infinite(c)) return 1;
        const CPoint& cc = c->circumcenter(tr.geom_traits());
        if (!sphere.has_on_bounded_side(cc)) return 1;
        const double f = object.signed_distance(to_point3(cc));
        return (f > 0) - (f < 0);
    };

    TriangleSoup soup;
    soup.triangles.reserve(c2t3.number_of_facets());
    std::unordered_map<Tr::Vertex_handle, std::uint32_t> index;
    const auto index_of = [&](Tr::Vertex_handle v) {
        const auto [it, inserted] =
            index.try_emplace(v, static_cast<std::uint32_t>(soup.points.size()));
        if (inserted) soup.points.push_back(to_point3(v->point()));
        return it->second;
    };
    for (auto it = c2t3.facets_begin(); it != c2t3.facets_end(); ++it) {
        Tr::Cell_handle c = it->first;
        int i = it->second;
        Tr::Cell_handle n = c->neighbor(i);
        const int lc = label(c);
        // (c, i) lists its vertices so that the normal points into c (CGAL's
        // vertex_triple_index convention for positively oriented cells), so view the facet
        // from the higher-labelled (outer) cell.
        const bool c_is_outer = lc > 0 || (lc == 0 && label(n) < 0);
        if (!c_is_outer) {
            i = n->index(c);
            c = n;
        }
        std::array<std::uint32_t, 3> t{};
        for (int j = 0; j < 3; ++j) t[j] = index_of(c->vertex(Tr::vertex_triple_index(i, j)));
        soup.triangles.push_back(t);
    }
    return soup;
}

/// Fills manifold, oriented and euler_characteristic from run.mesh.
inline void check_topology(CgalSurfaceRun& run) {
    const TriangleSoup& soup = run.mesh;
    // Undirected edge (lo, hi) -> (number of facets, number traversing it lo -> hi).
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<int, int>> edges;
    for (const auto& t : soup.triangles)
        for (int j = 0; j < 3; ++j) {
            const std::uint32_t a = t[j], b = t[(j + 1) % 3];
            auto& e = edges[{std::min(a, b), std::max(a, b)}];
            ++e.first;
            if (a < b) ++e.second;
        }
    bool edge_manifold = !soup.triangles.empty();
    bool oriented = edge_manifold;
    for (const auto& [key, e] : edges) {
        if (e.first != 2) edge_manifold = false;
        if (e.first != 2 || e.second != 1) oriented = false;
    }
    // Vertex links: with every edge in two facets, each link is a union of cycles; require one.
    bool vertex_manifold = edge_manifold;
    if (edge_manifold) {
        std::vector<std::vector<std::array<std::uint32_t, 2>>> link(soup.points.size());
        for (const auto& t : soup.triangles)
            for (int j = 0; j < 3; ++j) link[t[j]].push_back({t[(j + 1) % 3], t[(j + 2) % 3]});
        for (const auto& l : link) {
            if (l.empty()) continue;
            // Walk the cycle through l[0]; it must use every link edge.
            std::vector<bool> used(l.size(), false);
            used[0] = true;
            std::size_t walked = 1;
            const std::uint32_t start = l[0][0];
            std::uint32_t at = l[0][1];
            while (at != start) {
                std::size_t k = 0;
                while (k < l.size() && (used[k] || (l[k][0] != at && l[k][1] != at))) ++k;
                if (k == l.size()) break;
                used[k] = true;
                ++walked;
                at = l[k][0] == at ? l[k][1] : l[k][0];
            }
            if (walked != l.size()) {
                vertex_manifold = false;
                break;
            }
        }
    }
    run.manifold = edge_manifold && vertex_manifold;
    run.oriented = oriented;
    run.euler_characteristic = static_cast<long long>(soup.points.size()) -
                               static_cast<long long>(edges.size()) +
                               static_cast<long long>(soup.triangles.size());
}

template <class Tag>
CgalSurfaceRun run(const ProbeObject& object, const Ball& bounding, const Point3& inside,
                   double eps, double error_bound, unsigned int seed) {
    using Clock = std::chrono::steady_clock;
    if (!(eps > 0) || !(error_bound > 0) || !(bounding.radius > 0) || !is_finite(inside) ||
        !is_finite(bounding.center))
        throw InvalidInput(
            "cgal_make_surface_mesh: eps, error_bound and the bounding radius "
            "must be positive and finite");
    if (!(object.signed_distance(inside) < 0))
        throw InvalidInput(
            "cgal_make_surface_mesh: `inside` is not inside the object (CGAL "
            "needs f < 0 at the bounding sphere's centre)");

    CgalSurfaceRun result;
    std::size_t evaluations = 0;
    CountingImplicitOracle::Counters counters;
    const Function f = [&object, &evaluations](CPoint p) -> FT {
        ++evaluations;
        return object.signed_distance(to_point3(p));
    };
    const double radius = distance(inside, bounding.center) + bounding.radius;
    const Surface surface(f, GT::Sphere_3(CPoint(inside.x, inside.y, inside.z), radius * radius),
                          error_bound);
    const CGAL::Surface_mesh_default_criteria_3<Tr> criteria(0.0, eps, eps);
    const CountingImplicitOracle traits(&counters);
    constexpr int kInitialPoints = 20;  // make_surface_mesh's default

    Tr tr;
    C2t3 c2t3(tr);
    const auto t0 = Clock::now();
    {
        const DefaultRandomGuard guard(seed);
        CGAL::make_surface_mesh(c2t3, surface, traits, criteria, Tag(), kInitialPoints);
    }
    const auto t1 = Clock::now();
    result.mesh = extract_soup(c2t3, surface, object);
    check_topology(result);
    const auto t2 = Clock::now();

    result.seconds_mesh = std::chrono::duration<double>(t1 - t0).count();
    result.seconds = std::chrono::duration<double>(t2 - t0).count();
    result.initial_point_queries = kInitialPoints;
    // Each initial point is one query that found a crossing (file comment).
    result.oracle_queries = counters.queries + result.initial_point_queries;
    result.oracle_hits = counters.hits + result.initial_point_queries;
    result.function_evaluations = evaluations;
    result.triangulation_vertices = tr.number_of_vertices();
    return result;
}

}  // namespace cgal_baseline_detail

/// Runs CGAL's make_surface_mesh on `object` at radius bound `eps` (file comment).
/// \param bounding a ball containing S (e.g. ProbeSetup::omega)
/// \param inside   a point with object.signed_distance(inside) < 0: the bounding sphere's centre
/// \param manifold_tag Manifold_tag instead of Non_manifold_tag
/// \param error_bound  CGAL's bisection precision, relative to the bounding sphere's radius
/// \param seed     the seed of CGAL's default random generator during the run
/// \throw InvalidInput for a non-positive eps, error_bound or radius, or an `inside`
/// that is not inside the object.
inline CgalSurfaceRun cgal_make_surface_mesh(const ProbeObject& object, const Ball& bounding,
                                             const Point3& inside, double eps,
                                             bool manifold_tag = false, double error_bound = 1e-6,
                                             unsigned int seed = 0) {
    namespace d = cgal_baseline_detail;
    if (manifold_tag)
        return d::run<CGAL::Manifold_tag>(object, bounding, inside, eps, error_bound, seed);
    return d::run<CGAL::Non_manifold_tag>(object, bounding, inside, eps, error_bound, seed);
}

}  // namespace dynmesh::bench
