// The library in ten lines: sample a torus, mesh it, worsen the mesh, smooth it by edge
// flips, and compare the quality. Build: cmake --build --preset release --target flip_smoothing
#include <cstdio>

#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/flips/worsen.hpp"
#include "dynmesh/metrics/quality.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "dynmesh/shapes/analytic.hpp"

int main() {
    using namespace dynmesh;
    const Torus torus({0, 0, 0}, 5.0, 3.0);
    SurfaceMesh mesh = restricted_delaunay(torus.sample_uniform(10000, /*seed=*/1), torus);
    const auto before = mesh_quality(mesh, {.surface = &torus});
    (void)worsen(mesh, {.seed = 1});
    const auto worse = mesh_quality(mesh, {.surface = &torus});
    const FlipReport flips = flip_all(mesh, {.rule = FlipRule::AngleDef3});
    const auto after = mesh_quality(mesh, {.surface = &torus});
    std::printf("%zu flips in %.3f s\n", flips.flips, flips.seconds);
    std::printf("normal deviation mean (deg): initial %.2f, worsened %.2f, smoothed %.2f\n",
                before.normal_dev_deg->mean, worse.normal_dev_deg->mean, after.normal_dev_deg->mean);
    std::printf("180 - dihedral mean (deg):   initial %.2f, worsened %.2f, smoothed %.2f\n",
                before.dihedral_dev_deg.mean, worse.dihedral_dev_deg.mean, after.dihedral_dev_deg.mean);
}
