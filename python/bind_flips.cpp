// flip (global and local mode, both criteria), worsen and the quality measures.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "dict.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/flips/worsen.hpp"
#include "dynmesh/metrics/quality.hpp"

namespace dynmesh::python {

namespace {

/// The vertices of local mode: indices into the mesh's vertices (in range; at least one;
/// repeats kept, as `dynmesh flip --vertices` keeps them).
std::vector<Vertex> local_vertices(const py::array& given, const SurfaceMesh& mesh) {
    const Indices around = indices_of(given, "around");
    if (around.ndim() != 1 || around.size() == 0)
        throw InvalidInput("around must be a non-empty 1-D array of vertex indices");
    std::vector<Vertex> V;
    const auto a = around.unchecked<1>();
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
        const std::int64_t v = a(i);
        if (v < 0 || std::size_t(v) >= mesh.n_vertices())
            throw InvalidInput("around[" + std::to_string(i) + "] = " + std::to_string(v) + " is not a vertex index in [0, " +
                               std::to_string(mesh.n_vertices()) + ")");
        V.push_back(Vertex(std::uint32_t(v)));
    }
    return V;
}

}  // namespace

void bind_flips(py::module_& m) {
    m.def(
        "flip",
        [](const Doubles& vertices, const py::array& faces, const std::string& criterion, double feature_angle_deg,
           std::optional<py::array> around) {
            SurfaceMesh mesh = mesh_of(vertices, faces);
            const FlipRule rule = parse_flip_rule(criterion);
            FlipReport r;
            py::dict local;
            if (!around) {
                py::gil_scoped_release unlocked;
                r = flip_all(mesh, {.rule = rule, .feature_angle_deg = feature_angle_deg});
            } else {
                const std::vector<Vertex> V = local_vertices(*around, mesh);
                LocalFlipReport lr;
                {
                    py::gil_scoped_release unlocked;
                    lr = flip_local(mesh, V, {.rule = rule, .feature_angle_deg = feature_angle_deg});
                }
                r = lr.flips;
                local["vertices_given"] = V.size();
                local["rounds"] = lr.rounds;
                local["final_m"] = lr.final_m;
                local["changed_faces"] = lr.changed_faces.size();
                local["window_vertices"] = lr.window_vertices;
                local["ring_faces"] = lr.ring_faces;
                local["ball_tests"] = lr.ball_tests;
                local["unchecked_balls"] = lr.unchecked_balls;
            }
            py::dict report;
            report["criterion"] = std::string(to_string(rule));
            report["vertices"] = mesh.n_vertices();
            report["faces"] = mesh.n_faces();
            report["edges"] = mesh.n_edges();
            report["flips"] = r.flips;
            report["checks"] = r.checks;
            report["pushes"] = r.pushes;
            report["degenerate_tests"] = r.degenerate;
            report["not_improving_tests"] = r.not_improving;
            report["feature_angle_deg"] = feature_angle_deg;
            report["feature_locked_tests"] = r.feature_locked;
            report["converged"] = r.converged;
            report["renumbered"] = r.renumbered;
            report["seconds_flip"] = r.seconds;
            if (around) report["local"] = local;
            return py::make_tuple(faces_of(mesh), report);
        },
        py::arg("vertices"), py::arg("faces"), py::arg("criterion") = "angle", py::arg("feature_angle_deg") = 180.0,
        py::arg("around") = py::none(),
        "Flips edges until none is flippable under the criterion ('angle': Definition 3 of the\n"
        "edge-flip paper; 'diametric': the diametric-ball rule; 'planar'); returns (faces, report).\n"
        "Edges whose dihedral angle is sharper than feature_angle_deg are never flipped.\n"
        "around: vertex indices for local mode (only the neighbourhood of these vertices is\n"
        "repaired; the report then has a 'local' dict, as `dynmesh flip --vertices`).\n"
        "Vertices never move. The report has the field names of `dynmesh flip --report`.");

    m.def(
        "worsen",
        [](const Doubles& vertices, const py::array& faces, std::size_t rounds, double probability,
           double min_dihedral_deg, std::uint64_t seed) {
            SurfaceMesh mesh = mesh_of(vertices, faces);
            WorsenReport r;
            double seconds = 0;
            {
                py::gil_scoped_release unlocked;
                const auto t0 = std::chrono::steady_clock::now();
                r = worsen(mesh, {.rounds = rounds, .probability = probability, .min_dihedral_deg = min_dihedral_deg,
                                  .seed = seed});
                seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            }
            py::dict report;
            report["vertices"] = mesh.n_vertices();
            report["faces"] = mesh.n_faces();
            report["flips"] = r.flips;
            report["attempts"] = r.attempts;
            report["rejected"] = r.rejected;
            report["rounds"] = rounds;
            report["seed"] = seed;
            report["seconds_worsen"] = seconds;
            return py::make_tuple(faces_of(mesh), report);
        },
        py::arg("vertices"), py::arg("faces"), py::arg("rounds") = 5, py::arg("probability") = 0.5,
        py::arg("min_dihedral_deg") = 120.0, py::arg("seed") = 1,
        "Random edge flips (each edge tried with the given probability per round; a flip that\n"
        "makes a dihedral angle smaller than min_dihedral_deg is undone), reproducible by seed;\n"
        "returns (faces, report) with the field names of `dynmesh worsen --report`.");

    m.def(
        "quality",
        [](const Doubles& vertices, const py::array& faces, bool self_intersections) {
            const SurfaceMesh mesh = mesh_of(vertices, faces);
            QualityReport q;
            {
                py::gil_scoped_release unlocked;
                q = mesh_quality(mesh, {.self_intersections = self_intersections});
            }
            return quality_dict(flatten(q));
        },
        py::arg("vertices"), py::arg("faces"), py::arg("self_intersections") = false,
        "The quality measures of `dynmesh stats`: size and topology (vertices, faces, edges,\n"
        "euler, closed, boundary_edges, degenerate_faces), angles (min/max/mean_angle_deg),\n"
        "radius-edge ratios and circumradii, dihedral deviations and, when asked, the number of\n"
        "intersecting face pairs (self_intersections). Returns a dict of numbers.");
}

}  // namespace dynmesh::python
