#pragma once
/// \file DynQuadtree<D>: a balanced 2^D-tree over a dynamic point set (D = 2, 3), after Acar &
/// Hudson, "Dynamic Mesh Refinement with Quad Trees and Off-Centers" (CMU-CS-07-121), as
/// specified in shared/specs/dynamic-quadtree.md §1–§3, in two modes: "paper mode" (isolation
/// radius k = 1, the paper's tree) and "mesh mode" (k = 2 plus rules U and R, the tree the
/// simplicial meshes of quad_mesh.hpp / oct_mesh.hpp are derived from).
///
/// The tree is a function of (domain, point set, mode) alone (spec §1.4): its internal cells are
/// the least set I(P) closed under
///   (C) crowded_k(x) => x in I, where crowded_k(x) <=> |P ∩ x| >= 1 and |P ∩ N_k[x]| >= 2
///       (N_k[x] = the (2k+1)^D block of equal-size cells centred on x, clipped to the domain);
///   (A) x in I => parent(x) in I;
///   (B) x in I => every cell of size 2|x| touching x (closures meet) is in I;
///   (U) mesh mode: x in I and P ∩ x nonempty => every equal-size neighbour of x is in I;
///   (R) mesh mode: the root is in I whenever P is nonempty.
/// Leaves are the children of I-cells not in I (or the root alone). Cells are half-open dyadic
/// cubes on an integer grid of 2^52 units per axis; inputs are snapped to multiples of 8 units
/// (input quantum W·2^-49) and must lie in the middle third of the domain box.
///
/// Updates are incremental (spec §3.2, support counting): an insert or erase recomputes the
/// crowding flags of the (2k+1)^D cells around the point per level, then settles membership in I
/// smallest level first with a bucket queue, and finally splits / merges only the cells whose
/// membership changed. The result equals build() on the current point set, cell for cell.
///
/// **Resolution** (spec §7.2, "spread overflow"). The tree itself is exact, but the meshes built
/// on it put vertices at lattice positions origin + k·u (u = W·2^-52, the grid unit) and compute
/// off-centers in double precision, so every leaf must be resolved by the doubles at its
/// position. A leaf L of level ℓ (side 2^ℓ·u) is **resolved** when, with h = 2^(ℓ-1)·u (half its
/// side: the finest lattice spacing a mesh uses inside L) and X = the largest |coordinate| of L's
/// closed box:
///   * on a **dyadic** domain (W a power of two, every origin coordinate a multiple of W/8, e.g.
///     auto_domain() of domain.hpp and the unit box): X ≤ 2^53·min(h, W/8). Then every lattice
///     point of L at spacing h is a double, so mesh vertices are exact; leaves may shrink to
///     about one ulp of the coordinates;
///   * on any other domain (lattice positions are rounded): h ≥ 2^13·ulp(X), so a vertex moves
///     by at most 2^-13 of the finest spacing (the old CLI rule: a sixteenth of a leaf spans
///     1024 ulps).
/// insert() refuses a point whose insertion would create an unresolved leaf
/// (InsertResult::BeyondPrecision) and build() throws InvalidInput naming such a point, so every
/// leaf of a tree is always resolved. The rule is a property of the point set: a set is accepted
/// iff every leaf of its tree is resolved, whatever the order of insertion (every leaf of a
/// subset's tree is a union of leaves of the set's tree, hence resolved too: erase never fails).

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "dynmesh/check_report.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/system/hash.hpp"

namespace dynmesh {

/// The point type of dimension D: Vec2 for D = 2, Vec3 for D = 3.
template <int D>
using PointD = std::conditional_t<D == 2, Vec2, Vec3>;

/// Which tree of spec §1.4 is maintained.
enum class QuadtreeMode {
    Paper,  // isolation radius k = 1, rules C, A, B: the paper's balanced tree
    Mesh,   // k = 2 and rules U, R as well: every leaf touching a point leaf has its size
};

/// The fixed domain box Ω = [origin, origin + width]^D. It never follows the points (spec §1.1);
/// changing it means building a new tree.
template <int D>
struct QuadtreeOptions {
    PointD<D> origin{};  // lower corner of Ω
    double width = 1.0;  // side length W of Ω, finite and > 0
    QuadtreeMode mode = QuadtreeMode::Paper;
};

/// What a cell is in the current tree.
enum class CellKind {
    Absent,    // not a cell of the tree: strictly inside a leaf
    Leaf,
    Internal,  // a member of I(P)
};

enum class InsertResult {
    Inserted,
    Duplicate,        // a point with the same snapped grid coordinates is already stored
    OutsideDomain,    // not in the middle third [o + W/3, o + 2W/3]^D of the domain
    NotFinite,        // a NaN or infinite coordinate
    BeyondPrecision,  // the point is so close to others that its insertion would create a leaf
                      // finer than double precision resolves at its coordinates (file comment,
                      // "Resolution"); nothing changed
};

enum class EraseResult {
    Erased,
    NotFound,  // no stored point has these snapped grid coordinates (or the point is invalid)
};

/// A dyadic cell: ∏_i [index_i·2^level, (index_i+1)·2^level) in grid units. The root is
/// (level 52, index 0). Ordered by (level, index) for canonical output.
template <int D>
struct CellId {
    int level = 0;
    std::array<std::uint64_t, D> index{};
    auto operator<=>(const CellId&) const = default;
};

/// What the last insert/erase changed (the change log of spec §3.2 step 4).
template <int D>
struct QuadtreeUpdateReport {
    std::vector<CellId<D>> split;      // leaves that became internal, largest first
    std::vector<CellId<D>> merged;     // internal cells that became leaves, smallest first
    std::size_t crowding_changes = 0;  // cells whose crowded flag flipped
    std::size_t support_updates = 0;   // ±1 support messages sent during propagation
};

template <int D>
class DynQuadtree {
    static_assert(D == 2 || D == 3, "DynQuadtree supports D = 2 and D = 3");

public:
    using Point = PointD<D>;
    using GridPoint = std::array<std::uint64_t, D>;
    static constexpr int kLevels = 52;    // K: the grid has 2^K units per axis
    static constexpr int kGuardBits = 3;  // G: inputs are snapped to multiples of 2^G units

    /// A stored point: its snapped grid coordinates and the coordinates it was given.
    struct StoredPoint {
        GridPoint grid{};
        Point point{};
    };

    /// An empty tree (the root alone) over the given domain.
    /// \throw InvalidInput if the origin is not finite, the width is not finite and > 0, the
    ///        box [origin, origin + W]^D overflows, or the grid unit W·2^-52 is not a normal
    ///        double (W < 2^52·DBL_MIN).
    explicit DynQuadtree(const QuadtreeOptions<D>& options = {});

    /// From-scratch build (spec §2.3): computes I(P) directly, bottom-up by level, then closes
    /// it under rules A and B. Equals inserting the points one by one in any order.
    /// \throw InvalidInput naming the point (index and coordinates) if one is not finite, lies
    ///        outside the middle third, duplicates an earlier one after snapping, or lies at an
    ///        unresolved leaf (file comment, "Resolution": the point nearest to the first such
    ///        leaf is named).
    [[nodiscard]] static DynQuadtree build(std::span<const Point> points,
                                           const QuadtreeOptions<D>& options = {});

    /// Inserts p. On any result other than Inserted nothing changes (last_update() included).
    /// BeyondPrecision is decided exactly (every leaf the insertion would create is tested)
    /// after the membership changes are computed and before any cell is split; a refused
    /// insertion rolls those back, so the tree, its counts and last_update() are as before.
    [[nodiscard]] InsertResult insert(const Point& p);
    /// Erases the stored point with p's snapped grid coordinates. On NotFound nothing changes.
    [[nodiscard]] EraseResult erase(const Point& p);
    /// True when a point with p's snapped grid coordinates is stored.
    [[nodiscard]] bool contains(const Point& p) const;

    [[nodiscard]] std::size_t size() const { return size_; }
    [[nodiscard]] std::size_t leaf_count() const { return nodes_.size() - state_.size(); }
    [[nodiscard]] std::size_t internal_count() const { return state_.size(); }
    [[nodiscard]] const QuadtreeOptions<D>& options() const { return options_; }
    /// The change log of the last successful insert or erase (empty after construction).
    [[nodiscard]] const QuadtreeUpdateReport<D>& last_update() const { return last_update_; }

    /// True when p is finite and lies in the middle third of the domain.
    [[nodiscard]] bool is_admissible(const Point& p) const;
    /// Grid coordinates of p (multiples of 2^kGuardBits in [0, 2^kLevels)).
    /// \throw InvalidInput unless is_admissible(p).
    [[nodiscard]] GridPoint grid_point(const Point& p) const;

    /// True when the domain is dyadic (file comment, "Resolution").
    [[nodiscard]] bool dyadic() const { return dyadic_; }
    /// True when a leaf c would be resolved (file comment, "Resolution"), whether or not c is
    /// a cell of the tree. Cells of level 0 never are.
    [[nodiscard]] bool is_resolved(const CellId<D>& c) const;

    /// The isolation radius k of the mode (1 in paper mode, 2 in mesh mode).
    [[nodiscard]] int isolation_radius() const {
        return options_.mode == QuadtreeMode::Mesh ? 2 : 1;
    }

    /// Every leaf, sorted by (level, index).
    [[nodiscard]] std::vector<CellId<D>> leaves() const;
    /// What a cell is, and its points when it is a leaf.
    struct CellView {
        CellKind kind = CellKind::Absent;
        std::span<const StoredPoint> points;  // leaves only
    };
    /// One lookup: the kind of c and, for a leaf, its points. O(1) expected.
    [[nodiscard]] CellView cell_view(const CellId<D>& c) const;
    /// Whether c is a leaf, an internal cell or not a cell of the tree. O(1) expected.
    [[nodiscard]] CellKind cell_kind(const CellId<D>& c) const { return cell_view(c).kind; }
    /// The points of leaf c (at most one in a settled tree); empty if c is not a leaf.
    [[nodiscard]] std::span<const StoredPoint> leaf_points(const CellId<D>& c) const {
        return cell_view(c).points;
    }
    /// The leaf containing grid point g (g's coordinates in [0, 2^kLevels)). O(depth).
    [[nodiscard]] CellId<D> leaf_containing(const GridPoint& g) const;
    /// Every stored point with its grid coordinates, sorted by grid coordinates (canonical
    /// order: independent of the history of updates).
    [[nodiscard]] std::vector<std::pair<GridPoint, Point>> points() const;
    /// Deterministic text form of the tree: a header line, then one line per leaf sorted by
    /// (level, index) with the grid coordinates of its point if it holds one. Equal point sets
    /// (up to snapping) over equal domains give byte-identical dumps, whatever the history.
    [[nodiscard]] std::string canonical_dump() const;
    /// Every violated invariant, one problem each (ok() when the tree is valid; no figure).
    /// Checks the tree structure and counts, every point in exactly one leaf, no crowded and no
    /// unbalanced leaf in the sense of spec §1.3 (leaf neighbours, size ratio < 4), and the
    /// local certificate of spec §3.4 (closure under C, A, B; stored crowding flags and
    /// supports equal their recomputation, every internal cell has positive support).
    /// O(cells).
    [[nodiscard]] CheckReport check_invariants() const;

private:
    struct Key {
        std::array<std::uint64_t, D> a{};
        int level = 0;
        bool operator==(const Key& o) const {
            if (level != o.level) return false;
            for (int i = 0; i < D; ++i)
                if (a[i] != o.a[i]) return false;
            return true;
        }
    };
    struct KeyHash {
        std::size_t operator()(const Key& k) const noexcept {
            return static_cast<std::size_t>(hash_range(k.a, static_cast<std::uint64_t>(k.level)));
        }
    };
    using Entry = StoredPoint;
    /// A cell of the tree (internal or leaf). Leaves own their points (≤ 1 when settled).
    struct Node {
        std::uint64_t count = 0;  // |P ∩ cell|
        bool is_leaf = true;
        std::vector<Entry> points;  // leaves only
    };
    /// Support-counting state of spec §3.2; an entry exists iff support > 0 or in_i.
    struct CellState {
        int support = 0;  // [crowded] + #{z in I : |z| = |x|/2, z touches x}
        bool crowded = false;
        bool in_i = false;
    };
    using NodeMap = std::unordered_map<Key, Node, KeyHash>;
    using StateMap = std::unordered_map<Key, CellState, KeyHash>;

    [[nodiscard]] static Key root_key();
    [[nodiscard]] static Key cell_of(const GridPoint& g, int level);
    [[nodiscard]] static bool offset_cell(const Key& c, const std::array<int, D>& o, Key& out);
    [[nodiscard]] static std::vector<Key> up_neighbours(const Key& x);
    [[nodiscard]] InsertResult snap(const Point& p, GridPoint& g) const;
    /// The leaf containing g, and the root-to-leaf path (leaf last) if path != nullptr.
    [[nodiscard]] Node& find_leaf(const GridPoint& g, std::vector<Node*>* path);
    [[nodiscard]] const Node& find_leaf(const GridPoint& g) const;
    /// |P ∩ x| for any cell x (0 outside the domain), from stored counts or a leaf's points.
    [[nodiscard]] std::uint64_t count_in(const Key& x) const;
    /// crowded_k(x) from current counts (k = isolation_radius()).
    [[nodiscard]] bool is_crowded(const Key& x) const;
    /// Spec §3.2 steps 1–3 after p's counts and leaf entry were updated; sign = +1 or -1;
    /// path = the root-to-leaf path of p (already updated counts). Returns the membership flips
    /// (cell, now in I) and leaves the leaf structure alone.
    [[nodiscard]] std::vector<std::pair<Key, bool>> settle(const GridPoint& g, int sign,
                                                           const std::vector<Node*>& path);
    /// Spec §3.2 step 4: applies the flips of settle() to the leaf structure.
    void apply_flips(const std::vector<std::pair<Key, bool>>& flips);
    /// Largest |coordinate| of the closed box of the cells [lo, hi) (grid units) per axis.
    [[nodiscard]] double box_extent(const std::array<std::uint64_t, D>& lo,
                                    const std::array<std::uint64_t, D>& hi) const;
    /// The resolution rule for a leaf of `level` whose closed box has largest |coordinate| X.
    [[nodiscard]] bool resolved(int level, double x) const;
    /// Mesh mode: +-1 support from x (an I-cell holding a point, rule U) to each equal-size
    /// neighbour, which is queued in `bucket`.
    void push_u_support(const Key& x, int delta, std::vector<Key>& bucket);
    void split(const Key& x);
    void merge(const Key& x);

    QuadtreeOptions<D> options_;
    bool dyadic_ = false;
    std::size_t size_ = 0;
    NodeMap nodes_;   // I(P) ∪ leaves
    StateMap state_;  // I(P) when settled
    QuadtreeUpdateReport<D> last_update_;
};

extern template class DynQuadtree<2>;
extern template class DynQuadtree<3>;

}  // namespace dynmesh
