#pragma once
/// \file Deforming-surface scenarios with a known ground truth (spec `deforming-mesh.md` §7):
/// a closed surface Sigma(0), a fine reference mesh of it whose vertices are the pool of
/// samples, an initial sample P(0) drawn from the pool, and a smooth motion of space phi(t, .)
/// that carries everything. Sigma(t) = phi(t, Sigma(0)) and a sample at pool point x0 sits at
/// phi(t, x0), so the true surface, its normals and the sampling radius are known at every t.
///
/// Usage
/// \code
///   Scenario s = make_scenario("stretch", {.samples = 20000, .steps = 400});
///   std::vector<Point3> p0 = pool_positions(s, 0.0, s.initial);   // P(0), SampleId = i
///   ... DeformOptions{.lambda = s.lambda, .h0 = s.h0, .horizon = s.time_units} ...
///   for (int t = 1; t <= s.time_units; ++t) {
///       warp_points(s, t, x0, positions);                          // every live sample
///       if (update due && s.edits) {
///           SampleEdits e = plan_sample_edits(s, t, live_pool, s.h0);
///           ... queue e.insert_pool as new samples, e.delete_pool as deletions ...
///       }
///   }
/// \endcode
///
/// Time. Every motion is a cycle: with the path parameter u = t * speed / steps, the shape goes
/// out and comes back once per unit of u (every warp is periodic in u with period 1 and is the
/// identity at u = 0 and u = 1). The horizon is time_units = steps / speed (rounded up), so
/// `speed` plays the spec's theta: the same path in more, smaller steps.
///
/// Determinism: equal names and options give bit-identical scenarios on every platform
/// (dynmesh::Rng, no threads).
///
/// The motions themselves are in warp.hpp, the sample edits in sample_edits.hpp; this header
/// includes both.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dynmesh/deform/sample_edits.hpp"
#include "dynmesh/deform/warp.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh {

struct Scenario {
    /// "pulse", "stretch", "twist", "bend", "rotate", "dimple", or
    /// "mesh:<file name>+<warp>".
    std::string name;
    /// One line on the shape and the motion, with their parameters (for logs).
    std::string description;
    /// Sigma(0) when analytic (sphere or torus), else null.
    std::unique_ptr<ImplicitSurface> surface0;
    /// A fine closed mesh of Sigma(0); its vertices are the sample pool (vertex i is pool
    /// point i and lies on Sigma(0)). No deleted elements.
    SurfaceMesh reference;
    /// Unit outward normal of Sigma(0) at each pool point: exact for an analytic surface; for
    /// a mesh file the angle-weighted vertex normal of the input at its vertices, and the
    /// normalised mean of the two end normals at subdivision midpoints.
    std::vector<Vec3> normals0;
    /// Pool indices forming P(0), sorted.
    std::vector<std::uint32_t> initial;
    std::unique_ptr<Warp> warp;
    /// Path parameter per time unit (u = rate * t) = speed / steps.
    double rate = 0;
    /// Horizon I: the last time unit of interest (steps / speed, rounded up).
    int time_units = 0;
    /// Bound on |phi(t+1, x) - phi(t, x)| over x on Sigma(0) and every real t: 1.05 times the
    /// largest speed |d phi / dt| measured at every pool point over 64 phases of the period,
    /// refined around the worst phases of the 16 fastest points.
    double lambda = 0;
    /// Sampling radius of P(0): covering_radius of the reference probes (every pool point and
    /// every reference face's barycentre) by P(0), at t = 0.
    double h0 = 0;
    /// Typical spacing of P(0): the median distance from an initial sample to its nearest
    /// other initial sample, at t = 0.
    double spacing0 = 0;
    /// Radius of the density counts used by plan_sample_edits (4 * spacing0).
    double density_radius = 0;
    /// For every pool point: the number of initial samples within density_radius of it at
    /// t = 0 (counting itself when it is one).
    std::vector<std::uint32_t> initial_density;
    /// Bounding-box diagonal of Sigma(0) (the length scale of finite differences).
    double length_scale = 0;
    /// The caller inserts and deletes samples to keep the density (plan_sample_edits).
    bool edits = false;
    /// For a mesh file: the mesh as read (before subdivision), Sigma(0) itself; its vertex i
    /// is pool point i. run_deform() passes it as InitialSurface::reference, so Tri(0) is the
    /// restricted Delaunay triangulation of Vert(0) on it, with its topology.
    std::optional<SurfaceMesh> input_mesh;

    [[nodiscard]] std::size_t pool_size() const { return normals0.size(); }
};

struct ScenarioOptions {
    std::size_t samples = 20000;  ///< |P(0)| (mesh files: at most the vertex count)
    int steps = 400;              ///< time units of one out-and-back cycle at speed 1
    /// Multiplies the motion speed: the same path in steps / speed time units.
    double speed = 1.0;
    std::uint64_t seed = 1;
    /// For a mesh file: bend | twist | pulse | stretch | rotate (empty = bend). Analytic
    /// scenarios have their own motion; naming another one is an error.
    std::string warp;
    /// The pool holds about pool_factor * |P(0)| points (>= 1): exactly samples *
    /// pool_factor for analytic scenarios; for a mesh file, the input is midpoint-subdivided
    /// (each level about quadruples the vertices) while |pool| < pool_factor |P(0)| / 2.
    std::size_t pool_factor = 4;
    /// Overrides Scenario::edits (default: true for mesh files, false otherwise).
    std::optional<bool> edits;
};

/// The analytic scenario names: "pulse", "stretch", "twist", "bend", "boomerang" (= bend),
/// "rotate", "dimple".
[[nodiscard]] std::vector<std::string> scenario_names();

/// Builds a scenario.
/// - "pulse": unit sphere; radius 1 -> 1.5 -> 1 (make_pulse_warp).
/// - "stretch": unit sphere stretched along x into a 3:1:1 ellipsoid and back.
/// - "twist": torus R = 5, r = 3 (axis z, reach 2) twisted about the x axis (a diameter of
///   its plane; twisting about the symmetry axis z would leave Sigma unchanged), end angle
///   pi/4 at x = +-8: the two ends turn by up to +-pi/2 relative to each other.
/// - "bend" / "boomerang": unit sphere stretched along x to 3:1:1, then bent about z (towards
///   +y) until its 6-long axis is an arc turning by 2 pi/3 (radius 2.86 > the half-thickness 1),
///   then unbent and unstretched.
/// - "rotate": unit sphere turning once about (1, 2, 3) / |(1, 2, 3)| (rigid; spec S1).
/// - "dimple": unit sphere with the spec's S4 (Section-6 lower-bound) motion, make_dimple_warp
///   with, relative to the sampling radius h0 of P(0) (measured first):
///   radius rho = 2.5 h0, and displacement h0 t_k + (h0 / 4) c_k at centre c_k: a tangential
///   slide by h0 (about one mesh edge: the vertices of Vert(0) are >= h0 apart) along the
///   unit tangent t_k, plus an outward lift by h0 / 4 (L = 0.71). The centres are
///   fibonacci_sphere(K) with K the largest number <= 64 whose lattice points are all at
///   least 2.2 rho apart (so the supports are disjoint with a margin: K = 16 for 2000
///   samples); t_k is the east direction at c_k turned towards north by k times the golden
///   angle. Every surface point moves along a straight segment and back; about half of the
///   sphere moves and the rest stays put. Samples are never edited.
/// For these, pool = surface0->sample_uniform(samples * pool_factor, seed), reference =
/// restricted_delaunay(pool) (pool points the RDT leaves out are dropped), and P(0) = the
/// first `samples` pool points (itself a uniform sample, by the prefix property).
/// - Any other name is a path to a closed mesh file (read_mesh; unreferenced vertices are
///   dropped). Sigma(0) is the mesh itself. The reference is the mesh after 0-3 flat 1-to-4
///   midpoint subdivisions (see pool_factor; the input vertices keep their indices
///   0..|V|-1 and the midpoints follow, with normals0 the normalised mean of the two end
///   normals), so that the pool has spare points to insert where the surface stretches.
///   P(0) is a deterministic random subset of `samples` input vertices (all of them when
///   samples >= |V|). The motion is options.warp, relative to the bounding box: with centre
///   c, longest extent along the coordinate axis e1 (half-length L), second longest along e2
///   (half-width W): pulse = scale 1 -> 1.5 -> 1 about c; stretch = x3 along e1; twist about
///   e1 with end angle pi/4 at +-L; bend of e1 towards e2 turning by
///   min(2 pi/3, 2 L / (1.5 W)) (bend radius >= 1.5 W, so the inner side is compressed up to
///   3x and the outer stretched up to 1.67x); rotate = one turn about (1, 1, 1).
/// \throw InvalidInput for an unknown name that is not an existing file (listing the valid
///        names), an unreadable, open or non-manifold mesh, an unknown warp, a warp other
///        than its own for an analytic scenario, samples < 100, steps < 1, pool_factor < 1, speed <= 0 or non-finite, or a sample too sparse to
///        mesh the surface (the restricted Delaunay triangulation has the wrong topology).
[[nodiscard]] Scenario make_scenario(const std::string& name, const ScenarioOptions& options = {});

/// Positions at time t of the given points of Sigma(0) (out[i] = phi(t, x0[i])).
/// \throw InvalidInput when the spans differ in size.
void warp_points(const Scenario& s, double t, std::span<const Point3> x0, std::span<Point3> out);
/// Positions at time t of the given pool points. \throw InvalidInput for an index >= pool size.
[[nodiscard]] std::vector<Point3> pool_positions(const Scenario& s, double t,
                                                 std::span<const std::uint32_t> pool);
/// Positions at time t of every pool point (index = pool index).
[[nodiscard]] std::vector<Point3> pool_positions(const Scenario& s, double t);

/// The Jacobian d phi(t, x0) / d x0 as its three columns (central differences with step
/// 1e-6 * length_scale).
[[nodiscard]] std::array<Vec3, 3> warp_jacobian(const Scenario& s, double t, const Point3& x0);
/// Unit outward normal of Sigma(t) at the image of pool point i: cof(J) n0 normalised, with J
/// the Jacobian and n0 = normals0[i].
[[nodiscard]] Vec3 surface_normal(const Scenario& s, double t, std::uint32_t pool);
/// Local area scale factor of the warp at pool point i, relative to t = 0: |cof(J) n0|
/// (1 for a rigid motion, 2.25 everywhere for the pulse at its peak).
[[nodiscard]] double area_scale(const Scenario& s, double t, std::uint32_t pool);

/// max over `probes` of the distance to the nearest point of `samples`: the sampled covering
/// (sampling) radius. 0 for no probe. \throw InvalidInput when there are probes but no sample.
[[nodiscard]] double covering_radius(std::span<const Point3> probes,
                                     std::span<const Point3> samples);
/// The probe points used for h: every vertex of `mesh` and every face's barycentre.
[[nodiscard]] std::vector<Point3> reference_probes(const SurfaceMesh& mesh);
/// Measured sampling radius of the live samples on Sigma(t): covering_radius of
/// reference_probes(reference warped to t) by the live pool points warped to t.
[[nodiscard]] double sampling_radius(const Scenario& s, double t,
                                     std::span<const std::uint32_t> live_pool);

}  // namespace dynmesh
