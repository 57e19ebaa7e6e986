#include "dynmesh/deform/scenario.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <utility>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/mesh/normals.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "scenario_common.hpp"

namespace dynmesh {

using detail::fmt;
using detail::kNone;

namespace {

/// A cell size for n points spread over a surface with this bounding box: about the mean
/// spacing of a sphere-like surface.
double surface_cell(const Bbox3& box, std::size_t n) {
    const double d = box.diagonal();
    const double c = d / std::sqrt(static_cast<double>(std::max<std::size_t>(n, 1)));
    return c > 0 && std::isfinite(c) ? c : 1.0;
}

Bbox3 bbox_of(std::span<const Point3> pts) {
    Bbox3 b;
    for (const Point3& p : pts) b.extend(p);
    return b;
}

constexpr auto kAny = [](std::uint32_t) { return true; };

// ---- scenario construction -----------------------------------------------------------------

const std::vector<std::string>& analytic_names() {
    static const std::vector<std::string> names{"pulse",     "stretch", "twist", "bend",
                                                "boomerang", "rotate",  "dimple"};
    return names;
}
const std::vector<std::string>& warp_names() {
    static const std::vector<std::string> names{"bend", "twist", "pulse", "stretch", "rotate"};
    return names;
}
std::string joined(const std::vector<std::string>& v, const char* sep = ", ") {
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
    return s;
}

/// Drops the vertices no face uses (keeping the others' order).
SurfaceMesh without_isolated_vertices(const SurfaceMesh& mesh) {
    bool any = false;
    for (const Vertex v : mesh.vertices()) any = any || mesh.is_isolated(v);
    if (!any && !mesh.has_garbage()) return mesh;
    const TriangleSoup soup = mesh.to_soup();
    std::vector<std::uint32_t> map(soup.points.size(), kNone);
    for (const auto& t : soup.triangles)
        for (std::uint32_t i : t) map[i] = 0;
    TriangleSoup out;
    for (std::size_t i = 0; i < soup.points.size(); ++i)
        if (map[i] == 0) {
            map[i] = static_cast<std::uint32_t>(out.points.size());
            out.points.push_back(soup.points[i]);
        }
    out.triangles = soup.triangles;
    for (auto& t : out.triangles)
        for (std::uint32_t& i : t) i = map[i];
    return SurfaceMesh::from_soup(out);
}

/// One 1-to-4 midpoint subdivision of a closed mesh (no deleted elements). The geometry is
/// unchanged (new vertices lie on the old edges); old vertices keep their indices and the
/// midpoints follow. normals (one per vertex) is extended with the normalised mean of the
/// two end normals at every midpoint.
SurfaceMesh subdivided(const SurfaceMesh& mesh, std::vector<Vec3>& normals) {
    TriangleSoup soup = mesh.to_soup();
    const auto n = static_cast<std::uint64_t>(soup.points.size());
    std::unordered_map<std::uint64_t, std::uint32_t> mid;
    mid.reserve(soup.triangles.size() * 2);
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
        const std::uint64_t key = std::min(a, b) * n + std::max(a, b);
        const auto [it, fresh] = mid.emplace(key, static_cast<std::uint32_t>(soup.points.size()));
        if (fresh) {
            soup.points.push_back((soup.points[a] + soup.points[b]) * 0.5);
            Vec3 nm = normalized(normals[a] + normals[b]);
            if (nm == Vec3{}) nm = normals[a];
            normals.push_back(nm);
        }
        return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> tris;
    tris.reserve(4 * soup.triangles.size());
    for (const auto& t : soup.triangles) {
        const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]),
                            ca = midpoint(t[2], t[0]);
        tris.push_back({t[0], ab, ca});
        tris.push_back({t[1], bc, ab});
        tris.push_back({t[2], ca, bc});
        tris.push_back({ab, bc, ca});
    }
    soup.triangles = std::move(tris);
    return SurfaceMesh::from_soup(soup);
}

int horizon_of(int steps, double speed) {
    const double q = static_cast<double>(steps) / speed;
    const double r = std::round(q);
    const double h = std::abs(q - r) <= 1e-9 * std::max(1.0, q) ? r : std::ceil(q);
    if (!(h <= static_cast<double>(INT_MAX)))
        throw InvalidInput("make_scenario: steps / speed = " + fmt(q) +
                           " time units is too many (speed too small)");
    return std::max(1, static_cast<int>(h));
}

/// Largest |d phi / dt| over the pool points and the phases of one period (see
/// Scenario::lambda), without the safety factor.
double max_speed(const Warp& warp, double rate, std::span<const Point3> pool) {
    constexpr int kPhases = 64;
    constexpr double kDu = 1e-4;
    const double dt = kDu / rate;
    std::vector<std::pair<double, std::uint32_t>> best(pool.size(), {0.0, 0u});
    for (std::size_t i = 0; i < pool.size(); ++i) {
        for (int j = 0; j < kPhases; ++j) {
            const double t = (static_cast<double>(j) / kPhases) / rate;
            const double v =
                distance(warp.apply(t + dt, pool[i]), warp.apply(t - dt, pool[i])) / (2.0 * dt);
            if (v > best[i].first) best[i] = {v, static_cast<std::uint32_t>(j)};
        }
    }
    std::vector<std::uint32_t> order(pool.size());
    std::iota(order.begin(), order.end(), 0u);
    const std::size_t top = std::min<std::size_t>(16, order.size());
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(top), order.end(),
                      [&](std::uint32_t a, std::uint32_t b) {
                          return best[a].first > best[b].first ||
                                 (best[a].first == best[b].first && a < b);
                      });
    double vmax = 0;
    for (const auto& b : best) vmax = std::max(vmax, b.first);
    for (std::size_t r = 0; r < top; ++r) {
        const std::uint32_t i = order[r];
        const double u0 = static_cast<double>(best[i].second) / kPhases;
        for (int k = -64; k <= 64; ++k) {
            const double t = (u0 + static_cast<double>(k) / (64.0 * kPhases)) / rate;
            const double v =
                distance(warp.apply(t + dt, pool[i]), warp.apply(t - dt, pool[i])) / (2.0 * dt);
            vmax = std::max(vmax, v);
        }
    }
    return vmax;
}

/// Fills the fields every scenario derives from reference, initial, warp and rate.
void finish(Scenario& s) {
    const std::vector<Point3>& pool = s.reference.positions();
    s.length_scale = bbox_of(pool).diagonal();
    std::vector<Point3> p0;
    p0.reserve(s.initial.size());
    for (std::uint32_t i : s.initial) p0.push_back(pool[i]);

    s.h0 = covering_radius(reference_probes(s.reference), p0);

    // Typical spacing: median nearest-neighbour distance within P(0).
    const PointGrid g0 = PointGrid::bulk(surface_cell(bbox_of(p0), p0.size()), p0);
    std::vector<double> nn(p0.size());
    for (std::size_t i = 0; i < p0.size(); ++i) {
        const auto other = [i](std::uint32_t id) { return id != i; };
        nn[i] = g0.nearest(p0[i], PointGrid::positions(p0), other).second;
    }
    const auto mid = nn.begin() + static_cast<std::ptrdiff_t>(nn.size() / 2);
    std::nth_element(nn.begin(), mid, nn.end());
    s.spacing0 = *mid;
    if (!(s.spacing0 > 0))
        throw InvalidInput("make_scenario: '" + s.name +
                           "': more than half of the initial samples coincide with another one");

    s.density_radius = 4.0 * s.spacing0;
    const PointGrid gd = PointGrid::bulk(s.density_radius, p0);
    s.initial_density.assign(pool.size(), 0);
    for (std::size_t i = 0; i < pool.size(); ++i) {
        std::uint32_t n = 0;
        gd.for_each_within(pool[i], s.density_radius, PointGrid::positions(p0),
                           [&](std::uint32_t, double) { ++n; });
        s.initial_density[i] = n;
    }

    s.lambda = 1.05 * max_speed(*s.warp, s.rate, pool);
}

/// The "dimple" warp of a unit-sphere scenario whose reference and P(0) are built (see
/// make_scenario); `motion` receives its description.
std::unique_ptr<Warp> dimple_warp(const Scenario& s, double rate, std::string& motion) {
    std::vector<Point3> p0;
    p0.reserve(s.initial.size());
    for (std::uint32_t i : s.initial) p0.push_back(s.reference.positions()[i]);
    const double h0 = covering_radius(reference_probes(s.reference), p0);
    const double rho = 2.5 * h0, slide = h0, lift = 0.25 * h0;
    std::vector<Point3> centers;
    for (std::size_t k = 64; k >= 1; --k) {
        centers = fibonacci_sphere(k);
        double dmin = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < k; ++i)
            for (std::size_t j = i + 1; j < k; ++j)
                dmin = std::min(dmin, distance(centers[i], centers[j]));
        if (dmin >= 2.2 * rho) break;
    }
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    std::vector<Vec3> disp;
    disp.reserve(centers.size());
    for (std::size_t k = 0; k < centers.size(); ++k) {
        const Point3& c = centers[k];
        const Vec3 east = normalized(cross(Vec3{0, 0, 1}, c));  // no lattice point is a pole
        const Vec3 north = cross(c, east);
        const double a = golden * static_cast<double>(k);
        disp.push_back((east * std::cos(a) + north * std::sin(a)) * slide + c * lift);
    }
    motion = std::to_string(centers.size()) + " dimples (Fibonacci centres, bump radius " +
             fmt(rho) + " = 2.5 h0): each slides tangentially by up to " + fmt(slide) +
             " = h0 with an outward lift of " + fmt(lift) + " and back";
    return make_dimple_warp(std::move(centers), std::move(disp), rho, rate);
}

Scenario analytic_scenario(const std::string& name, const ScenarioOptions& o, double rate) {
    Scenario s;
    const std::string key = name == "boomerang" ? "bend" : name;
    s.name = key;
    s.rate = rate;
    const Point3 origin{0, 0, 0};
    std::string shape, motion;
    if (key == "twist") {
        s.surface0 = std::make_unique<Torus>(origin, 5.0, 3.0);
        s.warp = make_twist_warp(origin, {1, 0, 0}, 8.0, kPi / 4.0, rate);
        shape = "torus R=5 r=3 (axis z, reach 2)";
        motion = "twist about the x axis, end angle +-pi/4 at x=+-8 (ends turn by up to +-pi/2 "
                 "relative to each other), swinging both ways";
    } else {
        s.surface0 = std::make_unique<Sphere>(origin, 1.0);
        shape = "unit sphere";
        if (key == "pulse") {
            s.warp = make_pulse_warp(origin, 1.5, rate);
            motion = "radius 1 -> 1.5 -> 1";
        } else if (key == "stretch") {
            s.warp = make_stretch_warp(origin, {1, 0, 0}, 3.0, rate);
            motion = "stretched along x to a 3:1:1 ellipsoid and back";
        } else if (key == "bend") {
            s.warp = make_bend_warp(origin, {1, 0, 0}, {0, 1, 0}, 1.0, 2.0 * kPi / 3.0, 3.0, rate);
            motion = "stretched along x to 3:1:1, bent about z into an arc turning by 2pi/3 "
                     "(radius 2.86), then back";
        } else if (key == "rotate") {
            s.warp = make_rotation_warp(origin, {1, 2, 3}, rate);
            motion = "one rigid turn about (1,2,3)";
        }  // dimple: the warp depends on h0, made once P(0) is known (below)
    }
    const std::size_t m = o.samples * o.pool_factor;
    const std::vector<Point3> candidates = s.surface0->sample_uniform(m, o.seed);
    RestrictedDelaunayResult rdt;
    try {
        rdt = restricted_delaunay_with_report(candidates, *s.surface0);
    } catch (const InvalidInput& e) {
        throw InvalidInput("make_scenario: '" + name + "': a pool of " + std::to_string(m) +
                           " points is too sparse to mesh " + shape + " (" + e.what() +
                           "); use more samples");
    }
    s.reference = std::move(rdt.mesh);
    const long long expected_euler = key == "twist" ? 0 : 2;
    MeshCheckOptions co;
    co.require_closed = true;
    co.check_degenerate = false;
    const CheckReport rep = check_mesh(s.reference, co);
    if (!rep.ok() || rep.integer("euler") != expected_euler || rep.integer("components") != 1)
        throw InvalidInput("make_scenario: '" + name + "': a pool of " + std::to_string(m) +
                           " points is too sparse to mesh " + shape +
                           " (restricted Delaunay triangulation: Euler characteristic " +
                           std::to_string(rep.integer("euler")) + ", expected " +
                           std::to_string(expected_euler) + "); use more samples");
    // Pool points the RDT left out are dropped; P(0) = the first `samples` candidates kept.
    const std::vector<std::uint32_t>& vs = rdt.report.vertex_sample;
    for (std::size_t v = 0; v < vs.size(); ++v)
        if (vs[v] < o.samples) s.initial.push_back(static_cast<std::uint32_t>(v));
    s.normals0.reserve(s.reference.n_vertices());
    for (const Point3& p : s.reference.positions()) s.normals0.push_back(s.surface0->normal(p));
    if (key == "dimple") s.warp = dimple_warp(s, rate, motion);
    s.edits = o.edits.value_or(false);
    s.description = shape + ", " + motion + "; pool " + std::to_string(s.pool_size()) +
                    " points (" + std::to_string(m - s.pool_size()) + " dropped by the RDT), " +
                    std::to_string(s.initial.size()) + " initial samples";
    return s;
}

Scenario mesh_scenario(const std::string& path, const ScenarioOptions& o, double rate) {
    const std::string warp = o.warp.empty() ? "bend" : o.warp;
    if (std::find(warp_names().begin(), warp_names().end(), warp) == warp_names().end())
        throw InvalidInput("make_scenario: unknown warp '" + warp + "' (valid: " +
                           joined(warp_names(), "|") + ")");
    SurfaceMesh mesh;
    try {
        mesh = without_isolated_vertices(read_mesh(path));
    } catch (const Error& e) {
        throw InvalidInput("make_scenario: cannot use mesh file '" + path + "': " + e.what());
    }
    MeshCheckOptions co;
    co.require_closed = true;
    co.check_degenerate = false;
    const CheckReport rep = check_mesh(mesh, co);
    if (!rep.ok())
        throw InvalidInput("make_scenario: mesh file '" + path +
                           "' is not a closed oriented 2-manifold (" +
                           std::to_string(rep.integer("boundary_edges")) + " boundary edges, " +
                           std::to_string(rep.n_problems) + " problems):\n" + rep.summary("  "));

    Scenario s;
    s.name = "mesh:" + std::filesystem::path(path).filename().string() + "+" + warp;
    s.rate = rate;
    // The pool: the input vertices, plus (flat) midpoint subdivisions of the input until the
    // pool holds about pool_factor times |P(0)| points, so that there is something to insert
    // where the surface stretches.
    const std::size_t nv = mesh.n_vertices();
    const std::size_t n_init = std::min(o.samples, nv);
    s.normals0 = vertex_normals(mesh);
    s.input_mesh = mesh;
    int levels = 0;
    while (levels < 3 && 2 * mesh.n_vertices() < o.pool_factor * n_init) {
        mesh = subdivided(mesh, s.normals0);
        ++levels;
    }
    s.reference = std::move(mesh);
    if (o.samples >= nv) {
        s.initial.resize(nv);
        std::iota(s.initial.begin(), s.initial.end(), 0u);
    } else {  // partial Fisher-Yates
        std::vector<std::uint32_t> idx(nv);
        std::iota(idx.begin(), idx.end(), 0u);
        Rng rng(o.seed);
        for (std::size_t i = 0; i < o.samples; ++i) {
            const std::size_t j = i + static_cast<std::size_t>(rng.below(nv - i));
            std::swap(idx[i], idx[j]);
        }
        s.initial.assign(idx.begin(), idx.begin() + static_cast<std::ptrdiff_t>(o.samples));
        std::sort(s.initial.begin(), s.initial.end());
    }

    // The frame of the bounding box: e1 longest extent, e2 the second.
    const Bbox3 box = bbox_of(s.reference.positions());
    const Point3 c = (box.min + box.max) * 0.5;
    std::array<int, 3> ax{0, 1, 2};
    const Vec3 ext = box.max - box.min;
    std::stable_sort(ax.begin(), ax.end(), [&](int a, int b) { return ext[a] > ext[b]; });
    Vec3 e1{}, e2{};
    e1[static_cast<std::size_t>(ax[0])] = 1;
    e2[static_cast<std::size_t>(ax[1])] = 1;
    const double half_l = 0.5 * ext[static_cast<std::size_t>(ax[0])];
    const double half_w = std::max(0.5 * ext[static_cast<std::size_t>(ax[1])], 1e-12 * half_l);
    const char* names = "xyz";
    const std::string e1n(1, names[ax[0]]), e2n(1, names[ax[1]]);
    std::string motion;
    if (warp == "pulse") {
        s.warp = make_pulse_warp(c, 1.5, rate);
        motion = "scaled 1 -> 1.5 -> 1 about the bbox centre";
    } else if (warp == "stretch") {
        s.warp = make_stretch_warp(c, e1, 3.0, rate);
        motion = "stretched x3 along " + e1n + " and back";
    } else if (warp == "twist") {
        s.warp = make_twist_warp(c, e1, half_l, kPi / 4.0, rate);
        motion = "twisted about " + e1n + ", end angle +-pi/4 at +-" + fmt(half_l);
    } else if (warp == "bend") {
        const double turn = std::min(2.0 * kPi / 3.0, 2.0 * half_l / (1.5 * half_w));
        s.warp = make_bend_warp(c, e1, e2, half_l, turn, 1.0, rate);
        motion = "bent along " + e1n + " towards +" + e2n + ", turning by " + fmt(turn) +
                 " rad (radius " + fmt(2.0 * half_l / turn) + ", half-width " + fmt(half_w) +
                 ")";
    } else {
        s.warp = make_rotation_warp(c, Vec3{1, 1, 1}, rate);
        motion = "one rigid turn about (1,1,1)";
    }
    s.edits = o.edits.value_or(true);
    s.description = std::filesystem::path(path).filename().string() + " (" + std::to_string(nv) +
                    " vertices), " + motion + "; pool " + std::to_string(s.pool_size()) +
                    " points (" + std::to_string(levels) + " midpoint subdivisions), " +
                    std::to_string(s.initial.size()) + " initial samples";
    return s;
}

}  // namespace

// ---- scenarios -----------------------------------------------------------------------------

std::vector<std::string> scenario_names() { return analytic_names(); }

Scenario make_scenario(const std::string& name, const ScenarioOptions& o) {
    if (o.samples < 100)
        throw InvalidInput("make_scenario: samples must be >= 100 (got " +
                           std::to_string(o.samples) + ")");
    if (o.steps < 1)
        throw InvalidInput("make_scenario: steps must be >= 1 (got " + std::to_string(o.steps) +
                           ")");
    if (!(std::isfinite(o.speed) && o.speed > 0))
        throw InvalidInput("make_scenario: speed must be positive and finite (got " +
                           fmt(o.speed) + ")");
    if (o.pool_factor < 1) throw InvalidInput("make_scenario: pool_factor must be >= 1 (got 0)");
    if (o.samples > (std::size_t{1} << 31) / o.pool_factor)
        throw InvalidInput("make_scenario: samples * pool_factor is too large");
    const double rate = o.speed / static_cast<double>(o.steps);
    const int horizon = horizon_of(o.steps, o.speed);

    Scenario s;
    const auto& names = analytic_names();
    if (std::find(names.begin(), names.end(), name) != names.end()) {
        const std::string own = name == "boomerang" ? "bend" : name;
        if (!o.warp.empty() && o.warp != own && o.warp != name)
            throw InvalidInput("make_scenario: warp '" + o.warp +
                               "' applies to mesh files only; scenario '" + name +
                               "' has its own motion (" + own + ")");
        s = analytic_scenario(name, o, rate);
    } else {
        std::error_code ec;
        if (name.empty() || !std::filesystem::exists(name, ec))
            throw InvalidInput("make_scenario: unknown scenario '" + name + "' (valid: " +
                               joined(names) + ", or a path to a closed mesh file " +
                               joined(readable_mesh_extensions(), " ") + ")");
        s = mesh_scenario(name, o, rate);
    }
    s.time_units = horizon;
    finish(s);
    s.description += "; " + std::to_string(s.time_units) + " time units, lambda " +
                     fmt(s.lambda) + ", h0 " + fmt(s.h0);
    return s;
}

// ---- positions, normals --------------------------------------------------------------------

void warp_points(const Scenario& s, double t, std::span<const Point3> x0, std::span<Point3> out) {
    if (x0.size() != out.size())
        throw InvalidInput("warp_points: " + std::to_string(x0.size()) + " inputs but " +
                           std::to_string(out.size()) + " outputs");
    for (std::size_t i = 0; i < x0.size(); ++i) out[i] = s.warp->apply(t, x0[i]);
}

std::vector<Point3> pool_positions(const Scenario& s, double t,
                                   std::span<const std::uint32_t> pool) {
    const std::vector<Point3>& p = s.reference.positions();
    std::vector<Point3> out(pool.size());
    for (std::size_t i = 0; i < pool.size(); ++i) {
        if (pool[i] >= p.size())
            throw InvalidInput("pool_positions: pool index " + std::to_string(pool[i]) +
                               " >= pool size " + std::to_string(p.size()));
        out[i] = s.warp->apply(t, p[pool[i]]);
    }
    return out;
}

std::vector<Point3> pool_positions(const Scenario& s, double t) {
    const std::vector<Point3>& p = s.reference.positions();
    std::vector<Point3> out(p.size());
    warp_points(s, t, p, out);
    return out;
}

std::array<Vec3, 3> warp_jacobian(const Scenario& s, double t, const Point3& x0) {
    const double h = 1e-6 * (s.length_scale > 0 ? s.length_scale : 1.0);
    std::array<Vec3, 3> j{};
    for (std::size_t i = 0; i < 3; ++i) {
        Vec3 d{};
        d[i] = h;
        j[i] = (s.warp->apply(t, x0 + d) - s.warp->apply(t, x0 - d)) / (2.0 * h);
    }
    return j;
}

namespace {
Vec3 transported_normal(const Scenario& s, double t, std::uint32_t pool, const char* who) {
    if (pool >= s.pool_size())
        throw InvalidInput(std::string(who) + ": pool index " + std::to_string(pool) +
                           " >= pool size " + std::to_string(s.pool_size()));
    const Vec3& n = s.normals0[pool];
    const auto j = warp_jacobian(s, t, s.reference.positions()[pool]);
    return cross(j[1], j[2]) * n.x + cross(j[2], j[0]) * n.y + cross(j[0], j[1]) * n.z;
}
}  // namespace

Vec3 surface_normal(const Scenario& s, double t, std::uint32_t pool) {
    return normalized(transported_normal(s, t, pool, "surface_normal"));
}

double area_scale(const Scenario& s, double t, std::uint32_t pool) {
    return norm(transported_normal(s, t, pool, "area_scale"));
}

// ---- sampling radius -----------------------------------------------------------------------

double covering_radius(std::span<const Point3> probes, std::span<const Point3> samples) {
    if (probes.empty()) return 0.0;
    if (samples.empty())
        throw InvalidInput("covering_radius: " + std::to_string(probes.size()) +
                           " probes but no sample");
    const PointGrid g = PointGrid::bulk(surface_cell(bbox_of(samples), samples.size()), samples);
    double worst = 0;  // squared
    // A probe cannot raise the maximum once some sample is within it: try the sample found
    // for the previous probe first (a hit most of the time for spatially ordered probes).
    std::uint32_t last = kNone;
    for (const Point3& q : probes) {
        if (last != kNone && sqdistance(q, samples[last]) <= worst) continue;
        const auto [id, d2] = g.nearest_sq(q, PointGrid::positions(samples), kAny, worst);
        worst = std::max(worst, d2);
        last = id;
    }
    return std::sqrt(worst);
}

std::vector<Point3> reference_probes(const SurfaceMesh& mesh) {
    std::vector<Point3> out;
    out.reserve(mesh.n_vertices() + mesh.n_faces());
    for (const Vertex v : mesh.vertices()) out.push_back(mesh.position(v));
    for (const Face f : mesh.faces()) {
        const auto v = mesh.face_vertices(f);
        out.push_back((mesh.position(v[0]) + mesh.position(v[1]) + mesh.position(v[2])) / 3.0);
    }
    return out;
}

double sampling_radius(const Scenario& s, double t, std::span<const std::uint32_t> live_pool) {
    SurfaceMesh warped = s.reference;
    warp_points(s, t, s.reference.positions(), warped.positions());
    return covering_radius(reference_probes(warped), pool_positions(s, t, live_pool));
}

}  // namespace dynmesh
