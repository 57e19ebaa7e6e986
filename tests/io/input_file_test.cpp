// The checked reader behind every file argument: regular files only, size cap, BOM, and the
// readers' strictness about headers that promise fewer elements than the file holds.
#include <sys/stat.h>

#include <gtest/gtest.h>

#include "dynmesh/io/input_file.hpp"
#include "dynmesh/io/point_set_io.hpp"
#include "dynmesh/io/points_io.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

namespace dynmesh::test {
namespace {

TEST(InputFile, ReadsARegularFile) {
    const auto dir = scratch_dir("input_file_regular");
    write_bytes(dir / "a.txt", "hello\n");
    EXPECT_EQ(read_input_file(dir / "a.txt"), "hello\n");
}

TEST(InputFile, RefusesAFifoWithoutBlocking) {
    const auto dir = scratch_dir("input_file_fifo");
    const auto fifo = dir / "pipe.off";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // No writer: a reader that opened it blocking would hang here forever.
    const std::string msg = io_error_of([&] { (void)read_input_file(fifo); });
    EXPECT_NE(msg.find("pipe.off"), std::string::npos) << msg;
    EXPECT_NE(msg.find("FIFO"), std::string::npos) << msg;
    expect_read_error(fifo, {"not a regular file"});
}

TEST(InputFile, RefusesDevicesAndDirectories) {
    EXPECT_NE(io_error_of([] { (void)read_input_file("/dev/zero"); }).find("device"), std::string::npos);
    EXPECT_NE(io_error_of([] { (void)read_input_file("/dev/null"); }).find("device"), std::string::npos);
    const auto dir = scratch_dir("input_file_dir");
    EXPECT_NE(io_error_of([&] { (void)read_input_file(dir); }).find("directory"), std::string::npos);
    EXPECT_NE(io_error_of([&] { (void)read_input_file(dir / "missing.txt"); }).find("no such file"),
              std::string::npos);
}

TEST(InputFile, EnforcesTheSizeCap) {
    const auto dir = scratch_dir("input_file_cap");
    write_bytes(dir / "big.txt", std::string(1000, 'x'));
    EXPECT_EQ(read_input_file(dir / "big.txt", 1000).size(), 1000u);
    const std::string msg = io_error_of([&] { (void)read_input_file(dir / "big.txt", 999); });
    EXPECT_NE(msg.find("1000 bytes"), std::string::npos) << msg;
    EXPECT_NE(msg.find("limit"), std::string::npos) << msg;
}

TEST(InputFile, ByteOrderMarkIsSkippedAndLinesStillCount) {
    const auto dir = scratch_dir("input_file_bom");
    const std::string bom = "\xEF\xBB\xBF";
    write_bytes(dir / "m.off", bom + "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_EQ(read_soup(dir / "m.off").triangles.size(), 1u);
    write_bytes(dir / "p.xyz", bom + "0 0 0\n1 0 0\n");
    EXPECT_EQ(read_points_xyz(dir / "p.xyz").size(), 2u);
    write_bytes(dir / "p.node", bom + "2 2 0 0\n1 0 0\n2 1 oops\n");
    EXPECT_NE(io_error_of([&] { (void)read_point_set(dir / "p.node"); }).find("p.node:3:"),
              std::string::npos);
    write_bytes(dir / "q.xy", bom + "0 0\n1 1\n");
    const PointSet ps = read_point_set(dir / "q.xy");
    EXPECT_EQ(ps.points.size(), 2u);
    EXPECT_EQ(ps.lines, (std::vector<std::size_t>{1, 2}));
    write_bytes(dir / "a.ply", bom + "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\n"
                               "property double y\nproperty double z\nelement face 1\n"
                               "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n"
                               "0 1 0\n3 0 1 2\n");
    EXPECT_EQ(read_soup(dir / "a.ply").triangles.size(), 1u);
}

TEST(InputFile, PointSetKeepsTheLineOfEachPoint) {
    const auto dir = scratch_dir("input_file_lines");
    write_bytes(dir / "p.node", "# header next\n3 2 0 0\n1 0 0\n\n# gap\n2 1 0\n3 0 1\n");
    EXPECT_EQ(read_point_set(dir / "p.node").lines, (std::vector<std::size_t>{3, 6, 7}));
}

TEST(HeaderCounts, MoreFacesThanTheOffHeaderPromisesIsAnError) {
    const auto dir = scratch_dir("header_counts_off");
    write_bytes(dir / "extra.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 3\n");
    expect_read_error(dir / "extra.off", {"extra.off:8:", "1 faces announced on line 2"});
    // Trailing comments and blank lines are fine.
    write_bytes(dir / "ok.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n# end\n");
    EXPECT_EQ(read_soup(dir / "ok.off").triangles.size(), 1u);
}

TEST(HeaderCounts, MoreVerticesThanTheOffHeaderPromisesIsNamedAsSuch) {
    const auto dir = scratch_dir("header_counts_off_vertices");
    write_bytes(dir / "v.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n0.5 0.5 1\n3 0 1 2\n");
    expect_read_error(dir / "v.off", {"v.off:6:", "looks like a vertex", "line 2"});
    write_bytes(dir / "w.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n");
    expect_read_error(dir / "w.off", {"w.off:6:", "fewer than the file's vertices"});
}

TEST(HeaderCounts, MoreDataThanThePlyHeaderPromisesIsAnError) {
    const auto dir = scratch_dir("header_counts_ply");
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    write_bytes(dir / "extra.ply", head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n");
    expect_read_error(dir / "extra.ply", {"extra.ply:14:", "more data"});
    write_bytes(dir / "ok.ply", head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n");
    EXPECT_EQ(read_soup(dir / "ok.ply").triangles.size(), 1u);
    // Binary: bytes after the last element.
    std::string bin =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    bin.append(reinterpret_cast<const char*>(v), sizeof v);
    bin.push_back(3);
    const int f[3] = {0, 1, 2};
    bin.append(reinterpret_cast<const char*>(f), sizeof f);
    write_bytes(dir / "ok_bin.ply", bin);
    EXPECT_EQ(read_soup(dir / "ok_bin.ply").triangles.size(), 1u);
    bin.push_back(3);
    bin.append(reinterpret_cast<const char*>(f), sizeof f);
    write_bytes(dir / "extra_bin.ply", bin);
    expect_read_error(dir / "extra_bin.ply", {"byte offset", "after the elements"});
}

}  // namespace
}  // namespace dynmesh::test
