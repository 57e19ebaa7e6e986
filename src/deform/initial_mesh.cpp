#include "dynmesh/deform/initial_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "dynmesh/deform/local_ops.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/geometry/point_grid.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/reconstruct/restricted_delaunay.hpp"

namespace dynmesh {

std::string_view to_string(ReferenceMeshPath p) {
    return p == ReferenceMeshPath::RestrictedDelaunay ? "restricted_delaunay" : "decimated";
}

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

double largest_circumradius_of(const SurfaceMesh& m) {
    double r = 0;
    for (Face f : m.faces()) {
        const auto vs = m.face_vertices(f);
        r = std::max(r, circumradius(m.position(vs[0]), m.position(vs[1]), m.position(vs[2])));
    }
    return r;
}

/// Step 2 of initial_mesh_on_reference(): RefineVert's fixed point on the vertex set.
void refine_to_fixed_point(std::span<const Point3> samples, const SurfaceMesh& reference,
                           MeshRestrictedDelaunayOptions ro, const ReferenceMeshOptions& options,
                           MeshRestrictedDelaunayResult& r, ReferenceMesh& out) {
    ro.throw_on_failure = false;
    DYNMESH_CHECK(options.size.empty() || options.size.size() == samples.size(),
                  "initial_mesh_on_reference: one size per sample");
    std::vector<char> blocked(samples.size(), 0);
    auto at = [&](std::uint32_t x) { return samples[x]; };
    for (std::size_t round = 0; round < options.max_refine_rounds; ++round) {
        const double R = largest_circumradius_of(r.mesh);
        if (!(R > 0 && std::isfinite(R))) return;
        bool grew = false;
        for (int attempt = 0; attempt < 4 && !grew; ++attempt) {
            PointGrid g(R);
            std::vector<char> is_vertex(samples.size(), 0);
            std::vector<std::uint32_t> net(r.report.vertex_sample.begin(), r.report.vertex_sample.end());
            for (std::uint32_t s : net) {
                g.insert(s, samples[s]);
                is_vertex[s] = 1;
            }
            const std::size_t before = net.size();
            for (std::uint32_t p = 0; p < samples.size(); ++p) {
                if (is_vertex[p] || blocked[p]) continue;
                const double r = options.size.empty() ? R : std::min(R, options.size[p]);
                if (g.nearest(samples[p], at, [](std::uint32_t) { return true; }).second > r / 3) {
                    g.insert(p, samples[p]);
                    net.push_back(p);
                }
            }
            // A few stragglers are left to RefineVert's Adds (local), not worth a new RDT.
            if (net.size() - before <= before / 100) return;
            const std::vector<std::uint32_t> joined(net.begin() + static_cast<std::ptrdiff_t>(before), net.end());
            std::sort(net.begin(), net.end());
            MeshRestrictedDelaunayResult next = restricted_delaunay_on_mesh(samples, net, reference, ro);
            if (next.report.correct) {
                out.promoted += joined.size();
                out.added += next.report.added;
                r = std::move(next);
                grew = true;
                break;
            }
            // Keep out the samples that would join near the failure.
            const std::vector<Point3>& bad = next.report.defect_points;
            PointGrid bg(R);
            for (std::uint32_t k = 0; k < bad.size(); ++k) bg.insert(k, bad[k]);
            for (std::uint32_t p : joined) {
                bool near = bad.empty();
                bg.for_each_candidate(samples[p], 3 * R,
                                      [&](std::uint32_t k) { near |= distance(samples[p], bad[k]) <= 3 * R; });
                if (near) blocked[p] = 1;
            }
        }
        if (!grew) return;
    }
}

/// Path A: the reference with every vertex but the net removed. Throws InvalidInput (why)
/// when a non-sample vertex cannot be removed or a net sample is no reference vertex.
ReferenceMesh decimate_reference(std::span<const Point3> samples, std::span<const std::uint32_t> net,
                                 const SurfaceMesh& reference) {
    SurfaceMesh m = reference;
    if (auto old = m.get_vertex_property<std::uint32_t>("v:initial_sample"); old.is_valid()) m.remove_property(old);
    auto sample_of = m.add_vertex_property<std::uint32_t>("v:initial_sample", kNone);
    {   // reference vertex -> sample, by exact coordinates
        std::map<std::array<double, 3>, std::uint32_t> index;
        for (std::uint32_t i = 0; i < samples.size(); ++i)
            index.emplace(std::array<double, 3>{samples[i].x, samples[i].y, samples[i].z}, i);
        for (Vertex v : m.vertices()) {
            const Point3& p = m.position(v);
            const auto it = index.find({p.x, p.y, p.z});
            if (it != index.end()) sample_of[v] = it->second;
        }
    }
    std::vector<char> in_net(samples.size(), 0);
    for (std::uint32_t s : net) in_net[s] = 1;
    std::size_t found = 0;
    for (Vertex v : m.vertices())
        if (sample_of[v] != kNone && in_net[sample_of[v]]) ++found;
    if (found != net.size())
        throw InvalidInput(std::to_string(net.size() - found) + " net samples are not vertices of the reference");
    // Non-samples first, then the samples outside the net; a refused removal is retried after
    // the others, as long as some removal succeeds.
    std::vector<Vertex> todo;
    for (int pass = 0; pass < 2; ++pass)
        for (Vertex v : m.vertices()) {
            const std::uint32_t s = sample_of[v];
            if ((pass == 0 && s == kNone) || (pass == 1 && s != kNone && !in_net[s])) todo.push_back(v);
        }
    RemoveOptions ro;
    while (!todo.empty()) {
        std::vector<Vertex> refused;
        for (Vertex v : todo)
            if (!remove_point(m, v, ro).removed) refused.push_back(v);
        if (refused.size() == todo.size()) break;
        todo = std::move(refused);
    }
    for (Vertex v : todo)
        if (sample_of[v] == kNone) {
            const Point3& p = m.position(v);
            throw InvalidInput("the reference vertex at (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " +
                               std::to_string(p.z) + "), which is no sample, cannot be removed");
        }
    m.garbage_collection();
    ReferenceMesh out;
    out.path = ReferenceMeshPath::Decimated;
    for (Vertex v : m.vertices()) out.vertex_sample.push_back(sample_of[v]);
    out.added = todo.size();
    m.remove_property(sample_of);
    out.mesh = std::move(m);
    return out;
}

}  // namespace

ReferenceMesh initial_mesh_on_reference(std::span<const Point3> samples, std::span<const std::uint32_t> net,
                                        const SurfaceMesh& reference, const ReferenceMeshOptions& options) {
    MeshRestrictedDelaunayOptions ro;
    ro.max_rounds = options.max_rdt_rounds;
    ro.refine_diametric_balls = true;
    ro.min_spacing_factor = 1.0 / 3.0;
    ReferenceMesh out;
    std::string a_failed;
    if (options.decimate_first) {
        try {
            return decimate_reference(samples, net, reference);
        } catch (const InvalidInput& a) {
            a_failed = a.what();
        }
    }
    MeshRestrictedDelaunayResult r;
    try {
        r = restricted_delaunay_on_mesh(samples, net, reference, ro);
    } catch (const InvalidInput& b) {
        if (!a_failed.empty())
            throw InvalidInput(std::string("initial_mesh_on_reference: ") + b.what() +
                               "; and decimating the reference failed: " + a_failed);
        try {
            out = decimate_reference(samples, net, reference);
        } catch (const InvalidInput& a) {
            throw InvalidInput(std::string("initial_mesh_on_reference: ") + b.what() +
                               "; and decimating the reference failed: " + a.what());
        }
        out.fallback_reason = b.what();
        return out;
    }
    out.added = r.report.added;
    out.fallback_reason = a_failed;
    if (options.refine) refine_to_fixed_point(samples, reference, ro, options, r, out);
    out.mesh = std::move(r.mesh);
    out.vertex_sample = std::move(r.report.vertex_sample);
    return out;
}

}  // namespace dynmesh
