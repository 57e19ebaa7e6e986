// restricted_delaunay_on_mesh(): the restricted Delaunay triangulation of a net of samples
// with respect to a triangle mesh, refined where the net is too sparse for the mesh.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "restricted_facets.hpp"
#include "samples_common.hpp"

namespace dynmesh {
namespace {

using detail::DualProbe;
using detail::IndexTriangle;
using K = detail::RdtKernel;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

K::Point_3 to_cgal(const Point3& p) { return {p.x, p.y, p.z}; }
Point3 from_cgal(const K::Point_3& p) { return {p.x(), p.y(), p.z()}; }

std::string where(const Point3& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p.x, p.y, p.z);
    return buf;
}

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/// A surface point where the net is too sparse, with the radius of the ball about it that is
/// empty of net points (it passes through the vertices of the facet whose dual edge hits it).
struct RefineTarget {
    Point3 p;
    double r = 0;
    /// For the topology (a defect nearby): added even closer to the net than the minimum
    /// spacing.
    bool required = false;
};

/// True when a point of the grid (other than the triangle's vertices) lies strictly inside the
/// diametric ball of triangle t (exact predicate).
bool ball_holds_point(std::span<const Point3> pts, const IndexTriangle& t, const PointGrid& grid) {
    const Point3 &a = pts[t[0]], &b = pts[t[1]], &c = pts[t[2]];
    if (collinear(a, b, c)) return false;
    const Point3 cc = circumcenter(a, b, c);
    const double rad = distance(cc, a);
    bool hit = false;
    grid.for_each_candidate(cc, rad, [&](std::uint32_t w) {
        if (hit || w == t[0] || w == t[1] || w == t[2]) return;
        if (distance(pts[w], cc) > rad * (1 + 1e-9)) return;
        hit = in_diametric_ball(a, b, c, pts[w]) == Sign::Positive;
    });
    return hit;
}

/// The surface as an AABB tree of its triangles, with each triangle's outward normal.
struct MeshSurface {
    Triangles triangles;
    std::vector<Vec3> normals;
    Tree tree;
    Bbox3 box;
    double tolerance = 0;  ///< hits closer than this are one hit (through a mesh edge or vertex)

    explicit MeshSurface(const SurfaceMesh& mesh) {
        triangles.reserve(mesh.n_faces());
        for (Face f : mesh.faces()) {
            const auto vs = mesh.face_vertices(f);
            const Point3 &a = mesh.position(vs[0]), &b = mesh.position(vs[1]), &c = mesh.position(vs[2]);
            triangles.emplace_back(to_cgal(a), to_cgal(b), to_cgal(c));
            normals.push_back(cross(b - a, c - a));
            box.extend(a);
        }
        for (Vertex v : mesh.vertices()) box.extend(mesh.position(v));
        tree.insert(triangles.cbegin(), triangles.cend());
        tree.build();
        tolerance = 1e-9 * box.diagonal();
    }
};

/// The restricted_facets() oracle of a mesh: a dual edge meets the surface when the AABB tree
/// finds a triangle it meets. Records the hit point of every kept facet and every dual edge
/// that meets the surface at two or more distinct points.
class MeshOracle {
public:
    MeshOracle(const MeshSurface& surface, std::span<const Point3> net) : s_(surface), net_(net) {}

    [[nodiscard]] Bbox3 bbox() const { return s_.box; }
    [[nodiscard]] double value(const Point3&) const { return 0; }

    bool keep(const DualProbe& from, const DualProbe& to, IndexTriangle& t) {
        if (from.p == to.p) return false;  // cospherical cells: no dual edge
        hits_.clear();
        s_.tree.all_intersections(K::Segment_3(to_cgal(from.p), to_cgal(to.p)), std::back_inserter(hits_));
        if (hits_.empty()) return false;
        const Point3 &pa = net_[t[0]], &pb = net_[t[1]], &pc = net_[t[2]];
        const Point3 centroid = (pa + pb + pc) / 3.0;
        points_.clear();
        std::size_t best = 0;
        double best_d = std::numeric_limits<double>::infinity();
        Point3 best_x;
        for (std::size_t k = 0; k < hits_.size(); ++k) {
            const auto& obj = hits_[k].first;
            Point3 x;
            if (const auto* p = boost::get<K::Point_3>(&obj)) {
                x = from_cgal(*p);
            } else {  // the dual edge lies in the triangle's plane: take the overlap's midpoint
                const auto& seg = boost::get<K::Segment_3>(obj);
                x = 0.5 * (from_cgal(seg.source()) + from_cgal(seg.target()));
            }
            bool seen = false;
            for (const Point3& y : points_) seen |= distance(x, y) <= s_.tolerance;
            if (!seen) points_.push_back(x);
            const double d = distance(x, centroid);
            if (d < best_d) {
                best_d = d;
                best = k;
                best_x = x;
            }
        }
        const std::size_t face = static_cast<std::size_t>(hits_[best].second - s_.triangles.cbegin());
        const Vec3 n = cross(pb - pa, pc - pa);
        const double c = dot(n, s_.normals[face]);
        if (c < 0) std::swap(t[1], t[2]);
        // |cos| of the angle between the facet and the surface triangle it meets.
        const double nn = norm(n) * norm(s_.normals[face]);
        hits_of_.push_back({t, {best_x, distance(best_x, pa)}, nn > 0 ? std::abs(c) / nn : 0.0});
        if (points_.size() > 1) {
            ++multi_hit_facets_;
            for (const Point3& x : points_) multi_hits_.push_back({x, distance(x, pa)});
        }
        return true;
    }

    /// A kept facet: its vertices, where its dual edge meets the surface (the hit nearest its
    /// centroid), and |cos| of its angle with the surface triangle met there.
    struct KeptFacet {
        IndexTriangle t;
        RefineTarget target;  ///< the hit, and its distance to the facet's vertices
        double cos_surface = 0;
    };
    [[nodiscard]] const std::vector<KeptFacet>& kept() const { return hits_of_; }
    [[nodiscard]] const std::vector<RefineTarget>& multi_hits() const { return multi_hits_; }
    [[nodiscard]] std::size_t multi_hit_facets() const { return multi_hit_facets_; }

private:
    using Hit = Tree::Intersection_and_primitive_id<K::Segment_3>::Type;
    const MeshSurface& s_;
    std::span<const Point3> net_;
    std::vector<Hit> hits_;
    std::vector<Point3> points_;
    std::vector<KeptFacet> hits_of_;
    std::vector<RefineTarget> multi_hits_;
    std::size_t multi_hit_facets_ = 0;
};

}  // namespace

MeshRestrictedDelaunayResult restricted_delaunay_on_mesh(std::span<const Point3> samples,
                                                         std::span<const std::uint32_t> net_in,
                                                         const SurfaceMesh& surface,
                                                         const MeshRestrictedDelaunayOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const std::string who = "restricted_delaunay_on_mesh";
    detail::check_samples(samples, who);
    if (net_in.size() < 4) throw InvalidInput(who + ": the net needs at least 4 samples, got " + std::to_string(net_in.size()));
    std::vector<char> in_net(samples.size(), 0);
    for (std::uint32_t i : net_in) {
        if (i >= samples.size())
            throw InvalidInput(who + ": net index " + std::to_string(i) + " is not a sample (" +
                               std::to_string(samples.size()) + " samples)");
        in_net[i] = 1;
    }
    MeshCheckOptions co;
    co.require_closed = true;
    co.check_degenerate = false;
    const CheckReport target = check_mesh(surface, co);
    if (!target.ok() || surface.n_faces() == 0)
        throw InvalidInput(who + ": the surface is not a closed oriented 2-manifold:\n" + target.summary("  "));

    const MeshSurface mesh_surface(surface);
    const double diag = mesh_surface.box.diagonal();
    PointGrid pool(std::max(diag / std::sqrt(static_cast<double>(samples.size())), 1e-300));
    for (std::uint32_t i = 0; i < samples.size(); ++i) pool.insert(i, samples[i]);
    auto sample_at = [&](std::uint32_t i) { return samples[i]; };

    MeshRestrictedDelaunayResult result;
    MeshRestrictedDelaunayReport& report = result.report;
    report.samples = samples.size();
    std::vector<std::uint32_t> net;
    for (std::uint32_t i = 0; i < samples.size(); ++i)
        if (in_net[i]) net.push_back(i);
    report.net = net.size();

    std::string last_problem;
    std::optional<MeshRestrictedDelaunayResult> best;  // the last correct result
    std::vector<std::uint32_t> last_defects;  // pool indices of the last round's defect vertices
    std::vector<char> dropped(samples.size(), 0);
    for (std::size_t round = 0; round < std::max<std::size_t>(options.max_rounds, 1); ++round) {
        ++report.rounds;
        std::vector<Point3> pts;
        pts.reserve(net.size());
        for (std::uint32_t i : net) pts.push_back(samples[i]);
        MeshOracle oracle(mesh_surface, pts);
        const std::vector<IndexTriangle> facets = detail::restricted_facets(pts, oracle, report.delaunay_cells, who);
        const auto defects = detail::find_manifold_defects(facets, pts.size());

        // Where the net is too sparse, as surface points x with the radius of the empty ball
        // about x through the facet's vertices: every multiple hit, the hits of the facets
        // around each defect, and (optionally) of the facets whose diametric ball holds a
        // net point.
        std::vector<RefineTarget> targets = oracle.multi_hits();
        std::vector<char> bad(pts.size(), 0);
        for (std::uint32_t v : defects.vertices) bad[v] = 1;
        for (const auto& k : oracle.kept())
            if (bad[k.t[0]] || bad[k.t[1]] || bad[k.t[2]]) {
                targets.push_back(k.target);
                targets.back().required = true;
            }
        double rmax = 0;
        for (const auto& t : facets) rmax = std::max(rmax, circumradius(pts[t[0]], pts[t[1]], pts[t[2]]));
        if (!std::isfinite(rmax)) rmax = 0;
        std::size_t nonempty_balls = 0;
        if (options.refine_diametric_balls) {
            if (rmax > 0) {
                PointGrid g(rmax);
                for (std::uint32_t k = 0; k < pts.size(); ++k) g.insert(k, pts[k]);
                for (const auto& k : oracle.kept())
                    if (ball_holds_point(pts, k.t, g)) {
                        ++nonempty_balls;
                        targets.push_back(k.target);
                    }
            }
        }
        bool correct = false;
        if (facets.empty()) {
            last_problem = "no Delaunay facet of the net meets the surface";
        } else if (!defects.ok()) {
            last_problem = "not a 2-manifold: " + defects.describe() + " near " + where(pts[defects.vertices.front()]);
        } else {
            auto compact = detail::compact_soup(pts, facets);
            SurfaceMesh mesh = SurfaceMesh::from_soup(compact.soup);
            const CheckReport got = check_mesh(mesh, co);
            if (!got.ok()) {
                last_problem = "not a closed 2-manifold:\n" + got.summary("  ");
            } else if (got.integer("euler") != target.integer("euler") || got.integer("components") != target.integer("components")) {
                last_problem = "Euler characteristic " + std::to_string(got.integer("euler")) + " and " +
                               std::to_string(got.integer("components")) + " components instead of " +
                               std::to_string(target.integer("euler")) + " and " + std::to_string(target.integer("components"));
                // No visible cause: refine where facets turn by more than 60 degrees from the
                // surface, or everywhere when none does.
                std::vector<RefineTarget> more;
                for (const auto& k : oracle.kept())
                    if (k.cos_surface < 0.5) more.push_back(k.target);
                if (more.empty())
                    for (const auto& k : oracle.kept()) more.push_back(k.target);
                for (RefineTarget& x : more) x.required = true;
                targets.insert(targets.end(), more.begin(), more.end());
            } else {
                correct = true;
                best.emplace();
                best->mesh = std::move(mesh);
                MeshRestrictedDelaunayReport& r = best->report;
                r = report;
                r.euler = got.integer("euler");
                for (std::uint32_t k : compact.vertex_sample) r.vertex_sample.push_back(net[k]);
                r.multi_hit_facets = oracle.multi_hit_facets();
                r.nonempty_balls = nonempty_balls;
                r.facets = facets.size();
                r.vertices_used = r.vertex_sample.size();
                r.unused_samples = samples.size() - r.vertices_used;
                r.added = net.size() - report.net;
            }
        }
        if (!correct) {
            report.defect_points.clear();
            for (std::uint32_t v : defects.vertices) report.defect_points.push_back(pts[v]);
            for (const RefineTarget& x : targets)
                if (x.required && defects.vertices.empty()) report.defect_points.push_back(x.p);
        }
        // One sample per target, as far from the net as possible: among the samples in the
        // target's empty ball (closer to x than the facet's vertices), the one farthest from
        // the net and the samples added before it; without any, the sample nearest to x
        // (required targets only). A target that is not required takes no sample closer to
        // the net than min_spacing_factor times the largest facet circumradius.
        const double min_spacing = options.min_spacing_factor * rmax;
        PointGrid near(std::max(diag / std::sqrt(static_cast<double>(pts.size())), 1e-300));
        for (std::uint32_t i : net) near.insert(i, samples[i]);
        std::vector<std::uint32_t> add;
        for (const RefineTarget& x : targets) {
            std::uint32_t pick = kNone;
            double pick_d = -1;
            pool.for_each_candidate(x.p, x.r, [&](std::uint32_t i) {
                if (in_net[i] || dropped[i] || !(distance(samples[i], x.p) < x.r)) return;
                const double d = near.nearest(samples[i], sample_at, [](std::uint32_t) { return true; }).second;
                if (d > pick_d || (d == pick_d && i < pick)) {
                    pick_d = d;
                    pick = i;
                }
            });
            if (pick == kNone && x.required)
                pick = pool.nearest(x.p, sample_at, [&](std::uint32_t i) { return !in_net[i] && !dropped[i]; }).first;
            if (pick >= samples.size() || (!x.required && pick_d < min_spacing)) continue;
            in_net[pick] = 1;
            near.insert(pick, samples[pick]);
            add.push_back(pick);
        }
        // A defect at exactly the net vertices of the last round's is not helped by more
        // samples: those vertices leave the net for good.
        std::vector<std::uint32_t> here;
        for (std::uint32_t v : defects.vertices) here.push_back(net[v]);
        std::size_t drop = 0;
        if (!here.empty() && here == last_defects)
            for (std::uint32_t i : here)
                if (!dropped[i]) {
                    dropped[i] = 1;
                    in_net[i] = 0;
                    ++drop;
                }
        last_defects = std::move(here);
        if (add.empty() && drop == 0) break;
        net.insert(net.end(), add.begin(), add.end());
        if (drop > 0) std::erase_if(net, [&](std::uint32_t i) { return dropped[i] != 0; });
        std::sort(net.begin(), net.end());
    }
    if (best) {
        best->report.correct = true;
        best->report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return std::move(*best);
    }
    if (!options.throw_on_failure) {
        report.correct = false;
        report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return result;
    }
    throw InvalidInput(who + ": no restricted Delaunay triangulation with the surface's topology after " +
                       std::to_string(report.rounds) + " rounds (" + std::to_string(net.size()) +
                       " net samples of " + std::to_string(samples.size()) + "): " + last_problem +
                       "; the samples are too sparse for this surface there");
}

}  // namespace dynmesh
