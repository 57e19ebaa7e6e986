#include "dynmesh/quadtree/domain.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <string>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/format.hpp"

namespace dynmesh {

namespace {

template <int D>
std::string point_text(std::size_t i, const PointD<D>& p) {
    return "auto_domain: point " + std::to_string(i) + " " + format_point(p);
}

}  // namespace

template <int D>
QuadtreeOptions<D> auto_domain(std::span<const PointD<D>> points) {
    constexpr auto kD = static_cast<std::size_t>(D);
    QuadtreeOptions<D> o;
    if (points.empty()) return o;
    std::array<double, kD> lo{}, hi{};
    lo.fill(INFINITY);
    hi.fill(-INFINITY);
    for (std::size_t i = 0; i < points.size(); ++i)
        for (std::size_t d = 0; d < kD; ++d) {
            const double v = points[i][d];
            DYNMESH_CHECK(std::isfinite(v), point_text<D>(i, points[i]) + " is not finite");
            lo[d] = std::min(lo[d], v);
            hi[d] = std::max(hi[d], v);
        }
    std::array<double, kD> c{};
    double extent = 0;
    for (std::size_t d = 0; d < kD; ++d) {
        c[d] = 0.5 * lo[d] + 0.5 * hi[d];
        extent = std::max(extent, hi[d] - lo[d]);
    }
    if (!(extent > 0)) {  // one distinct position: a box of its own magnitude
        extent = 1;
        for (std::size_t d = 0; d < kD; ++d) extent = std::max(extent, std::fabs(c[d]));
    }
    int e = 0;
    const double m = std::frexp(6 * extent, &e);  // 6E = m·2^e, m in [0.5, 1)
    double width = m == 0.5 ? 6 * extent : std::ldexp(1.0, e);
    width = std::max(width, std::ldexp(DBL_MIN, DynQuadtree<D>::kLevels));
    DYNMESH_CHECK(std::isfinite(width),
                  "auto_domain: the points' extent overflows a double (coordinates too large)");
    o.width = width;
    const double g = width / 8;
    for (std::size_t d = 0; d < kD; ++d) {
        o.origin[d] = g * std::round((c[d] - 0.5 * width) / g);
        DYNMESH_CHECK(std::isfinite(o.origin[d] + width),
                      "auto_domain: the box overflows a double (coordinates too large)");
    }
    const DynQuadtree<D> probe(o);
    for (std::size_t i = 0; i < points.size(); ++i)
        DYNMESH_CHECK(probe.is_admissible(points[i]),
                      point_text<D>(i, points[i]) +
                          " is not in the middle third of the automatic box after rounding: the "
                          "spread of the points is below the double resolution at their "
                          "coordinates");
    return o;
}

template <int D>
QuadtreeOptions<D> auto_domain_for_updates(std::span<const PointD<D>> final_points,
                                           std::span<const PointD<D>> all_points) {
    const QuadtreeOptions<D> box = auto_domain<D>(final_points);
    const DynQuadtree<D> probe(box);
    if (std::all_of(all_points.begin(), all_points.end(),
                    [&](const PointD<D>& p) { return probe.is_admissible(p); }))
        return box;
    return auto_domain<D>(all_points);
}

template QuadtreeOptions<2> auto_domain<2>(std::span<const PointD<2>>);
template QuadtreeOptions<3> auto_domain<3>(std::span<const PointD<3>>);
template QuadtreeOptions<2> auto_domain_for_updates<2>(std::span<const PointD<2>>,
                                                       std::span<const PointD<2>>);
template QuadtreeOptions<3> auto_domain_for_updates<3>(std::span<const PointD<3>>,
                                                       std::span<const PointD<3>>);

}  // namespace dynmesh
