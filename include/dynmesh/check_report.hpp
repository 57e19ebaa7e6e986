#pragma once
/// \file CheckReport: what every check_*() function and every check_invariants() member
/// returns. The problems found (listed up to a cap, all of them counted), an ordered list of
/// named figures the check measured, and notes: findings reported without failing the check.
/// The figure names are the keys under which `dynmesh --report` writes them.

#include <concepts>
#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace dynmesh {

/// One measured figure of a check. Counts and flags keep their kind so that a writer can
/// print them as integers and booleans.
struct CheckFigure {
    enum class Kind { Real, Integer, Boolean };
    std::string name;
    double value = 0;
    Kind kind = Kind::Real;
};

struct CheckReport {
    std::vector<std::string> problems;  ///< one line per violation (possibly capped)
    std::size_t n_problems = 0;         ///< all violations, including unlisted ones
    std::vector<CheckFigure> figures;   ///< in the order the check added them
    /// Findings reported without failing the check (e.g. a soft finding the check's options
    /// let pass), one line each. They do not count as problems and do not affect ok().
    std::vector<std::string> notes;

    /// Records a figure: bool as Boolean, integers as Integer (exact below 2^53), floating
    /// point as Real. \throw InvalidInput if a figure of that name is already there.
    template <class T>
        requires std::is_arithmetic_v<T>
    void add(std::string name, T value) {
        if constexpr (std::same_as<T, bool>)
            add_figure(std::move(name), value ? 1.0 : 0.0, CheckFigure::Kind::Boolean);
        else if constexpr (std::is_integral_v<T>)
            add_figure(std::move(name), static_cast<double>(value), CheckFigure::Kind::Integer);
        else
            add_figure(std::move(name), static_cast<double>(value), CheckFigure::Kind::Real);
    }
    /// A report of these problems (all listed) and no figure.
    [[nodiscard]] static CheckReport of_problems(std::vector<std::string> problems);

    /// Records a problem: counted always, listed while fewer than `max_listed` are.
    void fail(std::string problem, std::size_t max_listed = static_cast<std::size_t>(-1));

    /// The figure's value (a Boolean is 0 or 1). \throw InternalError for an unknown name (a caller's bug).
    [[nodiscard]] double figure(std::string_view name) const;
    /// An Integer figure as an integer. \throw InternalError for an unknown name or a figure
    ///        of another kind.
    [[nodiscard]] long long integer(std::string_view name) const;
    /// A Boolean figure. \throw InternalError for an unknown name or a figure of another kind.
    [[nodiscard]] bool flag(std::string_view name) const;
    /// True when the check recorded a figure of that name.
    [[nodiscard]] bool has(std::string_view name) const;
    /// True when the check found no problem.
    [[nodiscard]] bool ok() const { return n_problems == 0 && problems.empty(); }
    /// All listed problems, one per line, prefixed with `prefix`, then "... and N more" when
    /// some were only counted.
    [[nodiscard]] std::string summary(const std::string& prefix = "") const;

private:
    [[nodiscard]] const CheckFigure& find(std::string_view name, const char* who) const;
    void add_figure(std::string name, double value, CheckFigure::Kind kind);
};

}  // namespace dynmesh
