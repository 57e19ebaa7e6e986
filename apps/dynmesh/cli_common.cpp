#include "cli_common.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/io/text_file.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/system/process.hpp"

namespace dynmesh::cli {

namespace fs = std::filesystem;

const std::string& exit_code_help() {
    static const std::string text =
        "Exit codes: 0 success; 1 the run's checks found a problem (--check, dynmesh check); "
        "2 usage error (unknown flag, bad value, clashing or unwritable output paths); "
        "3 bad input file (missing, unreadable, malformed, not a valid mesh), or an output "
        "that could not be written; 4 internal error (a bug in dynmesh).";
    return text;
}

std::optional<std::vector<double>> parse_number_list(const std::string& text) {
    std::vector<double> v;
    std::size_t at = 0;
    while (true) {
        const std::size_t comma = text.find(',', at);
        std::string t = text.substr(at, comma == std::string::npos ? comma : comma - at);
        t.erase(0, t.find_first_not_of(" \t"));
        t.erase(t.find_last_not_of(" \t") + 1);
        std::size_t used = 0;
        double x = 0;
        try {
            x = std::stod(t, &used);
        } catch (const std::exception&) {
            return std::nullopt;
        }
        if (used != t.size() || !std::isfinite(x)) return std::nullopt;
        v.push_back(x);
        if (comma == std::string::npos) return v;
        at = comma + 1;
    }
}

const CLI::Validator& finite_number() {
    static const CLI::Validator v(
        [](std::string& s) {
            double x = 0;
            try {
                x = std::stod(s);
            } catch (const std::exception&) {
                return std::string("not a number: " + s);
            }
            return std::isfinite(x) ? std::string() : std::string("not a finite number: " + s);
        },
        "FINITE");
    return v;
}

void add_common_options(CLI::App& app, CommonOptions& common) {
    app.add_flag("-q,--quiet", common.quiet, "No progress output on stderr");
    app.add_option("--report", common.report_path, "Write a machine-readable JSON report here");
    app.footer(exit_code_help());
}

// ---- outputs --------------------------------------------------------------------------------

RunOutputs::RunOutputs(const CommonOptions& common, std::vector<fs::path> inputs)
    : set_(std::move(inputs)) {
    if (!common.report_path.empty())
        report_staged_ = set_.add_file(common.report_path, "--report", OutputSet::Order::Last);
}

fs::path RunOutputs::file(const fs::path& target, std::string_view what) {
    return set_.add_file(target, what);
}

fs::path RunOutputs::file_set(const fs::path& base, const std::vector<std::string>& extensions,
                              std::string_view what) {
    return set_.add_file_set(base, extensions, what);
}

fs::path RunOutputs::directory(const fs::path& target, std::string_view what) {
    return set_.add_directory(target, what);
}

void RunOutputs::report(const nlohmann::json& report) {
    if (report_staged_.empty()) return;
    // Paths that are not UTF-8 must not make the report fail: replace invalid bytes.
    write_text_file(report_staged_,
                    report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

// ---- progress -------------------------------------------------------------------------------

Progress::Progress(std::string command, bool quiet)
    : command_(std::move(command)), quiet_(quiet), start_(std::chrono::steady_clock::now()) {
    if (!quiet_) thread_ = std::thread([this] { loop(); });
}

Progress::~Progress() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
}

void Progress::stage(const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    stage_ = name;
    detail_.clear();
}

void Progress::detail(const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex_);
    detail_ = text;
}

double Progress::elapsed() const { return seconds_since(start_); }

void Progress::loop() {
    using namespace std::chrono_literals;
    auto next = start_ + 2s;
    while (!stop_) {
        std::this_thread::sleep_for(50ms);
        if (std::chrono::steady_clock::now() < next) continue;
        next += 2s;
        std::string line;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            line = "dynmesh " + command_ + ": " + stage_ + (detail_.empty() ? "" : " (" + detail_ + ")");
        }
        char buf[32];
        std::snprintf(buf, sizeof buf, " ... %.0f s", elapsed());
        std::cerr << line << buf << std::endl;
    }
}

nlohmann::json check_json(const CheckReport& report, const CheckJsonKeys& keys) {
    nlohmann::json j = nlohmann::json::object();
    for (const CheckFigure& f : report.figures) {
        if (std::find(keys.leave_out.begin(), keys.leave_out.end(), f.name) != keys.leave_out.end()) continue;
        switch (f.kind) {
            case CheckFigure::Kind::Integer: j[f.name] = static_cast<long long>(f.value); break;
            case CheckFigure::Kind::Boolean: j[f.name] = f.value != 0; break;
            case CheckFigure::Kind::Real: j[f.name] = f.value; break;
        }
    }
    if (keys.ok) j["ok"] = report.ok();
    if (keys.problems) j["problems"] = report.problems;
    if (keys.n_problems) j["n_problems"] = report.n_problems;
    return j;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// ---- inputs ---------------------------------------------------------------------------------

SurfaceMesh load_mesh(const fs::path& path) { return read_mesh(path); }

void require_closed_manifold(const SurfaceMesh& mesh, const fs::path& path) {
    const CheckReport r = check_mesh(mesh, {.require_closed = true, .check_degenerate = false});
    if (!r.ok())
        throw TopologyError(path.string() + ": not a closed oriented 2-manifold: " + r.problems.front() +
                            (r.n_problems > 1 ? " (and " + std::to_string(r.n_problems - 1) + " more problems)" : ""));
    const CheckReport d = check_mesh(mesh, {.check_degenerate = true, .max_listed = 1});
    if (d.integer("degenerate_faces") > 0)
        throw TopologyError(path.string() + ": " + d.problems.front() +
                            (d.integer("degenerate_faces") > 1
                                 ? " (and " + std::to_string(d.integer("degenerate_faces") - 1) + " more)"
                                 : "") +
                            "; zero-area triangles are refused: remove them first");
}

std::string lower_extension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

void require_writable_mesh_extension(const std::string& path) {
    const std::string ext = fs::path(path).extension().string();
    const std::string lower = lower_extension(path);
    std::string list;
    for (const std::string& e : writable_mesh_extensions()) {
        if (e == lower) return;
        list += (list.empty() ? "" : " ") + e;
    }
    throw UsageError("-o " + path + ": unsupported extension '" + ext + "' (write " + list + ")");
}

void require_valid_output(const SurfaceMesh& mesh, const std::string& command, bool closed) {
    const CheckReport c = check_mesh(mesh, {.require_closed = closed});
    if (!c.ok()) throw InternalError(command + " produced an invalid mesh: " + c.problems.front());
}

// ---- plots ----------------------------------------------------------------------------------

void require_png_output(const std::string& png, const std::string& script) {
    if (lower_extension(png) != ".png") throw UsageError("--png " + png + ": expected a .png file");
    if (const auto why = plotting_unavailable(script)) throw UsageError("--png: " + *why);
}

std::optional<std::string> plotting_unavailable(const std::string& name) {
    if (find_bundled_script(name).empty())
        return "the plotting script " + name + " is not installed next to dynmesh (" +
               (executable_directory().parent_path() / "share/dynmesh/scripts").string() + ")";
    std::error_code ec;
    if (!fs::exists(plotting_python(), ec))
        return "needs " + plotting_python().string() + " with matplotlib (Debian python3-matplotlib)";
    return std::nullopt;
}

void run_plot_script(const std::string& name, const std::vector<std::string>& args,
                     const std::string& what) {
    if (const auto why = plotting_unavailable(name)) throw IoError(what + ": " + *why);
    std::vector<std::string> argv = {plotting_python().string(), find_bundled_script(name).string()};
    argv.insert(argv.end(), args.begin(), args.end());
    const ProcessResult r = run_process(argv);
    if (!r.ok())
        throw IoError(what + ": drawing failed (" + r.describe() +
                      (r.error_tail.find("matplotlib") != std::string::npos
                           ? "; install Debian python3-matplotlib"
                           : "") +
                      ")");
}

// ---- errors ---------------------------------------------------------------------------------

namespace {

std::string one_line(std::string msg) {
    for (char& c : msg)
        if (c == '\n' || c == '\r') c = ' ';
    return msg;
}

}  // namespace

int guarded(const std::string& command, const std::function<void(RunContext&)>& body) {
    RunContext ctx;
    const auto say = [&](const char* kind, const std::string& msg) {
        std::cerr << "dynmesh " << command << ": " << kind << ": " << one_line(msg) << std::endl;
    };
    try {
        body(ctx);
        return kExitOk;
    } catch (const CheckFailed& e) {
        say("check failed", e.what());
        return kExitCheckFailed;
    } catch (const UsageError& e) {
        say("usage error", e.what());
        return kExitUsage;
    } catch (const InternalError& e) {
        say("internal error (a bug in dynmesh; please report it)", e.what());
        return kExitInternal;
    } catch (const TopologyError& e) {
        say("error", e.what());
        return kExitBadInput;
    } catch (const Error& e) {
        // InvalidInput and IoError: about the command line and the output paths until the
        // inputs are read, about an input file (or writing an output) afterwards.
        const bool in_usage = ctx.phase() == RunContext::Phase::Usage;
        say(in_usage ? "usage error" : "error", e.what());
        return in_usage ? kExitUsage : kExitBadInput;
    } catch (const std::bad_alloc&) {
        say("error", "out of memory");
        return kExitInternal;
    } catch (const std::exception& e) {
        say("internal error (a bug in dynmesh; please report it)", e.what());
        return kExitInternal;
    }
}

}  // namespace dynmesh::cli
