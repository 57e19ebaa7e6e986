/// probe_curve: the refinement of refiner.hpp over the 2D Delaunay triangulation (spec §4.6).
#include "dynmesh/probing/refine.hpp"

#include "refiner.hpp"
#include "triangulation2.hpp"

namespace dynmesh {

ProbingResult probe_curve(const Oracle& oracle, const ProbingOptions& options) {
    detail::check_probing_options(options, 2);
    detail::Refiner<detail::Triangulation2> r(oracle, options);
    return r.run();
}

}  // namespace dynmesh
