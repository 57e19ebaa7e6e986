#pragma once
/// \file The soups with polylines that tests/io/polylines_write_test.cpp parses back and that
/// tests/io/polyline_samples.cpp writes for tests/io/polyline_readers_check.py (which spells
/// the same data out again, independently).

#include <cstdint>
#include <vector>

#include "dynmesh/io/mesh_io.hpp"

namespace dynmesh::test {

/// A 2D run: six points at z = 0, no triangle, one closed polygon through all of them.
inline TriangleSoup polygon_soup() {
    TriangleSoup s;
    s.points = {{0, 0, 0}, {2, 0, 0}, {3, 1, 0}, {2, 2, 0}, {0, 2, 0}, {-1, 1, 0}};
    return s;
}
inline std::vector<std::vector<std::uint32_t>> polygon_polylines() {
    return {{0, 1, 2, 3, 4, 5, 0}};
}

/// A 3D run: the octahedron (points 0-5, 8 triangles) and three points of a path (6-8)
/// that no triangle uses; a closed path and an open one through the octahedron's vertices.
inline TriangleSoup mixed_soup() {
    TriangleSoup s;
    s.points = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},  {0, -1, 0}, {0, 0, 1},
                {0, 0, -1}, {2, 2, 2},  {-2, 2, 2}, {0, -2, 2}};
    s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return s;
}
inline std::vector<std::vector<std::uint32_t>> mixed_polylines() {
    return {{6, 7, 8, 6}, {0, 6, 1, 7, 2}};
}

/// One polyline of 2500 indices over the mixed soup's points (index k is k mod 9): longer
/// than an OBJ line carries (1024 indices), so its `l` statement is continued twice.
inline std::vector<std::vector<std::uint32_t>> long_polylines() {
    std::vector<std::uint32_t> p;
    for (std::uint32_t k = 0; k < 2500; ++k) p.push_back(k % 9);
    return {p};
}

}  // namespace dynmesh::test
