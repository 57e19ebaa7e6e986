/// `dynmesh flip` and `dynmesh worsen`: edge-flip smoothing and the paper's worsening.
#include <cctype>
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/flips/diagnostics.hpp"
#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/flips/worsen.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/io/text_inputs.hpp"
#include "dynmesh/mesh/check.hpp"

namespace dynmesh::cli {

namespace {

struct FlipArgs {
    CommonOptions common;
    std::string input, output, criterion = "angle";
    std::size_t max_flips_per_vertex = 100;
    double feature_angle_deg = 180.0;
    std::string vertices_file;  ///< --vertices: flip locally around these vertex indices
    std::string reorder = "auto";
    bool check = false;
};

/// The --vertices file as vertex handles.
std::vector<Vertex> read_vertices(const std::string& path, const SurfaceMesh& mesh) {
    std::vector<Vertex> out;
    for (std::uint32_t v : read_vertex_list(path, mesh.n_vertices())) out.push_back(Vertex(v));
    return out;
}

void run_flip(const FlipArgs& a, RunContext& ctx) {
    using Clock = std::chrono::steady_clock;
    const FlipRule rule = parse_flip_rule(a.criterion);
    require_writable_mesh_extension(a.output);
    RunOutputs out(a.common, {a.input, a.vertices_file});
    const std::filesystem::path mesh_out = out.file(a.output, "-o");
    ctx.inputs_begin();
    Progress progress("flip", a.common.quiet);
    progress.stage("reading " + a.input);
    auto t0 = Clock::now();
    SurfaceMesh mesh = load_mesh(a.input);
    require_closed_manifold(mesh, a.input);
    const double seconds_read = seconds_since(t0);

    progress.stage("flipping");
    FlipOptions opt{.rule = rule,
                    .max_flips_per_vertex = a.max_flips_per_vertex,
                    .feature_angle_deg = a.feature_angle_deg};
    opt.reorder = a.reorder == "always" ? FlipReorder::Always
                  : a.reorder == "never" ? FlipReorder::Never
                                         : FlipReorder::Auto;
    opt.progress = [&](std::size_t flips, std::size_t queued) {
        progress.detail(std::to_string(flips) + " flips, " + std::to_string(queued) + " queued");
    };
    FlipReport r;
    nlohmann::json local;
    std::vector<Vertex> V;  // --vertices
    LocalFlipReport lr;
    std::optional<SurfaceMesh> before;
    if (a.vertices_file.empty()) {
        r = flip_all(mesh, opt);
    } else {
        V = read_vertices(a.vertices_file, mesh);
        if (a.check) before = mesh;  // the local-mode check compares with the input
        lr = flip_local(mesh, V, {.rule = rule,
                                  .feature_angle_deg = a.feature_angle_deg,
                                  .max_flips_per_vertex = a.max_flips_per_vertex});
        r = lr.flips;
        local = {{"vertices_given", V.size()},
                 {"rounds", lr.rounds},
                 {"final_m", lr.final_m},
                 {"changed_faces", lr.changed_faces.size()},
                 {"window_vertices", lr.window_vertices},
                 {"ring_faces", lr.ring_faces},
                 {"ball_tests", lr.ball_tests},
                 {"unchecked_balls", lr.unchecked_balls},
                 {"ball_check", "ring outside the window (grid over ring triangles)"}};
    }

    nlohmann::json rep = {{"command", "flip"},
                          {"input", a.input},
                          {"output", a.output},
                          {"criterion", std::string(to_string(rule))},
                          {"vertices", mesh.n_vertices()},
                          {"faces", mesh.n_faces()},
                          {"edges", mesh.n_edges()},
                          {"flips", r.flips},
                          {"checks", r.checks},
                          {"pushes", r.pushes},
                          {"degenerate_tests", r.degenerate},
                          {"not_improving_tests", r.not_improving},
                          {"feature_angle_deg", a.feature_angle_deg},
                          {"feature_locked_tests", r.feature_locked},
                          {"converged", r.converged},
                          {"renumbered", r.renumbered},
                          {"seconds_flip", r.seconds},
                          {"seconds_read", seconds_read}};
    if (!local.is_null()) rep["local"] = local;
    bool check_ok = true;
    if (a.check) {
        progress.stage("checking");
        const CheckReport c = check_mesh(mesh, {.require_closed = true});
        const FlipDiagnostics d = flip_diagnostics(mesh, rule);
        // Global mode: a second pass with the same options must flip nothing. Local mode: no
        // edge at a given vertex may be flippable (farther edges may be, by design).
        std::size_t second = 0;
        if (a.vertices_file.empty()) {
            SurfaceMesh again = mesh;
            second = flip_all(again, opt).flips;
        } else {
            for (Vertex v : V)
                for (Halfedge h : mesh.outgoing_halfedges(v))
                    second += is_flippable(mesh, SurfaceMesh::edge(h), rule, a.feature_angle_deg);
        }
        check_ok = c.ok() && second == 0;
        std::vector<std::string> problems = c.problems;
        rep["check"] = {{"flippable_edges", d.flippable},
                        {"illegal_edges", d.illegal},
                        {"nonempty_shrunk_balls", d.nonempty_balls},
                        {"unchecked_balls", d.unchecked_balls},
                        {a.vertices_file.empty() ? "second_pass_flips" : "flippable_at_given_vertices", second}};
        if (before) {
            // The digest's local-mode check: F repaired, everything beyond m + 1 hops untouched.
            const CheckReport lc = check_local_flip(
                *before, mesh, V, lr, {.rule = rule, .feature_angle_deg = a.feature_angle_deg});
            check_ok = check_ok && lc.ok();
            problems.insert(problems.end(), lc.problems.begin(), lc.problems.end());
            rep["check"]["local_check"] = check_json(lc, {.problems = true});
        }
        rep["check"]["ok"] = check_ok;
        rep["check"]["problems"] = problems;
        for (const std::string& p : problems) std::cout << "  check: " << p << "\n";
    }
    require_valid_output(mesh, "flip");
    progress.stage("writing " + a.output);
    t0 = Clock::now();
    write_mesh(mesh, mesh_out);
    rep["seconds_write"] = seconds_since(t0);
    out.report(rep);
    out.commit();
    std::cout << "flip: " << mesh.n_vertices() << " vertices, " << mesh.n_faces() << " faces, "
              << r.flips << " flips (" << to_string(rule) << "), " << r.checks << " checks, "
              << r.seconds << " s"
              << (r.converged ? ""
                  : a.vertices_file.empty()
                      ? ", NOT converged (flip cap reached)"
                      : ", NOT converged (window still growing after the last round, or flip cap)")
              << "\n  wrote " << a.output << "\n";
    if (!check_ok)
        throw CheckFailed(!r.converged ? "flipping did not converge"
                          : before     ? "the local-mode check failed (see the report's 'check')"
                                       : "the flipped mesh violates an invariant (see the report's 'check')");
}

struct WorsenArgs {
    CommonOptions common;
    std::string input, output;
    WorsenOptions options;
};

void run_worsen(const WorsenArgs& a, RunContext& ctx) {
    require_writable_mesh_extension(a.output);
    RunOutputs out(a.common, {a.input});
    const std::filesystem::path mesh_out = out.file(a.output, "-o");
    ctx.inputs_begin();
    Progress progress("worsen", a.common.quiet);
    progress.stage("reading " + a.input);
    SurfaceMesh mesh = load_mesh(a.input);
    require_closed_manifold(mesh, a.input);
    progress.stage("worsening");
    const auto t0 = std::chrono::steady_clock::now();
    const WorsenReport r = worsen(mesh, a.options);
    const double secs = seconds_since(t0);
    require_valid_output(mesh, "worsen");
    progress.stage("writing " + a.output);
    write_mesh(mesh, mesh_out);
    out.report({{"command", "worsen"},
                            {"input", a.input},
                            {"output", a.output},
                            {"vertices", mesh.n_vertices()},
                            {"faces", mesh.n_faces()},
                            {"flips", r.flips},
                            {"attempts", r.attempts},
                            {"rejected", r.rejected},
                            {"rounds", a.options.rounds},
                            {"seed", a.options.seed},
                            {"seconds_worsen", secs}});
    out.commit();
    std::cout << "worsen: " << r.flips << " random flips kept, " << r.rejected
              << " undone (dihedral floor " << a.options.min_dihedral_deg << " deg)\n  wrote "
              << a.output << "\n";
}

}  // namespace

void register_flip(CLI::App& root, int& result) {
    auto args = std::make_shared<FlipArgs>();
    CLI::App* sub = root.add_subcommand(
        "flip", "Smooth a closed triangle mesh by edge flips until no edge is flippable");
    sub->add_option("input", args->input, "Input mesh (.off .obj .ply .stl)")->required();
    sub->add_option("-o,--output", args->output, "Output mesh (.off .obj .ply .stl .vtk .vtp)")->required();
    sub->add_option("--criterion", args->criterion,
                    "angle: Definition 3 of the edge-flip paper; delaunay: diametric-ball rule")
        ->check(CLI::IsMember({"angle", "delaunay"}))
        ->capture_default_str();
    sub->add_option("--max-flips-per-vertex", args->max_flips_per_vertex,
                    "Diagnostic cap on flips (per vertex)")
        ->check(CLI::Range(std::size_t(1), std::size_t(1) << 32))
        ->capture_default_str();
    sub->add_option("--feature-angle", args->feature_angle_deg,
                    "Keep sharp edges: never flip an edge, or create one, whose 180 - dihedral "
                    "exceeds this many degrees (180 = off; 60 keeps CAD creases)")
        ->check(finite_number() & CLI::Range(0.0, 180.0))
        ->capture_default_str();
    sub->add_option("--vertices", args->vertices_file,
                    "Flip only around these vertices (a file of 0-based vertex indices), with the "
                    "doubling-window local method");
    sub->add_option("--reorder", args->reorder,
                    "Flip a spatially renumbered copy (outputs keep the input's numbering): auto "
                    "= for large meshes with scattered numbering")
        ->check(CLI::IsMember({"auto", "always", "never"}))
        ->capture_default_str();
    sub->add_flag("--check", args->check,
                  "Verify the result: manifold, nothing flippable (a second pass flips nothing); "
                  "with --vertices the local-mode check (no flippable or illegal edge and no "
                  "non-empty 0.95-ball near V, every triangle beyond m+1 hops unchanged)");
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("flip", [&](RunContext& ctx) { run_flip(*args, ctx); }); });
}

void register_worsen(CLI::App& root, int& result) {
    auto args = std::make_shared<WorsenArgs>();
    CLI::App* sub = root.add_subcommand(
        "worsen", "Randomly flip edges (the edge-flip paper's worsening) to make a bad mesh");
    sub->add_option("input", args->input, "Input mesh")->required();
    sub->add_option("-o,--output", args->output, "Output mesh")->required();
    sub->add_option("--rounds", args->options.rounds, "Passes over the edges")
        ->check(CLI::Range(std::size_t{0}, std::size_t{10000}))
        ->capture_default_str();
    sub->add_option("--seed", args->options.seed, "Random seed")->capture_default_str();
    sub->add_option("--probability", args->options.probability, "Chance to flip each edge")
        ->check(finite_number() & CLI::Range(0.0, 1.0))
        ->capture_default_str();
    sub->add_option("--min-dihedral", args->options.min_dihedral_deg,
                    "Undo a flip that makes a dihedral angle smaller than this (degrees)")
        ->check(finite_number() & CLI::Range(0.0, 180.0))
        ->capture_default_str();
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("worsen", [&](RunContext& ctx) { run_worsen(*args, ctx); }); });
}

}  // namespace dynmesh::cli
