/// `dynmesh deform`: a deforming-surface scenario (or any closed mesh carried by a warp) run
/// through DeformingMesh, with a ParaView series, a per-time-unit log, quality plots and a
/// JSON report (shared/specs/deforming-mesh.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "dynmesh/deform/run.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/io/text_file.hpp"

namespace dynmesh::cli {

namespace {

namespace fs = std::filesystem;

/// The creases of a mesh file unless --feature-angle says otherwise (spec §10.3: 45 degrees;
/// of the shared meshes, fandisk, elephant and spot have creases at that angle). The library's
/// DeformOptions keeps them off, so that a caller opts in.
constexpr double kMeshFeatureAngle = 45.0;

struct DeformArgs {
    CommonOptions common;
    std::string scenario;
    std::string warp;
    int steps = 400;
    std::size_t samples = 20000;
    double speed = 1.0;
    std::string schedule = "paper";
    double kappa = kPracticalKappa;
    std::size_t max_substeps = DeformOptions{}.max_substeps;
    std::string substep_updates = "local";
    double size_factor = DeformOptions{}.size_factor;
    /// Unset: kMeshFeatureAngle for a mesh file (spec §10.3's default), off for a scenario.
    std::optional<double> feature_angle;
    std::uint64_t seed = 1;
    std::string out;
    std::string format = "vtp";
    int every = 1;
    int measure_every = 1;
    bool no_self_intersections = false;
    bool no_plot = false;
    std::string check;  ///< empty: off; "invariants" or "strict"
};

/// Per-face fields of a frame for the .vtp series.
WriteOptions face_fields(const SurfaceMesh& m, double R) {
    WriteOptions o;
    ScalarField ma{"min_angle_deg", {}}, re{"radius_edge", {}}, cr{"circumradius_over_R", {}};
    for (Face f : m.faces()) {
        const auto vs = m.face_vertices(f);
        const Point3 &a = m.position(vs[0]), &b = m.position(vs[1]), &c = m.position(vs[2]);
        ma.values.push_back(rad_to_deg(min_angle(a, b, c)));
        re.values.push_back(radius_edge_ratio(a, b, c));
        cr.values.push_back(R > 0 ? circumradius(a, b, c) / R : 0.0);
    }
    o.face_fields = {std::move(ma), std::move(re), std::move(cr)};
    return o;
}

std::string frame_name(int t, const std::string& ext) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "mesh_%05d.", t);
    return buf + ext;
}

nlohmann::json report_json(const DeformRunReport& r, const Scenario& s) {
    nlohmann::json j;
    j["scenario"] = r.scenario;
    j["description"] = s.description;
    j["schedule"] = r.schedule;
    j["kappa"] = r.kappa;
    j["lambda"] = r.lambda;
    j["h0"] = r.h0;
    j["samples"] = r.samples;
    j["time_units"] = r.time_units;
    j["updates"] = r.updates;
    j["emergency_updates"] = r.emergency_updates;
    j["substeps"] = r.substeps;
    j["max_substeps_per_unit"] = r.max_substeps_per_unit;
    j["internal_updates"] = r.internal_updates;
    j["substep_retries"] = r.substep_retries;
    j["max_strain_ratio"] = r.max_strain_ratio;
    j["flips"] = r.flips;
    j["insertions"] = r.insertions;
    j["removals"] = r.removals;
    j["changes"] = r.flips + r.insertions + r.removals;
    j["samples_inserted"] = r.samples_inserted;
    j["samples_deleted"] = r.samples_deleted;
    j["seconds_updates"] = r.seconds_updates;
    j["seconds_init"] = r.seconds_init;
    j["seconds_total"] = r.seconds_total;
    j["worst_hausdorff_over_eps"] = r.worst_hausdorff_over_eps;
    j["worst_min_angle_deg"] = r.worst_min_angle_deg;
    j["worst_min_angle_off_creases_deg"] = r.worst_min_angle_off_creases_deg;
    j["worst_max_radius_edge"] = r.worst_max_radius_edge;
    j["worst_R_over_eps"] = r.worst_R_over_h;
    j["worst_normal_deviation_deg"] = r.worst_normal_dev_deg;
    j["worst_min_edge_angle_deg"] = r.worst_min_edge_angle_deg;
    j["self_intersections"] = r.self_intersections;
    j["inverted_triangles"] = r.inverted;
    j["invariant_failures"] = r.invariant_failures;
    j["first_invariant_failures"] = r.first_invariant_failures;
    j["nonempty_balls_max"] = r.nonempty_balls_max;
    j["nonempty_balls_total"] = r.nonempty_balls_total;
    j["violations"] = r.violations;
    j["updates_with_nonempty_balls"] = r.updates_with_nonempty_balls;
    j["first_nonempty_balls"] = r.first_nonempty_balls;
    j["rebuilds"] = r.rebuilds;
    j["rollbacks"] = r.rollbacks;
    j["flip_refusals"] = r.flip_refusals;
    j["first_self_intersection_t"] = r.first_self_intersection_t;
    j["first_inverted_t"] = r.first_inverted_t;
    j["first_self_intersection"] = r.first_self_intersection;
    j["first_inverted"] = r.first_inverted;
    j["init_vertices"] = r.init_vertices;
    j["crease_edges"] = r.crease_edges;
    j["crease_lines"] = r.crease_lines;
    j["corners"] = r.corners;
    j["euler"] = r.euler;
    j["warnings"] = r.warnings;
    nlohmann::json examples = nlohmann::json::array();
    for (const ViolationRecord& v : r.violation_examples)
        examples.push_back({{"t", v.t}, {"kind", std::string(to_string(v.kind))}, {"detail", v.detail}});
    j["violation_examples"] = examples;
    return j;
}

/// The deforming-mesh pipeline works in absolute units (sampling radii, motion bounds, its
/// tolerances), so a mesh far outside ordinary sizes is refused instead of measured wrongly.
void require_coordinate_range(const SurfaceMesh& mesh, const std::string& path) {
    constexpr double kMax = 1e50, kMinExtent = 1e-50;
    Point3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (const Vertex v : mesh.vertices())
        for (std::size_t i = 0; i < 3; ++i) {
            lo[i] = std::min(lo[i], mesh.position(v)[i]);
            hi[i] = std::max(hi[i], mesh.position(v)[i]);
        }
    double big = 0, extent = 0;
    for (std::size_t i = 0; i < 3; ++i) {
        big = std::max({big, std::fabs(lo[i]), std::fabs(hi[i])});
        extent = std::max(extent, 2 * (0.5 * hi[i] - 0.5 * lo[i]));  // no overflow below DBL_MAX
    }
    if (big > kMax || extent < kMinExtent) {
        char buf[160];
        std::snprintf(buf, sizeof buf,
                      ": coordinates up to %.3g and a size of %.3g are outside the range deform "
                      "handles (|x| <= 1e50, size >= 1e-50); rescale the mesh",
                      big, extent);
        throw InvalidInput(path + buf);
    }
}

void run_deform_cmd(const DeformArgs& a, RunContext& ctx) {
    const Schedule schedule = parse_schedule(a.schedule);
    // A built-in scenario name wins over a file of that name (write ./pulse for the file);
    // anything else is a mesh file.
    static const std::vector<std::string> kScenarios = {"pulse", "stretch", "twist", "bend",
                                                        "boomerang", "rotate", "dimple"};
    const bool builtin =
        std::find(kScenarios.begin(), kScenarios.end(), a.scenario) != kScenarios.end();
    std::error_code ec;
    const bool is_file = !builtin && (fs::exists(a.scenario, ec) || fs::path(a.scenario).has_extension());
    if (!is_file && !builtin)
        throw UsageError("'" + a.scenario +
                         "' is neither a scenario (pulse, stretch, twist, bend, boomerang, rotate, "
                         "dimple) nor a mesh file");
    if (!is_file && !a.warp.empty())
        throw UsageError("--warp is for a mesh file; the scenario '" + a.scenario +
                         "' has its own motion");
    if (!is_file && a.feature_angle && *a.feature_angle < 180.0)
        throw UsageError("--feature-angle finds the creases of a mesh file; the scenario '" + a.scenario +
                         "' is a smooth surface");
    if (!(static_cast<double>(a.steps) / a.speed <= 1e8))
        throw UsageError("--steps / --speed = " + std::to_string(static_cast<double>(a.steps) / a.speed) +
                         " time units is too many (at most 1e8)");
    RunOutputs out(a.common, is_file ? std::vector<fs::path>{a.scenario} : std::vector<fs::path>{});
    const fs::path out_dir = a.out.empty() ? fs::path{} : out.directory(a.out, "--out");
    ctx.inputs_begin();
    Progress progress("deform", a.common.quiet);
    if (is_file) {
        progress.stage("reading " + a.scenario);
        const SurfaceMesh mesh = load_mesh(a.scenario);
        require_closed_manifold(mesh, a.scenario);
        require_coordinate_range(mesh, a.scenario);
    }

    progress.stage("building the scenario");
    ScenarioOptions so;
    so.samples = a.samples;
    so.steps = a.steps;
    so.speed = a.speed;
    so.seed = a.seed;
    so.warp = a.warp;
    const Scenario s = make_scenario(a.scenario, so);
    if (!a.common.quiet)
        std::cerr << "dynmesh deform: " << s.description << "; " << s.initial.size() << " samples, "
                  << s.time_units << " time units, lambda = " << s.lambda << ", h0 = " << s.h0 << "\n";

    std::vector<std::pair<double, std::string>> series;

    DeformRunOptions ro;
    ro.schedule = schedule;
    ro.params.kappa = a.kappa;
    ro.params.max_substeps = a.max_substeps;
    ro.params.local_updates = a.substep_updates == "local";
    ro.params.size_factor = a.size_factor;
    ro.params.feature_angle_deg = a.feature_angle.value_or(is_file ? kMeshFeatureAngle : 180.0);
    ro.params.seed = a.seed;
    ro.measure_every = a.measure_every;
    ro.measure.self_intersections = !a.no_self_intersections;
    const CheckLevel check = a.check.empty() ? CheckLevel::Off : parse_check_level(a.check);
    ro.check_invariants = check != CheckLevel::Off;
    ro.on_frame = [&](const DeformFrame& f) {
        progress.stage("t = " + std::to_string(f.t) + " / " + std::to_string(s.time_units));
        if (out_dir.empty()) return;
        if (f.t % a.every != 0 && f.t != s.time_units) return;
        const SurfaceMesh& m = f.mesh->mesh();
        const std::string name = frame_name(f.t, a.format);
        if (a.format == "vtp") {
            write_mesh(m, out_dir / name, face_fields(m, f.mesh->max_circumradius()));
            series.emplace_back(f.t, name);
        } else {
            write_mesh(m, out_dir / name);
        }
    };
    const DeformRunReport r = run_deform(s, ro);

    nlohmann::json j = report_json(r, s);
    const CheckReport failures = check_failures(r, check);
    if (check != CheckLevel::Off) {
        j["check_level"] = std::string(to_string(check));
        j["check_failures"] = failures.problems;
    }
    if (!out_dir.empty()) {
        progress.stage("writing the log");
        if (a.format == "vtp") write_pvd(out_dir / "mesh.pvd", series);
        write_text_file(out_dir / "log.csv", log_csv(r));
        write_text_file(out_dir / "summary.json",
                        j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
        if (!a.no_plot) {
            // The plot is optional here: without Python/matplotlib the run still succeeds.
            progress.stage("plotting");
            const std::string title = s.name + " (" + r.schedule + ", kappa " +
                                      std::to_string(static_cast<int>(r.kappa)) + ")";
            try {
                run_plot_script("plot_deform.py",
                                {(out_dir / "log.csv").string(), (out_dir / "quality.png").string(),
                                 "--title", title},
                                "quality.png");
                j["plot"] = (fs::path(a.out) / "quality.png").string();
            } catch (const IoError& e) {
                if (!a.common.quiet) std::cerr << "dynmesh deform: note: no quality.png: " << e.what() << "\n";
            }
        }
    }
    out.report(j);
    out.commit();
    if (!a.common.quiet)
        for (const std::string& w : r.warnings) std::cerr << "dynmesh deform: warning: " << w << "\n";
    if (!a.common.quiet) {
        std::printf("%s: %zu samples, %d time units, %zu updates (%zu emergency), %zu sub-steps (at most %zu "
                    "per unit, %zu updates between them), %zu flips, %zu insertions, %zu removals, %.3f s in updates\n",
                    r.scenario.c_str(), r.samples, r.time_units, r.updates, r.emergency_updates, r.substeps,
                    r.max_substeps_per_unit, r.internal_updates, r.flips, r.insertions, r.removals, r.seconds_updates);
        std::printf("worst over all time units: Hausdorff/eps %.3f, min angle %.2f deg (%.2f off creases), "
                    "radius-edge %.2f, R/eps %.2f, normal deviation %.2f deg, self-intersections %zu, inverted %zu\n",
                    r.worst_hausdorff_over_eps, r.worst_min_angle_deg, r.worst_min_angle_off_creases_deg,
                    r.worst_max_radius_edge, r.worst_R_over_h, r.worst_normal_dev_deg, r.self_intersections,
                    r.inverted);
        if (r.crease_edges > 0)
            std::printf("creases at t = 0: %zu edges in %zu polylines, %zu corners\n", r.crease_edges, r.crease_lines,
                        r.corners);
        for (const auto& [k, n] : r.violations) std::printf("monitor %s: %zu\n", k.c_str(), n);
        if (!a.out.empty()) std::printf("wrote %s/{mesh.pvd,log.csv,summary.json}\n", a.out.c_str());
        for (const std::string& f : failures.problems) std::printf("check (%s): %s\n", a.check.c_str(), f.c_str());
    }
    if (!failures.ok())
        throw CheckFailed(std::to_string(failures.n_problems) + " problem(s) at --check=" +
                          std::string(to_string(check)) + "; first: " + failures.problems.front());
}

}  // namespace

void register_deform(CLI::App& root, int& result) {
    auto args = std::make_shared<DeformArgs>();
    CLI::App* sub = root.add_subcommand(
        "deform",
        "Maintain a mesh of a deforming surface known only by moving samples (Cheng-Dey): a built-in "
        "scenario (pulse, stretch, twist, bend/boomerang, rotate, dimple) or a closed mesh file carried by --warp");
    sub->add_option("scenario", args->scenario,
                    "pulse | stretch | twist | bend | boomerang | rotate | dimple, or a closed mesh file (.off .obj .ply .stl; a file named like a scenario: ./NAME)")
        ->required();
    sub->add_option("--warp", args->warp, "For a mesh file: bend | twist | pulse | stretch | rotate (default bend)")
        ->check(CLI::IsMember({"bend", "twist", "pulse", "stretch", "rotate"}));
    sub->add_option("--steps", args->steps, "Time units of one out-and-back cycle")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000000));
    sub->add_option("--samples", args->samples, "Number of samples |P(0)|")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t{100}, std::size_t{100000000}));
    sub->add_option("--speed", args->speed, "Motion speed factor theta (the same path in steps/speed units)")
        ->capture_default_str()
        ->check(finite_number())
        ->check(CLI::PositiveNumber);
    sub->add_option("--schedule", args->schedule,
                    "paper: update at t2 = t1 + floor(R/(kappa lambda)); every-step: at every time unit")
        ->check(CLI::IsMember({"paper", "every-step"}))
        ->capture_default_str();
    sub->add_option("--kappa", args->kappa, "Step constant (paper: 468; practical default: 32)")
        ->capture_default_str()
        ->check(finite_number())
        ->check(CLI::PositiveNumber);
    sub->add_option("--max-substeps", args->max_substeps,
                    "Cut a time unit into at most this many sub-steps when vertices move faster relative to their "
                    "neighbours than 2R/kappa between updates (1: off, the paper's schedule alone)")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t{1}, std::size_t{65536}));
    sub->add_option("--substep-updates", args->substep_updates,
                    "Updates between sub-steps: local (on the pairs over their budget and their 2-ring) or global "
                    "(the whole mesh)")
        ->check(CLI::IsMember({"local", "global"}))
        ->capture_default_str();
    sub->add_option("--size-factor", args->size_factor,
                    "Local size field: a sample's size is min(R, F * local feature size) in place of the global R "
                    "(thin parts get vertices across them; 0: off, the paper's global R; the analytic scenarios, "
                    "whose features are all thicker than R, run as with 0)")
        ->capture_default_str()
        ->check(finite_number())
        ->check(CLI::NonNegativeNumber);
    sub->add_option("--feature-angle", args->feature_angle,
                    "Creases: edges of the input mesh whose 180 - dihedral exceeds this many degrees are kept as "
                    "mesh-edge chains through the motion, never flipped, corners never removed (default 45 for a mesh "
                    "file; 180 = off)")
        ->check(finite_number())
        ->check(CLI::Validator(
            [](std::string& v) {
                const double x = std::stod(v);
                return x > 0 && x <= 180 ? std::string() : "must be in (0, 180] degrees, got " + v;
            },
            "(0, 180]"));
    sub->add_option("--seed", args->seed, "Random seed of the samples")->capture_default_str();
    sub->add_option("--out", args->out,
                    "Output directory: mesh_NNNNN.<format> per time unit, mesh.pvd (vtp), log.csv, summary.json, "
                    "quality.png");
    sub->add_option("--format", args->format, "Mesh files: vtp (ParaView series with quality fields) | ply | off")
        ->check(CLI::IsMember({"vtp", "ply", "off"}))
        ->capture_default_str();
    sub->add_option("--every", args->every, "Write the mesh every K time units")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000000));
    sub->add_option("--measure-every", args->measure_every,
                    "Shape, normals, inversions and self-intersections are measured at every time unit; h and "
                    "the Hausdorff distance every K units. 0 = measure only at the first and last unit")
        ->capture_default_str()
        ->check(CLI::Range(0, 100000000));
    sub->add_flag("--no-self-intersections", args->no_self_intersections,
                  "Skip the per-time-unit self-intersection test (faster)");
    sub->add_flag("--no-plot", args->no_plot, "Do not write quality.png");
    sub->add_flag("--check{invariants}", args->check,
                  "--check (= invariants): after every update (and at t = 0) the mesh is closed "
                  "with Tri(0)'s topology, radius-edge <= 3, spacing >= R/3, dormant lists "
                  "valid; no self-intersection or inverted triangle. "
                  "--check=strict: also no non-empty diametric ball and no monitor or "
                  "diagnostic of any kind (step_too_short, refused folds, coarsening, ...). Exit 1 on any failure, listed in the report's "
                  "check_failures")
        ->check(CLI::IsMember({"invariants", "on", "strict"}));
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("deform", [&](RunContext& ctx) { run_deform_cmd(*args, ctx); }); });
}

}  // namespace dynmesh::cli
