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

}  // namespace dynmesh
