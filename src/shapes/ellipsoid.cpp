#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "spec_format.hpp"

namespace dynmesh {
namespace {

// ---- Eberly, "Distance from a point to an ellipse, an ellipsoid, or a hyperellipsoid" ----
// Both solvers take semi-axes sorted e0 >= e1 (>= e2) > 0 and a query in the first quadrant
// (octant), y_i >= 0, and return the distance and the nearest point x (also with x_i >= 0).
// The nearest point is x_i = e_i^2 y_i / (t + e_i^2) for the largest root t of
// F(t) = sum_i (e_i y_i / (t + e_i^2))^2 - 1; with s = t / e_min^2 and r_i = (e_i / e_min)^2 the
// root is bracketed and found by bisection until the midpoint stops moving.

constexpr int kMaxBisections =
    std::numeric_limits<double>::digits - std::numeric_limits<double>::min_exponent + 8;

double robust_length(double a, double b) { return std::hypot(a, b); }
double robust_length(double a, double b, double c) {
    const double m = std::max({std::abs(a), std::abs(b), std::abs(c)});
    if (m == 0) return 0;
    const double x = a / m, y = b / m, z = c / m;
    return m * std::sqrt(x * x + y * y + z * z);
}

/// Bisection on [s0, s1] for the root of the decreasing function g (Eberly's method), to
/// full double precision.
template <class G>
double bisect_root(double s0, double s1, G&& g_of) {
    double s = 0;
    for (int i = 0; i < kMaxBisections; ++i) {
        s = 0.5 * (s0 + s1);
        if (s == s0 || s == s1) break;
        const double g = g_of(s);
        if (g > 0) {
            s0 = s;
        } else if (g < 0) {
            s1 = s;
        } else {
            break;
        }
    }
    return s;
}

double get_root(double r0, double z0, double z1, double g) {
    const double n0 = r0 * z0;
    return bisect_root(z1 - 1, g < 0 ? 0 : robust_length(n0, z1) - 1, [&](double s) {
        const double ratio0 = n0 / (s + r0), ratio1 = z1 / (s + 1);
        return ratio0 * ratio0 + ratio1 * ratio1 - 1;
    });
}

double get_root(double r0, double r1, double z0, double z1, double z2, double g) {
    const double n0 = r0 * z0, n1 = r1 * z1;
    return bisect_root(z2 - 1, g < 0 ? 0 : robust_length(n0, n1, z2) - 1, [&](double s) {
        const double ratio0 = n0 / (s + r0), ratio1 = n1 / (s + r1), ratio2 = z2 / (s + 1);
        return ratio0 * ratio0 + ratio1 * ratio1 + ratio2 * ratio2 - 1;
    });
}

double distance_point_ellipse(double e0, double e1, double y0, double y1, double& x0, double& x1) {
    if (y1 > 0) {
        if (y0 > 0) {
            const double z0 = y0 / e0, z1 = y1 / e1;
            const double g = z0 * z0 + z1 * z1 - 1;
            if (g != 0) {
                const double r0 = (e0 / e1) * (e0 / e1);
                const double s = get_root(r0, z0, z1, g);
                x0 = r0 * y0 / (s + r0);
                x1 = y1 / (s + 1);
                return std::hypot(x0 - y0, x1 - y1);
            }
            x0 = y0;
            x1 = y1;
            return 0;
        }
        x0 = 0;
        x1 = e1;
        return std::abs(y1 - e1);
    }
    const double numer0 = e0 * y0, denom0 = e0 * e0 - e1 * e1;
    if (numer0 < denom0) {  // on the medial segment: the nearest point leaves the axis
        const double xde0 = numer0 / denom0;
        x0 = e0 * xde0;
        x1 = e1 * std::sqrt(std::max(0.0, 1 - xde0 * xde0));
        return std::hypot(x0 - y0, x1);
    }
    x0 = e0;
    x1 = 0;
    return std::abs(y0 - e0);
}

double distance_point_ellipsoid(const double e[3], const double y[3], double x[3]) {
    if (y[2] > 0) {
        if (y[1] > 0) {
            if (y[0] > 0) {
                const double z0 = y[0] / e[0], z1 = y[1] / e[1], z2 = y[2] / e[2];
                const double g = z0 * z0 + z1 * z1 + z2 * z2 - 1;
                if (g != 0) {
                    const double r0 = (e[0] / e[2]) * (e[0] / e[2]);
                    const double r1 = (e[1] / e[2]) * (e[1] / e[2]);
                    const double s = get_root(r0, r1, z0, z1, z2, g);
                    x[0] = r0 * y[0] / (s + r0);
                    x[1] = r1 * y[1] / (s + r1);
                    x[2] = y[2] / (s + 1);
                    return robust_length(x[0] - y[0], x[1] - y[1], x[2] - y[2]);
                }
                x[0] = y[0];
                x[1] = y[1];
                x[2] = y[2];
                return 0;
            }
            x[0] = 0;
            return distance_point_ellipse(e[1], e[2], y[1], y[2], x[1], x[2]);
        }
        if (y[0] > 0) {
            x[1] = 0;
            return distance_point_ellipse(e[0], e[2], y[0], y[2], x[0], x[2]);
        }
        x[0] = 0;
        x[1] = 0;
        x[2] = e[2];
        return std::abs(y[2] - e[2]);
    }
    // y2 == 0: inside the medial region the nearest point leaves the plane.
    const double denom0 = e[0] * e[0] - e[2] * e[2], denom1 = e[1] * e[1] - e[2] * e[2];
    const double numer0 = e[0] * y[0], numer1 = e[1] * y[1];
    if (numer0 < denom0 && numer1 < denom1) {
        const double xde0 = numer0 / denom0, xde1 = numer1 / denom1;
        const double discr = 1 - xde0 * xde0 - xde1 * xde1;
        if (discr > 0) {
            x[0] = e[0] * xde0;
            x[1] = e[1] * xde1;
            x[2] = e[2] * std::sqrt(discr);
            return robust_length(x[0] - y[0], x[1] - y[1], x[2]);
        }
    }
    x[2] = 0;
    return distance_point_ellipse(e[0], e[1], y[0], y[1], x[0], x[1]);
}

/// Distance from (q0, q1), q_i >= 0, to the filled ellipse with semi-axes m0 >= m1 >= 0.
double distance_to_filled_ellipse(double m0, double m1, double q0, double q1) {
    if (m1 <= 0) return std::hypot(std::max(0.0, q0 - m0), q1);  // a segment or a point
    const double z0 = q0 / m0, z1 = q1 / m1;
    if (z0 * z0 + z1 * z1 <= 1) return 0;
    double x0 = 0, x1 = 0;
    return distance_point_ellipse(m0, m1, q0, q1, x0, x1);
}

/// Surface area of the ellipsoid with semi-axes a >= b >= c > 0 (Legendre).
double ellipsoid_area(double a, double b, double c) {
    if (a == c) return 4 * kPi * a * a;
    const double cos_phi = c / a;
    const double phi = std::acos(cos_phi), sin_phi = std::sin(phi);
    const double k2 = (a * a * (b * b - c * c)) / (b * b * (a * a - c * c));
    const double k = std::sqrt(std::clamp(k2, 0.0, 1.0));
    const double e = std::ellint_2(k, phi), f = std::ellint_1(k, phi);
    return 2 * kPi * c * c +
           2 * kPi * a * b / sin_phi * (e * sin_phi * sin_phi + f * cos_phi * cos_phi);
}

}  // namespace

Ellipsoid::Ellipsoid(const Point3& center, double a, double b, double c)
    : center_(center), axes_{a, b, c} {
    detail::check_center("Ellipsoid", center);
    detail::check_radius("Ellipsoid", "the semi-axis a", a);
    detail::check_radius("Ellipsoid", "the semi-axis b", b);
    detail::check_radius("Ellipsoid", "the semi-axis c", c);
    std::iota(order_.begin(), order_.end(), 0);
    std::stable_sort(order_.begin(), order_.end(), [&](int i, int j) {
        return axes_[static_cast<std::size_t>(i)] > axes_[static_cast<std::size_t>(j)];
    });
    const double e0 = axes_[static_cast<std::size_t>(order_[0])];
    const double e1 = axes_[static_cast<std::size_t>(order_[1])];
    const double e2 = axes_[static_cast<std::size_t>(order_[2])];
    reach_ = e2 * e2 / e0;
    medial_ = {(e0 - e2) * (e0 + e2) / e0, (e1 - e2) * (e1 + e2) / e1};
    area_ = ellipsoid_area(e0, e1, e2);
}

std::string Ellipsoid::spec() const {
    return detail::format_spec("ellipsoid", {axes_.x, axes_.y, axes_.z}, center_);
}

double Ellipsoid::value(const Point3& x) const {
    const Vec3 d = x - center_;
    const double u = d.x / axes_.x, v = d.y / axes_.y, w = d.z / axes_.z;
    return u * u + v * v + w * w - 1;
}

Point3 Ellipsoid::closest_offset(const Vec3& d, double* distance) const {
    double e[3], y[3], xs[3];
    for (std::size_t k = 0; k < 3; ++k) {
        const auto i = static_cast<std::size_t>(order_[k]);
        e[k] = axes_[i];
        y[k] = std::abs(d[i]);
    }
    const double dist = distance_point_ellipsoid(e, y, xs);
    if (distance != nullptr) *distance = dist;
    Vec3 out;
    for (std::size_t k = 0; k < 3; ++k) {
        const auto i = static_cast<std::size_t>(order_[k]);
        out[i] = std::copysign(xs[k], d[i]);
    }
    return out;
}

double Ellipsoid::signed_distance(const Point3& x) const {
    double dist = 0;
    (void)closest_offset(x - center_, &dist);
    return value(x) < 0 ? -dist : dist;
}

Point3 Ellipsoid::closest_point(const Point3& x) const {
    return center_ + closest_offset(x - center_, nullptr);
}

Vec3 Ellipsoid::normal(const Point3& x) const {
    const Vec3 s = closest_offset(x - center_, nullptr);
    return normalized(
        Vec3{s.x / (axes_.x * axes_.x), s.y / (axes_.y * axes_.y), s.z / (axes_.z * axes_.z)});
}

double Ellipsoid::local_feature_size(const Point3& x) const {
    const Vec3 s = closest_offset(x - center_, nullptr);
    const double q0 = std::abs(s[static_cast<std::size_t>(order_[0])]);
    const double q1 = std::abs(s[static_cast<std::size_t>(order_[1])]);
    const double h = std::abs(s[static_cast<std::size_t>(order_[2])]);
    return std::hypot(h, distance_to_filled_ellipse(medial_[0], medial_[1], q0, q1));
}

Bbox3 Ellipsoid::bbox() const { return {center_ - axes_, center_ + axes_}; }

std::vector<Point3> Ellipsoid::sample_uniform(std::size_t n, std::uint64_t seed) const {
    Rng rng(seed);
    std::vector<Point3> out;
    out.reserve(n);
    const double e_min = axes_[static_cast<std::size_t>(order_[2])];
    while (out.size() < n) {
        const Vec3 u = rng.unit_vector();
        const double a = u.x / axes_.x, b = u.y / axes_.y, c = u.z / axes_.z;
        const double weight = e_min * std::sqrt(a * a + b * b + c * c);  // in (0, 1]
        if (rng.uniform() >= weight) continue;
        out.push_back(center_ + Vec3{axes_.x * u.x, axes_.y * u.y, axes_.z * u.z});
    }
    return out;
}

}  // namespace dynmesh
