#pragma once
/// \file The one way dynmesh starts another program (the plotting scripts): posix_spawn with
/// an argument vector. No shell ever sees an argument, so file names with quotes, spaces,
/// `;` or `$(...)` are passed as they are. Bundled scripts are found relative to the running
/// executable, not through a path fixed at compile time.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace dynmesh {

struct ProcessResult {
    bool started = false;    ///< the program could be started
    int exit_code = -1;      ///< its exit status when it exited normally, else -1
    int signal = 0;          ///< the signal that ended it, else 0
    bool timed_out = false;  ///< killed because it ran longer than the timeout
    std::string error_tail;  ///< the last non-empty line it wrote to stderr (for messages)
    [[nodiscard]] bool ok() const { return started && exit_code == 0; }
    /// "exit status 2: <last stderr line>", "killed by signal 9", "could not start: ...".
    [[nodiscard]] std::string describe() const;
};

/// Runs the program `argv[0]` (a path; no PATH search, no shell) with the arguments
/// `argv[1..]` and waits for it, at most `timeout_seconds` (then it is killed with SIGKILL).
/// Its stdin is /dev/null, its stdout is discarded and its stderr is captured (the last line
/// is kept in error_tail); once it has exited, a descendant still holding its stderr open
/// does not keep the caller waiting. Never throws for a program that fails;
/// \throw InvalidInput for an empty argv.
[[nodiscard]] ProcessResult run_process(const std::vector<std::string>& argv,
                                        double timeout_seconds = 600);

/// Kills (SIGKILL) and reaps the program run_process is waiting for, if any. Async-signal-safe:
/// the signal cleanup of staged outputs calls it first, so that no child outlives an
/// interrupted run or writes after its outputs were removed.
void kill_running_process() noexcept;

/// The directory holding the running executable (from /proc/self/exe); empty if unknown.
[[nodiscard]] std::filesystem::path executable_directory();

/// A script bundled with dynmesh, looked up in order in `$DYNMESH_SCRIPTS_DIR`, then in
/// `<executable directory>/../share/dynmesh/scripts` (both the build tree and an installed
/// prefix have this layout). Returns an empty path when it is in neither.
[[nodiscard]] std::filesystem::path find_bundled_script(std::string_view name);

/// The Python interpreter the plotting scripts run under (Debian's, which has matplotlib
/// when python3-matplotlib is installed): /usr/bin/python3.
[[nodiscard]] std::filesystem::path plotting_python();

}  // namespace dynmesh
