#pragma once
/// \file Private helpers shared by the reconstruction algorithms.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/soup.hpp"

namespace dynmesh::detail {

using IndexTriangle = std::array<std::uint32_t, 3>;

/// Throws InvalidInput (prefixed by `who`) for fewer than 4 samples, more than 2^32 - 1,
/// a non-finite coordinate, or coincident samples (naming the first few pairs).
void check_samples(std::span<const Point3> samples, const std::string& who);

/// The soup of `triangles` (indices into `samples`) over the used samples only, renumbered in
/// input order; `vertex_sample[k]` is the input index of soup vertex k.
struct CompactSoup {
    TriangleSoup soup;
    std::vector<std::uint32_t> vertex_sample;
};
[[nodiscard]] CompactSoup compact_soup(std::span<const Point3> samples,
                                       std::span<const IndexTriangle> triangles);

/// What keeps a set of oriented triangles from being a closed, oriented 2-manifold.
struct ManifoldDefects {
    std::size_t edges = 0;              ///< distinct edges
    std::size_t boundary_edges = 0;     ///< in one triangle
    std::size_t overused_edges = 0;     ///< in three or more triangles
    std::size_t misoriented_edges = 0;  ///< in two triangles with the same direction
    std::size_t pinched_vertices = 0;   ///< link is not one cycle (edges otherwise fine)
    /// Where: the ends of every defective edge and every pinched vertex, sorted, unique.
    std::vector<std::uint32_t> vertices;
    [[nodiscard]] std::size_t non_manifold_edges() const { return boundary_edges + overused_edges; }
    [[nodiscard]] bool ok() const {
        return non_manifold_edges() + misoriented_edges + pinched_vertices == 0;
    }
    /// "N non-manifold edges (B with one triangle, M with three or more), ..." (only the
    /// nonzero parts).
    [[nodiscard]] std::string describe() const;
};
/// Finds the defects of `triangles` over vertex indices below `n_vertices`.
[[nodiscard]] ManifoldDefects find_manifold_defects(std::span<const IndexTriangle> triangles,
                                                    std::size_t n_vertices);

/// Sum over triangles of det(a, b, c) / 6: the enclosed volume of a closed, outward mesh.
[[nodiscard]] double signed_volume(const TriangleSoup& soup);

}  // namespace dynmesh::detail
