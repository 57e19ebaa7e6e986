#pragma once
/// \file The skin of a set of weighted points as the level set of one C¹ function
/// (specs/skin-surfaces.md §1.2–§1.6, with §8 correction 4 on the bounding points):
///
///     Φ(x) = min over balls b in conv(B) of ‖x − z_b‖²/s − w_b,
///
/// equal on each mixed cell μ_δ = (1−s)·δ ⊕ s·ν_δ of the regular triangulation to the quadric
/// Φ_δ(x) = ‖u_ν‖²/s − ‖u_δ‖²/(1−s) + W_δ, u = x − z_δ split along aff δ (u_δ) and its orthogonal
/// complement (u_ν). The skin at growth time t (every weight + t) is Φ = t; inside is Φ < t.
///
/// Six bounding points of weight −1 are added far enough from the balls (D = max(CGAL's distance,
/// half-diagonal + 2·max √(w/s) + 1) from the box centre) that Φ near the balls is that of the
/// balls alone, and so that any input (one ball, coplanar centres) has a 3D triangulation.
///
/// Locating the mixed cell of a point walks through the mixed complex from a hint (§1.5): from
/// simplex δ, a failed barycentric coordinate of vertex k moves to the face δ \ {k}, a failed
/// link constraint of vertex j to the coface δ ∪ {j}, the most violated first; a walk that
/// would revisit a simplex falls back to scanning every simplex (counted in locate_fallbacks()).

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/skin/molecule.hpp"

namespace dynmesh {

/// A simplex δ of the regular triangulation with what its mixed cell needs.
struct SkinSimplex {
    std::array<int, 4> vertices{-1, -1, -1, -1};  ///< indices into SkinFunction::balls(), dim + 1 of them
    int dim = 0;                                  ///< 0 vertex, 1 edge, 2 triangle, 3 tetrahedron
    Point3 z{};                                   ///< the orthocentre z_δ (equal power to every vertex)
    double W = 0;                                 ///< the ortho-weight ‖z_δ − z_i‖² − w_i
    std::vector<int> link;                        ///< the finite vertices j with δ ∪ {j} a simplex
};

struct SkinEvaluation {
    double value = 0;        ///< Φ(x)
    Vec3 gradient{};         ///< ∇Φ(x) = 2u_ν/s − 2u_δ/(1−s)
    double rho = 0;          ///< the length scale 1/κ, κ the maximum normal curvature of the level set through x
    std::size_t simplex = 0; ///< the index of δ with x in μ_δ
};

class SkinFunction {
public:
    /// \throw InvalidInput when s is not in (0, 1), there is no ball, or a centre or weight is
    ///        not finite.
    SkinFunction(std::vector<WeightedPoint> balls, double s);

    /// Φ, ∇Φ and ϱ at x, walking from simplex `hint` (any index; a nearby one is faster: pass the
    /// `simplex` of the previous evaluation of a nearby point).
    [[nodiscard]] SkinEvaluation evaluate(const Point3& x, std::size_t hint = 0) const;
    [[nodiscard]] double value(const Point3& x, std::size_t hint = 0) const { return evaluate(x, hint).value; }
    /// The index of a simplex whose mixed cell holds x, walking from `hint`.
    [[nodiscard]] std::size_t locate(const Point3& x, std::size_t hint = 0) const;
    /// The same by scanning every simplex (the reference the walk is tested against).
    [[nodiscard]] std::size_t locate_by_scan(const Point3& x) const;
    /// The simplex with exactly these ball indices (any order), if it is in the triangulation.
    [[nodiscard]] std::optional<std::size_t> find_simplex(std::array<int, 4> vertices, int count) const;
    /// Walks that fell back to a scan since construction (not synchronised across threads).
    [[nodiscard]] std::size_t locate_fallbacks() const { return fallbacks_; }
    /// Is x in the mixed cell of simplex k (up to a relative tolerance of 1e-12)?
    [[nodiscard]] bool in_mixed_cell(std::size_t k, const Point3& x) const;
    /// Φ_δ, ∇Φ_δ and ϱ of simplex k's quadric at x (anywhere: the patch extended).
    [[nodiscard]] SkinEvaluation evaluate_in(std::size_t k, const Point3& x) const;
    /// Φ_δ alone (no gradient or curvature).
    [[nodiscard]] double value_in(std::size_t k, const Point3& x) const;

    /// At s = 1/2: the point x0 moved along the orthogonal trajectory of simplex k's quadric
    /// (velocity ∇Φ/‖∇Φ‖², so Φ grows at rate 1) from its level Φ_k(x0) to the level t, in
    /// closed form (§2.3: a·b is conserved and a² − b² = (t − W)/2, with a = ‖u_ν‖, b = ‖u_δ‖).
    /// Whether the path stays in the mixed cell is the caller's concern.
    /// \throw InvalidInput when s ≠ 1/2, or x0 lies on an axis of the quadric (a or b zero) and
    ///        the level t is on the side the radial path cannot reach.
    [[nodiscard]] Point3 flow_in_cell(std::size_t k, const Point3& x0, double t) const;

    [[nodiscard]] double shrink() const { return s_; }
    /// The input balls followed by the six bounding points.
    [[nodiscard]] const std::vector<WeightedPoint>& balls() const { return balls_; }
    [[nodiscard]] std::size_t input_balls() const { return n_input_; }
    [[nodiscard]] const std::vector<SkinSimplex>& simplices() const { return simplices_; }

private:
    /// The violation of x's membership in μ_k (≤ 0 inside), relative to the simplex's scale.
    [[nodiscard]] double violation(std::size_t k, const Point3& x) const;
    /// Calls fn(amount, target) for each constraint of μ_k at x, in the order of walk_: the
    /// barycentric coordinate of each ball of δ (target δ without it), then the power bisector
    /// with each link ball j (target δ ∪ {j}); amount > 0 is a violation, relative to the
    /// simplex's scale.
    template <class Fn>
    void for_each_constraint(std::size_t k, const Point3& x, Fn&& fn) const;
    /// A walk's move out of μ_k, to the simplex `target`.
    struct Move {
        double amount = 0;
        std::size_t target = 0;
    };
    /// Every constraint of μ_k that x violates by more than the tolerance, in constraint order.
    void violated(std::size_t k, const Point3& x, std::vector<Move>& out) const;
    /// The simplex δ of simplex k without (drop ≥ 0) or with (add ≥ 0) one ball.
    [[nodiscard]] std::optional<std::size_t> neighbour(std::size_t k, int drop, int add) const;

    /// One constraint of a mixed cell, precomputed for the walk: the simplex a violation moves
    /// to and, for a link ball j, the power bisector of j and ball 0 of δ as a plane relative to
    /// z_0: the signed distance of q beyond it is dot(normal, q − z_0) − offset.
    struct WalkStep {
        std::size_t target = 0;
        Vec3 normal{0, 0, 0};  ///< (z_j − z_0)/‖z_j − z_0‖ (zero for a barycentric coordinate)
        double offset = 0;     ///< (‖z_j − z_0‖² + w_0 − w_j)/(2‖z_j − z_0‖)
    };
    std::vector<WalkStep> walk_;           ///< per simplex, its constraints in order
    std::vector<std::size_t> walk_begin_;  ///< simplex k's: [walk_begin_[k], walk_begin_[k + 1])

    std::vector<std::pair<std::array<int, 4>, std::size_t>> index_;  ///< sorted ball-index keys
    mutable std::size_t fallbacks_ = 0;

    std::vector<WeightedPoint> balls_;
    std::size_t n_input_ = 0;
    double s_ = 0.5;
    double scale_ = 1;
    std::vector<SkinSimplex> simplices_;
    /// u_δ, the component of u along aff δ of simplex k (u_ν = u − u_δ).
    [[nodiscard]] Vec3 along_simplex(std::size_t k, const Vec3& u) const;

    /// Per simplex, an orthonormal basis of the directions of aff δ (dim vectors).
    std::vector<std::array<Vec3, 3>> basis_;
    /// Per simplex, the dual basis of its edges e_i = z_{i+1} − z_0 (dot(dual_i, e_j) = δ_ij):
    /// the barycentric coordinate i + 1 of a point p of aff δ is dot(dual_i, p − z_0).
    std::vector<std::array<Vec3, 3>> dual_;
    std::vector<double> longest_edge_;
};

}  // namespace dynmesh
