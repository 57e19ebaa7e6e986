#include "dynmesh/metrics/quality.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/scaled_frame.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/metrics/self_intersection.hpp"

namespace dynmesh {
namespace {

/// The per-face pass: angles, circumradius, radius-edge ratio and (with normals) the normal
/// deviation. One cross product per face serves all three angles (|u x v| is twice the area
/// at every corner) and the circumradius.
void measure_faces(const SurfaceMesh& mesh, const std::vector<Vec3>* vertex_normals,
                   QualityReport& r, Histogram* normal_hist) {
    SummaryAccumulator angle, radius_edge, circumradius, normal_dev, normal_dev_abs;
    for (const Face f : mesh.faces()) {
        const auto vs = mesh.face_vertices(f);
        const Point3 &a0 = mesh.position(vs[0]), &b0 = mesh.position(vs[1]),
                     &c0 = mesh.position(vs[2]);
        // In the triangle's own frame (exact scaling): no square or product below overflows
        // or underflows, whatever the size of the coordinates or of the triangle.
        const UnitPoints<3> u = to_unit(std::array{a0, b0, c0});
        const Vec3 ab = u.p[1] - u.p[0], ac = u.p[2] - u.p[0], bc = u.p[2] - u.p[1];
        const Vec3 n = cross(ab, ac);
        const double s = norm(n);  // twice the area
        // atan2(|u x v|, u . v), as angle_between(): accurate near 0 and 180 degrees.
        angle.add(rad_to_deg(std::atan2(s, dot(ab, ac))));
        angle.add(rad_to_deg(std::atan2(s, -dot(ab, bc))));
        angle.add(rad_to_deg(std::atan2(s, dot(ac, bc))));
        // Degenerate as check_mesh() says (exact predicate): its circumradius and
        // radius-edge ratio are infinite.
        if (s == 0.0 || collinear(a0, b0, c0)) {
            ++r.degenerate_faces;
            continue;
        }
        const double la2 = sqnorm(bc), lb2 = sqnorm(ac), lc2 = sqnorm(ab);
        const double radius = std::sqrt(la2 * lb2 * lc2) / (2.0 * s);  // abc / (4 area)
        circumradius.add(u.scale.length(radius));
        radius_edge.add(radius / std::sqrt(std::min({la2, lb2, lc2})));
        if (vertex_normals != nullptr) {
            const Vec3 unit = n / s;
            for (const Vertex v : vs) {
                const double d = rad_to_deg(angle_between(unit, (*vertex_normals)[v.idx()]));
                normal_dev.add(d);
                normal_dev_abs.add(std::min(d, 180.0 - d));
                normal_hist->add(d);
            }
        }
    }
    r.angle_deg = angle.summary();
    r.radius_edge = radius_edge.summary();
    r.circumradius = circumradius.summary();
    if (r.degenerate_faces > 0) {
        r.radius_edge.max = std::numeric_limits<double>::infinity();
        r.circumradius.max = std::numeric_limits<double>::infinity();
    }
    if (vertex_normals != nullptr) {
        r.normal_dev_deg = normal_dev.summary();
        r.normal_dev_abs_deg = normal_dev_abs.summary();
    }
}

/// The per-edge pass: boundary edges and 180 - dihedral at interior edges.
void measure_edges(const SurfaceMesh& mesh, QualityReport& r) {
    SummaryAccumulator dev;
    for (const Edge e : mesh.edges()) {
        if (mesh.is_boundary(e)) {
            ++r.boundary_edges;
            continue;
        }
        const Halfedge h = SurfaceMesh::halfedge(e, 0);
        const double d = 180.0 - rad_to_deg(dihedral_angle(
                                     mesh.position(mesh.from_vertex(h)), mesh.position(mesh.to_vertex(h)),
                                     mesh.position(mesh.to_vertex(mesh.next(h))),
                                     mesh.position(mesh.to_vertex(mesh.next(SurfaceMesh::twin(h))))));
        dev.add(d);
        r.dihedral_dev_hist.add(d);
    }
    r.dihedral_dev_deg = dev.summary();
}

}  // namespace

QualityReport mesh_quality(const SurfaceMesh& mesh, const QualityOptions& options) {
    DYNMESH_CHECK(!options.hausdorff || options.surface != nullptr,
                  "mesh_quality: hausdorff requested without a surface");
    DYNMESH_CHECK(options.histogram_bins > 0, "mesh_quality: histogram_bins must be >= 1");
    DYNMESH_CHECK(options.histogram_max_deg > 0 && std::isfinite(options.histogram_max_deg),
                  "mesh_quality: histogram_max_deg must be positive, got " +
                      std::to_string(options.histogram_max_deg));

    QualityReport r;
    r.vertices = mesh.n_vertices();
    r.faces = mesh.n_faces();
    r.edges = mesh.n_edges();
    r.euler = static_cast<long long>(r.vertices) - static_cast<long long>(r.edges) +
              static_cast<long long>(r.faces);
    r.dihedral_dev_hist = make_histogram(0.0, options.histogram_max_deg, options.histogram_bins);

    if (options.surface != nullptr) {
        require_surface_range(mesh, "mesh_quality");
        // One surface normal per vertex instead of three per face.
        std::vector<Vec3> normals(mesh.vertices_size());
        for (const Vertex v : mesh.vertices())
            if (!mesh.is_isolated(v)) normals[v.idx()] = options.surface->normal(mesh.position(v));
        Histogram hist = make_histogram(0.0, options.histogram_max_deg, options.histogram_bins);
        measure_faces(mesh, &normals, r, &hist);
        r.normal_dev_hist = std::move(hist);
    } else {
        measure_faces(mesh, nullptr, r, nullptr);
    }
    measure_edges(mesh, r);
    r.closed = r.faces > 0 && r.boundary_edges == 0;

    if (options.hausdorff)
        r.hausdorff_to_surface =
            hausdorff_to_surface(mesh, *options.surface, options.hausdorff_sampling);
    if (options.self_intersections) r.self_intersecting_pairs = count_self_intersections(mesh);
    return r;
}

CheckFigure::Kind quality_field_kind(std::string_view name) {
    static constexpr std::array<std::string_view, 7> kCounts = {
        "vertices", "faces", "edges", "euler", "boundary_edges", "degenerate_faces", "self_intersections"};
    if (name == "closed") return CheckFigure::Kind::Boolean;
    return std::find(kCounts.begin(), kCounts.end(), name) != kCounts.end() ? CheckFigure::Kind::Integer
                                                                             : CheckFigure::Kind::Real;
}

std::vector<std::pair<std::string, double>> flatten(const QualityReport& r) {
    std::vector<std::pair<std::string, double>> out;
    auto put = [&out](const char* name, double value) { out.emplace_back(name, value); };
    put("vertices", static_cast<double>(r.vertices));
    put("faces", static_cast<double>(r.faces));
    put("edges", static_cast<double>(r.edges));
    put("euler", static_cast<double>(r.euler));
    put("closed", r.closed ? 1.0 : 0.0);
    put("boundary_edges", static_cast<double>(r.boundary_edges));
    put("degenerate_faces", static_cast<double>(r.degenerate_faces));
    put("min_angle_deg", r.angle_deg.min);
    put("max_angle_deg", r.angle_deg.max);
    put("mean_angle_deg", r.angle_deg.mean);
    put("radius_edge_max", r.radius_edge.max);
    put("radius_edge_mean", r.radius_edge.mean);
    put("circumradius_max", r.circumradius.max);
    put("circumradius_mean", r.circumradius.mean);
    put("dihedral_dev_mean_deg", r.dihedral_dev_deg.mean);
    put("dihedral_dev_sd_deg", r.dihedral_dev_deg.sd);
    put("dihedral_dev_max_deg", r.dihedral_dev_deg.max);
    if (r.normal_dev_deg) {
        put("normal_dev_mean_deg", r.normal_dev_deg->mean);
        put("normal_dev_sd_deg", r.normal_dev_deg->sd);
        put("normal_dev_max_deg", r.normal_dev_deg->max);
    }
    if (r.normal_dev_abs_deg) {
        put("normal_dev_abs_mean_deg", r.normal_dev_abs_deg->mean);
        put("normal_dev_abs_sd_deg", r.normal_dev_abs_deg->sd);
        put("normal_dev_abs_max_deg", r.normal_dev_abs_deg->max);
    }
    if (r.hausdorff_to_surface) {
        put("hausdorff", r.hausdorff_to_surface->distance);
        put("hausdorff_mesh_to_surface", r.hausdorff_to_surface->a_to_b);
        put("hausdorff_surface_to_mesh", r.hausdorff_to_surface->b_to_a);
    }
    if (r.self_intersecting_pairs)
        put("self_intersections", static_cast<double>(*r.self_intersecting_pairs));
    return out;
}

}  // namespace dynmesh
