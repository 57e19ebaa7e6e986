#include "dynmesh/mesh/surface_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <utility>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/system/hash.hpp"
#include "dynmesh/system/parallel.hpp"

namespace dynmesh {

namespace {
constexpr std::uint32_t kInvalid = Handle<VertexTag>::kInvalid;
using Triangle = std::array<std::uint32_t, 3>;

std::string vstr(std::uint32_t i) { return "vertex " + std::to_string(i); }

/// True when no vertex repeats in the cycle.
bool is_simple_cycle(const std::vector<Vertex>& cycle) {
    std::vector<std::uint32_t> ids;
    ids.reserve(cycle.size());
    for (Vertex w : cycle) ids.push_back(w.idx());
    std::sort(ids.begin(), ids.end());
    return std::adjacent_find(ids.begin(), ids.end()) == ids.end();
}

struct PairHash {
    std::size_t operator()(std::uint64_t k) const noexcept { return static_cast<std::size_t>(mix64(k)); }
};
inline std::uint64_t key(std::uint32_t a, std::uint32_t b) {
    return (static_cast<std::uint64_t>(a) << 32) | b;
}
}  // namespace

// ---- construction ----------------------------------------------------------------------------

Vertex SurfaceMesh::add_vertex(const Point3& p) {
    positions_.push_back(p);
    vhalfedge_.push_back(kInvalid);
    vdeleted_.push_back(false);
    vprops_.push_back();
    return Vertex(static_cast<std::uint32_t>(positions_.size() - 1));
}

void SurfaceMesh::remove_isolated_vertex(Vertex v) {
    if (!is_valid(v) || is_deleted(v) || !is_isolated(v))
        throw InvalidInput("remove_isolated_vertex: " + vstr(v.idx()) + " is invalid, deleted or not isolated");
    delete_vertex(v);
}

Halfedge SurfaceMesh::new_edge(Vertex from, Vertex to) {
    const auto h = static_cast<std::uint32_t>(hto_.size());
    hto_.push_back(to.idx());
    hto_.push_back(from.idx());
    for (int i = 0; i < 2; ++i) {
        hnext_.push_back(kInvalid);
        hprev_.push_back(kInvalid);
        hface_.push_back(kInvalid);
    }
    edeleted_.push_back(false);
    eprops_.push_back();
    return Halfedge(h);
}

Face SurfaceMesh::new_face() {
    fhalfedge_.push_back(kInvalid);
    fdeleted_.push_back(false);
    fprops_.push_back();
    return Face(static_cast<std::uint32_t>(fhalfedge_.size() - 1));
}

void SurfaceMesh::reserve(std::size_t nv, std::size_t ne, std::size_t nf) {
    positions_.reserve(nv);
    vhalfedge_.reserve(nv);
    vdeleted_.reserve(nv);
    vprops_.reserve(nv);
    for (auto* v : {&hto_, &hnext_, &hprev_, &hface_}) v->reserve(2 * ne);
    edeleted_.reserve(ne);
    eprops_.reserve(ne);
    fhalfedge_.reserve(nf);
    fdeleted_.reserve(nf);
    fprops_.reserve(nf);
}

namespace {

/// Corner j = 3t + i of a soup is the directed edge tri[i] -> tri[i + 1]. For each corner, the
/// corner of the opposite direction on the same edge (kInvalid when there is none), when every
/// edge is used at most once in each direction; null otherwise.
///
/// Corners are bucketed by the smaller end of their edge (a counting sort; each part of the
/// triangles counts and fills its own share of every bucket, so buckets list corners in soup
/// order whatever the number of parts). Within a bucket, the two corners of an edge meet at its
/// larger end, which remembers the first of them until the second comes; parts of the buckets
/// remember in arrays of their own.
std::unique_ptr<std::uint32_t[]> twin_corners(std::size_t nv, std::span<const Triangle> triangles, unsigned parts) {
    const std::size_t nf = triangles.size(), nc = nf * 3;
    // fill[p][v]: first the number of part p's corners in bucket v, then where the next goes.
    std::vector<std::vector<std::uint32_t>> fill(parts);
    run_parts(parts, nf, [&](unsigned p, std::size_t b, std::size_t e) {
        fill[p].assign(nv, 0);
        for (std::size_t t = b; t < e; ++t)
            for (int i = 0; i < 3; ++i) ++fill[p][std::min(triangles[t][i], triangles[t][(i + 1) % 3])];
    });
    std::vector<std::uint32_t> begin(nv + 1);
    std::uint32_t total = 0;
    for (std::size_t v = 0; v < nv; ++v) {
        begin[v] = total;
        for (unsigned p = 0; p < parts; ++p) total += std::exchange(fill[p][v], total);
    }
    begin[nv] = total;
    // An entry: the larger end of the edge, and the corner with kDown set when it runs from the
    // larger end to the smaller (corners stay below 2^31: from_soup bounds the triangle count).
    constexpr std::uint32_t kDown = 0x80000000u;
    struct Entry {
        std::uint32_t other, corner;
    };
    const std::unique_ptr<Entry[]> entries = uninitialized_huge_array<Entry>(nc);  // every slot is written below
    run_parts(parts, nf, [&](unsigned p, std::size_t b, std::size_t e) {
        std::vector<std::uint32_t>& next = fill[p];
        for (std::size_t t = b; t < e; ++t) {
            const auto& tri = triangles[t];
            for (int i = 0; i < 3; ++i) {
                const std::uint32_t a = tri[i], c = tri[(i + 1) % 3], j = std::uint32_t(3 * t + std::size_t(i));
                if (a < c)
                    entries[next[a]++] = {c, j};
                else
                    entries[next[c]++] = {a, j | kDown};
            }
        }
    });
    fill.clear();
    std::unique_ptr<std::uint32_t[]> twins = uninitialized_huge_array<std::uint32_t>(nc);
    run_parts(parts, nc, [&](unsigned, std::size_t b, std::size_t e) { std::fill(twins.get() + b, twins.get() + e, kInvalid); });
    struct Seen {
        std::uint32_t bucket = kInvalid;  // the bucket that last reached this vertex
        std::uint32_t corner = 0;         // its unpaired corner there; kInvalid once paired
    };
    std::vector<char> part_bad(parts, 0);
    run_parts(parts, nv, [&](unsigned p, std::size_t vb, std::size_t ve) {
        std::vector<Seen> seen(nv - vb);  // the larger ends of this part's buckets are >= vb
        for (std::size_t v = vb; v < ve; ++v) {
            for (std::uint32_t e = begin[v]; e < begin[v + 1]; ++e) {
                Seen& s = seen[entries[e].other - vb];
                const std::uint32_t c = entries[e].corner;
                if (s.bucket != v) {
                    s = {std::uint32_t(v), c};
                    continue;
                }
                // A third corner on the edge, or a second one in the same direction.
                if (s.corner == kInvalid || ((s.corner ^ c) & kDown) == 0) {
                    part_bad[p] = 1;
                    return;
                }
                const std::uint32_t j = c & ~kDown, k = s.corner & ~kDown;
                twins[j] = k;
                twins[k] = j;
                s.corner = kInvalid;
            }
        }
    });
    if (std::find(part_bad.begin(), part_bad.end(), 1) != part_bad.end()) return nullptr;
    return twins;
}

/// Throws the TopologyError naming the first triangle (in soup order) that uses an edge in a
/// direction an earlier triangle used already (called when twin_corners() found one).
[[noreturn]] void throw_first_repeated_edge(std::span<const Triangle> triangles) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> used;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const auto& tri = triangles[t];
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t a = tri[i], b = tri[(i + 1) % 3];
            if (!used.insert({a, b}).second)
                throw TopologyError("from_soup: triangle " + std::to_string(t) + ": edge (" + std::to_string(a) + ", " +
                                    std::to_string(b) +
                                    ") is used twice in the same direction (inconsistent "
                                    "orientation, or an edge shared by more than two triangles)");
        }
    }
    throw InternalError("from_soup: an edge is used twice in one direction, but no triangle repeats one");
}

}  // namespace

SurfaceMesh SurfaceMesh::from_soup(const TriangleSoup& soup, const FromSoupOptions& options) {
    std::vector<Point3> points = soup.points;
    return build(std::move(points), soup.triangles, options.threads);
}

SurfaceMesh SurfaceMesh::from_soup(TriangleSoup&& soup, const FromSoupOptions& options) {
    return build(std::move(soup.points), soup.triangles, options.threads);
}

SurfaceMesh SurfaceMesh::build(std::vector<Point3>&& points, std::span<const Triangle> triangles, unsigned threads) {
    SurfaceMesh m;
    const std::size_t nv = points.size(), nf = triangles.size();
    if (nv >= kInvalid || nf >= kInvalid / 6) throw InvalidInput("from_soup: too many elements for 32-bit indices");
    // Parts of at least 2^17 triangles each unless the caller says (below that, threads cost
    // more than they save). Each check below throws at a part's first bad element; run_parts
    // rethrows the lowest part's, so the message names the first in the soup.
    const unsigned parts = threads == 0 ? parallel_parts(nf, std::size_t(1) << 17)
                                        : unsigned(std::max<std::size_t>(1, std::min<std::size_t>({threads, nf, 64})));
    run_parts(parts, nv, [&](unsigned, std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i)
            if (!is_finite(points[i]))
                throw InvalidInput("from_soup: " + vstr(static_cast<std::uint32_t>(i)) +
                                   " has a non-finite coordinate (NaN or infinity)");
    });
    const auto where = [](std::size_t t) { return "from_soup: triangle " + std::to_string(t); };
    run_parts(parts, nf, [&](unsigned, std::size_t b, std::size_t e) {
        for (std::size_t t = b; t < e; ++t) {
            const auto& tri = triangles[t];
            for (std::uint32_t i : tri)
                if (i >= nv)
                    throw InvalidInput(where(t) + " uses vertex index " + std::to_string(i) +
                                       " but there are only " + std::to_string(nv) + " vertices");
            if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
                throw InvalidInput(where(t) + " repeats a vertex (" + std::to_string(tri[0]) + ", " +
                                   std::to_string(tri[1]) + ", " + std::to_string(tri[2]) + ")");
        }
    });
    const std::size_t nc = nf * 3;
    // The twin of each corner (the corner of the opposite direction of its edge), or the first
    // triangle that uses an edge twice in one direction.
    std::unique_ptr<std::uint32_t[]> twins = twin_corners(nv, triangles, parts);
    if (!twins) throw_first_repeated_edge(triangles);
    const std::uint32_t* twin_of = twins.get();
    // Corner j (directed edge tri[i] -> tri[i + 1]) gets halfedge 2e of a new edge e when it is
    // the first corner of its edge in soup order, the other halfedge of its twin's edge
    // otherwise. Each part numbers its first corners after those of the parts before it.
    const auto first = [&](std::size_t j) { return twin_of[j] == kInvalid || twin_of[j] > j; };
    std::vector<std::uint32_t> part_edges(parts + 1, 0);
    run_parts(parts, nc, [&](unsigned p, std::size_t b, std::size_t e) {
        std::uint32_t count = 0;
        for (std::size_t j = b; j < e; ++j) count += first(j) ? 1 : 0;
        part_edges[p + 1] = count;
    });
    std::partial_sum(part_edges.begin(), part_edges.end(), part_edges.begin());
    const std::size_t ne = part_edges[parts];
    // The halfedge of every corner: first the first corners, then the others from their twins.
    std::unique_ptr<std::uint32_t[]> corner_halfedge = uninitialized_huge_array<std::uint32_t>(nc);
    run_parts(parts, nc, [&](unsigned p, std::size_t b, std::size_t e) {
        std::uint32_t next_edge = part_edges[p];
        for (std::size_t j = b; j < e; ++j)
            if (first(j)) corner_halfedge[j] = 2 * next_edge++;
    });
    run_parts(parts, nc, [&](unsigned, std::size_t b, std::size_t e) {
        for (std::size_t j = b; j < e; ++j)
            if (!first(j)) corner_halfedge[j] = corner_halfedge[twin_of[j]] ^ 1u;
    });
    // Every array is sized once and written in place. The first corner of each edge writes both
    // its halfedges, so that each part writes its own range of halfedges.
    m.positions_ = std::move(points);
    // The four halfedge arrays are sized (and their pages faulted in) by as many parts.
    std::array<std::vector<std::uint32_t>*, 4> halfedge_arrays{&m.hto_, &m.hnext_, &m.hprev_, &m.hface_};
    run_parts(std::min(parts, 4u), 4, [&](unsigned, std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) {
            reserve_huge(*halfedge_arrays[i], 2 * ne);
            halfedge_arrays[i]->assign(2 * ne, kInvalid);
        }
    });
    m.edeleted_.assign(ne, false);
    m.eprops_.resize(ne);
    m.fhalfedge_.resize(nf);
    m.fdeleted_.assign(nf, false);
    m.fprops_.resize(nf);
    m.vdeleted_.assign(nv, false);
    m.vprops_.resize(nv);
    const auto corner_vertex = [&](std::size_t j, std::size_t shift) { return triangles[j / 3][(j + shift) % 3]; };
    const auto corner_after = [](std::size_t j, std::size_t shift) { return j - j % 3 + (j + shift) % 3; };
    const auto write_halfedge = [&](std::size_t j) {
        const std::uint32_t h = corner_halfedge[j];
        m.hto_[h] = corner_vertex(j, 1);
        m.hnext_[h] = corner_halfedge[corner_after(j, 1)];
        m.hprev_[h] = corner_halfedge[corner_after(j, 2)];
        m.hface_[h] = static_cast<std::uint32_t>(j / 3);
    };
    run_parts(parts, nc, [&](unsigned, std::size_t b, std::size_t e) {
        for (std::size_t j = b; j < e; ++j) {
            if (!first(j)) continue;
            write_halfedge(j);
            if (twin_of[j] != kInvalid)
                write_halfedge(twin_of[j]);
            else
                m.hto_[corner_halfedge[j] ^ 1u] = corner_vertex(j, 0);  // a boundary halfedge
        }
    });
    // A face's halfedge is that of its first corner; a vertex's, that of its last corner in
    // soup order: each part keeps its own (the last part the mesh's), and a part's choice
    // stands unless a later part has one.
    std::vector<std::vector<std::uint32_t>> part_vertex_halfedge(parts - 1);
    m.vhalfedge_.assign(nv, kInvalid);
    run_parts(parts, nf, [&](unsigned p, std::size_t b, std::size_t e) {
        std::vector<std::uint32_t>& vh = p + 1 == parts ? m.vhalfedge_ : part_vertex_halfedge[p];
        if (p + 1 != parts) vh.assign(nv, kInvalid);
        for (std::size_t t = b; t < e; ++t) {
            m.fhalfedge_[t] = corner_halfedge[3 * t];
            for (std::size_t i = 0; i < 3; ++i) vh[triangles[t][i]] = corner_halfedge[3 * t + i];
        }
    });
    for (int p = int(parts) - 2; p >= 0; --p)
        for (std::size_t v = 0; v < nv; ++v)
            if (m.vhalfedge_[v] == kInvalid) m.vhalfedge_[v] = part_vertex_halfedge[std::size_t(p)][v];
    twins.reset();
    corner_halfedge.reset();
    part_vertex_halfedge.clear();
    // Link boundary halfedges into loops; a vertex with two outgoing boundary halfedges is
    // pinched (non-manifold). The parts list their boundary halfedges; one pass links them in
    // halfedge order.
    std::vector<std::vector<std::uint32_t>> part_boundary(parts);
    run_parts(parts, m.hto_.size(), [&](unsigned p, std::size_t b, std::size_t e) {
        std::vector<std::uint32_t> list;
        for (std::size_t h = b; h < e; ++h)
            if (m.hface_[h] == kInvalid) list.push_back(std::uint32_t(h));
        part_boundary[p] = std::move(list);
    });
    std::vector<std::uint32_t> boundary_out(nv, kInvalid);
    for (const auto& list : part_boundary)
        for (std::uint32_t h : list) {
            const std::uint32_t from = m.hto_[h ^ 1u];
            if (boundary_out[from] != kInvalid)
                throw TopologyError("from_soup: " + vstr(from) +
                                    " is non-manifold: it has two separate boundary fans");
            boundary_out[from] = h;
        }
    for (const auto& list : part_boundary)
        for (std::uint32_t h : list) {
            m.set_next(Halfedge(h), Halfedge(boundary_out[m.hto_[h]]));
            m.set_halfedge(Vertex(m.hto_[h ^ 1u]), Halfedge(h));
        }
    // Every outgoing halfedge of a manifold vertex lies in the one fan around it: walk each
    // vertex's fan from its halfedge, marking what it reaches; an unmarked halfedge leaves a
    // vertex with another fan. (Each part marks only its own vertices' halfedges.)
    std::vector<char> reached(m.hto_.size(), 0);
    std::vector<std::uint32_t> part_broken(parts, kInvalid);
    run_parts(parts, nv, [&](unsigned p, std::size_t b, std::size_t e) {
        for (std::size_t v = b; v < e; ++v) {
            const std::uint32_t start = m.vhalfedge_[v];
            if (start == kInvalid) continue;
            std::uint32_t h = start;
            std::size_t steps = 0;
            do {
                reached[h] = 1;
                h = m.hprev_[h] ^ 1u;  // ccw_rotated
            } while (h != start && ++steps <= m.hto_.size());
            if (h != start) {
                part_broken[p] = std::uint32_t(v);
                return;
            }
        }
    });
    for (std::uint32_t v : part_broken)
        if (v != kInvalid)  // next is a permutation by now: every fan closes
            throw InternalError("from_soup: the fan of " + vstr(v) + " does not close");
    std::vector<std::uint32_t> part_pinched(parts, kInvalid);
    run_parts(parts, m.hto_.size(), [&](unsigned p, std::size_t b, std::size_t e) {
        for (std::size_t h = b; h < e; ++h)
            if (!reached[h]) part_pinched[p] = std::min(part_pinched[p], m.hto_[h ^ 1u]);
    });
    const std::uint32_t pinched = *std::min_element(part_pinched.begin(), part_pinched.end());
    if (pinched != kInvalid)
        throw TopologyError("from_soup: " + vstr(pinched) +
                            " is non-manifold: its triangles form more than one fan (pinched vertex)");
    return m;
}

TriangleSoup SurfaceMesh::to_soup() const {
    TriangleSoup s;
    std::vector<std::uint32_t> index(vertices_size(), kInvalid);
    for (Vertex v : vertices()) {
        index[v.idx()] = static_cast<std::uint32_t>(s.points.size());
        s.points.push_back(position(v));
    }
    s.triangles.reserve(n_faces());
    for (Face f : faces()) {
        const auto vs = face_vertices(f);
        s.triangles.push_back({index[vs[0].idx()], index[vs[1].idx()], index[vs[2].idx()]});
    }
    return s;
}

// ---- queries ---------------------------------------------------------------------------------

bool SurfaceMesh::is_closed() const {
    for (Edge e : edges())
        if (is_boundary(e)) return false;
    return true;
}

std::size_t SurfaceMesh::valence(Vertex v) const {
    std::size_t n = 0;
    for ([[maybe_unused]] Halfedge h : outgoing_halfedges(v)) ++n;
    return n;
}

Halfedge SurfaceMesh::find_halfedge(Vertex a, Vertex b) const {
    for (Halfedge h : outgoing_halfedges(a))
        if (to_vertex(h) == b) return h;
    return {};
}

std::vector<Vertex> SurfaceMesh::neighbors(Vertex v) const {
    std::vector<Vertex> out;
    for (Halfedge h : outgoing_halfedges(v)) out.push_back(to_vertex(h));
    return out;
}

// ---- deletion helpers ------------------------------------------------------------------------

void SurfaceMesh::delete_vertex(Vertex v) {
    if (!vdeleted_[v.idx()]) {
        vdeleted_[v.idx()] = true;
        ++n_deleted_vertices_;
    }
}
void SurfaceMesh::delete_edge(Edge e) {
    if (!edeleted_[e.idx()]) {
        edeleted_[e.idx()] = true;
        ++n_deleted_edges_;
    }
}
void SurfaceMesh::delete_face(Face f) {
    if (!fdeleted_[f.idx()]) {
        fdeleted_[f.idx()] = true;
        ++n_deleted_faces_;
        log_face(f);
    }
}

void SurfaceMesh::adjust_outgoing_halfedge(Vertex v) {
    const Halfedge start = halfedge(v);
    if (!start.is_valid()) return;
    Halfedge h = start;
    do {
        if (is_boundary(h)) {
            set_halfedge(v, h);
            return;
        }
        h = ccw_rotated(h);
    } while (h != start);
}

void SurfaceMesh::replace_in_cycle(Halfedge old, Halfedge by) {
    const Halfedge p = prev(old), n = next(old);
    set_next(p, by);
    set_next(by, n);
    const Face f = face(old);
    set_face(by, f);
    if (f.is_valid() && halfedge(f) == old) set_halfedge(f, by);
}

// ---- flips -----------------------------------------------------------------------------------

bool SurfaceMesh::is_flip_ok(Edge e) const {
    if (is_deleted(e) || is_boundary(e)) return false;
    const Halfedge h0 = halfedge(e, 0), h1 = halfedge(e, 1);
    const Vertex r = to_vertex(next(h0)), s = to_vertex(next(h1));
    if (r == s) return false;
    return !find_halfedge(r, s).is_valid();
}

void SurfaceMesh::flip(Edge e) {
    DYNMESH_ASSERT(is_flip_ok(e), "flip: edge " + std::to_string(e.idx()) + " is not flippable");
    // h0: p->q in (p,q,r) with a0: q->r, b0: r->p; h1: q->p in (q,p,s) with a1: p->s, b1: s->q.
    const Halfedge h0 = halfedge(e, 0), h1 = halfedge(e, 1);
    const Halfedge a0 = next(h0), b0 = next(a0);
    const Halfedge a1 = next(h1), b1 = next(a1);
    const Vertex p = to_vertex(h1), q = to_vertex(h0);
    const Vertex r = to_vertex(a0), s = to_vertex(a1);
    const Face f0 = face(h0), f1 = face(h1);
    // New faces: f0 = (q, r, s) = a0, h0 (r->s), b1; f1 = (p, s, r) = a1, h1 (s->r), b0.
    set_to(h0, s);
    set_to(h1, r);
    link_triangle(h0, b1, a0, f0);
    link_triangle(h1, b0, a1, f1);
    if (halfedge(p) == h0) set_halfedge(p, a1);
    if (halfedge(q) == h1) set_halfedge(q, a0);
}

// ---- splits ----------------------------------------------------------------------------------

Vertex SurfaceMesh::split_face(Face f, const Point3& p) {
    DYNMESH_CHECK(is_valid(f) && !is_deleted(f), "split_face: face is deleted or invalid");
    const Halfedge hab = halfedge(f), hbc = next(hab), hca = next(hbc);
    const Vertex b = to_vertex(hab), c = to_vertex(hbc), a = to_vertex(hca);
    const Vertex v = add_vertex(p);
    const Halfedge xa = new_edge(a, v), xb = new_edge(b, v), xc = new_edge(c, v);
    const Halfedge ya = twin(xa), yb = twin(xb), yc = twin(xc);
    const Face f1 = new_face(), f2 = new_face();
    // f = (a,b,v): hab, xb, ya ; f1 = (b,c,v): hbc, xc, yb ; f2 = (c,a,v): hca, xa, yc
    link_triangle(hab, xb, ya, f);
    link_triangle(hbc, xc, yb, f1);
    link_triangle(hca, xa, yc, f2);
    set_halfedge(v, ya);
    return v;
}

Vertex SurfaceMesh::split_edge(Edge e, const Point3& pos) {
    DYNMESH_CHECK(is_valid(e) && !is_deleted(e), "split_edge: edge is deleted or invalid");
    const Halfedge h0 = halfedge(e, 0), h1 = halfedge(e, 1);  // h0: p->q, h1: q->p
    const Vertex q = to_vertex(h0);
    const Vertex m = add_vertex(pos);
    const Halfedge n0 = new_edge(m, q), n1 = twin(n0);  // n0: m->q, n1: q->m
    set_to(h0, m);                                      // h0: p->m, h1: m->p
    if (halfedge(q) == h1) set_halfedge(q, n1);

    // Side of h0: face (p,q,r) = h0, a0 (q->r), b0 (r->p).
    if (!is_boundary(h0)) {
        const Halfedge a0 = next(h0), b0 = next(a0);
        const Vertex r = to_vertex(a0);
        const Face f0 = face(h0), g0 = new_face();
        const Halfedge t = new_edge(m, r), tt = twin(t);  // t: m->r, tt: r->m
        // f0 = (p, m, r): h0, t, b0 ; g0 = (m, q, r): n0, a0, tt
        link_triangle(h0, t, b0, f0);
        link_triangle(n0, a0, tt, g0);
    } else {
        // boundary loop: ... -> h0 (p->m) -> n0 (m->q) -> old next(h0)
        const Halfedge after = next(h0);
        set_next(h0, n0);
        set_next(n0, after);
    }
    // Side of h1: face (q,p,s) = h1, a1 (p->s), b1 (s->q). Now h1 is m->p.
    if (!is_boundary(h1)) {
        const Halfedge a1 = next(h1), b1 = next(a1);
        const Vertex s = to_vertex(a1);
        const Face f1 = face(h1), g1 = new_face();
        const Halfedge u = new_edge(s, m), uu = twin(u);  // u: s->m, uu: m->s
        // f1 = (m, p, s): h1, a1, u ; g1 = (q, m, s): n1, uu, b1
        link_triangle(h1, a1, u, f1);
        link_triangle(n1, uu, b1, g1);
    } else {
        // boundary loop: old prev(h1) -> n1 (q->m) -> h1 (m->p)
        const Halfedge before = prev(h1);
        set_next(before, n1);
        set_next(n1, h1);
    }
    set_halfedge(m, n0);
    adjust_outgoing_halfedge(m);
    adjust_outgoing_halfedge(q);
    return m;
}

// ---- collapse --------------------------------------------------------------------------------

bool SurfaceMesh::is_collapse_ok(Halfedge h) const {
    if (is_deleted(h)) return false;
    const Halfedge o = twin(h);
    const Vertex v0 = from_vertex(h), v1 = to_vertex(h);
    const Vertex vl = is_boundary(h) ? Vertex() : to_vertex(next(h));
    const Vertex vr = is_boundary(o) ? Vertex() : to_vertex(next(o));
    // A boundary edge's endpoints are both boundary; an interior edge joining two boundary
    // vertices would pinch the surface.
    if (is_boundary(v0) && is_boundary(v1) && !is_boundary(edge(h))) return false;
    // Opposite vertices must keep valence >= 3 (else two triangles would coincide).
    if (vl.is_valid() && valence(vl) <= 3 && !is_boundary(vl)) return false;
    if (vr.is_valid() && valence(vr) <= 3 && !is_boundary(vr)) return false;
    if (vl.is_valid() && vl == vr) return false;
    // A triangle whose two other edges are both boundary would leave a dangling edge.
    for (Halfedge x : {h, o})
        if (!is_boundary(x) && is_boundary(twin(next(x))) && is_boundary(twin(prev(x)))) return false;
    // Link condition: the common neighbours of v0 and v1 are exactly vl and vr.
    for (Halfedge g : outgoing_halfedges(v0)) {
        const Vertex w = to_vertex(g);
        if (w == v1 || w == vl || w == vr) continue;
        if (find_halfedge(w, v1).is_valid()) return false;
    }
    // A closed tetrahedron cannot shrink further.
    if (n_vertices() <= 4 && is_closed()) return false;
    return true;
}

void SurfaceMesh::collapse(Halfedge h) {
    DYNMESH_ASSERT(is_collapse_ok(h), "collapse: halfedge " + std::to_string(h.idx()) + " not collapsible");
    const Halfedge o = twin(h);
    const Vertex v0 = from_vertex(h), v1 = to_vertex(h);

    // 1. Every halfedge into v0 now points to v1 (v0's faces now have v1).
    for (Halfedge g : outgoing_halfedges(v0)) {
        set_to(twin(g), v1);
        if (const Face f = face(g); f.is_valid()) log_face(f);
    }

    // 2. Unlink h and o, removing their triangles.
    auto remove_side = [&](Halfedge x) {
        if (is_boundary(x)) {
            // boundary loop: prev(x) -> x -> next(x) becomes prev(x) -> next(x)
            set_next(prev(x), next(x));
            return;
        }
        // triangle (v0, v1, w) = x, hn (v1 -> w), hp (w -> v0, now w -> v1)
        const Halfedge hn = next(x), hp = next(hn);
        const Halfedge on = twin(hn);  // w -> v1, outside the triangle
        const Vertex w = to_vertex(hn);
        delete_face(face(x));
        // Keep the edge of hp; hp takes over on's place; delete hn's edge.
        replace_in_cycle(on, hp);
        if (halfedge(w) == on) set_halfedge(w, hp);
        if (halfedge(v1) == hn) set_halfedge(v1, twin(hp));
        delete_edge(edge(hn));
    };
    // An outgoing halfedge of v1 that survives: the kept edge of the h side.
    const Halfedge keep = is_boundary(h) ? next(h) : twin(prev(h));
    remove_side(h);
    remove_side(o);
    delete_edge(edge(h));
    delete_vertex(v0);
    set_halfedge(v0, Halfedge());
    set_halfedge(v1, keep);
    adjust_outgoing_halfedge(v1);
}

// ---- vertex removal --------------------------------------------------------------------------

void SurfaceMesh::remove_vertex(Vertex v, std::span<const std::array<std::uint32_t, 3>> tris) {
    const std::string where = "remove_vertex(" + vstr(v.idx()) + "): ";
    DYNMESH_CHECK(is_valid(v) && !is_deleted(v), where + "vertex is deleted or invalid");
    DYNMESH_CHECK(!is_boundary(v), where + "vertex is on the boundary or isolated");
    std::vector<Halfedge> spokes;
    for (Halfedge h : outgoing_halfedges(v)) spokes.push_back(h);
    const std::size_t k = spokes.size();
    DYNMESH_CHECK(k >= 3, where + "valence below 3");
    std::vector<Vertex> link(k);
    for (std::size_t i = 0; i < k; ++i) link[i] = to_vertex(spokes[i]);
    DYNMESH_CHECK(is_simple_cycle(link), where + "link is not a simple cycle");
    // A valence-3 vertex whose link triangle is already a face (a tetrahedron) cannot go:
    // the two copies of that triangle would enclose nothing.
    DYNMESH_CHECK(k > 3 || opposite_vertex(twin(next(spokes[0]))) != link[2],
                  where + "the link triangle is already a face (tetrahedron)");
    DYNMESH_CHECK(tris.size() == k - 2, where + "expected " + std::to_string(k - 2) +
                                             " triangles for a link of " + std::to_string(k) +
                                             " vertices, got " + std::to_string(tris.size()));
    // Validate: directed edges used once; polygon sides i->i+1 exactly once; diagonals in
    // both directions; no diagonal already an edge of the mesh.
    std::unordered_map<std::uint64_t, int, PairHash> used;
    for (const auto& t : tris) {
        for (int j = 0; j < 3; ++j) {
            const std::uint32_t a = t[j], b = t[(j + 1) % 3];
            DYNMESH_CHECK(a < k && b < k && a != b, where + "bad triangle index");
            DYNMESH_CHECK(++used[key(a, b)] == 1, where + "a directed edge is used twice");
        }
    }
    for (std::uint32_t i = 0; i < k; ++i) {
        const std::uint32_t j = static_cast<std::uint32_t>((i + 1) % k);
        DYNMESH_CHECK(used.count(key(i, j)) == 1 && used.count(key(j, i)) == 0,
                      where + "triangles do not cover link side " + std::to_string(i));
    }
    // The diagonals in increasing (a, b) order: the first bad one named does not depend on
    // the hash table's order.
    std::vector<std::uint64_t> diagonals;
    for (const auto& [kk, cnt] : used) {
        const auto a = static_cast<std::uint32_t>(kk >> 32), b = static_cast<std::uint32_t>(kk);
        if ((b != (a + 1) % k) && (a != (b + 1) % k)) diagonals.push_back(kk);
    }
    std::sort(diagonals.begin(), diagonals.end());
    for (const std::uint64_t kk : diagonals) {
        const auto a = static_cast<std::uint32_t>(kk >> 32), b = static_cast<std::uint32_t>(kk);
        DYNMESH_CHECK(used.count(key(b, a)) == 1, where + "diagonal used in one direction only");
        DYNMESH_CHECK(!find_halfedge(link[a], link[b]).is_valid(),
                      where + "diagonal (" + vstr(link[a].idx()) + ", " + vstr(link[b].idx()) +
                          ") is already an edge of the mesh");
    }

    // Polygon sides g_i = next(spoke_i): link[i] -> link[i+1].
    std::unordered_map<std::uint64_t, Halfedge, PairHash> he;
    for (std::uint32_t i = 0; i < k; ++i)
        he[key(i, static_cast<std::uint32_t>((i + 1) % k))] = next(spokes[i]);
    // Delete the star.
    std::vector<Face> free_faces;
    for (std::size_t i = 0; i < k; ++i) {
        free_faces.push_back(face(spokes[i]));
        const Vertex w = link[i];
        if (halfedge(w) == twin(spokes[i])) set_halfedge(w, he[key(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>((i + 1) % k))]);
        delete_edge(edge(spokes[i]));
    }
    delete_vertex(v);
    set_halfedge(v, Halfedge());
    // Reuse k - 2 of the k faces, delete the other two.
    for (std::size_t i = k - 2; i < k; ++i) delete_face(free_faces[i]);
    for (std::size_t t = 0; t < tris.size(); ++t) {
        std::array<Halfedge, 3> hs;
        for (int j = 0; j < 3; ++j) {
            const std::uint32_t a = tris[t][j], b = tris[t][(j + 1) % 3];
            auto it = he.find(key(a, b));
            if (it == he.end()) {
                const Halfedge nh = new_edge(link[a], link[b]);
                he[key(a, b)] = nh;
                he[key(b, a)] = twin(nh);
                hs[j] = nh;
            } else {
                hs[j] = it->second;
            }
        }
        link_triangle(hs[0], hs[1], hs[2], free_faces[t]);
    }
}

bool SurfaceMesh::remove_vertex(Vertex v) {
    if (!is_valid(v) || is_deleted(v) || is_boundary(v)) return false;
    const std::vector<Vertex> link = neighbors(v);
    const std::size_t k = link.size();
    if (k < 3) return false;
    if (!is_simple_cycle(link)) return false;
    if (k == 3 && opposite_vertex(find_halfedge(link[1], link[0])) == link[2]) return false;
    // Plane: through v, normal = area-weighted normal of the star.
    Vec3 n{};
    for (std::size_t i = 0; i < k; ++i)
        n += triangle_normal_raw(position(v), position(link[i]), position(link[(i + 1) % k]));
    n = normalized(n);
    if (sqnorm(n) == 0) return false;
    Vec3 u = std::abs(n.x) < 0.9 ? cross(n, Vec3{1, 0, 0}) : cross(n, Vec3{0, 1, 0});
    u = normalized(u);
    const Vec3 w = cross(n, u);
    std::vector<Point2> poly(k);
    for (std::size_t i = 0; i < k; ++i) {
        const Vec3 d = position(link[i]) - position(v);
        poly[i] = {dot(d, u), dot(d, w)};
    }
    // Ear clipping, best ear first.
    std::vector<std::uint32_t> ring(k);
    std::iota(ring.begin(), ring.end(), 0u);
    std::vector<std::array<std::uint32_t, 3>> tris;
    auto strictly_inside = [&](const Point2& a, const Point2& b, const Point2& c, const Point2& p) {
        return cross(b - a, p - a) > 0 && cross(c - b, p - b) > 0 && cross(a - c, p - c) > 0;
    };
    while (ring.size() > 3) {
        const std::size_t m = ring.size();
        double best = -1;
        std::size_t best_i = m;
        for (std::size_t i = 0; i < m; ++i) {
            const std::uint32_t ia = ring[(i + m - 1) % m], ib = ring[i], ic = ring[(i + 1) % m];
            const Point2 &a = poly[ia], &b = poly[ib], &c = poly[ic];
            if (cross(b - a, c - a) <= 0) continue;  // reflex or flat
            bool empty = true;
            for (std::uint32_t j : ring)
                if (j != ia && j != ib && j != ic && strictly_inside(a, b, c, poly[j])) {
                    empty = false;
                    break;
                }
            if (!empty) continue;
            if (find_halfedge(link[ia], link[ic]).is_valid()) continue;
            const double q = min_angle(a, b, c);
            if (q > best) {
                best = q;
                best_i = i;
            }
        }
        if (best_i == m) return false;
        tris.push_back({ring[(best_i + m - 1) % m], ring[best_i], ring[(best_i + 1) % m]});
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(best_i));
    }
    tris.push_back({ring[0], ring[1], ring[2]});
    if (cross(poly[ring[1]] - poly[ring[0]], poly[ring[2]] - poly[ring[0]]) <= 0) return false;
    remove_vertex(v, tris);
    return true;
}

// ---- garbage collection ----------------------------------------------------------------------

void SurfaceMesh::garbage_collection() {
    if (!has_garbage()) return;
    std::vector<std::uint32_t> vkeep, ekeep, fkeep;
    for (std::uint32_t i = 0; i < vertices_size(); ++i)
        if (!vdeleted_[i]) vkeep.push_back(i);
    for (std::uint32_t i = 0; i < edges_size(); ++i)
        if (!edeleted_[i]) ekeep.push_back(i);
    for (std::uint32_t i = 0; i < faces_size(); ++i)
        if (!fdeleted_[i]) fkeep.push_back(i);
    reindex(vkeep, ekeep, fkeep);
}

void SurfaceMesh::permute(std::span<const std::uint32_t> vertex_order,
                          std::span<const std::uint32_t> edge_order,
                          std::span<const std::uint32_t> face_order) {
    DYNMESH_CHECK(!has_garbage(), "SurfaceMesh::permute: the mesh has deleted elements");
    auto check = [](std::span<const std::uint32_t> order, std::size_t n, const char* what) {
        DYNMESH_CHECK(order.size() == n, std::string("SurfaceMesh::permute: the ") + what +
                                             " order has " + std::to_string(order.size()) +
                                             " entries, expected " + std::to_string(n));
        std::vector<char> seen(n, 0);
        for (std::uint32_t i : order) {
            DYNMESH_CHECK(i < n && !seen[i], std::string("SurfaceMesh::permute: the ") + what +
                                                 " order is not a permutation");
            seen[i] = 1;
        }
    };
    check(vertex_order, vertices_size(), "vertex");
    check(edge_order, edges_size(), "edge");
    check(face_order, faces_size(), "face");
    reindex(vertex_order, edge_order, face_order);
}

void SurfaceMesh::reindex(std::span<const std::uint32_t> vkeep, std::span<const std::uint32_t> ekeep,
                          std::span<const std::uint32_t> fkeep) {
    face_log_.clear();  // its indices are gone
    // Old index -> new index; elements left out of the lists map to kInvalid.
    auto inverse = [](std::span<const std::uint32_t> keep, std::size_t n) {
        std::vector<std::uint32_t> map(n, kInvalid);
        for (std::uint32_t i = 0; i < keep.size(); ++i) map[keep[i]] = i;
        return map;
    };
    const std::vector<std::uint32_t> vmap = inverse(vkeep, vertices_size()),
                                     emap = inverse(ekeep, edges_size()),
                                     fmap = inverse(fkeep, faces_size());
    auto hmap = [&](std::uint32_t h) {
        return h == kInvalid ? kInvalid : ((emap[h >> 1] << 1) | (h & 1u));
    };
    auto mapv = [&](std::uint32_t v) { return v == kInvalid ? kInvalid : vmap[v]; };
    auto mapf = [&](std::uint32_t f) { return f == kInvalid ? kInvalid : fmap[f]; };

    // Scatter each array through its map into one reused buffer (read in order, write each
    // element at its new place), then swap: one fresh allocation instead of one per array.
    std::vector<std::uint32_t> buf;
    auto scatter = [&buf](std::vector<std::uint32_t>& arr, std::size_t new_size, auto&& where, auto&& value) {
        buf.resize(new_size);
        for (std::uint32_t i = 0; i < arr.size(); ++i) {
            const std::uint32_t k = where(i);
            if (k != kInvalid) buf[k] = value(arr[i]);
        }
        arr.swap(buf);
    };
    auto at_v = [&](std::uint32_t i) { return vmap[i]; };
    auto at_h = [&](std::uint32_t h) { return emap[h >> 1] == kInvalid ? kInvalid : hmap(h); };
    auto at_f = [&](std::uint32_t i) { return fmap[i]; };
    scatter(vhalfedge_, vkeep.size(), at_v, hmap);
    scatter(hto_, 2 * ekeep.size(), at_h, mapv);
    scatter(hnext_, 2 * ekeep.size(), at_h, hmap);
    scatter(hprev_, 2 * ekeep.size(), at_h, hmap);
    scatter(hface_, 2 * ekeep.size(), at_h, mapf);
    scatter(fhalfedge_, fkeep.size(), at_f, hmap);
    std::vector<Point3> pos(vkeep.size());
    for (std::uint32_t i = 0; i < vmap.size(); ++i)
        if (vmap[i] != kInvalid) pos[vmap[i]] = positions_[i];
    positions_.swap(pos);
    vdeleted_.assign(vkeep.size(), false);
    edeleted_.assign(ekeep.size(), false);
    fdeleted_.assign(fkeep.size(), false);
    n_deleted_vertices_ = n_deleted_edges_ = n_deleted_faces_ = 0;
    vprops_.compact(vkeep);
    eprops_.compact(ekeep);
    fprops_.compact(fkeep);
}

// ---- surgery -----------------------------------------------------------------------------------

std::vector<Face> SurfaceMesh::replace_faces(std::span<const Face> remove,
                                             std::span<const std::array<Vertex, 3>> add) {
    const std::string where = "replace_faces: ";
    std::unordered_set<std::uint32_t> removed;
    for (Face f : remove) {
        if (!is_valid(f) || is_deleted(f))
            throw InvalidInput(where + "face " + std::to_string(f.idx()) + " is invalid or deleted");
        removed.insert(f.idx());
    }
    // The halfedges of removed triangles whose twin stays: the hole's slots, by (from, to).
    std::unordered_map<std::uint64_t, std::uint32_t, PairHash> slots;
    std::vector<Edge> dead_edges;
    std::unordered_set<std::uint32_t> touched;
    for (std::uint32_t fi : removed) {
        const Halfedge h0 = halfedge(Face(fi));
        Halfedge h = h0;
        do {
            touched.insert(to_vertex(h).idx());
            const Face other = face(twin(h));
            if (other.is_valid() && removed.count(other.idx()) == 0)
                slots.emplace(key(from_vertex(h).idx(), to_vertex(h).idx()), h.idx());
            else if (h.idx() < twin(h).idx() || !other.is_valid())
                dead_edges.push_back(edge(h));
            h = next(h);
        } while (h != h0);
    }
    // Every directed edge of the added triangles: a slot, or a new edge used both ways.
    std::unordered_map<std::uint64_t, int, PairHash> fresh;  // (a, b) -> uses
    std::size_t slots_used = 0;
    for (std::size_t t = 0; t < add.size(); ++t) {
        const auto& tri = add[t];
        const std::string at = where + "triangle " + std::to_string(t);
        for (Vertex v : tri)
            if (!is_valid(v) || is_deleted(v))
                throw InvalidInput(at + " uses an invalid or deleted vertex " + std::to_string(v.idx()));
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
            throw InvalidInput(at + " repeats a vertex");
        for (int i = 0; i < 3; ++i) {
            const Vertex a = tri[i], b = tri[(i + 1) % 3];
            const std::uint64_t k = key(a.idx(), b.idx());
            if (slots.count(k)) {
                if (fresh.count(k)) throw InvalidInput(at + " uses a boundary edge twice");
                fresh[k] = 1;
                ++slots_used;
                continue;
            }
            if (fresh.count(k))
                throw InvalidInput(at + ": edge (" + std::to_string(a.idx()) + ", " +
                                   std::to_string(b.idx()) + ") is used twice in one direction");
            const Halfedge existing = find_halfedge(a, b);
            if (existing.is_valid() && face(existing).is_valid() && removed.count(face(existing).idx()) == 0)
                throw InvalidInput(at + ": edge (" + std::to_string(a.idx()) + ", " +
                                   std::to_string(b.idx()) + ") is already used in this direction by a kept triangle");
            fresh[k] = 1;
        }
    }
    if (slots_used != slots.size())
        throw InvalidInput(where + std::to_string(slots.size() - slots_used) +
                           " edges of the hole's boundary are left open");
    // An open edge: a new directed edge whose reverse no added triangle uses. The smallest
    // is named, whatever the hash table's order.
    std::uint64_t open = std::numeric_limits<std::uint64_t>::max();
    for (const auto& [k, uses] : fresh) {
        (void)uses;
        if (slots.count(k)) continue;
        const std::uint64_t back = (k << 32) | (k >> 32);
        if (!fresh.count(back)) open = std::min(open, k);
    }
    if (open != std::numeric_limits<std::uint64_t>::max())
        throw InvalidInput(where + "the added triangles leave edge (" + std::to_string(open >> 32) + ", " +
                           std::to_string(open & 0xffffffffu) + ") open");

    // Apply: delete, then link the new triangles into the slots and new edges.
    for (std::uint32_t fi : removed) delete_face(Face(fi));
    for (Edge e : dead_edges) delete_edge(e);
    for (const auto& [k, h] : slots) hface_[h] = kInvalid;
    std::unordered_map<std::uint64_t, std::uint32_t, PairHash> half;  // (a, b) -> halfedge a -> b
    for (const auto& [k, h] : slots) half.emplace(k, h);
    std::vector<Face> faces;
    faces.reserve(add.size());
    std::unordered_set<std::uint32_t> in_new;
    for (const auto& tri : add) {
        std::array<Halfedge, 3> hs;
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t a = tri[i].idx(), b = tri[(i + 1) % 3].idx();
            auto it = half.find(key(a, b));
            if (it == half.end()) {
                const Halfedge h = new_edge(Vertex(a), Vertex(b));
                half.emplace(key(a, b), h.idx());
                half.emplace(key(b, a), twin(h).idx());
                hs[i] = h;
            } else {
                hs[i] = Halfedge(it->second);
            }
            in_new.insert(a);
        }
        const Face f = new_face();
        link_triangle(hs[0], hs[1], hs[2], f);
        for (int i = 0; i < 3; ++i) set_halfedge(tri[i], hs[i]);
        faces.push_back(f);
    }
    for (std::uint32_t v : touched)
        if (in_new.count(v) == 0) {
            // A vertex of the removed region that no added triangle uses: every triangle around
            // it was removed (a kept one would have left a slot at it).
            vhalfedge_[v] = kInvalid;
            delete_vertex(Vertex(v));
        }
    return faces;
}

}  // namespace dynmesh
