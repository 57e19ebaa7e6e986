#pragma once
/// \file The growing skin (specs/skin-surfaces.md §2–§4, with the corrections of §8): every
/// weight grows by t, from t_start (before the first atom is born) to t_end, and a mesh of the
/// skin Φ = t is kept the whole way.
///
/// - Vertices move with the surface along ∇Φ/‖∇Φ‖² (§2.3), lazily: each keeps a reference
///   position, time and mixed cell, and is moved in closed form (SkinFunction::flow_in_cell)
///   only when an element it belongs to is looked at, handing off between mixed cells.
/// - The size bounds [L] (edges not too short) and [U] (triangles not too large) are kept by
///   edge contractions and by insertions near circumcentres (the deforming-mesh Add, with its
///   diametric-ball flips), acting only in the gray zone between Q0 and Q1 (§4.1).
/// - Relaxed scheduling (§4.4–§4.5): each edge and triangle is checked when its safe duration
///   (Length Lemma; composite triangle bound with κ_t) runs out, from one event queue; the
///   every-step scheduler checks every element at each global step, the step being the
///   smallest safe duration of the mesh (as safe as relaxed, and the baseline it is measured
///   against).
/// - Topology changes at the critical events of the alpha-complex filtration (§2.2, §3.3):
///   births insert a level-2 icosphere, deaths remove the shrinking void; a neck or a tunnel
///   closing is surgery inside the ball B(z_δ, r_δ), r_δ half the inradius of the mixed cell,
///   where the skin is one quadric: the mesh in the ball is cut out when the skin enters the
///   inner ball (δ_in·r_δ) and the hole's two boundary loops are closed by a template (two
///   cones in the two-sheeted phase, a drum around the waist ring in the one-sheeted one),
///   swapped at t = W_δ and dissolved when the skin leaves the inner ball. Template elements
///   are exempt from the bounds and from scheduling; at dissolution each is checked at once.
///
/// Counters follow §8 correction 2: `violations` (the digest's miss: an element acceptable at
/// its previous check found beyond the Q1 threshold at or before its next one) must stay 0;
/// `born_bad` counts elements created beyond it (repaired at once), by cause.

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/skin/safe_duration.hpp"
#include "dynmesh/skin/skin_function.hpp"

namespace dynmesh {

enum class SkinSchedule {
    Relaxed,   ///< each element checked when its safe duration runs out (§4.5)
    EveryStep  ///< every element checked at every global step (the baseline of §4.6)
};

/// "relaxed" or "every-step".
[[nodiscard]] const char* schedule_name(SkinSchedule s);

/// The mesh at one time of the growth, garbage-collected: ϱ per vertex and the template
/// triangles of surgery in progress (exempt from the bounds) per face.
struct SkinSnapshot {
    double time = 0;
    SurfaceMesh mesh;
    std::vector<double> rho;
    std::vector<bool> exempt;
};

struct SkinGrowthOptions {
    SkinQuality quality{};
    SkinSchedule schedule = SkinSchedule::Relaxed;
    /// Every-step scheduler only: a fixed global step h instead of the adaptive one (the
    /// smallest safe duration in the mesh). A fixed h can let misses through (§4.6: "report a
    /// fixed user h and the violations it lets through"); 0 is the adaptive step.
    double fixed_step = 0;
    /// The smallest fixed step accepted, as a fraction of the growth's time span.
    static constexpr double kMinFixedStep = 1e-9;
    double t_end = 0;          ///< the growth stops here (0: the input radii)
    /// Snapshots at t_start + i·(t_end − t_start)/snapshots, i = 1 … snapshots (the last at
    /// t_end); 0 gives none but the final mesh.
    std::size_t snapshots = 0;
    /// The auditor of §8 correction 2: each element is also evaluated at 20 uniform times
    /// between consecutive checks, and a crossing of the Q1 threshold counts as a violation.
    bool audit = false;
    /// The floor h_min under ϱ (spec U9), as a fraction of the mean atom radius √(s·w):
    /// elements whose ϱ is under it are measured with it and left out of the violation count.
    double rho_floor_factor = 1e-2;
    double neighbourhood = 0.5;  ///< r_δ = neighbourhood · inradius(μ_δ) (§3.3)
    double inner = 0.5;          ///< δ_in: the window is while the skin is within δ_in·r_δ of z_δ
    double birth_radius = 0.05;  ///< births and deaths at radius birth_radius · inradius
    /// The run stops with an error naming the time and the place when its checks exceed this
    /// (a mesh that does not settle, instead of a run that never ends).
    std::size_t max_checks = 200'000'000;
    /// Called at each snapshot time (vertices on the skin at that time).
    std::function<void(const SkinSnapshot&)> on_snapshot;
    /// Called about every 1% of the time span with the current time.
    std::function<void(double time)> progress;
};

struct SkinGrowthCounters {
    std::size_t checks_edge = 0, checks_triangle = 0;
    std::size_t contractions = 0, insertions = 0, flips = 0;
    std::size_t births = 0, deaths = 0, necks = 0, tunnels = 0;
    std::size_t refused_contractions = 0, refused_insertions = 0;
    /// Operations put off because they touched a template (retried later).
    std::size_t deferred = 0;
    std::size_t violations = 0;                   ///< misses (§8 correction 2); must be 0
    std::map<std::string, std::size_t> born_bad;  ///< by cause: flip, contraction, insertion, dissolution, remesh, floor
    /// Checks that found an element beyond the Q1 threshold whose previous check had found it
    /// beyond already (its repair was refused or undone by a neighbouring operation); not misses.
    std::size_t still_bad = 0;
    /// The whole mesh remeshed by mesh_skin: at a surgery that could not use its template (no
    /// two loops in the ball, a neck under the floor of ϱ), when the repairs of one instant
    /// did not settle (more than 20 checks per triangle at one time), or before a snapshot
    /// with triangles turned against the skin's normal (a fold).
    std::size_t fallbacks = 0;
    std::size_t flow_fallbacks = 0;  ///< vertex moves done by Newton projection instead of the flow
    std::size_t evaluations = 0;     ///< vertex positions evaluated
    std::size_t heap_pushes = 0;
    std::size_t steps = 0;           ///< global steps (every-step scheduler)
    std::size_t audit_samples = 0;
    [[nodiscard]] std::size_t checks() const { return checks_edge + checks_triangle; }
    [[nodiscard]] std::size_t actions() const {
        return contractions + insertions + births + deaths + necks + tunnels;
    }
};

struct SkinGrowthReport {
    double t_start = 0, t_end = 0;
    std::size_t events = 0;     ///< critical events in (t_start, t_end]
    std::size_t snapshots = 0;
    SkinGrowthCounters counters;
    double rho_floor = 0;
    double seconds = 0;
    /// The first violations, one line each (element, time, ratio, previous check, where).
    std::vector<std::string> violation_examples;
    /// Why the mesh was remeshed, each time (the first ten).
    std::vector<std::string> fallback_reasons;
};

struct SkinGrowthResult {
    SkinSnapshot final;        ///< the mesh at t_end
    SkinGrowthReport report;
};

/// The time the growth starts: −max w − τ_b of the first birth (§8 correction 6).
[[nodiscard]] double skin_growth_start(const SkinFunction& phi, const SkinGrowthOptions& options = {});

/// Grows the skin of phi (s = 1/2) from skin_growth_start() to options.t_end.
/// \throw InvalidInput when s ≠ 1/2, the quality constants fail the feasibility checks, or
///        t_end is before the first birth.
[[nodiscard]] SkinGrowthResult grow_skin(const SkinFunction& phi, const SkinGrowthOptions& options = {});

/// The inradius of mixed cell μ_k about z_k: min((1 − s)·d_δ, s·d_ν) (§1.3), d_δ the distance
/// from z_k to the boundary of δ inside aff δ, d_ν to the boundary of ν_δ inside aff ν_δ
/// (infinite for a vertex and a tetrahedron respectively).
[[nodiscard]] double mixed_cell_inradius(const SkinFunction& phi, std::size_t k);

}  // namespace dynmesh
