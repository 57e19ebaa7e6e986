#include "dynmesh/deform/ground_truth.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <tuple>

#include "dynmesh/error.hpp"
#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/geometry/spatial_sort.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/metrics/self_intersection.hpp"

namespace dynmesh {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
using Tri = std::array<std::uint32_t, 3>;



/// Longest and mean edge length of a triangle list (each interior edge counted twice).
std::pair<double, double> edge_stats(std::span<const Point3> pts, std::span<const Tri> tris) {
    double lmax = 0, sum = 0;
    for (const Tri& t : tris)
        for (int i = 0; i < 3; ++i) {
            const double l = distance(pts[t[i]], pts[t[(i + 1) % 3]]);
            lmax = std::max(lmax, l);
            sum += l;
        }
    return {lmax, tris.empty() ? 0.0 : sum / (3.0 * static_cast<double>(tris.size()))};
}

/// Faces around each vertex, as CSR arrays.
void build_stars(std::size_t n_vertices, std::span<const Tri> tris,
                 std::vector<std::uint32_t>& begin, std::vector<std::uint32_t>& star) {
    begin.assign(n_vertices + 1, 0);
    for (const Tri& t : tris)
        for (std::uint32_t v : t) ++begin[v + 1];
    for (std::size_t i = 0; i < n_vertices; ++i) begin[i + 1] += begin[i];
    star.assign(begin.back(), 0);
    std::vector<std::uint32_t> fill(begin.begin(), begin.end() - 1);
    for (std::size_t f = 0; f < tris.size(); ++f)
        for (std::uint32_t v : tris[f]) star[fill[v]++] = static_cast<std::uint32_t>(f);
}

/// Exact sampled one-sided distances from query points to a triangle mesh (see the file
/// comment of ground_truth.hpp).
class LocalDistance {
public:
    /// `lmax` and `mean_edge`: the longest and the mean edge length of the mesh.
    LocalDistance(std::span<const Point3> pts, std::span<const Tri> tris,
                  std::span<const std::uint32_t> star_begin, std::span<const std::uint32_t> star,
                  double lmax, double mean_edge)
        : pts_(pts), tris_(tris), begin_(star_begin), star_(star), lmax_(lmax),
          cell_(mean_edge > 0 && std::isfinite(mean_edge) ? mean_edge : 1.0) {}

    /// The largest squared distance from a query to the mesh. hints[i] (if given and not
    /// kNone) is a mesh vertex near queries[i]; otherwise the search continues from the
    /// previous query, so queries should come in a spatially coherent order.
    [[nodiscard]] double max_sq(std::span<const Point3> queries,
                                std::span<const std::uint32_t> hints) const {
        if (queries.empty() || tris_.empty()) return 0.0;
        // Distances below 1e-9 longest edges count as 0 (else a mesh lying on the target,
        // where rounding leaves every distance at ~1e-17, would need an exact search for
        // every query).
        double h2 = 1e-18 * lmax_ * lmax_;
        std::uint32_t prev = kNone;
        auto start_of = [&](std::size_t i, const Point3& q) {
            std::uint32_t s = hints.empty() ? kNone : hints[i];
            if (s == kNone || begin_[s + 1] == begin_[s]) s = prev;
            if (s == kNone) s = nearest_vertex(q);
            return s;
        };
        // Seed the maximum with exact distances of the worst of a few spread-out queries.
        {
            std::vector<std::pair<double, std::size_t>> seed;
            const std::size_t stride = std::max<std::size_t>(1, queries.size() / 4096);
            for (std::size_t i = 0; i < queries.size(); i += stride) {
                const std::uint32_t w = walk(queries[i], start_of(i, queries[i]));
                seed.emplace_back(star_sq(queries[i], w, -1.0), i);
                prev = w;
            }
            const std::size_t k = std::min<std::size_t>(16, seed.size());
            std::partial_sort(seed.begin(), seed.begin() + static_cast<std::ptrdiff_t>(k),
                              seed.end(), std::greater<>());
            for (std::size_t j = 0; j < k; ++j)
                h2 = std::max(h2, exact_sq(queries[seed[j].second], seed[j].first));
            prev = kNone;
        }
        for (std::size_t i = 0; i < queries.size(); ++i) {
            const Point3& q = queries[i];
            const std::uint32_t s = start_of(i, q);
            const double us = star_sq(q, s, h2);
            if (us <= h2) {
                prev = s;
                continue;
            }
            const std::uint32_t w = walk(q, s);
            prev = w;
            // The closest triangle is nearly always around the nearest vertex or one of its
            // neighbours (not always for skinny triangles); only then search exactly.
            const double u2 = std::min(us, ring_sq(q, w, h2));
            if (u2 <= h2) continue;
            h2 = std::max(h2, exact_sq(q, u2));
        }
        return h2 > 1e-18 * lmax_ * lmax_ ? h2 : 0.0;
    }

    /// The largest dot(n, normal of g) over the triangles g of the mesh nearest to q: those
    /// within rounding of the smallest distance, so that where q's nearest point is on an edge
    /// or a vertex every triangle around it counts (any normal of the surface there). Searched
    /// among the triangles around the vertex a walk from `hint` (kNone: the nearest vertex)
    /// ends at and around its neighbours, where the closest triangle nearly always is.
    /// `scratch` is reused between calls.
    [[nodiscard]] double nearest_facing(const Point3& q, std::uint32_t hint, const Vec3& n,
                                        std::vector<std::pair<double, std::uint32_t>>& scratch) const {
        if (tris_.empty()) return 0.0;
        if (hint == kNone || begin_[hint + 1] == begin_[hint]) hint = nearest_vertex(q);
        const std::uint32_t w = walk(q, hint);
        scratch.clear();
        double best = std::numeric_limits<double>::infinity();
        auto fan = [&](std::uint32_t v) {
            for (std::uint32_t k = begin_[v]; k < begin_[v + 1]; ++k) {
                const Tri& t = tris_[star_[k]];
                const double d2 = sq_dist_to_triangle(q, pts_[t[0]], pts_[t[1]], pts_[t[2]]);
                best = std::min(best, d2);
                scratch.emplace_back(d2, star_[k]);
            }
        };
        fan(w);
        // Each neighbour once: the corner after w in each triangle of its (closed) fan.
        for (std::uint32_t k = begin_[w]; k < begin_[w + 1]; ++k) {
            const Tri& t = tris_[star_[k]];
            fan(t[0] == w ? t[1] : t[1] == w ? t[2] : t[0]);
        }
        const double tie = best * (1 + 1e-9) + 1e-18 * lmax_ * lmax_;
        double facing = -std::numeric_limits<double>::infinity();
        for (const auto& [d2, f] : scratch)
            if (d2 <= tie) {
                const Tri& t = tris_[f];
                facing = std::max(facing, dot(n, triangle_normal(pts_[t[0]], pts_[t[1]], pts_[t[2]])));
            }
        return facing;
    }

private:
    /// Squared distance from q to the fan of v; stops as soon as it is <= stop.
    [[nodiscard]] double star_sq(const Point3& q, std::uint32_t v, double stop) const {
        double best = std::numeric_limits<double>::infinity();
        for (std::uint32_t k = begin_[v]; k < begin_[v + 1]; ++k) {
            const Tri& t = tris_[star_[k]];
            best = std::min(best, sq_dist_to_triangle(q, pts_[t[0]], pts_[t[1]], pts_[t[2]]));
            if (best <= stop) break;
        }
        return best;
    }
    /// Squared distance from q to the triangles around v and around its neighbours; stops as
    /// soon as it is <= stop.
    [[nodiscard]] double ring_sq(const Point3& q, std::uint32_t v, double stop) const {
        double best = star_sq(q, v, stop);
        for (std::uint32_t k = begin_[v]; k < begin_[v + 1] && best > stop; ++k)
            for (std::uint32_t u : tris_[star_[k]]) {
                if (u == v) continue;
                best = std::min(best, star_sq(q, u, stop));
                if (best <= stop) break;
            }
        return best;
    }
    /// Greedy walk along edges to a vertex no neighbour of which is closer to q.
    [[nodiscard]] std::uint32_t walk(const Point3& q, std::uint32_t v) const {
        double dv = sqdistance(q, pts_[v]);
        for (std::uint32_t at = kNone; at != v;) {
            at = v;  // scan the fan of `at`, moving v to the closest neighbour seen
            for (std::uint32_t k = begin_[at]; k < begin_[at + 1]; ++k)
                for (std::uint32_t u : tris_[star_[k]]) {
                    const double du = sqdistance(q, pts_[u]);
                    if (du < dv) {
                        dv = du;
                        v = u;
                    }
                }
        }
        return v;
    }
    /// The grid over the vertices with a triangle, built on first use.
    const PointGrid& grid() const {
        if (!grid_built_) {
            std::vector<std::uint32_t> ids;
            ids.reserve(pts_.size());
            for (std::size_t v = 0; v + 1 < begin_.size(); ++v)
                if (begin_[v + 1] > begin_[v]) ids.push_back(static_cast<std::uint32_t>(v));
            grid_ = PointGrid::bulk(cell_, pts_, ids);
            grid_built_ = true;
        }
        return grid_;
    }
    [[nodiscard]] std::uint32_t nearest_vertex(const Point3& q) const {
        const auto any = [](std::uint32_t) { return true; };
        return grid().nearest_sq(q, PointGrid::positions(pts_), any).first;
    }
    /// The exact squared distance from q to the mesh, given an upper bound u2 of it: every
    /// triangle closer than sqrt(u2) has all its vertices within sqrt(u2) + longest edge.
    [[nodiscard]] double exact_sq(const Point3& q, double u2) const {
        double best = u2;
        const double r = std::sqrt(u2) + lmax_;
        grid().for_each_within(q, r, PointGrid::positions(pts_), [&](std::uint32_t v, double) {
            best = std::min(best, star_sq(q, v, -1.0));
        });
        return best;
    }

    std::span<const Point3> pts_;
    std::span<const Tri> tris_;
    std::span<const std::uint32_t> begin_, star_;
    double lmax_ = 0, cell_ = 1;
    mutable PointGrid grid_;
    mutable bool grid_built_ = false;
};

}  // namespace

GroundTruth::GroundTruth(const Scenario& scenario) : s_(&scenario), reference_(scenario.reference) {
    if (reference_.has_garbage())
        throw InvalidInput("GroundTruth: the scenario's reference mesh has deleted elements");
    const std::size_t nv = reference_.vertices_size();
    ref_order_ = spatial_order(reference_.positions());
    ref_rank_.assign(nv, 0);
    for (std::size_t k = 0; k < nv; ++k) ref_rank_[ref_order_[k]] = static_cast<std::uint32_t>(k);
    triangles_.reserve(reference_.n_faces());
    for (const Face f : reference_.faces()) {
        const auto v = reference_.face_vertices(f);
        Tri t{ref_rank_[v[0].idx()], ref_rank_[v[1].idx()], ref_rank_[v[2].idx()]};
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // same cycle
        triangles_.push_back(t);
    }
    std::sort(triangles_.begin(), triangles_.end());
    build_stars(nv, triangles_, star_begin_, star_);
    refpts_.resize(nv);
    probes_.resize(nv + triangles_.size());
    set_time(0.0);
    const std::vector<std::uint32_t> order = spatial_order(probes_);
    probe_src_ = order;
    std::vector<Point3> sorted(probes_.size());
    for (std::size_t i = 0; i < order.size(); ++i) sorted[i] = probes_[order[i]];
    probes_.swap(sorted);
}

void GroundTruth::set_time(double t) {
    if (!std::isfinite(t)) throw InvalidInput("GroundTruth::set_time: t is not finite");
    t_ = t;
    warp_points(*s_, t, s_->reference.positions(), reference_.positions());
    const std::vector<Point3>& p = reference_.positions();
    const std::size_t nv = p.size();
    for (std::size_t k = 0; k < nv; ++k) refpts_[k] = p[ref_order_[k]];
    std::tie(ref_lmax_, ref_mean_edge_) = edge_stats(refpts_, triangles_);
    auto probe = [&](std::uint32_t src) {
        if (src < nv) return refpts_[src];
        const Tri& tr = triangles_[src - nv];
        return (refpts_[tr[0]] + refpts_[tr[1]] + refpts_[tr[2]]) / 3.0;
    };
    if (probe_src_.empty()) {  // constructor: natural order
        for (std::size_t i = 0; i < probes_.size(); ++i)
            probes_[i] = probe(static_cast<std::uint32_t>(i));
    } else {
        for (std::size_t i = 0; i < probes_.size(); ++i) probes_[i] = probe(probe_src_[i]);
    }
}

Vec3 GroundTruth::normal(std::uint32_t pool) const { return surface_normal(*s_, t_, pool); }

double GroundTruth::sampling_radius(std::span<const std::uint32_t> live_pool) const {
    const std::vector<Point3>& p = reference_.positions();
    std::vector<Point3> live(live_pool.size());
    for (std::size_t i = 0; i < live_pool.size(); ++i) {
        if (live_pool[i] >= p.size())
            throw InvalidInput("GroundTruth: live pool index " + std::to_string(live_pool[i]) +
                               " >= pool size " + std::to_string(p.size()));
        live[i] = p[live_pool[i]];
    }
    return covering_radius(probes_, live);
}

FrameMetrics GroundTruth::measure(const SurfaceMesh& mesh,
                                  std::span<const std::uint32_t> vertex_pool,
                                  std::span<const std::uint32_t> live_pool,
                                  const MeasureOptions& options) const {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (vertex_pool.size() < mesh.vertices_size())
        throw InvalidInput("GroundTruth::measure: vertex_pool has " +
                           std::to_string(vertex_pool.size()) + " entries for " +
                           std::to_string(mesh.vertices_size()) + " vertex slots");
    const std::size_t m = s_->pool_size();
    FrameMetrics r;
    r.t = t_;
    r.samples = live_pool.size();
    r.vertices = mesh.n_vertices();
    r.faces = mesh.n_faces();

    // Dense copy of the mesh (live elements, ordered by the rank of their pool point for
    // locality) and the true normals at its vertices.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> by_rank;  // (rank, vertex index)
    by_rank.reserve(mesh.n_vertices());
    for (const Vertex v : mesh.vertices()) {
        const std::uint32_t p = vertex_pool[v.idx()];
        if (p >= m)
            throw InvalidInput("GroundTruth::measure: vertex v" + std::to_string(v.idx()) +
                               " names pool index " + std::to_string(p) + " >= pool size " +
                               std::to_string(m));
        by_rank.emplace_back(ref_rank_[p], v.idx());
    }
    std::sort(by_rank.begin(), by_rank.end());
    std::vector<std::uint32_t> dense(mesh.vertices_size(), kNone);
    std::vector<Point3> pts;
    std::vector<std::uint32_t> rank_of;  // rank of each dense vertex's pool point
    std::vector<Vec3> vn;
    pts.reserve(by_rank.size());
    rank_of.reserve(by_rank.size());
    vn.reserve(by_rank.size());
    for (const auto& [rank, vi] : by_rank) {
        const Vertex v(vi);
        dense[vi] = static_cast<std::uint32_t>(pts.size());
        pts.push_back(mesh.position(v));
        rank_of.push_back(rank);
        vn.push_back(mesh.is_isolated(v) ? Vec3{} : normal(vertex_pool[vi]));
    }
    std::vector<Tri> tris;
    std::vector<Face> tri_face;  // the face of each of tris
    tris.reserve(mesh.n_faces());
    tri_face.reserve(mesh.n_faces());
    for (const Face f : mesh.faces()) {
        const auto v = mesh.face_vertices(f);
        tris.push_back({dense[v[0].idx()], dense[v[1].idx()], dense[v[2].idx()]});
        tri_face.push_back(f);
    }

    // Vertices on a crease edge (dense indices).
    std::vector<char> on_crease(pts.size(), 0);
    if (const auto locked = locked_edges(mesh); locked.is_valid())
        for (const Edge e : mesh.edges())
            if (locked[e])
                for (int i = 0; i < 2; ++i) on_crease[dense[mesh.vertex(e, i).idx()]] = 1;

    // Faces: circumradius, angles, radius-edge, normal deviation, inversion.
    const LocalDistance to_ref(refpts_, triangles_, star_begin_, star_, ref_lmax_, ref_mean_edge_);
    std::vector<std::pair<double, std::uint32_t>> scratch;
    double R = 0, min_angle = kPi, min_angle_off = kPi, max_re = 0, dev_max = 0, dev_sum = 0;
    std::size_t dev_n = 0, inverted = 0;
    for (std::size_t ti = 0; ti < tris.size(); ++ti) {
        const Tri& t = tris[ti];
        const Point3 &a = pts[t[0]], &b = pts[t[1]], &c = pts[t[2]];
        R = std::max(R, circumradius(a, b, c));
        const double angle = dynmesh::min_angle(a, b, c);
        min_angle = std::min(min_angle, angle);
        if (!on_crease[t[0]] && !on_crease[t[1]] && !on_crease[t[2]]) min_angle_off = std::min(min_angle_off, angle);
        max_re = std::max(max_re, radius_edge_ratio(a, b, c));
        const Vec3 nf = triangle_normal(a, b, c);
        Vec3 sum{};
        for (const std::uint32_t x : t) {
            sum += vn[x];
            const double d = rad_to_deg(angle_between(nf, vn[x]));
            dev_max = std::max(dev_max, d);
            dev_sum += d;
            ++dev_n;
        }
        // Inverted: facing away both from the true normals at its corners (their sum) and
        // from every normal of Sigma(t) at the point nearest to its barycentre. The corners'
        // normals alone are averages at a sharp edge or corner of the input, and a stretched
        // coarse mesh then has triangles of Sigma(t) itself facing away from them (fandisk
        // stretched x3: 2 faces of the carried reference); the nearest point alone can lie on
        // one face of a sharp edge that a triangle across the edge makes more than 90 degrees
        // with, while it agrees with the surface at its corners.
        if (dot(nf, sum) < 0 && to_ref.nearest_facing((a + b + c) / 3.0, rank_of[t[0]], nf, scratch) < 0 &&
            inverted++ == 0)
            r.first_inverted = tri_face[ti];
    }
    r.R = R;
    r.min_angle_deg = tris.empty() ? nan : rad_to_deg(min_angle);
    r.min_angle_off_creases_deg = tris.empty() ? nan : rad_to_deg(min_angle_off);
    r.max_radius_edge = max_re;
    r.normal_dev_max_deg = dev_max;
    r.normal_dev_mean_deg = dev_n > 0 ? dev_sum / static_cast<double>(dev_n) : nan;
    r.inverted = inverted;

    // Edges: smallest edge-angle.
    double min_edge = kPi;
    bool any_edge = false;
    for (const Edge e : mesh.edges()) {
        if (mesh.is_boundary(e)) continue;
        const Halfedge h = SurfaceMesh::halfedge(e, 0);
        const Point3& p = mesh.position(mesh.from_vertex(h));
        const Point3& q = mesh.position(mesh.to_vertex(h));
        const Point3& x = mesh.position(mesh.opposite_vertex(h));
        const Point3& y = mesh.position(mesh.opposite_vertex(SurfaceMesh::twin(h)));
        min_edge = std::min(min_edge, dihedral_angle(p, q, x, y));
        any_edge = true;
    }
    r.min_edge_angle_deg = any_edge ? rad_to_deg(min_edge) : nan;

    r.h = options.sampling_radius ? sampling_radius(live_pool) : nan;
    r.R_over_h = r.h > 0 ? r.R / r.h : nan;

    r.hausdorff = nan;
    if (options.hausdorff && !tris.empty()) {
        // Sigma(t) -> mesh: the reference probes (vertices and barycentres), in spatial order.
        std::vector<std::uint32_t> mb, ms;
        build_stars(pts.size(), tris, mb, ms);
        const auto [mesh_lmax, mesh_mean] = edge_stats(pts, tris);
        const LocalDistance to_mesh(pts, tris, mb, ms, mesh_lmax, mesh_mean);
        // Start each probe at the mesh vertex of its own pool point (a vertex probe) or of a
        // corner of its reference face, when the mesh has one.
        const std::size_t nv = refpts_.size();
        std::vector<std::uint32_t> mesh_vertex_of(nv, kNone);  // by rank
        for (std::size_t v = 0; v < pts.size(); ++v)
            if (mb[v + 1] > mb[v]) mesh_vertex_of[rank_of[v]] = static_cast<std::uint32_t>(v);
        std::vector<std::uint32_t> probe_hint(probes_.size(), kNone);
        for (std::size_t i = 0; i < probes_.size(); ++i) {
            const std::uint32_t src = probe_src_[i];
            if (src < nv) {
                probe_hint[i] = mesh_vertex_of[src];
            } else {
                for (std::uint32_t c : triangles_[src - nv])
                    if (mesh_vertex_of[c] != kNone) {
                        probe_hint[i] = mesh_vertex_of[c];
                        break;
                    }
            }
        }
        // The two directions are independent: the first runs on a second thread.
        std::future<double> a2_future;
        double a2 = 0;
        if (options.parallel) {
            a2_future = std::async(std::launch::async,
                                   [&] { return to_mesh.max_sq(probes_, probe_hint); });
        } else {
            a2 = to_mesh.max_sq(probes_, probe_hint);
        }
        // mesh -> Sigma(t): the mesh's barycentres and any vertex off its reference vertex,
        // each starting from the reference vertex of one of its corners.
        std::vector<Point3> queries;
        std::vector<std::uint32_t> hints;
        queries.reserve(tris.size() + 16);
        hints.reserve(tris.size() + 16);
        for (std::size_t v = 0; v < pts.size(); ++v)
            if (!(pts[v] == refpts_[rank_of[v]])) {
                queries.push_back(pts[v]);
                hints.push_back(rank_of[v]);
            }
        for (const Tri& t : tris) {
            queries.push_back((pts[t[0]] + pts[t[1]] + pts[t[2]]) / 3.0);
            hints.push_back(rank_of[t[0]]);
        }
        const double b2 = to_ref.max_sq(queries, hints);
        if (a2_future.valid()) a2 = a2_future.get();
        r.hausdorff = std::sqrt(std::max(a2, b2));
    }
    r.hausdorff_over_h = r.h > 0 ? r.hausdorff / r.h : nan;
    r.self_intersections = options.self_intersections ? count_self_intersections(mesh) : 0;
    return r;
}

FrameMetrics measure_frame(const Scenario& s, double t, const SurfaceMesh& mesh,
                           std::span<const std::uint32_t> vertex_pool,
                           std::span<const std::uint32_t> live_pool,
                           const MeasureOptions& options) {
    GroundTruth g(s);
    g.set_time(t);
    return g.measure(mesh, vertex_pool, live_pool, options);
}

std::vector<std::pair<std::string, double>> flatten(const FrameMetrics& m) {
    auto d = [](std::size_t x) { return static_cast<double>(x); };
    return {{"t", m.t},
            {"samples", d(m.samples)},
            {"vertices", d(m.vertices)},
            {"faces", d(m.faces)},
            {"R", m.R},
            {"h", m.h},
            {"R_over_h", m.R_over_h},
            {"min_angle_deg", m.min_angle_deg},
            {"max_radius_edge", m.max_radius_edge},
            {"min_edge_angle_deg", m.min_edge_angle_deg},
            {"normal_dev_max_deg", m.normal_dev_max_deg},
            {"normal_dev_mean_deg", m.normal_dev_mean_deg},
            {"hausdorff", m.hausdorff},
            {"hausdorff_over_h", m.hausdorff_over_h},
            {"self_intersections", d(m.self_intersections)},
            {"inverted", d(m.inverted)},
            {"min_angle_off_creases_deg", m.min_angle_off_creases_deg}};
}

}  // namespace dynmesh
