/// `dynmesh stats` (quality measures) and `dynmesh check` (structural validation).
#include <cstdio>
#include <iostream>
#include <memory>

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

void run_stats(const StatsArgs& a, RunContext& ctx) {
    std::unique_ptr<ImplicitSurface> surface;
    if (!a.surface.empty()) surface = make_surface(a.surface);
    if (a.hausdorff && !surface && a.against.empty())
        throw UsageError("--hausdorff needs --surface or --against");
    RunOutputs out(a.common, {a.mesh, a.against});
    ctx.inputs_begin();
    Progress progress("stats", a.common.quiet);
    progress.stage("reading " + a.mesh);
    const SurfaceMesh mesh = load_mesh(a.mesh);
    QualityOptions opt;
    opt.surface = surface.get();
    opt.hausdorff = a.hausdorff && surface != nullptr;
    opt.self_intersections = a.self_intersections;
    progress.stage("measuring");
    const QualityReport q = mesh_quality(mesh, opt);
    nlohmann::json rep = {{"command", "stats"}, {"mesh", a.mesh}};
    if (surface) rep["surface"] = surface->spec();
    CheckReport figures;
    for (const auto& [name, value] : flatten(q)) figures.figures.push_back({name, value, quality_field_kind(name)});
    rep.update(check_json(figures));
    if (!a.against.empty()) {
        progress.stage("Hausdorff distance to " + a.against);
        const SurfaceMesh other = load_mesh(a.against);
        const HausdorffResult h = hausdorff(mesh, other);
        rep["hausdorff_to_mesh"] = h.distance;
        rep["against"] = a.against;
    }
    out.report(rep);
    out.commit();

    std::cout << a.mesh << ": " << q.vertices << " vertices, " << q.faces << " faces, "
              << q.edges << " edges, Euler " << q.euler << (q.closed ? ", closed" : ", open (")
              << (q.closed ? "" : std::to_string(q.boundary_edges) + " boundary edges)") << "\n";
    std::cout << "                          mean       sd      min      max\n";
    std::cout << "  angle (deg)         " << fmt(q.angle_deg) << "\n";
    std::cout << "  radius-edge ratio   " << fmt(q.radius_edge) << "\n";
    if (q.degenerate_faces > 0)
        std::cout << "  " << q.degenerate_faces
                  << " degenerate (zero-area) faces: their radius-edge ratio is infinite; mean and "
                     "sd are over the other faces\n";
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

void run_check(const CheckArgs& a, RunContext& ctx) {
    RunOutputs out(a.common, {a.mesh});
    ctx.inputs_begin();
    Progress progress("check", a.common.quiet);
    progress.stage("reading " + a.mesh);
    // A malformed file is a bad input (exit 3); triangles that do not form an oriented
    // 2-manifold are what `check` reports (exit 1).
    const TriangleSoup soup = read_soup(a.mesh);
    SurfaceMesh mesh;
    try {
        mesh = SurfaceMesh::from_soup(soup);
    } catch (const TopologyError& e) {
        std::string why = e.what();
        if (why.starts_with("from_soup: ")) why = why.substr(11);
        out.report({{"command", "check"}, {"mesh", a.mesh}, {"ok", false}, {"problems", {why}},
                    {"n_problems", 1}, {"vertices", soup.points.size()},
                    {"faces", soup.triangles.size()}});
        out.commit();
        std::cout << a.mesh << ": " << soup.points.size() << " V, " << soup.triangles.size()
                  << " F\n  problem: " << why << "\n";
        throw CheckFailed(a.mesh + ": not an oriented 2-manifold: " + why);
    }
    progress.stage("checking");
    const CheckReport r = check_mesh(mesh, {.require_closed = a.closed});
    nlohmann::json rep = check_json(r, {.ok = true,
                                        .problems = true,
                                        .n_problems = true,
                                        .leave_out = {"isolated_vertices", "non_manifold_vertices",
                                                      "duplicate_edges"}});
    rep["command"] = "check";
    rep["mesh"] = a.mesh;
    std::size_t si = 0;
    if (a.self_intersections) {
        progress.stage("self-intersection test");
        si = count_self_intersections(mesh);
        rep["self_intersections"] = si;
    }
    out.report(rep);
    out.commit();
    std::cout << a.mesh << ": " << r.integer("vertices") << " V, " << r.integer("edges") << " E, "
              << r.integer("faces") << " F, Euler " << r.integer("euler") << ", " << r.integer("components")
              << " component(s), "
              << (r.flag("closed") ? "closed" : std::to_string(r.integer("boundary_edges")) + " boundary edges")
              << "\n";
    std::cout << r.summary("  problem: ");
    if (a.self_intersections) std::cout << "  self-intersecting face pairs: " << si << "\n";
    if (!r.ok() || si > 0)
        throw CheckFailed(a.mesh + ": " + std::to_string(r.n_problems + si) + " problem(s) found");
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
    sub->callback([args, &result] { result = guarded("stats", [&](RunContext& ctx) { run_stats(*args, ctx); }); });
}

void register_check(CLI::App& root, int& result) {
    auto args = std::make_shared<CheckArgs>();
    CLI::App* sub = root.add_subcommand(
        "check", "Validate a mesh: manifoldness, orientation, closedness, Euler characteristic");
    sub->add_option("mesh", args->mesh, "Mesh file")->required();
    sub->add_flag("--closed", args->closed, "Boundary edges count as problems");
    sub->add_flag("--self-intersections", args->self_intersections, "Also test self-intersections");
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("check", [&](RunContext& ctx) { run_check(*args, ctx); }); });
}

}  // namespace dynmesh::cli
