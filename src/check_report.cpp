#include "dynmesh/check_report.hpp"

#include "dynmesh/error.hpp"

namespace dynmesh {

void CheckReport::add_figure(std::string name, double value, CheckFigure::Kind kind) {
    if (has(name)) throw InvalidInput("CheckReport::add: the figure '" + name + "' is already there");
    figures.push_back({std::move(name), value, kind});
}

CheckReport CheckReport::of_problems(std::vector<std::string> problems) {
    CheckReport r;
    r.n_problems = problems.size();
    r.problems = std::move(problems);
    return r;
}

void CheckReport::fail(std::string problem, std::size_t max_listed) {
    ++n_problems;
    if (problems.size() < max_listed) problems.push_back(std::move(problem));
}

bool CheckReport::has(std::string_view name) const {
    for (const CheckFigure& f : figures)
        if (f.name == name) return true;
    return false;
}

const CheckFigure& CheckReport::find(std::string_view name, const char* who) const {
    for (const CheckFigure& f : figures)
        if (f.name == name) return f;
    throw InternalError(std::string("CheckReport::") + who + ": no figure '" + std::string(name) + "'");
}

double CheckReport::figure(std::string_view name) const { return find(name, "figure").value; }

long long CheckReport::integer(std::string_view name) const {
    const CheckFigure& f = find(name, "integer");
    if (f.kind != CheckFigure::Kind::Integer)
        throw InternalError("CheckReport::integer: the figure '" + f.name + "' is not an integer");
    return static_cast<long long>(f.value);
}

bool CheckReport::flag(std::string_view name) const {
    const CheckFigure& f = find(name, "flag");
    if (f.kind != CheckFigure::Kind::Boolean)
        throw InternalError("CheckReport::flag: the figure '" + f.name + "' is not a flag");
    return f.value != 0;
}

std::string CheckReport::summary(const std::string& prefix) const {
    std::string s;
    for (const auto& p : problems) s += prefix + p + "\n";
    if (n_problems > problems.size())
        s += prefix + "... and " + std::to_string(n_problems - problems.size()) + " more\n";
    return s;
}

}  // namespace dynmesh
