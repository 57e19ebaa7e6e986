#pragma once
/// \file Point files: one point per line, `x y z` optionally followed by a normal `nx ny nz`
/// (the .xyz / .pwn convention). Same error discipline as mesh_io.hpp: IoError with file,
/// line and problem; atomic writes.

#include <filesystem>
#include <span>
#include <vector>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

/// Reads the points of a text file whose lines are `x y z` or `x y z nx ny nz` (normals are
/// read and dropped). Blank lines and `#` comments are skipped; the extension is not
/// checked.
/// \throw IoError when the file is missing or unreadable, a line does not hold 3 or 6
///        numbers, a coordinate is not finite, or there is no point at all.
[[nodiscard]] std::vector<Point3> read_points_xyz(const std::filesystem::path& path);

/// Writes `x y z` lines in shortest round-trip form, atomically.
/// \throw InvalidInput for a non-finite point; IoError on file-system failure.
void write_points_xyz(std::span<const Point3> points, const std::filesystem::path& path);

}  // namespace dynmesh
