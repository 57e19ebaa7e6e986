#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "dynmesh/mesh/soup.hpp"

namespace dynmesh {

TriangleSoup unit_icosphere(int level) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    TriangleSoup s;
    s.points = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : s.points) p = normalized(p);
    s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                   {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                   {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                   {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto k = std::minmax(a, b);
            auto it = mid.find(k);
            if (it != mid.end()) return it->second;
            s.points.push_back(normalized((s.points[a] + s.points[b]) * 0.5));
            const auto i = static_cast<std::uint32_t>(s.points.size() - 1);
            mid.emplace(k, i);
            return i;
        };
        std::vector<std::array<std::uint32_t, 3>> next;
        for (const auto& tr : s.triangles) {
            const auto a = midpoint(tr[0], tr[1]), b = midpoint(tr[1], tr[2]),
                       c = midpoint(tr[2], tr[0]);
            next.push_back({tr[0], a, c});
            next.push_back({tr[1], b, a});
            next.push_back({tr[2], c, b});
            next.push_back({a, b, c});
        }
        s.triangles.swap(next);
    }
    return s;
}

}  // namespace dynmesh
