#include "dynmesh/skin/critical_events.hpp"

#include <algorithm>
#include <tuple>

namespace dynmesh {

std::vector<SkinEvent> critical_events(const SkinFunction& phi, double t_min, double t_max) {
    std::vector<SkinEvent> out;
    const auto& S = phi.simplices();
    for (std::size_t k = 0; k < S.size(); ++k) {
        const SkinSimplex& sx = S[k];
        if (!(sx.W >= t_min && sx.W <= t_max)) continue;
        bool input = true;
        for (int i = 0; i <= sx.dim; ++i) input = input && std::size_t(sx.vertices[std::size_t(i)]) < phi.input_balls();
        if (!input || !phi.in_mixed_cell(k, sx.z)) continue;
        out.push_back({static_cast<SkinEvent::Kind>(sx.dim), sx.W, sx.z, k});
    }
    std::sort(out.begin(), out.end(), [](const SkinEvent& a, const SkinEvent& b) {
        return std::tuple(a.time, int(a.kind), a.simplex) < std::tuple(b.time, int(b.kind), b.simplex);
    });
    return out;
}

}  // namespace dynmesh
