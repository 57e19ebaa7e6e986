#include "dynmesh/quadtree/dyn_offcenter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <queue>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/format.hpp"
#include "dynmesh/quadtree/live_mesh.hpp"
#include "dynmesh/system/hash.hpp"

namespace dynmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using VertexHandle = Delaunay::Vertex_handle;

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();

inline bool lex_less(const Vec2& a, const Vec2& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
}
inline Kernel::Point_2 to_cgal(const Vec2& p) { return {p.x, p.y}; }

/// Position of an evaluation or a vertex in the static execution order (file comment of the
/// header). phase 0: inputs and box corners; 1: round-0 midpoints (seq = box side); 2: the
/// creation evaluations of initial vertices; 3: rounds (cls, round) with the canonical key of
/// the pair (pcls, len2, lo, hi, side); seq −1 is the processing itself, seq 0, 1 its outputs.
struct Stamp {
    int phase = 0;
    int cls = 0, round = 0;
    int pcls = 0;
    double len2 = 0;
    double lox = 0, loy = 0, hix = 0, hiy = 0;
    int side = 0;
    int seq = 0;

    [[nodiscard]] auto tie() const {
        return std::tie(phase, cls, round, pcls, len2, lox, loy, hix, hiy, side, seq);
    }
    bool operator<(const Stamp& o) const { return tie() < o.tie(); }
    bool operator==(const Stamp& o) const { return tie() == o.tie(); }
    /// A coarse, order-preserving rank (phase, class, round) for pruning the point index.
    [[nodiscard]] std::int64_t rank() const {
        return (static_cast<std::int64_t>(phase) << 40) +
               (static_cast<std::int64_t>(cls + 4096) << 20) + round;
    }
};

/// "Vertices stamped before `bound`" (or up to and including it).
struct Visibility {
    Stamp bound;
    bool inclusive = false;
    [[nodiscard]] bool sees(const Stamp& s) const { return inclusive ? !(bound < s) : s < bound; }
};

enum class VKind : std::uint8_t { Input, Corner, Mid0, Apex, Circum, Midpoint };
enum class Outcome : std::uint8_t { None, NotLoose, Inserted, Stuck, Split };

/// A disc-registration cell of the read-region index: level L has cells of size W·2^-L.
struct CellKey {
    int level = 0;
    std::int64_t ix = 0, iy = 0;
    bool operator==(const CellKey&) const = default;
};
struct CellKeyHash {
    std::size_t operator()(const CellKey& k) const noexcept {
        return static_cast<std::size_t>(hash_ints(k.level, k.ix, k.iy));
    }
};

/// Event codes: creation evaluation of vertex id (bit 31 clear) or processing id (bit 31 set).
constexpr std::uint32_t kProcBit = 0x80000000u;

struct Disc {
    Vec2 c{};
    double r = 0;  // +inf: the whole plane
};

/// A bound on the rounding error of a centre computed near c (a few ulps of its coordinates):
/// read-region discs are enlarged by it, because their radius can be as small as a few ulps
/// when the pair is (points a few ulps apart far from the origin).
double centre_error(const Vec2& c) { return 8 * kEps * (std::fabs(c.x) + std::fabs(c.y)); }

/// The circle through p, q whose centre lies at signed offset h (length units) from the
/// midpoint along the unit normal n, enlarged for floating-point safety (relative error of
/// h and r, rounding of the midpoint m and of the centre).
Disc pencil_disc(const Vec2& m, const Vec2& n, double h, double len) {
    if (!std::isfinite(h) || std::fabs(h) > 1e6 * len) return {m, kInf};
    const double r = std::sqrt(h * h + 0.25 * len * len);
    const Vec2 c = m + h * n;
    return {c, r * (1 + 1e-9) + 1e-9 * len + centre_error(m) + centre_error(c)};
}

}  // namespace

// ------------------------------------------------------------------------------------------
struct DynOffCenterMesh2::Impl {
    Impl(const QuadtreeOptions<2>& domain, const OffCenterOptions& opts)
        : tree(domain), options(opts), kernel(domain.origin, domain.width, opts) {
        origin = domain.origin;
        width = domain.width;
    }

    // ---- records --------------------------------------------------------------------------
    struct Vertex {
        Vec2 pos{};
        Stamp stamp;
        VKind kind = VKind::Input;
        bool alive = false;
        bool queued = false;
        int box_side = -1;                 // midpoints: the box side they lie on
        std::vector<std::uint32_t> cands;  // candidates created by this vertex
        std::vector<CellKey> regs;         // read-region cells of the creation evaluation
        bool global = false;               // creation read region unbounded
        VertexHandle vh;                   // in dt (null until applied)
        std::uint32_t live = kNone;        // its vertex in the live mesh (with vh)
        DynQuadtree<2>::GridPoint grid{};  // inputs: snapped coordinates (output order)
        bool touched = false;              // in touched_ (this update)
    };
    struct Cand {
        Vec2 lo{}, hi{};
        int side = 0;  // 0: ccw of lo -> hi, 1: cw
        int pcls = 0;
        double len2 = 0;
        std::uint32_t creator = kNone;
        std::uint32_t first = kNone;
        bool alive = false;
    };
    struct Proc {
        std::uint32_t cand = kNone;
        Stamp time;
        Outcome outcome = Outcome::None;
        bool apex = false;
        std::vector<std::uint32_t> outputs;
        bool retry = false;
        std::uint32_t next = kNone;
        bool alive = false;
        bool queued = false;
        std::vector<CellKey> regs;
        bool global = false;
        std::vector<std::tuple<int, double, double>> intervals;
    };
    struct Reg {
        std::uint32_t code;
        double cx, cy, r2;
    };

    // ---- point index: a bucket PR-quadtree over Ω holding every vertex ----------------------
    struct PEntry {
        Vec2 pos;
        std::int64_t rank;
        std::uint32_t id;
    };
    struct PNode {
        double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
        std::array<std::int32_t, 4> child{-1, -1, -1, -1};
        std::vector<PEntry> pts;  // leaves: the vertices with their position and stamp rank
        std::int64_t min_rank = std::numeric_limits<std::int64_t>::max();
        std::uint32_t count = 0;
        int depth = 0;
        bool leaf = true;
    };

    DynQuadtree<2> tree;
    OffCenterOptions options;
    detail::OffCenterKernel kernel;
    Vec2 origin{};
    double width = 1;

    std::vector<Vertex> verts;
    std::vector<Cand> cands;
    std::vector<Proc> procs;
    std::vector<std::uint32_t> free_verts, free_cands, free_procs;
    std::vector<std::uint32_t> dead_verts, dead_cands, dead_procs;  // freed after the update
    std::map<DynQuadtree<2>::GridPoint, std::uint32_t> inputs;      // grid -> vertex

    // Two point indices: [0] initial vertices (inputs, corners, round-0 midpoints), [1] Steiner
    // points of the rounds, so that queries of the initial phase never meet Steiner points.
    std::array<std::vector<PNode>, 2> pidx;
    std::array<std::vector<std::int32_t>, 2> pfree;
    [[nodiscard]] static int index_of(const Stamp& s) { return s.phase < 2 ? 0 : 1; }
    [[nodiscard]] static int indices_for(const Visibility& vis) {
        return vis.bound.phase >= 3 ? 2 : 1;
    }

    std::unordered_map<CellKey, std::vector<Reg>, CellKeyHash> grid;
    std::array<std::size_t, 72> level_count{};  // entries per level (level + 8)
    std::unordered_set<std::uint32_t> globals;
    std::array<std::map<std::pair<double, double>, std::vector<std::uint32_t>>, 4> intervals;
    std::array<std::vector<std::uint32_t>, 4> side_mids;  // boundary midpoint vertices per side
    std::array<std::size_t, 4> enc0{};                    // inputs in each side's diametral disc
    std::array<std::uint32_t, 4> mid0{kNone, kNone, kNone, kNone};

    struct QItem {
        Stamp time;
        std::uint32_t code;
        bool operator>(const QItem& o) const { return o.time < time; }
    };
    std::priority_queue<QItem, std::vector<QItem>, std::greater<>> queue;
    std::vector<std::uint32_t> touched;

    Delaunay dt;
    std::size_t alive_count = 0, input_count = 0;
    std::size_t boundary_count = 0, apex_count = 0, circum_count = 0, stuck_count = 0;
    std::map<std::pair<int, int>, std::size_t> rounds;

    OffCenterUpdateReport report;

    // ---- live mesh (live_mesh.hpp): the canonical triangles, updated locally ----------------
    /// A live-mesh vertex: its triangulation vertex, its output-order key (inputs first by
    /// snapped coordinates, then Steiner points lexicographically: mesh()'s index order) and
    /// the cells it belongs to.
    struct LiveVertex {
        VertexHandle vh;
        bool steiner = false;
        DynQuadtree<2>::GridPoint grid{};
        Vec2 pos{};
        std::vector<std::uint32_t> cells;
    };
    /// A Delaunay cell (a maximal set of triangles with one empty circumcircle): its boundary
    /// ring of live vertices, counter-clockwise from its smallest vertex, and the block of
    /// its fan triangles (ring[0], ring[j], ring[j + 1]).
    struct LiveCell {
        std::vector<std::uint32_t> ring;
        std::uint32_t first = 0;
    };
    LiveMesh<2> live;
    MeshDelta<2> change;
    std::vector<LiveVertex> lverts;
    std::vector<LiveCell> lcells;
    std::vector<std::uint32_t> free_lcells;
    std::vector<std::uint32_t> dirty;  // live vertices whose cells may have changed
    std::set<std::pair<int, int>> visited_rounds;
    Stamp last_time;

    // ---- setup ------------------------------------------------------------------------------
    void init_box() {
        PNode root;
        root.x0 = origin.x;
        root.y0 = origin.y;
        root.x1 = kernel.hi.x;
        root.y1 = kernel.hi.y;
        pidx[0].push_back(root);
        pidx[1].push_back(root);
        for (const Vec2& c :
             {origin, Vec2{kernel.hi.x, origin.y}, kernel.hi, Vec2{origin.x, kernel.hi.y}})
            (void)add_vertex(c, Stamp{}, VKind::Corner, -1);
    }

    // ---- point index ------------------------------------------------------------------------
    [[nodiscard]] int child_of(const PNode& n, const Vec2& p) const {
        const double mx = 0.5 * (n.x0 + n.x1), my = 0.5 * (n.y0 + n.y1);
        return (p.x >= mx ? 1 : 0) + (p.y >= my ? 2 : 0);
    }
    std::int32_t new_pnode(int w) {
        auto& pnodes = pidx[static_cast<std::size_t>(w)];
        auto& free_pnodes = pfree[static_cast<std::size_t>(w)];
        if (!free_pnodes.empty()) {
            const std::int32_t k = free_pnodes.back();
            free_pnodes.pop_back();
            pnodes[static_cast<std::size_t>(k)] = PNode{};
            return k;
        }
        pnodes.emplace_back();
        return static_cast<std::int32_t>(pnodes.size() - 1);
    }
    void split_pnode(int w, std::int32_t k) {
        std::array<std::int32_t, 4> ch{};
        for (int c = 0; c < 4; ++c) ch[static_cast<std::size_t>(c)] = new_pnode(w);
        auto& pnodes = pidx[static_cast<std::size_t>(w)];
        PNode& n = pnodes[static_cast<std::size_t>(k)];
        const double mx = 0.5 * (n.x0 + n.x1), my = 0.5 * (n.y0 + n.y1);
        for (int c = 0; c < 4; ++c) {
            PNode& cn = pnodes[static_cast<std::size_t>(ch[static_cast<std::size_t>(c)])];
            cn.x0 = (c & 1) ? mx : n.x0;
            cn.x1 = (c & 1) ? n.x1 : mx;
            cn.y0 = (c & 2) ? my : n.y0;
            cn.y1 = (c & 2) ? n.y1 : my;
            cn.depth = n.depth + 1;
        }
        for (const PEntry& e : n.pts) {
            PNode& cn =
                pnodes[static_cast<std::size_t>(ch[static_cast<std::size_t>(child_of(n, e.pos))])];
            cn.pts.push_back(e);
            ++cn.count;
            cn.min_rank = std::min(cn.min_rank, e.rank);
        }
        n.pts.clear();
        n.pts.shrink_to_fit();
        n.leaf = false;
        n.child = ch;
    }
    void index_insert(std::uint32_t id) {
        const Vec2 p = verts[id].pos;
        const std::int64_t rk = verts[id].stamp.rank();
        const int w = index_of(verts[id].stamp);
        auto& pnodes = pidx[static_cast<std::size_t>(w)];
        std::int32_t k = 0;
        for (;;) {
            PNode& n = pnodes[static_cast<std::size_t>(k)];
            ++n.count;
            n.min_rank = std::min(n.min_rank, rk);
            if (n.leaf) {
                n.pts.push_back({p, rk, id});
                if (n.pts.size() > 8 && n.depth < 56) split_pnode(w, k);
                return;
            }
            k = n.child[static_cast<std::size_t>(child_of(n, p))];
        }
    }
    void collect(int w, std::int32_t k, std::vector<PEntry>& out) {
        auto& pnodes = pidx[static_cast<std::size_t>(w)];
        auto& free_pnodes = pfree[static_cast<std::size_t>(w)];
        PNode& n = pnodes[static_cast<std::size_t>(k)];
        if (n.leaf) {
            out.insert(out.end(), n.pts.begin(), n.pts.end());
        } else {
            for (std::int32_t c : n.child) {
                collect(w, c, out);
                free_pnodes.push_back(c);
            }
        }
    }
    void index_erase(std::uint32_t id) {
        const Vec2 p = verts[id].pos;
        const int w = index_of(verts[id].stamp);
        auto& pnodes = pidx[static_cast<std::size_t>(w)];
        auto& free_pnodes = pfree[static_cast<std::size_t>(w)];
        std::vector<std::int32_t> path;
        std::int32_t k = 0;
        for (;;) {
            path.push_back(k);
            const PNode& n = pnodes[static_cast<std::size_t>(k)];
            if (n.leaf) break;
            k = n.child[static_cast<std::size_t>(child_of(n, p))];
        }
        auto& pts = pnodes[static_cast<std::size_t>(k)].pts;
        const auto it =
            std::find_if(pts.begin(), pts.end(), [&](const PEntry& e) { return e.id == id; });
        if (it == pts.end())
            throw InternalError("DynOffCenterMesh2: vertex missing from the index");
        pts.erase(it);
        for (auto pi = path.rbegin(); pi != path.rend(); ++pi) {
            PNode& n = pnodes[static_cast<std::size_t>(*pi)];
            --n.count;
            if (!n.leaf && n.count <= 4) {
                std::vector<PEntry> all;
                for (std::int32_t c : n.child) {
                    collect(w, c, all);
                    free_pnodes.push_back(c);
                }
                PNode& m = pnodes[static_cast<std::size_t>(*pi)];
                m.leaf = true;
                m.child = {-1, -1, -1, -1};
                m.pts = std::move(all);
            }
            PNode& m = pnodes[static_cast<std::size_t>(*pi)];
            m.min_rank = std::numeric_limits<std::int64_t>::max();
            if (m.leaf) {
                for (const PEntry& e : m.pts) m.min_rank = std::min(m.min_rank, e.rank);
            } else {
                for (std::int32_t c : m.child)
                    m.min_rank = std::min(m.min_rank, pnodes[static_cast<std::size_t>(c)].min_rank);
            }
        }
    }

    /// Visibility of an index entry: the coarse rank decides unless it ties.
    [[nodiscard]] bool sees(const Visibility& vis, const PEntry& e) const {
        const std::int64_t r = vis.bound.rank();
        if (e.rank != r) return e.rank < r;
        return vis.sees(verts[e.id].stamp);
    }

    /// The visible vertex at exactly p, or kNone.
    [[nodiscard]] std::uint32_t find_exact(const Vec2& p, const Visibility& vis) const {
        for (int w = 0; w < indices_for(vis); ++w) {
            const auto& pnodes = pidx[static_cast<std::size_t>(w)];
            std::int32_t k = 0;
            for (;;) {
                const PNode& n = pnodes[static_cast<std::size_t>(k)];
                if (n.leaf) {
                    for (const PEntry& e : n.pts)
                        if (e.pos == p && sees(vis, e)) return e.id;
                    break;
                }
                k = n.child[static_cast<std::size_t>(child_of(n, p))];
            }
        }
        return kNone;
    }

    /// The visible vertex nearest to v (exact distance comparisons), other than v itself.
    [[nodiscard]] std::uint32_t nearest(const Vec2& v, const Visibility& vis) {
        ++report.queries;
        const std::int64_t rank = vis.bound.rank();
        using Item = std::pair<double, std::int32_t>;
        std::priority_queue<Item, std::vector<Item>, std::greater<>> heap;
        auto box_d2 = [&](const PNode& n) {
            const double dx = std::max({n.x0 - v.x, 0.0, v.x - n.x1});
            const double dy = std::max({n.y0 - v.y, 0.0, v.y - n.y1});
            return dx * dx + dy * dy;
        };
        std::uint32_t best = kNone;
        double best_d2 = kInf;
        const auto cmp = Kernel().compare_distance_2_object();
        for (int w = 0; w < indices_for(vis); ++w) {
            const auto& pnodes = pidx[static_cast<std::size_t>(w)];
            heap = {};
            heap.push({0.0, 0});
            while (!heap.empty()) {
                const auto [lb, k] = heap.top();
                heap.pop();
                if (lb > best_d2 * (1 + 1e-9)) break;
                const PNode& n = pnodes[static_cast<std::size_t>(k)];
                if (n.min_rank > rank) continue;
                if (n.leaf) {
                    for (const PEntry& e : n.pts) {
                        if (e.pos == v || !sees(vis, e)) continue;
                        if (best == kNone) {
                            best = e.id;
                        } else {
                            const auto c =
                                cmp(to_cgal(v), to_cgal(e.pos), to_cgal(verts[best].pos));
                            if (c == CGAL::SMALLER ||
                                (c == CGAL::EQUAL && lex_less(e.pos, verts[best].pos)))
                                best = e.id;
                        }
                        const Vec2 d = verts[best].pos - v;
                        best_d2 = dot(d, d);
                    }
                } else {
                    for (std::int32_t c : n.child) {
                        const PNode& cn = pnodes[static_cast<std::size_t>(c)];
                        if (cn.count == 0 || cn.min_rank > rank) continue;
                        const double d2 = box_d2(cn);
                        if (d2 <= best_d2 * (1 + 1e-9)) heap.push({d2, c});
                    }
                }
            }
        }
        return best;
    }

    using HeapItem = std::pair<double, std::int32_t>;
    std::vector<HeapItem> heap_;

    struct Neighbour {
        bool blocked = false;             // a visible vertex on the open segment
        std::vector<std::uint32_t> ties;  // the minimisers (exactly cocircular)
        double h = kInf;                  // their offset (floating point)
        double h_err = 0;                 // a bound on the rounding error of h
    };

    /// The visible vertices x strictly on side `cw` of a -> b minimising the circle through
    /// a, b, x (i.e. the offset h of its centre along the unit normal towards that side), among
    /// those with h ≤ hmax (with a relative tolerance). Exact incircle comparisons; `ties` holds
    /// every exact minimiser.
    Neighbour neighbour(const Vec2& a, const Vec2& b, bool cw, const Visibility& vis, double hmax,
                        bool stop_on_block) {
        ++report.queries;
        Neighbour res;
        const std::int64_t rank = vis.bound.rank();
        const Vec2 d = b - a;
        const double len2 = dot(d, d), len = std::sqrt(len2);
        const Vec2 perp = cw ? Vec2{d.y, -d.x} : Vec2{-d.y, d.x};
        const Vec2 n{perp.x / len, perp.y / len};
        const Vec2 hm{0.5 * d.x, 0.5 * d.y};  // the midpoint relative to a (exact)
        const Sign want = cw ? Sign::Negative : Sign::Positive;
        // Candidates beyond it cannot be minimisers: the current best's offset plus its
        // rounding error (or hmax), with a relative margin.
        auto limit = [&]() {
            const double h = std::min(hmax, res.h + res.h_err);
            return std::isfinite(h) ? h + 1e-9 * (std::fabs(h) + len) : h;
        };
        auto lower = [&](const PNode& nd) {
            // Lower bound of h over the node box (on the wanted side), in coordinates relative
            // to a: box corners minus a are single roundings, hm = d/2 is exact, so every
            // error below is relative to distances from the pair, never to |coordinates|.
            const double bx0 = (nd.x0 - a.x) - hm.x, bx1 = (nd.x1 - a.x) - hm.x;
            const double by0 = (nd.y0 - a.y) - hm.y, by1 = (nd.y1 - a.y) - hm.y;
            const double dx = std::max({bx0, 0.0, -bx1});
            const double dy = std::max({by0, 0.0, -by1});
            const double dmin2 = dx * dx + dy * dy;
            double vmin = kInf, vmax = -kInf;
            for (const Vec2 c : {Vec2{bx0, by0}, Vec2{bx1, by0}, Vec2{bx0, by1}, Vec2{bx1, by1}}) {
                const double v = dot(c, n);
                vmin = std::min(vmin, v);
                vmax = std::max(vmax, v);
            }
            const double reach = std::max({std::fabs(bx0), std::fabs(bx1), std::fabs(by0),
                                           std::fabs(by1)}) + len;
            const double eps = 1e-14 * reach;
            if (vmax + eps <= 0) return kInf;  // entirely on the other side
            const double num = dmin2 - 0.25 * len2;
            const double num_err = 16 * kEps * (reach * reach + len2);
            double lb;
            if (num >= 0) {
                lb = (num - num_err) / (2 * (vmax + eps));
            } else {
                const double vm = vmin - eps;
                lb = vm > 0 ? (num - num_err) / (2 * vm) : -kInf;
            }
            return std::isfinite(lb) ? lb - 1e-9 * (std::fabs(lb) + len) : lb;
        };
        auto& heap = heap_;  // reused storage, a min-heap on the lower bound
        const auto later = [](const HeapItem& x, const HeapItem& y) { return x.first > y.first; };
        const bool vertical = a.x == b.x;
        for (int wi = 0; wi < indices_for(vis); ++wi) {
            const auto& pnodes = pidx[static_cast<std::size_t>(wi)];
            heap.clear();
            heap.push_back({lower(pnodes[0]), 0});
            while (!heap.empty()) {
                std::pop_heap(heap.begin(), heap.end(), later);
                const auto [lb, k] = heap.back();
                heap.pop_back();
                if (lb > limit()) break;
                const PNode& nd = pnodes[static_cast<std::size_t>(k)];
                if (nd.leaf) {
                    for (const PEntry& e : nd.pts) {
                        if (e.pos == a || e.pos == b || !sees(vis, e)) continue;
                        const std::uint32_t id = e.id;
                        const Sign o = orient2d(a, b, e.pos);
                        if (o == Sign::Zero) {
                            const bool between = vertical ? (std::min(a.y, b.y) < e.pos.y &&
                                                             e.pos.y < std::max(a.y, b.y))
                                                          : (std::min(a.x, b.x) < e.pos.x &&
                                                             e.pos.x < std::max(a.x, b.x));
                            if (between) {
                                res.blocked = true;
                                if (stop_on_block) return res;
                            }
                            continue;
                        }
                        if (o != want) continue;
                        // Relative to the midpoint through a: e.pos − a is one rounding, so the
                        // error of x is relative to |x|, not to the coordinates (points a few
                        // ulps apart far from the origin).
                        const Vec2 x = (e.pos - a) - hm;
                        // x is exactly on the wanted side, so its distance to the line is > 0
                        // even where rounding says otherwise (nearly collinear x).
                        const double v = std::max(dot(x, n), std::numeric_limits<double>::min());
                        const double xx = dot(x, x);
                        const double h = (xx - 0.25 * len2) / (2 * v);
                        // Skip only when h surely exceeds the limit: the error of the
                        // numerator, and the relative error of v (large for x nearly on the
                        // line of the pair).
                        const double h_err =
                            16 * kEps *
                            ((xx + len2) / (2 * v) + std::fabs(h) * (1 + std::sqrt(xx) / v));
                        if (h - h_err > limit()) continue;
                        if (res.ties.empty()) {
                            res.ties = {id};
                            res.h = h;
                            res.h_err = h_err;
                            continue;
                        }
                        const Vec2& bp = verts[res.ties.front()].pos;
                        const Sign s = cw ? incircle(b, a, bp, e.pos) : incircle(a, b, bp, e.pos);
                        if (s == Sign::Positive) {
                            res.ties = {id};
                            res.h = h;
                            res.h_err = h_err;
                        } else if (s == Sign::Zero) {
                            res.ties.push_back(id);
                            res.h_err = std::max(res.h_err, h_err);
                        }
                    }
                } else {
                    for (std::int32_t c : nd.child) {
                        const PNode& cn = pnodes[static_cast<std::size_t>(c)];
                        if (cn.count == 0 || cn.min_rank > rank) continue;
                        const double l = lower(cn);
                        if (l <= limit()) {
                            heap.push_back({l, c});
                            std::push_heap(heap.begin(), heap.end(), later);
                        }
                    }
                }
            }
        }
        return res;
    }

    [[nodiscard]] std::uint32_t lex_min(const std::vector<std::uint32_t>& ids) const {
        std::uint32_t best = ids.front();
        for (std::uint32_t id : ids)
            if (lex_less(verts[id].pos, verts[best].pos)) best = id;
        return best;
    }

    // ---- read-region index ------------------------------------------------------------------
    [[nodiscard]] std::int64_t cell_coord(double x, double o, int level) const {
        return static_cast<std::int64_t>(std::floor(std::ldexp((x - o) / width, level)));
    }
    void register_disc(std::uint32_t code, const Disc& disc, std::vector<CellKey>& regs,
                       bool& global) {
        if (!std::isfinite(disc.r) || disc.r > 4 * width) {
            if (!global) globals.insert(code);
            global = true;
            return;
        }
        int level = 60;
        if (disc.r > 0) {
            int e = 0;
            (void)std::frexp(width / (2 * disc.r), &e);  // W/(2r) in [2^(e-1), 2^e)
            level = std::clamp(e - 1, -8, 60);
        }
        const std::int64_t x0 = cell_coord(disc.c.x - disc.r, origin.x, level);
        const std::int64_t x1 = cell_coord(disc.c.x + disc.r, origin.x, level);
        const std::int64_t y0 = cell_coord(disc.c.y - disc.r, origin.y, level);
        const std::int64_t y1 = cell_coord(disc.c.y + disc.r, origin.y, level);
        for (std::int64_t ix = x0; ix <= x1; ++ix)
            for (std::int64_t iy = y0; iy <= y1; ++iy) {
                const CellKey key{level, ix, iy};
                grid[key].push_back({code, disc.c.x, disc.c.y, disc.r * disc.r});
                ++level_count[static_cast<std::size_t>(level + 8)];
                if (std::find(regs.begin(), regs.end(), key) == regs.end()) regs.push_back(key);
            }
    }
    void deregister(std::uint32_t code, std::vector<CellKey>& regs, bool& global) {
        for (const CellKey& key : regs) {
            const auto it = grid.find(key);
            if (it == grid.end()) continue;
            auto& v = it->second;
            const auto end =
                std::remove_if(v.begin(), v.end(), [&](const Reg& r) { return r.code == code; });
            level_count[static_cast<std::size_t>(key.level + 8)] -=
                static_cast<std::size_t>(v.end() - end);
            v.erase(end, v.end());
            if (v.empty()) grid.erase(it);
        }
        regs.clear();
        if (global) globals.erase(code);
        global = false;
    }
    void deregister_intervals(std::uint32_t pid) {
        for (const auto& [side, a, b] : procs[pid].intervals) {
            auto& m = intervals[static_cast<std::size_t>(side)];
            const auto it = m.find({a, b});
            if (it == m.end()) continue;
            auto& v = it->second;
            v.erase(std::remove(v.begin(), v.end(), pid), v.end());
            if (v.empty()) m.erase(it);
        }
        procs[pid].intervals.clear();
    }

    [[nodiscard]] Stamp event_time(std::uint32_t code) const {
        if (code & kProcBit) return procs[code & ~kProcBit].time;
        const Vertex& v = verts[code];
        if (v.stamp.phase >= 2) return v.stamp;
        Stamp s;
        s.phase = 2;
        s.lox = v.pos.x;
        s.loy = v.pos.y;
        return s;
    }
    void enqueue(std::uint32_t code) {
        if (code & kProcBit) {
            Proc& p = procs[code & ~kProcBit];
            if (!p.alive || p.queued) return;
            p.queued = true;
            queue.push({p.time, code});
        } else {
            Vertex& v = verts[code];
            if (!v.alive || v.queued) return;
            v.queued = true;
            queue.push({event_time(code), code});
        }
    }
    /// A vertex stamped `stamp` appeared or vanished at p: re-run every later evaluation whose
    /// read region contains p.
    void delta(const Vec2& p, const Stamp& stamp) {
        for (int level = -8; level <= 60; ++level) {
            if (level_count[static_cast<std::size_t>(level + 8)] == 0) continue;
            const auto it = grid.find(
                {level, cell_coord(p.x, origin.x, level), cell_coord(p.y, origin.y, level)});
            if (it == grid.end()) continue;
            for (const Reg& r : it->second) {
                const double dx = p.x - r.cx, dy = p.y - r.cy;
                if (dx * dx + dy * dy <= r.r2 && stamp < event_time(r.code)) enqueue(r.code);
            }
        }
        for (std::uint32_t code : globals)
            if (stamp < event_time(code)) enqueue(code);
    }
    void delta_interval(int side, double c, const Stamp& stamp) {
        for (const auto& [ab, ids] : intervals[static_cast<std::size_t>(side)])
            if (ab.first <= c && c <= ab.second)
                for (std::uint32_t pid : ids)
                    if (stamp < procs[pid].time) enqueue(pid | kProcBit);
    }

    // ---- vertices, candidates, processings --------------------------------------------------
    std::uint32_t add_vertex(const Vec2& pos, const Stamp& stamp, VKind kind, int box_side) {
        std::uint32_t id;
        if (!free_verts.empty()) {
            id = free_verts.back();
            free_verts.pop_back();
            verts[id] = Vertex{};
        } else {
            id = static_cast<std::uint32_t>(verts.size());
            if (id >= kProcBit) throw InternalError("DynOffCenterMesh2: too many vertices");
            verts.emplace_back();
        }
        Vertex& v = verts[id];
        v.pos = pos;
        v.stamp = stamp;
        v.kind = kind;
        v.alive = true;
        v.box_side = box_side;
        index_insert(id);
        ++alive_count;
        switch (kind) {
            case VKind::Input:
                ++input_count;
                break;
            case VKind::Apex:
                ++apex_count;
                break;
            case VKind::Circum:
                ++circum_count;
                break;
            default:
                ++boundary_count;
                break;
        }
        if (alive_count - input_count > options.max_steiner)
            throw InternalError("DynOffCenterMesh2: more than " +
                                std::to_string(options.max_steiner) +
                                " Steiner points (rho = " + std::to_string(options.rho) + ")");
        touch(id);
        if (box_side >= 0) {
            side_mids[static_cast<std::size_t>(box_side)].push_back(id);
            delta_interval(box_side, detail::OffCenterKernel::along(box_side, pos), stamp);
        }
        delta(pos, stamp);
        enqueue(id);
        return id;
    }
    void touch(std::uint32_t id) {
        if (!verts[id].touched) {
            verts[id].touched = true;
            touched.push_back(id);
        }
    }
    void delete_vertex(std::uint32_t id) {
        Vertex& v = verts[id];
        if (!v.alive) return;
        v.alive = false;
        v.queued = false;
        index_erase(id);
        --alive_count;
        switch (v.kind) {
            case VKind::Input:
                --input_count;
                break;
            case VKind::Apex:
                --apex_count;
                break;
            case VKind::Circum:
                --circum_count;
                break;
            default:
                --boundary_count;
                break;
        }
        touch(id);
        if (v.box_side >= 0) {
            auto& sm = side_mids[static_cast<std::size_t>(v.box_side)];
            sm.erase(std::remove(sm.begin(), sm.end(), id), sm.end());
            delta_interval(v.box_side, detail::OffCenterKernel::along(v.box_side, v.pos), v.stamp);
        }
        delta(v.pos, v.stamp);
        deregister(id, verts[id].regs, verts[id].global);
        const std::vector<std::uint32_t> cs = std::move(verts[id].cands);
        verts[id].cands.clear();
        for (std::uint32_t c : cs) delete_cand(c);
        dead_verts.push_back(id);
    }
    std::uint32_t new_proc(std::uint32_t cid, int cls, int round) {
        std::uint32_t id;
        if (!free_procs.empty()) {
            id = free_procs.back();
            free_procs.pop_back();
            procs[id] = Proc{};
        } else {
            id = static_cast<std::uint32_t>(procs.size());
            procs.emplace_back();
        }
        const Cand& c = cands[cid];
        Proc& p = procs[id];
        p.cand = cid;
        p.time = Stamp{3, cls, round, c.pcls, c.len2, c.lo.x, c.lo.y, c.hi.x, c.hi.y, c.side, -1};
        p.alive = true;
        ++rounds[{cls, round}];
        enqueue(id | kProcBit);
        return id;
    }
    void delete_proc(std::uint32_t pid) {
        while (pid != kNone) {
            Proc& p = procs[pid];
            if (!p.alive) return;
            p.alive = false;
            p.queued = false;
            deregister(pid | kProcBit, p.regs, p.global);
            deregister_intervals(pid);
            const auto it = rounds.find({p.time.cls, p.time.round});
            if (--it->second == 0) rounds.erase(it);
            if (p.outcome == Outcome::Stuck) --stuck_count;
            const std::vector<std::uint32_t> outs = std::move(procs[pid].outputs);
            procs[pid].outputs.clear();
            for (std::uint32_t v : outs) delete_vertex(v);
            dead_procs.push_back(pid);
            pid = procs[pid].next;
        }
    }
    std::uint32_t new_cand(const Vec2& lo, const Vec2& hi, int side, std::uint32_t creator) {
        std::uint32_t id;
        if (!free_cands.empty()) {
            id = free_cands.back();
            free_cands.pop_back();
            cands[id] = Cand{};
        } else {
            id = static_cast<std::uint32_t>(cands.size());
            cands.emplace_back();
        }
        Cand& c = cands[id];
        c.lo = lo;
        c.hi = hi;
        c.side = side;
        c.len2 = dot(hi - lo, hi - lo);
        c.pcls = kernel.size_class(c.len2);
        c.creator = creator;
        c.alive = true;
        const Stamp& s = verts[creator].stamp;
        int cls = c.pcls, round = 1;
        if (s.phase == 3 && c.pcls <= s.cls) {
            cls = s.cls;
            round = s.round + 1;
        }
        const std::uint32_t first = new_proc(id, cls, round);
        cands[id].first = first;
        return id;
    }
    void delete_cand(std::uint32_t cid) {
        Cand& c = cands[cid];
        if (!c.alive) return;
        c.alive = false;
        const std::uint32_t first = c.first;
        dead_cands.push_back(cid);
        delete_proc(first);
    }

    // ---- the evaluations --------------------------------------------------------------------
    /// True when lo, hi lie on one box side and `cw` is its outer side (static: opposite vertex
    /// infinite).
    [[nodiscard]] bool hull_side(const Vec2& lo, const Vec2& hi, bool cw) const {
        const Vec2 d = hi - lo;
        const Vec2 nv = cw ? Vec2{d.y, -d.x} : Vec2{-d.y, d.x};
        if (lo.x == hi.x && lo.x == origin.x && nv.x < 0) return true;
        if (lo.x == hi.x && lo.x == kernel.hi.x && nv.x > 0) return true;
        if (lo.y == hi.y && lo.y == origin.y && nv.y < 0) return true;
        if (lo.y == hi.y && lo.y == kernel.hi.y && nv.y > 0) return true;
        return false;
    }

    /// The loose test of spec §5.1 as offcenter_mesh() makes it (canonical opposite vertices,
    /// closed leaf with slack), answered by two time-filtered searches. Appends its read
    /// region to `discs` when given.
    bool loose(const Vec2& lo, const Vec2& hi, int side, const Visibility& vis,
               std::vector<Disc>* discs) {
        const bool cw = side == 1;
        if (hull_side(lo, hi, cw)) return false;
        const Vec2 d = hi - lo;
        const double len2 = dot(d, d), len = std::sqrt(len2);
        const double delta = kernel.slack(len2);
        const double as = kernel.theta - delta - 1e-7;
        const double hs = as > 0 ? 0.5 * len * std::cos(as) / std::sin(as) : kInf;
        const double ao = std::numbers::pi - kernel.theta - delta - 1e-7;
        const double ho = ao > 0 ? 0.5 * len * std::cos(ao) / std::sin(ao) : kInf;
        if (discs) {
            const Vec2 perp = cw ? Vec2{d.y, -d.x} : Vec2{-d.y, d.x};
            const Vec2 n{perp.x / len, perp.y / len};
            const Vec2 m{0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y)};
            discs->push_back(pencil_disc(m, n, hs, len));
            discs->push_back(pencil_disc(m, Vec2{-n.x, -n.y}, ho, len));
        }
        const Neighbour t = neighbour(lo, hi, cw, vis, hs, true);
        if (t.blocked) return false;
        if (!t.ties.empty() && kernel.in_leaf_same_side(verts[lex_min(t.ties)].pos, lo, hi, len2))
            return false;
        const Neighbour u = neighbour(lo, hi, !cw, vis, ho, true);
        if (u.blocked) return false;
        if (!u.ties.empty() && kernel.in_leaf_other_side(verts[lex_min(u.ties)].pos, lo, hi, len2))
            return false;
        return true;
    }

    /// Creation evaluation of vertex vid: its Delaunay star among the vertices stamped up to
    /// it (gift wrapping with best-first searches), then the loose (pair, side) candidates whose
    /// later endpoint it is.
    void run_create(std::uint32_t vid) {
        const Vec2 v = verts[vid].pos;
        const Stamp vstamp = verts[vid].stamp;
        Visibility vis;
        if (vstamp.phase < 2) {
            vis.bound.phase = 2;  // every initial vertex
        } else {
            vis.bound = vstamp;
            vis.inclusive = true;
        }
        deregister(vid, verts[vid].regs, verts[vid].global);
        std::vector<Disc> discs;
        // Star neighbours in walk order, each with the exact minimiser sets on the left (L) and
        // on the right (R) of v -> w: the vertices of the Delaunay cells on either side.
        struct Spoke {
            std::uint32_t w;
            std::vector<std::uint32_t> left, right;
            bool has_left = false, has_right = false;
        };
        std::vector<Spoke> star;
        const std::uint32_t w0 = nearest(v, vis);
        if (w0 == kNone) throw InternalError("DynOffCenterMesh2: a vertex without neighbours");
        star.push_back({w0, {}, {}, false, false});
        auto circum = [&](const Vec2& a, const Vec2& b, const Vec2& c) {
            const Vec2 ba = b - a, ca = c - a;
            const double den = 2 * cross(ba, ca);
            const double bl = dot(ba, ba), cl = dot(ca, ca);
            const Vec2 o{a.x + (ca.y * bl - ba.y * cl) / den, a.y + (ba.x * cl - ca.x * bl) / den};
            const double r = std::max({norm(a - o), norm(b - o), norm(c - o)});
            // The centre's rounding error grows like r·ε·|ba|·|ca|/|den| for flat triangles:
            // enlarge by a multiple of it so the disc surely covers the true circumdisc.
            const double cond = std::sqrt(bl * cl) / std::fabs(den);
            const double grow = 1e-9 + 256 * std::numeric_limits<double>::epsilon() * cond;
            const bool ok = std::isfinite(r) && std::isfinite(cond) && grow < 1e-3;
            discs.push_back(
                {o, ok ? r * (1 + grow) + 1e-9 * std::sqrt(bl) + centre_error(o) : kInf});
        };
        bool closed = false;
        for (int dir = 0; dir < 2 && !closed; ++dir) {
            const bool cw = dir == 1;
            std::size_t cur = 0;  // index in star
            for (std::size_t guard = 0;; ++guard) {
                if (guard > 100000)
                    throw InternalError("DynOffCenterMesh2: star walk does not close");
                const std::uint32_t cid = star[cur].w;
                // Outside the box there is nothing (and the search could not prune along
                // the box side).
                Neighbour nb = hull_side(v, verts[cid].pos, cw)
                                   ? Neighbour{}
                                   : neighbour(v, verts[cid].pos, cw, vis, kInf, false);
                (cw ? star[cur].has_right : star[cur].has_left) = true;
                (cw ? star[cur].right : star[cur].left) = nb.ties;
                if (nb.ties.empty()) break;
                // The tie farthest around v: the next non-degenerate star edge. The cell's
                // other vertices (cid and the remaining ties) lie on its far side.
                std::uint32_t y = nb.ties.front();
                for (std::uint32_t z : nb.ties) {
                    const Sign o = orient2d(v, verts[y].pos, verts[z].pos);
                    if (o == (cw ? Sign::Negative : Sign::Positive)) y = z;
                }
                circum(v, verts[cid].pos, verts[y].pos);
                std::vector<std::uint32_t> back{cid};
                for (std::uint32_t z : nb.ties)
                    if (z != y) back.push_back(z);
                if (verts[y].pos == verts[w0].pos) {
                    (cw ? star[0].left : star[0].right) = std::move(back);
                    (cw ? star[0].has_left : star[0].has_right) = true;
                    closed = true;
                    break;
                }
                Spoke sp{y, {}, {}, false, false};
                (cw ? sp.left : sp.right) = std::move(back);
                (cw ? sp.has_left : sp.has_right) = true;
                star.push_back(std::move(sp));
                cur = star.size() - 1;
            }
        }
        for (const Disc& d : discs) register_disc(vid, d, verts[vid].regs, verts[vid].global);

        // Candidates: star edges to earlier vertices, loose on a side (the loose test of
        // loose(), answered from the cells found by the walk).
        std::vector<std::tuple<Vec2, Vec2, int>> want;
        for (const Spoke& sp : star) {
            const Vertex& wv = verts[sp.w];
            const bool earlier = wv.stamp < vstamp || (wv.stamp == vstamp && lex_less(wv.pos, v));
            if (!earlier) continue;
            if (!sp.has_left || !sp.has_right)
                throw InternalError("DynOffCenterMesh2: incomplete star");
            const bool v_lo = lex_less(v, wv.pos);
            const Vec2 lo = v_lo ? v : wv.pos;
            const Vec2 hi = v_lo ? wv.pos : v;
            const double len2 = dot(hi - lo, hi - lo);
            for (int side = 0; side < 2; ++side) {
                // ccw of lo -> hi is the left of v -> w when v is lo.
                const bool same_is_left = (side == 0) == v_lo;
                const auto& same_set = same_is_left ? sp.left : sp.right;
                const auto& other_set = same_is_left ? sp.right : sp.left;
                if (same_set.empty() || hull_side(lo, hi, side == 1)) continue;
                if (kernel.in_leaf_same_side(verts[lex_min(same_set)].pos, lo, hi, len2)) continue;
                if (!other_set.empty() &&
                    kernel.in_leaf_other_side(verts[lex_min(other_set)].pos, lo, hi, len2))
                    continue;
                want.emplace_back(lo, hi, side);
            }
        }
        auto same = [](const Cand& c, const std::tuple<Vec2, Vec2, int>& w) {
            return c.lo == std::get<0>(w) && c.hi == std::get<1>(w) && c.side == std::get<2>(w);
        };
        std::vector<std::uint32_t> keep;
        const std::vector<std::uint32_t> old = verts[vid].cands;
        for (std::uint32_t c : old) {
            const bool wanted = std::any_of(want.begin(), want.end(),
                                            [&](const auto& w) { return same(cands[c], w); });
            if (wanted)
                keep.push_back(c);
            else
                delete_cand(c);
        }
        for (const auto& w : want) {
            const bool have = std::any_of(keep.begin(), keep.end(),
                                          [&](std::uint32_t c) { return same(cands[c], w); });
            if (!have)
                keep.push_back(new_cand(std::get<0>(w), std::get<1>(w), std::get<2>(w), vid));
        }
        verts[vid].cands = std::move(keep);
    }

    /// The box subsegment of `side` containing coordinate c at time vis (static subsegment_at).
    [[nodiscard]] std::pair<double, double> subsegment_at(int side, double c,
                                                          const Visibility& vis) const {
        const double s0 = side % 2 == 0 ? origin.x : origin.y;
        const double s1 = side % 2 == 0 ? kernel.hi.x : kernel.hi.y;
        std::vector<double> coords{s0, s1};
        for (std::uint32_t id : side_mids[static_cast<std::size_t>(side)])
            if (vis.sees(verts[id].stamp))
                coords.push_back(detail::OffCenterKernel::along(side, verts[id].pos));
        std::sort(coords.begin(), coords.end());
        coords.erase(std::unique(coords.begin(), coords.end()), coords.end());
        auto it = std::upper_bound(coords.begin(), coords.end(), c);
        if (it == coords.end()) --it;
        if (it == coords.begin()) ++it;
        return {*std::prev(it), *it};
    }
    [[nodiscard]] bool encroaches(int side, std::pair<double, double> s, const Vec2& p) const {
        return CGAL::side_of_bounded_circle(to_cgal(kernel.side_point(side, s.first)),
                                            to_cgal(kernel.side_point(side, s.second)),
                                            to_cgal(p)) != CGAL::ON_UNBOUNDED_SIDE;
    }

    /// Processing evaluation pid (offcenter_mesh's process()).
    void run_proc(std::uint32_t pid) {
        const std::uint32_t code = pid | kProcBit;
        deregister(code, procs[pid].regs, procs[pid].global);
        deregister_intervals(pid);
        const Cand c = cands[procs[pid].cand];
        const Stamp time = procs[pid].time;
        const bool cw = c.side == 1;
        const Visibility vis{time, false};
        std::vector<Disc> discs;
        Outcome out = Outcome::NotLoose;
        bool apex = false;
        Vec2 r{};
        std::vector<std::pair<int, double>> splits;  // (side, midpoint coordinate)
        std::vector<std::tuple<int, double, double>> ivals;
        if (loose(c.lo, c.hi, c.side, vis, &discs)) {
            const Vec2 d = c.hi - c.lo;
            const double len = std::sqrt(c.len2);
            const Vec2 perp = cw ? Vec2{d.y, -d.x} : Vec2{-d.y, d.x};
            const Vec2 n{perp.x / len, perp.y / len};
            const Vec2 m{0.5 * (c.lo.x + c.hi.x), 0.5 * (c.lo.y + c.hi.y)};
            const double hmax =
                kernel.use_offcenters ? kernel.sigma_apex * len * (1 + 1e-9) + 1e-9 * len : kInf;
            const Neighbour t = neighbour(c.lo, c.hi, cw, vis, hmax, false);
            if (!t.ties.empty()) {
                r = kernel.offcenter(c.lo, c.hi, cw, c.len2, verts[lex_min(t.ties)].pos, apex);
                discs.push_back(pencil_disc(m, n, std::min(t.h, hmax), len));
            } else {
                if (!kernel.use_offcenters)
                    throw InternalError("DynOffCenterMesh2: a loose pair without opposite vertex");
                r = kernel.apex_point(c.lo, c.hi, cw);
                apex = true;
                discs.push_back(pencil_disc(m, n, hmax, len));
            }
            discs.push_back({r, 0.0});
            // Boundary (static process()).
            std::vector<std::pair<int, std::pair<double, double>>> hit;
            for (int side = 0; side < 4; ++side) {
                const auto s = subsegment_at(side, detail::OffCenterKernel::along(side, r), vis);
                ivals.emplace_back(side, s.first, s.second);
                if (encroaches(side, s, r)) hit.push_back({side, s});
            }
            const Vec2 bo = origin, bh = kernel.hi;
            const bool inside = bo.x < r.x && r.x < bh.x && bo.y < r.y && r.y < bh.y;
            if (hit.empty() && !inside) {
                const Vec2 cl{std::clamp(r.x, bo.x, bh.x), std::clamp(r.y, bo.y, bh.y)};
                const int side = cl.y == bo.y ? 0 : cl.x == bh.x ? 1 : cl.y == bh.y ? 2 : 3;
                const auto s = subsegment_at(side, detail::OffCenterKernel::along(side, cl), vis);
                ivals.emplace_back(side, s.first, s.second);
                hit.push_back({side, s});
            }
            if (!hit.empty()) {
                out = Outcome::Split;
                for (const auto& [side, s] : hit) {
                    const double mid = s.first + 0.5 * (s.second - s.first);
                    if (!(s.first < mid && mid < s.second))
                        throw InternalError("DynOffCenterMesh2: box subsegment too short to split");
                    splits.emplace_back(side, mid);
                }
            } else {
                out = find_exact(r, vis) != kNone ? Outcome::Stuck : Outcome::Inserted;
            }
        }
        Proc& p = procs[pid];
        for (const Disc& dsc : discs) register_disc(code, dsc, p.regs, p.global);
        for (const auto& [side, a, b] : ivals) {
            intervals[static_cast<std::size_t>(side)][{a, b}].push_back(pid);
            p.intervals.emplace_back(side, a, b);
        }
        // Compare with the recorded outcome.
        bool same = p.outcome == out;
        if (same && out == Outcome::Inserted)
            same = p.apex == apex && verts[p.outputs.front()].pos == r;
        if (same && out == Outcome::Split) {
            same = p.outputs.size() == splits.size();
            for (std::size_t j = 0; same && j < splits.size(); ++j)
                same =
                    verts[p.outputs[j]].pos == kernel.side_point(splits[j].first, splits[j].second);
        }
        if (!same) {
            if (p.outcome == Outcome::Stuck) --stuck_count;
            const std::vector<std::uint32_t> outs = std::move(procs[pid].outputs);
            procs[pid].outputs.clear();
            for (std::uint32_t v : outs) delete_vertex(v);
            procs[pid].outcome = out;
            procs[pid].apex = apex;
            if (out == Outcome::Stuck) ++stuck_count;
            Stamp os = time;
            if (out == Outcome::Inserted) {
                os.seq = 0;
                const std::uint32_t v = add_vertex(r, os, apex ? VKind::Apex : VKind::Circum, -1);
                procs[pid].outputs.push_back(v);
            } else if (out == Outcome::Split) {
                for (std::size_t j = 0; j < splits.size(); ++j) {
                    os.seq = static_cast<int>(j);
                    const std::uint32_t v =
                        add_vertex(kernel.side_point(splits[j].first, splits[j].second), os,
                                   VKind::Midpoint, splits[j].first);
                    procs[pid].outputs.push_back(v);
                }
            }
        }
        bool retry = out == Outcome::Split;
        if (out == Outcome::Inserted) {
            Stamp os = time;
            os.seq = 0;
            retry = loose(c.lo, c.hi, c.side, Visibility{os, true}, nullptr);
        }
        procs[pid].retry = retry;
        if (retry && procs[pid].next == kNone) {
            const std::uint32_t nx = new_proc(procs[pid].cand, time.cls, time.round + 1);
            procs[pid].next = nx;
        } else if (!retry && procs[pid].next != kNone) {
            const std::uint32_t nx = procs[pid].next;
            procs[pid].next = kNone;
            delete_proc(nx);
        }
    }

    // ---- updates ----------------------------------------------------------------------------
    void begin_update() {
        report = OffCenterUpdateReport{};
        visited_rounds.clear();
        touched.clear();
        last_time = Stamp{};
    }
    void propagate() {
        while (!queue.empty()) {
            const QItem item = queue.top();
            queue.pop();
            if (item.code & kProcBit) {
                Proc& p = procs[item.code & ~kProcBit];
                if (!p.alive || !p.queued) continue;
                p.queued = false;
                visited_rounds.insert({p.time.cls, p.time.round});
                ++report.evaluations;
                run_proc(item.code & ~kProcBit);
            } else {
                Vertex& v = verts[item.code];
                if (!v.alive || !v.queued) continue;
                v.queued = false;
                ++report.evaluations;
                run_create(item.code);
            }
            if (item.time < last_time)
                throw InternalError("DynOffCenterMesh2: timeline order violated");
            last_time = item.time;
        }
    }
    /// Applies the symmetric difference of the vertex sets to the triangulation and the live
    /// mesh, and frees the records of deleted objects.
    void end_update() {
        change.clear();
        std::map<std::pair<double, double>, std::uint32_t>
            removed;  // position -> dead vertex with a handle
        std::vector<std::uint32_t> added;
        for (std::uint32_t id : touched) {
            Vertex& v = verts[id];
            v.touched = false;
            if (!v.alive && v.vh != VertexHandle())
                removed[{v.pos.x, v.pos.y}] = id;
            else if (v.alive && v.vh == VertexHandle())
                added.push_back(id);
        }
        for (std::uint32_t id : added) {
            Vertex& v = verts[id];
            const auto it = removed.find({v.pos.x, v.pos.y});
            if (it != removed.end()) {
                Vertex& old = verts[it->second];
                v.vh = old.vh;
                v.vh->info() = id;
                v.live = old.live;
                old.vh = VertexHandle();
                old.live = kNone;
                if ((old.kind == VKind::Input) != (v.kind == VKind::Input)) {
                    if (v.kind == VKind::Input)
                        ++report.steiner_removed;
                    else
                        ++report.steiner_added;
                    set_live_key(v.live, v);  // its place in the output order changed
                    dirty.push_back(v.live);
                }
                removed.erase(it);
                continue;
            }
            v.vh = dt.insert(to_cgal(v.pos));
            v.vh->info() = id;
            v.live = live.add_vertex(v.pos, change);
            if (v.live >= lverts.size()) lverts.resize(v.live + 1);
            lverts[v.live].vh = v.vh;
            set_live_key(v.live, v);
            mark_star(v.vh);
            if (v.kind != VKind::Input) ++report.steiner_added;
        }
        for (const auto& [pos, id] : removed) {
            Vertex& v = verts[id];
            mark_star(v.vh);
            dt.remove(v.vh);
            v.vh = VertexHandle();
            live.remove_vertex(v.live, change);
            lverts[v.live].vh = VertexHandle();
            v.live = kNone;
            if (v.kind != VKind::Input) ++report.steiner_removed;
        }
        update_cells();
        live.recycle();
        report.simplices_added = change.added_simplices.size();
        report.simplices_removed = change.removed_simplices.size();
        report.rounds_visited = visited_rounds.size();
        for (std::uint32_t id : dead_verts) {
            verts[id].cands.clear();
            verts[id].regs.clear();
            free_verts.push_back(id);
        }
        for (std::uint32_t id : dead_cands) free_cands.push_back(id);
        for (std::uint32_t id : dead_procs) {
            procs[id].outputs.clear();
            procs[id].regs.clear();
            free_procs.push_back(id);
        }
        dead_verts.clear();
        dead_cands.clear();
        dead_procs.clear();
        touched.clear();
    }

    void set_live_key(std::uint32_t lid, const Vertex& v) {
        LiveVertex& l = lverts[lid];
        l.steiner = v.kind != VKind::Input;
        l.grid = v.grid;
        l.pos = v.pos;
    }
    /// mesh()'s index order: inputs by snapped coordinates, then Steiner points by (x, y).
    [[nodiscard]] bool out_less(std::uint32_t a, std::uint32_t b) const {
        const LiveVertex &x = lverts[a], &y = lverts[b];
        if (x.steiner != y.steiner) return !x.steiner;
        return x.steiner ? lex_less(x.pos, y.pos) : x.grid < y.grid;
    }
    /// A vertex and its current neighbours: every Delaunay cell created or destroyed by
    /// inserting or removing it has one of them as a vertex.
    void mark_star(VertexHandle h) {
        dirty.push_back(verts[h->info()].live);
        const auto first = dt.incident_vertices(h);
        if (first == nullptr) return;
        auto w = first;
        do {
            if (!dt.is_infinite(w)) dirty.push_back(verts[w->info()].live);
        } while (++w != first);
    }
    /// The Delaunay cell of face f (faces joined across edges whose four points are
    /// cocircular, exact test, as detail::finish_offcenter_mesh), as its canonical ring; marks
    /// its faces in `seen`.
    std::vector<std::uint32_t> cell_ring(Delaunay::Face_handle f,
                                         std::unordered_set<const void*>& seen) const {
        std::vector<Delaunay::Face_handle> faces{f}, stack{f};
        seen.insert(&*f);
        const auto pos = [](VertexHandle h) { return Vec2{h->point().x(), h->point().y()}; };
        while (!stack.empty()) {
            const auto g = stack.back();
            stack.pop_back();
            for (int k = 0; k < 3; ++k) {
                const auto h = g->neighbor(k);
                if (dt.is_infinite(h) || seen.contains(&*h)) continue;
                const VertexHandle far = h->vertex(dt.mirror_index(g, k));
                if (incircle(pos(g->vertex(0)), pos(g->vertex(1)), pos(g->vertex(2)), pos(far)) !=
                    Sign::Zero)
                    continue;
                seen.insert(&*h);
                faces.push_back(h);
                stack.push_back(h);
            }
        }
        std::vector<std::uint32_t> ring;
        if (faces.size() == 1) {
            for (int k = 0; k < 3; ++k) ring.push_back(verts[f->vertex(k)->info()].live);
        } else {
            std::unordered_set<const void*> in_cell;
            for (const auto& g : faces) in_cell.insert(&*g);
            std::unordered_map<std::uint32_t, std::uint32_t> next;  // boundary edges, ccw
            for (const auto& g : faces)
                for (int k = 0; k < 3; ++k) {
                    if (!dt.is_infinite(g->neighbor(k)) && in_cell.contains(&*g->neighbor(k)))
                        continue;
                    next[verts[g->vertex(Delaunay::ccw(k))->info()].live] =
                        verts[g->vertex(Delaunay::cw(k))->info()].live;
                }
            std::uint32_t v = next.begin()->first;
            do {
                ring.push_back(v);
                v = next.at(v);
            } while (v != ring.front() && ring.size() <= next.size());
            if (ring.size() != next.size())
                throw InternalError("DynOffCenterMesh2: a degenerate Delaunay cell is not a polygon");
        }
        const auto lowest = std::min_element(
            ring.begin(), ring.end(), [&](std::uint32_t a, std::uint32_t b) { return out_less(a, b); });
        std::rotate(ring.begin(), lowest, ring.end());  // keeps the ccw order
        return ring;
    }
    void add_cell(std::vector<std::uint32_t> ring) {
        std::vector<LiveMesh<2>::Simplex> fan;
        for (std::size_t j = 1; j + 1 < ring.size(); ++j) fan.push_back({ring[0], ring[j], ring[j + 1]});
        std::uint32_t c;
        if (!free_lcells.empty()) {
            c = free_lcells.back();
            free_lcells.pop_back();
        } else {
            c = static_cast<std::uint32_t>(lcells.size());
            lcells.emplace_back();
        }
        lcells[c].first = live.add_simplices(fan, change);
        for (std::uint32_t v : ring) lverts[v].cells.push_back(c);
        lcells[c].ring = std::move(ring);
    }
    void remove_cell(std::uint32_t c) {
        LiveCell& cell = lcells[c];
        live.remove_simplices(cell.first, static_cast<std::uint32_t>(cell.ring.size() - 2), change);
        for (std::uint32_t v : cell.ring) {
            auto& cs = lverts[v].cells;
            cs.erase(std::find(cs.begin(), cs.end(), c));
        }
        cell.ring.clear();
        free_lcells.push_back(c);
    }
    /// Replaces the cells of the dirty vertices that changed by the current ones.
    void update_cells() {
        std::sort(dirty.begin(), dirty.end());
        dirty.erase(std::unique(dirty.begin(), dirty.end()), dirty.end());
        std::map<std::vector<std::uint32_t>, std::uint32_t> old;  // ring -> cell
        for (std::uint32_t v : dirty)
            for (std::uint32_t c : lverts[v].cells) old.emplace(lcells[c].ring, c);
        std::vector<std::uint32_t> kept;
        std::vector<std::vector<std::uint32_t>> fresh;
        std::unordered_set<const void*> seen;
        for (std::uint32_t v : dirty) {
            if (!live.has_vertex(v)) continue;
            const auto first = dt.incident_faces(lverts[v].vh);
            auto f = first;
            do {
                if (dt.is_infinite(f) || seen.contains(&*f)) continue;
                std::vector<std::uint32_t> ring = cell_ring(f, seen);
                if (const auto it = old.find(ring); it != old.end())
                    kept.push_back(it->second);
                else
                    fresh.push_back(std::move(ring));
            } while (++f != first);
        }
        std::sort(kept.begin(), kept.end());
        for (const auto& [ring, c] : old)
            if (!std::binary_search(kept.begin(), kept.end(), c)) remove_cell(c);
        for (auto& ring : fresh) add_cell(std::move(ring));
        dirty.clear();
    }

    /// Round 0 (static round_zero()): side k is split at its midpoint iff an input lies in its
    /// closed diametral disc (only whole sides can be encroached by middle-third points).
    void update_round0(const Vec2& p, int sign) {
        for (int side = 0; side < 4; ++side) {
            const double s0 = side % 2 == 0 ? origin.x : origin.y;
            const double s1 = side % 2 == 0 ? kernel.hi.x : kernel.hi.y;
            if (!encroaches(side, {s0, s1}, p)) continue;
            auto& cnt = enc0[static_cast<std::size_t>(side)];
            cnt = sign > 0 ? cnt + 1 : cnt - 1;
            auto& mid = mid0[static_cast<std::size_t>(side)];
            if (cnt > 0 && mid == kNone) {
                Stamp s;
                s.phase = 1;
                s.seq = side;
                mid =
                    add_vertex(kernel.side_point(side, s0 + 0.5 * (s1 - s0)), s, VKind::Mid0, side);
            } else if (cnt == 0 && mid != kNone) {
                delete_vertex(mid);
                mid = kNone;
            }
        }
    }

    /// The input closer to p than offcenter_min_separation() (other than one at p itself),
    /// or kNone. A check, not work of the update: report.queries is left alone.
    [[nodiscard]] std::uint32_t too_close(const Vec2& p) {
        Visibility vis;
        vis.bound.phase = 1;  // exclusive: the inputs and the box corners (phase 0)
        const std::size_t queries = report.queries;
        const std::uint32_t q = nearest(p, vis);
        report.queries = queries;
        if (q == kNone || verts[q].kind != VKind::Input) return kNone;
        const Vec2 d = verts[q].pos - p;
        const double sep = kernel.min_separation();
        return dot(d, d) < sep * sep ? q : kNone;
    }

    void add_input(const DynQuadtree<2>::GridPoint& g, const Vec2& p) {
        inputs[g] = add_vertex(p, Stamp{}, VKind::Input, -1);
        verts[inputs[g]].grid = g;
        update_round0(p, +1);
    }
};

// ------------------------------------------------------------------------------------------

DynOffCenterMesh2::DynOffCenterMesh2(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

DynOffCenterMesh2::DynOffCenterMesh2(const QuadtreeOptions<2>& domain,
                                     const OffCenterOptions& options) {
    detail::require_rho(options, "DynOffCenterMesh2");
    detail::require_offcenter_domain(domain, "DynOffCenterMesh2");
    impl_ = std::make_unique<Impl>(domain, options);
    impl_->begin_update();
    impl_->init_box();
    impl_->propagate();
    impl_->end_update();
    impl_->report = OffCenterUpdateReport{};
    impl_->change.clear();
}

DynOffCenterMesh2::~DynOffCenterMesh2() = default;
DynOffCenterMesh2::DynOffCenterMesh2(DynOffCenterMesh2&&) noexcept = default;
DynOffCenterMesh2& DynOffCenterMesh2::operator=(DynOffCenterMesh2&&) noexcept = default;

DynOffCenterMesh2 DynOffCenterMesh2::build(std::span<const Vec2> points,
                                           const QuadtreeOptions<2>& domain,
                                           const OffCenterOptions& options) {
    detail::require_rho(options, "DynOffCenterMesh2");
    detail::require_offcenter_domain(domain, "DynOffCenterMesh2");
    DynQuadtree<2> tree = DynQuadtree<2>::build(points, domain);  // validates, names bad points
    auto impl = std::make_unique<Impl>(domain, options);
    impl->tree = std::move(tree);
    impl->begin_update();
    impl->init_box();
    for (const auto& [g, p] : impl->tree.points()) impl->add_input(g, p);
    for (std::size_t i = 0; i < points.size(); ++i)
        if (const std::uint32_t q = impl->too_close(points[i]); q != kNone)
            throw InvalidInput("DynOffCenterMesh2::build: point " + std::to_string(i) + " " +
                               format_point(points[i]) + " is closer to the point " +
                               format_point(impl->verts[q].pos) + " than the " +
                               format_number(impl->kernel.min_separation()) +
                               " the off-center refinement resolves (offcenter_min_separation)",
                               i);
    impl->propagate();
    impl->end_update();
    impl->report = OffCenterUpdateReport{};
    impl->change.clear();
    return DynOffCenterMesh2(std::move(impl));
}

InsertResult DynOffCenterMesh2::insert(const Vec2& p) {
    Impl& m = *impl_;
    if (m.tree.is_admissible(p) && !m.tree.contains(p) && m.too_close(p) != kNone)
        return InsertResult::BeyondPrecision;
    const InsertResult r = m.tree.insert(p);
    if (r != InsertResult::Inserted) return r;
    m.begin_update();
    m.add_input(m.tree.grid_point(p), p);
    m.propagate();
    m.end_update();
    return r;
}

EraseResult DynOffCenterMesh2::erase(const Vec2& p) {
    Impl& m = *impl_;
    if (!m.tree.contains(p)) return EraseResult::NotFound;
    const auto g = m.tree.grid_point(p);
    const auto it = m.inputs.find(g);
    if (it == m.inputs.end()) throw InternalError("DynOffCenterMesh2: stored point without vertex");
    const EraseResult r = m.tree.erase(p);
    if (r != EraseResult::Erased) return r;
    m.begin_update();
    const std::uint32_t id = it->second;
    const Vec2 pos = m.verts[id].pos;
    m.inputs.erase(it);
    m.delete_vertex(id);
    m.update_round0(pos, -1);
    m.propagate();
    m.end_update();
    return r;
}

const DynQuadtree<2>& DynOffCenterMesh2::tree() const { return impl_->tree; }
const OffCenterOptions& DynOffCenterMesh2::options() const { return impl_->options; }
const OffCenterUpdateReport& DynOffCenterMesh2::last_update() const { return impl_->report; }
const LiveMesh<2>& DynOffCenterMesh2::current_mesh() const { return impl_->live; }
const MeshDelta<2>& DynOffCenterMesh2::last_change() const { return impl_->change; }
std::size_t DynOffCenterMesh2::vertex_count() const { return impl_->alive_count; }

OffCenterMesh2 DynOffCenterMesh2::mesh() const {
    const Impl& m = *impl_;
    OffCenterMesh2 out;
    out.origin = m.origin;
    out.width = m.width;
    std::vector<std::uint32_t> index(m.verts.size(), kNone);
    for (const auto& [g, id] : m.inputs) {
        index[id] = static_cast<std::uint32_t>(out.points.size());
        out.input_vertices.push_back(static_cast<std::uint32_t>(out.points.size()));
        out.points.push_back(m.verts[id].pos);
    }
    std::vector<std::uint32_t> steiner;
    for (std::uint32_t id = 0; id < m.verts.size(); ++id)
        if (m.verts[id].alive && m.verts[id].kind != VKind::Input) steiner.push_back(id);
    std::sort(steiner.begin(), steiner.end(), [&](std::uint32_t a, std::uint32_t b) {
        return lex_less(m.verts[a].pos, m.verts[b].pos);
    });
    for (std::uint32_t id : steiner) {
        index[id] = static_cast<std::uint32_t>(out.points.size());
        out.points.push_back(m.verts[id].pos);
    }
    out.steiner = steiner.size();
    out.boundary_steiner = m.boundary_count;
    out.apex_offcenters = m.apex_count;
    out.circumcentres = m.circum_count;
    out.rounds = m.rounds.size();
    out.stuck_pairs = m.stuck_count;
    out.triangles.reserve(m.dt.number_of_faces());
    for (auto f = m.dt.finite_faces_begin(); f != m.dt.finite_faces_end(); ++f) {
        std::array<std::uint32_t, 3> t{};
        for (int k = 0; k < 3; ++k) t[static_cast<std::size_t>(k)] = index[f->vertex(k)->info()];
        out.triangles.push_back(t);
    }
    detail::finish_offcenter_mesh(out);
    return out;
}

CheckReport DynOffCenterMesh2::check_invariants() const {
    std::vector<std::string> bad;
    const Impl& m = *impl_;
    // Stored counts and indices.
    std::size_t alive = 0;
    for (const auto& v : m.verts) alive += v.alive ? 1 : 0;
    if (alive != m.alive_count) bad.push_back("alive vertex count differs from the records");
    if (m.pidx[0][0].count + m.pidx[1][0].count != m.alive_count)
        bad.push_back("point index holds " +
                      std::to_string(m.pidx[0][0].count + m.pidx[1][0].count) +
                      " vertices, expected " + std::to_string(m.alive_count));
    if (m.dt.number_of_vertices() != m.alive_count)
        bad.push_back("triangulation vertex count differs");
    if (m.inputs.size() != m.tree.size()) bad.push_back("input count differs from the tree");
    if (!m.queue.empty()) bad.push_back("evaluations left in the queue");
    for (std::uint32_t id = 0; id < m.verts.size(); ++id) {
        const auto& v = m.verts[id];
        if (!v.alive) continue;
        if (v.vh == VertexHandle() || v.vh->info() != id ||
            !(Vec2{v.vh->point().x(), v.vh->point().y()} == v.pos))
            bad.push_back("vertex " + std::to_string(id) + " not in the triangulation");
    }
    // The trace against a from-scratch build.
    std::vector<Vec2> pts;
    for (const auto& [g, p] : m.tree.points()) pts.push_back(p);
    const DynOffCenterMesh2 fresh = build(pts, m.tree.options(), m.options);
    const Impl& f = *fresh.impl_;
    auto vertex_set = [](const Impl& s) {
        std::vector<std::tuple<double, double, int, Stamp>> out;
        for (const auto& v : s.verts)
            if (v.alive) out.emplace_back(v.pos.x, v.pos.y, static_cast<int>(v.kind), v.stamp);
        std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
            return std::tie(std::get<0>(a), std::get<1>(a)) <
                   std::tie(std::get<0>(b), std::get<1>(b));
        });
        return out;
    };
    const auto va = vertex_set(m), vb = vertex_set(f);
    if (va.size() != vb.size()) {
        bad.push_back("vertex count " + std::to_string(va.size()) +
                      " differs from a fresh build (" + std::to_string(vb.size()) + ")");
    } else {
        for (std::size_t k = 0; k < va.size(); ++k)
            if (!(std::get<0>(va[k]) == std::get<0>(vb[k]) &&
                  std::get<1>(va[k]) == std::get<1>(vb[k]) &&
                  std::get<2>(va[k]) == std::get<2>(vb[k]) &&
                  std::get<3>(va[k]) == std::get<3>(vb[k]))) {
                bad.push_back("vertex (" + std::to_string(std::get<0>(va[k])) + ", " +
                              std::to_string(std::get<1>(va[k])) + ") differs from a fresh build");
                break;
            }
    }
    auto proc_set = [](const Impl& s) {
        std::vector<std::tuple<Stamp, int, bool, std::size_t>> out;
        for (const auto& p : s.procs)
            if (p.alive)
                out.emplace_back(p.time, static_cast<int>(p.outcome), p.retry, p.outputs.size());
        std::sort(out.begin(), out.end(),
                  [](const auto& a, const auto& b) { return std::get<0>(a) < std::get<0>(b); });
        return out;
    };
    const auto pa = proc_set(m), pb = proc_set(f);
    if (pa.size() != pb.size()) {
        bad.push_back("processing count " + std::to_string(pa.size()) +
                      " differs from a fresh build (" + std::to_string(pb.size()) + ")");
    } else {
        for (std::size_t k = 0; k < pa.size(); ++k)
            if (!(std::get<0>(pa[k]) == std::get<0>(pb[k])) ||
                std::get<1>(pa[k]) != std::get<1>(pb[k]) ||
                std::get<2>(pa[k]) != std::get<2>(pb[k]) ||
                std::get<3>(pa[k]) != std::get<3>(pb[k])) {
                bad.push_back("processing record " + std::to_string(k) +
                              " differs from a fresh build");
                break;
            }
    }
    // The output against the static oracle.
    const OffCenterMesh2 a = mesh(), b = offcenter_mesh(m.tree, m.options);
    // The live mesh against mesh(), as sets of triangles (each starts at its smallest vertex
    // in output order, counter-clockwise, in both).
    {
        using Tri = std::array<double, 6>;
        std::vector<Tri> want, got;
        for (const auto& t : a.triangles)
            want.push_back({a.points[t[0]].x, a.points[t[0]].y, a.points[t[1]].x,
                            a.points[t[1]].y, a.points[t[2]].x, a.points[t[2]].y});
        for (std::uint32_t k = 0; k < m.live.simplex_slots(); ++k) {
            if (!m.live.has_simplex(k)) continue;
            const auto& t = m.live.simplex(k);
            const auto& P = [&](std::uint32_t v) { return m.live.point(v); };
            got.push_back({P(t[0]).x, P(t[0]).y, P(t[1]).x, P(t[1]).y, P(t[2]).x, P(t[2]).y});
        }
        std::sort(want.begin(), want.end());
        std::sort(got.begin(), got.end());
        if (want != got) bad.push_back("the live mesh differs from mesh()");
        if (m.live.vertex_count() != m.alive_count)
            bad.push_back("the live mesh has " + std::to_string(m.live.vertex_count()) +
                          " vertices, the triangulation " + std::to_string(m.alive_count));
    }
    if (a.points != b.points) bad.push_back("mesh points differ from offcenter_mesh()");
    if (a.triangles != b.triangles) bad.push_back("mesh triangles differ from offcenter_mesh()");
    if (a.input_vertices != b.input_vertices)
        bad.push_back("input vertices differ from offcenter_mesh()");
    if (a.steiner != b.steiner || a.boundary_steiner != b.boundary_steiner ||
        a.apex_offcenters != b.apex_offcenters || a.circumcentres != b.circumcentres ||
        a.rounds != b.rounds || a.stuck_pairs != b.stuck_pairs)
        bad.push_back("mesh counters differ from offcenter_mesh()");
    return CheckReport::of_problems(std::move(bad));
}

}  // namespace dynmesh
