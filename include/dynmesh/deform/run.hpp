#pragma once
/// \file run_deform(): drives a DeformingMesh through a Scenario (the caller of the paper):
/// moves the samples with the scenario's warp at every time unit, runs the update at each
/// time step (or at every unit, for comparison), inserts and deletes samples to keep the
/// density when the scenario asks for it, and measures the mesh against the ground truth at
/// every time unit.

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/deform/deforming_mesh.hpp"
#include "dynmesh/deform/ground_truth.hpp"
#include "dynmesh/deform/scenario.hpp"

namespace dynmesh {

enum class Schedule {
    Paper,     ///< update at the paper's time steps t2 = t1 + floor(R / (kappa lambda))
    EveryStep  ///< update at every time unit (the naive maintenance the paper improves on)
};
[[nodiscard]] std::string_view to_string(Schedule s);
/// "paper" or "every-step". \throw InvalidInput.
[[nodiscard]] Schedule parse_schedule(std::string_view name);

/// One time unit as seen by the callbacks.
struct DeformFrame {
    int t = 0;
    bool updated = false;     ///< an update ran at t
    bool emergency = false;   ///< ... because a motion monitor tripped
    const DeformingMesh* mesh = nullptr;
    const FrameMetrics* metrics = nullptr;  ///< h and Hausdorff are NaN between full measures
    UpdateCounters counters;  ///< work of the update at t (zero when none ran)
    std::size_t violations = 0;  ///< monitors and diagnostics raised at t
    std::size_t substeps = 1;          ///< StepReport::substeps of the unit ending at t
    std::size_t internal_updates = 0;  ///< StepReport::internal_updates (work in counters)
};

struct DeformRunOptions {
    Schedule schedule = Schedule::Paper;
    /// kappa, emergency steps, caps (lambda, h0 and horizon come from the scenario).
    DeformOptions params;
    /// Shape, normal deviation, inversions and self-intersections are measured at every time
    /// unit; the sampling radius h and the Hausdorff distance (which warp and search the whole
    /// reference) every this many units (and at t = 0 and T). 0: measure nothing but t = 0
    /// and T (for counting changes over long runs).
    int measure_every = 1;
    MeasureOptions measure{.hausdorff = true, .self_intersections = true, .sampling_radius = true};
    /// Run DeformingMesh::check_invariants() after every update (reported, never fatal; see
    /// check_failures()).
    bool check_invariants = false;
    /// Stop after this time unit (0: run to the scenario's horizon). The schedule still plans
    /// for the whole horizon; "the end" of the run (final measure, time_units) is this unit.
    int stop_after = 0;
    std::function<void(const DeformFrame&)> on_frame;
};

/// One line of the per-time-unit log.
struct DeformLogRow {
    FrameMetrics metrics;  ///< h, R_over_h, hausdorff* NaN when !measured
    bool measured = false;  ///< h and the Hausdorff distance were measured
    bool update = false;
    bool emergency = false;
    /// Work of the updates at t: the caller's update and the sub-step updates inside the
    /// unit ending at t.
    UpdateCounters counters;
    std::size_t violations = 0;
    std::size_t substeps = 1;          ///< sub-steps of the unit ending at t
    std::size_t internal_updates = 0;  ///< updates between sub-steps of that unit
    double max_strain_ratio = 0;       ///< StepReport::max_strain_ratio
};

struct DeformRunReport {
    std::string scenario;
    std::string schedule;
    double kappa = 0, lambda = 0, h0 = 0;
    std::size_t samples = 0;  ///< |P(0)|
    int time_units = 0;
    std::size_t updates = 0, emergency_updates = 0;
    /// Sub-stepping (DeformOptions::max_substeps): sub-steps over all time units, the most in
    /// one unit, the updates run between sub-steps (not in `updates`) and the largest strain
    /// ratio (StepReport::max_strain_ratio) of any unit.
    std::size_t substeps = 0, max_substeps_per_unit = 0, internal_updates = 0;
    /// Units redone with twice the sub-steps (StepReport::retries, summed).
    std::size_t substep_retries = 0;
    double max_strain_ratio = 0;
    std::size_t flips = 0, insertions = 0, removals = 0;
    std::size_t samples_inserted = 0, samples_deleted = 0;
    double seconds_updates = 0;  ///< time in DeformingMesh::update() alone
    double seconds_init = 0;
    double seconds_total = 0;
    // Worst values over every measured time unit.
    double worst_hausdorff_over_eps = 0;  ///< Hausdorff / h (h = eps gamma measured)
    double worst_min_angle_deg = 180;
    double worst_min_angle_off_creases_deg = 180;  ///< triangles with no crease vertex
    double worst_max_radius_edge = 0;
    double worst_R_over_h = 0;
    double worst_normal_dev_deg = 0;
    double worst_min_edge_angle_deg = 180;
    std::size_t self_intersections = 0;  ///< summed over all measured time units
    std::size_t inverted = 0;            ///< summed over all measured time units
    /// Updates after which check_invariants() failed (t = 0 counts as one, from
    /// InitReport::invariant_failures).
    std::size_t invariant_failures = 0;
    std::vector<std::string> first_invariant_failures;
    /// Diametric balls holding a vertex after an update (with check_invariants; t = 0 counts
    /// as one): largest count after one update, and the sum over updates (spec §9 P9).
    std::size_t nonempty_balls_max = 0, nonempty_balls_total = 0;
    std::size_t updates_with_nonempty_balls = 0;
    /// "t=T: the diametric ball of triangle (a, b, c) holds ..." for the first 10 such updates.
    std::vector<std::string> first_nonempty_balls;
    std::map<std::string, std::size_t> violations;  ///< by kind
    /// The first kViolationExamples records of every kind (t = 0: initialisation), by time.
    std::vector<ViolationRecord> violation_examples;
    /// Always 0 since updates never rebuild from scratch (Violation::Rebuild); kept so that
    /// scripts reading the report find them.
    std::size_t rebuilds = 0, rollbacks = 0;
    std::size_t flip_refusals = 0;  ///< flips refused by the circumradius guard (spec §9 P9)
    /// First time unit with a self-intersection / an inverted triangle (-1: none).
    int first_self_intersection_t = -1, first_inverted_t = -1;
    /// Where: "triangles (a, b, c) and (d, e, f)" / "triangle (a, b, c)" (sample ids; an
    /// inverted triangle's normal points against the sum of the true normals at its
    /// vertices). Empty when there is none.
    std::string first_self_intersection, first_inverted;
    /// Tri(0): vertices and Euler characteristic (kept by every update).
    std::size_t init_vertices = 0;
    std::size_t crease_edges = 0, crease_lines = 0, corners = 0;  ///< InitReport's
    long long euler = 0;
    /// Events to show even without --check, one line each with its time unit: every update
    /// that coarsened the mesh (R more than kCoarseningWarningFactor times larger) and a
    /// Tri(0) built by decimating the input mesh (t = 0); at most
    /// kMaxWarnings lines, then one line counting the rest.
    std::vector<std::string> warnings;
    std::vector<DeformLogRow> log;
};

inline constexpr std::size_t kViolationExamples = 5;
inline constexpr std::size_t kMaxWarnings = 100;

/// How much `dynmesh deform --check` demands.
enum class CheckLevel {
    Off,
    /// `--check`: the maintained mesh is a valid mesh of Sigma at every update: the invariants
    /// of check_invariants() (needs DeformRunOptions::check_invariants; t = 0 included):
    /// closed oriented manifold with Tri(0)'s Euler characteristic and components, dormant
    /// lists, radius-edge <= 3, spacing >= R/3, dormant points within 5R/4; no
    /// self-intersection and no inverted triangle at any measured time unit.
    Invariants,
    /// `--check=strict`: also the paper's Delaunay property and model: no diametric ball
    /// holding a vertex after any update (t = 0 included), and none of the monitors and
    /// diagnostics the report lists (violations of any kind: step_too_short,
    /// displacement_exceeds_lambda, edge_angle_below_90, normal_inverted,
    /// circumradius_growth, refine_cap_hit, deletion_cap_hit, add_vertex_case, far_sample,
    /// add_folded, remove_failed, non_empty_ball, rebuild, rollback, coarsened,
    /// init_fallback).
    Strict
};
[[nodiscard]] std::string_view to_string(CheckLevel level);
/// "off", "invariants" (or "on", what a bare --check means) or "strict". \throw InvalidInput.
[[nodiscard]] CheckLevel parse_check_level(std::string_view name);

/// Every reason the run fails `level` as the report's problems (no figures), one line each
/// naming the time unit ("t=12: ...") and the place (triangle or sample ids) where the report
/// has it; ok() when it passes (always for CheckLevel::Off). A kind with more records than
/// the report keeps ends with a line counting the rest.
[[nodiscard]] CheckReport check_failures(const DeformRunReport& report, CheckLevel level);

/// Runs the scenario from t = 0 to its horizon.
DeformRunReport run_deform(const Scenario& scenario, const DeformRunOptions& options = {});

/// The log as CSV (header + one row per time unit): the FrameMetrics columns (flatten()
/// names), then update, emergency, flips, insertions, removals, samples_inserted,
/// samples_deleted, violations, update_seconds.
[[nodiscard]] std::string log_csv(const DeformRunReport& report);

}  // namespace dynmesh
