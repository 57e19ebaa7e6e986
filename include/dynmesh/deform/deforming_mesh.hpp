#pragma once
/// \file DeformingMesh: a surface mesh kept good while the surface deforms and is known only
/// through moving samples (Cheng & Dey, "Maintaining deforming surface meshes", SODA 2008;
/// digest `specs/deforming-mesh.md`).
///
/// Usage
/// \code
///   DeformOptions params;  params.lambda = 1e-3;
///   DeformingMesh dm(P0, params, {.surface = &sphere});   // t = 0
///   for (int t = 1; t <= T; ++t) {
///       auto step = dm.advance(t, positions_at(t));         // every integer time
///       if (step.update_due) dm.update(t);                  // a time step: MeshUpdate
///   }
/// \endcode
///
/// Time is discrete. `advance(t, positions)` is called for every integer t with the position
/// of every live sample (indexed by SampleId); the mesh vertices simply follow their samples.
/// At a time step (t == next_step(), or when a motion monitor trips and emergency steps are
/// on) `update(t)` runs the paper's MeshUpdate: RefineVert, then Insertion of the queued new
/// samples, then Deletion of the queued ids, then schedules t2 = t + floor(R / (kappa lambda)).
///
/// Insertions and deletions: `queue_insertion()` gives the new sample its id at once, but the
/// sample only joins P at the next update (the paper allows user edits at time steps only);
/// until then the caller must still pass its position to advance(). `queue_deletion()` keeps
/// the sample live until the next update.
///
/// Order of work: inside, the samples are numbered along a Morton curve of P(0) (inserted
/// samples follow in insertion order) and the mesh vertices in that order, so that RefineVert,
/// Decimation, the flips after Add and Remove and the measures visit the surface in a spatially
/// coherent order whatever the caller's numbering. Every output (sample_of, owner_of,
/// violation and invariant messages) uses the caller's SampleIds.
///
/// Determinism: equal inputs give bit-identical results; ties break on the internal order,
/// itself a function of P(0) alone.

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh {

/// Stable identifier of a sample: its index in the position table passed to advance().
using SampleId = std::uint32_t;
inline constexpr SampleId kNoSample = std::numeric_limits<SampleId>::max();

/// The paper's step constant (certified bounds hold for kappa >= 468).
inline constexpr double kPaperKappa = 468.0;
/// The practical default: vertices move at most R/32 between updates (< 10 % of the
/// shortest edge, which is >= R/3); justified by the kappa sweep in the README.
inline constexpr double kPracticalKappa = 32.0;

struct DeformOptions {
    /// Upper bound on how far any surface point moves in one time unit (> 0, required).
    double lambda = 0;
    /// Step constant: the next step is floor(R / (kappa * lambda)) time units later.
    double kappa = kPracticalKappa;
    /// The sampling radius h0 = eps(0) * gamma(0) of P(0). When unset it is estimated from
    /// InitialSurface::surface (dense probes) or, failing that, from the initial mesh.
    std::optional<double> h0;
    /// Last time unit of interest: no step is scheduled after it.
    int horizon = std::numeric_limits<int>::max();
    /// Run an update at once when a motion monitor trips (a deviation from the paper that
    /// keeps the mesh valid when the caller's motion breaks the model; logged).
    bool emergency_steps = true;
    /// Caps of the RefineVert and Deletion loops (reported when hit).
    std::size_t refine_max_iters = 64;
    std::size_t deletion_max_iters = 64;
    /// Run RefineVert to a fixed point at t = 0 (not in the paper): the state at 0 is then
    /// one that a rigid motion keeps, and the first steps do not pay for initialisation.
    bool init_refine = true;
    /// Spec §9 P7 (not in the paper): at the end of an update, when vertex pairs have come
    /// closer than R/3 (old vertices under compression), remove one vertex of each such pair
    /// (Decimation with radius R/3) and run RefineVert, so spacing >= R/3 holds at every step.
    bool spacing_repair = true;
    /// The spacing repair of an update at an integer time looks only where a close pair can
    /// be: around the vertices changed since its last scan of every vertex, and at the close
    /// pairs that scan found (a scan of every vertex again when R has grown since). false:
    /// every vertex at every update, the reference the incremental scan is tested against
    /// (the same removals).
    bool incremental_spacing = true;
    /// Spec §4.3: after the global flips of every update at an integer time (and at t = 0;
    /// not after the updates between sub-steps), check every
    /// triangle's diametric ball against a grid of the vertices and report the balls that
    /// hold one (Violation::NonEmptyBall). Costs about one global flip pass (some 60 % of a
    /// 100K-sample update on the sphere); off, only a flip loop that hits its cap is reported.
    bool verify_balls = true;
    /// Number of probe points for estimating h0 from InitialSurface::surface.
    std::size_t h0_probes = 200000;
    std::uint64_t seed = 1;
    /// Sub-stepping (spec §10.1; not in the paper): advance() cuts a time unit into
    /// n = ceil(max D / B) sub-steps, at most this many, with D the relative displacement of
    /// a mesh edge's ends or of a dormant sample and its owner over the unit, and B the
    /// budget 2 R / kappa (R = largest circumradius at the last update). Every sample moves
    /// linearly between its positions at t - 1 and t, and an update runs before any sub-step
    /// that would take some pair's relative displacement since the last update beyond B.
    /// A sub-step moves only the samples whose positions at t - 1 and t differ and measures
    /// only the pairs with an end among them (a best-fit turn of the whole that moves no
    /// sample by 1% of B is left out), so its cost follows the part that moves.
    /// When the motion meets the paper's model (relative displacement <= 2 lambda per unit,
    /// lambda <= R / kappa) this never fires and the run is the paper's. 1 turns it off (the
    /// paper's algorithm alone; floor(R / (kappa lambda)) = 0 is then Violation::StepTooShort).
    std::size_t max_substeps = 256;
    /// Spec §10.1: an update between sub-steps works on a region U only: the ends of the pairs
    /// whose relative displacement would exceed half the budget (the spec: the budget), and
    /// their 2-ring. RefineVert
    /// promotes the dormant samples of U's vertices, the flips start from U's edges (and
    /// propagate as far as they must), the spacing repair looks around U's vertices, and the
    /// strain is reset on U's pairs and on every edge the update made. When U holds more than
    /// half of the vertices the update is global. false: every update between sub-steps is
    /// global (MeshUpdate at the sub-step's positions).
    bool local_updates = true;
    /// Local size field (spec §10.2; not in the paper): a sample's size is
    /// r(p) = min(R, size_factor * lfs(p)) instead of the global R (R = the largest
    /// circumradius, as in the paper), with lfs its local feature size: from
    /// InitialSurface::feature_size when given, else estimated on InitialSurface::reference
    /// (mesh_feature_size, graded by `grading` along the mesh) or taken from
    /// InitialSurface::surface. r replaces R in RefineVert's R/3 (promotion and placing), the
    /// Decimation and spacing-repair radii and the spacing invariant, and sets each pair's
    /// sub-step budget 2 r / kappa; samples inserted later take r(w) + grading |p - w| from
    /// their nearest vertex w. Where size_factor lfs >= R everywhere the run is the paper's
    /// (the analytic scenarios). About 9 vertices around a circular section at 0.4, the spec's
    /// value and the default; 0 turns it off (the paper's global R). With a reference mesh
    /// the net and RefineVert's fixed point on the reference follow r, so thin parts are
    /// resolved in Tri(0) before any Add. r has no floor: where a part is thinner than the
    /// samples are dense, every sample there becomes a vertex and the triangles are as good as
    /// the samples allow (a floor at twice the sample spacing was tried and made more runs
    /// fail: the spacing repair then thins such parts).
    double size_factor = 0.4;
    /// Lipschitz constant of the size along the surface (>= 0).
    double grading = 0.3;
    /// Creases (spec §10.3; not in the paper): at t = 0, the edges of InitialSurface::
    /// reference (or of InitialSurface::mesh) whose 180 - dihedral angle exceeds this many
    /// degrees are creases (mark_creases(); chains of fewer than 3 edges dropped, so a coarse
    /// CAD mesh may have none), cut into polylines between corners (where 1 or 3+ meet). The
    /// mesh carries them as locked edges (kLockedEdges) between consecutive crease vertices:
    /// - Tri(0) is the reference decimated to the net (spec §10.5 A: corners, then crease
    ///   samples, then the others). This needs the net to be reference vertices (same
    ///   coordinates); otherwise the restricted Delaunay path is taken and the creases are
    ///   dropped (Violation::InitFallback).
    /// - No flip touches a crease edge. Departure from the spec: the dihedral-angle guard of
    ///   flip_verdict() is not kept as a second lock (it also locks edges the motion folded).
    /// - Remove collapses a crease vertex along its crease onto a neighbour (the spec
    ///   re-triangulates each side by a CDT with the new crease edge constrained; the result
    ///   has the same edges on the crease); a corner is never removed; the Decimation never
    ///   picks a corner, prefers removing a surface vertex to a crease vertex, and the
    ///   Deletion's decimation leaves crease vertices to the spacing repair.
    /// - A dormant crease sample becomes a vertex only by splitting the crease edge between
    ///   its polyline's neighbouring vertices; a sample inserted later that lands on a crease
    ///   edge joins that polyline (between the samples it lies between) and splits it.
    ///   Dormant crease samples attach to the nearest vertex of any kind (the spec: of their
    ///   own polyline).
    /// - Crease edges are no folds for the monitors; the diametric-ball diagnostic counts a
    ///   vertex only for the triangles of its own patches.
    /// check_invariants() checks that every polyline's vertices are joined by crease edges and
    /// the corners keep theirs; the spacing invariant does not count a pair of corners. Without a reference or a given mesh it does nothing. 180 (the
    /// default) = off.
    double feature_angle_deg = 180.0;
    /// Spec §10.4 (with sub-stepping): a unit that ends with a new fold (an edge-angle <= 90
    /// degrees) or (with intersection_checks) a self-intersection is redone from its start
    /// with twice the sub-steps, at most this many times (0: never).
    std::size_t max_retries = 3;
    /// Test the whole mesh for self-intersections at the end of every unit (CGAL's
    /// self_intersections: O(F log F), about an update's cost) and retry as above.
    bool intersection_checks = true;
};

/// What the library knows about Sigma(0) besides the samples (all optional). Tri(0) comes
/// from the first of: mesh, reference, surface; without any, it is reconstructed with CGAL's
/// advancing front (which needs dense samples).
struct InitialSurface {
    /// The surface itself: h0 is estimated by probing it, and Tri(0) is the restricted
    /// Delaunay triangulation of Vert(0).
    const ImplicitSurface* surface = nullptr;
    /// A caller-supplied closed triangulation of Vert(0): mesh vertex i is sample
    /// vertex_samples[i]. Used as Tri(0) as it is (spec §4.1 (a)).
    const SurfaceMesh* mesh = nullptr;
    std::vector<SampleId> vertex_samples;
    /// A closed mesh of Sigma(0) whose vertices need not be samples (e.g. the input mesh the
    /// samples were taken from; spec §10.5 B). h0 is estimated from it (covering radius of its
    /// vertices and face barycentres), and Tri(0) is the restricted Delaunay triangulation of
    /// Vert(0) against it (restricted_delaunay_on_mesh(): AABB-tree queries on this mesh, with
    /// samples added where the net is too sparse for it), with its Euler characteristic and
    /// number of components. Nothing is reconstructed.
    const SurfaceMesh* reference = nullptr;
    /// Local feature size of Sigma(0) at each sample (SampleId order), when the caller knows
    /// it; otherwise it is estimated (DeformOptions::size_factor).
    std::vector<double> feature_size;
};

/// Motion-model monitors and algorithm diagnostics (spec §9 P5). None is silent.
enum class Violation {
    DisplacementExceedsLambda,  ///< a sample moved more than lambda in one time unit
    StepTooShort,               ///< floor(R / (kappa lambda)) = 0: the motion is too fast
    EdgeAngleBelow90,           ///< an edge-angle dropped to <= 90 degrees between steps
    NormalInverted,             ///< a triangle normal turned by more than 90 degrees
    CircumradiusGrowth,         ///< R(t) exceeded the L3.6 bound times R at the last step
    RefineCapHit,               ///< RefineVert hit refine_max_iters
    DeletionCapHit,             ///< Deletion hit deletion_max_iters
    AddVertexCase,              ///< Add found the sample on an existing vertex, or on a crease edge it may not split (kept dormant)
    FarSample,                  ///< a sample lies farther than 2R from the mesh (kept dormant)
    AddFolded,  ///< Add would fold the mesh or make it intersect itself; undone, kept dormant
    RemoveFailed,               ///< a vertex removal found no valid re-triangulation
    /// A diametric ball holds a vertex once an update's (or the initialisation's) global flips
    /// are done (DeformOptions::verify_balls), or a flip loop stopped at its cap.
    NonEmptyBall,
    /// Not raised any more: an update never rebuilds the mesh from scratch (spec §10.4; a fold
    /// or an intersection goes through the unit redo of advance() and, failing that, is
    /// reported). The kind, like TopologyRollback, stays for the reports' stable keys.
    Rebuild,
    TopologyRollback,  ///< not raised any more (see Rebuild)
    Coarsened,                  ///< one update raised R by more than 2x (e.g. a hole was cut)
    /// Tri(0) on the reference mesh had to decimate the reference (no restricted Delaunay
    /// triangulation with its topology; the detail says where).
    InitFallback,
    /// A time unit needed more sub-steps than DeformOptions::max_substeps; the cap was used.
    SubstepCapHit
};
[[nodiscard]] std::string_view to_string(Violation v);

struct ViolationRecord {
    int t = 0;
    Violation kind = Violation::StepTooShort;
    std::string detail;
};

/// Work done by one update (or accumulated over many).
struct UpdateCounters {
    std::size_t flips = 0;
    std::size_t insertions = 0;  ///< Add operations (samples made vertices)
    std::size_t removals = 0;    ///< Remove operations (vertices removed)
    std::size_t dormant_moves = 0;
    std::size_t refine_passes = 0;
    std::size_t deletion_iterations = 0;
    std::size_t flip_refusals = 0;    ///< flips refused by the circumradius guard (spec §9 P9)
    std::size_t spacing_repairs = 0;  ///< updates that ran the spacing repair (spec §9 P7)
    std::size_t samples_inserted = 0;  ///< user insertions applied
    std::size_t samples_deleted = 0;   ///< user deletions applied
    std::size_t rebuilds = 0;          ///< always 0 (see Violation::Rebuild); kept for the reports
    std::size_t rollbacks = 0;         ///< always 0 (see Violation::Rebuild); kept for the reports
    std::size_t distance_evals = 0;
    double seconds = 0;
    UpdateCounters& operator+=(const UpdateCounters& o);
    [[nodiscard]] std::size_t changes() const { return flips + insertions + removals; }
};

struct DeformUpdateReport {
    int t = 0;
    bool emergency = false;  ///< run because a monitor tripped, not because t was a step
    UpdateCounters counters;
    double R_before = 0, R_after = 0;  ///< largest circumradius at the start and the end
    int next_step = 0;
    std::size_t samples = 0, vertices = 0;  ///< at the end
    std::size_t vertices_before = 0;        ///< at the start
    std::vector<ViolationRecord> violations;
};

struct StepReport {
    int t = 0;
    bool update_due = false;  ///< t is a time step (or an emergency update is requested)
    bool emergency = false;   ///< update_due because a monitor tripped
    double max_displacement = 0;  ///< largest sample displacement since the last time unit
    double R = 0;                 ///< current largest circumradius
    /// Sub-steps the unit was cut into (1: moved at once; DeformOptions::max_substeps).
    std::size_t substeps = 1;
    /// Updates run inside the unit, before a sub-step, to keep the budget (their work is in
    /// `internal`; the caller's update() at t is not among them).
    std::size_t internal_updates = 0;
    /// Of those, the updates restricted to a region (DeformOptions::local_updates), and their
    /// regions' vertices summed (a global update counts none).
    std::size_t local_updates = 0, region_vertices = 0;
    UpdateCounters internal;
    /// Largest (relative displacement since the last update) / budget over the pairs at any
    /// sub-step of the unit: <= 1 unless an update's new edges move faster than the budget
    /// allows in one sub-step.
    double max_strain_ratio = 0;
    /// The unit's end state (spec §10.4): triangles whose normal turned by 90 degrees or more
    /// since the last update, edges newly folded to an edge-angle <= 90 degrees, and (with
    /// DeformOptions::intersection_checks) whether the mesh intersects itself.
    std::size_t inverted_triangles = 0, new_folds = 0;
    bool self_intersecting = false;
    /// Times the unit was redone from its start with twice the sub-steps because its end
    /// state had a new fold or a self-intersection (DeformOptions::max_retries); the report
    /// is the last try's.
    std::size_t retries = 0;
    std::vector<ViolationRecord> violations;
};

/// One update raising R by more than this factor is reported (Violation::Coarsened).
inline constexpr double kCoarseningWarningFactor = 2.0;

struct InvariantOptions {
    bool self_intersections = true;  ///< run the (n log n) self-intersection test
    bool empty_balls = true;         ///< every diametric ball empty of vertices
    /// Count non-empty balls without failing on them (they can survive where the
    /// circumradius guard refused a flip on sparse samples, spec §9 P9).
    bool empty_balls_soft = false;
    /// Slack factors for checks that hold between steps only up to the L3.6 constants.
    /// Every triangle's radius-edge ratio <= this (times 1 + 2 grading with a size field).
    double radius_edge_bound = 3.0;
    /// Every vertex pair >= spacing_factor * R (* min(r_u, r_v) with a size field).
    double spacing_factor = 1.0 / 3.0;
    double dormant_factor = 1.25;       ///< every dormant point within dormant_factor * R
};

struct InitReport {
    double h0 = 0;
    bool h0_estimated = false;
    std::size_t samples = 0, vertices = 0, faces = 0;
    double R0 = 0;
    int next_step = 0;
    std::size_t init_flips = 0;
    /// How Tri(0) was built: "given" (InitialSurface::mesh), "restricted_delaunay" or
    /// "decimated" (on InitialSurface::reference), "restricted_delaunay_surface",
    /// "advancing_front".
    std::string tri0;
    std::size_t net = 0;        ///< the h0-net Vert(0) before Tri(0) was built
    std::size_t net_added = 0;  ///< samples the restricted Delaunay rounds added to the net
    std::size_t init_removals = 0;  ///< vertices the spacing repair removed at t = 0
    long long euler = 0;            ///< Euler characteristic of Tri(0), kept by every update
    std::size_t components = 0;     ///< connected components of Tri(0)
    /// check_invariants() at t = 0 (without the self-intersection test; spec §4.1): its
    /// failures other than non-empty diametric balls (empty when the invariants hold), and
    /// those balls apart.
    std::vector<std::string> invariant_failures;
    std::size_t nonempty_balls = 0;
    std::string first_nonempty_ball;
    /// Tri(0) intersects itself (CGAL's exact test of the whole mesh, run once at t = 0; the
    /// tests after it look only at what changed since).
    bool self_intersecting = false;
    /// Samples made vertices by running RefineVert to a fixed point at t = 0 (not in the
    /// paper's initialisation; it makes the state at t = 0 one that a rigid motion keeps),
    /// on the reference mesh's vertex set or by Add.
    std::size_t init_insertions = 0;
    /// Creases found at t = 0 (DeformOptions::feature_angle_deg): edges, polylines, corners.
    std::size_t crease_edges = 0, crease_lines = 0, corners = 0;
    double seconds = 0;
};

class DeformingMesh {
public:
    /// Initialisation at t = 0 (spec §4.1): h0, farthest-point Vert(0), dormant lists,
    /// Tri(0), first step. positions[i] is sample i.
    /// \throw InvalidInput for lambda <= 0 or non-finite, kappa <= 0, fewer than 4 samples,
    ///        a non-finite position (naming the id), coincident samples, a sample set too
    ///        sparse to mesh (the initial mesh is not a closed manifold, or, with a
    ///        reference, has not its topology after the refinement rounds), or an inconsistent
    ///        InitialSurface::mesh.
    DeformingMesh(std::span<const Point3> positions, const DeformOptions& params,
                  const InitialSurface& initial = {});
    ~DeformingMesh();
    DeformingMesh(DeformingMesh&&) noexcept;
    DeformingMesh& operator=(DeformingMesh&&) noexcept;

    [[nodiscard]] const InitReport& init_report() const;

    /// Moves every live sample to positions[id] at integer time t (> the last t). The size of
    /// positions must be at least id_capacity(); entries of deleted ids are ignored.
    /// Runs the motion monitors. \throw InvalidInput for a short table, t not increasing, or
    /// a non-finite position of a live sample (naming the id).
    StepReport advance(int t, std::span<const Point3> positions);

    /// MeshUpdate at the current time (the t of the last advance(), or 0): RefineVert,
    /// Insertion of the queued samples, Deletion of the queued ids, next step. May be called
    /// early (correct, but voids the optimality of the schedule).
    DeformUpdateReport update();

    /// Queues a new sample at p (current time); returns its id. It joins P at the next update.
    SampleId queue_insertion(const Point3& p);
    /// Queues the deletion of a live sample. \throw InvalidInput for an unknown or dead id.
    void queue_deletion(SampleId id);

    [[nodiscard]] int time() const;
    [[nodiscard]] int next_step() const;
    [[nodiscard]] double lambda() const;
    [[nodiscard]] const DeformOptions& params() const;

    [[nodiscard]] const SurfaceMesh& mesh() const;
    /// The sample a mesh vertex is (kNoSample for an invalid vertex).
    [[nodiscard]] SampleId sample_of(Vertex v) const;
    /// The mesh vertex of a sample, or an invalid handle when it is dormant or dead.
    [[nodiscard]] Vertex vertex_of(SampleId id) const;
    /// For a dormant sample: the sample id of its owning vertex; kNoSample otherwise.
    [[nodiscard]] SampleId owner_of(SampleId id) const;
    /// One past the largest id handed out (position tables must be at least this long).
    [[nodiscard]] std::size_t id_capacity() const;
    [[nodiscard]] bool is_live(SampleId id) const;
    [[nodiscard]] std::size_t live_samples() const;
    [[nodiscard]] double max_circumradius() const;
    /// Every violation recorded so far.
    [[nodiscard]] const std::vector<ViolationRecord>& violations() const;
    /// Totals over all updates.
    [[nodiscard]] const UpdateCounters& totals() const;
    [[nodiscard]] std::size_t updates() const;

    /// The invariants of the paper computable from the samples (spec §3, §8.2): mesh
    /// validity (closed oriented manifold, Euler characteristic and components unchanged), radius-edge
    /// ratios, spacing >= R/3, dormant lists partition P \ Vert with every dormant point
    /// within 5R/4 of its owner, empty diametric balls, no self-intersection.
    /// Problems: one line per failed check, with a location (the first 50 listed, all counted).
    /// Figures, always all of them in this order: R (largest circumradius), min_spacing
    /// (shortest vertex-vertex distance, 0 when R is 0), max_radius_edge,
    /// max_dormant_distance (over dormant samples, the distance to the owner), and as
    /// Integer: nonempty_balls, self_intersections (0 when not tested), samples (vertices and
    /// dormant), vertices, dormant. Notes: with empty_balls_soft, the first non-empty
    /// diametric ball (its triangle and a vertex in it) when there is one.
    [[nodiscard]] CheckReport check_invariants(const InvariantOptions& options = {}) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace dynmesh
