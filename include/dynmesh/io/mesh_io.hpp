#pragma once
/// \file Reading and writing triangle meshes: OFF, OBJ, PLY and STL in; OFF, OBJ, PLY, legacy
/// VTK and VTK XML PolyData out, optionally with polylines (WriteOptions::polylines), plus
/// ParaView time series (.pvd).
///
/// Error discipline (every function here)
/// - Every failure throws `IoError` with a one-line message naming the file and where the
///   problem is: `<file>:<line>: ...` for text, `<file>: byte offset <n>, ...` for binary
///   data, followed by the element (vertex, face, facet) and what is wrong. File content is
///   quoted with control bytes escaped, so a message never spans lines.
/// - Readers never trust counts: a header count that cannot fit in the rest of the file is
///   rejected before anything is allocated, and non-regular files (directories, devices,
///   pipes) are refused, so a reader cannot hang or exhaust memory on a hostile file.
/// - Non-finite coordinates (NaN, infinity, overflow such as 1e999) are rejected and the
///   message names the vertex.
/// - Polygons are never triangulated behind the caller's back: a face with more than three
///   corners throws "face N has K vertices; only triangles are supported".
/// - Writers are atomic: the data go to a temporary file in the target's directory that is
///   renamed over the target only when complete. On failure the temporary file is removed
///   and the target is left as it was.

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "dynmesh/io/points_io.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

// ---- reading ------------------------------------------------------------------------------

/// Reads the triangles of a mesh file, choosing the format by extension (case-insensitive):
/// - `.off`: `OFF` (also `COFF`, `NOFF`, `STOFF`...; extra per-vertex and per-face values
///   such as colours are ignored). One vertex or face per line; `#` starts a comment.
/// - `.obj`: `v` and `f` lines; `f` accepts `a`, `a/b`, `a//c` and `a/b/c` corners and
///   negative (relative) indices; every index must refer to a vertex defined above the
///   face. Every other statement (`vt`, `vn`, `g`, `usemtl`, ...) is ignored.
/// - `.ply`: ascii, binary_little_endian and binary_big_endian. Positions come from the
///   `x`, `y`, `z` properties of element `vertex`; triangles from the list property
///   `vertex_indices` (or `vertex_index`) of element `face`, or from element `tristrips`
///   (list `vertex_indices`, -1 ends a strip; strip triangle k is (k, k+1, k+2) with the first
///   two swapped for odd k; triangles with a repeated index are skipped). Other elements and
///   properties are skipped.
/// - `.stl`: ascii or binary (binary when the size is exactly 84 + 50 * triangle count).
///   Corners with bit-identical coordinates (after -0 = +0) are welded into one vertex, in
///   order of first appearance; a facet with two welded corners is an error.
/// The soup is returned as in the file: vertices in file order, even unreferenced ones.
/// \throw IoError when the file is missing or unreadable, the extension is unknown, the
///        content is malformed, a face is not a triangle, a face repeats a vertex or uses
///        an index out of range, a coordinate is not finite, or the file holds no triangle.
[[nodiscard]] TriangleSoup read_soup(const std::filesystem::path& path);

/// `SurfaceMesh::from_soup(read_soup(path))`.
/// \throw IoError as read_soup; TopologyError (message prefixed with the file name) when the
///        triangles do not form an oriented 2-manifold (for instance a pinched vertex or
///        inconsistently oriented faces); IoError for the other from_soup rejections.
[[nodiscard]] SurfaceMesh read_mesh(const std::filesystem::path& path);

/// The extensions read_soup() understands, lower case with the dot: .off .obj .ply .stl
[[nodiscard]] std::vector<std::string> readable_mesh_extensions();

// ---- writing ------------------------------------------------------------------------------

/// A named scalar per vertex or per face. Names must be non-empty and made of letters,
/// digits, `_`, `-` and `.` (they end up unquoted in PLY and legacy VTK headers).
struct ScalarField {
    std::string name;
    std::vector<double> values;  ///< one per live element, in index order
};

enum class PlyEncoding {
    BinaryLittleEndian,  ///< compact and exact (positions as double)
    Ascii,               ///< readable; positions in shortest round-trip decimal form
};

struct WriteOptions {
    PlyEncoding ply_encoding = PlyEncoding::BinaryLittleEndian;  ///< .ply only
    /// Per-vertex fields: .vtk/.vtp PointData (Float64), .ply extra `float` vertex
    /// properties. Each must have n_vertices() values. Ignored by .off and .obj, which
    /// cannot carry them.
    std::vector<ScalarField> vertex_fields;
    /// Per-face fields: .vtk/.vtp CellData, .ply extra `float` face properties. Each must
    /// have n_faces() values (triangles only, never polylines). Ignored by .off and .obj.
    /// Refused together with polylines in .vtk/.vtp (see below).
    std::vector<ScalarField> face_fields;
    /// Polylines written after the triangles, each a list of at least 2 indices into the
    /// written vertices (the soup's points; for write_mesh the 0..n_vertices()-1 numbering
    /// the file gets). A closed polygon repeats its first index at the end. Empty (the
    /// default): the output is byte for byte the triangle-only one. Per format:
    /// - `.vtp`: a `<Lines>` section (connectivity, offsets) and NumberOfLines;
    /// - `.vtk`: `LINES n size`, one `k i0 ... ik-1` row per polyline;
    /// - `.obj`: `l i0 i1 ...` statements (1-based), continued on the next line with a
    ///   trailing backslash every 1024 indices (VTK's OBJ reader refuses lines over 256 KiB);
    /// - `.ply`: an `edge` element with `int vertex1, vertex2` (`uint` when the faces use
    ///   `uint`), one edge per segment, so a polyline of k indices becomes k - 1 edges;
    /// - `.off`: each segment as a face of 2 vertices (`2 i j`), counted in the header's
    ///   face count, after the triangles.
    /// read_soup() skips `l` statements and `edge` elements but refuses 2-vertex OFF faces,
    /// so only the triangles of .obj and .ply files read back. In VTK, cells are numbered
    /// verts, lines, polys, strips: the lines come before the triangles, so CellData would
    /// need a value per line too; face_fields together with polylines are therefore refused
    /// for .vtk and .vtp (InvalidInput). .ply keeps its face fields on the face element.
    std::vector<std::vector<std::uint32_t>> polylines;
};

/// Writes the live elements of `mesh`, choosing the format by extension (case-insensitive):
/// `.off`, `.obj`, `.ply`, `.stl` (binary; float32 corners, no shared vertices, no fields:
/// vertex and face fields are not written, polylines are refused), `.vtk` (legacy ASCII
/// POLYDATA) or `.vtp` (VTK XML PolyData with ascii DataArrays). Vertices are renumbered 0..n-1 in index order, skipping deleted ones
/// (the numbering garbage_collection() would give); faces follow in index order as
/// `mesh.to_soup()` lists them. Coordinates are written in shortest round-trip form (text)
/// or as doubles (binary PLY), so reading the file back reproduces them bit for bit.
/// The write is atomic (see the file comment). A mesh without faces is written (with
/// `options.polylines`, a file of polylines only), but read_soup() refuses such a file.
/// \throw InvalidInput when a field has the wrong size, a bad or duplicate name, or a
///        non-finite value (or, for PLY, a value that does not fit in a float), when a
///        position is not finite, when a polyline has fewer than 2 indices or an index out of
///        range, or when face fields and polylines go to one .vtk or .vtp file. IoError for
///        an unknown extension or any file-system failure (missing directory, permissions,
///        full disk).
void write_mesh(const SurfaceMesh& mesh, const std::filesystem::path& path,
                const WriteOptions& options = {});

/// As write_mesh, for a soup (all its points and triangles, in order; fields sized to
/// points.size() and triangles.size()).
/// \throw InvalidInput additionally when a triangle uses an index out of range.
void write_soup(const TriangleSoup& soup, const std::filesystem::path& path,
                const WriteOptions& options = {});

/// The extensions write_mesh() understands: .off .obj .ply .stl .vtk .vtp
[[nodiscard]] std::vector<std::string> writable_mesh_extensions();

/// Writes a ParaView collection (.pvd) listing one dataset per time step, in the given
/// order. File names are written as given (relative to the .pvd's directory, as ParaView
/// resolves them) and XML-escaped. Atomic, like write_mesh.
/// \throw InvalidInput for a non-finite time or an empty file name; IoError on file-system
///        failure.
void write_pvd(const std::filesystem::path& pvd,
               const std::vector<std::pair<double, std::string>>& time_and_relative_file);

/// Throws IoError when `in` and `out` name the same existing file (after following links
/// and `..`), so a command never overwrites its own input. Does nothing when either is
/// missing.
void ensure_not_same_file(const std::filesystem::path& in, const std::filesystem::path& out);

}  // namespace dynmesh
