// Skin surfaces of weighted atoms: molecule files, the static quality mesh and the growth.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "dict.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/skin/check.hpp"
#include "dynmesh/skin/growth.hpp"
#include "dynmesh/skin/molecule.hpp"
#include "dynmesh/skin/static_mesh.hpp"

namespace dynmesh::python {

namespace {

std::vector<Atom> atoms_of(const Doubles& centers, const Doubles& radii) {
    const std::vector<Point3> z = points3_of(centers, "centers");
    if (radii.ndim() != 1 || std::size_t(radii.shape(0)) != z.size())
        throw InvalidInput("radii must be a 1-D array with one radius per centre (" + std::to_string(z.size()) + ")");
    std::vector<Atom> atoms(z.size());
    for (std::size_t i = 0; i < z.size(); ++i) {
        atoms[i].center = z[i];
        atoms[i].radius = radii.at(py::ssize_t(i));
        if (!(atoms[i].radius > 0) || !std::isfinite(atoms[i].radius))
            throw InvalidInput("radii[" + std::to_string(i) + "] must be a positive number");
    }
    return atoms;
}

/// The mesh, ϱ at its vertices, and the report fields every skin run shares (`dynmesh skin`).
py::tuple skin_result(const SkinFunction& phi, const SurfaceMesh& mesh, std::vector<double>&& rho, double rho_floor,
                      const std::vector<bool>& exempt, py::dict rep, std::vector<std::string> problems = {}) {
    CheckReport chk;
    {
        py::gil_scoped_release unlocked;
        chk = check_skin_mesh(phi, mesh, {.rho_floor = rho_floor, .exempt = exempt});
    }
    rep["vertices"] = mesh.n_vertices();
    rep["triangles"] = mesh.n_faces();
    copy_figures(rep, chk,
                 {"euler", "components", "expected_euler", "expected_components", "min_angle_deg", "angle_floor_deg",
                  "frac_angles_below_15", "frac_angles_below_20", "frac_below_floor", "exempt_triangles",
                  "hausdorff_over_rho_max", "hausdorff_max", "normal_dev_max_deg", "normal_dev_mean_deg"});
    py::dict c;
    problems.insert(problems.end(), chk.problems.begin(), chk.problems.end());
    c["ok"] = problems.empty();
    c["problems"] = problems;
    rep["check"] = c;
    const py::tuple vf = compact_arrays_of(mesh);
    return py::make_tuple(vf[0], vf[1], adopt_flat(std::move(rho)), rep);
}

}  // namespace

void bind_skin(py::module_& m) {
    m.def(
        "read_molecule",
        [](const std::string& path, bool keep_water, bool keep_hydrogens) {
            MoleculeReadOptions ro;
            ro.keep_water = keep_water;
            ro.keep_hydrogens = keep_hydrogens;
            std::vector<Atom> atoms;
            {
                py::gil_scoped_release unlocked;
                atoms = read_molecule(path, RadiusTable::bondi(), ro);
            }
            std::vector<Point3> centers;
            std::vector<double> radii;
            for (const Atom& a : atoms) {
                centers.push_back(a.center);
                radii.push_back(a.radius);
            }
            return py::make_tuple(adopt<double, 3>(std::move(centers)), adopt_flat(std::move(radii)));
        },
        py::arg("path"), py::arg("keep_water") = false, py::arg("keep_hydrogens") = true,
        "Reads the atoms of a molecule (.pdb .cif .pqr .xyzr; Bondi radii by element);\n"
        "returns (centers (n, 3), radii (n,)).");

    m.def(
        "skin",
        [](const Doubles& centers, const Doubles& radii, double shrink) {
            const std::vector<WeightedPoint> balls = skin_weights(atoms_of(centers, radii), shrink);
            std::optional<SkinFunction> phi;
            SkinMeshResult r;
            {
                py::gil_scoped_release unlocked;
                phi.emplace(balls, shrink);
                r = mesh_skin(*phi);
            }
            py::dict rep;
            rep["mode"] = "static";
            rep["shrink"] = shrink;
            rep["atoms"] = balls.size();
            py::dict refinement;
            refinement["seeds"] = r.report.seeds;
            refinement["size"] = r.report.refined_size;
            refinement["shape"] = r.report.refined_shape;
            refinement["topology"] = r.report.refined_topology;
            refinement["rho_floor"] = r.report.rho_floor;
            rep["refinement"] = refinement;
            rep["seconds"] = r.report.seconds;
            return skin_result(*phi, r.mesh, std::move(r.rho), r.report.rho_floor, {}, rep);
        },
        py::arg("centers"), py::arg("radii"), py::arg("shrink") = 0.5,
        "The quality mesh of the skin of atoms (centers, radii) shrunk by `shrink`, as\n"
        "`dynmesh skin`: returns (vertices, faces, rho at each vertex, report).");

    m.def(
        "grow_skin",
        [](const Doubles& centers, const Doubles& radii, std::size_t snapshots, const std::string& schedule, bool audit) {
            if (schedule != "relaxed" && schedule != "every-step")
                throw InvalidInput("schedule must be 'relaxed' or 'every-step', not '" + schedule + "'");
            if (snapshots < 1 || snapshots > 100000) throw InvalidInput("snapshots must be in [1, 100000]");
            const std::vector<WeightedPoint> balls = skin_weights(atoms_of(centers, radii), 0.5);
            std::optional<SkinFunction> phi;
            SkinGrowthResult r;
            {
                py::gil_scoped_release unlocked;
                phi.emplace(balls, 0.5);
                SkinGrowthOptions go;
                go.schedule = schedule == "relaxed" ? SkinSchedule::Relaxed : SkinSchedule::EveryStep;
                go.snapshots = snapshots;
                go.audit = audit;
                r = grow_skin(*phi, go);
            }
            const SkinGrowthCounters& k = r.report.counters;
            py::dict rep;
            rep["mode"] = "grow";
            rep["shrink"] = 0.5;
            rep["atoms"] = balls.size();
            py::dict g;
            g["schedule"] = schedule;
            g["t_start"] = r.report.t_start;
            g["t_end"] = r.report.t_end;
            g["events"] = r.report.events;
            g["snapshots"] = r.report.snapshots;
            g["checks_edge"] = k.checks_edge;
            g["checks_triangle"] = k.checks_triangle;
            g["refused_contractions"] = k.refused_contractions;
            g["refused_insertions"] = k.refused_insertions;
            g["still_bad"] = k.still_bad;
            g["audit"] = audit;
            g["audit_samples"] = k.audit_samples;
            g["rho_floor"] = r.report.rho_floor;
            rep["growth"] = g;
            rep["checks"] = k.checks();
            rep["violations"] = k.violations;
            rep["born_bad"] = k.born_bad;
            py::dict actions;
            actions["contraction"] = k.contractions;
            actions["insertion"] = k.insertions;
            actions["flip"] = k.flips;
            actions["birth"] = k.births;
            actions["death"] = k.deaths;
            actions["neck"] = k.necks;
            actions["tunnel"] = k.tunnels;
            rep["actions"] = actions;
            rep["seconds"] = r.report.seconds;
            std::vector<std::string> missed;
            for (const std::string& e : r.report.violation_examples) missed.push_back("missed check: " + e);
            if (k.violations > r.report.violation_examples.size())
                missed.push_back(std::to_string(k.violations) + " missed checks in all");
            return skin_result(*phi, r.final.mesh, std::move(r.final.rho), r.report.rho_floor, r.final.exempt, rep,
                               std::move(missed));
        },
        py::arg("centers"), py::arg("radii"), py::arg("snapshots") = 10, py::arg("schedule") = "relaxed",
        py::arg("audit") = false,
        "Grows the skin (shrink 1/2) from the atoms' centres to their full radii, keeping the\n"
        "mesh good with relaxed scheduling, as `dynmesh skin --grow`: returns (vertices, faces,\n"
        "rho, report) at the end of the growth.");
}

}  // namespace dynmesh::python
