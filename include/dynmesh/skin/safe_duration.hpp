#pragma once
/// \file The arithmetic of relaxed scheduling (specs/skin-surfaces.md §4.2, §4.4, §5, with the
/// corrections of §8): how long an edge or a triangle of a growing skin mesh may go unchecked,
/// and the parameter checks F1–F4.
///
/// Time is the digest's normalisation: every weight grows by 1 per unit of t (w_i(t) = w_i + t),
/// and at s = 1/2 a point moves at speed 1/(4ϱ), so ϱ² changes at rate at most 1/2.

#include <string>
#include <vector>

namespace dynmesh {

/// The constants of the size bounds [L] R_ab/λ_ab ≥ C/Q and [U] R_abc/λ_abc ≤ C·Q, with the
/// gray zone between Q0 (act) and Q1 (must never be crossed).
struct SkinQuality {
    double C = 0.12;
    double Q0 = 1.75;
    double Q1 = 2.25;
    /// Safety factor on triangle durations (§8 correction 1: the Height Lemma alone is false).
    double kappa_t = 0.8;
};

/// The time for ϱ² to fall from ϱ0² to (1 − ε)²ϱ0² at rate 1/2: 2ε(2 − ε)ϱ0². Over it a point
/// with ϱ ≥ ϱ0 travels at most ε·ϱ0 (§4.2). \pre 0 ≤ ε < 1.
[[nodiscard]] double travel_duration(double eps, double rho0);

/// ε_e(γ) = (γQ1 − Q0)/(γQ1 + Q0) for an edge whose ratio R_ab/λ_ab is γ·C/Q0 (γ ≥ 1:
/// acceptable): over travel_duration(ε_e, ϱ0) it cannot fall below C/Q1 (§4.4).
[[nodiscard]] double edge_epsilon(double gamma, const SkinQuality& q = {});

/// ε_t(γ) = 1 − (γQ0/Q1)^(1/4) for a triangle whose ratio R_abc/λ_abc is γ·C·Q0 (γ ≤ 1:
/// acceptable): R1/λ1 ≤ (R0/λ0)/(1 − ε)⁴ keeps it below C·Q1 (§4.4, §8 correction 7).
[[nodiscard]] double triangle_epsilon(double gamma, const SkinQuality& q = {});

/// Δt_e = travel_duration(ε_e(γ), ϱ0), ϱ0 = min(ϱ(a), ϱ(b)); 0 when γ ≤ Q0/Q1 (already at
/// or beyond the Q1 threshold).
[[nodiscard]] double edge_safe_duration(double gamma, double rho0, const SkinQuality& q = {});

/// Δt_t = κ_t · travel_duration(ε_t(γ), ϱ0), ϱ0 the minimum over the three vertices; 0 when
/// γ ≥ Q1/Q0.
[[nodiscard]] double triangle_safe_duration(double gamma, double rho0, const SkinQuality& q = {});

/// What a check that finds an element beyond the Q1 threshold counts (§8 correction 2).
enum class BeyondCount {
    BornBad,   ///< the element is new (created, changed, or its exemption cleared) since its last check
    LeftFloor, ///< its previous check found it beyond but under the floor of ϱ, which excludes it
               ///< (§8 correction 2): the exclusion cleared, so it counts as born bad
    StillBad,  ///< its previous check found it beyond already: a repair was refused or undone
    Miss       ///< its previous check found it in range: the schedule let it cross (must never happen)
};
/// `persisted`: the same element was checked before; `was_beyond`: that check found its ratio
/// beyond the threshold (measured against max(ϱ, floor)); `was_floored`: ϱ was under the floor then.
[[nodiscard]] BeyondCount classify_beyond(bool persisted, bool was_beyond, bool was_floored);

/// The minimum angle every triangle meeting [L] and [U] at Q has: asin(1/Q²), in degrees
/// (11.39° at Q1 = 2.25).
[[nodiscard]] double min_angle_floor_deg(double Q);

/// The practical feasibility checks of §5 (F1 insertion makes no borderline edge:
/// Q0² ≥ 2.1(1 + 2·C·Q0); F2 contraction: Q0² ≥ 3 (heuristic); F3 a useful buffer:
/// Q1/Q0 ≥ 1.15; F4 approximation: C·Q1 ≤ 0.3), plus 0 < C, 1 < Q0 < Q1 and 0 < κ_t ≤ 1: one
/// message per failed check, naming it and its numbers; empty when all hold.
[[nodiscard]] std::vector<std::string> feasibility_problems(const SkinQuality& q);

}  // namespace dynmesh
