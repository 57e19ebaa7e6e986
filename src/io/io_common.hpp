#pragma once
/// \file Internal helpers of the I/O module (not installed): error context, whole-file
/// loading, line and token scanning, number parsing, and the atomic buffered writer.

#include <bit>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh::detail {

/// A single-line, printable form of file content or a path: bytes outside printable ASCII
/// become `\xNN` and text longer than `max_len` is cut with "...".
std::string printable(std::string_view s, std::size_t max_len = 40);
/// `printable(s)` between single quotes.
std::string quote_text(std::string_view s);
/// Lower-case extension with its dot ("" when there is none).
std::string lower_extension(const std::filesystem::path& p);
/// "a, b, c".
std::string join_list(const std::vector<std::string>& items);

/// The system's text for an errno value.
std::string errno_text(int err);

/// Staging paths of OutputSet are shown in messages as the targets they stand for.
void register_display_name(const std::filesystem::path& staged, const std::filesystem::path& target);
void unregister_display_name(const std::filesystem::path& staged);
/// `path`, or the target it stages, as a printable one-line string.
std::string display_name(const std::filesystem::path& path);

/// Names one file in every error message about it.
class FileContext {
public:
    explicit FileContext(const std::filesystem::path& path) : name_(display_name(path)) {}
    [[nodiscard]] const std::string& name() const { return name_; }
    /// Throws IoError("<file>: msg").
    [[noreturn]] void fail(const std::string& msg) const;
    /// Throws IoError("<file>:<line>: msg").
    [[noreturn]] void fail_line(std::size_t line, const std::string& msg) const;
    /// Throws IoError("<file>: byte offset <offset>, msg").
    [[noreturn]] void fail_byte(std::size_t offset, const std::string& msg) const;

private:
    std::string name_;
};

/// The whole content of a regular file of at most `max_bytes` (read_input_file of
/// input_file.hpp, with the caller's context).
/// \throw IoError when the file is missing, not a regular file, too large or unreadable.
std::string load_file(const std::filesystem::path& path, const FileContext& ctx,
                      std::uint64_t max_bytes = std::uint64_t{4} << 30);

constexpr bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// Iterates over the lines of a text ('\n' ends a line; '\r' counts as a blank). A leading
/// UTF-8 byte-order mark is skipped; positions stay offsets into the whole text.
class LineReader {
public:
    explicit LineReader(std::string_view text)
        : text_(text), pos_(text.starts_with("\xEF\xBB\xBF") ? 3 : 0) {}
    /// The next line without its terminator; false at the end of the text.
    bool next(std::string_view& line) {
        if (pos_ >= text_.size()) return false;
        const std::size_t end = text_.find('\n', pos_);
        const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
        line = text_.substr(pos_, stop - pos_);
        pos_ = stop + 1;
        ++line_number_;
        return true;
    }
    /// 1-based number of the line last returned by next().
    [[nodiscard]] std::size_t line_number() const { return line_number_; }
    /// Bytes after the line last returned.
    [[nodiscard]] std::size_t remaining_bytes() const {
        return pos_ >= text_.size() ? 0 : text_.size() - pos_;
    }
    [[nodiscard]] std::size_t position() const { return pos_ < text_.size() ? pos_ : text_.size(); }

private:
    std::string_view text_;
    std::size_t pos_;
    std::size_t line_number_ = 0;
};

/// `line` without a `#` comment.
constexpr std::string_view strip_comment(std::string_view line) {
    const std::size_t hash = line.find('#');
    return hash == std::string_view::npos ? line : line.substr(0, hash);
}

/// Splits a line into blank-separated tokens.
class Tokens {
public:
    explicit Tokens(std::string_view line) : rest_(line) {}
    bool next(std::string_view& token) {
        std::size_t i = 0;
        while (i < rest_.size() && is_blank(rest_[i])) ++i;
        if (i == rest_.size()) {
            rest_ = {};
            return false;
        }
        std::size_t j = i;
        while (j < rest_.size() && !is_blank(rest_[j])) ++j;
        token = rest_.substr(i, j - i);
        rest_ = rest_.substr(j);
        return true;
    }
    [[nodiscard]] bool empty() const {
        for (char c : rest_)
            if (!is_blank(c)) return false;
        return true;
    }

private:
    std::string_view rest_;
};

/// Parses the whole token as a double (a leading '+' is allowed). False for anything else,
/// including overflow; NaN and infinity parse (callers reject them with a better message).
inline bool parse_double(std::string_view token, double& out) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty()) return false;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, out);
    return ec == std::errc() && ptr == end;
}

/// Parses the whole token as a decimal integer (a leading '+' is allowed).
inline bool parse_int(std::string_view token, std::int64_t& out) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty()) return false;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, out);
    return ec == std::errc() && ptr == end;
}

/// Reads three coordinates of element `kind` number `index` from `tokens`.
/// \throw IoError naming the line and the element for a missing, malformed or non-finite
///        coordinate.
Point3 parse_point(Tokens& tokens, const FileContext& ctx, std::size_t line, const char* kind,
                   std::size_t index);

/// True when `count` elements of at least `min_bytes_each` bytes each can fit in
/// `available` bytes (overflow-safe; a zero size always fits).
constexpr bool fits_in(std::uint64_t count, std::uint64_t min_bytes_each, std::uint64_t available) {
    return min_bytes_each == 0 || count <= available / min_bytes_each;
}

/// Buffered output to a temporary file next to `target`, renamed over `target` by commit().
/// Destroying an uncommitted writer removes the temporary file, so a failed write leaves
/// no trace and does not touch an existing target.
class AtomicWriter {
public:
    /// \throw IoError when the temporary file cannot be created.
    explicit AtomicWriter(const std::filesystem::path& target);
    AtomicWriter(const AtomicWriter&) = delete;
    AtomicWriter& operator=(const AtomicWriter&) = delete;
    ~AtomicWriter();

    void put(std::string_view s) {
        buf_.append(s);
        if (buf_.size() >= kFlushSize) flush();
    }
    void put(char c) {
        buf_.push_back(c);
        if (buf_.size() >= kFlushSize) flush();
    }
    /// Shortest decimal form that reads back to the same double.
    void put_number(double v) { put_chars(v); }
    void put_number(float v) { put_chars(v); }
    void put_number(std::uint64_t v) { put_chars(v); }
    void put_number(std::uint32_t v) { put_chars(v); }
    /// The bytes of `v` in little-endian order.
    template <class T>
    void put_little_endian(T v) {
        unsigned char bytes[sizeof(T)];
        std::memcpy(bytes, &v, sizeof(T));
        if constexpr (std::endian::native == std::endian::big)
            for (std::size_t i = 0; i < sizeof(T) / 2; ++i)
                std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
        put(std::string_view(reinterpret_cast<const char*>(bytes), sizeof(T)));
    }
    /// Flushes, closes and renames the temporary file over the target.
    /// \throw IoError on any failure (the temporary file is then removed).
    void commit();

private:
    static constexpr std::size_t kFlushSize = std::size_t{1} << 20;
    template <class T>
    void put_chars(T v) {
        char tmp[64];
        const auto res = std::to_chars(tmp, tmp + sizeof(tmp), v);
        put(std::string_view(tmp, static_cast<std::size_t>(res.ptr - tmp)));
    }
    void flush();
    void discard() noexcept;

    std::filesystem::path target_, temp_;
    FileContext ctx_;
    std::FILE* file_ = nullptr;
    std::string buf_;
};

}  // namespace dynmesh::detail
