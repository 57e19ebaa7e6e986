#include "dynmesh/metrics/hausdorff.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>
#include <boost/iterator/counting_iterator.hpp>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/scaled_frame.hpp"
#include "dynmesh/geometry/triangle.hpp"

namespace dynmesh {
namespace {

// The kernel only builds the tree's boxes; distances are measurements, computed below in
// plain doubles (no filtered predicates, whose rounding-mode switches would cost more than
// the arithmetic).
using K = CGAL::Simple_cartesian<double>;

/// The triangles of a mesh as compact indexed arrays: the AABB tree's shared data, so that
/// a primitive is one 32-bit index instead of a stored Triangle_3 (72 bytes).
struct IndexedTriangles {
    std::vector<Point3> points;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// The shared data as CGAL's traits store it: a pointer that is null by default (a raw
/// pointer would be copied uninitialised by AABB_tree's default traits, and GCC says so).
struct TrianglesRef {
    const IndexedTriangles* p = nullptr;
    const IndexedTriangles* operator->() const { return p; }
};

/// A model of CGAL's AABBPrimitiveWithSharedData: triangle `id` of an IndexedTriangles.
class TrianglePrimitive {
public:
    using Id = std::uint32_t;
    using Point = K::Point_3;
    using Datum = K::Triangle_3;
    using Shared_data = TrianglesRef;

    TrianglePrimitive() = default;
    template <class Iterator>
    TrianglePrimitive(Iterator it, const IndexedTriangles* /*data*/) : id_(*it) {}

    [[nodiscard]] Id id() const { return id_; }
    [[nodiscard]] Datum datum(const Shared_data& d) const {
        const auto& t = d->triangles[id_];
        return {point(d, t[0]), point(d, t[1]), point(d, t[2])};
    }
    [[nodiscard]] Point reference_point(const Shared_data& d) const {
        return point(d, d->triangles[id_][0]);
    }
    static Shared_data construct_shared_data(const IndexedTriangles* d) { return {d}; }

private:
    static Point point(const Shared_data& d, std::uint32_t i) {
        const Point3& p = d->points[i];
        return {p.x, p.y, p.z};
    }
    Id id_ = 0;
};

using Traits = CGAL::AABB_traits<K, TrianglePrimitive>;
using Tree = CGAL::AABB_tree<Traits>;
using Node = CGAL::AABB_node<Traits>;



double sq_dist_point_box(const Point3& p, const CGAL::Bbox_3& b) {
    auto axis = [](double x, double lo, double hi) {
        const double d = x < lo ? lo - x : (x > hi ? x - hi : 0.0);
        return d * d;
    };
    return axis(p.x, b.xmin(), b.xmax()) + axis(p.y, b.ymin(), b.ymax()) +
           axis(p.z, b.zmin(), b.zmax());
}

/// Traversal traits for CGAL's AABB_tree::traversal_with_priority: the squared distance
/// from a query point to the mesh, nearest box first, stopping as soon as it is known to be
/// <= stop_sq (such a sample cannot raise the running maximum of a Hausdorff distance).
class BoundedDistanceTraits {
public:
    using Priority = double;  // larger first: minus the squared distance to the box

    BoundedDistanceTraits(const IndexedTriangles& data, double stop_sq)
        : data_(data), stop_sq_(stop_sq) {}

    [[nodiscard]] bool go_further() const { return best_sq_ > stop_sq_; }
    void intersection(const Point3& q, const TrianglePrimitive& primitive) {
        const auto& t = data_.triangles[primitive.id()];
        const double d =
            sq_dist_to_triangle(q, data_.points[t[0]], data_.points[t[1]], data_.points[t[2]]);
        best_sq_ = std::min(best_sq_, d);
    }
    [[nodiscard]] bool do_intersect(const Point3& q, const Node& node) const {
        return sq_dist_point_box(q, node.bbox()) < best_sq_;
    }
    [[nodiscard]] std::pair<bool, Priority> do_intersect_with_priority(const Point3& q,
                                                                       const Node& node) const {
        const double d = sq_dist_point_box(q, node.bbox());
        return {d < best_sq_, -d};
    }
    /// The exact squared distance if it exceeds stop_sq, otherwise some value <= stop_sq.
    [[nodiscard]] double best_sq() const { return best_sq_; }

private:
    const IndexedTriangles& data_;
    double stop_sq_;
    double best_sq_ = std::numeric_limits<double>::infinity();
};

/// Spreads the low 21 bits of x over every third bit (for a 63-bit Morton code).
std::uint64_t spread_bits(std::uint64_t x) {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffff;
    x = (x | x << 16) & 0x1f0000ff0000ff;
    x = (x | x << 8) & 0x100f00f00f00f00f;
    x = (x | x << 4) & 0x10c30c30c30c30c3;
    x = (x | x << 2) & 0x1249249249249249;
    return x;
}

/// The points in Morton (Z-curve) order: consecutive queries then walk nearby tree nodes,
/// which keeps them in cache (several times faster than index order on large meshes).
std::vector<Point3> spatially_sorted(const std::vector<Point3>& points) {
    Bbox3 box;
    for (const Point3& p : points) box.extend(p);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(points.size());
    const double scale = 2097151.0;  // 2^21 - 1
    auto cell = [&](double x, double lo, double hi) {
        const double t = hi > lo ? (x - lo) / (hi - lo) : 0.0;
        return static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * scale);
    };
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Point3& p = points[i];
        keys[i] = {spread_bits(cell(p.x, box.min.x, box.max.x)) |
                       spread_bits(cell(p.y, box.min.y, box.max.y)) << 1 |
                       spread_bits(cell(p.z, box.min.z, box.max.z)) << 2,
                   static_cast<std::uint32_t>(i)};
    }
    std::sort(keys.begin(), keys.end());
    std::vector<Point3> out;
    out.reserve(points.size());
    for (const auto& k : keys) out.push_back(points[k.second]);
    return out;
}

/// Point-to-mesh distances through an AABB tree over the mesh's live faces.
/// Holds pointers into itself: not copyable or movable.
class MeshDistance {
public:
    explicit MeshDistance(const SurfaceMesh& mesh) {
        std::vector<std::uint32_t> index(mesh.vertices_size(), 0);
        data_.points.reserve(mesh.n_vertices());
        for (const Vertex v : mesh.vertices()) {
            index[v.idx()] = static_cast<std::uint32_t>(data_.points.size());
            data_.points.push_back(mesh.position(v));
        }
        data_.triangles.reserve(mesh.n_faces());
        for (const Face f : mesh.faces()) {
            const auto vs = mesh.face_vertices(f);
            data_.triangles.push_back({index[vs[0].idx()], index[vs[1].idx()], index[vs[2].idx()]});
        }
        const auto n = static_cast<std::uint32_t>(data_.triangles.size());
        tree_.insert(boost::counting_iterator<std::uint32_t>(0),
                     boost::counting_iterator<std::uint32_t>(n), &data_);
        tree_.build();
    }
    MeshDistance(const MeshDistance&) = delete;
    MeshDistance& operator=(const MeshDistance&) = delete;

    /// Largest distance from the given points to the mesh. Each query stops early once the
    /// point is known to be no farther than the running maximum, so most queries touch only
    /// the few boxes around the nearest triangle.
    [[nodiscard]] double max_distance(const std::vector<Point3>& samples) const {
        double max_sq = 0;
        for (const Point3& p : spatially_sorted(samples)) {
            BoundedDistanceTraits traits(data_, max_sq);
            tree_.traversal_with_priority(p, traits);
            max_sq = std::max(max_sq, traits.best_sq());
        }
        return std::sqrt(max_sq);
    }

private:
    IndexedTriangles data_;
    Tree tree_;
};

void check_inputs(const char* fn, const SurfaceMesh& mesh, const char* which,
                  const HausdorffOptions& options) {
    DYNMESH_CHECK(mesh.n_faces() > 0,
                  std::string(fn) + ": mesh" + which + " has no face (distance undefined)");
    DYNMESH_CHECK(options.face_resolution > 0, std::string(fn) + ": face_resolution must be >= 1");
}

}  // namespace

std::vector<Point3> mesh_sample_points(const SurfaceMesh& mesh, std::size_t face_resolution) {
    DYNMESH_CHECK(face_resolution > 0, "mesh_sample_points: face_resolution must be >= 1");
    const std::size_t k = face_resolution;
    const double inv_k = 1.0 / static_cast<double>(k);
    const bool grid_has_barycentre = k % 3 == 0;
    std::vector<Point3> out;
    out.reserve(mesh.n_vertices() + mesh.n_edges() * (k - 1) +
                mesh.n_faces() * ((k - 1) * (k > 1 ? k - 2 : 0) / 2 + 1));
    for (const Vertex v : mesh.vertices())
        if (!mesh.is_isolated(v)) out.push_back(mesh.position(v));
    if (k > 1) {
        for (const Edge e : mesh.edges()) {
            const Point3& p = mesh.position(mesh.vertex(e, 0));
            const Vec3 d = mesh.position(mesh.vertex(e, 1)) - p;
            for (std::size_t i = 1; i < k; ++i)
                out.push_back(p + d * (static_cast<double>(i) * inv_k));
        }
    }
    for (const Face f : mesh.faces()) {
        const auto vs = mesh.face_vertices(f);
        const Point3 &a = mesh.position(vs[0]), &b = mesh.position(vs[1]),
                     &c = mesh.position(vs[2]);
        // Interior grid points (i, j, l >= 1, i + j + l = k).
        for (std::size_t i = 1; i + 2 <= k; ++i)
            for (std::size_t j = 1; i + j + 1 <= k; ++j) {
                const std::size_t l = k - i - j;
                out.push_back((a * static_cast<double>(i) + b * static_cast<double>(j) +
                               c * static_cast<double>(l)) *
                              inv_k);
            }
        if (!grid_has_barycentre) out.push_back((a + b + c) / 3.0);
    }
    return out;
}

void require_surface_range(const SurfaceMesh& mesh, const std::string& what) {
    double big = 0;
    for (const Vertex v : mesh.vertices()) {
        const Point3& p = mesh.position(v);
        big = std::max({big, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    }
    if (big > 1e50) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.3g", big);
        throw InvalidInput(what + ": the mesh's coordinates (up to " + buf +
                           ") are beyond 1e50, the range of analytic surfaces");
    }
}

namespace {

HausdorffResult hausdorff_in_frame(const SurfaceMesh& a, const SurfaceMesh& b,
                                   const HausdorffOptions& options) {
    HausdorffResult r;
    {
        const std::vector<Point3> samples = mesh_sample_points(a, options.face_resolution);
        const MeshDistance to_b(b);
        r.a_to_b = to_b.max_distance(samples);
        r.a_samples = samples.size();
    }
    {
        const std::vector<Point3> samples = mesh_sample_points(b, options.face_resolution);
        const MeshDistance to_a(a);
        r.b_to_a = to_a.max_distance(samples);
        r.b_samples = samples.size();
    }
    r.distance = std::max(r.a_to_b, r.b_to_a);
    return r;
}

/// A copy of `m` with every position scaled by `s`.
SurfaceMesh scaled_copy(const SurfaceMesh& m, const ExactScale& s) {
    SurfaceMesh c = m;
    for (Point3& p : c.positions()) p = s.apply(p);
    return c;
}

}  // namespace

HausdorffResult hausdorff(const SurfaceMesh& a, const SurfaceMesh& b,
                          const HausdorffOptions& options) {
    check_inputs("hausdorff", a, " a", options);
    check_inputs("hausdorff", b, " b", options);
    // Near the double limits (squared distances of coordinates beyond ~1e150 overflow, those
    // of subnormal ones underflow) both meshes are measured scaled by one exact power of two.
    std::vector<Point3> both = a.positions();
    both.insert(both.end(), b.positions().begin(), b.positions().end());
    const ExactScale s = ExactScale::to_unit(both);
    if (std::abs(s.exponent()) <= 256) return hausdorff_in_frame(a, b, options);
    HausdorffResult r = hausdorff_in_frame(scaled_copy(a, s), scaled_copy(b, s), options);
    r.a_to_b = s.length(r.a_to_b);
    r.b_to_a = s.length(r.b_to_a);
    r.distance = s.length(r.distance);
    return r;
}

double max_distance_to_mesh(const SurfaceMesh& mesh, const std::vector<Point3>& points) {
    DYNMESH_CHECK(mesh.n_faces() > 0, "max_distance_to_mesh: the mesh has no face");
    const MeshDistance to_mesh(mesh);
    return to_mesh.max_distance(points);
}

double hausdorff_distance(const SurfaceMesh& a, const SurfaceMesh& b,
                          const HausdorffOptions& options) {
    return hausdorff(a, b, options).distance;
}

HausdorffResult hausdorff_to_surface(const SurfaceMesh& mesh, const ImplicitSurface& surface,
                                     const HausdorffOptions& options) {
    check_inputs("hausdorff_to_surface", mesh, "", options);
    require_surface_range(mesh, "hausdorff_to_surface");
    HausdorffResult r;
    {
        const std::vector<Point3> samples = mesh_sample_points(mesh, options.face_resolution);
        double m = 0;
        for (const Point3& p : samples) m = std::max(m, std::abs(surface.signed_distance(p)));
        r.a_to_b = m;
        r.a_samples = samples.size();
    }
    if (options.surface_samples > 0) {
        const std::vector<Point3> samples =
            surface.sample_uniform(options.surface_samples, options.seed);
        r.b_to_a = max_distance_to_mesh(mesh, samples);
        r.b_samples = samples.size();
    }
    r.distance = std::max(r.a_to_b, r.b_to_a);
    return r;
}

}  // namespace dynmesh
