#include "dynmesh/io/output_set.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <random>
#include <system_error>

#include "dynmesh/error.hpp"
#include "dynmesh/system/process.hpp"
#include "io_common.hpp"

namespace dynmesh {

namespace fs = std::filesystem;

// ---- signal cleanup: a fixed table of staged paths, readable from a signal handler ---------

namespace {

constexpr int kCleanupSlots = 256;
constexpr std::size_t kCleanupPath = 4096;

struct CleanupSlot {
    std::atomic<int> state{0};  // 0 free, 1 being written, 2 a file, 3 a directory
    char path[kCleanupPath]{};
};
std::array<CleanupSlot, kCleanupSlots> g_cleanup;

int cleanup_add(const fs::path& p, bool directory) {
    const std::string s = p.string();
    if (s.size() >= kCleanupPath) return -1;
    for (int i = 0; i < kCleanupSlots; ++i) {
        int expected = 0;
        if (!g_cleanup[i].state.compare_exchange_strong(expected, 1)) continue;
        std::memcpy(g_cleanup[i].path, s.c_str(), s.size() + 1);
        g_cleanup[i].state.store(directory ? 3 : 2);
        return i;
    }
    return -1;
}

void cleanup_remove(int slot) {
    if (slot >= 0) g_cleanup[static_cast<std::size_t>(slot)].state.store(0);
}

/// Async-signal-safe enough: unlink, rmdir and a flat directory scan (staging directories
/// hold only files).
void remove_staged_now() {
    for (CleanupSlot& slot : g_cleanup) {
        const int state = slot.state.load();
        if (state == 2) {
            ::unlink(slot.path);
        } else if (state == 3) {
            if (DIR* d = ::opendir(slot.path)) {
                const int fd = ::dirfd(d);
                while (const dirent* e = ::readdir(d))
                    if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0)
                        ::unlinkat(fd, e->d_name, 0);
                ::closedir(d);
            }
            ::rmdir(slot.path);
        }
    }
}

extern "C" void dynmesh_output_signal_handler(int sig) {
    kill_running_process();  // a plotting child must not write after the cleanup
    remove_staged_now();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

}  // namespace

void install_output_cleanup_on_signals() {
    static std::atomic<bool> installed{false};
    if (installed.exchange(true)) return;
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction sa {};
        sa.sa_handler = dynmesh_output_signal_handler;
        sigemptyset(&sa.sa_mask);
        sa.sa_flags = 0;
        ::sigaction(sig, &sa, nullptr);
    }
}

// ---- OutputSet ------------------------------------------------------------------------------

namespace {

std::string shown(const fs::path& p) { return detail::quote_text(p.string()); }

/// Absolute and normalised, with the symbolic links of its existing part followed.
/// \throw InvalidInput for a path that cannot be resolved (e.g. /dev/stdout on a pipe).
fs::path resolve(const fs::path& p, std::string_view what) {
    std::error_code ec;
    const fs::path abs = fs::absolute(p, ec);
    if (ec) throw InvalidInput(std::string(what) + " " + shown(p) + ": cannot resolve the path: " + ec.message());
    const fs::path r = fs::weakly_canonical(abs, ec);
    if (ec || !r.is_absolute())
        throw InvalidInput(std::string(what) + " " + shown(p) + ": cannot resolve the path" +
                           (ec ? ": " + ec.message() : std::string()));
    return r;
}

/// Whether `a` and `b` are the same file: equal resolved paths, or existing hard links.
bool same_file(const fs::path& a, const fs::path& b) {
    if (a == b) return true;
    std::error_code ec;
    return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec) && !ec;
}

/// Whether `inner` lies strictly inside the directory `dir`.
bool inside(const fs::path& inner, const fs::path& dir) {
    const fs::path rel = inner.lexically_relative(dir);
    return !rel.empty() && *rel.begin() != ".." && rel != ".";
}

std::string random_tag() {
    static std::atomic<unsigned> counter{0};
    std::random_device rd;
    std::uint64_t x = (std::uint64_t{rd()} << 32) ^ rd() ^
                      (std::uint64_t{counter.fetch_add(1)} * 0x9e3779b97f4a7c15ull) ^
                      static_cast<std::uint64_t>(::getpid());
    static constexpr char kChars[] = "abcdefghijklmnopqrstuvwxyz0123456789";
    std::string s;
    for (int i = 0; i < 8; ++i, x /= 36) s.push_back(kChars[x % 36]);
    return s;
}

/// ".dynmesh-<tag>-<name>", with a long name shortened in its middle so that the result and
/// a writer's own temporary beside it (".<staged>.tmp-<12 chars>") fit in NAME_MAX; the
/// extension is always kept, since writers choose the format by it.
std::string staged_name(const std::string& name, const std::string& tag) {
    constexpr std::size_t kMax = 200;
    std::string prefix = ".dynmesh-" + tag + "-";
    if (prefix.size() + name.size() <= kMax) return prefix + name;
    const std::string ext = fs::path(name).extension().string();
    const std::size_t keep = kMax - prefix.size() - std::min(ext.size(), std::size_t{40});
    return prefix + name.substr(0, keep) + ext.substr(0, 40);
}

}  // namespace

OutputSet::OutputSet(std::vector<fs::path> inputs) {
    for (const fs::path& p : inputs) {
        if (p.empty()) continue;
        std::error_code ec;
        fs::path abs = fs::absolute(p, ec);
        fs::path r = fs::weakly_canonical(abs, ec);
        inputs_.push_back({p, ec ? abs.lexically_normal() : r, {}, "input"});
    }
}

void OutputSet::forget(Entry& e) {
    cleanup_remove(e.cleanup_slot);
    e.cleanup_slot = -1;
    detail::unregister_display_name(e.staged);
}

OutputSet::~OutputSet() {
    for (Entry& e : outputs_) {
        if ((!committed_ || e.scratch) && !e.staged.empty()) {
            std::error_code ec;
            if (e.directory)
                fs::remove_all(e.staged, ec);
            else
                fs::remove(e.staged, ec);
        }
        forget(e);
    }
}

void OutputSet::check_clashes(const Entry& e) const {
    for (const Entry& in : inputs_) {
        if (same_file(e.resolved, in.resolved))
            throw InvalidInput(e.what + " " + shown(e.target) + " is the input file " +
                               shown(in.target) + ": refusing to overwrite an input");
        if (e.directory && inside(in.resolved, e.resolved))
            throw InvalidInput(e.what + " " + shown(e.target) + " contains the input file " +
                               shown(in.target) + "; choose another directory");
    }
    for (const Entry& o : outputs_) {
        if (same_file(e.resolved, o.resolved))
            throw InvalidInput(e.what + " " + shown(e.target) + " and " + o.what + " " +
                               shown(o.target) + " are the same file");
        if ((o.directory && inside(e.resolved, o.resolved)) ||
            (e.directory && inside(o.resolved, e.resolved)))
            throw InvalidInput(e.what + " " + shown(e.target) + " and " + o.what + " " +
                               shown(o.target) +
                               ": one lies inside the other's output directory; choose "
                               "separate paths");
    }
}

fs::path OutputSet::reserve(const fs::path& target, std::string_view what, bool directory,
                            Order order) {
    if (committed_) throw InternalError("OutputSet: outputs registered after commit()");
    if (target.empty())
        throw InvalidInput(std::string(what) + ": an empty path is not a " +
                           (directory ? "directory" : "file") + " name");
    Entry e{target, resolve(target, what), {}, std::string(what), directory, false, false, order};
    const std::string name = e.resolved.filename().string();
    if (name.empty() || name == "." || name == "..")
        throw InvalidInput(e.what + " " + shown(target) + ": not a " +
                           (directory ? "directory" : "file") + " name");
    std::error_code ec;
    const fs::file_status st = fs::status(e.resolved, ec);
    const bool exists = fs::exists(st);
    if (!directory && fs::is_directory(st))
        throw InvalidInput(e.what + " " + shown(target) + " is a directory, not a file");
    if (!directory && exists && !fs::is_regular_file(st))
        throw InvalidInput(e.what + " " + shown(target) +
                           " exists and is not a regular file (a device, pipe or socket); "
                           "refusing to replace it");
    if (directory && exists && !fs::is_directory(st))
        throw InvalidInput(e.what + " " + shown(target) + " exists and is not a directory");
    const fs::path dir = e.resolved.parent_path();
    if (!fs::is_directory(dir, ec))
        throw InvalidInput(e.what + " " + shown(target) + ": the directory " + shown(dir) +
                           " does not exist");
    check_clashes(e);
    // An existing output directory is staged inside itself (it is the one that must be
    // writable); anything else beside its target.
    e.inside_target = directory && exists;
    const fs::path stage_dir = e.inside_target ? e.resolved : dir;
    // Reserve the staging name now: this also proves the directory is writable.
    for (int attempt = 0; attempt < 32 && e.staged.empty(); ++attempt) {
        const fs::path staged = stage_dir / staged_name(name, random_tag());
        errno = 0;
        if (directory) {
            if (::mkdir(staged.c_str(), 0777) == 0) e.staged = staged;
        } else {
            const int fd = ::open(staged.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
            if (fd >= 0) {
                ::close(fd);
                e.staged = staged;
            }
        }
        if (e.staged.empty() && errno != EEXIST) {
            const int err = errno;
            throw InvalidInput(e.what + " " + shown(target) + ": cannot write in " +
                               shown(stage_dir) + ": " + detail::errno_text(err));
        }
    }
    if (e.staged.empty())
        throw InvalidInput(e.what + " " + shown(target) + ": cannot reserve a temporary name");
    e.cleanup_slot = cleanup_add(e.staged, directory);
    detail::register_display_name(e.staged, e.target);
    outputs_.push_back(e);
    return outputs_.back().staged;
}

fs::path OutputSet::add_file(const fs::path& target, std::string_view what, Order order) {
    return reserve(target, what, false, order);
}

fs::path OutputSet::add_file_set(const fs::path& base, const std::vector<std::string>& extensions,
                                 std::string_view what) {
    if (extensions.empty()) throw InternalError("OutputSet::add_file_set: no extension");
    fs::path staged_base;
    for (const std::string& ext : extensions) {
        fs::path target = base;
        target += ext;
        const fs::path staged = reserve(target, what, false, Order::Normal);
        if (staged_base.empty()) {
            // The staged names share one base: the first one's, with each extension.
            const std::string n = staged.filename().string();
            if (!n.ends_with(ext)) throw InternalError("OutputSet::add_file_set: staged name lost its extension");
            staged_base = staged.parent_path() / n.substr(0, n.size() - ext.size());
            continue;
        }
        fs::path wanted = staged_base;
        wanted += ext;
        std::error_code ec;
        fs::rename(staged, wanted, ec);
        if (ec)
            throw InvalidInput(std::string(what) + " " + shown(target) +
                               ": cannot reserve a temporary name: " + ec.message());
        Entry& e = outputs_.back();
        forget(e);
        e.staged = wanted;
        e.cleanup_slot = cleanup_add(e.staged, false);
        detail::register_display_name(e.staged, e.target);
    }
    return staged_base;
}

fs::path OutputSet::add_directory(const fs::path& target, std::string_view what) {
    return reserve(target, what, true, Order::Normal);
}

fs::path OutputSet::scratch_directory(const fs::path& near) {
    const fs::path dir = resolve(near, "scratch").parent_path();
    for (int attempt = 0; attempt < 32; ++attempt) {
        const fs::path p = dir / (".dynmesh-" + random_tag() + "-scratch");
        if (::mkdir(p.c_str(), 0700) == 0) {
            Entry e{p, p, p, "scratch", true, false, true, Order::Normal};
            e.scratch = true;
            e.cleanup_slot = cleanup_add(p, true);
            outputs_.push_back(e);
            return p;
        }
        if (errno != EEXIST)
            throw IoError(detail::printable(dir.string(), 400) +
                          ": cannot create a scratch directory: " + detail::errno_text(errno));
    }
    throw IoError(detail::printable(dir.string(), 400) + ": cannot create a scratch directory");
}

namespace {

/// One rename of a commit, with what is needed to undo it.
struct Move {
    fs::path from, to;
    fs::path backup;      ///< a hard link to the old `to`, if it existed
    bool done = false;
    bool is_directory = false;
};

}  // namespace

void OutputSet::commit() {
    if (committed_) throw InternalError("OutputSet: commit() called twice");
    std::vector<Move> moves;
    std::vector<const Entry*> order;
    for (const Entry& e : outputs_)
        if (e.order == Order::Normal && !e.scratch) order.push_back(&e);
    for (const Entry& e : outputs_)
        if (e.order == Order::Last && !e.scratch) order.push_back(&e);
    std::error_code ec;
    for (const Entry* e : order) {
        if (!e->directory) {
            moves.push_back({e->staged, e->resolved});
        } else if (!e->inside_target && !fs::exists(e->resolved, ec)) {
            moves.push_back({e->staged, e->resolved, {}, false, true});
        } else {
            for (const fs::directory_entry& d : fs::directory_iterator(e->staged, ec))
                moves.push_back({d.path(), e->resolved / d.path().filename()});
            if (ec)
                throw IoError(detail::printable(e->target.string(), 400) +
                              ": cannot list the staged outputs: " + ec.message());
        }
    }
    const auto fail = [&](const Move& m, const std::string& why) {
        // Undo: put every replaced target back, remove every new one.
        for (auto it = moves.rbegin(); it != moves.rend(); ++it) {
            std::error_code ignored;
            if (it->done) {
                if (it->is_directory)
                    fs::rename(it->to, it->from, ignored);
                else if (!it->backup.empty())
                    fs::rename(it->backup, it->to, ignored);
                else
                    fs::rename(it->to, it->from, ignored);
            } else if (!it->backup.empty()) {
                fs::remove(it->backup, ignored);
            }
        }
        throw IoError(detail::display_name(m.to) + ": cannot move the finished output into place: " + why);
    };
    // 1. Keep every existing target reachable through a hard link, and give the staged file
    //    the target's permission bits.
    for (Move& m : moves) {
        struct stat st {};
        if (::lstat(m.to.c_str(), &st) != 0) continue;
        if (S_ISDIR(st.st_mode)) fail(m, "a directory of that name is in the way");
        if (!S_ISREG(st.st_mode)) fail(m, "not a regular file");
        const fs::path backup = m.to.parent_path() / staged_name(m.to.filename().string() + ".bak", random_tag());
        if (::link(m.to.c_str(), backup.c_str()) != 0) fail(m, detail::errno_text(errno));
        m.backup = backup;
        ::chmod(m.from.c_str(), st.st_mode & 07777);
    }
    // 2. The renames.
    for (Move& m : moves) {
        if (::rename(m.from.c_str(), m.to.c_str()) != 0) fail(m, detail::errno_text(errno));
        m.done = true;
    }
    // 3. Done: drop the backups and the emptied staging directories.
    for (const Move& m : moves)
        if (!m.backup.empty()) ::unlink(m.backup.c_str());
    for (Entry& e : outputs_) {
        if (e.scratch) continue;  // removed by the destructor
        if (e.directory && (e.inside_target || fs::exists(e.staged, ec))) fs::remove(e.staged, ec);
        forget(e);
        e.staged.clear();
    }
    committed_ = true;
}

}  // namespace dynmesh
