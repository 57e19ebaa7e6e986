/// Closed star-shaped planar curves (circle, smooth star) as prism objects.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "dynmesh/error.hpp"
#include "dynmesh/probing/oracles2.hpp"
#include "probe_common.hpp"

namespace dynmesh {

PlanarStarOracle::PlanarStarOracle(const Point2& center, double radius, double amplitude,
                                   int lobes, OracleOptions options)
    : ProbeObject(radius * (1 + std::fabs(amplitude)), options), center_(center),
      radius_(radius), amplitude_(amplitude), lobes_(lobes) {
    DYNMESH_CHECK(is_finite(center) && std::isfinite(radius) && radius > 0 &&
                      std::isfinite(amplitude) && amplitude >= 0 && amplitude < 1 && lobes >= 1,
                  "PlanarStarOracle: needs a finite centre, R > 0, 0 <= a < 1 and k >= 1");
    const double q = amplitude * lobes / (1 - amplitude);
    lipschitz_ = std::sqrt(1 + q * q);
    // Length and smallest radius of curvature by sampling φ.
    constexpr int n = 100000;
    double min_rc = INFINITY;
    for (int i = 0; i < n; ++i) {
        const double phi = 2 * std::numbers::pi * i / n;
        const double k = lobes_, r = radius_at(phi);
        const double r1 = -amplitude * k * radius * std::sin(k * phi);
        const double r2 = -amplitude * k * k * radius * std::cos(k * phi);
        const double ds = std::sqrt(r * r + r1 * r1);
        length_ += ds * 2 * std::numbers::pi / n;
        const double kappa = std::fabs(r * r + 2 * r1 * r1 - r * r2) / (ds * ds * ds);
        if (kappa > 0) min_rc = std::min(min_rc, 1 / kappa);
    }
    reach_ = std::min(min_rc, (1 - amplitude) * radius);
}

double PlanarStarOracle::radius_at(double phi) const {
    return radius_ * (1 + amplitude_ * std::cos(lobes_ * phi));
}

Point3 PlanarStarOracle::curve_point(double phi) const {
    const double r = radius_at(phi);
    return {center_.x + r * std::cos(phi), center_.y + r * std::sin(phi), 0};
}

double PlanarStarOracle::value(const Point3& p) const {
    const double x = p.x - center_.x, y = p.y - center_.y;
    return std::hypot(x, y) - radius_at(std::atan2(y, x));
}

Vec3 PlanarStarOracle::gradient(const Point3& p) const {
    const double x = p.x - center_.x, y = p.y - center_.y, rho = std::hypot(x, y);
    if (rho == 0) return {1, 0, 0};
    const double phi = std::atan2(y, x);
    const double r1 = -amplitude_ * lobes_ * radius_ * std::sin(lobes_ * phi);
    const Vec3 u{x / rho, y / rho, 0}, v{-y / rho, x / rho, 0};
    return u - (r1 / rho) * v;
}

double PlanarStarOracle::signed_distance(const Point3& p) const {
    return value(p) / lipschitz_;
}

double PlanarStarOracle::distance(const Point3& p) const {
    const Point3 q{p.x, p.y, 0};
    const auto dist = [&](double phi) { return dynmesh::distance(q, curve_point(phi)); };
    constexpr int n = 3600;
    int best = 0;
    double best_d = INFINITY;
    for (int i = 0; i < n; ++i) {
        const double d = dist(2 * std::numbers::pi * i / n);
        if (d < best_d) best_d = d, best = i;
    }
    double lo = 2 * std::numbers::pi * (best - 1) / n, hi = 2 * std::numbers::pi * (best + 1) / n;
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int i = 0; i < 100; ++i) {
        const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
        (dist(a) < dist(b) ? hi : lo) = (dist(a) < dist(b) ? b : a);
    }
    return std::min(best_d, dist(0.5 * (lo + hi)));
}

std::vector<Point3> PlanarStarOracle::sample_surface(double spacing) const {
    DYNMESH_CHECK(std::isfinite(spacing) && spacing > 0 && length_ / spacing <= 1e8,
                  "GroundTruth::sample_surface: the spacing must be positive and not too small");
    const auto n = static_cast<std::size_t>(std::max(3.0, std::ceil(length_ / spacing)));
    std::vector<Point3> out;
    // Arc-length steps: advance φ by spacing / |γ'(φ)| (at most `spacing` apart to first order).
    double phi = 0;
    while (phi < 2 * std::numbers::pi && out.size() < 4 * n) {
        out.push_back(curve_point(phi));
        const double r = radius_at(phi);
        const double r1 = -amplitude_ * lobes_ * radius_ * std::sin(lobes_ * phi);
        phi += spacing / std::sqrt(r * r + r1 * r1);
    }
    return out;
}

Ball PlanarStarOracle::default_omega() const {
    return {interior_point(), 1.1 * (1 + amplitude_) * radius_};
}

std::optional<ProbeHit> PlanarStarOracle::cast_checked(const Point3& s, const Vec3& d,
                                                       double t_max, bool strict) const {
    const double tau = tolerance();
    const auto sd = [&](const Point3& p) { return signed_distance(p); };
    const auto val = [&](const Point3& p) { return value(p); };
    const auto normal = [&](const Point3& p) { return normalized(gradient(p)); };
    const auto radial = [&](const Point3& p) {
        const Point3 c = curve_point(std::atan2(p.y - center_.y, p.x - center_.x));
        return Point3{c.x, c.y, p.z};
    };
    std::optional<ProbeHit> out;
    if (std::fabs(sd(s)) <= tau && dot(normal(s), d) < detail::kGrazingCos) {
        ProbeHit hit{radial(s), 0, false};
        if (accept(hit, dot(normal(s), d), t_max, strict)) return hit;
    }
    const auto finish = [&](double t, bool stalled) {
        const Point3 x = s + t * d;
        ProbeHit hit{stalled ? radial(x) : x, t, false};
        if (!accept(hit, stalled ? 0.0 : dot(normal(x), d), t_max, strict, stalled)) return false;
        out = hit;
        return true;
    };
    // A ray along z (no planar motion) never crosses the prism's wall.
    if (std::hypot(d.x, d.y) < 1e-12) return std::nullopt;
    detail::sphere_trace(s, d, t_max, tau, std::sqrt(8 * reach_ * tau), sd, val, finish);
    return out;
}

}  // namespace dynmesh
