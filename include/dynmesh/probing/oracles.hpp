#pragma once
/// \file The probing objects of specs/probing.md §6: each class is both the sensor (Oracle) and
/// the hidden truth (GroundTruth) of one object O.
///
/// Conventions (besides those of oracle.hpp)
/// - τ = tolerance() = 1e-12 × the object's scale (stated per class).
/// - is_free(p): the signed distance of p is ≥ −τ (a point within τ of S counts as on S).
/// - segment_is_free(a, b): both ends free and no crossing of S, grazing ones included, at
///   t < |b − a| − τ along a → b. Near-tangent contacts therefore count as not free
///   (conservative, spec §8.1: an edge is never declared free through a tangency).
/// - `strict` (constructor option): grazing contacts are ignored by cast() (spec §8.1, the
///   model of the paper); the search goes on past them.
/// - sample_surface(spacing): for the sphere, ellipsoid, torus and balls, ceil(area / spacing²)
///   points per surface drawn by the shape's sample_uniform with seed 1 (reproducible); for
///   the genus-2 surface the crossings of S with a grid of that spacing; for meshes the
///   vertices plus a grid on every triangle.
/// - Every query is const (thread safety is not promised: the mesh oracle uses lazily built
///   CGAL search structures).

#include <memory>
#include <string>
#include <vector>

#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/probing/oracle.hpp"
#include "dynmesh/shapes/analytic.hpp"

namespace dynmesh {

/// Options shared by every probing object.
struct OracleOptions {
    bool strict = false;  ///< ignore grazing contacts instead of reporting them
};

/// Oracle + GroundTruth, with the shared ray checks, the strict switch and the generic
/// segment test built on cast.
class ProbeObject : public Oracle, public GroundTruth {
public:
    /// Checks the ray (finite s, unit d within 1e-9, t_max ≥ 0, NaN refused; t_max may be
    /// +infinity) and the start (InvalidInput when s is deeper than τ inside O), then casts.
    [[nodiscard]] std::optional<ProbeHit> cast(const Point3& s, const Vec3& d,
                                               double t_max) const final;
    [[nodiscard]] double tolerance() const final { return tau_; }
    [[nodiscard]] bool segment_is_free(const Point3& a, const Point3& b) const override;
    [[nodiscard]] bool strict() const { return options_.strict; }
    /// Signed distance to S (negative inside): exact for the analytic shapes, see each class.
    [[nodiscard]] virtual double signed_distance(const Point3& p) const = 0;
    [[nodiscard]] bool is_free(const Point3& p) const override {
        return signed_distance(p) >= -tau_;
    }
    [[nodiscard]] double distance(const Point3& p) const override;

protected:
    ProbeObject(double scale, OracleOptions options);
    /// The cast proper; s is checked free, d unit. `strict` as in OracleOptions.
    [[nodiscard]] virtual std::optional<ProbeHit> cast_checked(const Point3& s, const Vec3& d,
                                                               double t_max,
                                                               bool strict) const = 0;
    /// The shared acceptance rule: t ≤ t_max + τ, grazing when |cos| < 1e-6 (or `stalled`).
    /// Returns false (no hit) when the contact is grazing and `strict`.
    [[nodiscard]] bool accept(ProbeHit& hit, double cos_angle, double t_max, bool strict,
                              bool stalled = false) const;
    [[nodiscard]] const OracleOptions& options() const { return options_; }

private:
    double tau_;
    OracleOptions options_;
};

/// The sphere (c, R): quadratic root, τ = 1e-12 R. reach R, diameter 2R, area 4πR².
class SphereOracle final : public ProbeObject {
public:
    explicit SphereOracle(const Sphere& sphere, OracleOptions options = {});
    [[nodiscard]] double signed_distance(const Point3& p) const override;
    [[nodiscard]] std::vector<Point3> sample_surface(double spacing) const override;
    [[nodiscard]] double reach() const override { return shape_.reach(); }
    [[nodiscard]] double diameter() const override { return 2 * shape_.radius(); }
    [[nodiscard]] double area() const override { return shape_.area(); }
    [[nodiscard]] int components() const override { return 1; }
    [[nodiscard]] int euler_characteristic() const override { return 2; }
    [[nodiscard]] const Sphere& shape() const { return shape_; }

private:
    [[nodiscard]] std::optional<ProbeHit> cast_checked(const Point3& s, const Vec3& d,
                                                       double t_max, bool strict) const override;
    Sphere shape_;
};

/// The axis-aligned ellipsoid: the ray is scaled to the unit sphere, quadratic root;
/// τ = 1e-12 × the largest semi-axis. reach e_min²/e_max, diameter 2 e_max, area Legendre's.
class EllipsoidOracle final : public ProbeObject {
public:
    explicit EllipsoidOracle(const Ellipsoid& ellipsoid, OracleOptions options = {});
    [[nodiscard]] double signed_distance(const Point3& p) const override;
    [[nodiscard]] std::vector<Point3> sample_surface(double spacing) const override;
    [[nodiscard]] double reach() const override { return shape_.reach(); }
    [[nodiscard]] double diameter() const override;
    [[nodiscard]] double area() const override { return shape_.area(); }
    [[nodiscard]] int components() const override { return 1; }
    [[nodiscard]] int euler_characteristic() const override { return 2; }
    [[nodiscard]] const Ellipsoid& shape() const { return shape_; }

private:
    [[nodiscard]] std::optional<ProbeHit> cast_checked(const Point3& s, const Vec3& d,
                                                       double t_max, bool strict) const override;
    Ellipsoid shape_;
};

/// The torus (R, r): sphere tracing with the exact signed distance, with a smallest step
/// h = sqrt(8 · reach · τ) (a crossing whose chord inside O is shorter than h penetrates less
/// than τ: it is a tangential contact), then bisection on the quartic implicit. A contact whose
/// sampled distance falls to ≤ 2τ without a sign change is a stalled search: a grazing hit at
/// the nearest surface point. τ = 1e-12 (R + r). reach min(r, R − r), diameter 2(R + r).
class TorusOracle final : public ProbeObject {
public:
    explicit TorusOracle(const Torus& torus, OracleOptions options = {});
    [[nodiscard]] double signed_distance(const Point3& p) const override;
    [[nodiscard]] std::vector<Point3> sample_surface(double spacing) const override;
    [[nodiscard]] double reach() const override { return shape_.reach(); }
    [[nodiscard]] double diameter() const override;
    [[nodiscard]] double area() const override { return shape_.area(); }
    [[nodiscard]] int components() const override { return 1; }
    [[nodiscard]] int euler_characteristic() const override { return 0; }
    [[nodiscard]] const Torus& shape() const { return shape_; }

private:
    [[nodiscard]] std::optional<ProbeHit> cast_checked(const Point3& s, const Vec3& d,
                                                       double t_max, bool strict) const override;
    Torus shape_;
};

/// Pairwise disjoint balls: the smallest entering root over all balls (in strict mode the
/// smallest non-grazing one). τ = 1e-12 × max_i (|c_i| + r_i).
/// reach min(min r_i, min gap / 2), diameter: max over pairs of |c_i − c_j| + r_i + r_j.
class BallsOracle final : public ProbeObject {
public:
    /// \throw InvalidInput (element = index of the second ball of the pair) when two balls
    /// intersect or touch (gap ≤ 0), a radius is not positive or a value is not finite; or when
    /// the list is empty.
    explicit BallsOracle(std::vector<Ball> balls, OracleOptions options = {});
    [[nodiscard]] double signed_distance(const Point3& p) const override;
    [[nodiscard]] std::vector<Point3> sample_surface(double spacing) const override;
    [[nodiscard]] double reach() const override { return reach_; }
    [[nodiscard]] double diameter() const override { return diameter_; }
    [[nodiscard]] double area() const override;
    [[nodiscard]] int components() const override { return static_cast<int>(balls_.size()); }
    [[nodiscard]] int euler_characteristic() const override { return 2 * components(); }
    [[nodiscard]] const std::vector<Ball>& balls() const { return balls_; }

private:
    [[nodiscard]] std::optional<ProbeHit> cast_checked(const Point3& s, const Vec3& d,
                                                       double t_max, bool strict) const override;
    std::vector<Ball> balls_;
    double reach_ = 0, diameter_ = 0;
};

/// A genus-2 surface: the smooth union of two tori T± (axis z, major radius 1, minor radius
/// 0.4, centres (±1.25, 0, 0)) by the polynomial smooth minimum with k = 0.6,
///     f = min(a, b) − k/4 · max(k − |a − b|, 0)² / k²,   a, b the tori's exact distances.
/// f is C¹ and 1-Lipschitz (its gradient is a convex combination of two unit vectors), so
/// f(p) is a lower bound of the distance from an outside p to S and sphere tracing with step f
/// is safe; a hit is refined by bisection on f. The tubes overlap near the origin (core gap
/// 0.5 < 2 × 0.4) while the core circles stay disjoint: S is connected, of genus 2, Euler
/// characteristic −2 (each hole stays open: f ≥ 0.5 at the tori's centres).
/// reach(): 0.25, a documented numeric estimate, not a proof: the largest principal curvature
/// measured on 4.3e5 points of sample_surface(0.01) (finite-difference Hessian of f) is 3.28,
/// at the saddle of the neck (0, ±0.92, 0), so 1/κ_max ≈ 0.30; the tubes give r = 0.4 and the
/// holes R − r = 0.6; 0.25 keeps a margin below the smallest of these.
/// distance(): |f| refined by projecting p onto S along ∇f (exact away from the blend,
/// where f is a torus distance). area(): numeric (grid coarea integral, about 1e-3 relative;
/// it costs about 0.2 s). τ = 1e-12 × 2.65 (the half-extent along x).
class Genus2Oracle final : public ProbeObject {
public:
    explicit Genus2Oracle(OracleOptions options = {});
    /// The smooth-union implicit f (not the exact distance inside the blend region).
    [[nodiscard]] double value(const Point3& p) const;
    [[nodiscard]] Vec3 gradient(const Point3& p) const;
    /// f itself: a 1-Lipschitz under-estimate of the signed distance with the same sign.
    [[nodiscard]] double signed_distance(const Point3& p) const override { return value(p); }
    [[nodiscard]] double distance(const Point3& p) const override;
    [[nodiscard]] std::vector<Point3> sample_surface(double spacing) const override;
    [[nodiscard]] double reach() const override { return 0.25; }
    /// 2 × (1.25 + 1.4) = 5.3 (the x extent).
    [[nodiscard]] double diameter() const override { return 5.3; }
    [[nodiscard]] double area() const override;
    [[nodiscard]] int components() const override { return 1; }
    [[nodiscard]] int euler_characteristic() const override { return -2; }
    /// Points strictly inside: one per component (here the first torus's core point).
    [[nodiscard]] static Point3 interior_point() { return {-0.25, 0, 0}; }
    [[nodiscard]] static Bbox3 bbox();

private:
    [[nodiscard]] std::optional<ProbeHit> cast_checked(const Point3& s, const Vec3& d,
                                                       double t_max, bool strict) const override;
    Torus left_, right_;
};

/// A closed, consistently oriented triangle mesh (CGAL AABB tree, first_intersection of a
/// Ray_3; Side_of_triangle_mesh for inside tests). τ = 1e-12 × half the bounding-box diagonal.
/// A hit is grazing when |cos(d, face normal)| < 1e-6, when the ray lies in a face's plane
/// (CGAL returns a segment: its endpoint nearest the source is reported), or when the ray does
/// not enter O just past the hit (a silhouette edge or vertex). reach 0; diameter: the
/// bounding-box diagonal (an upper bound); distance: to the nearest triangle.
class MeshOracle final : public ProbeObject {
public:
    /// \throw InvalidInput naming the problem when the soup is not an oriented 2-manifold
    /// (inconsistent orientation, non-manifold edge or vertex), has a boundary (not closed),
    /// intersects itself (CGAL's self-intersection test), or has no triangle.
    explicit MeshOracle(const TriangleSoup& soup, OracleOptions options = {});
    ~MeshOracle() override;
    MeshOracle(const MeshOracle&) = delete;
    MeshOracle& operator=(const MeshOracle&) = delete;

    /// Signed distance: −distance inside (Side_of_triangle_mesh), +distance outside.
    [[nodiscard]] double signed_distance(const Point3& p) const override;
    [[nodiscard]] bool is_free(const Point3& p) const override;
    /// do_intersect(Segment_3) on the tree; when it meets S, every piece between consecutive
    /// crossings is tested at its midpoint.
    [[nodiscard]] bool segment_is_free(const Point3& a, const Point3& b) const override;
    /// The same crossings: the midpoint of the first free piece (or a free end).
    [[nodiscard]] std::optional<double> free_point_on(const Point3& a, const Point3& b) const override;
    [[nodiscard]] double distance(const Point3& p) const override;
    /// The vertices the triangles use plus, on each triangle, a grid of points `spacing` apart.
    [[nodiscard]] std::vector<Point3> sample_surface(double spacing) const override;
    [[nodiscard]] double reach() const override { return 0; }
    [[nodiscard]] double diameter() const override;
    [[nodiscard]] double area() const override;
    [[nodiscard]] int components() const override;
    [[nodiscard]] int euler_characteristic() const override;
    /// One point strictly inside O per connected component of the mesh, well away from S: for
    /// each of the component's 16 largest faces, the midpoint of the chord from the face's
    /// centroid along the inward normal to the first wall it meets; the one farthest from S.
    /// \throw InvalidInput when no face of a component gives one.
    [[nodiscard]] std::vector<Point3> interior_points() const;
    [[nodiscard]] Bbox3 bbox() const;

private:
    /// 0, |b − a| and the distances from a of every point where ab meets a triangle, sorted.
    [[nodiscard]] std::vector<double> crossings(const Point3& a, const Point3& b) const;
    [[nodiscard]] std::optional<ProbeHit> cast_checked(const Point3& s, const Vec3& d,
                                                       double t_max, bool strict) const override;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// What make_probe_object returns.
struct ProbeSetup {
    std::unique_ptr<ProbeObject> object;
    std::vector<Point3> interior_points;  ///< one per component of O (assumption A1)
    Ball omega;                           ///< contains S with a margin (assumption A2)
    std::string spec;                     ///< the spec it was built from
    bool planar = false;                  ///< a curve in the plane z = 0 (probe_curve), not a surface
};

/// Builds the object of `spec`: "sphere:R", "ellipsoid:a,b,c", "torus:R,r" (with the
/// optional "@cx,cy,cz" of make_surface), "balls:FILE" (lines "x y z r", '#' comments; read
/// with read_input_file, errors "<file>:<line>: ..."), "genus2", the planar curves "circle2:R"
/// and "star2:R" of oracles2.hpp (centred at the origin), or a mesh file path read with
/// read_soup (any other spec with a ':' is refused as an unknown object). Ω is the ball
/// circumscribing the bounding box, enlarged by 10% of its radius.
/// \throw InvalidInput for a malformed spec or an object the oracle refuses; IoError for an
/// unreadable or malformed file.
[[nodiscard]] ProbeSetup make_probe_object(const std::string& spec, OracleOptions options = {});
/// The object of a closed mesh given as a triangle soup (a MeshOracle), Ω and the interior
/// points as for a mesh file; `name` prefixes the messages. \throw InvalidInput as MeshOracle.
[[nodiscard]] ProbeSetup make_probe_object(const TriangleSoup& soup, const std::string& name,
                                           OracleOptions options = {});

}  // namespace dynmesh
