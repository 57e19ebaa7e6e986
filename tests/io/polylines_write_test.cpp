// Writers with polylines (WriteOptions::polylines): every format parsed back structurally by
// this file's own small parsers (.off also by CGAL's OFF reader), validation, and the
// triangle-only output kept byte for byte. tests/io/polyline_readers_check.py reads .vtp, .vtk,
// .obj and .ply files with VTK's readers and meshio.

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <CGAL/IO/OFF.h>
#include <CGAL/Simple_cartesian.h>
#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "io_test_util.hpp"
#include "polyline_samples.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

namespace fs = std::filesystem;

// ---- triangle-only output is exactly what it was before polylines existed ---------------------

TriangleSoup tiny_soup() {
    TriangleSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.5}, {1, 1, 0.25}};
    s.triangles = {{0, 1, 2}, {1, 3, 2}};
    return s;
}

WriteOptions tiny_fields() {
    WriteOptions opt;
    opt.vertex_fields.push_back({"h", {0, 1, 2, 3}});
    opt.face_fields.push_back({"a", {0.5, 1.5}});
    return opt;
}

TEST(PolylinesWrite, TriangleOnlyOutputIsUnchanged) {
    const fs::path dir = test::scratch_dir("io_polylines_golden");
    const TriangleSoup soup = tiny_soup();
    const std::map<std::string, std::string> expected = {
        {"t.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0.5\n1 1 0.25\n3 0 1 2\n3 1 3 2\n"},
        {"t.obj",
         "# written by dynmesh\nv 0 0 0\nv 1 0 0\nv 0 1 0.5\nv 1 1 0.25\nf 1 2 3\nf 2 4 3\n"},
        {"t.ply",
         "ply\nformat ascii 1.0\ncomment written by dynmesh\nelement vertex 4\n"
         "property double x\nproperty double y\nproperty double z\nproperty float h\n"
         "element face 2\nproperty list uchar int vertex_indices\nproperty float a\n"
         "end_header\n0 0 0 0\n1 0 0 1\n0 1 0.5 2\n1 1 0.25 3\n3 0 1 2 0.5\n3 1 3 2 1.5\n"},
        {"t.vtk",
         "# vtk DataFile Version 3.0\ndynmesh surface mesh\nASCII\nDATASET POLYDATA\n"
         "POINTS 4 double\n0 0 0\n1 0 0\n0 1 0.5\n1 1 0.25\nPOLYGONS 2 8\n3 0 1 2\n3 1 3 2\n"
         "POINT_DATA 4\nSCALARS h double 1\nLOOKUP_TABLE default\n0\n1\n2\n3\n"
         "CELL_DATA 2\nSCALARS a double 1\nLOOKUP_TABLE default\n0.5\n1.5\n"},
        {"t.vtp",
         "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n"
         "  <PolyData>\n"
         "    <Piece NumberOfPoints=\"4\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
         "NumberOfStrips=\"0\" NumberOfPolys=\"2\">\n"
         "      <PointData Scalars=\"h\">\n"
         "        <DataArray type=\"Float64\" Name=\"h\" format=\"ascii\">\n"
         "          0 1 2 3\n"
         "        </DataArray>\n"
         "      </PointData>\n"
         "      <CellData Scalars=\"a\">\n"
         "        <DataArray type=\"Float64\" Name=\"a\" format=\"ascii\">\n"
         "          0.5 1.5\n"
         "        </DataArray>\n"
         "      </CellData>\n"
         "      <Points>\n"
         "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n"
         "          0 0 0\n"
         "          1 0 0\n"
         "          0 1 0.5\n"
         "          1 1 0.25\n"
         "        </DataArray>\n"
         "      </Points>\n"
         "      <Polys>\n"
         "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n"
         "          0 1 2\n"
         "          1 3 2\n"
         "        </DataArray>\n"
         "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n"
         "          3 6\n"
         "        </DataArray>\n"
         "      </Polys>\n"
         "    </Piece>\n"
         "  </PolyData>\n"
         "</VTKFile>\n"},
    };
    WriteOptions opt = tiny_fields();
    opt.ply_encoding = PlyEncoding::Ascii;
    for (const auto& [name, text] : expected) {
        write_soup(soup, dir / name, opt);
        EXPECT_EQ(test::read_bytes(dir / name), text) << name;
    }

    // Binary PLY, assembled here byte by byte.
    std::string bin =
        "ply\nformat binary_little_endian 1.0\ncomment written by dynmesh\nelement vertex 4\n"
        "property double x\nproperty double y\nproperty double z\nproperty float h\n"
        "element face 2\nproperty list uchar int vertex_indices\nproperty float a\nend_header\n";
    const auto append = [&bin](const auto& v) {
        char bytes[sizeof(v)];
        std::memcpy(bytes, &v, sizeof(v));
        if constexpr (std::endian::native == std::endian::big)
            for (std::size_t i = 0; i < sizeof(v) / 2; ++i)
                std::swap(bytes[i], bytes[sizeof(v) - 1 - i]);
        bin.append(bytes, sizeof(v));
    };
    for (std::size_t i = 0; i < soup.points.size(); ++i) {
        for (std::size_t c = 0; c < 3; ++c) append(soup.points[i][c]);
        append(static_cast<float>(i));
    }
    for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
        append(std::uint8_t{3});
        for (std::uint32_t v : soup.triangles[f]) append(static_cast<std::int32_t>(v));
        append(static_cast<float>(0.5 + static_cast<double>(f)));
    }
    opt.ply_encoding = PlyEncoding::BinaryLittleEndian;
    write_soup(soup, dir / "b.ply", opt);
    EXPECT_EQ(test::read_bytes(dir / "b.ply"), bin);
}

// ---- structural parsers, written against the formats, not against the writer ------------------

using Polylines = std::vector<std::vector<std::uint32_t>>;
using Segments = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/// What a file holds: counts, and the polylines (or, for formats that only know segments,
/// the segments) in file order.
struct Parsed {
    std::size_t points = 0;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    Polylines polylines;
    Segments segments;
    std::size_t point_data = 0;  // values per vertex field (.vtk/.vtp), 0 when none
    std::size_t cell_data = 0;   // values per cell field (.vtk/.vtp), 0 when none
};

Segments segments_of(const Polylines& polylines) {
    Segments s;
    for (const auto& p : polylines)
        for (std::size_t i = 0; i + 1 < p.size(); ++i) s.emplace_back(p[i], p[i + 1]);
    return s;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::vector<std::string> words_of(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> w;
    for (std::string t; in >> t;) w.push_back(t);
    return w;
}

std::uint32_t to_index(const std::string& word) {
    return static_cast<std::uint32_t>(std::stoul(word));
}

Parsed parse_off(const std::string& text) {
    Parsed r;
    const auto lines = lines_of(text);
    EXPECT_EQ(lines.at(0), "OFF");
    const auto counts = words_of(lines.at(1));
    EXPECT_EQ(counts.size(), 3u);
    r.points = std::stoul(counts.at(0));
    const std::size_t faces = std::stoul(counts.at(1));
    EXPECT_EQ(lines.size(), 2 + r.points + faces) << "lines after the header";
    for (std::size_t i = 0; i < r.points; ++i) EXPECT_EQ(words_of(lines.at(2 + i)).size(), 3u);
    for (std::size_t f = 0; f < faces && 2 + r.points + f < lines.size(); ++f) {
        const auto w = words_of(lines[2 + r.points + f]);
        const std::size_t k = std::stoul(w.at(0));
        EXPECT_EQ(w.size(), k + 1) << "face " << f;
        if (k == 3)
            r.triangles.push_back({to_index(w[1]), to_index(w[2]), to_index(w[3])});
        else if (k == 2)
            r.segments.emplace_back(to_index(w[1]), to_index(w[2]));
        else
            ADD_FAILURE() << "face " << f << " has " << k << " vertices";
    }
    return r;
}

/// OBJ statements with backslash continuations joined; `physical_l_lines` counts the file's
/// lines that belong to `l` statements.
Parsed parse_obj(const std::string& text, std::size_t* physical_l_lines = nullptr) {
    Parsed r;
    std::string statement;
    bool in_l = false;
    std::size_t l_lines = 0;
    for (const std::string& line : lines_of(text)) {
        if (statement.empty()) in_l = line.rfind("l ", 0) == 0;
        if (in_l) ++l_lines;
        if (!line.empty() && line.back() == '\\') {
            statement += line.substr(0, line.size() - 1) + " ";
            continue;
        }
        statement += line;
        const auto w = words_of(statement);
        statement.clear();
        if (w.empty() || w[0] == "#") continue;
        if (w[0] == "v") {
            EXPECT_EQ(w.size(), 4u);
            ++r.points;
        } else if (w[0] == "f") {
            EXPECT_EQ(w.size(), 4u);
            r.triangles.push_back({to_index(w[1]) - 1, to_index(w[2]) - 1, to_index(w[3]) - 1});
        } else if (w[0] == "l") {
            std::vector<std::uint32_t> p;
            for (std::size_t i = 1; i < w.size(); ++i) {
                EXPECT_GE(to_index(w[i]), 1u) << "OBJ indices are 1-based";
                p.push_back(to_index(w[i]) - 1);
            }
            r.polylines.push_back(p);
        } else {
            ADD_FAILURE() << "unexpected OBJ statement " << w[0];
        }
    }
    EXPECT_TRUE(statement.empty()) << "the file ends inside a continued statement";
    if (physical_l_lines) *physical_l_lines = l_lines;
    return r;
}

/// PLY, ascii or binary little-endian: vertex (double x y z, float extras), face (uchar
/// count + int/uint indices, float extras) and edge (int/uint vertex1 vertex2) elements.
Parsed parse_ply(const std::string& bytes, std::vector<std::string>* face_props = nullptr) {
    Parsed r;
    const std::size_t end = bytes.find("end_header\n");
    EXPECT_NE(end, std::string::npos);
    const auto header = lines_of(bytes.substr(0, end));
    const bool ascii = header.at(1) == "format ascii 1.0";
    EXPECT_TRUE(ascii || header.at(1) == "format binary_little_endian 1.0");
    struct Element {
        std::string name;
        std::size_t count = 0;
        std::vector<std::string> props;  // "type name", lists as "list uchar int name"
    };
    std::vector<Element> elements;
    for (const std::string& line : header) {
        const auto w = words_of(line);
        if (w.empty()) continue;
        if (w[0] == "element") {
            elements.push_back({w.at(1), std::stoul(w.at(2)), {}});
        } else if (w[0] == "property") {
            std::string p;
            for (std::size_t i = 1; i < w.size(); ++i) p += (i > 1 ? " " : "") + w[i];
            elements.back().props.push_back(p);
        }
    }
    std::size_t pos = end + std::string("end_header\n").size();
    std::istringstream text(ascii ? bytes.substr(pos) : std::string());
    const auto read_value = [&](const std::string& type) -> double {
        if (ascii) {
            double v = 0;
            text >> v;
            EXPECT_FALSE(text.fail()) << "ascii PLY value";
            return v;
        }
        const std::size_t size = type == "double" ? 8 : type == "uchar" ? 1 : 4;
        EXPECT_LE(pos + size, bytes.size()) << "binary PLY ends early";
        if (pos + size > bytes.size()) return 0;
        unsigned char b[8] = {};
        std::memcpy(b, bytes.data() + pos, size);
        pos += size;
        if constexpr (std::endian::native == std::endian::big)
            for (std::size_t i = 0; i < size / 2; ++i) std::swap(b[i], b[size - 1 - i]);
        if (type == "double") return std::bit_cast<double>(b);
        if (type == "float")
            return std::bit_cast<float>(std::array<unsigned char, 4>{b[0], b[1], b[2], b[3]});
        if (type == "uchar") return b[0];
        std::uint32_t u = 0;
        std::memcpy(&u, b, 4);
        return type == "int" ? static_cast<double>(static_cast<std::int32_t>(u)) : u;
    };
    for (const Element& e : elements) {
        if (e.name == "face" && face_props) *face_props = e.props;
        for (std::size_t i = 0; i < e.count; ++i) {
            std::vector<double> values;
            for (const std::string& prop : e.props) {
                const auto w = words_of(prop);
                if (w[0] == "list") {
                    const auto k = static_cast<std::size_t>(read_value(w[1]));
                    for (std::size_t j = 0; j < k; ++j) values.push_back(read_value(w[2]));
                } else {
                    values.push_back(read_value(w[0]));
                }
            }
            if (e.name == "vertex") {
                ++r.points;
            } else if (e.name == "face") {
                r.triangles.push_back({static_cast<std::uint32_t>(values.at(0)),
                                       static_cast<std::uint32_t>(values.at(1)),
                                       static_cast<std::uint32_t>(values.at(2))});
            } else if (e.name == "edge") {
                EXPECT_EQ(e.props, (std::vector<std::string>{"int vertex1", "int vertex2"}));
                r.segments.emplace_back(static_cast<std::uint32_t>(values.at(0)),
                                        static_cast<std::uint32_t>(values.at(1)));
            } else {
                ADD_FAILURE() << "unexpected PLY element " << e.name;
            }
        }
    }
    if (ascii) {
        std::string extra;
        EXPECT_FALSE(text >> extra) << "ascii PLY has data after its elements: " << extra;
    } else {
        EXPECT_EQ(pos, bytes.size()) << "binary PLY has bytes after its elements";
    }
    return r;
}

/// Legacy VTK POLYDATA: POINTS, LINES, POLYGONS and the data sections.
Parsed parse_vtk(const std::string& text) {
    Parsed r;
    const auto lines = lines_of(text);
    EXPECT_EQ(lines.at(3), "DATASET POLYDATA");
    std::istringstream in(text);
    for (int i = 0; i < 4; ++i) {
        std::string skip;
        std::getline(in, skip);
    }
    std::string keyword;
    while (in >> keyword) {
        if (keyword == "POINTS") {
            std::string type;
            in >> r.points >> type;
            for (std::size_t i = 0; i < 3 * r.points; ++i) {
                double v = 0;
                in >> v;
            }
        } else if (keyword == "LINES" || keyword == "POLYGONS") {
            std::size_t n = 0, size = 0, read = 0;
            in >> n >> size;
            for (std::size_t c = 0; c < n; ++c) {
                std::size_t k = 0;
                in >> k;
                std::vector<std::uint32_t> ids(k);
                for (auto& v : ids) in >> v;
                read += k + 1;
                if (keyword == "LINES")
                    r.polylines.push_back(ids);
                else if (k == 3)
                    r.triangles.push_back({ids[0], ids[1], ids[2]});
                else
                    ADD_FAILURE() << "polygon of " << k << " vertices";
            }
            EXPECT_EQ(read, size) << keyword << " size";
        } else if (keyword == "POINT_DATA" || keyword == "CELL_DATA") {
            std::size_t n = 0;
            in >> n;
            (keyword == "POINT_DATA" ? r.point_data : r.cell_data) = n;
            for (;;) {  // SCALARS name type 1 / LOOKUP_TABLE default / n values
                const auto at = in.tellg();
                std::string next;
                if (!(in >> next)) {
                    in.clear();
                    break;
                }
                if (next != "SCALARS") {
                    in.seekg(at);
                    break;
                }
                std::string name, type, lut, lut_name;
                std::size_t comps = 0;
                in >> name >> type >> comps >> lut >> lut_name;
                for (std::size_t i = 0; i < n; ++i) {
                    double v = 0;
                    in >> v;
                }
            }
        } else {
            ADD_FAILURE() << "unexpected legacy VTK keyword " << keyword;
            break;
        }
        EXPECT_FALSE(in.fail()) << "after " << keyword;
    }
    return r;
}

std::string xml_attribute(const std::string& tag, const std::string& name) {
    const std::string key = " " + name + "=\"";
    const auto at = tag.find(key);
    if (at == std::string::npos) return {};
    const auto start = at + key.size();
    return tag.substr(start, tag.find('"', start) - start);
}

/// Values of the DataArray named `name` inside <section>...</section> of `xml`.
std::vector<std::uint64_t> vtp_array(const std::string& xml, const std::string& section,
                                     const std::string& name) {
    const auto open = xml.find("<" + section + ">");
    const auto close = xml.find("</" + section + ">");
    if (open == std::string::npos || close == std::string::npos) return {};
    const std::string body = xml.substr(open, close - open);
    const auto at = body.find("Name=\"" + name + "\"");
    EXPECT_NE(at, std::string::npos) << section << "/" << name;
    const auto start = body.find('>', at) + 1;
    std::istringstream in(body.substr(start, body.find("</DataArray>", start) - start));
    std::vector<std::uint64_t> values;
    for (std::uint64_t v = 0; in >> v;) values.push_back(v);
    return values;
}

Polylines cells_of(const std::vector<std::uint64_t>& connectivity,
                   const std::vector<std::uint64_t>& offsets) {
    Polylines cells;
    std::uint64_t begin = 0;
    for (std::uint64_t end : offsets) {
        EXPECT_LE(begin, end);
        EXPECT_LE(end, connectivity.size());
        if (begin > end || end > connectivity.size()) break;
        cells.emplace_back(connectivity.begin() + static_cast<std::ptrdiff_t>(begin),
                           connectivity.begin() + static_cast<std::ptrdiff_t>(end));
        begin = end;
    }
    EXPECT_EQ(begin, connectivity.size()) << "the last offset ends the connectivity";
    return cells;
}

Parsed parse_vtp(const std::string& xml) {
    Parsed r;
    const auto piece_at = xml.find("<Piece");
    const std::string piece = xml.substr(piece_at, xml.find('>', piece_at) - piece_at);
    r.points = std::stoul(xml_attribute(piece, "NumberOfPoints"));
    const std::size_t n_lines = std::stoul(xml_attribute(piece, "NumberOfLines"));
    const std::size_t n_polys = std::stoul(xml_attribute(piece, "NumberOfPolys"));
    r.polylines =
        cells_of(vtp_array(xml, "Lines", "connectivity"), vtp_array(xml, "Lines", "offsets"));
    EXPECT_EQ(r.polylines.size(), n_lines) << "NumberOfLines";
    EXPECT_EQ(xml.find("<Lines>") == std::string::npos, n_lines == 0);
    for (const auto& c :
         cells_of(vtp_array(xml, "Polys", "connectivity"), vtp_array(xml, "Polys", "offsets"))) {
        EXPECT_EQ(c.size(), 3u);
        if (c.size() == 3) r.triangles.push_back({c[0], c[1], c[2]});
    }
    EXPECT_EQ(r.triangles.size(), n_polys) << "NumberOfPolys";
    if (xml.find("<CellData") != std::string::npos) r.cell_data = 1;
    if (xml.find("<PointData") != std::string::npos) r.point_data = 1;
    return r;
}

Parsed parse(const fs::path& path) {
    const std::string bytes = test::read_bytes(path);
    const std::string ext = path.extension().string();
    if (ext == ".off") return parse_off(bytes);
    if (ext == ".obj") return parse_obj(bytes);
    if (ext == ".ply") return parse_ply(bytes);
    if (ext == ".vtk") return parse_vtk(bytes);
    return parse_vtp(bytes);
}

/// The file at `path` holds exactly `soup`'s point count and triangles and `polylines`
/// (as polylines where the format has them, as segments in .off and .ply).
void expect_holds(const fs::path& path, const TriangleSoup& soup, const Polylines& polylines) {
    SCOPED_TRACE(path.filename().string());
    const Parsed r = parse(path);
    EXPECT_EQ(r.points, soup.points.size());
    EXPECT_EQ(r.triangles, soup.triangles);
    const std::string ext = path.extension().string();
    if (ext == ".off" || ext == ".ply") {
        EXPECT_TRUE(r.polylines.empty());
        EXPECT_EQ(r.segments, segments_of(polylines));
    } else {
        EXPECT_TRUE(r.segments.empty());
        EXPECT_EQ(r.polylines, polylines);
    }
}

struct Format {
    std::string ext;
    PlyEncoding ply = PlyEncoding::BinaryLittleEndian;
    std::string suffix;  // tells the two PLY encodings apart
};
const std::vector<Format> kFormats = {
    {".off"}, {".obj"}, {".ply"}, {".ply", PlyEncoding::Ascii, "_ascii"}, {".vtk"}, {".vtp"}};

TEST(PolylinesWrite, ClosedPolygonWithoutTriangles) {
    const fs::path dir = test::scratch_dir("io_polylines_polygon");
    const TriangleSoup soup = test::polygon_soup();
    WriteOptions opt;
    opt.polylines = test::polygon_polylines();
    for (const Format& f : kFormats) {
        opt.ply_encoding = f.ply;
        const fs::path path = dir / ("polygon" + f.suffix + f.ext);
        write_soup(soup, path, opt);
        expect_holds(path, soup, opt.polylines);
    }
    // The polygon is closed: 6 segments, the last one back to the first point.
    const Parsed off = parse(dir / "polygon.off");
    ASSERT_EQ(off.segments.size(), 6u);
    EXPECT_EQ(off.segments.back(), std::make_pair(5u, 0u));
    EXPECT_EQ(
        test::read_bytes(dir / "polygon.obj").find("\nl 1 2 3 4 5 6 1\n") == std::string::npos,
        false);
}

TEST(PolylinesWrite, TrianglesAndTwoPolylines) {
    const fs::path dir = test::scratch_dir("io_polylines_mixed");
    const TriangleSoup soup = test::mixed_soup();
    WriteOptions opt;
    opt.polylines = test::mixed_polylines();
    opt.vertex_fields.push_back({"height", {0, 1, 2, 3, 4, 5, 6, 7, 8}});
    for (const Format& f : kFormats) {
        opt.ply_encoding = f.ply;
        const fs::path path = dir / ("mixed" + f.suffix + f.ext);
        write_soup(soup, path, opt);
        expect_holds(path, soup, opt.polylines);
    }
    // Vertex fields go with polylines: one value per point, no cell data.
    for (const char* name : {"mixed.vtk", "mixed.vtp"}) {
        const Parsed r = parse(dir / name);
        EXPECT_EQ(r.point_data, std::string(name) == "mixed.vtk" ? 9u : 1u) << name;
        EXPECT_EQ(r.cell_data, 0u) << name;
    }
    // In VTK's cell order (verts, lines, polys, strips) the lines come first: the legacy
    // file lists LINES before POLYGONS, the XML file <Lines> before <Polys>.
    const std::string vtk = test::read_bytes(dir / "mixed.vtk");
    EXPECT_LT(vtk.find("\nLINES 2 11\n"), vtk.find("\nPOLYGONS 8 32\n"));
    const std::string vtp = test::read_bytes(dir / "mixed.vtp");
    EXPECT_LT(vtp.find("<Lines>"), vtp.find("<Polys>"));
    EXPECT_NE(vtp.find("NumberOfLines=\"2\""), std::string::npos);
    EXPECT_NE(test::read_bytes(dir / "mixed.off").find("OFF\n9 15 0\n"), std::string::npos);

    // Our own reader keeps the triangles of .obj (skips `l`) and .ply (skips `edge`)...
    for (const char* name : {"mixed.obj", "mixed.ply", "mixed_ascii.ply"}) {
        const TriangleSoup back = read_soup(dir / name);
        EXPECT_EQ(back.triangles, soup.triangles) << name;
        EXPECT_EQ(back.points.size(), soup.points.size()) << name;
    }
    // ...but refuses the 2-vertex faces of .off, as documented.
    EXPECT_THROW((void)read_soup(dir / "mixed.off"), IoError);
}

TEST(PolylinesWrite, LongPolylineIsContinuedInObj) {
    const fs::path dir = test::scratch_dir("io_polylines_long");
    const TriangleSoup soup = test::mixed_soup();
    WriteOptions opt;
    opt.polylines = test::long_polylines();
    opt.polylines.push_back({8, 0});
    for (const Format& f : kFormats) {
        opt.ply_encoding = f.ply;
        const fs::path path = dir / ("long" + f.suffix + f.ext);
        write_soup(soup, path, opt);
        expect_holds(path, soup, opt.polylines);
    }
    // 2500 indices: 1024 + 1024 + 452 on three lines, then the 2-index polyline on one.
    std::size_t physical = 0;
    const Parsed obj = parse_obj(test::read_bytes(dir / "long.obj"), &physical);
    EXPECT_EQ(physical, 4u);
    ASSERT_EQ(obj.polylines.size(), 2u);
    EXPECT_EQ(obj.polylines[0].size(), 2500u);
    for (const std::string& line : lines_of(test::read_bytes(dir / "long.obj")))
        EXPECT_LE(words_of(line).size(), 1026u) << "an OBJ line longer than 1024 indices";
}

TEST(PolylinesWrite, FaceFieldsWithPolylines) {
    const fs::path dir = test::scratch_dir("io_polylines_fields");
    const TriangleSoup soup = test::mixed_soup();
    WriteOptions opt;
    opt.polylines = test::mixed_polylines();
    opt.face_fields.push_back({"label", {1, 2, 3, 4, 5, 6, 7, 8}});
    // VTK: cell data would have to cover the lines (which come first): refused, nothing written.
    for (const char* name : {"f.vtk", "f.vtp", "F.VTP"}) {
        try {
            write_soup(soup, dir / name, opt);
            ADD_FAILURE() << name << ": face fields with polylines accepted";
        } catch (const InvalidInput& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(name), std::string::npos) << msg;
            EXPECT_NE(msg.find("face fields cannot go with polylines"), std::string::npos) << msg;
        }
        EXPECT_FALSE(fs::exists(dir / name)) << name;
    }
    EXPECT_TRUE(test::listing(dir).empty());
    // PLY keeps the fields on the face element; the edges have only their two vertices.
    for (PlyEncoding enc : {PlyEncoding::BinaryLittleEndian, PlyEncoding::Ascii}) {
        opt.ply_encoding = enc;
        write_soup(soup, dir / "f.ply", opt);
        std::vector<std::string> face_props;
        const Parsed r = parse_ply(test::read_bytes(dir / "f.ply"), &face_props);
        EXPECT_EQ(face_props,
                  (std::vector<std::string>{"list uchar int vertex_indices", "float label"}));
        EXPECT_EQ(r.triangles, soup.triangles);
        EXPECT_EQ(r.segments, segments_of(opt.polylines));
    }
    // OFF and OBJ ignore fields, as without polylines.
    for (const char* name : {"f.off", "f.obj"}) {
        write_soup(soup, dir / name, opt);
        expect_holds(dir / name, soup, opt.polylines);
    }
    // Without polylines the face fields still go to VTK files.
    opt.polylines.clear();
    write_soup(soup, dir / "f.vtk", opt);
    EXPECT_EQ(parse(dir / "f.vtk").cell_data, 8u);
}

/// A reader that is not ours: CGAL's OFF reader takes faces of any size, so it returns the
/// triangles and then each segment as a 2-vertex polygon.
TEST(PolylinesWrite, CgalReadsOffSegmentsAsTwoVertexFaces) {
    const fs::path dir = test::scratch_dir("io_polylines_cgal_off");
    const std::vector<std::tuple<std::string, TriangleSoup, Polylines>> cases = {
        {"polygon.off", test::polygon_soup(), test::polygon_polylines()},
        {"mixed.off", test::mixed_soup(), test::mixed_polylines()},
        {"long.off", test::mixed_soup(), test::long_polylines()}};
    for (const auto& [name, soup, polylines] : cases) {
        SCOPED_TRACE(name);
        WriteOptions opt;
        opt.polylines = polylines;
        write_soup(soup, dir / name, opt);
        std::vector<CGAL::Simple_cartesian<double>::Point_3> points;
        std::vector<std::vector<std::size_t>> faces;
        std::ifstream in(dir / name);
        ASSERT_TRUE(CGAL::IO::read_OFF(in, points, faces));
        ASSERT_EQ(points.size(), soup.points.size());
        for (std::size_t i = 0; i < points.size(); ++i)
            EXPECT_EQ(points[i], (CGAL::Simple_cartesian<double>::Point_3(
                                     soup.points[i].x, soup.points[i].y, soup.points[i].z)));
        std::vector<std::vector<std::size_t>> expected;
        for (const auto& t : soup.triangles) expected.push_back({t[0], t[1], t[2]});
        for (const auto& [a, b] : segments_of(polylines)) expected.push_back({a, b});
        EXPECT_EQ(faces, expected);
    }
}

/// The InvalidInput message of write_soup(soup, path, opt); fails when it does not throw one.
std::string invalid_input_of(const TriangleSoup& soup, const fs::path& path,
                             const WriteOptions& opt) {
    try {
        write_soup(soup, path, opt);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    ADD_FAILURE() << path << ": no InvalidInput";
    return {};
}

TEST(PolylinesWrite, RejectsBadPolylines) {
    const fs::path dir = test::scratch_dir("io_polylines_bad");
    const TriangleSoup soup = test::mixed_soup();
    for (const Format& f : kFormats) {
        const fs::path path = dir / ("bad" + f.ext);
        WriteOptions opt;
        opt.ply_encoding = f.ply;
        opt.polylines = {{0, 1, 2}, {3, 9, 1}};
        std::string msg = invalid_input_of(soup, path, opt);
        EXPECT_NE(msg.find("polyline 1, index 1: vertex 9 is out of range (there are 9 vertices)"),
                  std::string::npos)
            << msg;
        EXPECT_NE(msg.find(path.filename().string()), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;

        opt.polylines = {{0, 1}, {4}};
        msg = invalid_input_of(soup, path, opt);
        EXPECT_NE(msg.find("polyline 1 has 1 index; a polyline needs at least 2"),
                  std::string::npos)
            << msg;
        opt.polylines = {{}};
        msg = invalid_input_of(soup, path, opt);
        EXPECT_NE(msg.find("polyline 0 has 0 indices"), std::string::npos) << msg;
        opt.polylines = {{0, std::numeric_limits<std::uint32_t>::max()}};
        msg = invalid_input_of(soup, path, opt);
        EXPECT_NE(msg.find("polyline 0, index 1: vertex 4294967295 is out of range"),
                  std::string::npos)
            << msg;
    }
    EXPECT_TRUE(test::listing(dir).empty()) << "a refused write left a file";
}

TEST(PolylinesWrite, WriteMeshTakesPolylinesOverItsVertices) {
    const fs::path dir = test::scratch_dir("io_polylines_mesh");
    const SurfaceMesh mesh = test::octahedron();
    WriteOptions opt;
    opt.polylines = {{0, 1, 2, 3, 4, 5}};
    write_mesh(mesh, dir / "m.vtp", opt);
    expect_holds(dir / "m.vtp", mesh.to_soup(), opt.polylines);
    opt.polylines = {{0, 6}};
    EXPECT_THROW(write_mesh(mesh, dir / "m.vtk", opt), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
