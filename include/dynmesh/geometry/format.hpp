#pragma once
/// \file Numbers and points in messages: the shortest decimal text that reads back as the same
/// double (std::to_chars), so an error names exactly the value it is about.

#include <array>
#include <charconv>
#include <cstddef>
#include <string>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

/// The shortest round-trip decimal form of v ("0.1", "1e+300", "nan", "inf").
[[nodiscard]] inline std::string format_number(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

/// "(x, y, ...)" with format_number coordinates.
template <std::size_t D>
[[nodiscard]] std::string format_point(const std::array<double, D>& p) {
    std::string s = "(";
    for (std::size_t i = 0; i < D; ++i) {
        if (i) s += ", ";
        s += format_number(p[i]);
    }
    return s + ")";
}
[[nodiscard]] inline std::string format_point(const Vec3& p) {
    return format_point(std::array<double, 3>{p.x, p.y, p.z});
}
[[nodiscard]] inline std::string format_point(const Vec2& p) {
    return format_point(std::array<double, 2>{p.x, p.y});
}

}  // namespace dynmesh
