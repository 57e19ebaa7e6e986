#pragma once
/// \file Internal: the number and point formatting of the quadtree capability's messages
/// ("%.17g", which round-trips every double).

#include <cstddef>
#include <cstdio>
#include <string>

#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh::detail {

inline std::string format_double(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

/// "(x, y)" / "(x, y, z)".
template <int D>
std::string format_point(const PointD<D>& p) {
    std::string s = "(";
    for (int i = 0; i < D; ++i) {
        if (i) s += ", ";
        s += format_double(p[static_cast<std::size_t>(i)]);
    }
    return s + ")";
}

}  // namespace dynmesh::detail
