#pragma once
/// \file Meshing an unknown object by probing it (specs/probing.md §3–§5): Chew-style Delaunay
/// refinement in which every Voronoi edge is tested with a ray cast by a device that moves only
/// through free space, along Voronoi edges certified free by earlier probes.
///
/// The run keeps the Delaunay triangulation of the sample E (3D for a surface, 2D for a closed
/// curve in the plane z = 0); its simplices are the Voronoi vertices (nodes). A node is
/// *active* when a free path from outside Ω to it is known (its `prev` chain). Active nodes
/// probe their incident edges once each (memoised per directed edge, and inferred from the
/// other end's record when that one is known); a probe that hits S yields a ball of
/// Del^v_|S(E) centred at the hit; a probe that misses activates the node at the other end.
/// The largest ball bigger than ε is refined (its centre inserted) until none is left. The
/// output is the set of facets (2D: edges) whose dual Voronoi edge was hit (the visible
/// restricted Delaunay triangulation), oriented against the probe that found them.
///
/// Several components (spec §8.3): one bootstrap triangle per interior point; after the queue
/// empties, every interior point must be enclosed by a component of the output, else that
/// point's component is bootstrapped again from other points of ∂Ω and refinement resumes.
/// Components inside cavities of others cannot be reached from outside Ω (documented limit).
///
/// Positioning moves climb a chain to ∂Ω, travel on ∂Ω and descend (the via-root variant of
/// spec §3.5); their cost is accounted in O(1) from each node's stored depth and path length,
/// unless the safety monitor is on or the path is recorded, in which case the device walks
/// every segment.
///
/// `ProbingMode::Omniscient` is the baseline of the benchmarks: the same refinement, but every
/// Voronoi edge created is tested directly (a ray from whichever end is outside O, told by the
/// ground truth; for an edge with both ends inside O that still leaves O, from a free point of
/// it), and the device never moves.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/probing/oracle.hpp"

namespace dynmesh {

enum class ProbingMode {
    Device,      ///< the paper's algorithm: a device in free space, moving along certified edges
    Omniscient,  ///< every Voronoi edge tested from anywhere; no motion (baseline)
};

/// How the device gets from the node it sits on to the next node it must probe from (spec §3.5).
enum class ProbingPositioning {
    Lca,       ///< within one path tree: up to the two nodes' lowest common ancestor and down
    Boundary,  ///< always up to ∂Ω, along ∂Ω, and down (the simple variant, for ablations)
};

struct ProbingSnapshot;
struct ProbingProgress {
    std::size_t insertions = 0;  ///< samples inserted by refinement so far
    std::size_t queued = 0;      ///< ball entries in the queue (stale ones included)
    std::size_t probes = 0;
};

struct ProbingOptions {
    double eps = 0;                 ///< refinement size ε: no ball of Del^v larger than this
    /// A target Hausdorff distance δ instead of ε (used when eps is 0): ε is derived by
    /// probing_eps_from_delta (spec §2).
    std::optional<double> delta;
    double eps_S = 0;               ///< lower bound on the reach of S (assumption A3)
    Ball omega{};                   ///< Ω, contains S with a margin (assumption A2)
    std::vector<Point3> interior_points;  ///< one point inside each component of O (A1)
    bool allow_unguaranteed = false;      ///< accept ε ≥ 0.091·ε_S
    std::size_t max_points = 2'000'000;   ///< cap on |E| (InvalidInput beyond)
    ProbingMode mode = ProbingMode::Device;
    ProbingPositioning positioning = ProbingPositioning::Lca;
    /// Device mode: the safety monitor (checks only, never the algorithm): every segment the
    /// device travels is verified free, every exterior path outside Ω; a violation throws
    /// UnsafeMove naming the segment. Omniscient mode: required, tells which end of an edge
    /// is outside O.
    const GroundTruth* ground_truth = nullptr;
    /// Check the invariants (ProbingResult::problems) after every k-th insertion and at the
    /// end; 0: only at the end; SIZE_MAX: never.
    std::size_t check_every = 0;
    /// Keep the device's path as polylines (ProbingResult::path); the device then walks every
    /// segment of its positioning moves.
    bool record_path = false;
    /// Call on_snapshot after every k-th insertion (0: never) and once at the end.
    std::size_t snapshot_every = 0;
    std::function<void(const ProbingSnapshot&)> on_snapshot;
    /// Called about every 1,000 insertions.
    std::function<void(const ProbingProgress&)> on_progress;
};

/// ε from a target Hausdorff distance δ (spec §2): ε = ε_S·sqrt(δ / (4.5·2R_Ω)).
[[nodiscard]] double probing_eps_from_delta(double delta, double eps_S, double omega_radius);

/// The costs of a run, with the names of the CLI's report.
struct ProbingReport {
    std::size_t probes = 0;             ///< cast() calls, bootstrap included
    std::size_t probes_bootstrap = 0;   ///< casts of the bootstrap (and re-initialisations)
    std::size_t probes_inferred = 0;    ///< edge records inferred without a cast
    std::size_t voronoi_edges_travelled = 0;  ///< detection + positioning edge pieces
    std::size_t detection_edges = 0;
    std::size_t positioning_edges = 0;
    std::size_t voronoi_edges_created = 0;  ///< distinct facets of the simplices created
    double path_length = 0;           ///< travelled inside Ω
    double exterior_path_length = 0;  ///< travelled on or outside ∂Ω
    std::size_t cells_created = 0;    ///< Delaunay simplices = Voronoi vertices created
    std::size_t nodes_retained = 0;   ///< active nodes kept after their simplex died
    std::size_t activations = 0;      ///< in-Ω nodes made active by detect_access
    std::size_t detect_access_calls = 0;
    std::size_t queue_pushes = 0;
    std::size_t bootstrap_samples = 0;  ///< the first samples, from the bootstrap (spec §4.3)
    std::size_t insertions = 0;       ///< samples inserted by refinement
    std::size_t stale_pops = 0;
    std::size_t nonempty_pops = 0;  ///< popped balls that hold a sample (skipped; spec §8.2)
    std::size_t grazing_hits = 0;
    std::size_t reinitialisations = 0;  ///< components bootstrapped again (spec §8.3)
    std::size_t segments_checked = 0;   ///< by the safety monitor
    std::size_t vertices = 0, facets = 0;  ///< of the output (2D: facets = edges)
    std::size_t components = 0;            ///< of the output
    double max_ball_radius = 0;  ///< largest ball of the output's facets (≤ ε)
    double eps = 0;              ///< the ε of the run (derived from δ when given)
    double seconds = 0;
};

struct ProbingResult {
    std::vector<Point3> sample;  ///< E, in insertion order
    /// 3D: the facets of Del^v, oriented outward (points: the samples they use, in sample
    /// order). 2D: the points of the polygons, no triangles.
    TriangleSoup mesh;
    /// 2D: the closed polygons (indices into mesh.points, first index repeated at the end),
    /// counter-clockwise around O. Empty in 3D.
    std::vector<std::vector<std::uint32_t>> polygons;
    /// The device's path (ProbingOptions::record_path): one polyline per continuous stretch.
    std::vector<std::vector<Point3>> path;
    ProbingReport report;
    /// Violated invariants (spec §5.2: P1, P2, records of active nodes; hits on their current
    /// edge and their balls empty; interior points enclosed), each "after insertion k: ...".
    /// Empty when all hold.
    std::vector<std::string> problems;
};

/// The state handed to ProbingOptions::on_snapshot.
struct ProbingSnapshot {
    std::size_t insertions = 0;
    const TriangleSoup* mesh = nullptr;  ///< Del^v now (3D) or its polygon points (2D)
    const std::vector<std::vector<std::uint32_t>>* polygons = nullptr;  ///< 2D
    /// The device's path since the previous snapshot (empty unless record_path).
    const std::vector<std::vector<Point3>>* path = nullptr;
    bool final = false;
};

/// Meshes a surface. \throw InvalidInput for bad options (non-finite values, ε ≤ 0, ε ≥
/// 0.091·ε_S without allow_unguaranteed, no interior point, an interior point outside Ω, a
/// first probe that misses, a hit within the margin of ∂Ω, omniscient mode without a ground
/// truth); UnsafeMove when the safety monitor refuses a move.
[[nodiscard]] ProbingResult probe_surface(const Oracle& oracle, const ProbingOptions& options);

/// The 2D variant (spec §4.6): a closed curve in the plane z = 0 (interior points, Ω's centre
/// with z = 0). Same options and errors.
[[nodiscard]] ProbingResult probe_curve(const Oracle& oracle, const ProbingOptions& options);

}  // namespace dynmesh
