// The C++ side of bench/python/flip_overhead.py: the same mesh file, the same flips, timed
// in C++ so that the Python module's cost can be put against it.
//
// usage: flip_overhead_bench MESH.off
// Prints one JSON line: seconds_flip (flip_all on the built mesh: "the C++ call"),
// seconds_from_arrays (SurfaceMesh::from_soup of the triangle arrays), seconds_faces (the
// faces read back into arrays), flips, vertices, faces. Reading the file is not timed.
#include <chrono>
#include <cstdio>
#include <exception>

#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/mesh/soup.hpp"

int main(int argc, char** argv) {
    using namespace dynmesh;
    using Clock = std::chrono::steady_clock;
    if (argc != 2) {
        std::fprintf(stderr, "usage: flip_overhead_bench MESH.off\n");
        return 2;
    }
    try {
        const TriangleSoup soup = read_soup(argv[1]);
        auto t0 = Clock::now();
        SurfaceMesh mesh = SurfaceMesh::from_soup(soup);
        const double from_arrays = std::chrono::duration<double>(Clock::now() - t0).count();
        t0 = Clock::now();
        const FlipReport r = flip_all(mesh, {.rule = FlipRule::AngleDef3});
        const double flip = std::chrono::duration<double>(Clock::now() - t0).count();
        t0 = Clock::now();
        const TriangleSoup back = mesh.to_soup();
        const double faces = std::chrono::duration<double>(Clock::now() - t0).count();
        std::printf("{\"seconds_flip\": %.6f, \"seconds_from_arrays\": %.6f, \"seconds_faces\": %.6f, "
                    "\"flips\": %zu, \"vertices\": %zu, \"faces\": %zu}\n",
                    flip, from_arrays, faces, r.flips, mesh.n_vertices(), back.triangles.size());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "flip_overhead_bench: %s\n", e.what());
        return 3;
    }
}
