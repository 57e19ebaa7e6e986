#pragma once
/// \file What a probing run may ask of the unknown object, and what only checks may ask.
///
/// The object O is a bounded open set with a smooth boundary S (specs/probing.md §1, §6).
/// `Oracle` is the ray-casting device's sensor: from a point in free space (outside O) it shoots a
/// ray and reports the first point where the ray crosses S. `GroundTruth` is what tests, the
/// safety monitor and the benchmarks know about the object; the algorithm never calls it.
///
/// Conventions shared by every oracle
/// - τ = tolerance(): a start point with |signed distance| ≤ τ counts as on S (spec §10.12): a
///   root at t ≤ τ is ignored when the ray leaves O there, and reported as t = 0 when it enters.
/// - A ray that starts deeper than τ inside O violates the precondition: InvalidInput.
/// - Closed-segment convention: a crossing at t ≤ t_max (+ τ) is reported.
/// - Tangential contacts are not crossings. Near-tangent crossings (|cos(ray, normal)| < 1e-6,
///   or a stalled root search) are reported with `grazing = true`; with `strict` they are
///   ignored instead (spec §8.1, §10.11).

#include <optional>
#include <vector>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

/// A closed ball B(center, radius): the domain Ω of a probing run (spec §1: S lies in the open
/// ball with a margin, so ∂Ω is free).
struct Ball {
    Point3 center{};
    double radius = 0;
};

/// A crossing of S by a ray s + t·d.
struct ProbeHit {
    Point3 x{};            ///< the crossing point, on S
    double t = 0;          ///< its ray parameter (d is a unit vector: the distance from s)
    bool grazing = false;  ///< a near-tangent contact (see the file comment)
};

/// The probing sensor.
class Oracle {
public:
    virtual ~Oracle() = default;
    /// The first crossing of S by the ray from s in unit direction d with t ≤ t_max, if any.
    /// \pre s is free (outside O, or within tolerance() of S); d has unit length.
    /// \throw InvalidInput if s lies inside O (deeper than tolerance()) or d is not a unit vector.
    [[nodiscard]] virtual std::optional<ProbeHit> cast(const Point3& s, const Vec3& d,
                                                       double t_max) const = 0;
    /// τ of the file comment, in the units of the object.
    [[nodiscard]] virtual double tolerance() const = 0;
};

/// What checks and benchmarks know about the object (never the algorithm).
class GroundTruth {
public:
    virtual ~GroundTruth() = default;
    /// True when p is not in the open set O (on S counts as free).
    [[nodiscard]] virtual bool is_free(const Point3& p) const = 0;
    /// True when the closed segment ab misses O (it may touch S).
    [[nodiscard]] virtual bool segment_is_free(const Point3& a, const Point3& b) const = 0;
    /// The distance from a of a free point of the closed segment ab, if it has one. The default
    /// tests 65 evenly spaced points (so it may miss a free piece shorter than |b − a|/64);
    /// objects that can find the crossings override it.
    [[nodiscard]] virtual std::optional<double> free_point_on(const Point3& a, const Point3& b) const {
        const double len = dynmesh::distance(a, b);
        for (int k = 0; k <= 64; ++k)
            if (is_free(a + (k / 64.0) * (b - a))) return len * k / 64;
        return std::nullopt;
    }
    /// Unsigned distance from p to S.
    [[nodiscard]] virtual double distance(const Point3& p) const = 0;
    /// Points of S about `spacing` apart (for two-sided Hausdorff distances).
    [[nodiscard]] virtual std::vector<Point3> sample_surface(double spacing) const = 0;
    /// The reach of S (0 for a polyhedron).
    [[nodiscard]] virtual double reach() const = 0;
    /// The diameter of S (or an upper bound documented by the class).
    [[nodiscard]] virtual double diameter() const = 0;
    [[nodiscard]] virtual double area() const = 0;
    /// The number of connected components of S.
    [[nodiscard]] virtual int components() const = 0;
    /// The Euler characteristic of S (sum over components).
    [[nodiscard]] virtual int euler_characteristic() const = 0;
};

}  // namespace dynmesh
