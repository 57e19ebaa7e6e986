// Writers: round trips through every readable format, VTK/VTP/PVD structure, atomic writes.

#include "dynmesh/io/mesh_io.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/mesh/check.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

namespace fs = std::filesystem;

/// An icosphere whose coordinates are awkward decimals: random scales, a subnormal, huge and
/// tiny magnitudes, a negative zero.
SurfaceMesh awkward_mesh() {
    SurfaceMesh m = test::icosphere(2);
    Rng rng(7);
    for (Vertex v : m.vertices()) m.position(v) *= rng.uniform(0.5, 2.0);
    m.position(Vertex(0)) = {5e-324, -1.2345678901234567e300, 0.1};
    m.position(Vertex(1)) *= 1e-12;
    m.position(Vertex(2)).y = -0.0;
    return m;
}

void expect_identical(const TriangleSoup& expected, const TriangleSoup& actual,
                      const std::string& what) {
    SCOPED_TRACE(what);
    ASSERT_EQ(expected.points.size(), actual.points.size());
    ASSERT_EQ(expected.triangles.size(), actual.triangles.size());
    for (std::size_t i = 0; i < expected.points.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c)
            ASSERT_EQ(std::bit_cast<std::uint64_t>(expected.points[i][c]),
                      std::bit_cast<std::uint64_t>(actual.points[i][c]))
                << "vertex " << i << " coordinate " << c << ": " << expected.points[i][c] << " vs "
                << actual.points[i][c];
    EXPECT_EQ(expected.triangles, actual.triangles);
}

struct Case {
    std::string file;
    PlyEncoding ply = PlyEncoding::BinaryLittleEndian;
};
const std::vector<Case> kReadableCases = {
    {"m.off"}, {"m.obj"}, {"m.ply"}, {"m_ascii.ply", PlyEncoding::Ascii}, {"M.OFF"}};

TEST(MeshIo, RoundTripIsBitExact) {
    const fs::path dir = test::scratch_dir("io_round_trip");
    const SurfaceMesh mesh = awkward_mesh();
    const TriangleSoup expected = mesh.to_soup();
    for (const Case& c : kReadableCases) {
        const fs::path path = dir / c.file;
        write_mesh(mesh, path, {.ply_encoding = c.ply});
        expect_identical(expected, read_soup(path), c.file);
        const SurfaceMesh back = read_mesh(path);
        EXPECT_TRUE(check_mesh(back, {.require_closed = true, .check_degenerate = false}).ok())
            << c.file;
    }
    // Nothing but the outputs is left in the directory (no temporary files).
    EXPECT_EQ(test::listing(dir).size(), kReadableCases.size());
}

TEST(MeshIo, WritesOnlyLiveElements) {
    const fs::path dir = test::scratch_dir("io_garbage");
    SurfaceMesh mesh = test::icosphere(1);
    std::size_t collapses = 0;
    for (Edge e : mesh.edges()) {
        if (collapses == 3) break;
        if (mesh.is_deleted(e)) continue;
        const Halfedge h = SurfaceMesh::halfedge(e, 0);
        if (mesh.is_collapse_ok(h)) {
            mesh.collapse(h);
            ++collapses;
        }
    }
    ASSERT_EQ(collapses, 3u);
    ASSERT_TRUE(mesh.has_garbage());
    const TriangleSoup expected = mesh.to_soup();
    ASSERT_EQ(expected.points.size(), mesh.n_vertices());
    WriteOptions opt;
    opt.vertex_fields.push_back({"index", std::vector<double>(mesh.n_vertices(), 1.5)});
    opt.face_fields.push_back({"area", std::vector<double>(mesh.n_faces(), 2.5)});
    for (const Case& c : kReadableCases) {
        opt.ply_encoding = c.ply;
        write_mesh(mesh, dir / c.file, opt);
        expect_identical(expected, read_soup(dir / c.file), c.file);
    }
    // Fields sized to the array bounds (including deleted elements) are rejected.
    opt.vertex_fields[0].values.resize(mesh.vertices_size());
    EXPECT_THROW(write_mesh(mesh, dir / "bad.vtk", opt), InvalidInput);
    EXPECT_FALSE(fs::exists(dir / "bad.vtk"));
}

TEST(MeshIo, PlyCarriesFieldsAndReaderSkipsThem) {
    const fs::path dir = test::scratch_dir("io_ply_fields");
    const SurfaceMesh mesh = test::octahedron();
    WriteOptions opt;
    opt.vertex_fields.push_back({"height", {0, 1, 2, 3, 4, 5}});
    opt.vertex_fields.push_back({"quality", {0.5, 0.5, 0.5, 0.5, 0.5, 0.25}});
    opt.face_fields.push_back({"label", {1, 2, 3, 4, 5, 6, 7, 8}});
    for (PlyEncoding enc : {PlyEncoding::BinaryLittleEndian, PlyEncoding::Ascii}) {
        opt.ply_encoding = enc;
        write_mesh(mesh, dir / "f.ply", opt);
        const std::string text = test::read_bytes(dir / "f.ply");
        const std::string header = text.substr(0, text.find("end_header"));
        EXPECT_NE(header.find("property float height\nproperty float quality\nelement face"),
                  std::string::npos)
            << header;
        EXPECT_NE(header.find("vertex_indices\nproperty float label\n"), std::string::npos)
            << header;
        expect_identical(mesh.to_soup(), read_soup(dir / "f.ply"), "ply with fields");
    }
    // A value beyond float range cannot go into a PLY float, but is fine for VTK (double).
    opt.vertex_fields[0].values[0] = 1e300;
    EXPECT_THROW(write_mesh(mesh, dir / "g.ply", opt), InvalidInput);
    EXPECT_NO_THROW(write_mesh(mesh, dir / "g.vtk", opt));
}

// ---- VTK legacy -----------------------------------------------------------------------------

double to_double(const std::string& token) {
    double v = 0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    EXPECT_TRUE(ec == std::errc() && ptr == token.data() + token.size()) << token;
    return v;
}

struct VtkData {
    std::vector<Point3> points;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::map<std::string, std::vector<double>> point_data, cell_data;
};

/// A strict reader for the subset of legacy VTK that write_mesh produces.
VtkData parse_vtk(const std::string& text) {
    VtkData d;
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "# vtk DataFile Version 3.0");
    std::getline(in, line);  // title
    std::getline(in, line);
    EXPECT_EQ(line, "ASCII");
    std::getline(in, line);
    EXPECT_EQ(line, "DATASET POLYDATA");
    std::string word, type;
    std::size_t n = 0, size = 0;
    in >> word >> n >> type;
    EXPECT_EQ(word, "POINTS");
    EXPECT_EQ(type, "double");
    d.points.resize(n);
    for (auto& p : d.points)
        for (std::size_t c = 0; c < 3; ++c) {
            in >> word;
            p[c] = to_double(word);
        }
    in >> word >> n >> size;
    EXPECT_EQ(word, "POLYGONS");
    EXPECT_EQ(size, 4 * n);
    d.triangles.resize(n);
    for (auto& t : d.triangles) {
        std::size_t k = 0;
        in >> k >> t[0] >> t[1] >> t[2];
        EXPECT_EQ(k, 3u);
    }
    std::map<std::string, std::vector<double>>* section = nullptr;
    std::size_t section_size = 0;
    while (in >> word) {
        if (word == "POINT_DATA" || word == "CELL_DATA") {
            section = word == "POINT_DATA" ? &d.point_data : &d.cell_data;
            in >> section_size;
            EXPECT_EQ(section_size, word == "POINT_DATA" ? d.points.size() : d.triangles.size());
            continue;
        }
        EXPECT_EQ(word, "SCALARS");
        std::string name, lookup, table_name;
        std::size_t components = 0;
        in >> name >> type >> components >> lookup >> table_name;
        EXPECT_EQ(type, "double");
        EXPECT_EQ(components, 1u);
        EXPECT_EQ(lookup, "LOOKUP_TABLE");
        if (section == nullptr) {
            ADD_FAILURE() << "SCALARS outside POINT_DATA/CELL_DATA";
            break;
        }
        auto& values = (*section)[name];
        for (std::size_t i = 0; i < section_size && in >> word; ++i)
            values.push_back(to_double(word));
    }
    return d;
}

WriteOptions fields_for(const SurfaceMesh& mesh) {
    WriteOptions opt;
    std::vector<double> heights, ids;
    for (Vertex v : mesh.vertices()) heights.push_back(mesh.position(v).z);
    for (std::size_t i = 0; i < mesh.n_faces(); ++i) ids.push_back(static_cast<double>(i) / 3);
    opt.vertex_fields.push_back({"height", heights});
    opt.vertex_fields.push_back({"minus-height", {}});
    for (double h : heights) opt.vertex_fields.back().values.push_back(-h);
    opt.face_fields.push_back({"face.id", ids});
    return opt;
}

TEST(MeshIo, VtkLegacyIsWellFormed) {
    const fs::path dir = test::scratch_dir("io_vtk");
    const SurfaceMesh mesh = awkward_mesh();
    const WriteOptions opt = fields_for(mesh);
    write_mesh(mesh, dir / "m.vtk", opt);
    const VtkData d = parse_vtk(test::read_bytes(dir / "m.vtk"));
    const TriangleSoup expected = mesh.to_soup();
    expect_identical(expected, TriangleSoup{d.points, d.triangles}, "vtk");
    ASSERT_EQ(d.point_data.size(), 2u);
    EXPECT_EQ(d.point_data.at("height"), opt.vertex_fields[0].values);
    EXPECT_EQ(d.point_data.at("minus-height"), opt.vertex_fields[1].values);
    ASSERT_EQ(d.cell_data.size(), 1u);
    EXPECT_EQ(d.cell_data.at("face.id"), opt.face_fields[0].values);

    // Without fields there are no data sections.
    write_mesh(mesh, dir / "plain.vtk");
    const VtkData plain = parse_vtk(test::read_bytes(dir / "plain.vtk"));
    EXPECT_TRUE(plain.point_data.empty());
    EXPECT_TRUE(plain.cell_data.empty());
    EXPECT_EQ(plain.triangles.size(), mesh.n_faces());
}

// ---- VTK XML PolyData -------------------------------------------------------------------------

std::string attribute(const std::string& tag, const std::string& name) {
    const std::string key = " " + name + "=\"";
    const auto at = tag.find(key);
    if (at == std::string::npos) return {};
    const auto start = at + key.size();
    return tag.substr(start, tag.find('"', start) - start);
}

struct XmlArray {
    std::string open_tag;
    std::vector<std::string> values;
};

/// Every <DataArray ...>values</DataArray> of `xml`, in order.
std::vector<XmlArray> data_arrays(const std::string& xml) {
    std::vector<XmlArray> arrays;
    std::size_t pos = 0;
    while ((pos = xml.find("<DataArray", pos)) != std::string::npos) {
        const auto tag_end = xml.find('>', pos);
        const auto close = xml.find("</DataArray>", tag_end);
        if (tag_end == std::string::npos || close == std::string::npos) {
            ADD_FAILURE() << "unterminated DataArray";
            break;
        }
        XmlArray a{xml.substr(pos, tag_end + 1 - pos), {}};
        std::istringstream body(xml.substr(tag_end + 1, close - tag_end - 1));
        std::string token;
        while (body >> token) a.values.push_back(token);
        arrays.push_back(std::move(a));
        pos = close;
    }
    return arrays;
}

std::size_t occurrences(const std::string& s, const std::string& what) {
    std::size_t n = 0;
    for (auto pos = s.find(what); pos != std::string::npos; pos = s.find(what, pos + 1)) ++n;
    return n;
}

TEST(MeshIo, VtpIsWellFormed) {
    const fs::path dir = test::scratch_dir("io_vtp");
    const SurfaceMesh mesh = awkward_mesh();
    const WriteOptions opt = fields_for(mesh);
    write_mesh(mesh, dir / "m.vtp", opt);
    const std::string xml = test::read_bytes(dir / "m.vtp");
    const std::size_t nv = mesh.n_vertices(), nf = mesh.n_faces();

    EXPECT_EQ(xml.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\"", 0), 0u);
    for (const char* tag :
         {"VTKFile", "PolyData", "Piece", "PointData", "CellData", "Points", "Polys", "DataArray"})
        EXPECT_EQ(occurrences(xml, std::string("<") + tag + " ") +
                      occurrences(xml, std::string("<") + tag + ">"),
                  occurrences(xml, std::string("</") + tag + ">"))
            << tag;
    const auto piece_at = xml.find("<Piece");
    const std::string piece = xml.substr(piece_at, xml.find('>', piece_at) - piece_at);
    EXPECT_EQ(attribute(piece, "NumberOfPoints"), std::to_string(nv));
    EXPECT_EQ(attribute(piece, "NumberOfPolys"), std::to_string(nf));

    std::map<std::string, XmlArray> by_name;
    for (auto& a : data_arrays(xml)) by_name[attribute(a.open_tag, "Name")] = a;
    ASSERT_EQ(by_name.size(), 6u);  // height, minus-height, face.id, Points, connectivity, offsets
    EXPECT_EQ(by_name["height"].values.size(), nv);
    EXPECT_EQ(by_name["minus-height"].values.size(), nv);
    EXPECT_EQ(by_name["face.id"].values.size(), nf);
    EXPECT_EQ(attribute(by_name["Points"].open_tag, "NumberOfComponents"), "3");
    ASSERT_EQ(by_name["Points"].values.size(), 3 * nv);
    ASSERT_EQ(by_name["connectivity"].values.size(), 3 * nf);
    ASSERT_EQ(by_name["offsets"].values.size(), nf);
    EXPECT_EQ(by_name["offsets"].values.back(), std::to_string(3 * nf));
    // PointData must sit before Points inside the Piece, CellData before Polys? VTK accepts
    // any order; check only that the fields are in the right sections.
    EXPECT_LT(xml.find("<PointData"), xml.find("Name=\"height\""));
    EXPECT_LT(xml.find("Name=\"height\""), xml.find("</PointData>"));
    EXPECT_LT(xml.find("<CellData"), xml.find("Name=\"face.id\""));
    EXPECT_LT(xml.find("Name=\"face.id\""), xml.find("</CellData>"));

    const TriangleSoup expected = mesh.to_soup();
    TriangleSoup back;
    for (std::size_t i = 0; i < nv; ++i)
        back.points.push_back({to_double(by_name["Points"].values[3 * i]),
                               to_double(by_name["Points"].values[3 * i + 1]),
                               to_double(by_name["Points"].values[3 * i + 2])});
    for (std::size_t i = 0; i < nf; ++i) {
        std::array<std::uint32_t, 3> t{};
        for (std::size_t c = 0; c < 3; ++c)
            t[c] =
                static_cast<std::uint32_t>(std::stoul(by_name["connectivity"].values[3 * i + c]));
        back.triangles.push_back(t);
    }
    expect_identical(expected, back, "vtp");
}

TEST(MeshIo, PvdListsTheSeries) {
    const fs::path dir = test::scratch_dir("io_pvd");
    write_pvd(dir / "series.pvd", {{0.0, "frame_0000.vtp"}, {0.25, "frames/a&b <1>.vtp"}});
    const std::string xml = test::read_bytes(dir / "series.pvd");
    EXPECT_NE(xml.find("<VTKFile type=\"Collection\""), std::string::npos) << xml;
    EXPECT_EQ(occurrences(xml, "<DataSet "), 2u);
    EXPECT_NE(xml.find("timestep=\"0\" group=\"\" part=\"0\" file=\"frame_0000.vtp\"/>"),
              std::string::npos)
        << xml;
    EXPECT_NE(xml.find("timestep=\"0.25\""), std::string::npos) << xml;
    EXPECT_NE(xml.find("file=\"frames/a&amp;b &lt;1&gt;.vtp\""), std::string::npos) << xml;
    EXPECT_NE(xml.find("</Collection>\n</VTKFile>"), std::string::npos) << xml;
    EXPECT_THROW(write_pvd(dir / "bad.pvd", {{std::nan(""), "a.vtp"}}), InvalidInput);
    EXPECT_THROW(write_pvd(dir / "bad.pvd", {{1.0, ""}}), InvalidInput);
    EXPECT_FALSE(fs::exists(dir / "bad.pvd"));
}

TEST(MeshIo, StlIsBinaryAndReadsBackAsTheSameOrientedMesh) {
    const fs::path dir = test::scratch_dir("io_stl");
    SurfaceMesh mesh = test::octahedron();
    for (Vertex v : mesh.vertices()) mesh.position(v) = 0.5 * mesh.position(v) + Vec3{1, 2, 3};  // float-exact
    write_mesh(mesh, dir / "m.stl");
    EXPECT_EQ(fs::file_size(dir / "m.stl"), 84u + 50u * mesh.n_faces());  // binary STL
    const SurfaceMesh back = read_mesh(dir / "m.stl");
    ASSERT_EQ(back.n_vertices(), mesh.n_vertices());
    ASSERT_EQ(back.n_faces(), mesh.n_faces());
    // Each face of the input is a face of the output with the same orientation.
    const auto faces = [](const SurfaceMesh& m) {
        std::set<std::array<std::array<double, 3>, 3>> out;
        for (Face f : m.faces()) {
            std::array<std::array<double, 3>, 3> t{};
            std::size_t k = 0;
            for (Vertex v : m.face_vertices(f)) t[k++] = {m.position(v).x, m.position(v).y, m.position(v).z};
            std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
            out.insert(t);
        }
        return out;
    };
    EXPECT_EQ(faces(back), faces(mesh));
    // Each record's normal is its triangle's outward unit normal, as float32.
    std::ifstream in(dir / "m.stl", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto float_at = [&](std::size_t offset) {
        std::array<char, 4> b{};
        std::copy_n(bytes.begin() + std::ptrdiff_t(offset), 4, b.begin());
        return double(std::bit_cast<float>(b));
    };
    std::size_t k = 0;
    for (Face f : mesh.faces()) {
        const auto v = mesh.face_vertices(f);
        const Vec3 n = cross(mesh.position(v[1]) - mesh.position(v[0]), mesh.position(v[2]) - mesh.position(v[0]));
        const Vec3 expected = n / norm(n);
        const std::size_t at = 84 + 50 * k++;
        EXPECT_NEAR(float_at(at), expected.x, 1e-7);
        EXPECT_NEAR(float_at(at + 4), expected.y, 1e-7);
        EXPECT_NEAR(float_at(at + 8), expected.z, 1e-7);
        EXPECT_GT(dot(expected, mesh.position(v[0]) - Vec3{1, 2, 3}), 0.0);  // outward
    }
}

TEST(MeshIo, StlRefusesCoordinatesBeyondFloat) {
    const fs::path dir = test::scratch_dir("io_stl_range");
    SurfaceMesh mesh = test::octahedron();
    mesh.position(Vertex(4)).y = 1e39;  // finite as a double, infinite as a float
    try {
        write_mesh(mesh, dir / "m.stl");
        ADD_FAILURE() << "a coordinate beyond float was written to STL";
    } catch (const InvalidInput& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("vertex 4 has a coordinate beyond the float range STL stores"), std::string::npos) << msg;
    }
    EXPECT_TRUE(test::listing(dir).empty());
    mesh.position(Vertex(4)).y = -3.0e38;  // within float range: written
    write_mesh(mesh, dir / "m.stl");
    EXPECT_EQ(read_mesh(dir / "m.stl").n_faces(), mesh.n_faces());
}

// ---- validation and atomicity -------------------------------------------------------------

TEST(MeshIo, RejectsBadWriteRequests) {
    const fs::path dir = test::scratch_dir("io_bad_requests");
    const SurfaceMesh mesh = test::octahedron();
    const std::string msg = test::io_error_of([&] { write_mesh(mesh, dir / "m.xyz"); });
    EXPECT_NE(msg.find("m.xyz"), std::string::npos) << msg;
    EXPECT_NE(msg.find(".off, .obj, .ply, .stl, .vtk, .vtp"), std::string::npos) << msg;
    WriteOptions lines;
    lines.polylines = {{0, 1}};
    EXPECT_THROW(write_mesh(mesh, dir / "m.stl", lines), InvalidInput);
    EXPECT_FALSE(fs::exists(dir / "m.stl"));

    const auto with_vertex_field = [&](ScalarField f) {
        WriteOptions opt;
        opt.vertex_fields.push_back(std::move(f));
        return opt;
    };
    const std::vector<double> six(6, 1.0);
    EXPECT_THROW(write_mesh(mesh, dir / "m.vtk", with_vertex_field({"short", {1.0}})),
                 InvalidInput);
    EXPECT_THROW(write_mesh(mesh, dir / "m.vtk", with_vertex_field({"has space", six})),
                 InvalidInput);
    EXPECT_THROW(write_mesh(mesh, dir / "m.vtk", with_vertex_field({"", six})), InvalidInput);
    EXPECT_THROW(write_mesh(mesh, dir / "m.ply", with_vertex_field({"x", six})), InvalidInput);
    EXPECT_THROW(write_mesh(mesh, dir / "m.vtp", with_vertex_field({"q\"<", six})), InvalidInput);
    std::vector<double> nan_values = six;
    nan_values[4] = std::nan("");
    EXPECT_THROW(write_mesh(mesh, dir / "m.vtk", with_vertex_field({"n", nan_values})),
                 InvalidInput);
    WriteOptions twice = with_vertex_field({"a", six});
    twice.vertex_fields.push_back({"a", six});
    EXPECT_THROW(write_mesh(mesh, dir / "m.vtk", twice), InvalidInput);
    WriteOptions faces;
    faces.face_fields.push_back({"f", six});  // 8 faces
    EXPECT_THROW(write_mesh(mesh, dir / "m.vtk", faces), InvalidInput);

    SurfaceMesh broken = test::octahedron();
    broken.position(Vertex(3)).x = std::numeric_limits<double>::infinity();
    EXPECT_THROW(write_mesh(broken, dir / "m.off"), InvalidInput);
    TriangleSoup soup = mesh.to_soup();
    soup.triangles[2][1] = 99;
    EXPECT_THROW(write_soup(soup, dir / "m.off"), InvalidInput);
    EXPECT_TRUE(test::listing(dir).empty());
}

TEST(MeshIo, WriteIntoMissingDirectoryLeavesNothing) {
    const fs::path dir = test::scratch_dir("io_atomic_missing");
    const fs::path target = dir / "no_such_dir" / "m.off";
    const std::string msg = test::io_error_of([&] { write_mesh(test::octahedron(), target); });
    EXPECT_NE(msg.find("m.off"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no_such_dir"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(dir / "no_such_dir"));
    EXPECT_TRUE(test::listing(dir).empty());
    EXPECT_THROW(write_pvd(dir / "no_such_dir" / "s.pvd", {{0.0, "a.vtp"}}), IoError);
    EXPECT_THROW(write_points_xyz(std::vector<Point3>{{1, 2, 3}}, dir / "nope" / "p.xyz"), IoError);
    EXPECT_TRUE(test::listing(dir).empty());
}

TEST(MeshIo, FailedWriteKeepsTheOldFile) {
    const fs::path dir = test::scratch_dir("io_atomic_keep");
    const SurfaceMesh oct = test::octahedron();
    write_mesh(oct, dir / "m.off");
    const std::string before = test::read_bytes(dir / "m.off");
    // A rejected request leaves the previous content.
    WriteOptions bad;
    bad.vertex_fields.push_back({"v", {1.0}});
    EXPECT_THROW(write_mesh(test::icosphere(1), dir / "m.off", bad), InvalidInput);
    EXPECT_EQ(test::read_bytes(dir / "m.off"), before);
    // Rename onto a directory fails after the data were written: the temporary goes away.
    fs::create_directory(dir / "d.off");
    EXPECT_THROW(write_mesh(oct, dir / "d.off"), IoError);
    EXPECT_TRUE(fs::is_directory(dir / "d.off"));
    EXPECT_EQ(test::listing(dir), (std::vector<std::string>{"d.off", "m.off"}));
    // A successful write replaces the content.
    write_mesh(test::icosphere(1), dir / "m.off");
    EXPECT_NE(test::read_bytes(dir / "m.off"), before);
    EXPECT_EQ(read_soup(dir / "m.off").triangles.size(), 80u);
    EXPECT_EQ(test::listing(dir), (std::vector<std::string>{"d.off", "m.off"}));
}

TEST(MeshIo, EnsureNotSameFile) {
    const fs::path dir = test::scratch_dir("io_same_file");
    write_mesh(test::octahedron(), dir / "a.off");
    write_mesh(test::octahedron(), dir / "b.off");
    EXPECT_NO_THROW(ensure_not_same_file(dir / "a.off", dir / "b.off"));
    EXPECT_NO_THROW(ensure_not_same_file(dir / "a.off", dir / "missing.off"));
    EXPECT_NO_THROW(ensure_not_same_file(dir / "missing.off", dir / "a.off"));
    EXPECT_THROW(ensure_not_same_file(dir / "a.off", dir / "a.off"), IoError);
    fs::create_directory(dir / "sub");
    EXPECT_THROW(ensure_not_same_file(dir / "a.off", dir / "sub" / ".." / "a.off"), IoError);
    fs::create_symlink(dir / "a.off", dir / "link.off");
    const std::string msg =
        test::io_error_of([&] { ensure_not_same_file(dir / "a.off", dir / "link.off"); });
    EXPECT_NE(msg.find("link.off"), std::string::npos) << msg;
}

TEST(MeshIo, WriteSoupKeepsUnreferencedPoints) {
    const fs::path dir = test::scratch_dir("io_soup");
    TriangleSoup soup;
    soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {7, 7, 7}};
    soup.triangles = {{0, 1, 2}};
    for (const char* name : {"s.off", "s.obj", "s.ply"}) {
        write_soup(soup, dir / name);
        expect_identical(soup, read_soup(dir / name), name);
    }
}

}  // namespace
}  // namespace dynmesh
