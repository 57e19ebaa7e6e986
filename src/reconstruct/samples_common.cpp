#include "samples_common.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <unordered_map>

#include "dynmesh/error.hpp"

namespace dynmesh::detail {

void check_samples(std::span<const Point3> samples, const std::string& who) {
    const std::size_t n = samples.size();
    if (n < 4) throw InvalidInput(who + ": needs at least 4 samples, got " + std::to_string(n));
    if (n > std::numeric_limits<std::uint32_t>::max())
        throw InvalidInput(who + ": too many samples for 32-bit indices");
    for (std::size_t i = 0; i < n; ++i) {
        if (!is_finite(samples[i]))
            throw InvalidInput(who + ": sample " + std::to_string(i) +
                               " has a non-finite coordinate");
    }
    std::vector<std::uint32_t> idx(n);
    std::iota(idx.begin(), idx.end(), 0u);
    auto key = [&](std::uint32_t i) {
        const Point3& p = samples[i];
        return std::array<double, 3>{p.x, p.y, p.z};
    };
    std::sort(idx.begin(), idx.end(), [&](std::uint32_t a, std::uint32_t b) {
        const auto ka = key(a), kb = key(b);
        return ka != kb ? ka < kb : a < b;
    });
    std::string pairs;
    std::size_t count = 0;
    for (std::size_t k = 1; k < n; ++k) {
        if (key(idx[k]) != key(idx[k - 1])) continue;
        if (++count <= 5) {
            pairs += (pairs.empty() ? "" : ", ") + std::to_string(idx[k - 1]) + " and " +
                     std::to_string(idx[k]);
        }
    }
    if (count > 0)
        throw InvalidInput(who + ": " + std::to_string(count) +
                           " samples coincide with an earlier one: samples " + pairs +
                           (count > 5 ? ", ..." : "") + " are at the same position");
}

CompactSoup compact_soup(std::span<const Point3> samples,
                         std::span<const IndexTriangle> triangles) {
    constexpr auto kUnused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> new_index(samples.size(), kUnused);
    for (const auto& t : triangles)
        for (std::uint32_t i : t) new_index[i] = 0;
    CompactSoup out;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        if (new_index[i] == kUnused) continue;
        new_index[i] = static_cast<std::uint32_t>(out.vertex_sample.size());
        out.vertex_sample.push_back(static_cast<std::uint32_t>(i));
        out.soup.points.push_back(samples[i]);
    }
    out.soup.triangles.reserve(triangles.size());
    for (const auto& t : triangles)
        out.soup.triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
    return out;
}

std::string ManifoldDefects::describe() const {
    std::string s;
    auto add = [&](const std::string& part) { s += (s.empty() ? "" : ", ") + part; };
    if (non_manifold_edges() > 0)
        add(std::to_string(non_manifold_edges()) + " non-manifold edges (" +
            std::to_string(boundary_edges) + " with one facet, " + std::to_string(overused_edges) +
            " with three or more)");
    if (misoriented_edges > 0)
        add(std::to_string(misoriented_edges) + " edges whose two facets have the same direction");
    if (pinched_vertices > 0)
        add(std::to_string(pinched_vertices) + " non-manifold (pinched) vertices");
    return s;
}

ManifoldDefects find_manifold_defects(std::span<const IndexTriangle> triangles,
                                      std::size_t n_vertices) {
    ManifoldDefects out;
    // Undirected edge -> (number of triangles, number of them running from min to max).
    std::unordered_map<std::uint64_t, std::array<std::uint32_t, 2>> count;
    count.reserve(triangles.size() * 2);
    for (const auto& t : triangles) {
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t a = t[k], b = t[(k + 1) % 3];
            const auto [lo, hi] = std::minmax(a, b);
            auto& c = count[(std::uint64_t{lo} << 32) | hi];
            ++c[0];
            if (a < b) ++c[1];
        }
    }
    out.edges = count.size();
    for (const auto& [key, c] : count) {
        if (c[0] == 2 && c[1] == 1) continue;
        out.vertices.push_back(static_cast<std::uint32_t>(key >> 32));
        out.vertices.push_back(static_cast<std::uint32_t>(key & 0xFFFFFFFFu));
        if (c[0] == 1) {
            ++out.boundary_edges;
        } else if (c[0] > 2) {
            ++out.overused_edges;
        } else {
            ++out.misoriented_edges;
        }
    }
    // Vertex links: with every edge in two triangles, each link is a union of cycles; the
    // vertex is a manifold vertex when it is one cycle (one union-find component).
    std::vector<std::uint32_t> first(n_vertices + 1, 0);
    for (const auto& t : triangles)
        for (std::uint32_t v : t) ++first[v + 1];
    std::partial_sum(first.begin(), first.end(), first.begin());
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1), incident(first.back());
    for (std::size_t f = 0; f < triangles.size(); ++f)
        for (std::uint32_t v : triangles[f]) incident[fill[v]++] = static_cast<std::uint32_t>(f);
    std::vector<std::uint32_t> local, parent;
    for (std::uint32_t v = 0; v < n_vertices; ++v) {
        const std::uint32_t begin = first[v], end = first[v + 1];
        if (begin == end) continue;
        local.clear();
        for (std::uint32_t k = begin; k < end; ++k)
            for (std::uint32_t w : triangles[incident[k]])
                if (w != v) local.push_back(w);
        std::sort(local.begin(), local.end());
        local.erase(std::unique(local.begin(), local.end()), local.end());
        parent.resize(local.size());
        std::iota(parent.begin(), parent.end(), 0u);
        auto find = [&](std::uint32_t x) {
            while (parent[x] != x) x = parent[x] = parent[parent[x]];
            return x;
        };
        auto pos = [&](std::uint32_t w) {
            return static_cast<std::uint32_t>(std::lower_bound(local.begin(), local.end(), w) -
                                              local.begin());
        };
        std::size_t components = local.size();
        for (std::uint32_t k = begin; k < end; ++k) {
            std::array<std::uint32_t, 2> ends{};
            std::size_t m = 0;
            for (std::uint32_t w : triangles[incident[k]])
                if (w != v && m < 2) ends[m++] = w;
            const std::uint32_t ra = find(pos(ends[0])), rb = find(pos(ends[1]));
            if (ra != rb) {
                parent[ra] = rb;
                --components;
            }
        }
        if (components != 1) {
            ++out.pinched_vertices;
            out.vertices.push_back(v);
        }
    }
    std::sort(out.vertices.begin(), out.vertices.end());
    out.vertices.erase(std::unique(out.vertices.begin(), out.vertices.end()), out.vertices.end());
    return out;
}

double signed_volume(const TriangleSoup& soup) {
    if (soup.points.empty()) return 0;
    const Point3 o = soup.points.front();  // a nearby origin keeps the sum accurate
    double v = 0;
    for (const auto& t : soup.triangles) {
        const Vec3 a = soup.points[t[0]] - o, b = soup.points[t[1]] - o, c = soup.points[t[2]] - o;
        v += dot(a, cross(b, c));
    }
    return v / 6.0;
}

}  // namespace dynmesh::detail
