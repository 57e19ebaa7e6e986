/// `dynmesh stats` (quality measures) and `dynmesh check` (structural validation).
#include <cstdio>
#include <iostream>
#include <memory>
#include <set>

#include "cli_common.hpp"
#include "commands.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/metrics/quality.hpp"
#include "dynmesh/metrics/self_intersection.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh::cli {

namespace {

struct StatsArgs {
    CommonOptions common;
    std::string mesh, surface, against;
    bool hausdorff = false, self_intersections = false, histograms = false;
};

std::string fmt(const Summary& s) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%8.3f %8.3f %8.3f %8.3f", s.mean, s.sd, s.min, s.max);
    return buf;
}

void run_stats(const StatsArgs& a) {
    check_report_path(a.common, {a.mesh, a.against});
    Progress progress("stats", a.common.quiet);
    progress.stage("reading " + a.mesh);
    const SurfaceMesh mesh = load_mesh(a.mesh);
    std::unique_ptr<ImplicitSurface> surface;
    if (!a.surface.empty()) surface = make_surface(a.surface);
    DYNMESH_CHECK(!a.hausdorff || surface || !a.against.empty(),
                  "--hausdorff needs --surface or --against");
    QualityOptions opt;
    opt.surface = surface.get();
    opt.hausdorff = a.hausdorff && surface != nullptr;
    opt.self_intersections = a.self_intersections;
    progress.stage("measuring");
    const QualityReport q = mesh_quality(mesh, opt);
    nlohmann::json rep = {{"command", "stats"}, {"mesh", a.mesh}};
    if (surface) rep["surface"] = surface->spec();
    static const std::set<std::string> counts = {"vertices", "faces", "edges", "euler",
                                                  "boundary_edges", "degenerate_faces",
                                                  "self_intersections"};
    for (const auto& [name, value] : flatten(q)) {
        if (counts.count(name))
            rep[name] = static_cast<long long>(value);
        else
            rep[name] = value;
    }
    rep["closed"] = q.closed;
    if (!a.against.empty()) {
        progress.stage("Hausdorff distance to " + a.against);
        const SurfaceMesh other = load_mesh(a.against);
        const HausdorffResult h = hausdorff(mesh, other);
        rep["hausdorff_to_mesh"] = h.distance;
        rep["against"] = a.against;
    }
    write_report(a.common, rep);

    std::cout << a.mesh << ": " << q.vertices << " vertices, " << q.faces << " faces, "
              << q.edges << " edges, Euler " << q.euler << (q.closed ? ", closed" : ", open (")
              << (q.closed ? "" : std::to_string(q.boundary_edges) + " boundary edges)") << "\n";
    std::cout << "                          mean       sd      min      max\n";
    std::cout << "  angle (deg)         " << fmt(q.angle_deg) << "\n";
    std::cout << "  radius-edge ratio   " << fmt(q.radius_edge) << "\n";
    std::cout << "  180 - dihedral (deg)" << fmt(q.dihedral_dev_deg) << "\n";
    if (q.normal_dev_deg) std::cout << "  normal dev. (deg)   " << fmt(*q.normal_dev_deg) << "\n";
    if (q.hausdorff_to_surface)
        std::cout << "  Hausdorff to " << surface->spec() << ": " << q.hausdorff_to_surface->distance << "\n";
    if (rep.contains("hausdorff_to_mesh"))
        std::cout << "  Hausdorff to " << a.against << ": " << rep["hausdorff_to_mesh"].get<double>() << "\n";
    if (q.self_intersecting_pairs)
        std::cout << "  self-intersecting face pairs: " << *q.self_intersecting_pairs << "\n";
    if (a.histograms) {
        std::cout << "  histogram of 180 - dihedral (deg):\n" << render_ascii(q.dihedral_dev_hist);
        if (q.normal_dev_hist)
            std::cout << "  histogram of normal deviation (deg):\n" << render_ascii(*q.normal_dev_hist);
    }
}

struct CheckArgs {
    CommonOptions common;
    std::string mesh;
    bool closed = false, self_intersections = false;
};

void run_check(const CheckArgs& a) {
    check_report_path(a.common, {a.mesh});
    Progress progress("check", a.common.quiet);
    progress.stage("reading " + a.mesh);
    const SurfaceMesh mesh = load_mesh(a.mesh);
    progress.stage("checking");
    const MeshCheckReport r = check_mesh(mesh, {.require_closed = a.closed});
    nlohmann::json rep = {{"command", "check"},      {"mesh", a.mesh},
                          {"ok", r.ok()},            {"problems", r.problems},
                          {"n_problems", r.n_problems}, {"vertices", r.vertices},
                          {"edges", r.edges},        {"faces", r.faces},
                          {"euler", r.euler},        {"closed", r.closed},
                          {"components", r.components}, {"boundary_edges", r.boundary_edges},
                          {"degenerate_faces", r.degenerate_faces}};
    std::size_t si = 0;
    if (a.self_intersections) {
        progress.stage("self-intersection test");
        si = count_self_intersections(mesh);
        rep["self_intersections"] = si;
    }
    write_report(a.common, rep);
    std::cout << a.mesh << ": " << r.vertices << " V, " << r.edges << " E, " << r.faces
              << " F, Euler " << r.euler << ", " << r.components << " component(s), "
              << (r.closed ? "closed" : std::to_string(r.boundary_edges) + " boundary edges") << "\n";
    std::cout << r.summary("  problem: ");
    if (a.self_intersections) std::cout << "  self-intersecting face pairs: " << si << "\n";
    if (!r.ok() || si > 0)
        throw TopologyError(a.mesh + ": " + std::to_string(r.n_problems + si) + " problem(s) found");
    std::cout << "  ok\n";
}

}  // namespace

void register_stats(CLI::App& root, int& result) {
    auto args = std::make_shared<StatsArgs>();
    CLI::App* sub = root.add_subcommand("stats", "Quality measures of a triangle mesh");
    sub->add_option("mesh", args->mesh, "Mesh file")->required();
    sub->add_option("--surface", args->surface,
                    "True surface for normal deviation / Hausdorff: sphere[:R], ellipsoid:a,b,c, "
                    "torus:R,r (optional @cx,cy,cz centre)");
    sub->add_option("--against", args->against, "Another mesh to measure the Hausdorff distance to");
    sub->add_flag("--hausdorff", args->hausdorff, "Two-sided Hausdorff distance to --surface");
    sub->add_flag("--self-intersections", args->self_intersections, "Count self-intersecting face pairs");
    sub->add_flag("--histograms", args->histograms, "Print histograms of the angle deviations");
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("stats", [&] { run_stats(*args); }); });
}

void register_check(CLI::App& root, int& result) {
    auto args = std::make_shared<CheckArgs>();
    CLI::App* sub = root.add_subcommand(
        "check", "Validate a mesh: manifoldness, orientation, closedness, Euler characteristic");
    sub->add_option("mesh", args->mesh, "Mesh file")->required();
    sub->add_flag("--closed", args->closed, "Boundary edges count as problems");
    sub->add_flag("--self-intersections", args->self_intersections, "Also test self-intersections");
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("check", [&] { run_check(*args); }); });
}

}  // namespace dynmesh::cli
