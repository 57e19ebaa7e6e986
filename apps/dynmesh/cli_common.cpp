#include "cli_common.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

#include "dynmesh/error.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/io/text_file.hpp"
#include "dynmesh/mesh/check.hpp"

namespace dynmesh::cli {

void check_report_path(const CommonOptions& common, const std::vector<std::string>& files) {
    if (common.report_path.empty()) return;
    for (const std::string& f : files)
        if (!f.empty()) ensure_not_same_file(f, common.report_path);
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
}

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

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void write_report(const CommonOptions& common, const nlohmann::json& report) {
    if (common.report_path.empty()) return;
    // Paths that are not UTF-8 must not make the report fail: replace invalid bytes.
    write_text_file(common.report_path,
                    report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

SurfaceMesh load_mesh(const std::filesystem::path& path) { return read_mesh(path); }

void require_closed_manifold(const SurfaceMesh& mesh, const std::filesystem::path& path) {
    const MeshCheckReport r = check_mesh(mesh, {.require_closed = true, .check_degenerate = false});
    if (r.ok()) return;
    throw TopologyError(path.string() + ": not a closed oriented 2-manifold: " + r.problems.front() +
                        (r.n_problems > 1 ? " (and " + std::to_string(r.n_problems - 1) + " more problems)" : ""));
}

int guarded(const std::string& command, const std::function<void()>& body) {
    try {
        body();
        return 0;
    } catch (const std::bad_alloc&) {
        std::cerr << "dynmesh " << command << ": error: out of memory" << std::endl;
    } catch (const std::exception& e) {
        std::string msg = e.what();
        for (char& c : msg)
            if (c == '\n' || c == '\r') c = ' ';
        std::cerr << "dynmesh " << command << ": error: " << msg << std::endl;
    }
    return 1;
}

}  // namespace dynmesh::cli
