#include "dynmesh/flips/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "dynmesh/geometry/triangle.hpp"

namespace dynmesh {

FlipDiagnostics flip_diagnostics(const SurfaceMesh& m, FlipRule rule, double shrink) {
    FlipDiagnostics d;
    d.ball_shrink = shrink;
    for (Edge e : m.edges()) {
        ++d.edges;
        if (is_flippable(m, e, rule)) ++d.flippable;
        if (is_illegal(m, e)) ++d.illegal;
    }
    // Uniform grid over vertices, cell = mean edge length.
    double len = 0;
    for (Edge e : m.edges()) len += distance(m.position(m.vertex(e, 0)), m.position(m.vertex(e, 1)));
    const double cell = d.edges ? std::max(len / double(d.edges), 1e-300) : 1.0;
    auto key = [cell](double x) {
        const double k = std::floor(x / cell);  // clamped: huge coordinates must not overflow
        return static_cast<std::int64_t>(std::clamp(k, -1e15, 1e15));
    };
    auto hash = [](std::int64_t i, std::int64_t j, std::int64_t k) {
        return static_cast<std::uint64_t>(i) * 73856093ULL ^ static_cast<std::uint64_t>(j) * 19349663ULL ^
               static_cast<std::uint64_t>(k) * 83492791ULL;
    };
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
    for (Vertex v : m.vertices()) {
        const Point3& p = m.position(v);
        grid[hash(key(p.x), key(p.y), key(p.z))].push_back(v.idx());
    }
    for (Face f : m.faces()) {
        ++d.faces;
        const auto vs = m.face_vertices(f);
        const Point3 &a = m.position(vs[0]), &b = m.position(vs[1]), &c = m.position(vs[2]);
        const Point3 cc = circumcenter(a, b, c);
        const double rad = shrink * distance(cc, a);
        if (!is_finite(cc) || !(rad / cell <= 16.0)) {
            ++d.unchecked_balls;
            continue;
        }
        const double r2 = rad * rad;
        const std::int64_t span = static_cast<std::int64_t>(std::ceil(rad / cell));
        bool hit = false;
        for (std::int64_t i = key(cc.x) - span; i <= key(cc.x) + span && !hit; ++i)
            for (std::int64_t j = key(cc.y) - span; j <= key(cc.y) + span && !hit; ++j)
                for (std::int64_t k = key(cc.z) - span; k <= key(cc.z) + span && !hit; ++k) {
                    auto it = grid.find(hash(i, j, k));
                    if (it == grid.end()) continue;
                    for (std::uint32_t w : it->second) {
                        if (w == vs[0].idx() || w == vs[1].idx() || w == vs[2].idx()) continue;
                        if (sqdistance(m.position(Vertex(w)), cc) < r2) {
                            hit = true;
                            break;
                        }
                    }
                }
        if (hit) ++d.nonempty_balls;
    }
    return d;
}

}  // namespace dynmesh
