#pragma once
/// \file Helpers shared by the I/O tests: writing raw bytes, checking IoError messages.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "test_support.hpp"

namespace dynmesh::test {

inline void write_bytes(const std::filesystem::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    ASSERT_TRUE(out.good()) << p;
}

inline std::string read_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Files in `dir`, by name.
inline std::vector<std::string> listing(const std::filesystem::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

/// Expects read_soup(path) to throw a one-line IoError naming the file and containing every
/// string of `parts`.
inline void expect_read_error(const std::filesystem::path& path,
                              const std::vector<std::string>& parts) {
    const std::string msg = io_error_of([&] { (void)read_soup(path); });
    SCOPED_TRACE(path.string());
    EXPECT_NE(msg.find(path.filename().string()), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "multi-line message: " << msg;
    for (const auto& part : parts) EXPECT_NE(msg.find(part), std::string::npos) << msg;
}

}  // namespace dynmesh::test
