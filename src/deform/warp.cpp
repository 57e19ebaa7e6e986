#include "dynmesh/deform/warp.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"  // kPi
#include "scenario_common.hpp"

namespace dynmesh {

using detail::check_positive;
using detail::fmt;

// ---- profiles ------------------------------------------------------------------------------

double cycle_profile(double u) { return 0.5 * (1.0 - std::cos(2.0 * kPi * u)); }
double swing_profile(double u) { return std::sin(2.0 * kPi * u); }

namespace {

/// Quintic smoothstep on [0, 1], clamped outside (C2 at both ends).
double smoothstep5(double x) {
    if (x <= 0) return 0;
    if (x >= 1) return 1;
    return x * x * x * (x * (6.0 * x - 15.0) + 10.0);
}

Vec3 unit_axis(const char* who, const Vec3& axis) {
    const double n = norm(axis);
    if (!(std::isfinite(n) && n > 0))
        throw InvalidInput(std::string(who) + ": the axis must be a non-zero finite vector");
    return axis / n;
}

/// Common part of the warps: the path parameter u = rate * t.
class CyclicWarp : public Warp {
public:
    CyclicWarp(const char* who, const Point3& center, double rate) : center_(center), rate_(rate) {
        check_positive(who, "the rate", rate);
        if (!is_finite(center)) throw InvalidInput(std::string(who) + ": the centre is not finite");
    }

protected:
    [[nodiscard]] double u(double t) const { return rate_ * t; }
    Point3 center_;
    double rate_;
};

class PulseWarp final : public CyclicWarp {
public:
    PulseWarp(const Point3& c, double max_scale, double rate)
        : CyclicWarp("make_pulse_warp", c, rate), amp_(max_scale - 1.0) {
        check_positive("make_pulse_warp", "max_scale", max_scale);
    }
    [[nodiscard]] std::string name() const override { return "pulse"; }
    [[nodiscard]] Point3 apply(double t, const Point3& x) const override {
        const double f = 1.0 + amp_ * cycle_profile(u(t));
        if (f == 1.0) return x;
        return center_ + (x - center_) * f;
    }

private:
    double amp_;
};

class StretchWarp final : public CyclicWarp {
public:
    StretchWarp(const Point3& c, const Vec3& axis, double max_stretch, double rate)
        : CyclicWarp("make_stretch_warp", c, rate),
          axis_(unit_axis("make_stretch_warp", axis)),
          amp_(max_stretch - 1.0) {
        check_positive("make_stretch_warp", "max_stretch", max_stretch);
    }
    [[nodiscard]] std::string name() const override { return "stretch"; }
    [[nodiscard]] Point3 apply(double t, const Point3& x) const override {
        const double g = amp_ * cycle_profile(u(t));  // f - 1
        if (g == 0.0) return x;
        return x + axis_ * (dot(x - center_, axis_) * g);
    }

private:
    Vec3 axis_;
    double amp_;
};

/// Rotation of d about the unit axis k by the angle with cosine c and sine s (Rodrigues).
Vec3 rotate(const Vec3& d, const Vec3& k, double c, double s) {
    const Vec3 par = k * dot(k, d);
    const Vec3 perp = d - par;
    return par + perp * c + cross(k, perp) * s;
}

class TwistWarp final : public CyclicWarp {
public:
    TwistWarp(const Point3& c, const Vec3& axis, double half_length, double end_angle, double rate)
        : CyclicWarp("make_twist_warp", c, rate),
          axis_(unit_axis("make_twist_warp", axis)),
          k_(end_angle / half_length) {
        check_positive("make_twist_warp", "half_length", half_length);
        check_positive("make_twist_warp", "end_angle", end_angle);
    }
    [[nodiscard]] std::string name() const override { return "twist"; }
    [[nodiscard]] Point3 apply(double t, const Point3& x) const override {
        const double w = swing_profile(u(t));
        if (w == 0.0) return x;
        const Vec3 d = x - center_;
        const double theta = w * k_ * dot(d, axis_);
        return center_ + rotate(d, axis_, std::cos(theta), std::sin(theta));
    }

private:
    Vec3 axis_;
    double k_;  // end angle per unit length along the axis
};

class BendWarp final : public CyclicWarp {
public:
    BendWarp(const Point3& c, const Vec3& axis, const Vec3& toward, double half_length,
             double max_turn, double pre_stretch, double rate)
        : CyclicWarp("make_bend_warp", c, rate), pre_stretch_(pre_stretch) {
        check_positive("make_bend_warp", "half_length", half_length);
        check_positive("make_bend_warp", "max_turn", max_turn);
        if (!(std::isfinite(pre_stretch) && pre_stretch >= 1.0))
            throw InvalidInput("make_bend_warp: pre_stretch must be >= 1 and finite (got " +
                               fmt(pre_stretch) + ")");
        if (!(max_turn < 2.0 * kPi))
            throw InvalidInput("make_bend_warp: max_turn must be < 2 pi (got " + fmt(max_turn) +
                               ")");
        e1_ = unit_axis("make_bend_warp", axis);
        const Vec3 b = toward - e1_ * dot(toward, e1_);
        if (!(norm(b) > 1e-9 * std::max(1.0, norm(toward))))
            throw InvalidInput("make_bend_warp: 'toward' must not be parallel to the axis");
        e2_ = normalized(b);
        e3_ = cross(e1_, e2_);
        kmax_ = max_turn / (2.0 * half_length * pre_stretch);
    }
    [[nodiscard]] std::string name() const override { return "bend"; }
    [[nodiscard]] Point3 apply(double t, const Point3& x) const override {
        const double q = cycle_profile(u(t));
        double sigma = 1.0, k = 0.0;
        if (pre_stretch_ > 1.0) {
            sigma = 1.0 + (pre_stretch_ - 1.0) * smoothstep5(2.0 * q);
            k = kmax_ * smoothstep5(2.0 * q - 1.0);
        } else {
            k = kmax_ * q;
        }
        if (sigma == 1.0 && k == 0.0) return x;
        const Vec3 d = x - center_;
        const double a = dot(d, e1_) * sigma, b = dot(d, e2_), cc = dot(d, e3_);
        double a2 = a, b2 = b;
        if (k != 0.0) {
            const double phi = k * a;
            const double sp = std::sin(phi), cp = std::cos(phi), sh = std::sin(0.5 * phi);
            a2 = sp / k - b * sp;
            b2 = b * cp + 2.0 * sh * sh / k;
        }
        return center_ + e1_ * a2 + e2_ * b2 + e3_ * cc;
    }

private:
    double pre_stretch_;
    Vec3 e1_, e2_, e3_;
    double kmax_ = 0;
};

class RotationWarp final : public CyclicWarp {
public:
    RotationWarp(const Point3& c, const Vec3& axis, double rate)
        : CyclicWarp("make_rotation_warp", c, rate), axis_(unit_axis("make_rotation_warp", axis)) {}
    [[nodiscard]] std::string name() const override { return "rotate"; }
    [[nodiscard]] Point3 apply(double t, const Point3& x) const override {
        const double theta = 2.0 * kPi * u(t);
        if (theta == 0.0) return x;
        return center_ + rotate(x - center_, axis_, std::cos(theta), std::sin(theta));
    }

private:
    Vec3 axis_;
};

class DimpleWarp final : public CyclicWarp {
public:
    DimpleWarp(std::vector<Point3> centers, std::vector<Vec3> displacements, double radius,
               double rate)
        : CyclicWarp("make_dimple_warp", Point3{0, 0, 0}, rate),
          c_(std::move(centers)),
          d_(std::move(displacements)) {
        const char* who = "make_dimple_warp";
        check_positive(who, "radius", radius);
        if (c_.empty()) throw InvalidInput("make_dimple_warp: no centre");
        if (c_.size() != d_.size())
            throw InvalidInput("make_dimple_warp: " + std::to_string(c_.size()) +
                               " centres but " + std::to_string(d_.size()) + " displacements");
        double dmax = 0;
        for (std::size_t k = 0; k < c_.size(); ++k) {
            if (!is_finite(c_[k]) || !is_finite(d_[k]))
                throw InvalidInput("make_dimple_warp: centre or displacement " +
                                   std::to_string(k) + " is not finite");
            dmax = std::max(dmax, norm(d_[k]));
        }
        for (std::size_t i = 0; i < c_.size(); ++i)
            for (std::size_t j = i + 1; j < c_.size(); ++j)
                if (distance(c_[i], c_[j]) < 2.0 * radius)
                    throw InvalidInput("make_dimple_warp: centres " + std::to_string(i) + " and " +
                                       std::to_string(j) + " are " +
                                       fmt(distance(c_[i], c_[j])) + " apart, closer than 2 radius = " +
                                       fmt(2.0 * radius) + " (the supports overlap)");
        const double lip = dmax * kDimpleBumpSlope / radius;
        if (!(lip < 1.0))
            throw InvalidInput("make_dimple_warp: the displacement field has Lipschitz constant " +
                               fmt(lip) + " >= 1 (largest displacement " + fmt(dmax) +
                               ", radius " + fmt(radius) +
                               "): not a diffeomorphism; use a larger radius or smaller "
                               "displacements");
        r2_ = radius * radius;
    }
    [[nodiscard]] std::string name() const override { return "dimple"; }
    [[nodiscard]] Point3 apply(double t, const Point3& x) const override {
        const double p = cycle_profile(u(t));
        if (p == 0.0) return x;
        for (std::size_t k = 0; k < c_.size(); ++k) {
            const double d2 = sqdistance(x, c_[k]);
            if (d2 < r2_) {  // the supports are disjoint: at most one centre moves x
                const double q = 1.0 - d2 / r2_;
                return x + d_[k] * (p * q * q * q);
            }
        }
        return x;
    }

private:
    std::vector<Point3> c_;
    std::vector<Vec3> d_;
    double r2_ = 0;
};

}  // namespace

// ---- warp factories ------------------------------------------------------------------------

std::unique_ptr<Warp> make_pulse_warp(const Point3& center, double max_scale, double rate) {
    return std::make_unique<PulseWarp>(center, max_scale, rate);
}
std::unique_ptr<Warp> make_stretch_warp(const Point3& center, const Vec3& axis,
                                        double max_stretch, double rate) {
    return std::make_unique<StretchWarp>(center, axis, max_stretch, rate);
}
std::unique_ptr<Warp> make_twist_warp(const Point3& center, const Vec3& axis, double half_length,
                                      double end_angle, double rate) {
    return std::make_unique<TwistWarp>(center, axis, half_length, end_angle, rate);
}
std::unique_ptr<Warp> make_bend_warp(const Point3& center, const Vec3& axis, const Vec3& toward,
                                     double half_length, double max_turn, double pre_stretch,
                                     double rate) {
    return std::make_unique<BendWarp>(center, axis, toward, half_length, max_turn, pre_stretch,
                                      rate);
}
std::unique_ptr<Warp> make_rotation_warp(const Point3& center, const Vec3& axis, double rate) {
    return std::make_unique<RotationWarp>(center, axis, rate);
}

double dimple_bump(double r) {
    if (!(std::abs(r) < 1.0)) return 0.0;
    const double q = 1.0 - r * r;
    return q * q * q;
}
std::unique_ptr<Warp> make_dimple_warp(std::vector<Point3> centers, std::vector<Vec3> displacements,
                                       double radius, double rate) {
    return std::make_unique<DimpleWarp>(std::move(centers), std::move(displacements), radius,
                                        rate);
}

std::vector<Point3> fibonacci_sphere(std::size_t n) {
    if (n == 0) throw InvalidInput("fibonacci_sphere: n must be >= 1");
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    std::vector<Point3> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double z = 1.0 - (2.0 * static_cast<double>(i) + 1.0) / static_cast<double>(n);
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const double phi = golden * static_cast<double>(i);
        out.push_back(Point3{r * std::cos(phi), r * std::sin(phi), z});
    }
    return out;
}

}  // namespace dynmesh
