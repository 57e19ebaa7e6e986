/// \file `dynmesh probe`: mesh an unknown object by probing it with a ray-casting device that
/// moves only through free space (specs/probing.md).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/metrics/hausdorff.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "dynmesh/probing/refine.hpp"

namespace dynmesh::cli {
namespace {

struct ProbeArgs {
    std::string object, output;
    std::optional<double> eps, delta, eps_S;
    std::vector<std::string> interior;
    std::string omega;
    bool check = false;
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

void run_probe(const ProbeArgs& a, RunContext& ctx) {
    require_writable_mesh_extension(a.output);
    if (a.eps.has_value() == a.delta.has_value()) throw UsageError("give exactly one of --eps and --delta");
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
    RunOutputs outputs(a.common, {});
    const auto mesh_path = outputs.file(a.output, "-o");
    ctx.inputs_begin();

    Progress progress("probe", a.common.quiet);
    progress.stage("reading the object");
    const ProbeSetup setup = make_probe_object(a.object);
    const ProbeObject& object = *setup.object;
    ProbingOptions o;
    o.omega_center = omega ? omega->center : setup.omega.center;
    o.omega_radius = omega ? omega->radius : setup.omega.radius;
    o.interior_points = interior.empty() ? setup.interior_points : interior;
    if (a.eps_S) {
        o.eps_S = *a.eps_S;
    } else if (object.reach() > 0) {
        o.eps_S = object.reach();  // the analytic shapes know their reach
    } else {
        throw UsageError(a.object + ": --eps-s is required (a polyhedron has no reach to take it from)");
    }
    o.eps = a.eps ? *a.eps : probing_eps_from_delta(*a.delta, o.eps_S, o.omega_radius);
    if (a.check) o.ground_truth = &object;
    o.check_every = a.check ? 0 : SIZE_MAX;

    progress.stage("probing");
    const ProbingResult r = probe_surface(object, o);

    progress.stage("checking");
    const SurfaceMesh mesh = SurfaceMesh::from_soup(r.mesh);
    const MeshCheckReport mc = check_mesh(mesh, {.require_closed = true});
    std::optional<double> hausdorff;
    if (mesh.n_faces() > 0) {
        double to_s = 0;
        for (const Point3& p : mesh_sample_points(mesh, 2)) to_s = std::max(to_s, object.distance(p));
        const double from_s = max_distance_to_mesh(
            mesh, object.sample_surface(std::max(o.eps / 4, std::sqrt(object.area() / 2e5))));
        hausdorff = std::max(to_s, from_s);
    }
    std::vector<std::string> problems = r.problems;
    if (a.check) {
        if (!mc.ok()) problems.push_back("the output is not a closed oriented 2-manifold: " + mc.summary());
        if (mc.euler != object.euler_characteristic())
            problems.push_back("Euler characteristic " + std::to_string(mc.euler) + ", the object's is " +
                               std::to_string(object.euler_characteristic()));
        if (static_cast<int>(mc.components) != object.components())
            problems.push_back(std::to_string(mc.components) + " components, the object has " +
                               std::to_string(object.components()));
        if (r.report.max_ball_radius > o.eps)
            problems.push_back("a restricted ball of radius " + std::to_string(r.report.max_ball_radius) +
                               " exceeds eps = " + std::to_string(o.eps));
    }
    if (problems.empty()) require_valid_output(mesh, "probe");

    write_mesh(mesh, mesh_path);
    const ProbingReport& p = r.report;
    nlohmann::json rep = {{"command", "probe"},
                          {"object", a.object},
                          {"output", a.output},
                          {"eps", o.eps},
                          {"eps_S", o.eps_S},
                          {"omega", {{"center", {o.omega_center.x, o.omega_center.y, o.omega_center.z}},
                                     {"radius", o.omega_radius}}},
                          {"probes", p.probes},
                          {"probes_bootstrap", p.probes_bootstrap},
                          {"voronoi_edges_travelled", p.voronoi_edges_travelled},
                          {"detection_edges", p.detection_edges},
                          {"positioning_edges", p.positioning_edges},
                          {"path_length", p.path_length},
                          {"exterior_path_length", p.exterior_path_length},
                          {"cells_created", p.cells_created},
                          {"nodes_retained", p.nodes_retained},
                          {"grazing_hits", p.grazing_hits},
                          {"vertices", p.vertices},
                          {"facets", p.facets},
                          {"euler", mc.euler},
                          {"max_ball_radius", p.max_ball_radius},
                          {"seconds", p.seconds}};
    if (hausdorff) rep["hausdorff"] = *hausdorff;
    if (a.check) rep["check"] = {{"problems", problems}, {"segments_checked", p.segments_checked}};
    outputs.report(rep);
    outputs.commit();
    std::cout << "probe: " << p.vertices << " vertices, " << p.facets << " facets, Euler " << mc.euler << "; "
              << p.probes << " probes, " << p.voronoi_edges_travelled << " Voronoi edges travelled, "
              << p.seconds << " s\n  wrote " << a.output << "\n";
    if (!problems.empty())
        throw CheckFailed(std::to_string(problems.size()) + " problems: " + problems.front());
}

}  // namespace

void register_probe(CLI::App& root, int& result) {
    auto args = std::make_shared<ProbeArgs>();
    CLI::App* sub = root.add_subcommand(
        "probe",
        "Mesh an unknown object by probing it: a device that moves only through free space casts "
        "rays along Voronoi edges; Chew-style refinement until no restricted ball exceeds eps");
    sub->add_option("object", args->object,
                    "sphere:R, ellipsoid:a,b,c, torus:R,r, balls:FILE ('x y z r' lines), genus2, or a "
                    "closed triangle mesh file (then --eps-s is required)")
        ->required();
    sub->add_option("-o,--output", args->output, "The mesh (.off .obj .ply .vtk .vtp)")->required();
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
    sub->add_flag("--check", args->check,
                  "Verify every move of the device against the object, the invariants of the run, and "
                  "that the output is a closed 2-manifold of the object's topology with every ball <= eps");
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("probe", [&](RunContext& ctx) { run_probe(*args, ctx); }); });
}

}  // namespace dynmesh::cli
