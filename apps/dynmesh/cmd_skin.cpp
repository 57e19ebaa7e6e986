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
#include "dynmesh/io/text_file.hpp"
#include "dynmesh/skin/check.hpp"
#include "dynmesh/skin/growth.hpp"
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
    bool grow = false;
    std::size_t steps = 10;
    std::string schedule = "relaxed";
    double step = 0;
    std::string out, png;
    bool audit = false;
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

/// The mesh a run ends with, however it was made.
struct SkinOutcome {
    SurfaceMesh mesh;
    std::vector<double> rho;
    std::vector<bool> exempt;
    double rho_floor = 0;
    double seconds = 0;
    nlohmann::json details;                 ///< mode-specific report fields
    nlohmann::json checks = 0, actions = nlohmann::json::object(), born_bad = nlohmann::json::object();
    std::size_t violations = 0;
    std::vector<std::string> problems;      ///< from the growth (snapshots, misses)
};

std::vector<double> exempt_field(const std::vector<bool>& exempt, std::size_t faces) {
    std::vector<double> out(faces, 0.0);
    for (std::size_t i = 0; i < std::min(faces, exempt.size()); ++i) out[i] = exempt[i] ? 1.0 : 0.0;
    return out;
}

WriteOptions mesh_fields(const SurfaceMesh& mesh, const std::vector<double>& rho, const std::vector<bool>& exempt) {
    WriteOptions wo;
    wo.vertex_fields.push_back({"rho", rho});
    wo.face_fields.push_back({"min_angle_deg", face_min_angles(mesh)});
    if (!exempt.empty()) wo.face_fields.push_back({"exempt", exempt_field(exempt, mesh.n_faces())});
    return wo;
}

SkinOutcome static_mesh(const SkinFunction& phi, Progress& progress) {
    progress.stage("meshing the skin");
    SkinMeshOptions mo;
    mo.progress = [&](std::size_t vertices, std::size_t bad) {
        progress.detail(std::to_string(vertices) + " samples, " + std::to_string(bad) + " facets to refine");
    };
    SkinMeshResult r = mesh_skin(phi, mo);
    progress.detail("");
    SkinOutcome o;
    o.mesh = std::move(r.mesh);
    o.rho = std::move(r.rho);
    o.rho_floor = r.report.rho_floor;
    o.seconds = r.report.seconds;
    o.details = {{"mode", "static"},
                 {"refinement", {{"seeds", r.report.seeds},
                                 {"size", r.report.refined_size},
                                 {"shape", r.report.refined_shape},
                                 {"topology", r.report.refined_topology},
                                 {"locate_fallbacks", r.report.locate_fallbacks},
                                 {"rho_floor", r.report.rho_floor}}}};
    return o;
}

SkinOutcome grown_mesh(const SkinArgs& a, const SkinFunction& phi, const fs::path& out_dir, Progress& progress) {
    progress.stage("growing the skin");
    SkinGrowthOptions go;
    go.schedule = a.schedule == "every-step" ? SkinSchedule::EveryStep : SkinSchedule::Relaxed;
    go.snapshots = a.steps;
    go.audit = a.audit;
    go.fixed_step = a.step;
    const double t0 = skin_growth_start(phi, go);
    if (a.step > 0 && a.step < SkinGrowthOptions::kMinFixedStep * (go.t_end - t0))
        throw UsageError("--step " + format_number(a.step) + " is under " +
                         format_number(SkinGrowthOptions::kMinFixedStep) + " of the growth's time span (" +
                         format_number(go.t_end - t0) + ")");
    go.progress = [&](double t) { progress.detail("t = " + format_number(t) + " of [" + format_number(t0) + ", 0]"); };
    std::vector<std::pair<double, std::string>> series;
    std::vector<std::string> problems;
    std::size_t frame = 0;
    go.on_snapshot = [&](const SkinSnapshot& snap) {
        ++frame;
        if (a.check && snap.mesh.n_faces() > 0) {
            SkinMeshCheckOptions co;
            co.time = snap.time;
            co.exempt = snap.exempt;
            for (const std::string& p : check_skin_mesh(phi, snap.mesh, co).problems)
                problems.push_back("t = " + format_number(snap.time) + ": " + p);
        }
        if (out_dir.empty()) return;
        char name[32];
        std::snprintf(name, sizeof name, "skin_%05zu.vtp", frame);
        write_mesh(snap.mesh, out_dir / name, mesh_fields(snap.mesh, snap.rho, snap.exempt));
        series.emplace_back(snap.time, name);
    };
    SkinGrowthResult r = grow_skin(phi, go);
    progress.detail("");
    if (!out_dir.empty()) write_pvd(out_dir / "skin.pvd", series);
    const SkinGrowthCounters& k = r.report.counters;
    SkinOutcome o;
    o.mesh = std::move(r.final.mesh);
    o.rho = std::move(r.final.rho);
    o.exempt = std::move(r.final.exempt);
    o.rho_floor = r.report.rho_floor;
    o.seconds = r.report.seconds;
    o.checks = k.checks();
    o.actions = {{"contraction", k.contractions}, {"insertion", k.insertions}, {"flip", k.flips},
                 {"birth", k.births},             {"death", k.deaths},         {"neck", k.necks},
                 {"tunnel", k.tunnels}};
    o.born_bad = k.born_bad;
    o.violations = k.violations;
    for (const std::string& e : r.report.violation_examples) problems.push_back("missed check: " + e);
    if (k.violations > r.report.violation_examples.size())
        problems.push_back(std::to_string(k.violations) + " missed checks in all");
    o.problems = std::move(problems);
    o.details = {{"mode", "grow"},
                 {"growth", {{"schedule", schedule_name(go.schedule)},
                             {"t_start", r.report.t_start},
                             {"t_end", r.report.t_end},
                             {"events", r.report.events},
                             {"snapshots", r.report.snapshots},
                             {"checks_edge", k.checks_edge},
                             {"checks_triangle", k.checks_triangle},
                             {"steps", k.steps},
                             {"fixed_step", a.step},
                             {"refused_contractions", k.refused_contractions},
                             {"refused_insertions", k.refused_insertions},
                             {"deferred", k.deferred},
                             {"still_bad", k.still_bad},
                             {"fallbacks", k.fallbacks},
                             {"flow_fallbacks", k.flow_fallbacks},
                             {"evaluations", k.evaluations},
                             {"heap_pushes", k.heap_pushes},
                             {"audit", a.audit},
                             {"audit_samples", k.audit_samples},
                             {"fallback_reasons", r.report.fallback_reasons},
                             {"rho_floor", r.report.rho_floor}}}};
    return o;
}

/// Draws the mesh coloured by ϱ (scripts/plot_skin.py).
void draw_png(const SkinOutcome& o, const fs::path& png, const fs::path& scratch, const std::string& png_arg,
              const std::string& title) {
    const fs::path mesh = scratch / "mesh.obj", rho = scratch / "rho.txt";
    write_mesh(o.mesh, mesh);
    std::ostringstream os;
    os << std::setprecision(9);
    for (double r : o.rho) os << r << "\n";
    write_text_file(rho, os.str());
    run_plot_script("plot_skin.py", {png.string(), mesh.string(), rho.string(), "--title", title}, "--png " + png_arg);
}

void run_skin(const SkinArgs& a, RunContext& ctx) {
    if (!a.output.empty()) require_writable_mesh_extension(a.output);
    if (!(a.shrink > 0 && a.shrink < 1)) throw UsageError("--shrink must be in (0, 1)");
    if (a.altloc.size() != 1 || a.altloc[0] == ' ') throw UsageError("--altloc takes one character, e.g. A");
    if (a.model < 1) throw UsageError("--model must be at least 1");
    if (a.schedule != "relaxed" && a.schedule != "every-step")
        throw UsageError("--schedule must be relaxed or every-step, got '" + a.schedule + "'");
    if (!(std::isfinite(a.step) && a.step >= 0))
        throw UsageError("--step must be a positive time step (or 0: the adaptive step)");
    if (a.step > 0 && (!a.grow || a.schedule != "every-step"))
        throw UsageError("--step needs --grow --schedule every-step");
    if (!a.grow && (!a.out.empty() || a.audit))
        throw UsageError(std::string(a.audit ? "--audit" : "--out") + " needs --grow");
    if (a.grow && a.shrink != 0.5) throw UsageError("--grow needs --shrink 0.5 (the growth model is for s = 1/2)");
    if (a.grow && (a.steps < 1 || a.steps > 100000)) throw UsageError("--steps must be in [1, 100000]");
    if (!a.png.empty()) require_png_output(a.png, "plot_skin.py");
    std::vector<fs::path> inputs{fs::path(a.molecule)};
    if (!a.radii.empty()) inputs.emplace_back(a.radii);
    RunOutputs outputs(a.common, inputs);
    const fs::path mesh_path = a.output.empty() ? fs::path{} : outputs.file(a.output, "-o");
    const fs::path png_path = a.png.empty() ? fs::path{} : outputs.file(a.png, "--png");
    const fs::path out_dir = a.out.empty() ? fs::path{} : outputs.directory(a.out, "--out");
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
    // A .cin file (CGAL's skin input) holds the ball set itself: x y z w per line, w = r^2.
    const bool weighted = lower_extension(a.molecule) == ".cin";
    std::vector<WeightedPoint> balls;
    if (weighted) {
        balls = read_weighted_points(a.molecule);
        read.format = "cin";
    } else {
        balls = skin_weights(read_molecule(a.molecule, radii, ro, &read), a.shrink);
    }

    progress.stage("building the mixed complex");
    const SkinFunction phi(balls, a.shrink);
    SkinOutcome o = a.grow ? grown_mesh(a, phi, out_dir, progress) : static_mesh(phi, progress);
    progress.stage("measuring the mesh");
    SkinMeshCheckOptions co;
    co.rho_floor = o.rho_floor;
    co.exempt = o.exempt;
    const CheckReport chk = check_skin_mesh(phi, o.mesh, co);
    std::vector<std::string> problems = o.problems;
    problems.insert(problems.end(), chk.problems.begin(), chk.problems.end());

    progress.stage("writing");
    if (!mesh_path.empty()) write_mesh(o.mesh, mesh_path, mesh_fields(o.mesh, o.rho, o.exempt));
    if (!png_path.empty()) {
        progress.stage("drawing " + a.png);
        draw_png(o, png_path, outputs.scratch(a.png), a.png,
                 fs::path(a.molecule).filename().string() + (a.grow ? " grown" : "") + ": " +
                     std::to_string(o.mesh.n_vertices()) + " vertices, coloured by rho");
    }
    nlohmann::json rep = {{"command", "skin"},
                          {"molecule", a.molecule},
                          {"format", read.format},
                          {"shrink", a.shrink},
                          {"atoms", balls.size()},
                          {"skipped", {{"water", read.skipped_water},
                                       {"hydrogens", read.skipped_hydrogens},
                                       {"altloc", read.skipped_altloc}}},
                          {"unknown_radius", read.unknown_radius},
                          {"models", read.models},
                          {"vertices", o.mesh.n_vertices()},
                          {"triangles", o.mesh.n_faces()},
                          // A static mesh runs no scheduler: no checks, actions or violations.
                          {"checks", o.checks},
                          {"actions", o.actions},
                          {"violations", o.violations},
                          {"born_bad", o.born_bad},
                          {"seconds", o.seconds}};
    rep.update(check_json(chk, {.leave_out = {"vertex_offset_max", "inward_faces"}}));
    rep.update(o.details);
    if (a.check) rep["check"] = {{"problems", problems}};
    outputs.report(rep);
    outputs.commit();
    if (!a.common.quiet) {
        std::ostringstream os;
        os << std::setprecision(3) << "skin: " << balls.size() << (weighted ? " balls, " : " atoms, ") << o.mesh.n_vertices() << " vertices, "
           << o.mesh.n_faces() << " triangles, Euler " << chk.integer("euler") << ", " << chk.integer("components")
           << " component(s); min angle " << chk.figure("min_angle_deg") << " deg, "
           << 100 * chk.figure("frac_angles_below_15")
           << "% under 15 deg; Hausdorff/rho " << chk.figure("hausdorff_over_rho_max") << "; " << o.seconds << " s\n";
        if (a.grow)
            os << "  growth (" << a.schedule << "): " << o.checks << " checks, " << o.actions.dump() << ", "
               << o.violations << " missed, born bad " << o.born_bad.dump() << "\n";
        if (!a.output.empty()) os << "  wrote " << a.output << "\n";
        if (!a.out.empty()) os << "  wrote " << a.out << "/skin.pvd\n";
        if (!a.png.empty()) os << "  wrote " << a.png << "\n";
        std::cout << os.str();
        for (const std::string& p : problems) std::cout << "  check: " << p << "\n";
    }
    if (a.check && !problems.empty())
        throw CheckFailed(std::to_string(problems.size()) + " problem(s); first: " + problems.front());
}

}  // namespace

void register_skin(CLI::App& root, int& result) {
    auto args = std::make_shared<SkinArgs>();
    CLI::App* sub = root.add_subcommand(
        "skin", "Mesh the skin surface of a molecule: a restricted Delaunay mesh whose triangles follow the "
                "length scale of the skin (circumradius <= C Q0 rho, angles >= 30 deg)");
    sub->add_option("molecule", args->molecule, "The molecule: .pdb/.ent, .cif/.mmcif (gemmi), .pqr or .xyzr; or the ball set itself as .cin (x y z w per line, w = r^2, as CGAL's skin examples)")->required();
    sub->add_option("-o,--output", args->output,
                    "The mesh (.off .obj .ply .stl .vtk .vtp); .ply/.vtk/.vtp carry the vertex field rho and the "
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
    sub->add_flag("--grow", args->grow,
                  "Grow the skin: every weight grows with time t from before the first atom is born to t = 0, "
                  "and the mesh is kept through every topology change (needs --shrink 0.5)");
    sub->add_option("--steps", args->steps, "With --grow: snapshots at equal time steps, the last at t = 0 (default 10)");
    sub->add_option("--schedule", args->schedule,
                    "With --grow: relaxed (each edge and triangle checked when its safe duration runs out) or "
                    "every-step (every element checked at every global step; the baseline)");
    sub->add_option("--step", args->step,
                    "With --schedule every-step: a fixed global time step instead of the smallest safe duration "
                    "in the mesh (misses it lets through are counted as violations)");
    sub->add_option("--out", args->out,
                    "With --grow: a directory for the ParaView series skin.pvd + skin_NNNNN.vtp (vertex field rho, "
                    "face fields min_angle_deg and exempt)");
    sub->add_flag("--audit", args->audit,
                  "With --grow: also evaluate every element at 20 times between its checks and count a crossing "
                  "of the Q1 bounds as a violation (about 20 times the work)");
    sub->add_option("--png", args->png, "A picture of the final mesh coloured by the length scale rho");
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("skin", [&](RunContext& ctx) { run_skin(*args, ctx); }); });
}

}  // namespace dynmesh::cli
