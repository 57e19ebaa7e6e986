#pragma once
/// \file Shared plumbing of the dynmesh subcommands: progress on stderr, JSON reports
/// written atomically, input loading with one-line errors, and the error-to-exit-code rule.

#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh::cli {

/// Options every subcommand shares.
struct CommonOptions {
    bool quiet = false;
    std::string report_path;  ///< --report FILE (JSON); empty = none
};
void add_common_options(CLI::App& app, CommonOptions& common);
/// Refuses a --report path that names one of the command's input or output files.
void check_report_path(const CommonOptions& common, const std::vector<std::string>& files);
/// A CLI11 validator that rejects NaN and infinities (CLI::Range lets NaN through).
const CLI::Validator& finite_number();

/// Prints "dynmesh <cmd>: <stage> ... <elapsed> s" to stderr every two seconds while a run
/// is longer than two seconds, from a background thread; silent with --quiet and for short
/// runs. The stage is set by the main thread.
class Progress {
public:
    Progress(std::string command, bool quiet);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    void stage(const std::string& name);
    /// Optional detail shown after the stage (e.g. "1200000 flips").
    void detail(const std::string& text);
    [[nodiscard]] double elapsed() const;

private:
    void loop();
    std::string command_;
    bool quiet_;
    std::chrono::steady_clock::time_point start_;
    std::mutex mutex_;
    std::string stage_, detail_;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

/// Seconds since `t0`.
double seconds_since(std::chrono::steady_clock::time_point t0);

/// Writes the report as pretty JSON if a path was given.
void write_report(const CommonOptions& common, const nlohmann::json& report);

/// Reads a mesh; errors come back as IoError/TopologyError naming the file.
[[nodiscard]] SurfaceMesh load_mesh(const std::filesystem::path& path);
/// Throws TopologyError "<file>: not a closed oriented 2-manifold: <first problem>" unless the
/// mesh is one.
void require_closed_manifold(const SurfaceMesh& mesh, const std::filesystem::path& path);

/// Runs `body`, turning dynmesh and standard exceptions into a one-line message on stderr
/// ("dynmesh <cmd>: error: ...") and exit code 1.
int guarded(const std::string& command, const std::function<void()>& body);

}  // namespace dynmesh::cli
