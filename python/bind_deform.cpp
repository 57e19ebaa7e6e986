// DeformingMesh: a surface mesh kept good while its samples move (advance / update / queued
// edits / current mesh / reports).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <optional>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "dict.hpp"
#include "dynmesh/deform/deforming_mesh.hpp"
#include "dynmesh/deform/run.hpp"
#include "dynmesh/error.hpp"

namespace dynmesh::python {

namespace {

py::list violations_list(const std::vector<ViolationRecord>& records) {
    py::list out;
    for (const ViolationRecord& v : records) {
        py::dict d;
        d["t"] = v.t;
        d["kind"] = std::string(to_string(v.kind));
        d["detail"] = v.detail;
        out.append(d);
    }
    return out;
}

/// The work counters under the names of the CLI's deform report and log.csv.
void put_counters(py::dict& d, const UpdateCounters& c) {
    d["flips"] = c.flips;
    d["insertions"] = c.insertions;
    d["removals"] = c.removals;
    d["changes"] = c.changes();
    d["samples_inserted"] = c.samples_inserted;
    d["samples_deleted"] = c.samples_deleted;
    d["rebuilds"] = c.rebuilds;
    d["rollbacks"] = c.rollbacks;
    d["flip_refusals"] = c.flip_refusals;
}

/// The violations by kind, as `dynmesh deform --report` counts them.
py::dict violations_by_kind(const std::vector<ViolationRecord>& records) {
    py::dict d;
    for (const ViolationRecord& v : records) {
        const py::str kind(std::string(to_string(v.kind)));
        d[kind] = (d.contains(kind) ? d[kind].cast<std::size_t>() : 0) + 1;
    }
    return d;
}

/// The first kViolationExamples records of each kind (the report's violation_examples).
std::vector<ViolationRecord> examples_of(const std::vector<ViolationRecord>& records) {
    std::map<Violation, std::size_t> seen;
    std::vector<ViolationRecord> out;
    for (const ViolationRecord& v : records)
        if (seen[v.kind]++ < kViolationExamples) out.push_back(v);
    return out;
}

/// The Python object: the library's DeformingMesh and the reference mesh it was started on.
/// Its methods keep the GIL: two threads never change one object at once.
struct PyDeformingMesh {
    std::unique_ptr<SurfaceMesh> reference;
    std::unique_ptr<DeformingMesh> mesh;

    const DeformingMesh& get() const { return *mesh; }
};

/// The position table of advance(): finiteness is checked by the library for live samples
/// only (rows of deleted ids may hold anything, NaN included).
std::vector<Point3> positions_of(const Doubles& positions, std::size_t at_least) {
    std::vector<Point3> p = points3_of(positions, "positions", false);
    if (p.size() < at_least)
        throw InvalidInput("positions has " + std::to_string(p.size()) + " rows; every sample id up to " +
                           std::to_string(at_least - 1) + " needs one");
    return p;
}

}  // namespace

void bind_deform(py::module_& m) {
    py::class_<PyDeformingMesh>(m, "DeformingMesh",
                                "A mesh of a surface known only through moving samples, updated at scheduled\n"
                                "time steps (Cheng & Dey). Time is discrete: call advance(t, positions) for\n"
                                "t = 1, 2, ... and update() when it says update_due.")
        .def(py::init([](const Doubles& positions, double lambda_, double kappa, std::optional<double> h0,
                         std::optional<int> horizon, std::optional<py::array> reference_faces, bool emergency_steps,
                         std::uint64_t seed, std::size_t max_substeps, double size_factor, double feature_angle_deg,
                         bool local_updates) {
                 auto self = std::make_unique<PyDeformingMesh>();
                 const std::vector<Point3> p = points3_of(positions, "positions");
                 DeformOptions params;
                 params.lambda = lambda_;
                 params.kappa = kappa;
                 params.h0 = h0;
                 if (horizon) params.horizon = *horizon;
                 params.emergency_steps = emergency_steps;
                 params.seed = seed;
                 params.max_substeps = max_substeps;
                 params.size_factor = size_factor;
                 params.feature_angle_deg = feature_angle_deg;
                 params.local_updates = local_updates;
                 InitialSurface initial;
                 if (reference_faces) {
                     self->reference = std::make_unique<SurfaceMesh>(SurfaceMesh::from_soup(soup_of(p, *reference_faces)));
                     initial.reference = self->reference.get();
                 }
                 py::gil_scoped_release unlocked;  // the object is not visible to Python yet
                 self->mesh = std::make_unique<DeformingMesh>(p, params, initial);
                 return self;
             }),
             py::arg("positions"), py::arg("lambda_"), py::arg("kappa") = kPracticalKappa, py::arg("h0") = py::none(),
             py::arg("horizon") = py::none(), py::arg("reference_faces") = py::none(),
             py::arg("emergency_steps") = true, py::arg("seed") = 1,
             py::arg("max_substeps") = DeformOptions{}.max_substeps,
             py::arg("size_factor") = DeformOptions{}.size_factor,
             py::arg("feature_angle_deg") = DeformOptions{}.feature_angle_deg,
             py::arg("local_updates") = DeformOptions{}.local_updates,
             "positions: the samples at t = 0, (n, 3). lambda_: how far any surface point moves in one\n"
             "time unit at most. kappa: the step constant (next step floor(R / (kappa lambda)) later).\n"
             "h0: the sampling radius (estimated when None). horizon: no step after this time.\n"
             "reference_faces: faces (m, 3) over the positions of a closed mesh of the surface at\n"
             "t = 0 (the first mesh is the restricted Delaunay triangulation of the net against it;\n"
             "without it the mesh is reconstructed from the samples, which must then be dense).\n"
             "max_substeps: advance() cuts a time unit into at most this many sub-steps when the\n"
             "samples move faster than the schedule allows (1: off).\n"
             "size_factor: a sample's size is min(R, size_factor * local feature size) (default 0.4;\n"
             "0: off, the global R of the paper).\n"
             "feature_angle_deg: edges of the reference sharper than this (180 - dihedral) are creases,\n"
             "kept as mesh-edge chains through the motion (180: off).\n"
             "local_updates: an update between sub-steps works on the pairs over their budget and\n"
             "their 2-ring (True, the default) or on the whole mesh (False).")
        .def(
            "advance",
            [](PyDeformingMesh& self, int t, const Doubles& positions) {
                const std::vector<Point3> p = positions_of(positions, self.get().id_capacity());
                const StepReport s = self.mesh->advance(t, p);
                py::dict d;
                d["t"] = s.t;
                d["update_due"] = s.update_due;
                d["emergency"] = s.emergency;
                d["max_displacement"] = s.max_displacement;
                d["R"] = s.R;
                d["substeps"] = s.substeps;
                d["internal_updates"] = s.internal_updates;
                d["local_updates"] = s.local_updates;
                d["region_vertices"] = s.region_vertices;
                d["max_strain_ratio"] = s.max_strain_ratio;
                d["retries"] = s.retries;
                d["inverted_triangles"] = s.inverted_triangles;
                d["new_folds"] = s.new_folds;
                d["self_intersecting"] = s.self_intersecting;
                d["violations"] = violations_list(s.violations);
                return d;
            },
            py::arg("t"), py::arg("positions"),
            "Moves every live sample to positions[id] at integer time t (greater than the last one);\n"
            "returns the step report (update_due: call update() now).")
        .def(
            "update",
            [](PyDeformingMesh& self) {
                const DeformUpdateReport u = self.mesh->update();
                py::dict d;
                d["t"] = u.t;
                d["emergency"] = u.emergency;
                put_counters(d, u.counters);
                d["update_seconds"] = u.counters.seconds;
                d["R_before"] = u.R_before;
                d["R_after"] = u.R_after;
                d["next_step"] = u.next_step;
                d["samples"] = u.samples;
                d["vertices"] = u.vertices;
                d["vertices_before"] = u.vertices_before;
                d["violations"] = violations_list(u.violations);
                return d;
            },
            "The paper's MeshUpdate at the current time: refinement, the queued insertions, the\n"
            "queued deletions, the next step. Returns the update report.")
        .def(
            "queue_insertion",
            [](PyDeformingMesh& self, const Doubles& p) { return self.mesh->queue_insertion(point3_of(p, "p")); },
            py::arg("p"),
            "Queues a new sample at p; returns its id. It joins at the next update; pass its position\n"
            "to advance() from now on.")
        .def(
            "queue_deletion", [](PyDeformingMesh& self, SampleId id) { self.mesh->queue_deletion(id); }, py::arg("id"),
            "Queues the deletion of a live sample (it stays live until the next update).")
        .def(
            "mesh",
            [](const PyDeformingMesh& self) {
                std::vector<Vertex> kept;
                const py::tuple vf = compact_arrays_of(self.get().mesh(), &kept);
                std::vector<std::int64_t> samples(kept.size());
                for (std::size_t i = 0; i < kept.size(); ++i) samples[i] = self.get().sample_of(kept[i]);
                return py::make_tuple(vf[0], vf[1], adopt_flat(std::move(samples)));
            },
            "The current mesh: (vertices (n, 3), faces (m, 3), samples (n,)), samples[i] being the\n"
            "sample id of vertex i.")
        .def_property_readonly("time", [](const PyDeformingMesh& self) { return self.get().time(); })
        .def_property_readonly("next_step", [](const PyDeformingMesh& self) { return self.get().next_step(); })
        .def_property_readonly("id_capacity", [](const PyDeformingMesh& self) { return self.get().id_capacity(); },
                               "One past the largest sample id handed out (advance() needs this many rows).")
        .def_property_readonly("live_samples", [](const PyDeformingMesh& self) { return self.get().live_samples(); })
        .def_property_readonly("updates", [](const PyDeformingMesh& self) { return self.get().updates(); })
        .def_property_readonly(
            "init_report",
            [](const PyDeformingMesh& self) {
                const InitReport& r = self.get().init_report();
                py::dict d;
                d["h0"] = r.h0;
                d["h0_estimated"] = r.h0_estimated;
                d["samples"] = r.samples;
                d["init_vertices"] = r.vertices;
                d["faces"] = r.faces;
                d["R0"] = r.R0;
                d["next_step"] = r.next_step;
                d["tri0"] = r.tri0;
                d["euler"] = r.euler;
                d["components"] = r.components;
                d["invariant_failures"] = r.invariant_failures;
                d["nonempty_balls"] = r.nonempty_balls;
                d["crease_edges"] = r.crease_edges;
                d["crease_lines"] = r.crease_lines;
                d["corners"] = r.corners;
                d["seconds_init"] = r.seconds;
                return d;
            },
            "What the start at t = 0 did (h0, the first mesh and how it was built, its topology).")
        .def_property_readonly(
            "report",
            [](const PyDeformingMesh& self) {
                const DeformingMesh& dm = self.get();
                py::dict d;
                d["time_units"] = dm.time();
                d["updates"] = dm.updates();
                put_counters(d, dm.totals());
                d["seconds_updates"] = dm.totals().seconds;
                d["samples"] = dm.live_samples();
                d["vertices"] = dm.mesh().n_vertices();
                d["violations"] = violations_by_kind(dm.violations());
                d["violation_examples"] = violations_list(examples_of(dm.violations()));
                return d;
            },
            "Totals over all updates so far (the field names of `dynmesh deform --report`).")
        .def(
            "check",
            [](const PyDeformingMesh& self, bool self_intersections) {
                return check_dict(self.get().check_invariants({.self_intersections = self_intersections}));
            },
            py::arg("self_intersections") = true,
            "The paper's invariants (closed manifold with the first mesh's topology, radius-edge\n"
            "ratios, spacing, dormant lists, empty diametric balls, no self-intersection): a dict\n"
            "with ok, problems and the measured figures.");
}

}  // namespace dynmesh::python
