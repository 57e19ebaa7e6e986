#pragma once
/// \file Ground-truth measurements of a mesh Tri(t) of a deforming scenario (spec
/// `deforming-mesh.md` §7): size, largest circumradius R, the measured sampling radius h of the
/// live samples on Sigma(t), triangle shape, edge-angles, normal deviation against the true
/// normals of Sigma(t), Hausdorff distance to Sigma(t) and embedding checks.
///
/// Sigma(t) is represented by the scenario's reference mesh carried to time t (a much finer
/// mesh than Tri(t): its vertices are the whole sample pool); its normals are the exact
/// normals of Sigma(0) transported by the warp's Jacobian.
///
/// Hausdorff distance: the two one-sided distances are sampled at the vertices and face
/// barycentres of each mesh (HausdorffOptions::face_resolution = 1) and are exact for these
/// samples: a local search (walk to a nearby vertex, check its triangle fan) bounds each
/// sample's distance from above, and only samples whose bound could raise the running maximum
/// get an exact search (every triangle with a vertex within bound + longest edge). So the
/// result equals hausdorff(mesh, reference at t, {.face_resolution = 1}) at a fraction of the
/// cost (distances below 1e-9 of the target's longest edge count as 0).
///
/// Cost (20K samples, pool 80K, reference 160K faces, mesh 40K faces): set_time ~10 ms;
/// measure ~30-50 ms without the Hausdorff distance, 0.08-0.13 s with it on two threads
/// (0.1-0.2 s on one); the self-intersection count (optional) adds ~0.1 s. Run deform_tests
/// --gtest_also_run_disabled_tests --gtest_filter='*Timing*' for current numbers.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

struct MeasureOptions {
    /// Two-sided sampled Hausdorff distance between the mesh and the reference at time t
    /// (vertices and barycentres of both meshes; see the file comment).
    bool hausdorff = true;
    /// Compute the two directions of the Hausdorff distance on two threads (same result).
    bool parallel = true;
    /// Count intersecting face pairs of the mesh (metrics/self_intersection.hpp).
    bool self_intersections = false;
    /// Measure h (otherwise h, R_over_h and hausdorff_over_h are NaN).
    bool sampling_radius = true;
};

/// One row of the per-time-unit log. Angles in degrees. NaN marks a quantity not measured.
struct FrameMetrics {
    double t = 0;
    std::size_t samples = 0;   ///< live samples
    std::size_t vertices = 0;  ///< mesh vertices
    std::size_t faces = 0;     ///< mesh faces
    /// Largest triangle circumradius.
    double R = 0;
    /// Measured sampling radius of the live samples on Sigma(t): max over the probe points
    /// of the reference at t (vertices and face barycentres) of the distance to the nearest
    /// live sample. Plays eps(t) gamma(t).
    double h = 0;
    double R_over_h = 0;
    double min_angle_deg = 0;    ///< smallest triangle angle
    /// Smallest angle of the triangles with no vertex on a crease edge (the mesh's
    /// kLockedEdges; = min_angle_deg without them).
    double min_angle_off_creases_deg = 0;
    double max_radius_edge = 0;  ///< largest circumradius / shortest edge
    /// Smallest edge-angle (the spec's min(theta1, theta2) = dihedral angle; 180 when flat).
    double min_edge_angle_deg = 0;
    /// Angle between each face's normal and the true normal of Sigma(t) at each of its three
    /// vertices (3 values per face; 0..180, so an inverted face counts > 90).
    double normal_dev_max_deg = 0;
    double normal_dev_mean_deg = 0;
    /// Two-sided sampled Hausdorff distance between the mesh and Sigma(t).
    double hausdorff = 0;
    double hausdorff_over_h = 0;
    /// Intersecting face pairs (only with MeasureOptions::self_intersections; else 0).
    std::size_t self_intersections = 0;
    /// Faces whose normal points away from Sigma(t) both at their corners and at their
    /// middle: dot(n_face, n_a + n_b + n_c) < 0 with the true normals at the vertices, and
    /// dot(n_face, n) < 0 for every normal n of Sigma(t) at the point of Sigma(t) nearest to
    /// the face's barycentre (every face of the reference around that point when it lies on
    /// an edge or a vertex of the reference).
    std::size_t inverted = 0;
    /// The first of them in mesh order (invalid when there is none).
    Face first_inverted;
};

/// Sigma(t) of a scenario at one time: the reference mesh carried to t plus the queries
/// measure() needs. Keeps a pointer to the scenario, which must outlive it. Reuse one
/// object over time (set_time) to avoid copying the reference every frame.
class GroundTruth {
public:
    /// At t = 0.
    explicit GroundTruth(const Scenario& scenario);

    /// Carries the reference to time t.
    void set_time(double t);
    [[nodiscard]] double time() const { return t_; }
    [[nodiscard]] const Scenario& scenario() const { return *s_; }
    /// The reference mesh at time(): vertex i is pool point i carried to time().
    [[nodiscard]] const SurfaceMesh& reference() const { return reference_; }
    /// Unit outward normal of Sigma(time()) at pool point i (surface_normal()).
    [[nodiscard]] Vec3 normal(std::uint32_t pool) const;
    /// Measured sampling radius of these live pool points on Sigma(time()).
    [[nodiscard]] double sampling_radius(std::span<const std::uint32_t> live_pool) const;

    /// Measures `mesh` at time(). Mesh vertex v is the sample at pool point
    /// vertex_pool[v.idx()] (the mesh may hold deleted vertices; only live ones are read).
    /// The mesh's own positions are used for its geometry.
    /// \throw InvalidInput when vertex_pool is shorter than mesh.vertices_size(), or a live
    ///        vertex or live sample names a pool index >= the pool size.
    [[nodiscard]] FrameMetrics measure(const SurfaceMesh& mesh,
                                       std::span<const std::uint32_t> vertex_pool,
                                       std::span<const std::uint32_t> live_pool,
                                       const MeasureOptions& options = {}) const;

private:
    const Scenario* s_;
    double t_ = 0;
    SurfaceMesh reference_;
    // For cache locality the distance queries use the reference renumbered along a Morton
    // curve at t = 0: rank k is reference vertex ref_order_[k], at refpts_[k].
    std::vector<std::uint32_t> ref_order_, ref_rank_;
    std::vector<Point3> refpts_;
    /// Triangles in rank numbering (sorted) and, per rank, its faces (CSR): fixed over time.
    std::vector<std::array<std::uint32_t, 3>> triangles_;
    std::vector<std::uint32_t> star_begin_, star_;
    double ref_lmax_ = 0, ref_mean_edge_ = 0;  ///< longest and mean edge at time()
    /// The probe points (every vertex and every face barycentre of the reference at
    /// time()) in a fixed Morton order at t = 0: probe i is rank probe_src_[i] when it is
    /// < the vertex count, else the barycentre of triangles_[probe_src_[i] - vertex count].
    std::vector<Point3> probes_;
    std::vector<std::uint32_t> probe_src_;
};

/// GroundTruth(s), set_time(t), measure(mesh, vertex_pool, live_pool, options).
[[nodiscard]] FrameMetrics measure_frame(const Scenario& s, double t, const SurfaceMesh& mesh,
                                         std::span<const std::uint32_t> vertex_pool,
                                         std::span<const std::uint32_t> live_pool,
                                         const MeasureOptions& options = {});

/// The fields as named numbers, for logs: "t", "samples", "vertices", "faces", "R", "h",
/// "R_over_h", "min_angle_deg", "max_radius_edge", "min_edge_angle_deg",
/// "normal_dev_max_deg", "normal_dev_mean_deg", "hausdorff", "hausdorff_over_h",
/// "self_intersections", "inverted", "min_angle_off_creases_deg" (in this order; the names match
/// scripts/plot_deform.py's columns).
[[nodiscard]] std::vector<std::pair<std::string, double>> flatten(const FrameMetrics& m);

}  // namespace dynmesh
