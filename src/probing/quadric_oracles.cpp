/// Sphere, ellipsoid and disjoint balls: closed-form roots of a quadric along the ray.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "dynmesh/error.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "probe_common.hpp"

namespace dynmesh {
namespace {

double max_axis(const Ellipsoid& e) {
    const Vec3& a = e.semi_axes();
    return std::max({a.x, a.y, a.z});
}

/// n points of sample_uniform for about one point per spacing² of area.
std::size_t count_for(double area, double spacing) {
    DYNMESH_CHECK(std::isfinite(spacing) && spacing > 0,
                  "GroundTruth::sample_surface: the spacing must be a positive number");
    const double n = std::ceil(area / (spacing * spacing));
    DYNMESH_CHECK(n <= 1e8, "GroundTruth::sample_surface: spacing too small (more than 1e8 points)");
    return static_cast<std::size_t>(std::max(n, 1.0));
}

/// The candidate entry of the ray into the ball (c, r); `near` when |s − c| − r is within tau.
std::optional<ProbeHit> ball_entry(const Point3& c, double r, const Point3& s, const Vec3& d,
                                   double tau, double* cos_out) {
    const Vec3 m = s - c;
    const double dist = norm(m);
    const bool near = std::fabs(dist - r) <= tau;
    const double cos0 = dist > 0 ? dot(m, d) / dist : -1;
    const auto root = detail::quadric_entry(1, dot(m, d), sqnorm(m) - r * r, near, cos0);
    if (!root) return std::nullopt;
    const Point3 x = s + root->t * d;
    const Vec3 n = x - c;
    if (root->touch) {
        if (norm(n) - r > tau) return std::nullopt;  // a clean miss
        *cos_out = 0;
    } else {
        *cos_out = dot(n, d) / r;
    }
    const double nn = norm(n);
    return ProbeHit{nn > 0 ? c + n * (r / nn) : x, root->t, false};
}

}  // namespace

// ---- sphere ------------------------------------------------------------------------------

SphereOracle::SphereOracle(const Sphere& sphere, OracleOptions options)
    : ProbeObject(sphere.radius(), options), shape_(sphere) {}

double SphereOracle::signed_distance(const Point3& p) const { return shape_.signed_distance(p); }

std::vector<Point3> SphereOracle::sample_surface(double spacing) const {
    return shape_.sample_uniform(count_for(area(), spacing), 1);
}

std::optional<ProbeHit> SphereOracle::cast_checked(const Point3& s, const Vec3& d, double t_max,
                                                   bool strict) const {
    double cos = 0;
    auto hit = ball_entry(shape_.center(), shape_.radius(), s, d, tolerance(), &cos);
    if (!hit || !accept(*hit, cos, t_max, strict)) return std::nullopt;
    return hit;
}

// ---- ellipsoid ---------------------------------------------------------------------------

EllipsoidOracle::EllipsoidOracle(const Ellipsoid& ellipsoid, OracleOptions options)
    : ProbeObject(max_axis(ellipsoid), options), shape_(ellipsoid) {}

double EllipsoidOracle::signed_distance(const Point3& p) const {
    return shape_.signed_distance(p);
}

double EllipsoidOracle::diameter() const { return 2 * max_axis(shape_); }

std::vector<Point3> EllipsoidOracle::sample_surface(double spacing) const {
    return shape_.sample_uniform(count_for(area(), spacing), 1);
}

std::optional<ProbeHit> EllipsoidOracle::cast_checked(const Point3& s, const Vec3& d,
                                                      double t_max, bool strict) const {
    const Vec3& e = shape_.semi_axes();
    const auto scale = [&](const Vec3& v) { return Vec3{v.x / e.x, v.y / e.y, v.z / e.z}; };
    const Vec3 m = scale(s - shape_.center()), ds = scale(d);
    const bool near = std::fabs(shape_.signed_distance(s)) <= tolerance();
    const auto cos_at = [&](const Point3& x) { return dot(shape_.normal(x), d); };
    const auto root = detail::quadric_entry(sqnorm(ds), dot(m, ds), sqnorm(m) - 1, near,
                                            near ? cos_at(s) : 0.0);
    if (!root) return std::nullopt;
    const Point3 x = s + root->t * d;
    double cos = 0;
    if (root->touch) {
        if (shape_.signed_distance(x) > tolerance()) return std::nullopt;
    } else {
        cos = cos_at(x);
    }
    ProbeHit hit{root->touch || near ? shape_.closest_point(x) : x, root->t, false};
    if (!accept(hit, cos, t_max, strict)) return std::nullopt;
    return hit;
}

// ---- disjoint balls ----------------------------------------------------------------------

namespace {
double balls_scale(const std::vector<Ball>& balls) {
    double s = 0;
    for (const Ball& b : balls) s = std::max(s, norm(b.center) + b.radius);
    return s;
}
const std::vector<Ball>& checked(const std::vector<Ball>& balls) {
    DYNMESH_CHECK(!balls.empty(), "BallsOracle: no ball");
    for (std::size_t i = 0; i < balls.size(); ++i) {
        const Ball& b = balls[i];
        if (!is_finite(b.center) || !std::isfinite(b.radius) || !(b.radius > 0))
            throw InvalidInput("BallsOracle: ball " + std::to_string(i) +
                                   " needs a finite centre and a positive radius",
                               i);
        for (std::size_t j = 0; j < i; ++j) {
            const double gap = distance(b.center, balls[j].center) - b.radius - balls[j].radius;
            if (!(gap > 0))
                throw InvalidInput("BallsOracle: balls " + std::to_string(j) + " and " +
                                       std::to_string(i) + " overlap or touch (gap " +
                                       std::to_string(gap) + "); the balls must be disjoint",
                                   i);
        }
    }
    return balls;
}
}  // namespace

BallsOracle::BallsOracle(std::vector<Ball> balls, OracleOptions options)
    : ProbeObject(balls_scale(checked(balls)), options), balls_(std::move(balls)) {
    reach_ = INFINITY;
    diameter_ = 0;
    for (std::size_t i = 0; i < balls_.size(); ++i) {
        reach_ = std::min(reach_, balls_[i].radius);
        diameter_ = std::max(diameter_, 2 * balls_[i].radius);
        for (std::size_t j = 0; j < i; ++j) {
            const double c = dynmesh::distance(balls_[i].center, balls_[j].center);
            reach_ = std::min(reach_, 0.5 * (c - balls_[i].radius - balls_[j].radius));
            diameter_ = std::max(diameter_, c + balls_[i].radius + balls_[j].radius);
        }
    }
}

double BallsOracle::signed_distance(const Point3& p) const {
    double best = INFINITY;
    for (const Ball& b : balls_) best = std::min(best, dynmesh::distance(p, b.center) - b.radius);
    return best;
}

double BallsOracle::area() const {
    double a = 0;
    for (const Ball& b : balls_) a += 4 * std::numbers::pi * b.radius * b.radius;
    return a;
}

std::vector<Point3> BallsOracle::sample_surface(double spacing) const {
    std::vector<Point3> out;
    for (const Ball& b : balls_) {
        const Sphere s(b.center, b.radius);
        const auto pts = s.sample_uniform(count_for(s.area(), spacing), 1);
        out.insert(out.end(), pts.begin(), pts.end());
    }
    return out;
}

std::optional<ProbeHit> BallsOracle::cast_checked(const Point3& s, const Vec3& d, double t_max,
                                                  bool strict) const {
    std::optional<ProbeHit> best;
    for (const Ball& b : balls_) {
        double cos = 0;
        auto hit = ball_entry(b.center, b.radius, s, d, tolerance(), &cos);
        if (!hit || !accept(*hit, cos, t_max, strict)) continue;
        if (!best || hit->t < best->t) best = hit;
    }
    return best;
}

}  // namespace dynmesh
