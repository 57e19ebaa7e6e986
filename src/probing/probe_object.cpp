#include <cmath>
#include <cstdio>
#include <string>

#include "dynmesh/error.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "probe_common.hpp"

namespace dynmesh {

namespace detail {

std::optional<QuadricRoot> quadric_entry(double A, double B, double C, bool near, double cos0) {
    if (near) {
        // On S: entering (or tangent) at the start is a hit at t = 0; leaving a convex set
        // never re-enters it.
        if (cos0 < kGrazingCos) return QuadricRoot{0, false};
        return std::nullopt;
    }
    if (B >= 0) return std::nullopt;  // moving away from a convex set that s is outside of
    const double disc = B * B - A * C;
    if (disc <= 0) return QuadricRoot{-B / A, true};
    const double q = -B + std::sqrt(disc);  // > 0, no cancellation since B < 0
    return QuadricRoot{C / q, false};
}

}  // namespace detail

ProbeObject::ProbeObject(double scale, OracleOptions options)
    : tau_(1e-12 * scale), options_(options) {}

std::optional<ProbeHit> ProbeObject::cast(const Point3& s, const Vec3& d, double t_max) const {
    if (!is_finite(s))
        throw InvalidInput("Oracle::cast: the start " + format_point(s) + " is not finite");
    if (!is_finite(d) || std::fabs(norm(d) - 1) > 1e-9)
        throw InvalidInput("Oracle::cast: the direction " + format_point(d) +
                           " is not a unit vector");
    if (std::isnan(t_max) || t_max < 0)
        throw InvalidInput("Oracle::cast: t_max must be >= 0, not " + std::to_string(t_max));
    const double sd = signed_distance(s);
    if (sd < -tau_)
        throw InvalidInput("Oracle::cast: the start " + format_point(s) +
                           " lies inside the object (signed distance " + std::to_string(sd) +
                           ", tolerance " + std::to_string(tau_) + ")");
    return cast_checked(s, d, t_max, options_.strict);
}

bool ProbeObject::accept(ProbeHit& hit, double cos_angle, double t_max, bool strict,
                         bool stalled) const {
    if (hit.t > t_max + tau_) return false;
    if (hit.t < 0) hit.t = 0;
    hit.grazing = stalled || std::fabs(cos_angle) < detail::kGrazingCos;
    return !(hit.grazing && strict);
}

bool ProbeObject::segment_is_free(const Point3& a, const Point3& b) const {
    if (!is_free(a) || !is_free(b)) return false;
    const double len = dynmesh::distance(a, b);
    if (len <= tau_) return true;
    const auto hit = cast_checked(a, (b - a) / len, len, false);
    return !hit || hit->t >= len - tau_;
}

double ProbeObject::distance(const Point3& p) const { return std::fabs(signed_distance(p)); }

}  // namespace dynmesh
