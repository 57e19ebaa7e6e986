#pragma once
/// \file Private helpers of the probing oracles: the convex quadric root rule shared by
/// spheres, ellipsoids and balls, and the sphere-tracing march shared by the torus and the
/// genus-2 surface.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/format.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/probing/oracle.hpp"

namespace dynmesh::detail {


/// |cos(ray, normal)| below this is a near-tangent (grazing) contact (spec §8.1).
inline constexpr double kGrazingCos = 1e-6;

/// The entering root of the ray s + t d against a convex quadric whose restriction to the ray
/// is f(t) = A t² + 2 B t + C (A > 0, negative inside). `near` when the start is within τ of
/// S, `cos0` the cosine between d and the outward normal at s (used when near). Returns the
/// candidate parameter, or nothing; `touch` is set for a tangential approach (no real
/// crossing, closest approach at the returned t, to be checked by the caller against τ).
struct QuadricRoot {
    double t = 0;
    bool touch = false;
};
std::optional<QuadricRoot> quadric_entry(double A, double B, double C, bool near, double cos0);

/// The march of sphere tracing along s + t d for t ≤ t_max + τ.
/// `sd(p)` is a signed distance or a 1-Lipschitz under-estimate with the same sign; `value(p)`
/// the implicit used for bisection (same sign as sd). `finish(t, stalled)` decides about a
/// crossing at t (stalled: a contact without sign change at the nearest sample) and returns
/// true to stop (the hit was accepted) or false to go on past it (strict mode).
/// `h` is the smallest step. Returns true when finish() accepted a hit.
template <class Sd, class Value, class Finish>
bool sphere_trace(const Point3& s, const Vec3& d, double t_max, double tau, double h, Sd&& sd,
                  Value&& value, Finish&& finish) {
    const auto at = [&](double t) { return s + t * d; };
    const double t_end = t_max + tau;
    double t = 0, f = sd(s);
    double min_f = std::numeric_limits<double>::infinity(), t_min = 0;
    bool near_zone = false;
    constexpr long kMaxSteps = 50'000'000;
    for (long step = 0; t <= t_end; ++step) {
        if (step == kMaxSteps)  // hovering within h of S for 5e7 steps: a bug, not an input
            throw InternalError("sphere_trace: no decision after 5e7 steps from " +
                                format_point(s));
        const double t_next = t + std::max(std::fabs(f), h);
        const double f_next = sd(at(t_next));
        if (!std::isfinite(t_next) || !std::isfinite(f_next)) break;  // gone to infinity
        if (f >= 0 && f_next < 0) {
            // A sign change: bisection on the implicit, lo outside, hi inside.
            double lo = t, hi = t_next;
            for (int i = 0; i < 200; ++i) {
                const double mid = 0.5 * (lo + hi);
                if (mid <= lo || mid >= hi) break;
                (value(at(mid)) < 0 ? hi : lo) = mid;
            }
            if (lo > t_end) return false;
            near_zone = false;
            min_f = std::numeric_limits<double>::infinity();
            if (finish(lo, false)) return true;
        } else if (f_next >= 0) {
            if (f_next <= h) {
                near_zone = true;
                if (f_next < min_f) min_f = f_next, t_min = t_next;
            } else if (near_zone) {
                near_zone = false;
                if (min_f <= 2 * tau && t_min <= t_end && finish(t_min, true)) return true;
                min_f = std::numeric_limits<double>::infinity();
            }
        }
        t = t_next;
        f = f_next;
    }
    if (near_zone && min_f <= 2 * tau && t_min <= t_end) return finish(t_min, true);
    return false;
}

}  // namespace dynmesh::detail
