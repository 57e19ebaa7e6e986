#pragma once
/// \file Output of simplicial meshes (triangles in 2D, tetrahedra in 3D), e.g. the quadtree
/// meshes QuadMesh2 / OctMesh3, in the format named by the output file's extension:
///   * `.node` (or `.ele`): Triangle's / TetGen's pair OUT.node + OUT.ele (write_node_ele of
///     point_set_io.hpp: 1-based ids, shortest round-trip numbers);
///   * `.off`: a polygon soup. 2D: every triangle, vertices written as `x y 0`. 3D: the
///     **boundary surface only** (the triangles used by exactly one tetrahedron, oriented
///     outwards, in tetrahedron order), over the vertices it uses (in increasing index order);
///   * `.vtu`: VTK XML UnstructuredGrid, ASCII, Float64 points (z = 0 in 2D), Int64
///     connectivity and offsets, cell types 5 (triangle) or 10 (tetrahedron);
///   * `.mesh`: Medit (`MeshVersionFormatted 2`, `Dimension 2|3`, `Vertices` with reference
///     0, `Triangles` or `Tetrahedra` with 1-based indices and reference 0, `End`).
/// Extensions are matched case-insensitively. Numbers of .off, .vtu and .mesh files are
/// printed with printf's "%.17g" (round-trips every double). Output is deterministic (equal
/// input gives byte-identical files) and atomic (write_text_file: a failed write leaves no
/// partial file and does not touch an existing one). Simplices are written as given: the
/// caller's orientation is kept.

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

enum class SimplexMeshFormat {
    NodeEle,  // .node / .ele
    Off,      // .off
    Vtu,      // .vtu
    Medit,    // .mesh
};

/// The format named by `path`'s extension.
/// \throw InvalidInput naming the path and the supported extensions for any other extension.
[[nodiscard]] SimplexMeshFormat simplex_mesh_format(const std::filesystem::path& path);

/// A simplicial mesh to write: `dimension` 2 (triangles: the first 3 entries of each simplex
/// are used, points' z ignored) or 3 (tetrahedra).
struct SimplexMeshView {
    int dimension = 3;
    std::span<const Point3> points;
    std::span<const std::array<std::uint32_t, 4>> simplices;
};

/// Writes `mesh` in the format of `path`'s extension (see the file comment) and returns the
/// files written, in order (two for .node/.ele: OUT.node then OUT.ele, whichever of the two
/// extensions `path` carries).
/// \throw InvalidInput for an unknown extension, a dimension other than 2 or 3, a non-finite
///        coordinate, or a simplex index out of range (nothing is written);
///        IoError on file-system failure.
std::vector<std::filesystem::path> write_simplex_mesh(const std::filesystem::path& path,
                                                      const SimplexMeshView& mesh);

/// 2D convenience form (e.g. QuadMesh2's points and triangles).
std::vector<std::filesystem::path> write_triangle_mesh(
    const std::filesystem::path& path, std::span<const Vec2> points,
    std::span<const std::array<std::uint32_t, 3>> triangles);

/// 3D convenience form (e.g. OctMesh3's points and tets).
std::vector<std::filesystem::path> write_tet_mesh(
    const std::filesystem::path& path, std::span<const Point3> points,
    std::span<const std::array<std::uint32_t, 4>> tets);

/// The file contents write_simplex_mesh would produce for .off, .vtu or .mesh (for tests and
/// in-memory use). \throw InvalidInput as write_simplex_mesh, and for NodeEle (two files).
[[nodiscard]] std::string simplex_mesh_text(SimplexMeshFormat format, const SimplexMeshView& mesh);

}  // namespace dynmesh
