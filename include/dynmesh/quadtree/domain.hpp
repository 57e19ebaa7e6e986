#pragma once
/// \file The automatic domain box of a point set (spec §1.1, §7.2: the domain is fixed before
/// any point is inserted and never follows the points; this is how a caller that has no box
/// of its own picks one).
///
/// Rule. Let [lo, hi] be the bounding box of the points, c = (lo + hi) / 2 its centre and
/// E = max_d (hi_d − lo_d) its larger extent (for E = 0, i.e. one distinct position,
/// E = max(1, max_d |c_d|)). Then
///   * the width W is the smallest power of two with W ≥ 6·E (so E ≤ W/6), but at least
///     2^52·DBL_MIN (the grid unit W·2^-52 stays a normal double);
///   * each origin coordinate is snapped to the grid of step g = W/8:
///     o_d = g·round((c_d − W/2) / g), the multiple of g nearest to the centred origin.
/// Snapping moves the box by at most W/16 from the centred position, and the middle third
/// [o + W/3, o + 2W/3]^D then holds the bounding box with a margin of at least W/48 on every
/// side. The box is dyadic (quadtree.hpp, "Resolution"): every lattice point is an exact double
/// wherever the coordinates allow it, so points may be as close as about one ulp of their
/// coordinates.
///
/// Stability. The box depends on the points only through two integers: ⌈log2(6·E)⌉ and
/// round((c_d − W/2) / g) per axis. A change of the bounding box that moves neither across a
/// threshold (6·E across a power of two, c_d across a half-integer multiple of g, offset by
/// W/2) leaves the box, hence the tree and the mesh, bit for bit unchanged. In particular
/// erasing or adding points well inside the bounding box never moves it, and two point sets
/// whose bounding boxes differ by a small fraction of E get the same box unless they straddle a
/// threshold.
///
/// Update runs: auto_domain_for_updates() picks the box of the final point set when every
/// point the run ever holds fits in its middle third, so that an update run and a from-scratch
/// run on the final points use the same box and write the same bytes (history independence).

#include <span>

#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh {

/// The automatic box of `points` (see the file comment); the unit box [0, 1]^D when there
/// are none. The mode is QuadtreeMode::Paper (set it as needed).
/// \throw InvalidInput naming a point if one is not finite, if the box would overflow
///        (coordinates near DBL_MAX), or if a point is not in the middle third of the box
///        after rounding (a spread of a few ulps at coordinates beyond 2^50·W: the points are
///        not resolvable).
template <int D>
[[nodiscard]] QuadtreeOptions<D> auto_domain(std::span<const PointD<D>> points);

/// The box for a run that builds over some points, then inserts and erases: `final_points`
/// is the point set at the end of the run and `all_points` every point the run ever holds
/// (the initial ones and every inserted one). Returns auto_domain(final_points) when every
/// point of `all_points` lies in its middle third (DynQuadtree::is_admissible), else
/// auto_domain(all_points). In the first case a from-scratch run on the final points, which
/// uses auto_domain(final_points), gets the same box.
/// \throw InvalidInput as auto_domain().
template <int D>
[[nodiscard]] QuadtreeOptions<D> auto_domain_for_updates(std::span<const PointD<D>> final_points,
                                                         std::span<const PointD<D>> all_points);

extern template QuadtreeOptions<2> auto_domain<2>(std::span<const PointD<2>>);
extern template QuadtreeOptions<3> auto_domain<3>(std::span<const PointD<3>>);
extern template QuadtreeOptions<2> auto_domain_for_updates<2>(std::span<const PointD<2>>,
                                                              std::span<const PointD<2>>);
extern template QuadtreeOptions<3> auto_domain_for_updates<3>(std::span<const PointD<3>>,
                                                              std::span<const PointD<3>>);

}  // namespace dynmesh
