/// The triangle-mesh oracle: CGAL AABB tree, first_intersection(Ray_3), Side_of_triangle_mesh.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <string>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include "dynmesh/error.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/metrics/self_intersection.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "probe_common.hpp"

namespace dynmesh {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CMesh = CGAL::Surface_mesh<K::Point_3>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<CMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
using Side = CGAL::Side_of_triangle_mesh<CMesh, K, CGAL::Default, Tree>;

K::Point_3 to_cgal(const Point3& p) { return {p.x, p.y, p.z}; }
Point3 from_cgal(const K::Point_3& p) { return {p.x(), p.y(), p.z()}; }

/// Checks the soup is a closed oriented 2-manifold.
void check_soup(const TriangleSoup& soup) {
    DYNMESH_CHECK(!soup.triangles.empty(), "MeshOracle: the mesh has no triangle");
    SurfaceMesh m;
    try {
        m = SurfaceMesh::from_soup(soup);
    } catch (const TopologyError& e) {
        throw InvalidInput(std::string("MeshOracle: the mesh is not a consistently oriented "
                                       "2-manifold: ") +
                           e.what());
    }
    std::size_t boundary = 0;
    for (const Edge e : m.edges())
        if (m.is_boundary(e)) ++boundary;
    if (boundary > 0)
        throw InvalidInput("MeshOracle: the mesh is not closed (" + std::to_string(boundary) +
                           " boundary edges); a probing object needs a closed surface");
    const auto pairs = self_intersections(m, 1);
    if (!pairs.empty())
        throw InvalidInput("MeshOracle: the mesh intersects itself (faces " + std::to_string(pairs[0].first.idx()) +
                           " and " + std::to_string(pairs[0].second.idx()) +
                           "); a probing object needs the boundary of a solid");
}

}  // namespace

struct MeshOracle::Impl {
    TriangleSoup soup;
    CMesh mesh;
    Tree tree;
    std::unique_ptr<Side> side;
    Bbox3 box;

    explicit Impl(const TriangleSoup& s) : soup(s) {
        std::vector<CMesh::Vertex_index> vs;
        vs.reserve(soup.points.size());
        for (const Point3& p : soup.points) {
            vs.push_back(mesh.add_vertex(to_cgal(p)));
            box.extend(p);
        }
        for (const auto& t : soup.triangles)
            if (mesh.add_face(vs[t[0]], vs[t[1]], vs[t[2]]) == CMesh::null_face())
                throw InternalError("MeshOracle: CGAL refused a face that from_soup accepted");
        tree.insert(faces(mesh).first, faces(mesh).second, mesh);
        tree.build();
        tree.accelerate_distance_queries();
        side = std::make_unique<Side>(tree);
    }
    [[nodiscard]] bool inside(const Point3& p) const {
        return (*side)(to_cgal(p)) == CGAL::ON_BOUNDED_SIDE;
    }
    [[nodiscard]] Vec3 face_normal(CMesh::Face_index f) const {
        const auto h = mesh.halfedge(f);
        const Point3 a = from_cgal(mesh.point(mesh.source(h)));
        const Point3 b = from_cgal(mesh.point(mesh.target(h)));
        const Point3 c = from_cgal(mesh.point(mesh.target(mesh.next(h))));
        return normalized(cross(b - a, c - a));
    }
};

namespace {
double half_diagonal(const TriangleSoup& soup) {
    Bbox3 b;
    for (const Point3& p : soup.points) b.extend(p);
    return 0.5 * b.diagonal();
}
}  // namespace

MeshOracle::MeshOracle(const TriangleSoup& soup, OracleOptions options)
    : ProbeObject((check_soup(soup), half_diagonal(soup)), options),
      impl_(std::make_unique<Impl>(soup)) {}

MeshOracle::~MeshOracle() = default;

double MeshOracle::distance(const Point3& p) const {
    return std::sqrt(impl_->tree.squared_distance(to_cgal(p)));
}

double MeshOracle::signed_distance(const Point3& p) const {
    const double d = distance(p);
    return impl_->inside(p) ? -d : d;
}

bool MeshOracle::is_free(const Point3& p) const {
    return !impl_->inside(p) || distance(p) <= tolerance();
}

std::vector<double> MeshOracle::crossings(const Point3& a, const Point3& b) const {
    const double len = dynmesh::distance(a, b);
    std::vector<double> ts{0, len};
    const K::Segment_3 seg(to_cgal(a), to_cgal(b));
    if (len <= tolerance() || !impl_->tree.do_intersect(seg)) return ts;
    const Vec3 u = (b - a) / len;
    std::vector<Tree::Intersection_and_primitive_id<K::Segment_3>::Type> hits;
    impl_->tree.all_intersections(seg, std::back_inserter(hits));
    for (const auto& h : hits) {
        if (const auto* p = boost::get<K::Point_3>(&h.first)) {
            ts.push_back(dot(from_cgal(*p) - a, u));
        } else if (const auto* s = boost::get<K::Segment_3>(&h.first)) {
            ts.push_back(dot(from_cgal(s->source()) - a, u));
            ts.push_back(dot(from_cgal(s->target()) - a, u));
        }
    }
    std::sort(ts.begin(), ts.end());
    return ts;
}

bool MeshOracle::segment_is_free(const Point3& a, const Point3& b) const {
    if (!is_free(a) || !is_free(b)) return false;
    const std::vector<double> ts = crossings(a, b);
    if (ts.size() == 2) return true;  // no crossing between two free ends
    const Vec3 u = (b - a) / std::max(dynmesh::distance(a, b), std::numeric_limits<double>::min());
    for (std::size_t i = 0; i + 1 < ts.size(); ++i)
        if (ts[i + 1] - ts[i] > tolerance() && impl_->inside(a + 0.5 * (ts[i] + ts[i + 1]) * u))
            return false;
    return true;
}

std::optional<double> MeshOracle::free_point_on(const Point3& a, const Point3& b) const {
    if (is_free(a)) return 0.0;
    const std::vector<double> ts = crossings(a, b);
    if (ts.size() == 2) return std::nullopt;  // no crossing: inside O like a
    const Vec3 u = (b - a) / std::max(dynmesh::distance(a, b), std::numeric_limits<double>::min());
    for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
        const double mid = 0.5 * (ts[i] + ts[i + 1]);
        if (ts[i + 1] - ts[i] > tolerance() && !impl_->inside(a + mid * u)) return mid;
    }
    if (is_free(b)) return ts.back();
    return std::nullopt;
}

std::optional<ProbeHit> MeshOracle::cast_checked(const Point3& s, const Vec3& d, double t_max,
                                                 bool strict) const {
    const double tau = tolerance(), eta = 1e3 * tau;
    // A start on S (first_intersection does not report a crossing at the ray's source):
    // entering is a hit at t = 0 at the nearest mesh point.
    const auto nearest = impl_->tree.closest_point_and_primitive(to_cgal(s));
    if (std::sqrt(CGAL::squared_distance(nearest.first, to_cgal(s))) <= tau &&
        impl_->inside(s + eta * d)) {
        ProbeHit hit{from_cgal(nearest.first), 0, false};
        if (accept(hit, dot(impl_->face_normal(nearest.second), d), t_max, strict)) return hit;
    }
    Point3 from = s;
    for (int round = 0; round < 64; ++round) {
        const K::Ray_3 ray(to_cgal(from), K::Vector_3(d.x, d.y, d.z));
        const auto r = impl_->tree.first_intersection(ray);
        if (!r) return std::nullopt;
        Point3 x, far;
        bool in_plane = false;
        if (const auto* p = boost::get<K::Point_3>(&r->first)) {
            x = far = from_cgal(*p);
        } else {
            const auto& seg = boost::get<K::Segment_3>(r->first);
            const Point3 a = from_cgal(seg.source()), b = from_cgal(seg.target());
            const bool a_first = sqdistance(a, from) <= sqdistance(b, from);
            x = a_first ? a : b;
            far = a_first ? b : a;
            in_plane = true;
        }
        const double t = dot(x - s, d);
        if (t > t_max + tau) return std::nullopt;
        const bool enters = impl_->inside(x + eta * d);
        if (t <= tau && !enters) {
            from = x + eta * d;  // leaving S from a start on S: look further
            continue;
        }
        const double cos = in_plane ? 0.0 : dot(impl_->face_normal(r->second), d);
        ProbeHit hit{x, t, false};
        if (accept(hit, cos, t_max, strict, in_plane || !enters)) return hit;
        from = far + eta * d;  // strict: go on past the grazing contact
    }
    return std::nullopt;
}

std::vector<Point3> MeshOracle::sample_surface(double spacing) const {
    DYNMESH_CHECK(std::isfinite(spacing) && spacing > 0,
                  "GroundTruth::sample_surface: the spacing must be a positive number");
    DYNMESH_CHECK(area() / (spacing * spacing) <= 1e8,
                  "GroundTruth::sample_surface: spacing too small (more than 1e8 points)");
    // The vertices the triangles use (an unused vertex is not a point of S), then a grid on
    // every triangle.
    std::vector<bool> used(impl_->soup.points.size(), false);
    for (const auto& t : impl_->soup.triangles)
        for (auto v : t) used[v] = true;
    std::vector<Point3> out;
    for (std::size_t v = 0; v < used.size(); ++v)
        if (used[v]) out.push_back(impl_->soup.points[v]);
    for (const auto& t : impl_->soup.triangles) {
        const Point3 a = impl_->soup.points[t[0]], b = impl_->soup.points[t[1]],
                     c = impl_->soup.points[t[2]];
        const double longest = std::max({dynmesh::distance(a, b), dynmesh::distance(b, c), dynmesh::distance(c, a)});
        const int n = static_cast<int>(std::ceil(longest / spacing));
        for (int i = 1; i < n; ++i)
            for (int j = 1; i + j < n; ++j) {
                const double u = double(i) / n, v = double(j) / n;
                out.push_back(a + u * (b - a) + v * (c - a));
            }
    }
    return out;
}

double MeshOracle::diameter() const { return impl_->box.diagonal(); }
Bbox3 MeshOracle::bbox() const { return impl_->box; }

double MeshOracle::area() const {
    double a = 0;
    for (const auto& t : impl_->soup.triangles) {
        const auto& p = impl_->soup.points;
        a += 0.5 * norm(cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]));
    }
    return a;
}

namespace {
/// Component label per triangle (union-find over shared vertices).
std::vector<std::uint32_t> triangle_components(const TriangleSoup& soup, std::size_t* count) {
    std::vector<std::uint32_t> parent(soup.points.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto find = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const auto& t : soup.triangles) {
        parent[find(t[1])] = find(t[0]);
        parent[find(t[2])] = find(t[0]);
    }
    std::vector<std::uint32_t> label(soup.points.size(), UINT32_MAX), out;
    std::uint32_t next = 0;
    for (const auto& t : soup.triangles) {
        const std::uint32_t r = find(t[0]);
        if (label[r] == UINT32_MAX) label[r] = next++;
        out.push_back(label[r]);
    }
    *count = next;
    return out;
}
}  // namespace

int MeshOracle::components() const {
    std::size_t n = 0;
    (void)triangle_components(impl_->soup, &n);
    return static_cast<int>(n);
}

int MeshOracle::euler_characteristic() const {
    std::vector<bool> used(impl_->soup.points.size(), false);
    for (const auto& t : impl_->soup.triangles)
        for (auto v : t) used[v] = true;
    const auto v = std::count(used.begin(), used.end(), true);
    const auto f = static_cast<long>(impl_->soup.triangles.size());
    return static_cast<int>(v - 3 * f / 2 + f);  // closed: E = 3F/2
}

std::vector<Point3> MeshOracle::interior_points() const {
    // Per component, from its 16 largest faces: a ray from the face's centroid into O to the
    // first wall it meets; the midpoint of that chord, the one farthest from S.
    std::size_t n = 0;
    const auto label = triangle_components(impl_->soup, &n);
    const auto& pts = impl_->soup.points;
    const auto& tris = impl_->soup.triangles;
    std::vector<double> area2(tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i)
        area2[i] = norm(cross(pts[tris[i][1]] - pts[tris[i][0]], pts[tris[i][2]] - pts[tris[i][0]]));
    std::vector<std::vector<std::size_t>> faces(n);
    for (std::size_t i = 0; i < tris.size(); ++i) faces[label[i]].push_back(i);
    std::vector<Point3> out(n);
    const double eta = 1e3 * tolerance();
    for (std::size_t k = 0; k < n; ++k) {
        auto& fs = faces[k];
        const std::size_t m = std::min<std::size_t>(16, fs.size());
        std::partial_sort(fs.begin(), fs.begin() + std::ptrdiff_t(m), fs.end(),
                          [&](std::size_t a, std::size_t b) { return area2[a] > area2[b] || (area2[a] == area2[b] && a < b); });
        double best = -1;
        for (std::size_t f = 0; f < m; ++f) {
            const auto& t = tris[fs[f]];
            const Point3 c = (pts[t[0]] + pts[t[1]] + pts[t[2]]) / 3.0;
            const Vec3 nrm = normalized(cross(pts[t[1]] - pts[t[0]], pts[t[2]] - pts[t[0]]));
            for (const Vec3 d : {-nrm, nrm}) {
                if (!impl_->inside(c + eta * d)) continue;
                const K::Ray_3 ray(to_cgal(c + eta * d), K::Vector_3(d.x, d.y, d.z));
                const auto wall = impl_->tree.first_intersection(ray);
                if (!wall) continue;
                const auto* y = boost::get<K::Point_3>(&wall->first);
                if (y == nullptr) continue;
                const Point3 q = 0.5 * (c + from_cgal(*y));
                const double clearance = distance(q);
                if (impl_->inside(q) && clearance > 10 * tolerance() && clearance > best) {
                    best = clearance;
                    out[k] = q;
                }
                break;
            }
        }
        if (best < 0)
            throw InvalidInput("MeshOracle::interior_points: no interior point found for mesh component " +
                               std::to_string(k));
    }
    return out;
}

}  // namespace dynmesh
