#include "dynmesh/io/point_set_io.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "dynmesh/error.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

std::filesystem::path write(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
    const auto p = dir / name;
    std::ofstream(p) << text;
    return p;
}

std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(PointSetIo, ReadsTheSharedPlanarFiles) {
    struct Case {
        const char* file;
        std::size_t n;
    };
    for (const Case& c : {Case{"planar/dots.node", 100}, Case{"planar/spiral.node", 15},
                          Case{"planar/greenland.node", 33343}, Case{"planar/CD500.xy", 500},
                          Case{"planar/blob00.xy", 320}}) {
        const PointSet ps = read_point_set(test::shared_data(c.file));
        EXPECT_EQ(ps.dimension, 2) << c.file;
        EXPECT_EQ(ps.points.size(), c.n) << c.file;
    }
    const PointSet g = read_point_set(test::shared_data("planar/greenland.node"));
    EXPECT_EQ(g.points[0], (Point3{105, 39.5, 0}));
    const PointSet k = read_point_set(test::shared_data("points3d/oneK.xyz"));
    EXPECT_EQ(k.dimension, 3);
    EXPECT_EQ(k.points.size(), 1000u);
}

TEST(PointSetIo, MalformedFilesGiveOneLineErrors) {
    const auto dir = test::scratch_dir("point_set_io");
    const std::vector<std::pair<std::string, std::string>> bad = {
        {"count.node", "3 2 0 0\n1 0 0\n2 1 0\n"},
        {"dim.node", "1 4 0 0\n1 0 0 0 0\n"},
        {"ids.node", "2 2 0 0\n1 0 0\n3 1 0\n"},
        {"nan.node", "1 2 0 0\n1 nan 0\n"},
        {"huge.node", "99999999999 2 0 0\n1 0 0\n"},
        {"marker.node", "1 2 0 1\n1 0 0\n"},
        {"mixed.xy", "0 0\n1 1 1\n"},
        {"word.xy", "0 zero\n"},
        {"empty.xy", "# nothing\n"},
    };
    for (const auto& [name, text] : bad) {
        const auto p = write(dir, name, text);
        try {
            (void)read_point_set(p);
            ADD_FAILURE() << name << " was accepted";
        } catch (const IoError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(name), std::string::npos) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    }
}

TEST(PointSetIo, NodeEleRoundTripIsDeterministic) {
    const auto dir = test::scratch_dir("node_ele");
    PointSet ps{2, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.1, 0.7, 0}}};
    const std::vector<std::array<std::uint32_t, 4>> tris = {{0, 1, 2, 0}, {0, 2, 3, 0}};
    write_node_ele(dir / "a", ps, tris);
    write_node_ele(dir / "b", ps, tris);
    EXPECT_EQ(slurp(dir / "a.node"), slurp(dir / "b.node"));
    EXPECT_EQ(slurp(dir / "a.ele"), slurp(dir / "b.ele"));
    const PointSet back = read_point_set(dir / "a.node");
    EXPECT_EQ(back.points, ps.points);
    EXPECT_NE(slurp(dir / "a.ele").find("2 1 3 4"), std::string::npos);
    const std::vector<std::array<std::uint32_t, 4>> bad = {{0, 1, 9, 0}};
    EXPECT_THROW(write_node_ele(dir / "c", ps, bad), InvalidInput);
    EXPECT_FALSE(std::filesystem::exists(dir / "c.node"));
}

}  // namespace
}  // namespace dynmesh
