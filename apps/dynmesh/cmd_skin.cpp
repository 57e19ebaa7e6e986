/// \file `dynmesh skin`: the quality mesh of a molecule's skin surface (specs/skin-surfaces.md).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/geometry/format.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/skin/check.hpp"
#include "dynmesh/skin/molecule.hpp"
#include "dynmesh/skin/static_mesh.hpp"

namespace dynmesh::cli {
namespace {

namespace fs = std::filesystem;

struct SkinArgs {
    std::string molecule, output, radii;
    double shrink = 0.5;
    bool keep_water = false;
    bool no_hydrogens = false;
    std::string altloc = "A";
    int model = 1;
    bool check = false;
    CommonOptions common;
};

/// The triangles' smallest angles (degrees), per face in index order.
std::vector<double> face_min_angles(const SurfaceMesh& mesh) {
    std::vector<double> out;
    out.reserve(mesh.n_faces());
    for (Face f : mesh.faces()) {
        const auto v = mesh.face_vertices(f);
        out.push_back(rad_to_deg(min_angle(mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2]))));
    }
    return out;
}

void run_skin(const SkinArgs& a, RunContext& ctx) {
    if (!a.output.empty()) require_writable_mesh_extension(a.output);
    if (!(a.shrink > 0 && a.shrink < 1)) throw UsageError("--shrink must be in (0, 1)");
    if (a.altloc.size() != 1 || a.altloc[0] == ' ') throw UsageError("--altloc takes one character, e.g. A");
    if (a.model < 1) throw UsageError("--model must be at least 1");
    std::vector<fs::path> inputs{fs::path(a.molecule)};
    if (!a.radii.empty()) inputs.emplace_back(a.radii);
    RunOutputs outputs(a.common, inputs);
    const fs::path mesh_path = a.output.empty() ? fs::path{} : outputs.file(a.output, "-o");
    ctx.inputs_begin();

    Progress progress("skin", a.common.quiet);
    progress.stage("reading " + fs::path(a.molecule).filename().string());
    const RadiusTable radii = a.radii.empty() ? RadiusTable::bondi() : RadiusTable::read_csv(a.radii);
    MoleculeReadOptions ro;
    ro.keep_water = a.keep_water;
    ro.keep_hydrogens = !a.no_hydrogens;
    ro.altloc = a.altloc[0];
    ro.model = a.model;
    MoleculeReadReport read;
    const std::vector<Atom> atoms = read_molecule(a.molecule, radii, ro, &read);
    const std::vector<WeightedPoint> balls = skin_weights(atoms, a.shrink);

    progress.stage("building the mixed complex");
    const SkinFunction phi(balls, a.shrink);
    progress.stage("meshing the skin");
    SkinMeshOptions mo;
    mo.progress = [&](std::size_t vertices, std::size_t bad) {
        progress.detail(std::to_string(vertices) + " samples, " + std::to_string(bad) + " facets to refine");
    };
    const SkinMeshResult r = mesh_skin(phi, mo);
    progress.detail("");
    progress.stage("measuring the mesh");
    SkinMeshCheckOptions co;
    co.rho_floor = r.report.rho_floor;
    const SkinMeshCheck chk = check_skin_mesh(phi, r.mesh, co);

    progress.stage("writing");
    if (!mesh_path.empty()) {
        WriteOptions wo;
        wo.vertex_fields.push_back({"rho", r.rho});
        wo.face_fields.push_back({"min_angle_deg", face_min_angles(r.mesh)});
        write_mesh(r.mesh, mesh_path, wo);
    }
    nlohmann::json rep = {{"command", "skin"},
                          {"molecule", a.molecule},
                          {"format", read.format},
                          {"mode", "static"},
                          {"shrink", a.shrink},
                          {"atoms", atoms.size()},
                          {"skipped", {{"water", read.skipped_water},
                                       {"hydrogens", read.skipped_hydrogens},
                                       {"altloc", read.skipped_altloc}}},
                          {"unknown_radius", read.unknown_radius},
                          {"models", read.models},
                          {"vertices", r.mesh.n_vertices()},
                          {"triangles", r.mesh.n_faces()},
                          {"euler", chk.euler},
                          {"components", chk.components},
                          {"expected_euler", chk.expected_euler},
                          {"expected_components", chk.expected_components},
                          {"min_angle_deg", chk.min_angle_deg},
                          {"angle_floor_deg", chk.angle_floor_deg},
                          {"frac_angles_below_15", chk.frac_angles_below_15},
                          {"frac_angles_below_20", chk.frac_angles_below_20},
                          {"hausdorff_over_rho_max", chk.hausdorff_over_rho_max},
                          {"hausdorff_max", chk.hausdorff_max},
                          {"normal_dev_max_deg", chk.normal_dev_max_deg},
                          {"normal_dev_mean_deg", chk.normal_dev_mean_deg},
                          // A static mesh runs no scheduler: no checks, actions or violations.
                          {"checks", 0},
                          {"actions", nlohmann::json::object()},
                          {"violations", 0},
                          {"born_bad", nlohmann::json::object()},
                          {"refinement", {{"seeds", r.report.seeds},
                                          {"size", r.report.refined_size},
                                          {"shape", r.report.refined_shape},
                                          {"topology", r.report.refined_topology},
                                          {"locate_fallbacks", r.report.locate_fallbacks},
                                          {"rho_floor", r.report.rho_floor}}},
                          {"seconds", r.report.seconds}};
    if (a.check) rep["check"] = {{"problems", chk.problems}};
    outputs.report(rep);
    outputs.commit();
    if (!a.common.quiet) {
        std::ostringstream os;
        os << std::setprecision(3) << "skin: " << atoms.size() << " atoms, " << r.mesh.n_vertices() << " vertices, "
           << r.mesh.n_faces() << " triangles, Euler " << chk.euler << ", " << chk.components
           << " component(s); min angle " << chk.min_angle_deg << " deg, " << 100 * chk.frac_angles_below_15
           << "% under 15 deg; Hausdorff/rho " << chk.hausdorff_over_rho_max << "; " << r.report.seconds << " s\n";
        if (!a.output.empty()) os << "  wrote " << a.output << "\n";
        std::cout << os.str();
        for (const std::string& s : chk.problems) std::cout << "  check: " << s << "\n";
    }
    if (a.check && !chk.problems.empty())
        throw CheckFailed(std::to_string(chk.problems.size()) + " problem(s); first: " + chk.problems.front());
}

}  // namespace

void register_skin(CLI::App& root, int& result) {
    auto args = std::make_shared<SkinArgs>();
    CLI::App* sub = root.add_subcommand(
        "skin", "Mesh the skin surface of a molecule: a restricted Delaunay mesh whose triangles follow the "
                "length scale of the skin (circumradius <= C Q0 rho, angles >= 30 deg)");
    sub->add_option("molecule", args->molecule, "The molecule: .pdb/.ent, .cif/.mmcif (gemmi), .pqr or .xyzr")->required();
    sub->add_option("-o,--output", args->output,
                    "The mesh (.off .obj .ply .vtk .vtp); .ply/.vtk/.vtp carry the vertex field rho and the "
                    "face field min_angle_deg");
    sub->add_option("--shrink", args->shrink, "The shrink factor s in (0, 1) (default 0.5); weights are r^2/s")
        ->check(finite_number());
    sub->add_option("--radii", args->radii,
                    "A CSV table with columns symbol and radius (default: Bondi's van der Waals radii; PQR and "
                    "XYZR files carry their own)");
    sub->add_flag("--keep-water", args->keep_water, "Keep water molecules (skipped by default)");
    sub->add_flag("--no-hydrogens", args->no_hydrogens, "Skip hydrogen atoms");
    sub->add_option("--altloc", args->altloc,
                    "The alternate location kept besides blank ones (default A; the first one of a residue "
                    "without it)");
    sub->add_option("--model", args->model, "The model of a multi-model (NMR) file, 1-based (default 1)");
    sub->add_flag("--check", args->check,
                  "Exit 1 unless the mesh is a closed oriented manifold with the alpha complex's Euler "
                  "characteristic and components, every vertex on the skin, every angle >= asin(1/Q1^2), "
                  "mesh-to-skin distance <= (C Q1)^2 rho and normals within 25 deg");
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("skin", [&](RunContext& ctx) { run_skin(*args, ctx); }); });
}

}  // namespace dynmesh::cli
