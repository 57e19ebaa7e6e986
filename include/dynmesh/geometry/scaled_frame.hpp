#pragma once
/// \file Exact rescaling by a power of two, so that measures of geometry near the limits of
/// double precision (coordinates near 1e308, or subnormal ones near 1e-310) are computed
/// where products and squares neither overflow nor underflow.
///
/// Multiplying a double by a power of two only changes its exponent: as long as the result
/// is a normal number it is exact, and scaling back restores the input bit for bit. Angles
/// and ratios are scale-invariant, so they can be measured on scaled positions; a length
/// measured there is scaled back with `length()`.

#include <array>
#include <cmath>
#include <span>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

/// Scaling by 2^exponent.
class ExactScale {
public:
    ExactScale() = default;
    explicit ExactScale(int exponent)
        : exponent_(exponent),
          // A factor 2^e is itself a finite double only for |e| <= 1000 or so; beyond that
          // (subnormal inputs) each value goes through ldexp.
          factor_(std::abs(exponent) <= 1000 ? std::ldexp(1.0, exponent) : 0.0) {}

    /// The power of two that brings max|coordinate| of `points` into [1, 2) (exponent 0 for
    /// no points, all zeros, or non-finite input).
    [[nodiscard]] static ExactScale to_unit(std::span<const Point3> points) {
        double big = 0;
        for (const Point3& p : points)
            big = std::fmax(big, std::fmax(std::fabs(p.x), std::fmax(std::fabs(p.y), std::fabs(p.z))));
        if (!(big > 0) || !std::isfinite(big)) return ExactScale(0);
        return ExactScale(-std::ilogb(big));
    }

    [[nodiscard]] int exponent() const { return exponent_; }
    [[nodiscard]] double apply(double x) const {
        return factor_ != 0.0 ? x * factor_ : std::ldexp(x, exponent_);
    }
    [[nodiscard]] Vec3 apply(const Vec3& p) const {
        if (factor_ != 0.0) return p * factor_;
        return {std::ldexp(p.x, exponent_), std::ldexp(p.y, exponent_), std::ldexp(p.z, exponent_)};
    }
    /// A length measured in the scaled frame, in the original units.
    [[nodiscard]] double length(double scaled) const { return std::ldexp(scaled, -exponent_); }

private:
    int exponent_ = 0;
    double factor_ = 1.0;
};

/// A few points (a triangle, the quad of an edge) scaled together by the power of two that
/// brings their largest coordinate into [1, 2): the frame in which their shape is measured.
/// Edges there are at least about 2^-52 long (coordinates cannot resolve less), so every
/// square and product of edge vectors stays a normal number, whatever the magnitude of the
/// coordinates (near 1e308, subnormal, or a mesh mixing both). Where the unscaled
/// computation neither overflows nor underflows, the scaled one gives bit-identical angles
/// and ratios; `scale.length()` brings a length back.
template <std::size_t N>
struct UnitPoints {
    std::array<Point3, N> p{};
    ExactScale scale;
};

template <std::size_t N>
[[nodiscard]] UnitPoints<N> to_unit(const std::array<Point3, N>& points) {
    UnitPoints<N> u;
    u.scale = ExactScale::to_unit(points);
    for (std::size_t i = 0; i < N; ++i) u.p[i] = u.scale.apply(points[i]);
    return u;
}

}  // namespace dynmesh
