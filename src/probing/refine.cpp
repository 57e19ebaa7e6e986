/// probe_surface: the refinement of refiner.hpp over the 3D Delaunay triangulation, and the
/// helpers both dimensions share (options, enclosure tests). probe_curve: refine_curve.cpp.
#include "dynmesh/probing/refine.hpp"

#include <cmath>
#include <string>

#include "dynmesh/error.hpp"
#include "refiner.hpp"
#include "triangulation3.hpp"

namespace dynmesh {
namespace detail {

double resolved_eps(const ProbingOptions& o) {
    if (o.eps == 0 && o.delta) return probing_eps_from_delta(*o.delta, o.eps_S, o.omega.radius);
    return o.eps;
}

void check_probing_options(const ProbingOptions& o, int dim) {
    const auto bad = [](const std::string& what) { return InvalidInput("probe: " + what); };
    if (!(std::isfinite(o.eps_S) && o.eps_S > 0)) throw bad("eps_S must be finite and > 0");
    if (!(std::isfinite(o.omega.radius) && o.omega.radius > 0) || !is_finite(o.omega.center))
        throw bad("Omega must be a finite ball of positive radius");
    if (o.eps != 0 && o.delta) throw bad("give eps or delta, not both");
    if (o.delta && !(std::isfinite(*o.delta) && *o.delta > 0)) throw bad("delta must be finite and > 0");
    const double eps = resolved_eps(o);
    if (!(std::isfinite(eps) && eps > 0)) throw bad("eps must be finite and > 0");
    if (eps >= 0.091 * o.eps_S && !o.allow_unguaranteed)
        throw bad("eps = " + std::to_string(eps) + " is not below 0.091 * eps_S = " +
                  std::to_string(0.091 * o.eps_S) + ": the output would carry no guarantee" +
                  (o.delta ? " (delta is too large)" : ""));
    if (o.interior_points.empty()) throw bad("no interior point");
    if (dim == 2 && o.omega.center.z != 0) throw bad("a curve lies in the plane z = 0: Omega's centre must too");
    for (const Point3& p : o.interior_points) {
        if (!is_finite(p)) throw bad("an interior point is not finite");
        if (!(distance(p, o.omega.center) < o.omega.radius))
            throw bad("the interior point " + format_point(p) + " lies outside Omega");
        if (dim == 2 && p.z != 0) throw bad("the interior point " + format_point(p) + " is not in the plane z = 0");
    }
    if (o.mode == ProbingMode::Omniscient && o.ground_truth == nullptr)
        throw bad("the omniscient baseline needs the ground truth");
}

namespace {

/// Möller–Trumbore: does the ray p + t·d (t > 0) cross triangle abc? 1 when it does, 0 when it
/// does not, −1 when it passes within rounding of an edge or is parallel (try another ray).
int ray_crosses(const Point3& p, const Vec3& d, const Point3& a, const Point3& b, const Point3& c) {
    const Vec3 e1 = b - a, e2 = c - a, h = cross(d, e2);
    const double det = dot(e1, h);
    const double scale = norm(e1) * norm(e2);
    if (std::fabs(det) <= 1e-12 * scale) return -1;
    const Vec3 s = p - a;
    const double u = dot(s, h) / det;
    const Vec3 q = cross(s, e1);
    const double v = dot(d, q) / det;
    const double t = dot(e2, q) / det;
    constexpr double kEdge = 1e-9;
    if (u < -kEdge || v < -kEdge || u + v > 1 + kEdge || t <= 0) return 0;
    if (u < kEdge || v < kEdge || u + v > 1 - kEdge) return -1;
    return 1;
}

}  // namespace

bool surface_encloses(const TriangleSoup& soup, const std::vector<std::size_t>& faces, const Point3& p) {
    // Rays in a few fixed, irrational directions; the first one that meets no edge decides.
    static const Vec3 kDirections[] = {normalized(Vec3{0.5773, 0.6181, 0.5335}),
                                       normalized(Vec3{-0.2137, 0.8713, -0.4419}),
                                       normalized(Vec3{0.7071, -0.3183, 0.6324}),
                                       normalized(Vec3{-0.6543, -0.5109, 0.5577})};
    for (const Vec3& d : kDirections) {
        int crossings = 0;
        bool clean = true;
        for (std::size_t f : faces) {
            const auto& t = soup.triangles[f];
            const int k = ray_crosses(p, d, soup.points[t[0]], soup.points[t[1]], soup.points[t[2]]);
            if (k < 0) {
                clean = false;
                break;
            }
            crossings += k;
        }
        if (clean) return crossings % 2 == 1;
    }
    return false;
}

bool polygon_encloses(const TriangleSoup& soup, const std::vector<std::uint32_t>& loop, const Point3& p) {
    bool inside = false;
    for (std::size_t k = 0; k + 1 < loop.size(); ++k) {
        const Point3& a = soup.points[loop[k]];
        const Point3& b = soup.points[loop[k + 1]];
        if ((a.y > p.y) != (b.y > p.y)) {
            const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (x > p.x) inside = !inside;
        }
    }
    return inside;
}

}  // namespace detail

double probing_eps_from_delta(double delta, double eps_S, double omega_radius) {
    DYNMESH_CHECK(std::isfinite(delta) && delta > 0, "probing_eps_from_delta: delta must be finite and > 0");
    return eps_S * std::sqrt(delta / (4.5 * 2 * omega_radius));
}

ProbingResult probe_surface(const Oracle& oracle, const ProbingOptions& options) {
    detail::check_probing_options(options, 3);
    detail::Refiner<detail::Triangulation3> r(oracle, options);
    return r.run();
}

}  // namespace dynmesh
