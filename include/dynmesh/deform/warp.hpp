#pragma once
/// \file Warps: the smooth motions of space that carry the deforming-surface scenarios
/// (scenario.hpp), with the out-and-back profiles of their time dependence. A warp maps the
/// position x0 of a point at t = 0 to its position at time t, and is the identity at t = 0.
///
/// Usage
/// \code
///   const auto w = make_stretch_warp({0, 0, 0}, {1, 0, 0}, 3.0, 1.0 / 400);
///   const Point3 x = w->apply(200.0, x0);   // u = 1/2: stretched 3x along x about 0
/// \endcode

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

/// A smooth motion of space: position at (real) time t of the point that was at x0 at t = 0.
/// Implementations are diffeomorphisms of R^3 at every t (or of a neighbourhood of the
/// surface they are made for, see the factories), so an embedded surface stays embedded.
/// apply(0, x) == x exactly.
class Warp {
public:
    virtual ~Warp() = default;
    /// "pulse", "stretch", "twist", "bend", "rotate" or "dimple".
    [[nodiscard]] virtual std::string name() const = 0;
    [[nodiscard]] virtual Point3 apply(double t, const Point3& x0) const = 0;
};

/// The out-and-back profile of the cyclic motions: (1 - cos(2 pi u)) / 2, which goes
/// 0 -> 1 (at u = 1/2) -> 0 over one period; exactly 0 at u = 0.
[[nodiscard]] double cycle_profile(double u);
/// The swinging profile: sin(2 pi u), 0 -> 1 -> 0 -> -1 -> 0 over one period.
[[nodiscard]] double swing_profile(double u);

// ---- warp factories ------------------------------------------------------------------------
// `rate` is the path parameter per time unit (u = rate * t). Axes are normalised here.
// Each factory throws InvalidInput for a non-finite or non-positive size or rate, a zero axis
// or (bend) a `toward` direction parallel to the axis.

/// "pulse": uniform scaling about `center` by 1 + (max_scale - 1) * cycle_profile(u).
[[nodiscard]] std::unique_ptr<Warp> make_pulse_warp(const Point3& center, double max_scale,
                                                    double rate);
/// "stretch": scaling along `axis` (through center) by 1 + (max_stretch - 1) * cycle_profile(u).
[[nodiscard]] std::unique_ptr<Warp> make_stretch_warp(const Point3& center, const Vec3& axis,
                                                      double max_stretch, double rate);
/// "twist": each plane orthogonal to `axis` turns rigidly about the axis (through center) by
/// theta = swing_profile(u) * end_angle * a / half_length, a = (x - center) . axis: the ends
/// a = +-half_length turn by +-end_angle, so their relative turn swings up to 2 end_angle one
/// way, back, and then the other way. A diffeomorphism of R^3 at every t (slices move
/// rigidly).
[[nodiscard]] std::unique_ptr<Warp> make_twist_warp(const Point3& center, const Vec3& axis,
                                                    double half_length, double end_angle,
                                                    double rate);
/// "bend": optionally stretches along `axis` first, then bends the axis into a circular arc
/// lying in the plane of (axis, toward), curving towards `toward`; afterwards it unbends and
/// unstretches. In local coordinates (a, b, c) along (axis, toward', axis x toward') with
/// toward' the part of `toward` orthogonal to axis:
///   a' = sigma a;  with curvature k, phi = k a':  a'' = sin(phi) / k - b sin(phi),
///   b'' = b cos(phi) + (1 - cos(phi)) / k,  c'' = c   (k = 0: a'' = a', b'' = b).
/// With pre_stretch = 1: sigma = 1 and k = cycle_profile(u) * max_turn / (2 half_length).
/// With pre_stretch > 1: q = cycle_profile(u); sigma = 1 + (pre_stretch - 1) S(2q) and
/// k = S(2q - 1) * max_turn / (2 half_length pre_stretch), S the quintic smoothstep clamped to
/// [0, 1]: the shape stretches while q < 1/2, then bends, and undoes both in reverse order.
/// At full bend the arc of length 2 half_length pre_stretch turns by max_turn, with radius
/// rho = 2 half_length pre_stretch / max_turn. A diffeomorphism of the slab b < rho when
/// max_turn < 2 pi; make_scenario keeps every surface point at b <= rho / 1.5.
[[nodiscard]] std::unique_ptr<Warp> make_bend_warp(const Point3& center, const Vec3& axis,
                                                   const Vec3& toward, double half_length,
                                                   double max_turn, double pre_stretch,
                                                   double rate);
/// "rotate": rigid rotation about `axis` through center by 2 pi u (one turn per period; the
/// spec's S1, where a correct mesh update makes no change at all).
[[nodiscard]] std::unique_ptr<Warp> make_rotation_warp(const Point3& center, const Vec3& axis,
                                                       double rate);

/// The bump of the dimple warp: (1 - r^2)^3 for r < 1, else 0 (C2, 1 at r = 0, 0 with its
/// first two derivatives at r = 1).
[[nodiscard]] double dimple_bump(double r);
/// Largest |d dimple_bump / dr|: 6 r (1 - r^2)^2 at r^2 = 1/5, i.e. 96 / (25 sqrt 5).
inline constexpr double kDimpleBumpSlope = 1.7173002067198384;
/// "dimple" (spec S4, the Section-6 lower-bound motion as a smooth warp): K local excursions.
/// A point x within `radius` of centre c_k moves by
///   cycle_profile(u) * dimple_bump(|x - c_k| / radius) * displacements[k]
/// and every other point stays put: the region around c_k slides out by up to
/// |displacements[k]| (at c_k itself, at u = 1/2) and comes back, once per period.
/// The displacement field is Lipschitz with constant
///   L = max_k |displacements[k]| * kDimpleBumpSlope / radius < 1
/// (the supports are disjoint balls), so x -> x + w(x) is a diffeomorphism of R^3 at every t.
/// \throw InvalidInput when there is no centre, the two lists differ in length, a centre or
///        displacement is not finite, radius or rate is not positive and finite, two centres
///        are closer than 2 radius (overlapping supports), or L >= 1.
[[nodiscard]] std::unique_ptr<Warp> make_dimple_warp(std::vector<Point3> centers,
                                                     std::vector<Vec3> displacements,
                                                     double radius, double rate);
/// The first n points of the spherical Fibonacci lattice on the unit sphere about the origin:
/// z_i = 1 - (2 i + 1) / n, longitude i * pi (3 - sqrt 5); none is at a pole.
/// \throw InvalidInput for n = 0.
[[nodiscard]] std::vector<Point3> fibonacci_sphere(std::size_t n);

}  // namespace dynmesh
