#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh {
namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

/// Splits "a,b,c" into finite numbers; `what` names the list in error messages.
std::vector<double> parse_numbers(std::string_view list, const std::string& fail_prefix,
                                  const char* what) {
    std::vector<double> out;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = list.find(',', start);
        const std::string_view tok =
            trim(list.substr(start, comma == std::string_view::npos ? list.npos : comma - start));
        double v = 0;
        const auto res = std::from_chars(tok.data(), tok.data() + tok.size(), v);
        if (tok.empty() || res.ec != std::errc() || res.ptr != tok.data() + tok.size())
            throw InvalidInput(fail_prefix + what + " '" + std::string(tok) + "' is not a number");
        if (!std::isfinite(v))
            throw InvalidInput(fail_prefix + what + " '" + std::string(tok) + "' is not finite");
        out.push_back(v);
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    return out;
}

}  // namespace

std::unique_ptr<ImplicitSurface> make_surface(const std::string& spec) {
    const std::string fail = "make_surface(\"" + spec + "\"): ";
    std::string_view body = spec, center_text;
    const std::size_t at = body.find('@');
    if (at != std::string_view::npos) {
        center_text = body.substr(at + 1);
        body = body.substr(0, at);
    }
    const std::size_t colon = body.find(':');
    const bool has_params = colon != std::string_view::npos;
    const std::string_view name = trim(body.substr(0, colon));
    const std::string_view params_text = has_params ? body.substr(colon + 1) : std::string_view();
    if (name != "sphere" && name != "ellipsoid" && name != "torus")
        throw InvalidInput(fail + "unknown surface '" + std::string(name) +
                           "' (expected sphere, sphere:R, ellipsoid:a,b,c or torus:R,r, "
                           "optionally followed by @cx,cy,cz)");
    Point3 center{};
    if (at != std::string_view::npos) {
        const auto c = parse_numbers(center_text, fail, "centre coordinate");
        if (c.size() != 3)
            throw InvalidInput(fail + "the centre needs 3 coordinates \"@cx,cy,cz\", got " +
                               std::to_string(c.size()));
        center = {c[0], c[1], c[2]};
    }
    std::vector<double> p;
    if (has_params) p = parse_numbers(params_text, fail, "parameter");

    auto expect = [&](std::size_t count, const char* form) {
        if (p.size() != count)
            throw InvalidInput(fail + std::string(name) + " takes " + std::to_string(count) +
                               (count == 1 ? " parameter" : " parameters") + " (\"" + form +
                               "\"), got " + std::to_string(p.size()));
    };
    if (name == "sphere" && !has_params) p = {1.0};
    // Sizes double precision resolves: every length in [1e-50, 1e50], and the centre within
    // 1e9 sizes of the origin (so points on the surface keep 7 significant digits of it).
    double smallest = INFINITY;
    for (const double x : p) {
        if (std::fabs(x) > 0) smallest = std::min(smallest, std::fabs(x));
        if (std::fabs(x) > 1e50 || (x != 0 && std::fabs(x) < 1e-50))
            throw InvalidInput(fail + "parameter " + std::to_string(x) +
                               " is outside the supported range [1e-50, 1e50]");
    }
    const double far = std::max({std::fabs(center.x), std::fabs(center.y), std::fabs(center.z)});
    if (far > 1e50 || (std::isfinite(smallest) && far > 1e9 * smallest))
        throw InvalidInput(fail + "the centre is too far from the origin for the surface's size "
                                  "(|centre| must be <= 1e9 times its smallest parameter and <= 1e50)");
    try {
        if (name == "sphere") {
            expect(1, "sphere:R");
            return std::make_unique<Sphere>(center, p[0]);
        }
        if (name == "ellipsoid") {
            expect(3, "ellipsoid:a,b,c");
            return std::make_unique<Ellipsoid>(center, p[0], p[1], p[2]);
        }
        if (name == "torus") {
            expect(2, "torus:R,r");
            return std::make_unique<Torus>(center, p[0], p[1]);
        }
    } catch (const InvalidInput& e) {
        const std::string what = e.what();
        if (what.rfind(fail, 0) == 0) throw;  // already names the spec
        throw InvalidInput(fail + what);
    }
    throw InternalError(fail + "unhandled surface name");
}

}  // namespace dynmesh
