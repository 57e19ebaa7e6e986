#pragma once
/// \file A triangle soup: positions plus index triples, the exchange format between file
/// readers, generators and `SurfaceMesh::from_soup`.

#include <array>
#include <cstdint>
#include <vector>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

struct TriangleSoup {
    std::vector<Point3> points;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// The unit icosphere: the icosahedron with each triangle split 1-to-4 `level` times and the
/// new vertices pushed onto the unit sphere (12 + 10·(4^level − 1) vertices, 20·4^level
/// triangles), oriented outward.
[[nodiscard]] TriangleSoup unit_icosphere(int level);

}  // namespace dynmesh
