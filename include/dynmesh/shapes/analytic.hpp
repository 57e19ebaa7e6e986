#pragma once
/// \file Sphere, Ellipsoid and Torus: closed smooth surfaces whose geometry (distance, closest
/// point, normal, reach, local feature size, area) is known in closed form or to machine
/// precision. `make_surface` (shapes/surface.hpp) builds them from a spec string.
///
/// Conventions shared by the three classes
/// - `value` is a smooth function, negative inside; near the surface it approximates the
///   signed distance to first order where stated. Only its sign and zero set are contractual.
/// - Queries at points with no unique nearest surface point (on the medial axis) return one
///   of the nearest points; which one is documented per class.
/// - `sample_uniform(n, seed)` draws from `Rng(seed)` only, so the output is bit-identical on
///   every platform for the same (n, seed), and a prefix property holds: the first k points of
///   `sample_uniform(n, seed)` are `sample_uniform(k, seed)`.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh {

/// The sphere |x - center| = radius.
/// value(x) = (|x - c|^2 - radius^2) / (2 radius): the signed distance to first order.
/// The medial axis is the centre; queries there return the point in direction +x.
class Sphere final : public ImplicitSurface {
public:
    /// \throw InvalidInput unless radius > 0 and all inputs are finite.
    Sphere(const Point3& center, double radius);

    [[nodiscard]] const Point3& center() const { return center_; }
    [[nodiscard]] double radius() const { return radius_; }

    [[nodiscard]] std::string spec() const override;
    [[nodiscard]] double value(const Point3& x) const override;
    [[nodiscard]] double signed_distance(const Point3& x) const override;
    [[nodiscard]] Point3 closest_point(const Point3& x) const override;
    [[nodiscard]] Vec3 normal(const Point3& x) const override;
    /// The radius.
    [[nodiscard]] double reach() const override { return radius_; }
    /// The radius, everywhere.
    [[nodiscard]] double local_feature_size(const Point3& x) const override;
    [[nodiscard]] double area() const override;
    [[nodiscard]] Bbox3 bbox() const override;
    /// The centre.
    [[nodiscard]] Point3 interior_point() const override { return center_; }
    /// Uniform directions from Rng::unit_vector() (one point per draw, no rejection).
    [[nodiscard]] std::vector<Point3> sample_uniform(std::size_t n,
                                                     std::uint64_t seed) const override;

private:
    Point3 center_;
    double radius_;
};

/// The axis-aligned ellipsoid sum_i ((x_i - c_i) / e_i)^2 = 1 with semi-axes e = (a, b, c)
/// along x, y, z (any order of sizes, equal axes allowed).
/// value(x) = sum_i ((x_i - c_i) / e_i)^2 - 1.
/// Distances and closest points solve the one-dimensional root problem of Eberly ("Distance
/// from a point to an ellipse, an ellipsoid, or a hyperellipsoid") by bisection to full
/// double precision; the closest point is accurate to a few ulps of the largest semi-axis.
/// With semi-axes e0 >= e1 >= e2, the medial axis is the planar region inside the ellipse with
/// semi-axes (e0^2 - e2^2) / e0 and (e1^2 - e2^2) / e1 in the plane of the two largest axes;
/// queries on it return the nearest point on the positive side of the smallest axis.
class Ellipsoid final : public ImplicitSurface {
public:
    /// \throw InvalidInput unless a, b, c > 0 and all inputs are finite.
    Ellipsoid(const Point3& center, double a, double b, double c);

    [[nodiscard]] const Point3& center() const { return center_; }
    /// Semi-axes along x, y, z.
    [[nodiscard]] const Vec3& semi_axes() const { return axes_; }

    [[nodiscard]] std::string spec() const override;
    [[nodiscard]] double value(const Point3& x) const override;
    [[nodiscard]] double signed_distance(const Point3& x) const override;
    [[nodiscard]] Point3 closest_point(const Point3& x) const override;
    [[nodiscard]] Vec3 normal(const Point3& x) const override;
    /// The smallest radius of curvature, e_min^2 / e_max (attained at the tips of the
    /// largest axis), which here equals the distance from the surface to the medial axis.
    [[nodiscard]] double reach() const override { return reach_; }
    /// Distance from the surface point nearest to x to the medial axis.
    [[nodiscard]] double local_feature_size(const Point3& x) const override;
    /// Legendre's closed form with incomplete elliptic integrals (std::ellint_1/2).
    [[nodiscard]] double area() const override { return area_; }
    [[nodiscard]] Bbox3 bbox() const override;
    /// The centre.
    [[nodiscard]] Point3 interior_point() const override { return center_; }
    /// Rejection sampling: a uniform direction u of the unit sphere is mapped to
    /// c + diag(a, b, c) u and accepted with probability proportional to the area element,
    /// e_min * sqrt(sum_i u_i^2 / e_i^2).
    [[nodiscard]] std::vector<Point3> sample_uniform(std::size_t n,
                                                     std::uint64_t seed) const override;

private:
    /// Closest point and unsigned distance of x - center_.
    [[nodiscard]] Point3 closest_offset(const Vec3& d, double* distance) const;

    Point3 center_;
    Vec3 axes_;
    std::array<int, 3> order_{};      ///< axis indices by decreasing semi-axis
    std::array<double, 2> medial_{};  ///< semi-axes of the medial region (largest first)
    double reach_ = 0, area_ = 0;
};

/// The torus with axis z through `center`, major radius R (centre to tube centre) and minor
/// radius r (tube), R > r > 0:  (sqrt(x^2 + y^2) - R)^2 + z^2 = r^2 in local coordinates.
/// value(x) = ((rho - R)^2 + z^2 - r^2) ((rho + R)^2 + z^2 - r^2) / (8 R^2 r), a quartic
/// polynomial whose gradient on the surface has length rho / R.
/// The medial axis is the core circle (inside) and the z-axis (outside); queries on the core
/// circle return the outer point, queries on the z-axis the point in direction +x.
class Torus final : public ImplicitSurface {
public:
    /// \throw InvalidInput unless R > r > 0 and all inputs are finite.
    Torus(const Point3& center, double major_radius, double minor_radius);

    [[nodiscard]] const Point3& center() const { return center_; }
    [[nodiscard]] double major_radius() const { return major_; }
    [[nodiscard]] double minor_radius() const { return minor_; }

    [[nodiscard]] std::string spec() const override;
    [[nodiscard]] double value(const Point3& x) const override;
    [[nodiscard]] double signed_distance(const Point3& x) const override;
    [[nodiscard]] Point3 closest_point(const Point3& x) const override;
    [[nodiscard]] Vec3 normal(const Point3& x) const override;
    /// min(r, R - r): the core circle is at distance r from every surface point, the z-axis at
    /// distance R - r from the inner equator.
    [[nodiscard]] double reach() const override;
    /// min(r, rho) with rho the distance of the surface point nearest to x from the z-axis.
    [[nodiscard]] double local_feature_size(const Point3& x) const override;
    /// 4 pi^2 R r.
    [[nodiscard]] double area() const override;
    [[nodiscard]] Bbox3 bbox() const override;
    /// The point center + (R, 0, 0) on the core circle.
    [[nodiscard]] Point3 interior_point() const override;
    /// Rejection sampling on the angle parameterisation (R + r cos v) (cos u, sin u) +
    /// r sin v e_z: v uniform, accepted with probability (R + r cos v) / (R + r), then u uniform.
    [[nodiscard]] std::vector<Point3> sample_uniform(std::size_t n,
                                                     std::uint64_t seed) const override;

private:
    Point3 center_;
    double major_, minor_;
};

}  // namespace dynmesh
