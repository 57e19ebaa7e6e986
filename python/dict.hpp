#pragma once
// Reports as dicts with the CLI's field names and types.
#include <pybind11/pybind11.h>

#include <string>
#include <utility>
#include <vector>

#include "dynmesh/metrics/quality.hpp"

namespace dynmesh::python {

/// The quality measures as `dynmesh stats --report` writes them (counts as int, "closed" as
/// bool, the rest as float).
inline pybind11::dict quality_dict(const std::vector<std::pair<std::string, double>>& fields) {
    pybind11::dict d;
    for (const auto& [name, value] : fields) {
        switch (quality_field_kind(name)) {
            case QualityFieldKind::Count: d[pybind11::str(name)] = static_cast<long long>(value); break;
            case QualityFieldKind::Flag: d[pybind11::str(name)] = value != 0; break;
            case QualityFieldKind::Real: d[pybind11::str(name)] = value; break;
        }
    }
    return d;
}

}  // namespace dynmesh::python
