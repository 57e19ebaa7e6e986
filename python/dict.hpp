#pragma once
// Reports as dicts with the CLI's field names and types.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/metrics/quality.hpp"

namespace dynmesh::python {

/// A figure of a check with its kind: int, bool or float.
inline pybind11::object figure_value(const CheckFigure& f) {
    switch (f.kind) {
        case CheckFigure::Kind::Integer: return pybind11::int_(static_cast<long long>(f.value));
        case CheckFigure::Kind::Boolean: return pybind11::bool_(f.value != 0);
        case CheckFigure::Kind::Real: break;
    }
    return pybind11::float_(f.value);
}

/// Copies the named figures of `check` into `d` (the names the CLI's report uses).
inline void copy_figures(pybind11::dict& d, const CheckReport& check, std::initializer_list<const char*> names) {
    for (const char* name : names)
        for (const CheckFigure& f : check.figures)
            if (f.name == name) d[pybind11::str(name)] = figure_value(f);
}

/// A check as a dict: every figure, then ok, problems (the listed ones), n_problems (all of
/// them) and notes (findings that do not fail the check).
inline pybind11::dict check_dict(const CheckReport& check) {
    pybind11::dict d;
    for (const CheckFigure& f : check.figures) d[pybind11::str(f.name)] = figure_value(f);
    d["ok"] = check.ok();
    d["problems"] = check.problems;
    d["n_problems"] = check.n_problems;
    d["notes"] = check.notes;
    return d;
}

/// The quality measures as `dynmesh stats --report` writes them (counts as int, "closed" as
/// bool, the rest as float).
inline pybind11::dict quality_dict(const std::vector<std::pair<std::string, double>>& fields) {
    pybind11::dict d;
    for (const auto& [name, value] : fields) d[pybind11::str(name)] = figure_value({name, value, quality_field_kind(name)});
    return d;
}

}  // namespace dynmesh::python
