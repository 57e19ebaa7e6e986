#include "dynmesh/io/simplex_mesh_io.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "dynmesh/error.hpp"
#include "dynmesh/io/point_set_io.hpp"
#include "dynmesh/io/text_file.hpp"
#include "io_common.hpp"

namespace dynmesh {

namespace {

/// Appends v as printf("%.17g") would (C locale: the library never calls setlocale).
void put_double(std::string& out, double v) {
    char buf[32];
    const int n = std::snprintf(buf, sizeof(buf), "%.17g", v);
    out.append(buf, static_cast<std::size_t>(n));
}

void put_uint(std::string& out, std::uint64_t v) { out += std::to_string(v); }

/// Checks the mesh; `who` names the calling function in error messages.
void validate(const SimplexMeshView& mesh, const std::string& who) {
    DYNMESH_CHECK(mesh.dimension == 2 || mesh.dimension == 3,
                  who + ": dimension must be 2 or 3, not " + std::to_string(mesh.dimension));
    for (std::size_t i = 0; i < mesh.points.size(); ++i) {
        const Point3& p = mesh.points[i];
        const bool finite = mesh.dimension == 2 ? is_finite(Vec2{p.x, p.y}) : is_finite(p);
        DYNMESH_CHECK(finite, who + ": point " + std::to_string(i) + " has a non-finite coordinate");
    }
    const auto corners = static_cast<std::size_t>(mesh.dimension) + 1;
    for (std::size_t s = 0; s < mesh.simplices.size(); ++s)
        for (std::size_t k = 0; k < corners; ++k)
            DYNMESH_CHECK(mesh.simplices[s][k] < mesh.points.size(),
                          who + ": simplex " + std::to_string(s) + " uses point index " +
                              std::to_string(mesh.simplices[s][k]) + " but there are only " +
                              std::to_string(mesh.points.size()) + " points");
}

/// The boundary triangles of a tetrahedral mesh (used by exactly one tetrahedron), oriented
/// outwards for positively oriented tetrahedra, in (tetrahedron, local face) order.
std::vector<std::array<std::uint32_t, 3>> boundary_triangles(const SimplexMeshView& mesh) {
    // Faces of (a, b, c, d) with outward orientation when orient3d(a, b, c, d) > 0.
    constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    struct Face {
        std::array<std::uint32_t, 3> key;
        std::uint64_t at;  // 4 · tetrahedron + local face
        bool operator<(const Face& o) const { return key < o.key || (key == o.key && at < o.at); }
    };
    std::vector<Face> faces;
    faces.reserve(4 * mesh.simplices.size());
    for (std::size_t t = 0; t < mesh.simplices.size(); ++t)
        for (std::size_t f = 0; f < 4; ++f) {
            std::array<std::uint32_t, 3> key{};
            for (std::size_t k = 0; k < 3; ++k)
                key[k] = mesh.simplices[t][static_cast<std::size_t>(kFaces[f][k])];
            std::sort(key.begin(), key.end());
            faces.push_back({key, 4 * t + f});
        }
    std::sort(faces.begin(), faces.end());
    std::vector<std::uint64_t> single;
    for (std::size_t i = 0; i < faces.size();) {
        std::size_t j = i + 1;
        while (j < faces.size() && faces[j].key == faces[i].key) ++j;
        if (j - i == 1) single.push_back(faces[i].at);
        i = j;
    }
    std::sort(single.begin(), single.end());
    std::vector<std::array<std::uint32_t, 3>> out;
    out.reserve(single.size());
    for (std::uint64_t at : single) {
        const auto& tet = mesh.simplices[at / 4];
        const int* f = kFaces[at % 4];
        out.push_back({tet[static_cast<std::size_t>(f[0])], tet[static_cast<std::size_t>(f[1])],
                       tet[static_cast<std::size_t>(f[2])]});
    }
    return out;
}

std::string off_text(const SimplexMeshView& mesh) {
    std::string out = "OFF\n";
    if (mesh.dimension == 2) {
        put_uint(out, mesh.points.size());
        out += ' ';
        put_uint(out, mesh.simplices.size());
        out += " 0\n";
        for (const Point3& p : mesh.points) {
            put_double(out, p.x);
            out += ' ';
            put_double(out, p.y);
            out += " 0\n";
        }
        for (const auto& s : mesh.simplices) {
            out += '3';
            for (std::size_t k = 0; k < 3; ++k) {
                out += ' ';
                put_uint(out, s[k]);
            }
            out += '\n';
        }
        return out;
    }
    const auto tris = boundary_triangles(mesh);
    std::vector<std::uint32_t> vertices;
    vertices.reserve(3 * tris.size());
    for (const auto& t : tris) vertices.insert(vertices.end(), t.begin(), t.end());
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    put_uint(out, vertices.size());
    out += ' ';
    put_uint(out, tris.size());
    out += " 0\n";
    for (std::uint32_t v : vertices) {
        const Point3& p = mesh.points[v];
        put_double(out, p.x);
        out += ' ';
        put_double(out, p.y);
        out += ' ';
        put_double(out, p.z);
        out += '\n';
    }
    for (const auto& t : tris) {
        out += '3';
        for (std::uint32_t v : t) {
            out += ' ';
            put_uint(out, static_cast<std::uint64_t>(
                              std::lower_bound(vertices.begin(), vertices.end(), v) -
                              vertices.begin()));
        }
        out += '\n';
    }
    return out;
}

std::string vtu_text(const SimplexMeshView& mesh) {
    const std::size_t corners = static_cast<std::size_t>(mesh.dimension) + 1;
    const char* cell_type = mesh.dimension == 2 ? "5" : "10";  // VTK_TRIANGLE, VTK_TETRA
    std::string out =
        "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" "
        "header_type=\"UInt64\">\n"
        "  <UnstructuredGrid>\n"
        "    <Piece NumberOfPoints=\"";
    put_uint(out, mesh.points.size());
    out += "\" NumberOfCells=\"";
    put_uint(out, mesh.simplices.size());
    out +=
        "\">\n"
        "      <Points>\n"
        "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Point3& p : mesh.points) {
        out += "          ";
        put_double(out, p.x);
        out += ' ';
        put_double(out, p.y);
        out += ' ';
        put_double(out, mesh.dimension == 2 ? 0.0 : p.z);
        out += '\n';
    }
    out +=
        "        </DataArray>\n"
        "      </Points>\n"
        "      <Cells>\n"
        "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto& s : mesh.simplices) {
        out += "         ";
        for (std::size_t k = 0; k < corners; ++k) {
            out += ' ';
            put_uint(out, s[k]);
        }
        out += '\n';
    }
    out +=
        "        </DataArray>\n"
        "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < mesh.simplices.size(); ++i) {
        out += "          ";
        put_uint(out, (i + 1) * corners);
        out += '\n';
    }
    out +=
        "        </DataArray>\n"
        "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < mesh.simplices.size(); ++i) {
        out += "          ";
        out += cell_type;
        out += '\n';
    }
    out +=
        "        </DataArray>\n"
        "      </Cells>\n"
        "    </Piece>\n"
        "  </UnstructuredGrid>\n"
        "</VTKFile>\n";
    return out;
}

std::string medit_text(const SimplexMeshView& mesh) {
    const std::size_t corners = static_cast<std::size_t>(mesh.dimension) + 1;
    std::string out = "MeshVersionFormatted 2\n\nDimension ";
    put_uint(out, static_cast<std::uint64_t>(mesh.dimension));
    out += "\n\nVertices\n";
    put_uint(out, mesh.points.size());
    out += '\n';
    for (const Point3& p : mesh.points) {
        put_double(out, p.x);
        out += ' ';
        put_double(out, p.y);
        if (mesh.dimension == 3) {
            out += ' ';
            put_double(out, p.z);
        }
        out += " 0\n";
    }
    out += mesh.dimension == 2 ? "\nTriangles\n" : "\nTetrahedra\n";
    put_uint(out, mesh.simplices.size());
    out += '\n';
    for (const auto& s : mesh.simplices) {
        for (std::size_t k = 0; k < corners; ++k) {
            put_uint(out, std::uint64_t{s[k]} + 1);
            out += ' ';
        }
        out += "0\n";
    }
    out += "\nEnd\n";
    return out;
}

}  // namespace

SimplexMeshFormat simplex_mesh_format(const std::filesystem::path& path) {
    const std::string ext = detail::lower_extension(path);
    if (ext == ".node" || ext == ".ele") return SimplexMeshFormat::NodeEle;
    if (ext == ".off") return SimplexMeshFormat::Off;
    if (ext == ".vtu") return SimplexMeshFormat::Vtu;
    if (ext == ".mesh") return SimplexMeshFormat::Medit;
    throw InvalidInput("simplex mesh output " + detail::quote_text(path.string()) +
                       ": unknown extension " +
                       (ext.empty() ? std::string("(none)") : detail::quote_text(ext)) +
                       "; expected .node (with .ele), .off, .vtu or .mesh");
}

std::string simplex_mesh_text(SimplexMeshFormat format, const SimplexMeshView& mesh) {
    validate(mesh, "simplex_mesh_text");
    switch (format) {
        case SimplexMeshFormat::Off:
            return off_text(mesh);
        case SimplexMeshFormat::Vtu:
            return vtu_text(mesh);
        case SimplexMeshFormat::Medit:
            return medit_text(mesh);
        case SimplexMeshFormat::NodeEle:
            break;
    }
    throw InvalidInput("simplex_mesh_text: the .node/.ele format is two files; use write_simplex_mesh");
}

std::vector<std::filesystem::path> write_simplex_mesh(const std::filesystem::path& path,
                                                      const SimplexMeshView& mesh) {
    const SimplexMeshFormat format = simplex_mesh_format(path);
    validate(mesh, "write_simplex_mesh(" + detail::printable(path.string(), 200) + ")");
    if (format == SimplexMeshFormat::NodeEle) {
        std::filesystem::path base = path;
        base.replace_extension();
        PointSet ps;
        ps.dimension = mesh.dimension;
        ps.points.assign(mesh.points.begin(), mesh.points.end());
        if (mesh.dimension == 2)
            for (Point3& p : ps.points) p.z = 0;
        write_node_ele(base, ps, mesh.simplices);
        std::filesystem::path node = base, ele = base;
        node += ".node";
        ele += ".ele";
        return {node, ele};
    }
    write_text_file(path, simplex_mesh_text(format, mesh));
    return {path};
}

std::vector<std::filesystem::path> write_triangle_mesh(
    const std::filesystem::path& path, std::span<const Vec2> points,
    std::span<const std::array<std::uint32_t, 3>> triangles) {
    std::vector<Point3> p3;
    p3.reserve(points.size());
    for (const Vec2& p : points) p3.push_back({p.x, p.y, 0.0});
    std::vector<std::array<std::uint32_t, 4>> s4;
    s4.reserve(triangles.size());
    for (const auto& t : triangles) s4.push_back({t[0], t[1], t[2], 0});
    return write_simplex_mesh(path, {.dimension = 2, .points = p3, .simplices = s4});
}

std::vector<std::filesystem::path> write_tet_mesh(
    const std::filesystem::path& path, std::span<const Point3> points,
    std::span<const std::array<std::uint32_t, 4>> tets) {
    return write_simplex_mesh(path, {.dimension = 3, .points = points, .simplices = tets});
}

}  // namespace dynmesh
