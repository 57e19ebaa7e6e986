#pragma once
/// \file Atomic writing of small text files (reports, CSV logs).

#include <filesystem>
#include <string_view>

namespace dynmesh {

/// Writes `text` to `path` atomically: a temporary file in the same directory, renamed over
/// the target when complete. \throw IoError naming the path on any failure (the target is
/// then left as it was and no temporary file remains).
void write_text_file(const std::filesystem::path& path, std::string_view text);

}  // namespace dynmesh
