#include "dynmesh/skin/safe_duration.hpp"

#include <cmath>
#include <numbers>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/format.hpp"

namespace dynmesh {

double travel_duration(double eps, double rho0) {
    DYNMESH_CHECK(eps >= 0 && eps < 1, "travel_duration: eps must be in [0, 1)");
    return 2 * eps * (2 - eps) * rho0 * rho0;
}

double edge_epsilon(double gamma, const SkinQuality& q) {
    return (gamma * q.Q1 - q.Q0) / (gamma * q.Q1 + q.Q0);
}

double triangle_epsilon(double gamma, const SkinQuality& q) {
    return 1 - std::pow(gamma * q.Q0 / q.Q1, 0.25);
}

double edge_safe_duration(double gamma, double rho0, const SkinQuality& q) {
    const double eps = edge_epsilon(gamma, q);
    return eps > 0 ? travel_duration(eps, rho0) : 0.0;
}

double triangle_safe_duration(double gamma, double rho0, const SkinQuality& q) {
    const double eps = triangle_epsilon(gamma, q);
    return eps > 0 ? q.kappa_t * travel_duration(eps, rho0) : 0.0;
}

BeyondCount classify_beyond(bool persisted, bool was_beyond, bool was_floored) {
    if (!persisted) return BeyondCount::BornBad;
    if (!was_beyond) return BeyondCount::Miss;
    return was_floored ? BeyondCount::LeftFloor : BeyondCount::StillBad;
}

double min_angle_floor_deg(double Q) { return std::asin(1 / (Q * Q)) * 180 / std::numbers::pi; }

std::vector<std::string> feasibility_problems(const SkinQuality& q) {
    std::vector<std::string> out;
    const auto f = [](double v) { return format_number(v); };
    if (!(q.C > 0) || !std::isfinite(q.C)) out.push_back("C must be a positive number, not " + f(q.C));
    if (!(q.Q0 > 1 && q.Q1 > q.Q0) || !std::isfinite(q.Q1))
        out.push_back("the quality bounds must satisfy 1 < Q0 < Q1, not Q0 = " + f(q.Q0) + ", Q1 = " + f(q.Q1));
    if (!(q.kappa_t > 0 && q.kappa_t <= 1)) out.push_back("kappa_t must be in (0, 1], not " + f(q.kappa_t));
    if (!out.empty()) return out;
    if (!(q.Q0 * q.Q0 >= 2.1 * (1 + 2 * q.C * q.Q0)))
        out.push_back("F1 (insertion makes no borderline edge): Q0^2 = " + f(q.Q0 * q.Q0) + " < 2.1 (1 + 2 C Q0) = " +
                      f(2.1 * (1 + 2 * q.C * q.Q0)));
    if (!(q.Q0 * q.Q0 >= 3)) out.push_back("F2 (contraction makes no oversized triangle): Q0^2 = " + f(q.Q0 * q.Q0) + " < 3");
    if (!(q.Q1 / q.Q0 >= 1.15)) out.push_back("F3 (a useful buffer): Q1/Q0 = " + f(q.Q1 / q.Q0) + " < 1.15");
    if (!(q.C * q.Q1 <= 0.3)) out.push_back("F4 (approximation): C Q1 = " + f(q.C * q.Q1) + " > 0.3");
    return out;
}

}  // namespace dynmesh
