/// make_probe_object: spec strings to probing objects, with A1's interior points and A2's Ω.
#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>

#include "../io/io_common.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/geometry/format.hpp"
#include "dynmesh/io/input_file.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/io/text_inputs.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "dynmesh/probing/oracles2.hpp"
#include "dynmesh/shapes/surface.hpp"

namespace dynmesh {
namespace {

Ball omega_of(const Bbox3& b) {
    return {0.5 * (b.min + b.max), 1.1 * 0.5 * b.diagonal()};
}

/// The sizes a probing run handles: an object between 1e-50 and 1e50 across, at most 1e6 of
/// its sizes away from the origin (farther, double coordinates lose the precision the
/// probes need). \throw InvalidInput "<what>: ..." otherwise.
void check_extent(const Bbox3& box, const std::string& what) {
    // The longest side, not the diagonal: a diagonal of 1e300-sized sides overflows.
    const double size = std::max({box.max.x - box.min.x, box.max.y - box.min.y, box.max.z - box.min.z});
    double far = 0;
    for (const Point3& p : {box.min, box.max}) far = std::max({far, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    if (!(size >= 1e-50 && size <= 1e50))
        throw InvalidInput(what + ": the object is " + format_number(size) +
                           " across; probing handles objects from 1e-50 to 1e50 across");
    if (far > 1e6 * size)
        throw InvalidInput(what + ": the object is " + format_number(size) + " across but " + format_number(far) +
                           " from the origin: move it near the origin (coordinates that far lose the "
                           "precision the probes need)");
}

std::vector<Ball> read_balls(const std::string& path) {
    const detail::FileContext ctx(path);
    std::vector<Ball> balls;
    std::vector<std::size_t> lines;
    for (const NumberRow& row : read_four_number_rows(path, "x y z r", "ball")) {
        if (!(row.v[3] > 0)) ctx.fail_line(row.line, "the radius must be positive");
        balls.push_back({{row.v[0], row.v[1], row.v[2]}, row.v[3]});
        lines.push_back(row.line);
    }
    try {
        const BallsOracle check(balls);
    } catch (const InvalidInput& e) {
        const std::size_t i = e.element;
        if (i < lines.size()) ctx.fail_line(lines[i], e.what());
        throw;
    }
    return balls;
}

}  // namespace

ProbeSetup make_probe_object(const std::string& spec, OracleOptions options) {
    ProbeSetup out;
    out.spec = spec;
    const auto has_prefix = [&](std::string_view p) { return spec.starts_with(p); };
    if (has_prefix("sphere") || has_prefix("ellipsoid") || has_prefix("torus")) {
        const auto surface = make_surface(spec);
        if (const auto* s = dynamic_cast<const Sphere*>(surface.get()))
            out.object = std::make_unique<SphereOracle>(*s, options);
        else if (const auto* e = dynamic_cast<const Ellipsoid*>(surface.get()))
            out.object = std::make_unique<EllipsoidOracle>(*e, options);
        else if (const auto* t = dynamic_cast<const Torus*>(surface.get()))
            out.object = std::make_unique<TorusOracle>(*t, options);
        else
            throw InternalError("make_probe_object: unexpected surface type for " + spec);
        out.interior_points = {surface->interior_point()};
        out.omega = omega_of(surface->bbox());
        check_extent(surface->bbox(), spec);
    } else if (has_prefix("balls:")) {
        auto balls = read_balls(spec.substr(6));
        Bbox3 box;
        for (const Ball& b : balls) {
            out.interior_points.push_back(b.center);
            box.extend(b.center - Vec3{b.radius, b.radius, b.radius});
            box.extend(b.center + Vec3{b.radius, b.radius, b.radius});
        }
        check_extent(box, spec.substr(6));
        out.object = std::make_unique<BallsOracle>(std::move(balls), options);
        out.omega = omega_of(box);
    } else if (has_prefix("circle2:") || has_prefix("star2:")) {
        const bool circle = has_prefix("circle2:");
        const std::string arg = spec.substr(circle ? 8 : 6);
        double r = 0;
        if (!detail::parse_double(arg, r) || !std::isfinite(r) || !(r > 0))
            throw InvalidInput("make_probe_object: '" + spec + "': the radius must be a positive "
                               "number");
        check_extent({{-r, -r, 0}, {r, r, 0}}, spec);
        std::unique_ptr<PlanarStarOracle> o;
        if (circle)
            o = std::make_unique<CircleOracle2>(Point2{0, 0}, r, options);
        else
            o = std::make_unique<StarOracle2>(Point2{0, 0}, r, options);
        out.interior_points = {o->interior_point()};
        out.omega = o->default_omega();
        out.planar = true;
        out.object = std::move(o);
    } else if (spec == "genus2") {
        out.object = std::make_unique<Genus2Oracle>(options);
        out.interior_points = {Genus2Oracle::interior_point()};
        out.omega = omega_of(Genus2Oracle::bbox());
    } else if (spec.empty() || spec.find(':') != std::string::npos) {
        throw InvalidInput("make_probe_object: unknown object '" + spec +
                           "' (expected sphere:R, ellipsoid:a,b,c, torus:R,r, balls:FILE, "
                           "genus2, circle2:R, star2:R or a mesh file)");
    } else {
        out = make_probe_object(read_soup(spec), spec, options);
    }
    return out;
}

ProbeSetup make_probe_object(const TriangleSoup& soup, const std::string& name, OracleOptions options) {
    ProbeSetup out;
    out.spec = name;
    std::unique_ptr<MeshOracle> mesh;
    try {
        mesh = std::make_unique<MeshOracle>(soup, options);
    } catch (const InvalidInput& e) {
        throw InvalidInput(name + ": " + e.what());
    }
    check_extent(mesh->bbox(), name);
    out.interior_points = mesh->interior_points();
    out.omega = omega_of(mesh->bbox());
    out.object = std::move(mesh);
    return out;
}

}  // namespace dynmesh
