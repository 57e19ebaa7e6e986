#pragma once
/// \file Meshing an unknown object by probing it (specs/probing.md §3–§5): Chew-style Delaunay
/// refinement in which every Voronoi edge is tested with a ray cast by a device that moves only
/// through free space, along Voronoi edges certified free by earlier probes.
///
/// The run keeps the 3D Delaunay triangulation of the sample E; its cells are the Voronoi
/// vertices (nodes). A node is *active* when a free path from outside Ω to it is known (its
/// `prev` chain). Active nodes probe their incident edges once each (memoised per directed
/// edge); a probe that hits S yields a ball of Del^v_|S(E) centred at the hit; a probe that
/// misses activates the node at the other end. The largest ball bigger than ε is refined
/// (its centre inserted) until none is left. The output is the set of facets whose dual edge
/// was hit (the visible restricted Delaunay triangulation), oriented against the probe that
/// found them.
///
/// Scope of this version: one component (one interior point), 3D. Positioning moves climb to
/// ∂Ω and descend (the via-root variant of spec §3.5).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/probing/oracle.hpp"

namespace dynmesh {

struct ProbingOptions {
    double eps = 0;                 ///< refinement size ε: no ball of Del^v larger than this
    double eps_S = 0;               ///< lower bound on the reach of S (assumption A3)
    Point3 omega_center{};          ///< Ω = B(omega_center, omega_radius) contains S
    double omega_radius = 0;
    std::vector<Point3> interior_points;  ///< one point inside each component of O (A1)
    bool allow_unguaranteed = false;      ///< accept ε ≥ 0.091·ε_S
    std::size_t max_points = 2'000'000;  ///< cap on |E| (InvalidInput beyond)
    /// The safety monitor (checks only, never the algorithm): every segment the device is
    /// about to travel inside Ω is verified free; a violation throws InternalError naming it.
    const GroundTruth* ground_truth = nullptr;
    /// Check the invariants (ProbingResult::problems) after every k-th insertion and at the
    /// end; 0: only at the end; SIZE_MAX: never.
    std::size_t check_every = 0;
};

/// ε from a target Hausdorff distance δ (spec §2): ε = ε_S·sqrt(δ / (4.5·2R_Ω)).
[[nodiscard]] double probing_eps_from_delta(double delta, double eps_S, double omega_radius);

/// The costs of a run, with the names of the CLI's report.
struct ProbingReport {
    std::size_t probes = 0;             ///< cast() calls, bootstrap included
    std::size_t probes_bootstrap = 0;
    std::size_t voronoi_edges_travelled = 0;  ///< detection + positioning edge pieces
    std::size_t detection_edges = 0;
    std::size_t positioning_edges = 0;
    double path_length = 0;           ///< travelled inside Ω
    double exterior_path_length = 0;  ///< travelled on ∂Ω
    std::size_t cells_created = 0;    ///< Delaunay cells = Voronoi vertices created
    std::size_t nodes_retained = 0;   ///< active nodes kept after their cell died
    std::size_t insertions = 0;
    std::size_t stale_pops = 0;
    std::size_t nonempty_pops = 0;  ///< popped balls that hold a sample (skipped; spec §8.2)
    std::size_t grazing_hits = 0;
    std::size_t segments_checked = 0;  ///< by the safety monitor
    std::size_t vertices = 0, facets = 0;
    double max_ball_radius = 0;  ///< largest ball of the output's facets (≤ ε)
    double seconds = 0;
};

struct ProbingResult {
    std::vector<Point3> sample;  ///< E, in insertion order
    TriangleSoup mesh;           ///< the facets of Del^v, oriented outward (points = sample)
    ProbingReport report;
    /// Violated invariants (spec §5.2: P1, P2, records of active nodes; hits on their current
    /// edge and their balls empty), each "after insertion k: ...". Empty when all hold.
    std::vector<std::string> problems;
};

/// Runs the refinement. \throw InvalidInput for bad options (non-finite values, ε ≤ 0, ε ≥
/// 0.091·ε_S without allow_unguaranteed, no interior point, an interior point outside Ω, a
/// first probe that misses, a hit within the margin of ∂Ω).
[[nodiscard]] ProbingResult probe_surface(const Oracle& oracle, const ProbingOptions& options);

}  // namespace dynmesh
