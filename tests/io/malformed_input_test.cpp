// Readers on small files written by the tests: accepted variants of each format, and
// malformed content that must give a precise one-line IoError (never a crash or a hang).

#include <bit>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

namespace fs = std::filesystem;
using Tri = std::array<std::uint32_t, 3>;

class Malformed : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::scratch_dir(std::string("io_malformed_") +
                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
    }
    /// Writes `content` to a scratch file named `name` and returns its path.
    fs::path file(const std::string& name, const std::string& content) {
        const fs::path p = dir_ / name;
        test::write_bytes(p, content);
        return p;
    }
    void expect_error(const std::string& name, const std::string& content,
                      const std::vector<std::string>& parts) {
        test::expect_read_error(file(name, content), parts);
    }
    fs::path dir_;
};

// ---- OFF ----------------------------------------------------------------------------------

const char* kTriangleOff = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

TEST_F(Malformed, OffVariantsAreAccepted) {
    TriangleSoup s = read_soup(file("a.off", kTriangleOff));
    EXPECT_EQ(s.points.size(), 3u);
    EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 1, 2}}));
    // Counts on the keyword line, comments, CRLF, colours, '+' signs, no edge count.
    s = read_soup(file("b.off",
                       "# comment\r\nCOFF 4 2\r\n\r\n0 0 0 255 0 0 # red\r\n+1 0 0 0 255 0\r\n"
                       "0 1 0 0 0 255\r\n1 1 1e0 1 1 1\r\n3 0 1 2 0.5 0.5 0.5\r\n3 1 3 2"));
    EXPECT_EQ(s.points.size(), 4u);
    EXPECT_EQ(s.points[3], (Point3{1, 1, 1}));
    EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 1, 2}, {1, 3, 2}}));
    // Upper-case extension.
    EXPECT_EQ(read_soup(file("C.OFF", kTriangleOff)).triangles.size(), 1u);
}

TEST_F(Malformed, OffErrors) {
    expect_error("nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n",
                 {"nan.off:4:", "vertex 1 has a non-finite coordinate 'nan'"});
    expect_error("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 -inf\n3 0 1 2\n",
                 {"inf.off:5:", "vertex 2 has a non-finite coordinate '-inf'"});
    expect_error("overflow.off", "OFF\n3 1 0\n0 0 0\n1e999 0 0\n0 1 0\n3 0 1 2\n",
                 {"overflow.off:4:", "vertex 1: invalid coordinate '1e999'"});
    expect_error("word.off", "OFF\n3 1 0\n0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n",
                 {"word.off:4:", "vertex 1: invalid coordinate 'zero'"});
    expect_error("short.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n",
                 {"short.off:4:", "vertex 1: expected 3 coordinates, found 2"});
    expect_error("negative.off", "OFF\n-3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                 {"negative.off:2:", "negative vertex count '-3'"});
    expect_error("negface.off", "OFF\n3 -1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                 {"negface.off:2:", "negative face count '-1'"});
    expect_error("huge.off", "OFF\n3 99999999999999999999 0\n0 0 0\n",
                 {"huge.off:2:", "invalid face count '99999999999999999999'"});
    expect_error("toomany.off", "OFF\n1000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                 {"toomany.off:2:", "1000 vertices", "cannot fit"});
    expect_error("onecount.off", "OFF\n3\n", {"onecount.off:2:", "found only one number"});
    expect_error("nocount.off", "OFF\n# nothing\n", {"nocount.off:", "vertex and face counts"});
    expect_error("keyword.off", "PLY\n3 1 0\n", {"keyword.off:1:", "expected the keyword 'OFF'"});
    expect_error("nd.off", "4OFF\n3 1 0\n", {"nd.off:1:", "only 3D"});
    expect_error("binary.off", "OFF BINARY\n", {"binary.off:1:", "binary OFF"});
    expect_error("comments.off", "# only\n  # comments\n", {"comments.off", "no content"});
    expect_error("noface.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", {"noface.off:2:", "no faces"});
    expect_error("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                 {"range.off:6:", "face 0: vertex index 3 is out of range (the file has 3"});
    expect_error("negindex.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
                 {"negindex.off:6:", "vertex index -1 is out of range"});
    expect_error("repeat.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n",
                 {"repeat.off:6:", "face 0 repeats a vertex (0 1 1)"});
    expect_error("quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
                 {"quad.off:7:", "face 0 has 4 vertices; only triangles are supported"});
    expect_error("edge.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                 {"edge.off:6:", "face 0 has 2 vertices"});
    expect_error("missing.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n",
                 {"missing.off:6:", "face 0: expected 3 vertex indices, found 2"});
    // Counts that fit the size check, but the lines are not there.
    expect_error("truncated.off",
                 "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n" + std::string(40, ' '),
                 {"truncated.off:", "found 1 of the 2 faces announced on line 2"});
    expect_error("ctrl.off", std::string("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1\x01 0\n3 0 1 2\n"),
                 {"ctrl.off:5:", "invalid coordinate '1\\x01'"});
}

// ---- OBJ ----------------------------------------------------------------------------------

TEST_F(Malformed, ObjVariantsAreAccepted) {
    const TriangleSoup s = read_soup(
        file("a.obj",
             "# a square\nmtllib x.mtl\no square\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\n"
             "vt 0 0\nvn 0 0 1\ng g1\nusemtl m\ns off\nf 1/1/1 2/1/1 3/1/1\nv 0 1 0\n"
             "f -4//1 -2//1 -1//1 # comment\nl 1 2\nf 2/1 3/1 4/1\n"));
    EXPECT_EQ(s.points.size(), 4u);
    EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {1, 2, 3}}));
}

TEST_F(Malformed, ObjErrors) {
    const std::string v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    expect_error("quad.obj", v3 + "v 1 1 0\nf 1 2 4 3\n",
                 {"quad.obj:5:", "face 0 has 4 vertices; only triangles are supported"});
    expect_error("zero.obj", v3 + "f 0 1 2\n", {"zero.obj:4:", "invalid vertex reference '0'"});
    expect_error("range.obj", v3 + "f 1 2 4\n",
                 {"range.obj:4:", "face 0: vertex reference '4' is out of range"});
    expect_error("negrange.obj", v3 + "f -1 -2 -4\n", {"negrange.obj:4:", "'-4' is out of range"});
    expect_error("later.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", {"later.obj:3:", "'3'"});
    expect_error("repeat.obj", v3 + "f 1 2 2\n", {"repeat.obj:4:", "face 0 repeats a vertex"});
    expect_error("word.obj", v3 + "f 1 two 3\n", {"word.obj:4:", "invalid vertex reference 'two'"});
    expect_error("slash.obj", v3 + "f 1 /2 3\n", {"slash.obj:4:", "invalid vertex reference '/2'"});
    expect_error("nan.obj", "v 0 0 0\nv NaN 0 0\n",
                 {"nan.obj:2:", "vertex 1 has a non-finite coordinate 'NaN'"});
    expect_error("short.obj", "v 0 0\n", {"short.obj:1:", "vertex 0: expected 3 coordinates"});
    expect_error("nofaces.obj", v3, {"nofaces.obj", "no faces"});
    expect_error("empty.obj", "", {"empty.obj", "empty file"});
    expect_error("line.obj", v3 + "f 1 2\n", {"line.obj:4:", "face 0 has 2 vertices"});
}

// ---- PLY ----------------------------------------------------------------------------------

std::string ascii_ply(const std::string& vertex_header, const std::string& body_vertices,
                      const std::string& face_header, const std::string& body_faces) {
    return "ply\nformat ascii 1.0\ncomment test\n" + vertex_header + face_header + "end_header\n" +
           body_vertices + body_faces;
}

const char* kVertexHeader =
    "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n";
const char* kVertices = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";

TEST_F(Malformed, PlyAsciiVariantsAreAccepted) {
    // Extra properties and elements are skipped; vertex_index is accepted; CRLF endings.
    const std::string text =
        "ply\r\nformat ascii 1.0\r\nobj_info x\r\nelement vertex 4\r\nproperty uchar red\r\n"
        "property double z\r\nproperty float y\r\nproperty list uchar float junk\r\n"
        "property int x\r\nelement material 1\r\nproperty float shine\r\nelement face 2\r\n"
        "property uchar flags\r\nproperty list uchar uint vertex_index\r\n"
        "property float quality\r\nend_header\r\n"
        "7 0 0 2 1.5 2.5 0\r\n7 0 0 0 1\r\n7 0 1 0 1\r\n7 0 1 0 0\r\n0.5\r\n"
        "1 3 0 1 2 0.5\r\n1 3 0 2 3 0.5\r\n";
    const TriangleSoup s = read_soup(file("a.ply", text));
    ASSERT_EQ(s.points.size(), 4u);
    EXPECT_EQ(s.points[1], (Point3{1, 0, 0}));
    EXPECT_EQ(s.points[2], (Point3{1, 1, 0}));
    EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}}));
}

TEST_F(Malformed, PlyTristripsAlternateOrientationAndSkipDegenerates) {
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
        "property float z\nelement tristrips 1\nproperty list int int vertex_indices\n"
        "end_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 2 0\n1 2 0\n";
    TriangleSoup s = read_soup(file("strip.ply", head + "9 0 1 2 3 4 -1 3 4 5\n"));
    EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 1, 2}, {2, 1, 3}, {2, 3, 4}, {3, 4, 5}}));
    // A repeated index (used to restart strips) gives degenerate triangles, which are
    // skipped while the alternation continues.
    s = read_soup(file("degenerate.ply", head + "6 0 1 2 2 3 4\n"));
    EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 1, 2}, {3, 2, 4}}));
    expect_error("striprange.ply", head + "4 0 1 2 6\n",
                 {"striprange.ply:16:", "tristrips 0: vertex index 6 is out of range"});
    expect_error("stripneg.ply", head + "4 0 1 2 -2\n", {"stripneg.ply:16:", "vertex index -2"});
    expect_error("stripempty.ply", head + "3 0 1 -1\n", {"stripempty.ply", "no triangle"});
}

TEST_F(Malformed, PlyAsciiErrors) {
    const std::string face = "element face 1\nproperty list uchar int vertex_indices\n";
    expect_error("nan.ply",
                 ascii_ply(kVertexHeader, "0 0 0\n1 nan 0\n1 1 0\n0 1 0\n", face, "3 0 1 2\n"),
                 {"nan.ply:12:", "vertex 1 has a non-finite coordinate 'nan'"});
    expect_error("quad.ply", ascii_ply(kVertexHeader, kVertices, face, "4 0 1 2 3\n"),
                 {"quad.ply:15:", "face 0 has 4 vertices; only triangles are supported"});
    expect_error("range.ply", ascii_ply(kVertexHeader, kVertices, face, "3 0 1 4\n"),
                 {"range.ply:15:", "face 0: vertex index 4 is out of range (the file has 4"});
    expect_error("repeat.ply", ascii_ply(kVertexHeader, kVertices, face, "3 0 1 0\n"),
                 {"repeat.ply:15:", "face 0 repeats a vertex"});
    expect_error("word.ply", ascii_ply(kVertexHeader, kVertices, face, "3 0 one 2\n"),
                 {"word.ply:15:", "face 0: invalid integer 'one'"});
    expect_error("truncated.ply", ascii_ply(kVertexHeader, kVertices, face, "3 0 1\n"),
                 {"truncated.ply:", "face 0: unexpected end of file"});
    expect_error("negcount.ply",
                 ascii_ply("element vertex -4\nproperty float x\n", kVertices, face, ""),
                 {"negcount.ply:4:", "element 'vertex' has an invalid count '-4'"});
    expect_error("hugecount.ply",
                 ascii_ply("element vertex 4000000000000\nproperty float x\nproperty float y\n"
                           "property float z\n",
                           kVertices, face, "3 0 1 2\n"),
                 {"hugecount.ply:4:", "4000000000000 items", "cannot fit"});
    expect_error("nox.ply",
                 ascii_ply("element vertex 4\nproperty float y\nproperty float z\n", kVertices,
                           face, "3 0 1 2\n"),
                 {"nox.ply:4:", "no scalar property 'x'"});
    expect_error("noface.ply", ascii_ply(kVertexHeader, kVertices, "", ""),
                 {"noface.ply", "neither a 'face' nor a 'tristrips'"});
    expect_error(
        "nolist.ply",
        ascii_ply(kVertexHeader, kVertices, "element face 1\nproperty int vertex_indices\n", "3\n"),
        {"nolist.ply:8:", "no list property 'vertex_indices'"});
    expect_error(
        "floatidx.ply",
        ascii_ply(kVertexHeader, kVertices,
                  "element face 1\nproperty list uchar float vertex_indices\n", "3 0 1 2\n"),
        {"floatidx.ply:8:", "must have an integer type"});
    expect_error("badtype.ply",
                 ascii_ply("element vertex 4\nproperty float32 x\nproperty real y\n", "", "", ""),
                 {"badtype.ply:6:", "unknown PLY type 'real'"});
    expect_error("noend.ply", "ply\nformat ascii 1.0\nelement vertex 0\n", {"no 'end_header'"});
    expect_error("noformat.ply", "ply\nelement vertex 0\nend_header\n", {"no 'format' line"});
    expect_error("format.ply", "ply\nformat binary 1.0\nend_header\n",
                 {"format.ply:2:", "unknown PLY format 'binary'"});
    expect_error("magic.ply", "plx\nformat ascii 1.0\nend_header\n", {"magic.ply:1:", "'ply'"});
    expect_error("keyword.ply", "ply\nformat ascii 1.0\nelemental x 1\nend_header\n",
                 {"keyword.ply:3:", "unexpected 'elemental'"});
    expect_error("twice.ply", "ply\nformat ascii 1.0\nelement vertex 1\nelement vertex 1\n",
                 {"twice.ply:4:", "declared twice"});
    expect_error("orphan.ply", "ply\nformat ascii 1.0\nproperty float x\n",
                 {"orphan.ply:3:", "'property' before any 'element'"});
    expect_error("noprops.ply", "ply\nformat ascii 1.0\nelement foo 1000000\nend_header\n",
                 {"noprops.ply:3:", "element 'foo' has no properties"});
}

/// Bytes of `v` in the given byte order.
template <class T>
std::string bytes_of(T v, bool big_endian) {
    std::string s(sizeof(T), '\0');
    std::memcpy(s.data(), &v, sizeof(T));
    if (big_endian != (std::endian::native == std::endian::big)) std::reverse(s.begin(), s.end());
    return s;
}

/// A binary PLY of a tetrahedron; `nan_vertex` gets a NaN y if set.
std::string binary_tetra(bool big_endian, int nan_vertex = -1, std::uint8_t first_count = 3) {
    std::string s = std::string("ply\nformat ") +
                    (big_endian ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
    const float pts[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c)
            s += bytes_of(i == nan_vertex && c == 1 ? std::nanf("") : pts[i][c], big_endian);
    const std::int32_t tris[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (int t = 0; t < 4; ++t) {
        s += static_cast<char>(t == 0 ? first_count : 3);
        for (int c = 0; c < 3; ++c) s += bytes_of(tris[t][c], big_endian);
        if (t == 0 && first_count == 4) s += bytes_of(std::int32_t{3}, big_endian);
    }
    return s;
}

TEST_F(Malformed, PlyBinaryBothEndians) {
    const TriangleSoup le = read_soup(file("le.ply", binary_tetra(false)));
    const TriangleSoup be = read_soup(file("be.ply", binary_tetra(true)));
    EXPECT_EQ(le.points, be.points);
    EXPECT_EQ(le.triangles, be.triangles);
    EXPECT_EQ(le.points[3], (Point3{0, 0, 1}));
    EXPECT_EQ(le.triangles, (std::vector<Tri>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}));
    EXPECT_NO_THROW((void)read_mesh(dir_ / "be.ply"));
}

TEST_F(Malformed, PlyBinaryErrors) {
    const std::string good = binary_tetra(false);
    const std::size_t body = good.find("end_header\n") + 11;
    // Offsets point at the offending value: vertex 2's y, the first face's count.
    expect_error("nan.ply", binary_tetra(false, 2),
                 {"nan.ply: byte offset " + std::to_string(body + 2 * 12 + 4) +
                  ", vertex 2 has a non-finite coordinate"});
    const std::string quad = binary_tetra(true, -1, 4);
    expect_error(
        "bequad.ply", quad,
        {"bequad.ply: byte offset " + std::to_string(quad.find("end_header\n") + 11 + 4 * 12) +
         ", face 0 has 4 vertices; only triangles"});
    std::string bad_index = good;
    bad_index[body + 4 * 12 + 1 + 13 + 4] = 9;  // face 1, second index (little endian)
    expect_error("index.ply", bad_index,
                 {"index.ply: byte offset " + std::to_string(body + 4 * 12 + 13 + 5) +
                  ", face 1: vertex index 9 is out of range (the file has 4 vertices)"});
    // Every truncation inside the body is reported with a byte offset, never a crash.
    for (std::size_t n = body; n < good.size(); ++n) {
        const std::string msg =
            test::io_error_of([&] { (void)read_soup(file("cut.ply", good.substr(0, n))); });
        EXPECT_NE(msg.find("cut.ply"), std::string::npos) << msg;
        EXPECT_TRUE(msg.find("byte offset") != std::string::npos ||
                    msg.find("cannot fit") != std::string::npos)
            << n << ": " << msg;
    }
    // Our own writer's output, truncated anywhere, too.
    write_mesh(test::icosphere(1), dir_ / "ico.ply");
    const std::string ico = test::read_bytes(dir_ / "ico.ply");
    for (std::size_t n = 0; n < ico.size(); n += 7)
        (void)test::io_error_of([&] { (void)read_soup(file("cut.ply", ico.substr(0, n))); });
    // A list length that cannot fit in the rest of the file.
    std::string big = good;
    big[body + 48] = static_cast<char>(255);  // first face's count (after 4 * 12 bytes)
    expect_error("biglist.ply", big, {"biglist.ply: byte offset", "face 0 has 255 vertices"});
}

// ---- STL ----------------------------------------------------------------------------------

std::string binary_stl(const std::vector<std::array<Point3, 3>>& tris,
                       const std::string& header_text = "binary") {
    std::string s = header_text;
    s.resize(80, ' ');
    s += bytes_of(static_cast<std::uint32_t>(tris.size()), false);
    for (const auto& t : tris) {
        for (int c = 0; c < 3; ++c) s += bytes_of(0.0f, false);  // normal
        for (const Point3& p : t)
            for (std::size_t c = 0; c < 3; ++c) s += bytes_of(static_cast<float>(p[c]), false);
        s += std::string(2, '\0');
    }
    return s;
}

TEST_F(Malformed, StlBinaryWeldsAndChecks) {
    // Two triangles sharing an edge; -0 and +0 weld.
    const std::vector<std::array<Point3, 3>> square = {{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}},
                                                       {{{-0.0, 0, 0}, {1, 1, 0}, {0, 1, -0.0}}}};
    TriangleSoup s = read_soup(file("square.stl", binary_stl(square)));
    EXPECT_EQ(s.points.size(), 4u);
    EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}}));
    // Many binary files start with "solid": the size decides.
    s = read_soup(file("solid.stl", binary_stl(square, "solid but binary")));
    EXPECT_EQ(s.triangles.size(), 2u);

    auto bad = square;
    bad[1][2].z = std::numeric_limits<double>::infinity();
    expect_error("inf.stl", binary_stl(bad),
                 {"inf.stl: byte offset 170,", "triangle 1 corner 2 has a non-finite"});
    bad = square;
    bad[1][2] = bad[1][1];
    expect_error("degenerate.stl", binary_stl(bad),
                 {"degenerate.stl: byte offset 134,", "facet 1 is degenerate"});
    std::string cut = binary_stl(square);
    cut.pop_back();
    expect_error("cut.stl", cut, {"cut.stl: byte offset 80,", "announces 2 triangles"});
    expect_error("none.stl", binary_stl({}), {"none.stl: byte offset 80,", "no triangles"});
    expect_error("tiny.stl", "abc", {"tiny.stl", "neither an ascii STL"});
}

TEST_F(Malformed, StlAsciiErrors) {
    const std::string facet =
        "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
        "endfacet\n";
    TriangleSoup s = read_soup(
        file("ok.stl", "SOLID x\n" + facet + "endsolid\nsolid y\n" + facet + "endsolid y\n"));
    EXPECT_EQ(s.points.size(), 3u);  // the second solid's corners weld onto the first
    EXPECT_EQ(s.triangles.size(), 2u);
    expect_error("nan.stl", "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\n",
                 {"nan.stl:5:", "facet 0 has a non-finite coordinate 'nan'"});
    expect_error("extra.stl", "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0 1\n",
                 {"extra.stl:4:", "unexpected '1' after the 3 coordinates"});
    expect_error("two.stl",
                 "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
                 {"two.stl:6:", "facet 0 has 2 vertices"});
    expect_error("eof.stl", "solid\n" + facet.substr(0, facet.find("endloop")),
                 {"eof.stl:", "unexpected end of file inside facet 0 (started on line 2)"});
    expect_error("keyword.stl", "solid\nfacet normal 0 0 1\nloop\n",
                 {"keyword.stl:3:", "expected 'outer loop', found 'loop'"});
    expect_error("degenerate.stl",
                 "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                 "vertex 1 0 0\nendloop\nendfacet\nendsolid\n",
                 {"degenerate.stl:2:", "facet 0 is degenerate"});
}

// ---- dispatch and file system -------------------------------------------------------------

TEST_F(Malformed, FileSystemErrors) {
    test::expect_read_error(dir_ / "missing.off", {"no such file"});
    fs::create_directory(dir_ / "dir.off");
    test::expect_read_error(dir_ / "dir.off", {"is a directory"});
    test::expect_read_error(file("mesh.xyz", "0 0 0\n"),
                            {"unsupported extension '.xyz'", ".off, .obj, .ply, .stl"});
    test::expect_read_error(file("noext", kTriangleOff), {"unsupported extension ''"});
    // A device never ends: it must be refused, not read.
    std::error_code ec;
    fs::create_symlink("/dev/zero", dir_ / "zero.off", ec);
    if (!ec) test::expect_read_error(dir_ / "zero.off", {"not a regular file"});
}

// ---- robustness ---------------------------------------------------------------------------

TEST_F(Malformed, RandomCorruptionNeverCrashes) {
    const SurfaceMesh mesh = test::icosphere(1);
    std::vector<std::pair<std::string, std::string>> originals;
    for (const char* name : {"m.off", "m.obj", "m.ply"}) {
        write_mesh(mesh, dir_ / name);
        originals.emplace_back(name, test::read_bytes(dir_ / name));
    }
    write_mesh(mesh, dir_ / "a.ply", {.ply_encoding = PlyEncoding::Ascii});
    originals.emplace_back("a.ply", test::read_bytes(dir_ / "a.ply"));
    std::vector<std::array<Point3, 3>> tris;
    const TriangleSoup soup = mesh.to_soup();
    for (const auto& t : soup.triangles)
        tris.push_back({soup.points[t[0]], soup.points[t[1]], soup.points[t[2]]});
    originals.emplace_back("b.stl", binary_stl(tris));

    Rng rng(42);
    const char replacements[] = {'\0', '\n', ' ', '-', '9', '#', '/', 'e', '\xff', '.'};
    std::size_t failures = 0, successes = 0;
    for (const auto& [name, original] : originals) {
        for (int trial = 0; trial < 150; ++trial) {
            std::string data = original;
            const auto edits = 1 + rng.below(4);
            for (std::uint64_t e = 0; e < edits; ++e) {
                const std::size_t at = rng.below(data.size());
                data[at] = rng.coin() ? replacements[rng.below(sizeof(replacements))]
                                      : static_cast<char>(rng.below(256));
            }
            if (rng.coin(0.3)) data.resize(rng.below(data.size() + 1));
            const fs::path p = file("fuzz_" + name, data);
            try {
                (void)read_soup(p);
                ++successes;
            } catch (const IoError& e) {
                const std::string msg = e.what();
                EXPECT_NE(msg.find("fuzz_" + name), std::string::npos) << msg;
                EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
                ++failures;
            }
        }
    }
    EXPECT_GT(failures, 0u);
    EXPECT_GT(successes, 0u);
}

}  // namespace
}  // namespace dynmesh
