// Sample a torus, mesh it, worsen the mesh and smooth it again by edge flips, with the
// installed library (find_package(dynmesh) in CMakeLists.txt).
#include <cstdio>

#include <dynmesh/flips/flip_smooth.hpp>
#include <dynmesh/flips/worsen.hpp>
#include <dynmesh/metrics/quality.hpp>
#include <dynmesh/reconstruct/restricted_delaunay.hpp>
#include <dynmesh/shapes/analytic.hpp>
#include <dynmesh/version.hpp>

int main() {
    using namespace dynmesh;
    const Torus torus({0, 0, 0}, 5.0, 3.0);
    SurfaceMesh mesh = restricted_delaunay(torus.sample_uniform(2000, /*seed=*/1), torus);
    (void)worsen(mesh, {.seed = 1});
    const double worse = mesh_quality(mesh, {.surface = &torus}).normal_dev_deg->mean;
    const FlipReport flips = flip_all(mesh, {.rule = FlipRule::AngleDef3});
    const double after = mesh_quality(mesh, {.surface = &torus}).normal_dev_deg->mean;
    std::printf("dynmesh %s: %zu vertices, %zu triangles, %zu flips, mean normal deviation %.2f -> %.2f deg\n",
                kVersion, mesh.n_vertices(), mesh.n_faces(), flips.flips, worse, after);
    return after < worse ? 0 : 1;
}
