#include "dynmesh/geometry/spatial_sort.hpp"

#include <algorithm>
#include <numeric>

#include "dynmesh/error.hpp"

namespace dynmesh {

namespace {
/// Spreads the low 21 bits of x so that two zero bits separate consecutive ones.
std::uint64_t spread3(std::uint64_t x) {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
}
}  // namespace

std::vector<std::uint32_t> spatial_order(std::span<const Point3> points) {
    DYNMESH_CHECK(points.size() < (std::size_t(1) << 32), "spatial_order: too many points");
    Bbox3 box;
    for (const Point3& p : points) box.extend(p);
    const double ext = std::max({box.max.x - box.min.x, box.max.y - box.min.y, box.max.z - box.min.z});
    const double scale = ext > 0 ? double((1u << 21) - 1) / ext : 0.0;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Point3& p = points[i];
        auto q = [&](double v, double lo) {
            const double t = (v - lo) * scale;
            return static_cast<std::uint64_t>(std::isfinite(t) ? std::clamp(t, 0.0, 2097151.0) : 0.0);
        };
        keyed[i] = {spread3(q(p.x, box.min.x)) | spread3(q(p.y, box.min.y)) << 1 |
                        spread3(q(p.z, box.min.z)) << 2,
                    static_cast<std::uint32_t>(i)};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::uint32_t> order(points.size());
    for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
    return order;
}

void spatial_sort(std::vector<Point3>& points) {
    const std::vector<std::uint32_t> order = spatial_order(points);
    std::vector<Point3> out;
    out.reserve(points.size());
    for (std::uint32_t i : order) out.push_back(points[i]);
    points.swap(out);
}

}  // namespace dynmesh
