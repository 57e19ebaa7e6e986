/// \file `dynmesh probe`: mesh an unknown object by probing it with a ray-casting device that
/// moves only through free space (specs/probing.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/geometry/format.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/io/points_io.hpp"
#include "dynmesh/probing/check.hpp"
#include "dynmesh/probing/device.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "dynmesh/probing/refine.hpp"

namespace dynmesh::cli {
namespace {

namespace fs = std::filesystem;

struct ProbeArgs {
    std::string object, output;
    std::optional<double> eps, delta, eps_S;
    std::vector<std::string> interior;
    std::string omega;
    int dim = 3;
    std::string mode = "device";
    std::string positioning = "lca";
    std::string out_dir, png, sample;
    std::size_t every = 200;
    std::size_t max_points = 2'000'000;
    bool check = false;
    bool strict = false;
    CommonOptions common;
};

/// "x,y,z" or "x,y,z,r" with finite numbers. \throw UsageError naming the option.
std::vector<double> parse_tuple(const std::string& text, std::size_t n, const std::string& option) {
    const std::optional<std::vector<double>> v = parse_number_list(text);
    if (!v)
        throw UsageError(option + " " + text + ": expected " + std::to_string(n) + " finite numbers separated by commas");
    if (v->size() != n)
        throw UsageError(option + " " + text + ": expected " + std::to_string(n) + " numbers, got " + std::to_string(v->size()));
    return *v;
}

/// "x,y,z" as the options take it, each number in its shortest round-trip form.
std::string format3(const Point3& p) {
    return format_number(p.x) + "," + format_number(p.y) + "," + format_number(p.z);
}

/// Is OBJECT a file (a mesh or a balls list) rather than an analytic spec?
/// \throw UsageError for a spec of an unknown kind ("cube:1").
std::optional<fs::path> object_file(const std::string& object) {
    if (object.starts_with("balls:")) return fs::path(object.substr(6));
    if (object == "genus2") return std::nullopt;
    for (const char* kind : {"sphere:", "ellipsoid:", "torus:", "circle2:", "star2:"})
        if (object.starts_with(kind)) return std::nullopt;
    if (object.empty() || object.find(':') != std::string::npos)
        throw UsageError("unknown object '" + object +
                         "' (expected sphere:R, ellipsoid:a,b,c, torus:R,r, balls:FILE, genus2, circle2:R, "
                         "star2:R or a mesh file)");
    return fs::path(object);
}

bool is_planar_object(const std::string& object) {
    return object.starts_with("circle2:") || object.starts_with("star2:");
}

/// The output (3D: the facets; 2D: the polygons) and, optionally, the device's path, as one
/// soup with polylines: the path's points follow the mesh's.
void add_path(TriangleSoup& soup, std::vector<std::vector<std::uint32_t>>& lines,
              const std::vector<std::vector<Point3>>& path) {
    for (const auto& pl : path) {
        if (pl.size() < 2) continue;
        std::vector<std::uint32_t> idx;
        for (const Point3& p : pl) {
            idx.push_back(static_cast<std::uint32_t>(soup.points.size()));
            soup.points.push_back(p);
        }
        lines.push_back(std::move(idx));
    }
}

void write_output(const ProbingResult& r, const fs::path& path, const std::vector<std::vector<Point3>>* device_path) {
    TriangleSoup soup = r.mesh;
    WriteOptions wo;
    wo.polylines = r.polygons;
    if (device_path != nullptr) add_path(soup, wo.polylines, *device_path);
    write_soup(soup, path, wo);
}

/// Draws the final output with the device's path (scripts/plot_probe.py).
void draw_png(const ProbingResult& r, const fs::path& png, const fs::path& scratch, const std::string& png_arg,
              const std::string& title) {
    const fs::path mesh = scratch / "mesh.obj", path = scratch / "path.obj";
    write_output(r, mesh, nullptr);
    TriangleSoup soup;
    WriteOptions wo;
    add_path(soup, wo.polylines, r.path);
    write_soup(soup, path, wo);
    run_plot_script("plot_probe.py", {png.string(), mesh.string(), path.string(), "--title", title}, "--png " + png_arg);
}

void run_probe(const ProbeArgs& a, RunContext& ctx) {
    require_writable_mesh_extension(a.output);
    if (a.eps.has_value() == a.delta.has_value()) throw UsageError("give exactly one of --eps and --delta");
    if (a.dim != 2 && a.dim != 3) throw UsageError("--dim must be 2 or 3");
    if (a.dim == 2 && lower_extension(a.output) == ".stl")
        throw UsageError("-o " + a.output + ": STL holds triangles only; a curve (--dim 2) goes to .off .obj .ply .vtk or .vtp");
    if (is_planar_object(a.object) != (a.dim == 2))
        throw UsageError(a.dim == 2 ? "--dim 2: the object must be a planar curve (circle2:R or star2:R), got " + a.object
                                    : a.object + " is a planar curve: give --dim 2");
    if (!a.png.empty()) require_png_output(a.png, "plot_probe.py");
    std::vector<Point3> interior;
    for (const std::string& s : a.interior) {
        const auto v = parse_tuple(s, 3, "--interior");
        interior.push_back({v[0], v[1], v[2]});
    }
    std::optional<Ball> omega;
    if (!a.omega.empty()) {
        const auto v = parse_tuple(a.omega, 4, "--omega");
        if (!(v[3] > 0)) throw UsageError("--omega " + a.omega + ": the radius must be > 0");
        omega = Ball{{v[0], v[1], v[2]}, v[3]};
    }
    const std::optional<fs::path> input = object_file(a.object);
    // An analytic object reads no file: a bad spec ("sphere:-1") is a usage error.
    std::optional<ProbeSetup> setup_holder;
    if (!input) setup_holder = make_probe_object(a.object, {.strict = a.strict});
    RunOutputs outputs(a.common, input ? std::vector<fs::path>{*input} : std::vector<fs::path>{});
    const fs::path mesh_path = outputs.file(a.output, "-o");
    const fs::path sample_path = a.sample.empty() ? fs::path{} : outputs.file(a.sample, "--sample");
    const fs::path png_path = a.png.empty() ? fs::path{} : outputs.file(a.png, "--png");
    const fs::path out_dir = a.out_dir.empty() ? fs::path{} : outputs.directory(a.out_dir, "--out");
    ctx.inputs_begin();

    Progress progress("probe", a.common.quiet);
    progress.stage("reading the object");
    if (!setup_holder) setup_holder = make_probe_object(a.object, {.strict = a.strict});
    const ProbeSetup& setup = *setup_holder;
    const ProbeObject& object = *setup.object;

    // Options, checked against what the object is (usage errors, exit 2).
    ProbingOptions o;
    o.omega = omega ? *omega : setup.omega;
    o.interior_points = interior.empty() ? setup.interior_points : interior;
    o.max_points = a.max_points;
    const std::string omega_arg = "--omega " + a.omega;
    if (a.dim == 2 && o.omega.center.z != 0) throw UsageError(omega_arg + ": a 2D run needs its centre at z = 0");
    // The object's own ball (1.1 times its bounding box's): Omega far larger than the object
    // would put clip points so far away that the probes lose their precision.
    if (omega && (o.omega.radius > 1e4 * setup.omega.radius ||
                  distance(o.omega.center, setup.omega.center) > 1e4 * setup.omega.radius))
        throw UsageError(omega_arg + ": Omega is more than 1e4 times larger than the object (radius " +
                         format_number(setup.omega.radius) + " around " + format_point(setup.omega.center) +
                         "): the probes would lose their precision");
    if (a.eps_S) {
        o.eps_S = *a.eps_S;
        if (object.reach() > 0 && o.eps_S > object.reach() * (1 + 1e-12))
            throw UsageError("--eps-s " + format_number(o.eps_S) + " exceeds the reach of " + a.object + ", " +
                             format_number(object.reach()) + ": it must be a lower bound of the reach");
    } else if (object.reach() > 0) {
        o.eps_S = object.reach();  // the analytic shapes know their reach
    } else {
        throw UsageError(a.object + ": --eps-s is required (a polyhedron has no reach to take it from)");
    }
    if (a.eps) o.eps = *a.eps;
    if (a.delta) o.delta = *a.delta;
    const double eps = o.eps > 0 ? o.eps : probing_eps_from_delta(*o.delta, o.eps_S, o.omega.radius);
    const std::string eps_arg =
        a.eps ? "--eps " + format_number(eps) : "--delta " + format_number(*a.delta) + " gives eps = " + format_number(eps) + ", which";
    if (!(eps < 0.091 * o.eps_S))
        throw UsageError(eps_arg + " is not below 0.091 * eps_S = " + format_number(0.091 * o.eps_S) +
                         ": the output would carry no guarantee");
    // The output size the paper predicts, N ~ 0.7 area / eps^2 (2D: length / eps), against
    // the cap on samples: refused up front rather than after a long run.
    const double expected = a.dim == 3 ? 0.7 * object.area() / (eps * eps) : object.area() / eps;
    if (!(expected <= static_cast<double>(o.max_points)))
        throw UsageError(eps_arg + " would need about " + format_number(std::round(expected)) +
                         " samples, more than --max-points " + std::to_string(o.max_points));
    for (const Point3& p : o.interior_points) {
        if (a.dim == 2 && p.z != 0) throw UsageError("--interior " + format3(p) + ": a 2D run needs z = 0");
        if (object.is_free(p))
            throw UsageError("--interior " + format3(p) + ": the point is not inside the object");
    }
    {
        // Every point of S is within `spacing` of a sample: the object reaches at most
        // max + spacing from the centre.
        const double spacing = o.omega.radius / 64;
        double reach = 0;
        for (const Point3& q : object.sample_surface(spacing)) reach = std::max(reach, distance(q, o.omega.center));
        reach += spacing;
        if (!(reach < o.omega.radius * (1 - 1e-6)))
            throw UsageError("--omega " + format3(o.omega.center) + "," + format_number(o.omega.radius) +
                             ": the object may reach " + format_number(reach) +
                             " from the centre (up to 1/64 of the radius): Omega must contain it with a margin");
    }
    o.mode = a.mode == "omniscient" ? ProbingMode::Omniscient : ProbingMode::Device;
    o.positioning = a.positioning == "boundary" ? ProbingPositioning::Boundary : ProbingPositioning::Lca;
    if (a.check || o.mode == ProbingMode::Omniscient) o.ground_truth = &object;
    o.check_every = a.check ? 0 : SIZE_MAX;
    o.record_path = !png_path.empty() || !out_dir.empty();

    std::vector<std::pair<double, std::string>> series;
    if (!out_dir.empty()) {
        o.snapshot_every = a.every;
        o.on_snapshot = [&](const ProbingSnapshot& s) {
            char name[64];
            std::snprintf(name, sizeof name, "probe_%07zu.vtp", s.insertions);
            TriangleSoup soup = *s.mesh;
            WriteOptions wo;
            wo.polylines = *s.polygons;
            add_path(soup, wo.polylines, *s.path);
            write_soup(soup, out_dir / name, wo);
            series.emplace_back(static_cast<double>(s.insertions), name);
        };
    }
    o.on_progress = [&](const ProbingProgress& p) {
        progress.detail(std::to_string(p.insertions) + " samples inserted, " + std::to_string(p.probes) + " probes");
    };

    progress.stage("probing");
    const ProbingResult r = a.dim == 3 ? probe_surface(object, o) : probe_curve(object, o);

    progress.stage("checking");
    const CheckReport chk = check_probing(r, object, o, a.dim);
    // Without --check a broken topology still fails the run (every exit-0 output is a closed
    // manifold); with it, every check counts.
    std::vector<std::string> problems;
    if (a.check) {
        problems = chk.problems;
    } else if (!chk.flag("closed_manifold")) {
        problems.push_back("the output is not a closed manifold (run with --check for the details)");
    }

    progress.stage("writing");
    write_output(r, mesh_path, nullptr);
    if (!sample_path.empty()) write_points_xyz(r.sample, sample_path);
    if (!out_dir.empty()) {
        write_pvd(out_dir / "probe.pvd", series);
        TriangleSoup soup;
        WriteOptions wo;
        add_path(soup, wo.polylines, r.path);
        write_soup(soup, out_dir / "path.vtp", wo);
    }
    if (!png_path.empty()) {
        progress.stage("drawing " + a.png);
        char title[256];
        const std::string name = input ? input->filename().string() : a.object;
        std::snprintf(title, sizeof title, "%s, eps %.4g: %zu probes, path %.4g inside Omega", name.c_str(),
                      r.report.eps, r.report.probes, r.report.path_length);
        draw_png(r, png_path, outputs.scratch(a.png), a.png, title);
    }
    const ProbingReport& p = r.report;
    nlohmann::json rep = {{"command", "probe"},
                          {"object", a.object},
                          {"dim", a.dim},
                          {"mode", a.mode},
                          {"positioning", a.positioning},
                          {"output", a.output},
                          {"eps", p.eps},
                          {"eps_S", o.eps_S},
                          {"omega", {{"center", {o.omega.center.x, o.omega.center.y, o.omega.center.z}},
                                     {"radius", o.omega.radius}}},
                          {"interior_points", nlohmann::json::array()},
                          {"probes", p.probes},
                          {"probes_bootstrap", p.probes_bootstrap},
                          {"probes_inferred", p.probes_inferred},
                          {"voronoi_edges_travelled", p.voronoi_edges_travelled},
                          {"detection_edges", p.detection_edges},
                          {"positioning_edges", p.positioning_edges},
                          {"voronoi_edges_created", p.voronoi_edges_created},
                          {"path_length", p.path_length},
                          {"exterior_path_length", p.exterior_path_length},
                          {"cells_created", p.cells_created},
                          {"nodes_retained", p.nodes_retained},
                          {"activations", p.activations},
                          {"detect_access_calls", p.detect_access_calls},
                          {"insertions", p.insertions},
                          {"queue_pushes", p.queue_pushes},
                          {"stale_pops", p.stale_pops},
                          {"nonempty_pops", p.nonempty_pops},
                          {"grazing_hits", p.grazing_hits},
                          {"reinitialisations", p.reinitialisations},
                          {"vertices", p.vertices},
                          {"facets", p.facets},
                          {"seconds", p.seconds}};
    rep.update(check_json(chk, {.leave_out = {"closed_manifold"}}));
    if (!chk.flag("closed_manifold")) rep["hausdorff"] = nullptr;  // measured only on a closed manifold
    if (o.delta) rep["delta"] = *o.delta;
    for (const Point3& q : o.interior_points) rep["interior_points"].push_back({q.x, q.y, q.z});
    if (a.check) rep["check"] = {{"problems", problems}, {"segments_checked", p.segments_checked}};
    outputs.report(rep);
    outputs.commit();
    if (!a.common.quiet) {
        // Three significant digits for people; the report has every digit.
        const auto short_number = [](double v) {
            std::ostringstream os;
            os << std::setprecision(3) << v;
            return os.str();
        };
        std::cout << "probe: " << p.vertices << " vertices, " << p.facets << (a.dim == 3 ? " facets" : " edges")
                  << ", Euler " << chk.integer("euler") << ", Hausdorff "
                  << (chk.flag("closed_manifold") ? short_number(chk.figure("hausdorff")) : std::string("n/a"))
                  << " (bound " << short_number(chk.figure("hausdorff_bound")) << "); " << p.probes << " probes, "
                  << p.voronoi_edges_travelled << " Voronoi edges travelled, path " << std::fixed << std::setprecision(1) << p.path_length << std::defaultfloat
                  << ", " << short_number(p.seconds) << " s\n  wrote " << a.output << "\n";
        for (const std::string& s : problems) std::cout << "  check: " << s << "\n";
        if (!a.check && chk.flag("closed_manifold") && chk.figure("hausdorff") > chk.figure("hausdorff_bound"))
            std::cerr << "dynmesh probe: warning: the Hausdorff distance exceeds the bound: eps_S is not a lower "
                         "bound of the reach, or a component cannot be reached from outside Omega (run with "
                         "--check)\n";
    }
    if (!problems.empty())
        throw CheckFailed(std::to_string(problems.size()) + " problem(s); first: " + problems.front());
}

}  // namespace

void register_probe(CLI::App& root, int& result) {
    auto args = std::make_shared<ProbeArgs>();
    CLI::App* sub = root.add_subcommand(
        "probe",
        "Mesh an unknown object by probing it: a device that moves only through free space casts "
        "rays along Voronoi edges; Chew-style refinement until no restricted ball exceeds eps");
    sub->add_option("object", args->object,
                    "sphere:R, ellipsoid:a,b,c, torus:R,r, balls:FILE ('x y z r' lines, disjoint), genus2, a "
                    "closed triangle mesh file (then --eps-s is required), or with --dim 2 the planar "
                    "curves circle2:R, star2:R")
        ->required();
    sub->add_option("-o,--output", args->output,
                    "The mesh (.off .obj .ply .stl .vtk .vtp); with --dim 2 the closed polyline in the same formats but .stl")
        ->required();
    sub->add_option("--eps", args->eps, "Refinement size: no restricted Delaunay ball larger than this")
        ->check(finite_number())
        ->check(CLI::PositiveNumber);
    sub->add_option("--delta", args->delta,
                    "Target Hausdorff distance instead of --eps: eps = eps_S sqrt(delta / (9 R_Omega))")
        ->check(finite_number())
        ->check(CLI::PositiveNumber);
    sub->add_option("--eps-s", args->eps_S,
                    "A lower bound on the reach of the surface (default: the analytic object's reach)")
        ->check(finite_number())
        ->check(CLI::PositiveNumber);
    sub->add_option("--interior", args->interior,
                    "x,y,z: a point inside the object (repeatable, one per component; default: the "
                    "object's own)");
    sub->add_option("--omega", args->omega,
                    "cx,cy,cz,r: a ball containing the object with a margin (default: around its "
                    "bounding box)");
    sub->add_option("--dim", args->dim, "2 for a closed planar curve (circle2:R, star2:R), 3 for a surface")
        ->check(CLI::IsMember({2, 3}));
    sub->add_option("--mode", args->mode,
                    "device: the paper's moving device; omniscient: the same refinement testing every "
                    "Voronoi edge from anywhere, without moving (the baseline)")
        ->check(CLI::IsMember({"device", "omniscient"}));
    sub->add_option("--positioning", args->positioning,
                    "How the device reaches the next node to probe from: lca (through the lowest common "
                    "ancestor of the two nodes' free paths when they share one, default) or boundary "
                    "(always out to the boundary of Omega and back in)")
        ->check(CLI::IsMember({"lca", "boundary"}));
    sub->add_option("--out", args->out_dir,
                    "Directory for a ParaView series of the refinement (probe.pvd, probe_NNNNNNN.vtp every "
                    "--every insertions with the device's path since the previous one) and path.vtp");
    sub->add_option("--every", args->every, "Insertions between two --out snapshots (default 200)")
        ->check(CLI::Range(std::size_t{1}, std::size_t{1'000'000'000}));
    sub->add_option("--max-points", args->max_points,
                    "Refuse a run that needs more samples than this (default 2,000,000; the expected number "
                    "is about 0.7 area / eps^2)")
        ->check(CLI::Range(std::size_t{4}, std::size_t{1'000'000'000}));
    sub->add_option("--png", args->png, "Picture of the final mesh with the device's path");
    sub->add_option("--sample", args->sample, "The sample (x y z lines)");
    sub->add_flag("--strict", args->strict,
                  "Ignore grazing (tangent) contacts instead of reporting them as hits (the paper's model)");
    sub->add_flag("--check", args->check,
                  "Verify every move of the device against the object, the invariants of the run, and "
                  "that the output is a closed manifold of the object's topology, every ball <= eps, a "
                  "2eps-sample, Hausdorff within 4.5 diam eps^2 / eps_S^2");
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("probe", [&](RunContext& ctx) { run_probe(*args, ctx); }); });
}

}  // namespace dynmesh::cli
