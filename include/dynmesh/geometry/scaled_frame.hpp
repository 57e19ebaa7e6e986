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

/// The vectors from `origin` to `points`, scaled by one exact power of two so that their
/// largest component lies in [1, 2): the frame in which the shape of a triangle (or of a
/// pair of triangles) is measured. Every square and product of these vectors stays a normal
/// number, whatever the magnitude of the coordinates (near 1e308, subnormal) or of the
/// triangle itself (a 1e-170 triangle in a unit mesh). `scale.length()` brings a length
/// measured there back.
template <std::size_t N>
struct LocalFrame {
    std::array<Vec3, N> v{};
    ExactScale scale;
};

template <std::size_t N>
[[nodiscard]] LocalFrame<N> local_frame(const Point3& origin, const std::array<Point3, N>& points) {
    // Coordinates near overflow are halved a few times first, so that differences stay finite.
    double big = std::fmax(std::fabs(origin.x), std::fmax(std::fabs(origin.y), std::fabs(origin.z)));
    for (const Point3& p : points)
        big = std::fmax(big, std::fmax(std::fabs(p.x), std::fmax(std::fabs(p.y), std::fabs(p.z))));
    const ExactScale pre(big > 0x1p1000 ? -8 : 0);
    LocalFrame<N> f;
    double m = 0;
    for (std::size_t i = 0; i < N; ++i) {
        f.v[i] = pre.apply(points[i]) - pre.apply(origin);
        m = std::fmax(m, std::fmax(std::fabs(f.v[i].x), std::fmax(std::fabs(f.v[i].y), std::fabs(f.v[i].z))));
    }
    if (!(m > 0) || !std::isfinite(m)) {
        f.scale = pre;
        return f;
    }
    const int e = -std::ilogb(m);
    const ExactScale s(e);
    for (Vec3& x : f.v) x = s.apply(x);
    f.scale = ExactScale(pre.exponent() + e);
    return f;
}

}  // namespace dynmesh
