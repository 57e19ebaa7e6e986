#include "dynmesh/deform/snapshot.hpp"

#include <string>

#include "dynmesh/error.hpp"

namespace dynmesh {

SurfaceMesh deform_snapshot(const Scenario& s, int t, DeformRunOptions options) {
    DYNMESH_CHECK(t >= 0 && t <= s.time_units, "deform_snapshot: time " + std::to_string(t) +
                                                   " is outside the run [0, " + std::to_string(s.time_units) + "]");
    SurfaceMesh out;
    options.stop_after = t;
    options.on_frame = [&](const DeformFrame& f) {
        if (f.t == t) out = f.mesh->mesh();
    };
    (void)run_deform(s, options);
    out.garbage_collection();
    return out;
}

SurfaceMesh boomerang_snapshot(std::size_t samples, std::uint64_t seed) {
    const Scenario s = make_scenario("boomerang", {.samples = samples, .seed = seed});
    DeformRunOptions o;
    o.measure_every = 0;
    o.measure = {.hausdorff = false, .self_intersections = false, .sampling_radius = false};
    // The bend is a cycle out and back (scenario.hpp): fully stretched and bent at u = 1/2.
    return deform_snapshot(s, s.time_units / 2, o);
}

}  // namespace dynmesh
