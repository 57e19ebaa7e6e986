#pragma once
/// \file Private helpers shared by the analytic surfaces: spec strings and argument checks.

#include <charconv>
#include <cmath>
#include <initializer_list>
#include <string>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/vec.hpp"

namespace dynmesh::detail {

/// Shortest decimal text that reads back to the same double ("5", "0.1", "1e-07").
inline std::string format_number(double v) {
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, res.ptr);
}

/// "name:p0,p1,..." plus "@cx,cy,cz" when the centre is not the origin.
inline std::string format_spec(const char* name, std::initializer_list<double> params,
                               const Point3& center) {
    std::string s = name;
    char sep = ':';
    for (double p : params) {
        s += sep;
        s += format_number(p);
        sep = ',';
    }
    if (center != Point3{}) {
        s += '@' + format_number(center.x) + ',' + format_number(center.y) + ',' +
             format_number(center.z);
    }
    return s;
}

inline void check_center(const char* who, const Point3& c) {
    if (!is_finite(c))
        throw InvalidInput(std::string(who) + ": the centre (" + format_number(c.x) + ", " +
                           format_number(c.y) + ", " + format_number(c.z) + ") is not finite");
}

inline void check_radius(const char* who, const char* what, double r) {
    if (!(std::isfinite(r) && r > 0))
        throw InvalidInput(std::string(who) + ": " + what + " must be positive and finite, got " +
                           format_number(r));
}

}  // namespace dynmesh::detail
