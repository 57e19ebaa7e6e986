#pragma once
/// \file The small text inputs of the command-line tool, read through read_input_file()
/// (regular files only, size-capped, UTF-8 byte-order mark skipped) with the error discipline
/// of mesh_io.hpp: one-line IoError messages "<file>:<line>: <problem>".
///   * vertex lists (`dynmesh flip --vertices`): whitespace-separated 0-based vertex indices;
///   * point update scripts (`dynmesh qmesh --ops`): one `+ x y [z]` (insert) or `- x y [z]`
///     (erase) per line.
/// In both, `#` starts a comment and blank lines are ignored.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

/// Reads the vertex indices of `path`; each must be < n_vertices. Duplicates are kept.
/// \throw IoError naming the file and line for a missing, non-regular or oversized file, a
///        token that is not a non-negative integer, an index >= n_vertices, or a file without
///        any index.
[[nodiscard]] std::vector<std::uint32_t> read_vertex_list(const std::filesystem::path& path,
                                                          std::size_t n_vertices);

/// One line of an update script.
struct PointUpdate {
    bool insert = true;    ///< '+' inserts, '-' erases
    Point3 point{};        ///< z = 0 for dimension 2
    std::size_t line = 0;  ///< 1-based line of the file
};

/// Reads an update script of points of `dimension` (2 or 3) coordinates. An empty script
/// (only comments and blanks) is valid and gives no updates.
/// \throw IoError naming the file and line for a missing, non-regular or oversized file, a
///        line that is not `+`/`-` followed by exactly `dimension` numbers, or a coordinate
///        that is not a finite number. InvalidInput for a dimension other than 2 or 3.
[[nodiscard]] std::vector<PointUpdate> read_update_script(const std::filesystem::path& path,
                                                          int dimension);

/// One row of a table of four numbers, with its line.
struct NumberRow {
    double v[4]{};
    std::size_t line = 0;  ///< 1-based line of the file
};

/// Reads rows of exactly four finite numbers (balls `x y z r`, weighted points `x y z w`);
/// `layout` names the columns in messages ("x y z r"), `what` the rows ("ball", "atom").
/// \throw IoError "<file>:<line>: expected '<layout>' (four finite numbers), got '...'" for a
///        bad row, "<file>: no <what> in the file" for a file without rows.
[[nodiscard]] std::vector<NumberRow> read_four_number_rows(const std::filesystem::path& path,
                                                           std::string_view layout, std::string_view what);

}  // namespace dynmesh
