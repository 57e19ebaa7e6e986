/// `dynmesh sample` (a mesh of samples of an analytic surface) and `dynmesh experiment`
/// (the edge-flip paper's tables, reproduced side by side with the paper's numbers).
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>

#include "cli_common.hpp"
#include "commands.hpp"
#include "dynmesh/deform/snapshot.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/flips/experiment.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/io/text_file.hpp"
#include "dynmesh/metrics/statistics.hpp"
#include "dynmesh/reconstruct/advancing_front.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh::cli {

namespace {

// ---- dynmesh sample ------------------------------------------------------------------------

struct SampleArgs {
    CommonOptions common;
    std::string surface = "sphere", output, method = "rdt";
    std::size_t samples = 10000;
    std::uint64_t seed = 1;
};

void run_sample(const SampleArgs& a, RunContext& ctx) {
    const auto surface = make_surface(a.surface);
    require_writable_mesh_extension(a.output);
    RunOutputs out(a.common, {});
    const std::filesystem::path mesh_out = out.file(a.output, "-o");
    // No input file: a surface that its --samples cannot mesh is a usage error (exit 2).
    (void)ctx;
    Progress progress("sample", a.common.quiet);
    progress.stage("sampling " + surface->spec());
    const std::vector<Point3> pts = surface->sample_uniform(a.samples, a.seed);
    progress.stage("meshing");
    nlohmann::json rep = {{"command", "sample"}, {"surface", surface->spec()}, {"samples", a.samples},
                          {"seed", a.seed}, {"method", a.method}, {"output", a.output}};
    SurfaceMesh mesh;
    if (a.method == "rdt") {
        auto r = restricted_delaunay_with_report(pts, *surface);
        mesh = std::move(r.mesh);
        rep["seconds_mesh"] = r.report.seconds;
        rep["unused_samples"] = r.report.unused_samples;
    } else {
        auto r = reconstruct_advancing_front_with_report(pts);
        mesh = std::move(r.mesh);
        rep["seconds_mesh"] = r.report.seconds;
        rep["unused_samples"] = r.report.unused_samples;
    }
    rep["vertices"] = mesh.n_vertices();
    rep["faces"] = mesh.n_faces();
    require_valid_output(mesh, "sample", /*closed=*/false);
    progress.stage("writing " + a.output);
    write_mesh(mesh, mesh_out);
    out.report(rep);
    out.commit();
    std::cout << "sample: " << surface->spec() << ", " << a.samples << " samples -> "
              << mesh.n_vertices() << " vertices, " << mesh.n_faces() << " faces (" << a.method
              << ")\n  wrote " << a.output << "\n";
}

// ---- dynmesh experiment --------------------------------------------------------------------

struct ExperimentArgs {
    CommonOptions common;
    std::size_t samples = 10000;
    std::size_t seeds = 5;
    std::vector<std::string> surfaces = {"sphere", "torus:5,3", "boomerang"};
    std::vector<std::string> meshes;
    std::string out_dir;
    std::string criterion = "angle";
};

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The paper's Tables 1-3: (mean, sd, max) of normal deviation and of 180 - dihedral (NaN:
/// not given).
struct PaperRow {
    double n_mean, n_sd, n_max, d_mean, d_sd, d_max;
};
const std::map<std::string, std::array<PaperRow, 3>>& paper_tables() {
    static const std::map<std::string, std::array<PaperRow, 3>> t = {
        {"sphere:1", {PaperRow{1.5, 0.56, 3.8, 1.4, 0.87, 5.3}, PaperRow{5.5, 7.68, 59, 8.8, 10.56, 60},
                      PaperRow{1.5, 0.56, 3.8, 1.4, 0.87, 5.3}}},
        {"torus:5,3", {PaperRow{2.6, 1.50, 16.8, 2.6, 1.93, 16.3}, PaperRow{6.8, 8.11, 63.7, 10, 11.09, 60},
                       PaperRow{2.6, 1.49, 15.8, 2.6, 1.92, 16}}},
        // Table 3 gives dihedral statistics only.
        {"boomerang", {PaperRow{kNaN, kNaN, kNaN, 4.3, 5.23, 50.8}, PaperRow{kNaN, kNaN, kNaN, 11.2, 12.11, 60},
                       PaperRow{kNaN, kNaN, kNaN, 4.3, 5.23, 50.9}}},
    };
    return t;
}

/// Mean and SD across seeds of one statistic.
struct Across {
    SummaryAccumulator acc;
    void add(double x) { acc.add(x); }
    [[nodiscard]] std::string str(int prec = 2) const {
        const Summary s = acc.summary();
        char buf[64];
        if (acc.count() > 1)
            std::snprintf(buf, sizeof buf, "%.*f±%.*f", prec, s.mean, prec, s.sd);
        else
            std::snprintf(buf, sizeof buf, "%.*f", prec, s.mean);
        return buf;
    }
    [[nodiscard]] double mean() const { return acc.summary().mean; }
};

struct RowStats {
    Across n_mean, n_sd, n_max, d_mean, d_sd, d_max;
    void add(const QualityReport& q) {
        if (q.normal_dev_deg) {
            n_mean.add(q.normal_dev_deg->mean);
            n_sd.add(q.normal_dev_deg->sd);
            n_max.add(q.normal_dev_deg->max);
        }
        d_mean.add(q.dihedral_dev_deg.mean);
        d_sd.add(q.dihedral_dev_deg.sd);
        d_max.add(q.dihedral_dev_deg.max);
    }
    [[nodiscard]] nlohmann::json json() const {
        nlohmann::json j = {{"dihedral_dev_mean_deg", d_mean.mean()},
                            {"dihedral_dev_sd_deg", d_sd.mean()},
                            {"dihedral_dev_max_deg", d_max.mean()}};
        if (n_mean.acc.count())
            j.update({{"normal_dev_mean_deg", n_mean.mean()},
                      {"normal_dev_sd_deg", n_sd.mean()},
                      {"normal_dev_max_deg", n_max.mean()}});
        return j;
    }
};

void write_histograms(const std::filesystem::path& path, const SmoothingExperimentResult& r) {
    std::ostringstream os;
    const Histogram& h = r.worsened.dihedral_dev_hist;
    os << "bin_lo_deg,bin_hi_deg,initial_dihedral,worsened_dihedral,smoothed_dihedral";
    const bool normals = r.worsened.normal_dev_hist.has_value();
    if (normals) os << ",initial_normal,worsened_normal,smoothed_normal";
    os << "\n";
    for (std::size_t i = 0; i < h.bins.size(); ++i) {
        os << h.lo + h.bin_width() * double(i) << "," << h.lo + h.bin_width() * double(i + 1) << ","
           << r.initial.dihedral_dev_hist.bins[i] << "," << h.bins[i] << ","
           << r.smoothed.dihedral_dev_hist.bins[i];
        if (normals)
            os << "," << r.initial.normal_dev_hist->bins[i] << "," << r.worsened.normal_dev_hist->bins[i]
               << "," << r.smoothed.normal_dev_hist->bins[i];
        os << "\n";
    }
    write_text_file(path, os.str());
}

std::string safe_name(std::string s) {
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s;
}

/// One case: an analytic surface (sampled anew for every seed) or a given mesh; `paper_key`
/// names its row of paper_tables() (empty: none).
nlohmann::json run_case(const ExperimentArgs& a, const std::filesystem::path& out_dir,
                        const std::string& name, const ImplicitSurface* surface,
                        const SurfaceMesh* given, const std::string& paper_key, Progress& progress) {
    const FlipRule rule = parse_flip_rule(a.criterion);
    RowStats rows[3];
    Across flips_per_vertex, shared, seconds;
    std::size_t vertices = 0;
    const std::size_t n_seeds = std::max<std::size_t>(1, a.seeds);
    for (std::size_t seed = 1; seed <= n_seeds; ++seed) {
        progress.stage(name + ", seed " + std::to_string(seed));
        SurfaceMesh mesh = given ? *given : restricted_delaunay(surface->sample_uniform(a.samples, seed), *surface);
        vertices = mesh.n_vertices();
        SmoothingExperimentOptions opt;
        opt.surface = surface;
        opt.worsen.seed = seed;
        opt.flip.rule = rule;
        SurfaceMesh worsened, smoothed;
        const SmoothingExperimentResult r = run_smoothing_experiment(mesh, opt, &worsened, &smoothed);
        rows[0].add(r.initial);
        rows[1].add(r.worsened);
        rows[2].add(r.smoothed);
        flips_per_vertex.add(double(r.flip.flips) / double(mesh.n_vertices()));
        shared.add(100.0 * r.shared_edge_fraction);
        seconds.add(r.flip.seconds);
        if (seed == 1 && !out_dir.empty()) {
            const std::filesystem::path& dir = out_dir;
            const std::string base = safe_name(name);
            write_histograms(dir / (base + "_histograms.csv"), r);
            write_mesh(mesh, dir / (base + "_initial.ply"));
            write_mesh(worsened, dir / (base + "_worsened.ply"));
            write_mesh(smoothed, dir / (base + "_smoothed.ply"));
        }
    }
    // Print the table.
    const bool normals = rows[0].n_mean.acc.count() > 0;
    const auto& tables = paper_tables();
    const auto paper = tables.find(paper_key);
    std::cout << "\n" << name << ": " << vertices << " vertices, " << n_seeds << " seed(s)"
              << (n_seeds > 1 ? " (mean±sd across seeds)" : "") << ", criterion " << a.criterion << "\n";
    std::cout << "  mesh       source   | normal deviation (deg)         | 180 - dihedral (deg)\n"
              << "                      | mean      sd        max        | mean      sd        max\n";
    const char* labels[3] = {"initial ", "worsened", "smoothed"};
    // Pads to a display width (the ± sign is two bytes but one column).
    auto col = [](const std::string& t, std::size_t width = 10) {
        std::size_t shown = 0;
        for (unsigned char c : t) shown += (c & 0xC0) != 0x80;
        return t + std::string(shown < width ? width - shown : 1, ' ');
    };
    auto num = [](double x, int prec) {
        if (std::isnan(x)) return std::string("-");
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.*f", prec, x);
        return std::string(buf);
    };
    for (int i = 0; i < 3; ++i) {
        const RowStats& r = rows[i];
        std::cout << "  " << labels[i] << "   dynmesh  | "
                  << (normals ? col(r.n_mean.str()) + col(r.n_sd.str()) + col(r.n_max.str(1))
                              : col("-") + col("-") + col("-"))
                  << " | " << col(r.d_mean.str()) + col(r.d_sd.str()) + col(r.d_max.str(1)) << "\n";
        if (paper != tables.end()) {
            const PaperRow& p = paper->second[i];
            std::cout << "             paper    | " << col(num(p.n_mean, 2)) << col(num(p.n_sd, 2))
                      << col(num(p.n_max, 1)) << " | " << col(num(p.d_mean, 2)) << col(num(p.d_sd, 2))
                      << col(num(p.d_max, 1)) << "\n";
        }
    }
    std::cout << "  flips per vertex " << flips_per_vertex.str(3) << ", flip time " << seconds.str(4)
              << " s, edges shared with the initial mesh " << shared.str(2) << " %\n";
    nlohmann::json j = {{"name", name},
                        {"vertices", vertices},
                        {"seeds", n_seeds},
                        {"initial", rows[0].json()},
                        {"worsened", rows[1].json()},
                        {"smoothed", rows[2].json()},
                        {"flips_per_vertex", flips_per_vertex.mean()},
                        {"seconds_flip", seconds.mean()},
                        {"shared_edges_percent", shared.mean()}};
    if (paper != tables.end()) {
        nlohmann::json pj = nlohmann::json::array();
        for (const PaperRow& p : paper->second) {
            nlohmann::json row = {{"dihedral_dev_mean_deg", p.d_mean}, {"dihedral_dev_sd_deg", p.d_sd},
                                  {"dihedral_dev_max_deg", p.d_max}};
            if (!std::isnan(p.n_mean))
                row.update({{"normal_dev_mean_deg", p.n_mean}, {"normal_dev_sd_deg", p.n_sd},
                            {"normal_dev_max_deg", p.n_max}});
            pj.push_back(row);
        }
        j["paper"] = pj;
    }
    return j;
}

/// "boomerang" or "boomerang:SAMPLES" -> the sample count; anything else -> nullopt.
std::optional<std::size_t> boomerang_spec(const std::string& spec) {
    const std::string name = "boomerang";
    if (spec.compare(0, name.size(), name) != 0) return std::nullopt;
    if (spec.size() == name.size()) return kBoomerangSamples;
    const std::string_view n = std::string_view(spec).substr(name.size() + 1);
    std::size_t v = 0;
    const auto [end, err] = std::from_chars(n.data(), n.data() + n.size(), v);
    if (spec[name.size()] != ':' || n.empty() || err != std::errc() || end != n.data() + n.size() || v < 100)
        throw InvalidInput("--surface " + spec + ": expected boomerang or boomerang:SAMPLES with SAMPLES >= 100");
    return v;
}

void run_experiment(const ExperimentArgs& a, RunContext& ctx) {
    // Usage errors first: bad surface specs, and cases whose --out files would collide.
    std::set<std::string> names;
    for (const std::string& spec : a.surfaces)
        if (!names.insert(boomerang_spec(spec) ? "boomerang" : safe_name(make_surface(spec)->spec())).second)
            throw UsageError("--surface " + spec + " is given twice");
    for (const std::string& file : a.meshes)
        if (!names.insert(safe_name(std::filesystem::path(file).filename().string())).second)
            throw UsageError("--mesh " + file +
                             ": another case has the same file name (their --out files would collide)");
    RunOutputs out(a.common, {a.meshes.begin(), a.meshes.end()});
    const std::filesystem::path out_dir = a.out_dir.empty() ? std::filesystem::path{} : out.directory(a.out_dir, "--out");
    ctx.inputs_begin();
    Progress progress("experiment", a.common.quiet);
    nlohmann::json cases = nlohmann::json::array();
    for (const std::string& spec : a.surfaces) {
        if (const auto samples = boomerang_spec(spec)) {
            progress.stage("deforming the boomerang (" + std::to_string(*samples) + " samples)");
            const SurfaceMesh snapshot = boomerang_snapshot(*samples);
            const std::string name = "boomerang snapshot (Table 3), " + std::to_string(*samples) + " samples";
            cases.push_back(run_case(a, out_dir, name, nullptr, &snapshot, "boomerang", progress));
            continue;
        }
        const auto surface = make_surface(spec);
        const std::string name = surface->spec() + ", " + std::to_string(a.samples) + " uniform samples";
        cases.push_back(run_case(a, out_dir, name, surface.get(), nullptr, surface->spec(), progress));
    }
    for (const std::string& file : a.meshes) {
        progress.stage("reading " + file);
        const SurfaceMesh mesh = load_mesh(file);
        require_closed_manifold(mesh, file);
        cases.push_back(run_case(a, out_dir, std::filesystem::path(file).filename().string(), nullptr, &mesh, "", progress));
    }
    out.report({{"command", "experiment"}, {"criterion", a.criterion}, {"cases", cases}});
    out.commit();
    if (!a.out_dir.empty()) std::cout << "\nwrote meshes and histogram CSVs to " << a.out_dir << "\n";
}

}  // namespace

void register_sample(CLI::App& root, int& result) {
    auto args = std::make_shared<SampleArgs>();
    CLI::App* sub = root.add_subcommand(
        "sample", "Sample an analytic surface uniformly and mesh the samples");
    sub->add_option("--surface", args->surface, "sphere[:R], ellipsoid:a,b,c or torus:R,r")->capture_default_str();
    sub->add_option("--samples", args->samples, "Number of samples")
        ->check(CLI::Range(std::size_t{4}, std::size_t{100000000}))
        ->capture_default_str();
    sub->add_option("--seed", args->seed, "Random seed")->capture_default_str();
    sub->add_option("--method", args->method,
                    "rdt: restricted Delaunay (surface known); advancing-front: reconstruction")
        ->check(CLI::IsMember({"rdt", "advancing-front"}))
        ->capture_default_str();
    sub->add_option("-o,--output", args->output, "Output mesh")->required();
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("sample", [&](RunContext& ctx) { run_sample(*args, ctx); }); });
}

void register_experiment(CLI::App& root, int& result) {
    auto args = std::make_shared<ExperimentArgs>();
    CLI::App* sub = root.add_subcommand(
        "experiment",
        "Reproduce the edge-flip paper's tables: build, worsen and smooth meshes, compare with the paper");
    sub->add_option("--samples", args->samples, "Samples per analytic surface")
        ->check(CLI::Range(std::size_t{1000}, std::size_t{100000000}))
        ->capture_default_str();
    sub->add_option("--seeds", args->seeds, "Seeds 1..N; statistics are averaged across seeds")
        ->check(CLI::Range(std::size_t{1}, std::size_t{1000}))
        ->capture_default_str();
    sub->add_option("--surface", args->surfaces,
                    "Analytic surfaces (repeatable), or boomerang[:SAMPLES] for Table 3: the deforming-mesh "
                    "boomerang (a ball stretched and bent into a 120-degree arc) at its most bent time, "
                    "default " + std::to_string(kBoomerangSamples) +
                        " samples (about 5.7K vertices, the paper's 5,802); dihedral statistics only")
        ->capture_default_str();
    sub->add_option("--mesh", args->meshes, "Real meshes to worsen and smooth as well (repeatable)");
    sub->add_option("--criterion", args->criterion, "angle or delaunay")
        ->check(CLI::IsMember({"angle", "delaunay"}))
        ->capture_default_str();
    sub->add_option("--out", args->out_dir, "Directory for meshes and histogram CSVs (seed 1)");
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("experiment", [&](RunContext& ctx) { run_experiment(*args, ctx); }); });
}

}  // namespace dynmesh::cli
