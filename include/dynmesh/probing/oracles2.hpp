#pragma once
/// \file Closed planar curves for two-dimensional probing, behind the 3D Oracle interface.
///
/// The curve lies in the plane z = 0; a 2D run uses points with z = 0 and directions with
/// d.z = 0. So that every 3D query stays well defined, the object is the prism
/// O = {(x, y, z) : (x, y) inside the curve}: z is ignored by every query, and S means the
/// curve (sample_surface returns points with z = 0). GroundTruth reads, for a curve:
/// area() = its length, components() = 1, euler_characteristic() = 0 (a circle).
///
/// The curve is star-shaped about its centre c: ρ = r(φ) = R (1 + a cos(k φ)) in polar
/// coordinates about c, 0 ≤ a < 1 (a = 0: the circle). The implicit g = ρ − r(φ) is negative
/// inside. Outside O, ρ ≥ (1 − a) R, so |∇g| ≤ L = sqrt(1 + (a k / (1 − a))²) there: g / L is a
/// lower bound of the distance from an outside point to S, which makes sphere tracing safe
/// (the same march as the torus, then bisection on g; τ = 1e-12 (1 + a) R).
/// signed_distance() returns g / L (an under-estimate with the right sign; exact for the
/// circle); distance() is the exact distance (dense sampling of φ, then golden-section search).

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/probing/oracles.hpp"

namespace dynmesh {

class PlanarStarOracle : public ProbeObject {
public:
    /// \throw InvalidInput unless R > 0, 0 ≤ a < 1, k ≥ 1 and all values are finite.
    PlanarStarOracle(const Point2& center, double radius, double amplitude, int lobes,
                     OracleOptions options = {});
    [[nodiscard]] double radius_at(double phi) const;
    [[nodiscard]] double value(const Point3& p) const;
    [[nodiscard]] double signed_distance(const Point3& p) const override;
    [[nodiscard]] double distance(const Point3& p) const override;
    [[nodiscard]] std::vector<Point3> sample_surface(double spacing) const override;
    /// The smallest radius of curvature of the curve (numeric, 1e5 samples of φ), bounded by
    /// half the narrowest width; for the circle R.
    [[nodiscard]] double reach() const override { return reach_; }
    /// 2 (1 + a) R (an upper bound; exact for the circle).
    [[nodiscard]] double diameter() const override { return 2 * (1 + amplitude_) * radius_; }
    /// The length of the curve (numeric quadrature; exact for the circle).
    [[nodiscard]] double area() const override { return length_; }
    [[nodiscard]] int components() const override { return 1; }
    [[nodiscard]] int euler_characteristic() const override { return 0; }
    [[nodiscard]] Point3 interior_point() const { return {center_.x, center_.y, 0}; }
    [[nodiscard]] Ball default_omega() const;

private:
    [[nodiscard]] std::optional<ProbeHit> cast_checked(const Point3& s, const Vec3& d,
                                                       double t_max, bool strict) const override;
    [[nodiscard]] Point3 curve_point(double phi) const;
    [[nodiscard]] Vec3 gradient(const Point3& p) const;
    Point2 center_;
    double radius_, amplitude_;
    int lobes_;
    double lipschitz_ = 1, reach_ = 0, length_ = 0;
};

/// The circle (c, R) in the plane z = 0.
class CircleOracle2 final : public PlanarStarOracle {
public:
    CircleOracle2(const Point2& center, double radius, OracleOptions options = {})
        : PlanarStarOracle(center, radius, 0, 1, options) {}
};

/// The smooth star r(φ) = R (1 + 0.2 cos 3φ) about c, in the plane z = 0.
class StarOracle2 final : public PlanarStarOracle {
public:
    StarOracle2(const Point2& center, double radius, OracleOptions options = {})
        : PlanarStarOracle(center, radius, 0.2, 3, options) {}
};

}  // namespace dynmesh
