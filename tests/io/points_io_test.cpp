#include "dynmesh/io/points_io.hpp"

#include <bit>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

namespace fs = std::filesystem;

std::size_t non_empty_lines(const fs::path& p) {
    const std::string text = test::read_bytes(p);
    std::size_t n = 0;
    bool content = false;
    for (char c : text) {
        if (c == '\n') {
            n += content;
            content = false;
        } else if (c != ' ' && c != '\r' && c != '\t') {
            content = true;
        }
    }
    return n + content;
}

TEST(PointsIo, ReadsSharedPointFiles) {
    for (const char* name : {"points3d/kitten.xyz", "points3d/oneK.xyz"}) {
        const fs::path p = test::shared_data(name);
        const std::vector<Point3> points = read_points_xyz(p);
        EXPECT_EQ(points.size(), non_empty_lines(p)) << name;
        for (const Point3& q : points) ASSERT_TRUE(is_finite(q));
    }
    EXPECT_EQ(read_points_xyz(test::shared_data("points3d/oneK.xyz")).size(), 1000u);
    // kitten.xyz has normals: the first point is its first three numbers.
    const auto kitten = read_points_xyz(test::shared_data("points3d/kitten.xyz"));
    EXPECT_EQ(kitten.front(), (Point3{-0.0721898, -0.159749, -0.108444}));
}

TEST(PointsIo, RoundTripIsBitExact) {
    const fs::path dir = test::scratch_dir("io_points");
    Rng rng(3);
    std::vector<Point3> points;
    for (int i = 0; i < 500; ++i)
        points.push_back(rng.unit_vector() * std::exp(rng.uniform(-30.0, 30.0)));
    points.push_back({-0.0, 5e-324, 1.7976931348623157e308});
    write_points_xyz(points, dir / "p.xyz");
    const std::vector<Point3> back = read_points_xyz(dir / "p.xyz");
    ASSERT_EQ(back.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c)
            ASSERT_EQ(std::bit_cast<std::uint64_t>(back[i][c]),
                      std::bit_cast<std::uint64_t>(points[i][c]))
                << i;
    EXPECT_EQ(test::listing(dir), std::vector<std::string>{"p.xyz"});
    points[7].z = std::nan("");
    EXPECT_THROW(write_points_xyz(points, dir / "q.xyz"), InvalidInput);
    EXPECT_FALSE(fs::exists(dir / "q.xyz"));
}

TEST(PointsIo, Errors) {
    const fs::path dir = test::scratch_dir("io_points_errors");
    const auto expect_error = [&](const std::string& name, const std::string& content,
                                  const std::vector<std::string>& parts) {
        test::write_bytes(dir / name, content);
        const std::string msg = test::io_error_of([&] { (void)read_points_xyz(dir / name); });
        EXPECT_NE(msg.find(name), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        for (const auto& part : parts) EXPECT_NE(msg.find(part), std::string::npos) << msg;
    };
    expect_error("four.xyz", "0 0 0\n1 2 3 4\n", {"four.xyz:2:", "point 1: expected 3 or 6"});
    expect_error("two.xyz", "0 0\n", {"two.xyz:1:", "point 0: expected 3 coordinates"});
    expect_error("nan.xyz", "# c\n\n0 0 0\n1 nan 2\n",
                 {"nan.xyz:4:", "point 1 has a non-finite coordinate 'nan'"});
    expect_error("normal.xyz", "0 0 0 0 0 inf\n", {"normal.xyz:1:", "invalid normal component"});
    expect_error("empty.xyz", "", {"empty file"});
    expect_error("blank.xyz", "\n  \n# only a comment\n", {"no points"});
    EXPECT_THROW((void)read_points_xyz(dir / "missing.xyz"), IoError);
    // Comments, CRLF and normals are fine.
    test::write_bytes(dir / "ok.xyz", "# header\r\n1 2 3 0 0 1\r\n\r\n4 5 6 # note\r\n");
    EXPECT_EQ(read_points_xyz(dir / "ok.xyz"), (std::vector<Point3>{{1, 2, 3}, {4, 5, 6}}));
}

}  // namespace
}  // namespace dynmesh
