#include <cmath>

#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "spec_format.hpp"

namespace dynmesh {

Sphere::Sphere(const Point3& center, double radius) : center_(center), radius_(radius) {
    detail::check_center("Sphere", center);
    detail::check_radius("Sphere", "the radius", radius);
}

std::string Sphere::spec() const { return detail::format_spec("sphere", {radius_}, center_); }

double Sphere::value(const Point3& x) const {
    return (sqnorm(x - center_) - radius_ * radius_) / (2.0 * radius_);
}

double Sphere::signed_distance(const Point3& x) const { return norm(x - center_) - radius_; }

Point3 Sphere::closest_point(const Point3& x) const { return center_ + radius_ * normal(x); }

Vec3 Sphere::normal(const Point3& x) const {
    const Vec3 d = x - center_;
    const double l = norm(d);
    return l > 0 ? d / l : Vec3{1, 0, 0};
}

double Sphere::local_feature_size(const Point3& /*x*/) const { return radius_; }

double Sphere::area() const { return 4.0 * kPi * radius_ * radius_; }

Bbox3 Sphere::bbox() const {
    const Vec3 e{radius_, radius_, radius_};
    return {center_ - e, center_ + e};
}

std::vector<Point3> Sphere::sample_uniform(std::size_t n, std::uint64_t seed) const {
    Rng rng(seed);
    std::vector<Point3> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) out.push_back(center_ + radius_ * rng.unit_vector());
    return out;
}

}  // namespace dynmesh
