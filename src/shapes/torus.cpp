#include <algorithm>
#include <cmath>

#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "spec_format.hpp"

namespace dynmesh {

Torus::Torus(const Point3& center, double major_radius, double minor_radius)
    : center_(center), major_(major_radius), minor_(minor_radius) {
    detail::check_center("Torus", center);
    detail::check_radius("Torus", "the major radius R", major_radius);
    detail::check_radius("Torus", "the minor radius r", minor_radius);
    if (!(minor_radius < major_radius))
        throw InvalidInput(
            "Torus: the minor radius r = " + detail::format_number(minor_radius) +
            " must be smaller than the major radius R = " + detail::format_number(major_radius));
}

std::string Torus::spec() const { return detail::format_spec("torus", {major_, minor_}, center_); }

double Torus::value(const Point3& x) const {
    const Vec3 d = x - center_;
    const double rho = std::hypot(d.x, d.y);
    const double z2r2 = d.z * d.z - minor_ * minor_;
    const double inner = (rho - major_) * (rho - major_) + z2r2;  // sign carrier
    const double outer = (rho + major_) * (rho + major_) + z2r2;  // > 0 always
    return inner * outer / (8.0 * major_ * major_ * minor_);
}

double Torus::signed_distance(const Point3& x) const {
    const Vec3 d = x - center_;
    return std::hypot(std::hypot(d.x, d.y) - major_, d.z) - minor_;
}

Vec3 Torus::normal(const Point3& x) const {
    const Vec3 d = x - center_;
    const double rho = std::hypot(d.x, d.y);
    const double ux = rho > 0 ? d.x / rho : 1.0, uy = rho > 0 ? d.y / rho : 0.0;
    const Vec3 w = d - Vec3{major_ * ux, major_ * uy, 0.0};  // from the core circle
    const double l = norm(w);
    return l > 0 ? w / l : Vec3{ux, uy, 0.0};
}

Point3 Torus::closest_point(const Point3& x) const {
    const Vec3 d = x - center_;
    const double rho = std::hypot(d.x, d.y);
    const double ux = rho > 0 ? d.x / rho : 1.0, uy = rho > 0 ? d.y / rho : 0.0;
    return center_ + Vec3{major_ * ux, major_ * uy, 0.0} + minor_ * normal(x);
}

double Torus::reach() const { return std::min(minor_, major_ - minor_); }

double Torus::local_feature_size(const Point3& x) const {
    const Vec3 s = closest_point(x) - center_;
    return std::min(minor_, std::hypot(s.x, s.y));
}

double Torus::area() const { return 4.0 * kPi * kPi * major_ * minor_; }

Bbox3 Torus::bbox() const {
    const Vec3 e{major_ + minor_, major_ + minor_, minor_};
    return {center_ - e, center_ + e};
}

Point3 Torus::interior_point() const { return center_ + Vec3{major_, 0.0, 0.0}; }

std::vector<Point3> Torus::sample_uniform(std::size_t n, std::uint64_t seed) const {
    Rng rng(seed);
    std::vector<Point3> out;
    out.reserve(n);
    const double two_pi = 2.0 * kPi;
    while (out.size() < n) {
        // The area element is r (R + r cos v) du dv: accept v with that weight.
        const double v = rng.uniform(0.0, two_pi);
        const double ring = major_ + minor_ * std::cos(v);
        if (rng.uniform() * (major_ + minor_) >= ring) continue;
        const double u = rng.uniform(0.0, two_pi);
        out.push_back(center_ + Vec3{ring * std::cos(u), ring * std::sin(u), minor_ * std::sin(v)});
    }
    return out;
}

}  // namespace dynmesh
