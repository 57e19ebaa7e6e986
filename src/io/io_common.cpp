#include "io_common.hpp"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <map>
#include <mutex>
#include <cmath>
#include <memory>
#include <system_error>

#include "dynmesh/error.hpp"

namespace dynmesh::detail {

namespace fs = std::filesystem;

std::string printable(std::string_view s, std::size_t max_len) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (out.size() >= max_len) {
            out += "...";
            break;
        }
        const auto c = static_cast<unsigned char>(s[i]);
        if (c >= 0x20 && c < 0x7f) {
            out.push_back(static_cast<char>(c));
        } else {
            out += "\\x";
            out.push_back(kHex[c >> 4]);
            out.push_back(kHex[c & 15]);
        }
    }
    return out;
}

std::string quote_text(std::string_view s) {
    std::string out(1, '\'');
    out += printable(s);
    out += '\'';
    return out;
}

std::string lower_extension(const fs::path& p) {
    std::string ext = p.extension().string();
    for (char& c : ext)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return ext;
}

std::string join_list(const std::vector<std::string>& items) {
    std::string s;
    for (const auto& item : items) {
        if (!s.empty()) s += ", ";
        s += item;
    }
    return s;
}

namespace {

std::mutex& display_mutex() {
    static std::mutex m;
    return m;
}
std::map<std::string, std::string>& display_names() {
    static std::map<std::string, std::string> names;
    return names;
}

}  // namespace

void register_display_name(const fs::path& staged, const fs::path& target) {
    const std::lock_guard<std::mutex> lock(display_mutex());
    display_names()[staged.string()] = target.string();
}

void unregister_display_name(const fs::path& staged) {
    const std::lock_guard<std::mutex> lock(display_mutex());
    display_names().erase(staged.string());
}

std::string display_name(const fs::path& path) {
    {
        const std::lock_guard<std::mutex> lock(display_mutex());
        const auto& names = display_names();
        if (!names.empty()) {
            // The staged file itself, or a writer's temporary beside it.
            const auto it = names.find(path.string());
            if (it != names.end()) return printable(it->second, 400);
            for (const auto& [staged, target] : names)
                if (path.string().starts_with(staged + "/"))
                    return printable(target + path.string().substr(staged.size()), 400);
        }
    }
    return printable(path.string(), 400);
}

void FileContext::fail(const std::string& msg) const { throw IoError(name_ + ": " + msg); }

void FileContext::fail_line(std::size_t line, const std::string& msg) const {
    throw IoError(name_ + ":" + std::to_string(line) + ": " + msg);
}

void FileContext::fail_byte(std::size_t offset, const std::string& msg) const {
    throw IoError(name_ + ": byte offset " + std::to_string(offset) + ", " + msg);
}

std::string errno_text(int err) { return std::generic_category().message(err); }

Point3 parse_point(Tokens& tokens, const FileContext& ctx, std::size_t line, const char* kind,
                   std::size_t index) {
    Point3 p;
    for (std::size_t k = 0; k < 3; ++k) {
        std::string_view token;
        if (!tokens.next(token))
            ctx.fail_line(line, std::string(kind) + " " + std::to_string(index) +
                                    ": expected 3 coordinates, found " + std::to_string(k));
        double v = 0;
        if (!parse_double(token, v))
            ctx.fail_line(line, std::string(kind) + " " + std::to_string(index) +
                                    ": invalid coordinate " + quote_text(token) +
                                    " (expected a finite decimal number)");
        if (!std::isfinite(v))
            ctx.fail_line(line, std::string(kind) + " " + std::to_string(index) +
                                    " has a non-finite coordinate " + quote_text(token));
        p[k] = v;
    }
    return p;
}

// ---- AtomicWriter ------------------------------------------------------------------------

namespace {

std::string unique_suffix() {
    static std::atomic<std::uint64_t> counter{0};
    const auto now = static_cast<std::uint64_t>(
        std::chrono::high_resolution_clock::now().time_since_epoch().count());
    std::uint64_t x = now ^ (counter.fetch_add(1) * 0x9e3779b97f4a7c15ull);
    static constexpr char kHex[] = "0123456789abcdef";
    std::string s;
    for (int i = 0; i < 12; ++i, x >>= 4) s.push_back(kHex[x & 15]);
    return s;
}

}  // namespace

AtomicWriter::AtomicWriter(const fs::path& target) : target_(target), ctx_(target) {
    const std::string name = target.filename().string();
    if (name.empty() || name == "." || name == "..") ctx_.fail("not a file name");
    for (int attempt = 0; attempt < 16 && file_ == nullptr; ++attempt) {
        temp_ = target.parent_path() / ("." + name + ".tmp-" + unique_suffix());
        errno = 0;
        file_ = std::fopen(temp_.c_str(), "wbx");  // "x": never reuse an existing file
        if (file_ == nullptr && errno != EEXIST) break;
    }
    if (file_ == nullptr) {
        const int err = errno;
        const std::string dir = target.parent_path().empty() ? "." : target.parent_path().string();
        temp_.clear();
        ctx_.fail("cannot create a temporary file in directory '" + printable(dir, 400) +
                  "': " + errno_text(err));
    }
    buf_.reserve(kFlushSize + 4096);
}

AtomicWriter::~AtomicWriter() { discard(); }

void AtomicWriter::flush() {
    if (buf_.empty()) return;
    errno = 0;
    const std::size_t n = std::fwrite(buf_.data(), 1, buf_.size(), file_);
    if (n != buf_.size()) {
        const int err = errno;
        discard();
        ctx_.fail("write error: " + errno_text(err));
    }
    buf_.clear();
}

void AtomicWriter::commit() {
    if (file_ == nullptr) ctx_.fail("internal: commit() called twice");
    flush();
    errno = 0;
    const bool flushed = std::fflush(file_) == 0;
    const int err_flush = errno;
    const bool closed = std::fclose(file_) == 0;
    const int err_close = errno;
    file_ = nullptr;
    if (!flushed || !closed) {
        discard();
        ctx_.fail("write error: " + errno_text(flushed ? err_close : err_flush));
    }
    std::error_code ec;
    fs::rename(temp_, target_, ec);
    if (ec) {
        discard();
        ctx_.fail("cannot move the finished file into place: " + ec.message());
    }
    temp_.clear();
}

void AtomicWriter::discard() noexcept {
    if (file_ != nullptr) {
        std::fclose(file_);
        file_ = nullptr;
    }
    if (!temp_.empty()) {
        std::error_code ec;
        fs::remove(temp_, ec);
        temp_.clear();
    }
}

}  // namespace dynmesh::detail
