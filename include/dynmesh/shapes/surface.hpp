#pragma once
/// \file Analytic closed surfaces with known geometry: the ground truth for tests,
/// experiments and quality measures.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

/// A smooth closed surface given analytically. Implementations: Sphere, Ellipsoid, Torus
/// (shapes/analytic.hpp).
class ImplicitSurface {
public:
    virtual ~ImplicitSurface() = default;
    /// A short spec that `make_surface` parses back, e.g. "torus:5,3".
    [[nodiscard]] virtual std::string spec() const = 0;
    /// Implicit function: negative inside, zero on the surface, positive outside.
    [[nodiscard]] virtual double value(const Point3& x) const = 0;
    /// Signed Euclidean distance (negative inside).
    [[nodiscard]] virtual double signed_distance(const Point3& x) const = 0;
    /// The nearest surface point to x (x off the medial axis).
    [[nodiscard]] virtual Point3 closest_point(const Point3& x) const = 0;
    /// Outward unit normal at the surface point nearest to x.
    [[nodiscard]] virtual Vec3 normal(const Point3& x) const = 0;
    /// The reach: the smallest distance from the surface to its medial axis.
    [[nodiscard]] virtual double reach() const = 0;
    /// Local feature size at surface point x (>= reach()).
    [[nodiscard]] virtual double local_feature_size(const Point3& x) const = 0;
    /// Total area.
    [[nodiscard]] virtual double area() const = 0;
    [[nodiscard]] virtual Bbox3 bbox() const = 0;
    /// A point strictly inside.
    [[nodiscard]] virtual Point3 interior_point() const = 0;
    /// n points drawn uniformly with respect to area, reproducible from the seed.
    [[nodiscard]] virtual std::vector<Point3> sample_uniform(std::size_t n,
                                                             std::uint64_t seed) const = 0;
};

/// Parses "sphere", "sphere:R", "ellipsoid:a,b,c", "torus:R,r" (optionally "...@cx,cy,cz"
/// for a centre). \throw InvalidInput naming the spec and what is wrong.
[[nodiscard]] std::unique_ptr<ImplicitSurface> make_surface(const std::string& spec);

}  // namespace dynmesh
