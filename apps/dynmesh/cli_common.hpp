#pragma once
/// \file Shared plumbing of the dynmesh subcommands: the exit-code contract, progress on
/// stderr, all-or-nothing outputs (OutputSet) with the JSON report among them, input loading
/// with one-line errors, and the plotting scripts.
///
/// Exit codes, the same for every subcommand (printed by --help):
///   0  success
///   1  the run's checks found a problem (--check, `dynmesh check`)
///   2  usage error: unknown flag, bad value or choice, clashing or unwritable output paths
///   3  bad input file (missing, unreadable, malformed, not a valid mesh or point set), or an
///      output that could not be written
///   4  internal error (a bug in dynmesh)

#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/io/output_set.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh::cli {

enum ExitCode : int {
    kExitOk = 0,
    kExitCheckFailed = 1,
    kExitUsage = 2,
    kExitBadInput = 3,
    kExitInternal = 4,
};

/// The exit-code table as --help shows it.
[[nodiscard]] const std::string& exit_code_help();

/// A bad command line that CLI11's validators cannot express (exit 2).
struct UsageError : Error {
    using Error::Error;
};
/// The run finished but its checks found a problem (exit 1); outputs are still written.
struct CheckFailed : Error {
    using Error::Error;
};

/// Where a run is. An InvalidInput or IoError while the command line and the output paths
/// are checked is a usage error (2); later it is about an input file (3).
class RunContext {
public:
    enum class Phase { Usage, Input };
    /// Command line and output paths are done; from now on errors are about the input.
    void inputs_begin() { phase_ = Phase::Input; }
    [[nodiscard]] Phase phase() const { return phase_; }

private:
    Phase phase_ = Phase::Usage;
};

/// Options every subcommand shares.
struct CommonOptions {
    bool quiet = false;
    std::string report_path;  ///< --report FILE (JSON); empty = none
};
/// Adds -q/--quiet and --report, and the exit-code table to the subcommand's help.
void add_common_options(CLI::App& app, CommonOptions& common);

/// A CLI11 validator that rejects NaN and infinities (CLI::Range lets NaN through).
const CLI::Validator& finite_number();
/// "a,b,c": comma-separated finite numbers (blanks around each allowed), as --domain and
/// --omega take them; nullopt if any piece is not a finite number.
[[nodiscard]] std::optional<std::vector<double>> parse_number_list(const std::string& text);

/// The outputs of one run (OutputSet) plus its --report: every output is registered up
/// front, written to its staging path, and moved into place by commit() only when all of
/// them were written.
class RunOutputs {
public:
    /// Registers the --report file (if any) against `inputs` and the outputs added later.
    RunOutputs(const CommonOptions& common, std::vector<std::filesystem::path> inputs);
    /// Registers an output file; returns the path to write it to.
    std::filesystem::path file(const std::filesystem::path& target, std::string_view what);
    /// Registers base+ext for each extension; returns the staging base.
    std::filesystem::path file_set(const std::filesystem::path& base,
                                   const std::vector<std::string>& extensions, std::string_view what);
    /// Registers an output directory; returns the staging directory.
    std::filesystem::path directory(const std::filesystem::path& target, std::string_view what);
    /// A private scratch directory beside the output `near` (OutputSet::scratch_directory).
    std::filesystem::path scratch(const std::filesystem::path& near) { return set_.scratch_directory(near); }
    /// Writes the report (pretty JSON) to its staging path if --report was given.
    void report(const nlohmann::json& report);
    /// Moves everything into place.
    void commit() { set_.commit(); }

private:
    OutputSet set_;
    std::filesystem::path report_staged_;
};

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

/// Which keys besides the figures check_json() writes, as each report has them.
struct CheckJsonKeys {
    bool ok = false;          ///< "ok": CheckReport::ok()
    bool problems = false;    ///< "problems": the listed problems
    bool n_problems = false;  ///< "n_problems": all problems, listed or not
    /// Figures the report does not carry (measured by the library, never written by the CLI).
    std::vector<std::string> leave_out;
};

/// A check's figures as a JSON object, one key per figure: Integer figures as integers,
/// Boolean ones as true/false, Real ones as numbers; then the keys `keys` asks for.
[[nodiscard]] nlohmann::json check_json(const CheckReport& report, const CheckJsonKeys& keys = {});

/// Seconds since `t0`.
double seconds_since(std::chrono::steady_clock::time_point t0);

/// Reads a mesh; errors come back as IoError/TopologyError naming the file.
[[nodiscard]] SurfaceMesh load_mesh(const std::filesystem::path& path);
/// The input rule of every command that changes a mesh (flip, worsen, deform): a closed
/// oriented 2-manifold without zero-area triangles.
/// \throw TopologyError "<file>: not a closed oriented 2-manifold: <first problem>", or
///        "<file>: face N is degenerate (zero area) ..." naming the first such face.
void require_closed_manifold(const SurfaceMesh& mesh, const std::filesystem::path& path);

/// The extension of `path` in lower case, with its dot (".pdb"), or "" when it has none.
std::string lower_extension(const std::string& path);

/// The mesh-writing commands check the output's extension before any work.
/// \throw UsageError naming `path` and the writable extensions.
void require_writable_mesh_extension(const std::string& path);
/// An exit-0 output always passes `dynmesh check` (with --closed when `closed`): verifies a
/// result before it is written. \throw InternalError naming the command and the first problem.
void require_valid_output(const SurfaceMesh& mesh, const std::string& command, bool closed = true);

/// The bundled plotting script `name`, run as /usr/bin/python3 script args... without a
/// shell.
/// \throw IoError "<what>: drawing failed: <the script's last error line>" when it fails.
void run_plot_script(const std::string& name, const std::vector<std::string>& args,
                     const std::string& what);
/// Checked before any work: `png` names a .png file (any case) and `script` can run here.
/// \throw UsageError "--png <png>: expected a .png file" or "--png: <why not>".
void require_png_output(const std::string& png, const std::string& script);
/// Why a plot cannot be drawn here (script or interpreter missing), or nullopt.
[[nodiscard]] std::optional<std::string> plotting_unavailable(const std::string& name);

/// Runs `body`, turning every exception into one line on stderr
/// ("dynmesh <cmd>: error: ...") and the exit code of the contract above.
int guarded(const std::string& command, const std::function<void(RunContext&)>& body);

}  // namespace dynmesh::cli
