// Meshing by probing: an unknown object learnt by a ray-casting device in free space.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "dict.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/probing/check.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "dynmesh/probing/refine.hpp"

namespace dynmesh::python {

namespace {

py::object probe(const std::optional<std::string>& object, const std::optional<Doubles>& vertices,
                 const std::optional<py::array>& faces, std::optional<double> eps, std::optional<double> delta,
                 std::optional<double> eps_S, int dim, const std::string& mode, const std::string& positioning,
                 bool check) {
    if (dim != 2 && dim != 3) throw InvalidInput("dim must be 2 or 3, not " + std::to_string(dim));
    if (object.has_value() == (vertices.has_value() || faces.has_value()))
        throw InvalidInput("give the object either by name (a spec or a mesh file) or as vertices and faces");
    if (vertices.has_value() != faces.has_value()) throw InvalidInput("vertices and faces go together");
    if (eps.has_value() == delta.has_value()) throw InvalidInput("give exactly one of eps and delta");
    if (mode != "device" && mode != "omniscient") throw InvalidInput("mode must be 'device' or 'omniscient'");
    if (positioning != "lca" && positioning != "boundary") throw InvalidInput("positioning must be 'lca' or 'boundary'");

    ProbeSetup setup;
    if (object) {
        py::gil_scoped_release unlocked;  // reads a file, or checks a mesh
        setup = make_probe_object(*object);
    } else {
        const TriangleSoup soup = soup_of(points3_of(*vertices, "vertices"), *faces);
        py::gil_scoped_release unlocked;
        setup = make_probe_object(soup, "the mesh");
    }
    if (setup.planar != (dim == 2))
        throw InvalidInput(setup.planar ? "dim=2 is for planar curves; " + setup.spec + " is one: pass dim=2"
                                        : "dim=2 needs a planar curve (circle2:R or star2:R), not " + setup.spec);
    const ProbeObject& obj = *setup.object;
    ProbingOptions o;
    o.omega = setup.omega;
    o.interior_points = setup.interior_points;
    if (eps_S) {
        o.eps_S = *eps_S;
        if (obj.reach() > 0 && o.eps_S > obj.reach() * (1 + 1e-12))
            throw InvalidInput("eps_S = " + std::to_string(o.eps_S) + " exceeds the reach of " + setup.spec + ", " +
                               std::to_string(obj.reach()) + ": it must be a lower bound of the reach");
    } else if (obj.reach() > 0)
        o.eps_S = obj.reach();
    else
        throw InvalidInput("eps_S is required (a polyhedron has no reach to take it from)");
    if (eps) o.eps = *eps;
    o.delta = delta;
    o.mode = mode == "omniscient" ? ProbingMode::Omniscient : ProbingMode::Device;
    o.positioning = positioning == "boundary" ? ProbingPositioning::Boundary : ProbingPositioning::Lca;
    if (check || o.mode == ProbingMode::Omniscient) o.ground_truth = &obj;
    o.check_every = check ? 0 : SIZE_MAX;

    ProbingResult r;
    CheckReport chk;
    {
        py::gil_scoped_release unlocked;
        r = dim == 3 ? probe_surface(obj, o) : probe_curve(obj, o);
        chk = check_probing(r, obj, o, dim);
    }
    const ProbingReport& p = r.report;
    py::dict rep;
    rep["dim"] = dim;
    rep["mode"] = mode;
    rep["positioning"] = positioning;
    rep["eps"] = p.eps;
    rep["eps_S"] = o.eps_S;
    rep["probes"] = p.probes;
    rep["probes_bootstrap"] = p.probes_bootstrap;
    rep["probes_inferred"] = p.probes_inferred;
    rep["voronoi_edges_travelled"] = p.voronoi_edges_travelled;
    rep["path_length"] = p.path_length;
    rep["exterior_path_length"] = p.exterior_path_length;
    rep["cells_created"] = p.cells_created;
    rep["insertions"] = p.insertions;
    rep["reinitialisations"] = p.reinitialisations;
    rep["vertices"] = p.vertices;
    rep["facets"] = p.facets;
    copy_figures(rep, chk, {"euler", "components"});
    rep["max_ball_radius"] = p.max_ball_radius;
    copy_figures(rep, chk, {"hausdorff", "hausdorff_bound", "sample_gap"});
    if (!chk.flag("closed_manifold")) rep["hausdorff"] = py::none();  // measured only on a closed manifold
    rep["seconds"] = p.seconds;
    if (check) {
        py::dict c;
        c["ok"] = chk.ok();
        c["problems"] = chk.problems;
        c["segments_checked"] = p.segments_checked;
        rep["check"] = c;
    }
    py::array sample = adopt<double, 3>(std::move(r.sample));
    py::array points = adopt<double, 3>(std::move(r.mesh.points));
    if (dim == 3)
        return py::make_tuple(sample, points, adopt<std::uint32_t, 3>(std::move(r.mesh.triangles)), rep);
    py::list polygons;
    for (auto& poly : r.polygons) polygons.append(adopt_flat(std::move(poly)));
    return py::make_tuple(sample, points, polygons, rep);
}

}  // namespace

void bind_probing(py::module_& m) {
    m.def("probe", &probe, py::arg("object") = py::none(), py::kw_only(), py::arg("vertices") = py::none(),
          py::arg("faces") = py::none(), py::arg("eps") = py::none(), py::arg("delta") = py::none(),
          py::arg("eps_S") = py::none(), py::arg("dim") = 3, py::arg("mode") = "device",
          py::arg("positioning") = "lca", py::arg("check") = false,
          "Learns an object by probing (Boissonnat, Guibas & Oudot) and meshes it, as `dynmesh probe`.\n"
          "object: 'sphere:R', 'ellipsoid:a,b,c', 'torus:R,r', 'balls:FILE', 'genus2', 'circle2:R',\n"
          "'star2:R' or a mesh file; or vertices= and faces= of a closed mesh. eps (or delta): the\n"
          "refinement size; eps_S: a lower bound of the reach (analytic objects know theirs).\n"
          "check: verify the free paths and the output against the object (report['check']).\n"
          "Returns (sample (n, 3), vertices (k, 3), faces (m, 3) uint32, report) for dim 3, and\n"
          "(sample, points, polygons: a list of index arrays, report) for dim 2.");
}

}  // namespace dynmesh::python
