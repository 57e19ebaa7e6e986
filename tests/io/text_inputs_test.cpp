// Vertex lists and update scripts: the checked reader, line numbers, strict syntax.
#include <sys/stat.h>

#include <gtest/gtest.h>

#include "dynmesh/io/text_inputs.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

namespace dynmesh::test {
namespace {

TEST(VertexList, ReadsIndicesAcrossLinesWithComments) {
    const auto dir = scratch_dir("vertex_list_ok");
    write_bytes(dir / "v.txt", "\xEF\xBB\xBF# cap\n3 1 4\n\n1 # again\n5\n");
    EXPECT_EQ(read_vertex_list(dir / "v.txt", 6), (std::vector<std::uint32_t>{3, 1, 4, 1, 5}));
}

TEST(VertexList, NamesTheLineOfABadEntry) {
    const auto dir = scratch_dir("vertex_list_bad");
    write_bytes(dir / "v.txt", "1 2\n3 x\n");
    EXPECT_NE(io_error_of([&] { (void)read_vertex_list(dir / "v.txt", 10); }).find("v.txt:2:"),
              std::string::npos);
    write_bytes(dir / "w.txt", "1\n\n-2\n");
    EXPECT_NE(io_error_of([&] { (void)read_vertex_list(dir / "w.txt", 10); }).find("w.txt:3:"),
              std::string::npos);
    write_bytes(dir / "big.txt", "0\n10\n");
    const std::string msg = io_error_of([&] { (void)read_vertex_list(dir / "big.txt", 10); });
    EXPECT_NE(msg.find("big.txt:2:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("does not exist"), std::string::npos) << msg;
    write_bytes(dir / "empty.txt", "# nothing\n");
    EXPECT_NE(io_error_of([&] { (void)read_vertex_list(dir / "empty.txt", 10); }).find("no vertex"),
              std::string::npos);
}

TEST(VertexList, RefusesAFifo) {
    const auto dir = scratch_dir("vertex_list_fifo");
    ASSERT_EQ(::mkfifo((dir / "v.fifo").c_str(), 0600), 0);
    EXPECT_NE(io_error_of([&] { (void)read_vertex_list(dir / "v.fifo", 10); }).find("FIFO"),
              std::string::npos);
}

TEST(UpdateScript, ReadsInsertsAndErasesWithTheirLines) {
    const auto dir = scratch_dir("update_script_ok");
    write_bytes(dir / "ops.txt", "# script\n+ 0.5 0.25\n\n- 1e-3 -2 # erase\n");
    const auto ops = read_update_script(dir / "ops.txt", 2);
    ASSERT_EQ(ops.size(), 2u);
    EXPECT_TRUE(ops[0].insert);
    EXPECT_EQ(ops[0].point, (Point3{0.5, 0.25, 0}));
    EXPECT_EQ(ops[0].line, 2u);
    EXPECT_FALSE(ops[1].insert);
    EXPECT_EQ(ops[1].point, (Point3{1e-3, -2, 0}));
    EXPECT_EQ(ops[1].line, 4u);
    write_bytes(dir / "empty.txt", "");
    EXPECT_TRUE(read_update_script(dir / "empty.txt", 3).empty());
}

TEST(UpdateScript, StrictSyntaxWithLineNumbers) {
    const auto dir = scratch_dir("update_script_bad");
    const auto error_of = [&](const std::string& text, int dim) {
        write_bytes(dir / "s.txt", text);
        return io_error_of([&] { (void)read_update_script(dir / "s.txt", dim); });
    };
    EXPECT_NE(error_of("+ 1 2\n* 1 2\n", 2).find("s.txt:2:"), std::string::npos);
    EXPECT_NE(error_of("+ 1 2 3\n", 2).find("s.txt:1:"), std::string::npos);
    EXPECT_NE(error_of("+ 1 2\n", 3).find("s.txt:1:"), std::string::npos);
    EXPECT_NE(error_of("\n\n+ 1 y\n", 2).find("s.txt:3: not a number"), std::string::npos);
    EXPECT_NE(error_of("- nan 1\n", 2).find("non-finite"), std::string::npos);
    EXPECT_NE(error_of("+1 2\n", 2).find("s.txt:1:"), std::string::npos);
    EXPECT_THROW((void)read_update_script(dir / "s.txt", 4), InvalidInput);
}

TEST(UpdateScript, RefusesDevicesInsteadOfReadingForever) {
    // `--ops /dev/zero` used to read 2 GB and report zero updates.
    EXPECT_NE(io_error_of([] { (void)read_update_script("/dev/zero", 2); }).find("device"),
              std::string::npos);
}

TEST(FourNumberRows, ReadsRowsWithTheirLinesAndNamesBadOnes) {
    const auto dir = scratch_dir("four_number_rows");
    write_bytes(dir / "ok.txt", "# balls\n0 0 0 1\n\n1.5 -2 3e-1 0.25  # second\n");
    const auto rows = read_four_number_rows(dir / "ok.txt", "x y z r", "ball");
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[1].line, 4u);
    EXPECT_EQ(rows[1].v[2], 0.3);
    EXPECT_EQ(rows[1].v[3], 0.25);
    for (const char* bad : {"0 0 0\n", "0 0 0 1 2\n", "0 0 x 1\n", "0 0 inf 1\n"}) {
        write_bytes(dir / "bad.txt", std::string("1 1 1 1\n") + bad);
        const std::string msg = io_error_of([&] { (void)read_four_number_rows(dir / "bad.txt", "x y z w", "point"); });
        EXPECT_NE(msg.find("bad.txt:2: expected 'x y z w'"), std::string::npos) << msg;
    }
    write_bytes(dir / "none.txt", "# nothing\n\n");
    EXPECT_NE(io_error_of([&] { (void)read_four_number_rows(dir / "none.txt", "x y z r", "ball"); }).find("no ball in the file"),
              std::string::npos);
}

}  // namespace
}  // namespace dynmesh::test
