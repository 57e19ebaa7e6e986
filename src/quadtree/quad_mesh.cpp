#include "dynmesh/quadtree/quad_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/scaled_frame.hpp"
#include "dynmesh/geometry/format.hpp"
#include "leaf_mesh.hpp"

namespace dynmesh {

namespace {

/// 2·signed area of (a, b, c), in long double.
long double twice_area(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (static_cast<long double>(b.x) - a.x) * (static_cast<long double>(c.y) - a.y) -
           (static_cast<long double>(b.y) - a.y) * (static_cast<long double>(c.x) - a.x);
}

}  // namespace

namespace detail {

template <>
void leaf_simplices<2>(const CellId<2>& leaf, LeafCode code,
                       std::vector<LatticeSimplex<2>>& out) {
    using L = Lattice<2>;
    const auto [lo, s] = cell_box(leaf);
    const std::uint64_t h = s / 2, x = lo[0], y = lo[1];
    std::array<L, 8> cycle{};
    std::size_t m = 0;
    bool hanging = false;
    const auto push_side = [&](L corner, L mid) {
        cycle[m++] = corner;
        if (h > 0 && code_has_vertex<2>(leaf, code, mid)) {
            cycle[m++] = mid;
            hanging = true;
        }
    };
    push_side({x, y}, {x + h, y});
    push_side({x + s, y}, {x + s, y + h});
    push_side({x + s, y + s}, {x + h, y + s});
    push_side({x, y + s}, {x, y + h});
    const bool star = code_is_star<2>(code);
    if (star && code_holds_point<2>(code)) {
        const L v = code_apex<2>(leaf, code);  // cone from the point (at v) over the far sides
        for (std::size_t k = 0; k < m; ++k) {
            const L a = cycle[k], b = cycle[(k + 1) % m];
            if (a != v && b != v) out.push_back({v, a, b});
        }
    } else if (star || hanging) {
        const L centre{x + h, y + h};
        for (std::size_t k = 0; k < m; ++k) out.push_back({centre, cycle[k], cycle[(k + 1) % m]});
    } else {
        out.push_back({cycle[0], cycle[1], cycle[2]});
        out.push_back({cycle[0], cycle[2], cycle[3]});
    }
}

}  // namespace detail

QuadMesh2 quad_mesh(const DynQuadtree<2>& tree) { return detail::mesh_of_tree<2>(tree); }

CheckReport check_quad_mesh(const QuadMesh2& mesh) {
    std::vector<std::string> bad;
    const auto n = mesh.points.size();
    std::vector<bool> used(n, false);
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<bool>> edges;  // dir: a<b
    long double area2 = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        if (tri[0] >= n || tri[1] >= n || tri[2] >= n) {
            bad.push_back("triangle " + std::to_string(t) + ": index out of range");
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            used[tri[k]] = true;
            const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
            edges[{std::min(a, b), std::max(a, b)}].push_back(a < b);
        }
        const Vec2 &a = mesh.points[tri[0]], &b = mesh.points[tri[1]], &c = mesh.points[tri[2]];
        if (orient2d(a, b, c) != Sign::Positive)
            bad.push_back("triangle " + std::to_string(t) + " is not counter-clockwise");
        area2 += twice_area(a, b, c);
    }
    // The box the vertices span: its far corner is origin + W rounded, as the mesh places it.
    const double x0 = mesh.origin.x, y0 = mesh.origin.y, x1 = x0 + mesh.width, y1 = y0 + mesh.width;
    const long double want = (static_cast<long double>(x1) - x0) * (static_cast<long double>(y1) - y0);
    if (std::fabs(area2 / 2 - want) > 1e-12L * want)
        bad.push_back("total area " + format_number(static_cast<double>(area2 / 2)) +
                      " differs from the domain area " + format_number(static_cast<double>(want)));
    for (const auto& [e, dirs] : edges) {
        const std::string name =
            "edge (" + std::to_string(e.first) + ", " + std::to_string(e.second) + ")";
        if (dirs.size() == 1) {
            const Vec2 &p = mesh.points[e.first], &q = mesh.points[e.second];
            const bool on_box = (p.x == x0 && q.x == x0) || (p.x == x1 && q.x == x1) ||
                                (p.y == y0 && q.y == y0) || (p.y == y1 && q.y == y1);
            if (!on_box)
                bad.push_back(name + " has one triangle but is not on the domain boundary");
        } else if (dirs.size() == 2) {
            if (dirs[0] == dirs[1])
                bad.push_back(name + ": its two triangles disagree in orientation");
        } else {
            bad.push_back(name + " is shared by " + std::to_string(dirs.size()) + " triangles");
        }
    }
    detail::append_vertex_problems<2>(mesh.points, used, bad);
    return CheckReport::of_problems(std::move(bad));
}

AngleRangeDeg angle_range_deg(const QuadMesh2& mesh) {
    AngleRangeDeg r;
    for (const auto& t : mesh.triangles) {
        // Measured in the triangle's exact unit frame (scaled_frame.hpp): no square or product
        // of edge vectors underflows or overflows, whatever the magnitude of the coordinates.
        std::array<Point3, 3> c;
        for (std::size_t k = 0; k < 3; ++k) c[k] = {mesh.points[t[k]].x, mesh.points[t[k]].y, 0.0};
        const UnitPoints<3> u = to_unit(c);
        for (std::size_t k = 0; k < 3; ++k) {
            const Point3& p = u.p[k];
            const Point3& a = u.p[(k + 1) % 3];
            const Point3& b = u.p[(k + 2) % 3];
            const double ux = a.x - p.x, uy = a.y - p.y, vx = b.x - p.x, vy = b.y - p.y;
            const double deg = std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180.0 /
                               std::numbers::pi;
            r.min = std::min(r.min, deg);
            r.max = std::max(r.max, deg);
        }
    }
    return r;
}

}  // namespace dynmesh
