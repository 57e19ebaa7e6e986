#pragma once
/// \file Internal helpers of the scenario sources (warp.cpp, scenario.cpp, sample_edits.cpp;
/// not installed): numbers in error messages and the checks of positive parameters.

#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>

#include "dynmesh/error.hpp"

namespace dynmesh::detail {

/// "No such point" for pool indices and ids.
inline constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/// x with 4 significant digits.
inline std::string fmt(double x) {
    std::ostringstream os;
    os.precision(4);
    os << x;
    return os.str();
}

/// \throw InvalidInput "who: what must be positive and finite (got x)" unless x is.
inline void check_positive(const char* who, const char* what, double x) {
    if (!(std::isfinite(x) && x > 0))
        throw InvalidInput(std::string(who) + ": " + what + " must be positive and finite (got " +
                           fmt(x) + ")");
}

}  // namespace dynmesh::detail
