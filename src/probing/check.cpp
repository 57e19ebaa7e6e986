/// check_probing: a probing run's output against the object's ground truth.
#include "dynmesh/probing/check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/metrics/hausdorff.hpp"
#include "probe_common.hpp"

namespace dynmesh {
namespace {

double point_segment_distance(const Point3& p, const Point3& a, const Point3& b) {
    const Vec3 ab = b - a;
    const double l2 = sqnorm(ab);
    const double t = l2 > 0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
    return distance(p, a + t * ab);
}

double orient2(const Point3& a, const Point3& b, const Point3& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// Do the closed segments ab and cd meet (crossing, touching or overlapping)?
bool segments_meet(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
    const double o1 = orient2(a, b, c), o2 = orient2(a, b, d), o3 = orient2(c, d, a), o4 = orient2(c, d, b);
    const auto sign = [](double v) { return (v > 0) - (v < 0); };
    // q on the segment pq's line, within its bounding box.
    const auto within = [](const Point3& p, const Point3& q, const Point3& r) {
        return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
               r.y <= std::max(p.y, q.y);
    };
    if (sign(o1) * sign(o2) < 0 && sign(o3) * sign(o4) < 0) return true;
    return (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) || (o3 == 0 && within(c, d, a)) ||
           (o4 == 0 && within(c, d, b));
}

/// 2D topology: every vertex in exactly one closed loop, one edge in and one out; no two
/// segments that do not share a vertex cross. Returns the problems.
std::vector<std::string> check_polygons(const std::vector<Point3>& pts,
                                        const std::vector<std::vector<std::uint32_t>>& polygons,
                                        std::size_t& edges) {
    std::vector<std::string> problems;
    std::vector<int> uses(pts.size(), 0);
    std::vector<std::array<std::uint32_t, 2>> segs;
    for (std::size_t k = 0; k < polygons.size(); ++k) {
        const auto& loop = polygons[k];
        if (loop.size() < 4 || loop.front() != loop.back()) {
            problems.push_back("polygon " + std::to_string(k) + " is not closed (" + std::to_string(loop.size()) +
                               " indices)");
            continue;
        }
        for (std::size_t i = 0; i + 1 < loop.size(); ++i) {
            ++uses[loop[i]];
            segs.push_back({loop[i], loop[i + 1]});
        }
    }
    edges = segs.size();
    for (std::size_t v = 0; v < pts.size(); ++v)
        if (uses[v] != 1 && problems.size() < 20)
            problems.push_back("vertex " + std::to_string(v) + " is on " + std::to_string(uses[v]) +
                               " polygon corners (expected 1)");
    double cell = 0;
    for (const auto& s : segs) cell = std::max(cell, distance(pts[s[0]], pts[s[1]]));
    if (segs.empty() || !(cell > 0)) return problems;
    // Segments bucketed by the grid cell of their first end; a crossing pair lies in
    // neighbouring cells (both are shorter than the cell).
    PointGrid grid(cell);
    for (std::uint32_t i = 0; i < segs.size(); ++i) grid.insert(i, pts[segs[i][0]]);
    std::size_t crossings = 0;
    for (std::uint32_t i = 0; i < segs.size(); ++i) {
        grid.for_each_candidate(pts[segs[i][0]], 2 * cell, [&](std::uint32_t j) {
            if (j <= i) return;
            const auto &s = segs[i], &t = segs[j];
            if (s[0] == t[0] || s[0] == t[1] || s[1] == t[0] || s[1] == t[1]) return;
            if (segments_meet(pts[s[0]], pts[s[1]], pts[t[0]], pts[t[1]])) ++crossings;
        });
    }
    if (crossings > 0) problems.push_back(std::to_string(crossings) + " pairs of polygon edges without a common vertex meet");
    return problems;
}

}  // namespace

double surface_hausdorff(const TriangleSoup& mesh, const GroundTruth& truth, const std::vector<Point3>& surface_samples) {
    const SurfaceMesh m = SurfaceMesh::from_soup(mesh);
    double to_s = 0;
    for (const Point3& p : mesh_sample_points(m, 2)) to_s = std::max(to_s, truth.distance(p));
    return std::max(to_s, max_distance_to_mesh(m, surface_samples));
}

double polyline_hausdorff(const std::vector<Point3>& points, const std::vector<std::vector<std::uint32_t>>& polygons,
                          const GroundTruth& truth, const std::vector<Point3>& curve_samples) {
    double worst = 0, longest = 0;
    // Polyline to curve: each segment at its ends and 7 inner points.
    std::vector<std::vector<std::uint32_t>> incident(points.size());
    for (const auto& loop : polygons)
        for (std::size_t i = 0; i + 1 < loop.size(); ++i) {
            const Point3 &a = points[loop[i]], &b = points[loop[i + 1]];
            longest = std::max(longest, distance(a, b));
            incident[loop[i]].push_back(loop[i + 1]);
            incident[loop[i + 1]].push_back(loop[i]);
            for (int k = 0; k <= 8; ++k) worst = std::max(worst, truth.distance(a + (k / 8.0) * (b - a)));
        }
    if (points.empty() || !(longest > 0)) return worst;
    // Curve to polyline: the nearest segment is incident to a vertex within (distance to the
    // nearest vertex) + (longest segment).
    PointGrid grid(longest);
    for (std::uint32_t v = 0; v < points.size(); ++v) grid.insert(v, points[v]);
    const auto pos = [&](std::uint32_t v) { return points[v]; };
    for (const Point3& q : curve_samples) {
        const auto [nv, dv] = grid.nearest(q, pos, [](std::uint32_t) { return true; });
        double best = dv;
        grid.for_each_candidate(q, dv + longest, [&](std::uint32_t v) {
            for (std::uint32_t w : incident[v]) best = std::min(best, point_segment_distance(q, points[v], points[w]));
        });
        worst = std::max(worst, best);
    }
    return worst;
}

double default_check_spacing(const GroundTruth& truth, double eps, int dim) {
    return std::max(eps / 4, dim == 3 ? std::sqrt(truth.area() / 2e5) : truth.area() / 2e5);
}

namespace {

/// What check_probing() measures, before it becomes the report's figures.
struct ProbingMeasures {
    std::vector<std::string> problems;
    bool closed_manifold = false;
    long long euler = 0;
    std::size_t components = 0;
    double hausdorff = 0, hausdorff_bound = 0, sample_gap = 0, max_ball_radius = 0;
};

}  // namespace

CheckReport check_probing(const ProbingResult& r, const GroundTruth& truth, const ProbingOptions& options,
                          int dim, const ProbingCheckOptions& check) {
    DYNMESH_CHECK(dim == 2 || dim == 3, "check_probing: dim must be 2 or 3");
    ProbingMeasures out;
    out.problems = r.problems;
    const double eps = r.report.eps > 0 ? r.report.eps : options.eps;
    const auto fail = [&](const std::string& what) { out.problems.push_back(what); };

    // Topology.
    if (dim == 3) {
        try {
            const SurfaceMesh m = SurfaceMesh::from_soup(r.mesh);
            const CheckReport mc = check_mesh(m, {.require_closed = true});
            out.closed_manifold = mc.ok() && mc.integer("faces") > 0;
            out.euler = mc.integer("euler");
            out.components = static_cast<std::size_t>(mc.integer("components"));
            if (!mc.ok()) fail("the output is not a closed oriented 2-manifold: " + mc.summary());
            // Outward: the enclosed volume (sum of signed tetrahedra from any origin) is positive.
            double volume = 0;
            for (const auto& t : r.mesh.triangles)
                volume += dot(r.mesh.points[t[0]], cross(r.mesh.points[t[1]], r.mesh.points[t[2]])) / 6;
            if (out.closed_manifold && !(volume > 0))
                fail("the output is oriented inward (enclosed volume " + std::to_string(volume) + ")");
        } catch (const Error& e) {
            fail(std::string("the output is not an oriented 2-manifold: ") + e.what());
        }
    } else {
        std::size_t edges = 0;
        const auto problems = check_polygons(r.mesh.points, r.polygons, edges);
        out.closed_manifold = problems.empty() && !r.polygons.empty();
        out.euler = static_cast<long long>(r.mesh.points.size()) - static_cast<long long>(edges);
        out.components = r.polygons.size();
        for (const auto& p : problems) fail("the output polygons: " + p);
        // Counter-clockwise around O: the signed areas add up to a positive total.
        double area = 0;
        for (const auto& loop : r.polygons)
            for (std::size_t k = 0; k + 1 < loop.size(); ++k) {
                const Point3 &p = r.mesh.points[loop[k]], &q = r.mesh.points[loop[k + 1]];
                area += (p.x * q.y - q.x * p.y) / 2;
            }
        if (out.closed_manifold && !(area > 0))
            fail("the output polygons run clockwise (signed area " + std::to_string(area) + ")");
    }
    if (out.euler != truth.euler_characteristic())
        fail("Euler characteristic " + std::to_string(out.euler) + ", the object's is " +
             std::to_string(truth.euler_characteristic()));
    if (static_cast<int>(out.components) != truth.components())
        fail(std::to_string(out.components) + " components, the object has " + std::to_string(truth.components()));

    // Ball sizes: the run's own measure, and independently the facets themselves: a facet's
    // circumcircle is a section of its ball, so its circumradius (2D: half its length) is at
    // most eps too.
    out.max_ball_radius = r.report.max_ball_radius;
    if (out.max_ball_radius > eps)
        fail("a restricted ball of radius " + std::to_string(out.max_ball_radius) + " exceeds eps = " +
             std::to_string(eps));
    double circumradius = 0;
    if (dim == 3) {
        for (const auto& t : r.mesh.triangles) {
            const Point3 &a = r.mesh.points[t[0]], &b = r.mesh.points[t[1]], &c = r.mesh.points[t[2]];
            const double area2 = norm(cross(b - a, c - a));
            circumradius = std::max(circumradius, area2 > 0 ? distance(a, b) * distance(b, c) * distance(c, a) / (2 * area2)
                                                            : std::numeric_limits<double>::infinity());
        }
    } else {
        for (const auto& loop : r.polygons)
            for (std::size_t k = 0; k + 1 < loop.size(); ++k)
                circumradius = std::max(circumradius, distance(r.mesh.points[loop[k]], r.mesh.points[loop[k + 1]]) / 2);
    }
    if (circumradius > eps * (1 + 1e-9))
        fail("an output facet has circumradius " + std::to_string(circumradius) + " > eps = " + std::to_string(eps));

    // Samples of S: 2ε-sample and Hausdorff.
    const double spacing = check.spacing > 0 ? check.spacing : default_check_spacing(truth, eps, dim);
    const std::vector<Point3> s_samples = truth.sample_surface(spacing);
    if (!r.sample.empty()) {
        PointGrid grid(eps);
        for (std::uint32_t i = 0; i < r.sample.size(); ++i) grid.insert(i, r.sample[i]);
        const auto pos = [&](std::uint32_t i) { return r.sample[i]; };
        for (const Point3& q : s_samples)
            out.sample_gap = std::max(out.sample_gap, grid.nearest(q, pos, [](std::uint32_t) { return true; }).second);
        if (out.sample_gap > 2 * eps)
            fail("the sample is not a 2eps-sample: a point of S is " + std::to_string(out.sample_gap) +
                 " from every sample (2 eps = " + std::to_string(2 * eps) + ")");
    }
    if (dim == 3 && !r.mesh.triangles.empty() && out.closed_manifold) {
        out.hausdorff = surface_hausdorff(r.mesh, truth, s_samples);
    } else if (dim == 2) {
        out.hausdorff = polyline_hausdorff(r.mesh.points, r.polygons, truth, s_samples);
    }
    out.hausdorff_bound = 4.5 * truth.diameter() * eps * eps / (options.eps_S * options.eps_S);
    if (out.hausdorff > out.hausdorff_bound)
        fail("Hausdorff distance " + std::to_string(out.hausdorff) + " exceeds the bound 4.5 diam eps^2 / eps_S^2 = " +
             std::to_string(out.hausdorff_bound));
    CheckReport rep = CheckReport::of_problems(std::move(out.problems));
    rep.add("euler", out.euler);
    rep.add("components", out.components);
    rep.add("max_ball_radius", out.max_ball_radius);
    rep.add("hausdorff", out.hausdorff);
    rep.add("hausdorff_bound", out.hausdorff_bound);
    rep.add("sample_gap", out.sample_gap);
    rep.add("closed_manifold", out.closed_manifold);
    return rep;
}

}  // namespace dynmesh
