// ScopedUnitFrame: exact scaling into [1, 2) and a bit-for-bit restore, even when scaling
// would underflow a tiny coordinate of a huge mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dynmesh/mesh/unit_frame.hpp"
#include "test_support.hpp"

namespace dynmesh::test {
namespace {

double max_abs(const SurfaceMesh& m) {
    double big = 0;
    for (const Point3& p : m.positions())
        big = std::fmax(big, std::fmax(std::fabs(p.x), std::fmax(std::fabs(p.y), std::fabs(p.z))));
    return big;
}

TEST(ScopedUnitFrame, ScalesIntoTheUnitRangeAndRestoresExactly) {
    for (const double s : {1.0, 1e308, 1e-310, 3.0e-200, 7.5e150}) {
        SCOPED_TRACE(s);
        SurfaceMesh mesh = octahedron();
        for (Point3& p : mesh.positions()) p = p * s;
        mesh.positions()[0].y = s * 1e-290;  // underflows when s = 1e308 is scaled to 1
        const std::vector<Point3> before = mesh.positions();
        {
            const ScopedUnitFrame frame(mesh);
            EXPECT_GE(max_abs(mesh), 1.0);
            EXPECT_LT(max_abs(mesh), 2.0);
            EXPECT_EQ(frame.scale().length(mesh.positions()[1].x), before[1].x);
        }
        EXPECT_EQ(mesh.positions(), before);
    }
}

TEST(ScopedUnitFrame, RestoresWhenAnExceptionPropagates) {
    SurfaceMesh mesh = octahedron();
    for (Point3& p : mesh.positions()) p = p * 1e300;
    const std::vector<Point3> before = mesh.positions();
    try {
        const ScopedUnitFrame frame(mesh);
        throw std::runtime_error("algorithm failed");
    } catch (const std::runtime_error&) {
    }
    EXPECT_EQ(mesh.positions(), before);
}

}  // namespace
}  // namespace dynmesh::test
