// Writing side of mesh_io.hpp: OFF, OBJ, PLY, legacy VTK, VTK XML PolyData and PVD.

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <string>

#include "dynmesh/error.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "io_common.hpp"

namespace dynmesh {

namespace fs = std::filesystem;

namespace {

using detail::AtomicWriter;

bool is_valid_field_name(const std::string& name) {
    if (name.empty()) return false;
    for (char c : name)
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '_' || c == '-' || c == '.'))
            return false;
    return true;
}

/// Checks one kind of fields (`kind` is "vertex" or "face") against `n` elements.
void validate_fields(const std::vector<ScalarField>& fields, std::size_t n, const char* fn,
                     const std::string& kind, const std::string& count_name, bool as_float) {
    std::set<std::string> names;
    for (const ScalarField& f : fields) {
        const std::string what =
            std::string(fn) + ": " + kind + " field '" + detail::printable(f.name) + "'";
        if (!is_valid_field_name(f.name))
            throw InvalidInput(what +
                               ": a field name must be non-empty and use only letters, "
                               "digits, '_', '-' and '.'");
        if ((kind == "vertex" && (f.name == "x" || f.name == "y" || f.name == "z")) ||
            (kind == "face" && f.name == "vertex_indices"))
            throw InvalidInput(what + ": the name is reserved for the geometry");
        if (!names.insert(f.name).second) throw InvalidInput(what + " is given twice");
        if (f.values.size() != n)
            throw InvalidInput(what + " has " + std::to_string(f.values.size()) +
                               " values, expected " + std::to_string(n) + " (" + count_name + ")");
        for (std::size_t i = 0; i < n; ++i) {
            const double v = f.values[i];
            if (!std::isfinite(v))
                throw InvalidInput(what + ": value " + std::to_string(i) + " is not finite");
            if (as_float && std::abs(v) > std::numeric_limits<float>::max())
                throw InvalidInput(what + ": value " + std::to_string(i) + " (" +
                                   std::to_string(v) + ") does not fit in a PLY float");
        }
    }
}

void put_point(AtomicWriter& out, const Point3& p) {
    out.put_number(p.x);
    out.put(' ');
    out.put_number(p.y);
    out.put(' ');
    out.put_number(p.z);
}

void put_triangle(AtomicWriter& out, const std::array<std::uint32_t, 3>& t, std::uint32_t base) {
    out.put_number(t[0] + base);
    out.put(' ');
    out.put_number(t[1] + base);
    out.put(' ');
    out.put_number(t[2] + base);
}

using Polylines = std::vector<std::vector<std::uint32_t>>;

/// Segments of all polylines (a polyline of k indices has k - 1).
std::uint64_t segment_count(const Polylines& polylines) {
    std::uint64_t n = 0;
    for (const auto& p : polylines) n += p.size() - 1;
    return n;
}

/// Indices of all polylines, plus one count per polyline (the legacy VTK cell-array size).
std::uint64_t vtk_cell_array_size(const Polylines& polylines) {
    std::uint64_t n = 0;
    for (const auto& p : polylines) n += p.size() + 1;
    return n;
}

void write_off(AtomicWriter& out, const TriangleSoup& soup, const Polylines& polylines) {
    out.put("OFF\n");
    out.put_number(std::uint64_t{soup.points.size()});
    out.put(' ');
    out.put_number(std::uint64_t{soup.triangles.size()} + segment_count(polylines));
    out.put(" 0\n");
    for (const Point3& p : soup.points) {
        put_point(out, p);
        out.put('\n');
    }
    for (const auto& t : soup.triangles) {
        out.put("3 ");
        put_triangle(out, t, 0);
        out.put('\n');
    }
    // OFF has no line element: each segment is a face of two vertices.
    for (const auto& p : polylines)
        for (std::size_t i = 0; i + 1 < p.size(); ++i) {
            out.put("2 ");
            out.put_number(p[i]);
            out.put(' ');
            out.put_number(p[i + 1]);
            out.put('\n');
        }
}

/// Indices per physical line of an OBJ `l` statement before a backslash continues it.
constexpr std::size_t kObjIndicesPerLine = 1024;

void write_obj(AtomicWriter& out, const TriangleSoup& soup, const Polylines& polylines) {
    out.put("# written by dynmesh\n");
    for (const Point3& p : soup.points) {
        out.put("v ");
        put_point(out, p);
        out.put('\n');
    }
    for (const auto& t : soup.triangles) {
        out.put("f ");
        put_triangle(out, t, 1);
        out.put('\n');
    }
    for (const auto& p : polylines) {
        out.put('l');
        for (std::size_t i = 0; i < p.size(); ++i) {
            if (i > 0 && i % kObjIndicesPerLine == 0) out.put(" \\\n");
            out.put(' ');
            out.put_number(p[i] + 1);
        }
        out.put('\n');
    }
}

void write_ply(AtomicWriter& out, const TriangleSoup& soup, const WriteOptions& opt) {
    const bool ascii = opt.ply_encoding == PlyEncoding::Ascii;
    const bool use_uint =
        soup.points.size() > std::size_t{std::numeric_limits<std::int32_t>::max()};
    out.put("ply\nformat ");
    out.put(ascii ? "ascii" : "binary_little_endian");
    out.put(" 1.0\ncomment written by dynmesh\nelement vertex ");
    out.put_number(std::uint64_t{soup.points.size()});
    out.put("\nproperty double x\nproperty double y\nproperty double z\n");
    for (const ScalarField& f : opt.vertex_fields) out.put("property float " + f.name + "\n");
    out.put("element face ");
    out.put_number(std::uint64_t{soup.triangles.size()});
    out.put(use_uint ? "\nproperty list uchar uint vertex_indices\n"
                     : "\nproperty list uchar int vertex_indices\n");
    for (const ScalarField& f : opt.face_fields) out.put("property float " + f.name + "\n");
    const std::uint64_t segments = segment_count(opt.polylines);
    if (segments > 0) {
        out.put("element edge ");
        out.put_number(segments);
        out.put(use_uint ? "\nproperty uint vertex1\nproperty uint vertex2\n"
                         : "\nproperty int vertex1\nproperty int vertex2\n");
    }
    out.put("end_header\n");

    for (std::size_t i = 0; i < soup.points.size(); ++i) {
        const Point3& p = soup.points[i];
        if (ascii) {
            put_point(out, p);
            for (const ScalarField& f : opt.vertex_fields) {
                out.put(' ');
                out.put_number(static_cast<float>(f.values[i]));
            }
            out.put('\n');
        } else {
            out.put_little_endian(p.x);
            out.put_little_endian(p.y);
            out.put_little_endian(p.z);
            for (const ScalarField& f : opt.vertex_fields)
                out.put_little_endian(static_cast<float>(f.values[i]));
        }
    }
    for (std::size_t i = 0; i < soup.triangles.size(); ++i) {
        const auto& t = soup.triangles[i];
        if (ascii) {
            out.put("3 ");
            put_triangle(out, t, 0);
            for (const ScalarField& f : opt.face_fields) {
                out.put(' ');
                out.put_number(static_cast<float>(f.values[i]));
            }
            out.put('\n');
        } else {
            out.put_little_endian(std::uint8_t{3});
            for (std::uint32_t v : t) out.put_little_endian(v);  // same bits as int for < 2^31
            for (const ScalarField& f : opt.face_fields)
                out.put_little_endian(static_cast<float>(f.values[i]));
        }
    }
    for (const auto& p : opt.polylines)
        for (std::size_t i = 0; i + 1 < p.size(); ++i) {
            if (ascii) {
                out.put_number(p[i]);
                out.put(' ');
                out.put_number(p[i + 1]);
                out.put('\n');
            } else {
                out.put_little_endian(p[i]);  // same bits as int for < 2^31
                out.put_little_endian(p[i + 1]);
            }
        }
}

/// Binary STL: an 80-byte header (not starting with "solid"), the triangle count, then per
/// triangle its unit normal (zero when degenerate), its corners as float32 and a zero
/// attribute word. STL has no shared vertices and no fields.
void write_stl(AtomicWriter& out, const TriangleSoup& soup) {
    std::string header = "binary STL written by dynmesh";
    header.resize(80, ' ');
    out.put(header);
    out.put_little_endian(static_cast<std::uint32_t>(soup.triangles.size()));
    for (const auto& t : soup.triangles) {
        const Point3& a = soup.points[t[0]];
        const Point3& b = soup.points[t[1]];
        const Point3& c = soup.points[t[2]];
        const Vec3 n = cross(b - a, c - a);
        const double len = norm(n);
        const Vec3 u = len > 0 && std::isfinite(len) ? n / len : Vec3{};
        for (double x : {u.x, u.y, u.z}) out.put_little_endian(static_cast<float>(x));
        for (const Point3* p : {&a, &b, &c})
            for (double x : {p->x, p->y, p->z}) out.put_little_endian(static_cast<float>(x));
        out.put_little_endian(std::uint16_t{0});
    }
}

void write_vtk_scalars(AtomicWriter& out, const std::vector<ScalarField>& fields) {
    for (const ScalarField& f : fields) {
        out.put("SCALARS " + f.name + " double 1\nLOOKUP_TABLE default\n");
        for (double v : f.values) {
            out.put_number(v);
            out.put('\n');
        }
    }
}

void write_vtk(AtomicWriter& out, const TriangleSoup& soup, const WriteOptions& opt) {
    const std::uint64_t nv = soup.points.size(), nf = soup.triangles.size();
    out.put("# vtk DataFile Version 3.0\ndynmesh surface mesh\nASCII\nDATASET POLYDATA\nPOINTS ");
    out.put_number(nv);
    out.put(" double\n");
    for (const Point3& p : soup.points) {
        put_point(out, p);
        out.put('\n');
    }
    if (!opt.polylines.empty()) {
        out.put("LINES ");
        out.put_number(std::uint64_t{opt.polylines.size()});
        out.put(' ');
        out.put_number(vtk_cell_array_size(opt.polylines));
        out.put('\n');
        for (const auto& p : opt.polylines) {
            out.put_number(std::uint64_t{p.size()});
            for (std::uint32_t v : p) {
                out.put(' ');
                out.put_number(v);
            }
            out.put('\n');
        }
    }
    out.put("POLYGONS ");
    out.put_number(nf);
    out.put(' ');
    out.put_number(4 * nf);
    out.put('\n');
    for (const auto& t : soup.triangles) {
        out.put("3 ");
        put_triangle(out, t, 0);
        out.put('\n');
    }
    if (!opt.vertex_fields.empty()) {
        out.put("POINT_DATA ");
        out.put_number(nv);
        out.put('\n');
        write_vtk_scalars(out, opt.vertex_fields);
    }
    if (!opt.face_fields.empty()) {
        out.put("CELL_DATA ");
        out.put_number(nf);
        out.put('\n');
        write_vtk_scalars(out, opt.face_fields);
    }
}

void write_vtp_arrays(AtomicWriter& out, const char* section,
                      const std::vector<ScalarField>& fields) {
    if (fields.empty()) return;
    out.put(std::string("      <") + section + " Scalars=\"" + fields.front().name + "\">\n");
    for (const ScalarField& f : fields) {
        out.put("        <DataArray type=\"Float64\" Name=\"" + f.name + "\" format=\"ascii\">");
        for (std::size_t i = 0; i < f.values.size(); ++i) {
            out.put(i % 8 == 0 ? "\n          " : " ");
            out.put_number(f.values[i]);
        }
        out.put("\n        </DataArray>\n");
    }
    out.put(std::string("      </") + section + ">\n");
}

void write_vtp(AtomicWriter& out, const TriangleSoup& soup, const WriteOptions& opt) {
    const std::uint64_t nv = soup.points.size(), nf = soup.triangles.size();
    out.put(
        "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
        "header_type=\"UInt64\">\n"
        "  <PolyData>\n"
        "    <Piece NumberOfPoints=\"");
    out.put_number(nv);
    out.put("\" NumberOfVerts=\"0\" NumberOfLines=\"");
    out.put_number(std::uint64_t{opt.polylines.size()});
    out.put("\" NumberOfStrips=\"0\" NumberOfPolys=\"");
    out.put_number(nf);
    out.put("\">\n");
    write_vtp_arrays(out, "PointData", opt.vertex_fields);
    write_vtp_arrays(out, "CellData", opt.face_fields);
    out.put(
        "      <Points>\n"
        "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
        "format=\"ascii\">\n");
    for (const Point3& p : soup.points) {
        out.put("          ");
        put_point(out, p);
        out.put('\n');
    }
    out.put(
        "        </DataArray>\n"
        "      </Points>\n");
    if (!opt.polylines.empty()) {
        // VTK numbers the cells verts, lines, polys, strips: Lines come before Polys.
        out.put(
            "      <Lines>\n"
            "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">");
        std::uint64_t k = 0;
        for (const auto& p : opt.polylines)
            for (std::uint32_t v : p) {
                out.put(k++ % 16 == 0 ? "\n          " : " ");
                out.put_number(v);
            }
        out.put(
            "\n        </DataArray>\n"
            "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">");
        std::uint64_t end = 0;
        for (std::size_t i = 0; i < opt.polylines.size(); ++i) {
            end += opt.polylines[i].size();
            out.put(i % 16 == 0 ? "\n          " : " ");
            out.put_number(end);
        }
        out.put(
            "\n        </DataArray>\n"
            "      </Lines>\n");
    }
    out.put(
        "      <Polys>\n"
        "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for (const auto& t : soup.triangles) {
        out.put("          ");
        put_triangle(out, t, 0);
        out.put('\n');
    }
    out.put(
        "        </DataArray>\n"
        "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">");
    for (std::uint64_t i = 1; i <= nf; ++i) {
        out.put(i % 16 == 1 ? "\n          " : " ");
        out.put_number(3 * i);
    }
    out.put(
        "\n        </DataArray>\n"
        "      </Polys>\n"
        "    </Piece>\n"
        "  </PolyData>\n"
        "</VTKFile>\n");
}

/// Validates everything, then writes atomically. `fn` names the public function and
/// `vertex_count`/`face_count` what the field sizes must match, for messages.
void write_checked(const TriangleSoup& soup, const fs::path& path, const WriteOptions& opt,
                   const char* fn, const char* vertex_count, const char* face_count) {
    const detail::FileContext ctx(path);
    const std::string ext = detail::lower_extension(path);
    enum class Format { Off, Obj, Ply, Stl, Vtk, Vtp };
    Format format = Format::Off;
    if (ext == ".off")
        format = Format::Off;
    else if (ext == ".obj")
        format = Format::Obj;
    else if (ext == ".ply")
        format = Format::Ply;
    else if (ext == ".stl")
        format = Format::Stl;
    else if (ext == ".vtk")
        format = Format::Vtk;
    else if (ext == ".vtp")
        format = Format::Vtp;
    else
        ctx.fail("unsupported extension " + detail::quote_text(ext) + " (meshes are written to " +
                 detail::join_list(writable_mesh_extensions()) + ")");

    const std::size_t nv = soup.points.size();
    for (std::size_t i = 0; i < nv; ++i)
        if (!is_finite(soup.points[i]))
            throw InvalidInput(std::string(fn) + ": vertex " + std::to_string(i) +
                               " has a non-finite coordinate");
    for (std::size_t t = 0; t < soup.triangles.size(); ++t)
        for (std::uint32_t v : soup.triangles[t])
            if (v >= nv)
                throw InvalidInput(std::string(fn) + ": triangle " + std::to_string(t) +
                                   " uses vertex index " + std::to_string(v) + " but there are " +
                                   std::to_string(nv) + " vertices");
    // Polyline errors name the file too: "write_soup: out.vtp: polyline 2, index 5: ...".
    const std::string where = std::string(fn) + ": " + ctx.name();
    for (std::size_t l = 0; l < opt.polylines.size(); ++l) {
        const auto& p = opt.polylines[l];
        if (p.size() < 2)
            throw InvalidInput(where + ": polyline " + std::to_string(l) + " has " +
                               std::to_string(p.size()) + (p.size() == 1 ? " index" : " indices") +
                               "; a polyline needs at least 2");
        for (std::size_t i = 0; i < p.size(); ++i)
            if (p[i] >= nv)
                throw InvalidInput(where + ": polyline " + std::to_string(l) + ", index " +
                                   std::to_string(i) + ": vertex " + std::to_string(p[i]) +
                                   " is out of range (there are " + std::to_string(nv) +
                                   " vertices)");
    }
    if (!opt.polylines.empty() && !opt.face_fields.empty() &&
        (format == Format::Vtk || format == Format::Vtp))
        throw InvalidInput(where + ": face fields cannot go with polylines in a " + ext +
                           " file (VTK cell data would need a value per line as well)");
    if (format == Format::Stl) {
        if (!opt.polylines.empty())
            throw InvalidInput(where + ": STL holds triangles only, not polylines");
        if (soup.triangles.size() > std::numeric_limits<std::uint32_t>::max())
            throw InvalidInput(where + ": more triangles than binary STL can count (2^32 - 1)");
        constexpr double kFloatMax = std::numeric_limits<float>::max();
        for (std::size_t i = 0; i < nv; ++i)
            for (std::size_t k = 0; k < 3; ++k)
                if (std::fabs(soup.points[i][k]) > kFloatMax)
                    throw InvalidInput(where + ": vertex " + std::to_string(i) +
                                       " has a coordinate beyond the float range STL stores");
    }
    const bool as_float = format == Format::Ply;
    validate_fields(opt.vertex_fields, nv, fn, "vertex", vertex_count, as_float);
    validate_fields(opt.face_fields, soup.triangles.size(), fn, "face", face_count, as_float);

    AtomicWriter out(path);
    switch (format) {
        case Format::Off:
            write_off(out, soup, opt.polylines);
            break;
        case Format::Obj:
            write_obj(out, soup, opt.polylines);
            break;
        case Format::Ply:
            write_ply(out, soup, opt);
            break;
        case Format::Stl:
            write_stl(out, soup);
            break;
        case Format::Vtk:
            write_vtk(out, soup, opt);
            break;
        case Format::Vtp:
            write_vtp(out, soup, opt);
            break;
    }
    out.commit();
}

std::string xml_escaped(std::string_view s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            default:
                out.push_back(c);
        }
    }
    return out;
}

}  // namespace

std::vector<std::string> writable_mesh_extensions() {
    return {".off", ".obj", ".ply", ".stl", ".vtk", ".vtp"};
}

void write_soup(const TriangleSoup& soup, const fs::path& path, const WriteOptions& options) {
    write_checked(soup, path, options, "write_soup", "points.size()", "triangles.size()");
}

void write_mesh(const SurfaceMesh& mesh, const fs::path& path, const WriteOptions& options) {
    write_checked(mesh.to_soup(), path, options, "write_mesh", "n_vertices()", "n_faces()");
}

void write_pvd(const fs::path& pvd,
               const std::vector<std::pair<double, std::string>>& time_and_relative_file) {
    for (std::size_t i = 0; i < time_and_relative_file.size(); ++i) {
        const auto& [time, file] = time_and_relative_file[i];
        if (!std::isfinite(time))
            throw InvalidInput("write_pvd: the time of data set " + std::to_string(i) +
                               " is not finite");
        if (file.empty())
            throw InvalidInput("write_pvd: data set " + std::to_string(i) + " has no file name");
        for (char c : file)
            if (static_cast<unsigned char>(c) < 0x20)
                throw InvalidInput("write_pvd: the file name of data set " + std::to_string(i) +
                                   " contains a control character");
    }
    AtomicWriter out(pvd);
    out.put(
        "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        "  <Collection>\n");
    for (const auto& [time, file] : time_and_relative_file) {
        out.put("    <DataSet timestep=\"");
        out.put_number(time);
        out.put("\" group=\"\" part=\"0\" file=\"" + xml_escaped(file) + "\"/>\n");
    }
    out.put(
        "  </Collection>\n"
        "</VTKFile>\n");
    out.commit();
}

}  // namespace dynmesh
