#pragma once
/// \file Point sets in 2D or 3D: Triangle's and TetGen's `.node` files and plain text
/// (`x y` or `x y z` per line), and `.node`/`.ele` output of simplicial meshes.
///
/// Errors follow mesh_io.hpp: one-line IoError messages naming the file, the line and the
/// point; counts are checked against the file size before anything is allocated.

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

/// Points of dimension 2 (z = 0) or 3.
struct PointSet {
    int dimension = 2;
    std::vector<Point3> points;
    /// 1-based line of each point in the file it was read from (read_point_set fills it; empty
    /// for point sets made in code), for messages about a point.
    std::vector<std::size_t> lines;
};

/// Reads a point set. `.node`: header `n dim attributes markers`, then one line per point
/// `id x y [z] [attributes...] [marker]` with consecutive ids starting at 0 or 1 (attributes
/// and markers are read and dropped). Any other extension: one point per line, all lines
/// with the same count of 2 or 3 numbers. `#` starts a comment.
/// \throw IoError for a missing file, a malformed or inconsistent line, a non-finite
///        coordinate, a dimension other than 2 or 3, or no points.
[[nodiscard]] PointSet read_point_set(const std::filesystem::path& path);

/// Writes `base.node` (1-based ids, no attributes or markers) and `base.ele` with one
/// simplex per line (3 corners in 2D, 4 in 3D; corner indices 1-based), atomically, as
/// Triangle and TetGen do. Deterministic: equal input gives byte-identical files.
/// \throw InvalidInput for a bad dimension, a non-finite point or an index out of range;
///        IoError on file-system failure.
void write_node_ele(const std::filesystem::path& base, const PointSet& points,
                    std::span<const std::array<std::uint32_t, 4>> simplices);

}  // namespace dynmesh
