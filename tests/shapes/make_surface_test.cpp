#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh {
namespace {

TEST(MakeSurface, ParsesEachKind) {
    const auto unit = make_surface("sphere");
    ASSERT_NE(dynamic_cast<const Sphere*>(unit.get()), nullptr);
    EXPECT_EQ(unit->spec(), "sphere:1");
    EXPECT_DOUBLE_EQ(unit->area(), 4 * kPi);

    const auto s = make_surface("sphere:2.5");
    const auto* sphere = dynamic_cast<const Sphere*>(s.get());
    ASSERT_NE(sphere, nullptr);
    EXPECT_EQ(sphere->radius(), 2.5);
    EXPECT_EQ(sphere->center(), (Point3{0, 0, 0}));

    const auto e = make_surface("ellipsoid:3,1,2");
    const auto* ellipsoid = dynamic_cast<const Ellipsoid*>(e.get());
    ASSERT_NE(ellipsoid, nullptr);
    EXPECT_EQ(ellipsoid->semi_axes(), (Vec3{3, 1, 2}));

    const auto t = make_surface("torus:5,3@1,-2,0.25");
    const auto* torus = dynamic_cast<const Torus*>(t.get());
    ASSERT_NE(torus, nullptr);
    EXPECT_EQ(torus->major_radius(), 5);
    EXPECT_EQ(torus->minor_radius(), 3);
    EXPECT_EQ(torus->center(), (Point3{1, -2, 0.25}));
    EXPECT_EQ(t->spec(), "torus:5,3@1,-2,0.25");

    const auto spaced = make_surface(" torus : 5 , 3 @ 0, 0 ,1");
    EXPECT_EQ(spaced->spec(), "torus:5,3@0,0,1");
    EXPECT_EQ(make_surface("sphere:1e-3")->spec(), "sphere:0.001");
}

TEST(MakeSurface, SpecRoundTrips) {
    for (const std::string spec :
         {"sphere:1", "sphere:0.1@0.3,-0.7,1e+07", "ellipsoid:1,2,3", "ellipsoid:0.5,0.5,7@1,1,1",
          "torus:5,3", "torus:1,0.999999@-1,0,0"}) {
        const auto s = make_surface(spec);
        EXPECT_EQ(s->spec(), spec);
        EXPECT_EQ(make_surface(s->spec())->spec(), spec);
    }
    // Non-representable decimals still round-trip exactly through the shortest form.
    const Sphere odd({0.1 + 0.2, 1.0 / 3.0, -2.0 / 7.0}, std::sqrt(2.0));
    const auto back = make_surface(odd.spec());
    const auto* sphere = dynamic_cast<const Sphere*>(back.get());
    ASSERT_NE(sphere, nullptr);
    EXPECT_EQ(sphere->center(), odd.center());
    EXPECT_EQ(sphere->radius(), odd.radius());
}

TEST(MakeSurface, BadSpecsThrowNamingTheSpec) {
    for (const std::string spec : {"",
                                   "cube",
                                   "cube:1",
                                   "Sphere:1",
                                   "sphere:",
                                   "sphere:0",
                                   "sphere:-1",
                                   "sphere:1,2",
                                   "sphere:abc",
                                   "sphere:1x",
                                   "sphere:nan",
                                   "sphere:inf",
                                   "sphere:1e999",
                                   "sphere:,",
                                   "ellipsoid",
                                   "ellipsoid:1,2",
                                   "ellipsoid:1,2,3,4",
                                   "ellipsoid:1,0,3",
                                   "ellipsoid:1,-2,3",
                                   "ellipsoid:1,nan,3",
                                   "torus",
                                   "torus:5",
                                   "torus:5,3,1",
                                   "torus:3,5",
                                   "torus:3,3",
                                   "torus:5,0",
                                   "torus:-5,-6",
                                   "sphere:1@1,2",
                                   "sphere:1@1,2,3,4",
                                   "sphere:1@a,b,c",
                                   "sphere:1@nan,0,0",
                                   "sphere:1@1,2,3@4",
                                   "sphere@",
                                   "torus:5;3"}) {
        try {
            (void)make_surface(spec);
            ADD_FAILURE() << "accepted \"" << spec << "\"";
        } catch (const InvalidInput& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("\"" + spec + "\""), std::string::npos) << what;
        }
    }
}

TEST(MakeSurface, MessagesSayWhatIsWrong) {
    auto message = [](const std::string& spec) {
        try {
            (void)make_surface(spec);
        } catch (const InvalidInput& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(message("cube").find("unknown surface 'cube'"), std::string::npos);
    EXPECT_NE(message("torus:5").find("takes 2 parameters"), std::string::npos);
    EXPECT_NE(message("sphere:abc").find("'abc' is not a number"), std::string::npos);
    EXPECT_NE(message("sphere:nan").find("not finite"), std::string::npos);
    EXPECT_NE(message("torus:3,5").find("smaller than the major radius"), std::string::npos);
    EXPECT_NE(message("sphere:-1").find("positive"), std::string::npos);
    EXPECT_NE(message("sphere:1@1,2").find("3 coordinates"), std::string::npos);
}

}  // namespace
}  // namespace dynmesh

namespace dynmesh {
namespace {

TEST(MakeSurface, RefusesSizesDoublesCannotResolve) {
    for (const std::string spec : {"sphere:1e100", "sphere:1e-100", "torus:1e60,1", "ellipsoid:1,1,1e-60",
                                   "sphere:1@1e300,0,0", "sphere:0.1@0,0,1e20"})
        EXPECT_THROW((void)make_surface(spec), InvalidInput) << spec;
    EXPECT_NO_THROW((void)make_surface("sphere:1e40@0,0,1e45"));
    EXPECT_NO_THROW((void)make_surface("sphere:1e-40"));
}

}  // namespace
}  // namespace dynmesh
