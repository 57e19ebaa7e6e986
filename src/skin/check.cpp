#include "dynmesh/skin/check.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dynmesh/geometry/format.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/skin/static_mesh.hpp"
#include "dynmesh/skin/topology.hpp"

namespace dynmesh {
namespace {

/// What check_skin_mesh() measures, before it becomes the report's figures.
struct SkinMeasures {
    std::vector<std::string> problems;
    long long euler = 0;
    std::size_t components = 0;
    long long expected_euler = 0, expected_components = 0;
    double min_angle_deg = 0, angle_floor_deg = 0;
    double frac_angles_below_15 = 0, frac_angles_below_20 = 0, frac_below_floor = 0;
    double hausdorff_over_rho_max = 0, hausdorff_max = 0;
    double normal_dev_max_deg = 0, normal_dev_mean_deg = 0;
    double vertex_offset_max = 0;
    std::size_t inward_faces = 0, exempt_faces = 0;
};

}  // namespace

CheckReport check_skin_mesh(const SkinFunction& phi, const SurfaceMesh& mesh, const SkinMeshCheckOptions& options) {
    SkinMeasures out;
    const double t = options.time;
    MeshCheckOptions mo;
    mo.require_closed = true;
    const CheckReport topo_check = check_mesh(mesh, mo);
    out.euler = topo_check.integer("euler");
    out.components = static_cast<std::size_t>(topo_check.integer("components"));
    if (!topo_check.ok()) out.problems.push_back("not a closed oriented 2-manifold: " + topo_check.summary());
    const std::vector<WeightedPoint> input(phi.balls().begin(), phi.balls().begin() + std::ptrdiff_t(phi.input_balls()));
    const SkinTopology alpha = skin_topology(input, t);
    out.expected_euler = alpha.euler();
    out.expected_components = alpha.components();
    if (out.euler != out.expected_euler || (long long)(out.components) != out.expected_components)
        out.problems.push_back("topology: Euler characteristic " + std::to_string(out.euler) + " and " +
                               std::to_string(out.components) + " component(s), the alpha complex has " +
                               std::to_string(out.expected_euler) + " and " + std::to_string(out.expected_components));

    // The extent of the skin, for relative offsets.
    Point3 lo{0, 0, 0}, hi{0, 0, 0};
    bool first = true;
    for (Vertex v : mesh.vertices()) {
        const Point3& p = mesh.position(v);
        lo = first ? p : Point3{std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = first ? p : Point3{std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
        first = false;
    }
    const double extent = std::max(norm(hi - lo), 1e-300);
    std::size_t hint = 0;
    for (Vertex v : mesh.vertices()) {
        const SkinEvaluation ev = phi.evaluate(mesh.position(v), hint);
        hint = ev.simplex;
        const double off = std::fabs(ev.value - t) / std::max(norm(ev.gradient), 1e-300) / extent;
        out.vertex_offset_max = std::max(out.vertex_offset_max, off);
    }
    if (out.vertex_offset_max > options.max_vertex_offset)
        out.problems.push_back("a vertex is " + format_number(out.vertex_offset_max) + " of the extent off the skin");

    out.angle_floor_deg = min_angle_floor_deg(options.quality.Q1);
    out.min_angle_deg = mesh.n_faces() ? 180 : 0;
    std::size_t below15 = 0, below20 = 0, below_floor = 0;
    double dev_sum = 0;
    const double bound = options.quality.C * options.quality.Q1 * options.quality.C * options.quality.Q1;
    // Ten points per triangle: the centroid, the three edge midpoints' halfway points to it,
    // and six more on the medians.
    static const double kBary[10][3] = {{1. / 3, 1. / 3, 1. / 3}, {2. / 3, 1. / 6, 1. / 6}, {1. / 6, 2. / 3, 1. / 6},
                                        {1. / 6, 1. / 6, 2. / 3}, {0.5, 0.5, 0},          {0, 0.5, 0.5},
                                        {0.5, 0, 0.5},           {0.25, 0.25, 0.5},       {0.25, 0.5, 0.25},
                                        {0.5, 0.25, 0.25}};
    for (Face f : mesh.faces()) {
        if (f.idx() < options.exempt.size() && options.exempt[f.idx()]) {
            ++out.exempt_faces;
            continue;
        }
        const auto fv = mesh.face_vertices(f);
        const Point3 a = mesh.position(fv[0]), b = mesh.position(fv[1]), c = mesh.position(fv[2]);
        const double angle = rad_to_deg(min_angle(a, b, c));
        out.min_angle_deg = std::min(out.min_angle_deg, angle);
        below15 += angle < 15;
        below20 += angle < 20;
        below_floor += angle < out.angle_floor_deg;
        const Vec3 n = cross(b - a, c - a);
        for (int k = 0; k < 10; ++k) {
            const Point3 x = a + kBary[k][1] * (b - a) + kBary[k][2] * (c - a);
            const Point3 foot = project_to_skin(phi, x, t, hint);
            const SkinEvaluation ev = phi.evaluate(foot, hint);
            hint = ev.simplex;
            const double d = norm(foot - x);
            out.hausdorff_max = std::max(out.hausdorff_max, d);
            out.hausdorff_over_rho_max = std::max(out.hausdorff_over_rho_max, d / std::max(ev.rho, options.rho_floor));
            if (k == 0) {
                const double cosv = dot(n, ev.gradient) / std::max(norm(n) * norm(ev.gradient), 1e-300);
                const double dev = rad_to_deg(std::acos(std::clamp(cosv, -1.0, 1.0)));
                if (cosv <= 0) ++out.inward_faces;
                out.normal_dev_max_deg = std::max(out.normal_dev_max_deg, dev);
                dev_sum += dev;
            }
        }
    }
    const double nf = double(std::max<std::size_t>(mesh.n_faces() - out.exempt_faces, 1));
    out.frac_angles_below_15 = double(below15) / nf;
    out.frac_angles_below_20 = double(below20) / nf;
    out.frac_below_floor = double(below_floor) / nf;
    out.normal_dev_mean_deg = dev_sum / nf;
    if (out.inward_faces) out.problems.push_back(std::to_string(out.inward_faces) + " triangle(s) turned inward");
    if (below_floor)
        out.problems.push_back(std::to_string(below_floor) + " triangle(s) with an angle under asin(1/Q1^2) = " +
                               format_number(out.angle_floor_deg) + " deg (smallest " + format_number(out.min_angle_deg) + ")");
    if (out.hausdorff_over_rho_max > bound)
        out.problems.push_back("mesh-to-skin distance " + format_number(out.hausdorff_over_rho_max) +
                               " times the length scale, above (C Q1)^2 = " + format_number(bound));
    if (out.normal_dev_max_deg > options.max_normal_deviation_deg)
        out.problems.push_back("normal deviation " + format_number(out.normal_dev_max_deg) + " deg, above " +
                               format_number(options.max_normal_deviation_deg));
    CheckReport rep = CheckReport::of_problems(std::move(out.problems));
    rep.add("euler", out.euler);
    rep.add("components", out.components);
    rep.add("expected_euler", out.expected_euler);
    rep.add("expected_components", out.expected_components);
    rep.add("min_angle_deg", out.min_angle_deg);
    rep.add("angle_floor_deg", out.angle_floor_deg);
    rep.add("frac_angles_below_15", out.frac_angles_below_15);
    rep.add("frac_angles_below_20", out.frac_angles_below_20);
    rep.add("frac_below_floor", out.frac_below_floor);
    rep.add("exempt_triangles", out.exempt_faces);
    rep.add("hausdorff_over_rho_max", out.hausdorff_over_rho_max);
    rep.add("hausdorff_max", out.hausdorff_max);
    rep.add("normal_dev_max_deg", out.normal_dev_max_deg);
    rep.add("normal_dev_mean_deg", out.normal_dev_mean_deg);
    rep.add("vertex_offset_max", out.vertex_offset_max);
    rep.add("inward_faces", out.inward_faces);
    return rep;
}

}  // namespace dynmesh
