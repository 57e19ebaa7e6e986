// The C++ side of bench/python/flip_overhead.py: the same mesh file, the same flips, timed
// in C++ so that the Python module's cost can be put against it.
//
// usage: flip_overhead_bench MESH.off [REPEATS]
// Prints one JSON line: seconds_flip (flip_all on the built mesh: "the C++ call"),
// seconds_from_arrays (SurfaceMesh::from_soup of the triangle arrays), seconds_faces (the
// faces read back into arrays), each the fastest of REPEATS runs (default 3) on a fresh mesh;
// flips, vertices, faces. Reading the file is not timed.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/mesh/soup.hpp"

int main(int argc, char** argv) {
    using namespace dynmesh;
    using Clock = std::chrono::steady_clock;
    const int repeats = argc == 3 ? std::atoi(argv[2]) : 3;
    if ((argc != 2 && argc != 3) || repeats < 1) {
        std::fprintf(stderr, "usage: flip_overhead_bench MESH.off [REPEATS]\n");
        return 2;
    }
    try {
        const TriangleSoup soup = read_soup(argv[1]);
        double from_arrays = 1e300, flip = 1e300, faces = 1e300;
        FlipReport r;
        TriangleSoup back;
        const auto seconds = [](Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); };
        for (int k = 0; k < repeats; ++k) {
            auto t0 = Clock::now();
            SurfaceMesh mesh = SurfaceMesh::from_soup(soup);
            from_arrays = std::min(from_arrays, seconds(t0));
            t0 = Clock::now();
            r = flip_all(mesh, {.rule = FlipRule::AngleDef3});
            flip = std::min(flip, seconds(t0));
            t0 = Clock::now();
            back = mesh.to_soup();
            faces = std::min(faces, seconds(t0));
        }
        std::printf("{\"seconds_flip\": %.6f, \"seconds_from_arrays\": %.6f, \"seconds_faces\": %.6f, "
                    "\"flips\": %zu, \"vertices\": %zu, \"faces\": %zu}\n",
                    flip, from_arrays, faces, r.flips, back.points.size(), back.triangles.size());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "flip_overhead_bench: %s\n", e.what());
        return 3;
    }
}
