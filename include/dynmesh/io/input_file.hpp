#pragma once
/// \file The one checked reader behind every file argument of dynmesh: meshes, point sets,
/// update scripts and vertex lists all come through read_input_file().
///
/// What it guarantees
/// - Only regular files are read. The file is opened without blocking and checked with
///   fstat() on the open descriptor, so a FIFO, a device (`/dev/zero`), a socket or a
///   directory is refused at once, never read from (no hang, no endless input), and a file
///   swapped for a FIFO between a check and the open cannot slip through.
/// - The size is capped before anything is allocated (`max_bytes`); the message names the
///   file, its size and the cap.
/// - A file that cannot be opened or read (permissions, I/O error) is an error naming the file
///   and the system's reason.
/// Text parsers then skip a leading UTF-8 byte-order mark and count lines from 1 on the
/// original text (see `skip_utf8_bom`), so line numbers in messages match an editor's.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace dynmesh {

/// Default size caps: mesh and point files (binary PLY of tens of millions of triangles
/// fits), and small text inputs (update scripts, vertex lists).
inline constexpr std::uint64_t kMaxMeshFileBytes = std::uint64_t{4} << 30;   // 4 GiB
inline constexpr std::uint64_t kMaxScriptFileBytes = std::uint64_t{1} << 30;  // 1 GiB

/// The whole content of the regular file `path`.
/// \throw IoError "<file>: <problem>" when the file does not exist, is not a regular file,
///        cannot be opened or read, or is larger than `max_bytes`.
[[nodiscard]] std::string read_input_file(const std::filesystem::path& path,
                                          std::uint64_t max_bytes = kMaxMeshFileBytes);

/// `text` without a leading UTF-8 byte-order mark (EF BB BF), if it has one.
[[nodiscard]] constexpr std::string_view skip_utf8_bom(std::string_view text) {
    return text.starts_with("\xEF\xBB\xBF") ? text.substr(3) : text;
}

}  // namespace dynmesh
