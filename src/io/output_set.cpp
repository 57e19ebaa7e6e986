#include "dynmesh/io/output_set.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <random>
#include <system_error>

#include "dynmesh/error.hpp"
#include "io_common.hpp"

namespace dynmesh {

namespace fs = std::filesystem;

namespace {

/// Absolute and normalised, with the symbolic links of its existing part followed.
fs::path resolve(const fs::path& p) {
    std::error_code ec;
    fs::path abs = fs::absolute(p, ec);
    if (ec) abs = p;
    fs::path r = fs::weakly_canonical(abs, ec);
    return ec ? abs.lexically_normal() : r;
}

std::string shown(const fs::path& p) { return detail::quote_text(p.string()); }

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

}  // namespace

OutputSet::OutputSet(std::vector<fs::path> inputs) {
    for (const fs::path& p : inputs)
        if (!p.empty()) inputs_.push_back({p, resolve(p), {}, "input", false});
}

OutputSet::~OutputSet() {
    if (committed_) return;
    for (const Entry& e : outputs_) {
        if (e.staged.empty()) continue;
        std::error_code ec;
        if (e.directory)
            fs::remove_all(e.staged, ec);
        else
            fs::remove(e.staged, ec);
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

fs::path OutputSet::reserve(const fs::path& target, std::string_view what, bool directory) {
    DYNMESH_CHECK(!committed_, "OutputSet: outputs registered after commit()");
    Entry e{target, target.empty() ? fs::path{} : resolve(target), {}, std::string(what), directory};
    const std::string name = e.resolved.filename().string();
    if (target.empty() || name.empty() || name == "." || name == "..")
        throw InvalidInput(std::string(what) + " " + shown(target) + ": not a " +
                           (directory ? "directory" : "file") + " name");
    std::error_code ec;
    const fs::file_status st = fs::status(e.resolved, ec);
    if (!directory && fs::is_directory(st))
        throw InvalidInput(e.what + " " + shown(target) + " is a directory, not a file");
    if (directory && fs::exists(st) && !fs::is_directory(st))
        throw InvalidInput(e.what + " " + shown(target) + " exists and is not a directory");
    const fs::path dir = e.resolved.parent_path();
    if (!fs::is_directory(dir, ec))
        throw InvalidInput(e.what + " " + shown(target) + ": the directory " + shown(dir) +
                           " does not exist");
    check_clashes(e);
    // Reserve the staging name now: this also proves the directory is writable.
    for (int attempt = 0; attempt < 32 && e.staged.empty(); ++attempt) {
        const fs::path staged = dir / (".dynmesh-" + random_tag() + "-" + name);
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
            throw InvalidInput(e.what + " " + shown(target) + ": cannot write in " + shown(dir) +
                               ": " + detail::errno_text(err));
        }
    }
    if (e.staged.empty())
        throw InvalidInput(e.what + " " + shown(target) + ": cannot reserve a temporary name");
    outputs_.push_back(e);
    return outputs_.back().staged;
}

fs::path OutputSet::add_file(const fs::path& target, std::string_view what) {
    return reserve(target, what, false);
}

fs::path OutputSet::add_file_set(const fs::path& base, const std::vector<std::string>& extensions,
                                 std::string_view what) {
    DYNMESH_CHECK(!extensions.empty(), "OutputSet::add_file_set: no extension");
    fs::path staged_base;
    for (const std::string& ext : extensions) {
        fs::path target = base;
        target += ext;
        const fs::path staged = reserve(target, what, false);
        // The staged names share one base: the first one's, with each extension.
        if (staged_base.empty()) {
            staged_base = staged.parent_path() / staged.filename().string().substr(
                                                     0, staged.filename().string().size() - ext.size());
        } else {
            fs::path wanted = staged_base;
            wanted += ext;
            std::error_code ec;
            fs::rename(staged, wanted, ec);
            if (ec)
                throw InvalidInput(std::string(what) + " " + shown(target) +
                                   ": cannot reserve a temporary name: " + ec.message());
            outputs_.back().staged = wanted;
        }
    }
    return staged_base;
}

fs::path OutputSet::add_directory(const fs::path& target, std::string_view what) {
    return reserve(target, what, true);
}

void OutputSet::commit() {
    DYNMESH_CHECK(!committed_, "OutputSet: commit() called twice");
    for (Entry& e : outputs_) {
        std::error_code ec;
        if (!e.directory) {
            fs::rename(e.staged, e.resolved, ec);
        } else if (!fs::exists(e.resolved, ec)) {
            fs::rename(e.staged, e.resolved, ec);
        } else {
            for (const fs::directory_entry& d : fs::directory_iterator(e.staged, ec)) {
                fs::rename(d.path(), e.resolved / d.path().filename(), ec);
                if (ec) break;
            }
            if (!ec) fs::remove(e.staged, ec);
        }
        if (ec)
            throw IoError(detail::printable(e.target.string(), 400) +
                          ": cannot move the finished output into place: " + ec.message());
        e.staged.clear();
    }
    committed_ = true;
}

}  // namespace dynmesh
