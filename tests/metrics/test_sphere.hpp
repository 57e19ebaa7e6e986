#pragma once
/// \file A minimal analytic sphere for the metrics tests (shapes/analytic.hpp is written
/// separately; this keeps the metrics tests independent of it).

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "dynmesh/geometry/random.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh::test {

class TestSphere final : public ImplicitSurface {
public:
    explicit TestSphere(double radius = 1.0, Point3 center = {}) : r_(radius), c_(center) {}
    [[nodiscard]] std::string spec() const override { return "sphere:" + std::to_string(r_); }
    [[nodiscard]] double value(const Point3& x) const override { return sqnorm(x - c_) - r_ * r_; }
    [[nodiscard]] double signed_distance(const Point3& x) const override {
        return norm(x - c_) - r_;
    }
    [[nodiscard]] Point3 closest_point(const Point3& x) const override {
        return c_ + normal(x) * r_;
    }
    [[nodiscard]] Vec3 normal(const Point3& x) const override { return normalized(x - c_); }
    [[nodiscard]] double reach() const override { return r_; }
    [[nodiscard]] double local_feature_size(const Point3&) const override { return r_; }
    [[nodiscard]] double area() const override { return 4.0 * std::numbers::pi * r_ * r_; }
    [[nodiscard]] Bbox3 bbox() const override {
        Bbox3 b;
        b.extend(c_ - Vec3{r_, r_, r_});
        b.extend(c_ + Vec3{r_, r_, r_});
        return b;
    }
    [[nodiscard]] Point3 interior_point() const override { return c_; }
    [[nodiscard]] std::vector<Point3> sample_uniform(std::size_t n,
                                                     std::uint64_t seed) const override {
        Rng rng(seed);
        std::vector<Point3> out;
        out.reserve(n);
        for (std::size_t i = 0; i < n; ++i) out.push_back(c_ + rng.unit_vector() * r_);
        return out;
    }

private:
    double r_;
    Point3 c_;
};

}  // namespace dynmesh::test
