// Writes the soups of polyline_samples.hpp in every format into a directory, for
// tests/io/polyline_readers_check.py to read back with VTK's readers and meshio.
// usage: io_polyline_samples DIR

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "dynmesh/io/mesh_io.hpp"
#include "polyline_samples.hpp"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: io_polyline_samples DIR\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    try {
        using dynmesh::PlyEncoding;
        using dynmesh::WriteOptions;
        for (const std::string ext : {".off", ".obj", ".ply", ".vtk", ".vtp"}) {
            WriteOptions polygon;
            polygon.polylines = dynmesh::test::polygon_polylines();
            dynmesh::write_soup(dynmesh::test::polygon_soup(), dir / ("polygon" + ext), polygon);

            WriteOptions mixed;
            mixed.polylines = dynmesh::test::mixed_polylines();
            mixed.vertex_fields.push_back({"height", {0, 1, 2, 3, 4, 5, 6, 7, 8}});
            dynmesh::write_soup(dynmesh::test::mixed_soup(), dir / ("mixed" + ext), mixed);
            if (ext == ".ply") {
                mixed.ply_encoding = PlyEncoding::Ascii;
                dynmesh::write_soup(dynmesh::test::mixed_soup(), dir / "mixed_ascii.ply", mixed);
            }

            WriteOptions long_line;
            long_line.polylines = dynmesh::test::long_polylines();
            dynmesh::write_soup(dynmesh::test::mixed_soup(), dir / ("long" + ext), long_line);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "io_polyline_samples: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
