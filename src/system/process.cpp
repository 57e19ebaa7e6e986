#include "dynmesh/system/process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <atomic>
#include <csignal>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include "dynmesh/error.hpp"

extern char** environ;

namespace dynmesh {

namespace fs = std::filesystem;

std::string ProcessResult::describe() const {
    if (!started) return "could not start" + (error_tail.empty() ? "" : ": " + error_tail);
    if (timed_out) return "killed after running longer than its time limit";
    if (signal != 0) return "killed by signal " + std::to_string(signal);
    std::string s = "exit status " + std::to_string(exit_code);
    if (!error_tail.empty()) s += ": " + error_tail;
    return s;
}

namespace {

/// Keeps the last non-empty line of what a program writes, bounded in size.
class TailLine {
public:
    void add(const char* data, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) {
            const char c = data[i];
            if (c == '\n' || c == '\r') {
                if (!current_.empty()) last_ = current_;
                current_.clear();
            } else if (current_.size() < 1000) {
                current_.push_back(static_cast<unsigned char>(c) < 0x20 ? ' ' : c);
            }
        }
    }
    [[nodiscard]] std::string line() const { return current_.empty() ? last_ : current_; }

private:
    std::string current_, last_;
};

/// The child run_process is waiting for (0: none), for kill_running_process().
std::atomic<pid_t> g_running{0};

struct SpawnActions {
    posix_spawn_file_actions_t actions{};
    SpawnActions() { posix_spawn_file_actions_init(&actions); }
    ~SpawnActions() { posix_spawn_file_actions_destroy(&actions); }
};

}  // namespace

ProcessResult run_process(const std::vector<std::string>& argv, double timeout_seconds) {
    DYNMESH_CHECK(!argv.empty() && !argv[0].empty(), "run_process: no program given");
    ProcessResult r;
    std::vector<char*> args;
    args.reserve(argv.size() + 1);
    for (const std::string& s : argv) args.push_back(const_cast<char*>(s.c_str()));
    args.push_back(nullptr);

    int pipe_fd[2] = {-1, -1};
    if (::pipe2(pipe_fd, O_CLOEXEC) != 0) {
        r.error_tail = "cannot create a pipe: " + std::generic_category().message(errno);
        return r;
    }
    SpawnActions sa;
    posix_spawn_file_actions_addopen(&sa.actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&sa.actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&sa.actions, pipe_fd[1], 2);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, args[0], &sa.actions, nullptr, args.data(), environ);
    ::close(pipe_fd[1]);
    if (rc != 0) {
        ::close(pipe_fd[0]);
        r.error_tail = argv[0] + ": " + std::generic_category().message(rc);
        return r;
    }
    r.started = true;
    g_running.store(pid);
    TailLine tail;
    char buf[4096];
    const auto start = std::chrono::steady_clock::now();
    bool exited = false, pipe_open = true;
    int status = 0;
    while (!exited) {
        if (pipe_open) {
            pollfd p{pipe_fd[0], POLLIN, 0};
            if (::poll(&p, 1, 100) > 0) {
                const ssize_t n = ::read(pipe_fd[0], buf, sizeof buf);
                if (n > 0) tail.add(buf, static_cast<std::size_t>(n));
                else if (n == 0 || errno != EINTR) pipe_open = false;
            }
        } else {
            ::usleep(100000);
        }
        const pid_t w = ::waitpid(pid, &status, WNOHANG);
        if (w == pid) exited = true;
        if (!exited && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
                           timeout_seconds) {
            ::kill(pid, SIGKILL);
            while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            r.timed_out = true;
            exited = true;
        }
    }
    g_running.store(0);
    // What the program wrote before it exited (without waiting for descendants).
    ::fcntl(pipe_fd[0], F_SETFL, O_NONBLOCK);
    for (ssize_t n; pipe_open && (n = ::read(pipe_fd[0], buf, sizeof buf)) > 0;)
        tail.add(buf, static_cast<std::size_t>(n));
    ::close(pipe_fd[0]);
    if (WIFEXITED(status) && !r.timed_out) r.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
    r.error_tail = tail.line();
    return r;
}

void kill_running_process() noexcept {
    const pid_t pid = g_running.exchange(0);
    if (pid <= 0) return;
    ::kill(pid, SIGKILL);
    while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
    }
}

fs::path executable_directory() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path{} : exe.parent_path();
}

fs::path find_bundled_script(std::string_view name) {
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv("DYNMESH_SCRIPTS_DIR"); env != nullptr && *env != '\0')
        dirs.emplace_back(env);
    if (const fs::path exe = executable_directory(); !exe.empty())
        dirs.push_back(exe.parent_path() / "share" / "dynmesh" / "scripts");
    for (const fs::path& d : dirs) {
        std::error_code ec;
        const fs::path p = d / name;
        if (fs::is_regular_file(p, ec)) return p;
    }
    return {};
}

fs::path plotting_python() { return "/usr/bin/python3"; }

}  // namespace dynmesh
