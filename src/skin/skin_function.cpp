#include "dynmesh/skin/skin_function.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Regular_triangulation_cell_base_3.h>
#include <CGAL/Regular_triangulation_vertex_base_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "dynmesh/error.hpp"

namespace dynmesh {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb0 = CGAL::Regular_triangulation_vertex_base_3<K>;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K, Vb0>;
using Cb = CGAL::Regular_triangulation_cell_base_3<K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using RT = CGAL::Regular_triangulation_3<K, Tds>;

/// Solves the d×d symmetric system G·m = r (d ≤ 3) by Gaussian elimination with partial
/// pivoting; false when G is singular to working precision.
bool solve_small(int d, double G[3][3], double r[3], double m[3]) {
    double a[3][4];
    for (int i = 0; i < d; ++i) {
        for (int j = 0; j < d; ++j) a[i][j] = G[i][j];
        a[i][d] = r[i];
    }
    double norm = 0;
    for (int i = 0; i < d; ++i)
        for (int j = 0; j < d; ++j) norm = std::max(norm, std::fabs(a[i][j]));
    for (int c = 0; c < d; ++c) {
        int p = c;
        for (int i = c + 1; i < d; ++i)
            if (std::fabs(a[i][c]) > std::fabs(a[p][c])) p = i;
        if (!(std::fabs(a[p][c]) > 1e-14 * norm)) return false;
        for (int j = 0; j <= d; ++j) std::swap(a[c][j], a[p][j]);
        for (int i = c + 1; i < d; ++i) {
            const double f = a[i][c] / a[c][c];
            for (int j = c; j <= d; ++j) a[i][j] -= f * a[c][j];
        }
    }
    for (int i = d - 1; i >= 0; --i) {
        double v = a[i][d];
        for (int j = i + 1; j < d; ++j) v -= a[i][j] * m[j];
        m[i] = v / a[i][i];
    }
    return true;
}

double power(const WeightedPoint& b, const Point3& x) { return sqnorm(x - b.center) - b.weight; }

}  // namespace

SkinFunction::SkinFunction(std::vector<WeightedPoint> balls, double s) : balls_(std::move(balls)), s_(s) {
    DYNMESH_CHECK(std::isfinite(s) && s > 0 && s < 1, "SkinFunction: the shrink factor must be in (0, 1)");
    DYNMESH_CHECK(!balls_.empty(), "SkinFunction: no ball");
    n_input_ = balls_.size();
    Point3 lo = balls_[0].center, hi = balls_[0].center;
    double w_max = 0;
    for (const WeightedPoint& b : balls_) {
        DYNMESH_CHECK(is_finite(b.center) && std::isfinite(b.weight), "SkinFunction: a centre or a weight is not finite");
        lo = {std::min(lo.x, b.center.x), std::min(lo.y, b.center.y), std::min(lo.z, b.center.z)};
        hi = {std::max(hi.x, b.center.x), std::max(hi.y, b.center.y), std::max(hi.z, b.center.z)};
        w_max = std::max(w_max, b.weight);
    }
    // Bounding points (§1.5 with §8 correction 4): CGAL's distance, or far enough that every
    // ball–bounding-point distance is at least 2r/s.
    const Vec3 ext = hi - lo;
    const double half_diagonal = 0.5 * norm(ext);
    const double d_cgal = (ext.x + ext.y + ext.z + std::sqrt(w_max) + 0.001) / s;
    const double D = std::max(d_cgal, half_diagonal + 2 * std::sqrt(w_max / s) + 1);
    const Point3 c = lo + 0.5 * ext;
    for (int k = 0; k < 3; ++k)
        for (double sign : {-1.0, 1.0}) {
            Vec3 e{0, 0, 0};
            (k == 0 ? e.x : k == 1 ? e.y : e.z) = sign * D;
            balls_.push_back({c + e, -1});
        }
    scale_ = std::max({2 * half_diagonal, std::sqrt(w_max), 1e-300});

    std::vector<std::pair<K::Weighted_point_3, int>> input;
    input.reserve(balls_.size());
    for (std::size_t i = 0; i < balls_.size(); ++i) {
        const Point3& p = balls_[i].center;
        input.emplace_back(K::Weighted_point_3(K::Point_3(p.x, p.y, p.z), balls_[i].weight), int(i));
    }
    RT rt(input.begin(), input.end());
    DYNMESH_CHECK(rt.dimension() == 3, "SkinFunction: the regular triangulation is not 3-dimensional");

    // Every finite simplex is a face of a finite cell; its link gathers the cells' other vertices.
    std::map<std::array<int, 4>, std::size_t> index;
    std::vector<std::set<int>> links;
    for (auto cell = rt.finite_cells_begin(); cell != rt.finite_cells_end(); ++cell) {
        int v[4];
        for (int i = 0; i < 4; ++i) v[i] = cell->vertex(i)->info();
        for (int mask = 1; mask < 16; ++mask) {
            std::array<int, 4> key{-1, -1, -1, -1};
            int n = 0;
            for (int i = 0; i < 4; ++i)
                if (mask & (1 << i)) key[std::size_t(n++)] = v[i];
            for (int i = 1; i < n; ++i)  // insertion sort of at most four indices
                for (int j = i; j > 0 && key[std::size_t(j - 1)] > key[std::size_t(j)]; --j)
                    std::swap(key[std::size_t(j - 1)], key[std::size_t(j)]);
            auto [it, fresh] = index.emplace(key, simplices_.size());
            if (fresh) {
                SkinSimplex sx;
                sx.vertices = key;
                sx.dim = n - 1;
                simplices_.push_back(sx);
                links.emplace_back();
            }
            for (int i = 0; i < 4; ++i)
                if (!(mask & (1 << i))) links[it->second].insert(v[i]);
        }
    }
    index_.assign(index.begin(), index.end());  // std::map iterates in key order
    basis_.resize(simplices_.size());
    dual_.resize(simplices_.size());
    longest_edge_.assign(simplices_.size(), 0.0);
    for (std::size_t k = 0; k < simplices_.size(); ++k) {
        SkinSimplex& sx = simplices_[k];
        sx.link.assign(links[k].begin(), links[k].end());
        const WeightedPoint& b0 = balls_[std::size_t(sx.vertices[0])];
        const int d = sx.dim;
        Vec3 e[3];
        double G[3][3], r[3], m[3] = {0, 0, 0};
        for (int i = 0; i < d; ++i) {
            const WeightedPoint& bi = balls_[std::size_t(sx.vertices[std::size_t(i + 1)])];
            e[i] = bi.center - b0.center;
            r[i] = 0.5 * (sqnorm(e[i]) - bi.weight + b0.weight);
        }
        for (int i = 0; i < d; ++i)
            for (int j = 0; j < d; ++j) G[i][j] = dot(e[i], e[j]);
        if (d > 0 && !solve_small(d, G, r, m))
            throw InternalError("SkinFunction: a degenerate simplex in the regular triangulation");
        Point3 z = b0.center;
        for (int i = 0; i < d; ++i) z = z + m[i] * e[i];
        // Dual basis: column j of G⁻¹ combines the edges into dual_j.
        for (int j = 0; j < d; ++j) {
            double unit[3] = {0, 0, 0}, col[3] = {0, 0, 0};
            unit[j] = 1;
            solve_small(d, G, unit, col);
            Vec3 dj{0, 0, 0};
            for (int i = 0; i < d; ++i) dj = dj + col[i] * e[i];
            dual_[k][std::size_t(j)] = dj;
            longest_edge_[k] = std::max(longest_edge_[k], norm(e[j]));
        }
        sx.z = z;
        sx.W = power(b0, z);
        // Orthonormal basis of aff δ's directions (Gram–Schmidt).
        for (int i = 0; i < d; ++i) {
            Vec3 v = e[i];
            for (int j = 0; j < i; ++j) v = v - dot(v, basis_[k][std::size_t(j)]) * basis_[k][std::size_t(j)];
            basis_[k][std::size_t(i)] = v / norm(v);
        }
    }
    // The walk's table: each constraint of each mixed cell with the simplex it moves to (a face
    // of a simplex and δ ∪ {j} for a link vertex j are simplices of the triangulation).
    walk_begin_.assign(simplices_.size() + 1, 0);
    for (std::size_t k = 0; k < simplices_.size(); ++k) {
        const SkinSimplex& sx = simplices_[k];
        walk_begin_[k] = walk_.size();
        const auto to = [&](int drop, int add) {
            const std::optional<std::size_t> target = neighbour(k, drop, add);
            if (!target) throw InternalError("SkinFunction: a face or coface is missing from the triangulation");
            return *target;
        };
        if (sx.dim > 0) {
            for (int i = 0; i < sx.dim; ++i) walk_.push_back({to(sx.vertices[std::size_t(i + 1)], -1), {0, 0, 0}, 0.0});
            walk_.push_back({to(sx.vertices[0], -1), {0, 0, 0}, 0.0});
        }
        const WeightedPoint& b0 = balls_[std::size_t(sx.vertices[0])];
        for (int j : sx.link) {
            // power(b0, q) − power(b_j, q) = 2 (q − z_0)·e − ‖e‖² − w_0 + w_j with e = z_j − z_0.
            const WeightedPoint& bj = balls_[std::size_t(j)];
            const Vec3 e = bj.center - b0.center;
            const double len = norm(e);
            walk_.push_back({to(-1, j), e / len, (len * len + b0.weight - bj.weight) / (2 * len)});
        }
    }
    walk_begin_[simplices_.size()] = walk_.size();
}

Vec3 SkinFunction::along_simplex(std::size_t k, const Vec3& u) const {
    Vec3 ud{0, 0, 0};
    for (int i = 0; i < simplices_[k].dim; ++i) ud = ud + dot(u, basis_[k][std::size_t(i)]) * basis_[k][std::size_t(i)];
    return ud;
}

template <class Fn>
void SkinFunction::for_each_constraint(std::size_t k, const Point3& x, Fn&& fn) const {
    const SkinSimplex& sx = simplices_[k];
    const Vec3 u = x - sx.z;
    const Vec3 ud = along_simplex(k, u);
    const Vec3 un = u - ud;
    const WeightedPoint& b0 = balls_[std::size_t(sx.vertices[0])];
    const WalkStep* step = walk_.data() + walk_begin_[k];
    if (sx.dim > 0) {
        // p = z + u_δ/(1 − s) in δ: barycentric coordinates ≥ 0, scaled by the longest edge.
        const Vec3 p = sx.z + ud / (1 - s_) - b0.center;
        double l0 = 1;
        for (int i = 0; i < sx.dim; ++i) {
            const double m = dot(dual_[k][std::size_t(i)], p);
            l0 -= m;
            fn(-m * longest_edge_[k], step->target);
            ++step;
        }
        fn(-l0 * longest_edge_[k], step->target);
        ++step;
    }
    // q = z + u_ν/s in ν_δ: on the δ side of the power bisector with every link vertex j
    // (signed distance to that plane).
    const Vec3 d = sx.z + un / s_ - b0.center;
    for (const WalkStep* end = walk_.data() + walk_begin_[k + 1]; step != end; ++step)
        fn(dot(step->normal, d) - step->offset, step->target);
}

void SkinFunction::violated(std::size_t k, const Point3& x, std::vector<Move>& out) const {
    out.clear();
    const double tol = 1e-12 * scale_;
    for_each_constraint(k, x, [&](double amount, std::size_t target) {
        if (amount > tol) out.push_back({amount, target});
    });
}

double SkinFunction::violation(std::size_t k, const Point3& x) const {
    double worst = -std::numeric_limits<double>::infinity();
    for_each_constraint(k, x, [&](double amount, std::size_t) { worst = std::max(worst, amount); });
    return worst;
}

std::optional<std::size_t> SkinFunction::find_simplex(std::array<int, 4> v, int count) const {
    if (count < 1 || count > 4) return std::nullopt;
    for (int i = count; i < 4; ++i) v[std::size_t(i)] = -1;
    std::sort(v.begin(), v.begin() + count);
    const auto it = std::lower_bound(index_.begin(), index_.end(), v,
                                     [](const auto& e, const std::array<int, 4>& key) { return e.first < key; });
    if (it == index_.end() || it->first != v) return std::nullopt;
    return it->second;
}

std::optional<std::size_t> SkinFunction::neighbour(std::size_t k, int drop, int add) const {
    const SkinSimplex& sx = simplices_[k];
    std::array<int, 4> key{-1, -1, -1, -1};
    int n = 0;
    for (int i = 0; i <= sx.dim; ++i)
        if (sx.vertices[std::size_t(i)] != drop) key[std::size_t(n++)] = sx.vertices[std::size_t(i)];
    if (add >= 0) {
        if (n == 4) return std::nullopt;
        key[std::size_t(n++)] = add;
    }
    return find_simplex(key, n);
}

std::size_t SkinFunction::locate_by_scan(const Point3& x) const {
    std::size_t best = 0;
    double best_violation = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < simplices_.size(); ++k) {
        const double v = violation(k, x);
        if (v <= 1e-12 * scale_) return k;
        if (v < best_violation) {
            best_violation = v;
            best = k;
        }
    }
    return best;
}

std::size_t SkinFunction::locate(const Point3& x, std::size_t hint) const {
    DYNMESH_CHECK(is_finite(x), "SkinFunction::locate: the point is not finite");
    std::size_t k = hint < simplices_.size() ? hint : 0;
    thread_local std::vector<Move> moves;
    thread_local std::vector<std::size_t> visited;
    visited.clear();
    const auto fresh = [&](std::size_t target) {
        return std::find(visited.begin(), visited.end(), target) == visited.end();
    };
    for (std::size_t step = 0; step < simplices_.size() + 8; ++step) {
        violated(k, x, moves);
        if (moves.empty()) return k;
        visited.push_back(k);
        // The most violated constraint whose simplex the walk has not visited, ties in
        // constraint order: the first maximum usually, else the moves sorted (stably).
        std::size_t first = 0;
        for (std::size_t m = 1; m < moves.size(); ++m)
            if (moves[m].amount > moves[first].amount) first = m;
        std::optional<std::size_t> next;
        if (fresh(moves[first].target)) {
            next = moves[first].target;
        } else {
            std::stable_sort(moves.begin(), moves.end(), [](const Move& a, const Move& b) { return a.amount > b.amount; });
            for (const Move& m : moves)
                if (fresh(m.target)) {
                    next = m.target;
                    break;
                }
        }
        if (!next) break;
        k = *next;
    }
    ++fallbacks_;
    return locate_by_scan(x);
}

bool SkinFunction::in_mixed_cell(std::size_t k, const Point3& x) const {
    return violation(k, x) <= 1e-12 * scale_;
}

double SkinFunction::value_in(std::size_t k, const Point3& x) const {
    const Vec3 u = x - simplices_[k].z;
    const Vec3 ud = along_simplex(k, u);
    return sqnorm(u - ud) / s_ - sqnorm(ud) / (1 - s_) + simplices_[k].W;
}

SkinEvaluation SkinFunction::evaluate_in(std::size_t k, const Point3& x) const {
    const SkinSimplex& sx = simplices_[k];
    const Vec3 u = x - sx.z;
    const Vec3 ud = along_simplex(k, u);
    const Vec3 un = u - ud;
    SkinEvaluation ev;
    ev.simplex = k;
    ev.value = value_in(k, x);
    ev.gradient = (2 / s_) * un - (2 / (1 - s_)) * ud;
    // Φ_δ = uᵀAu + W with A = P_ν/s − P_δ/(1−s): κ = max |tᵀAt| over unit tangents / ‖Au‖.
    const auto A = [&](const Vec3& v) {
        const Vec3 vd = along_simplex(k, v);
        return (1 / s_) * (v - vd) - (1 / (1 - s_)) * vd;
    };
    const Vec3 g = A(u);
    const double gn = norm(g);
    if (!(gn > 0)) return ev;  // at z_δ of a critical simplex: infinite curvature, ϱ = 0
    const Vec3 n = g / gn;
    const Vec3 a = std::fabs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 t1 = normalized(a - dot(a, n) * n);
    const Vec3 t2 = cross(n, t1);
    const double m11 = dot(t1, A(t1)), m12 = dot(t1, A(t2)), m22 = dot(t2, A(t2));
    const double mean = 0.5 * (m11 + m22), rad = std::hypot(0.5 * (m11 - m22), m12);
    const double kappa = std::max(std::fabs(mean + rad), std::fabs(mean - rad)) / gn;
    ev.rho = kappa > 0 ? 1 / kappa : std::numeric_limits<double>::infinity();
    return ev;
}

Point3 SkinFunction::flow_in_cell(std::size_t k, const Point3& x0, double t) const {
    DYNMESH_CHECK(s_ == 0.5, "SkinFunction::flow_in_cell: the closed-form flow needs s = 1/2");
    DYNMESH_CHECK(k < simplices_.size() && is_finite(x0) && std::isfinite(t), "SkinFunction::flow_in_cell: bad arguments");
    const SkinSimplex& sx = simplices_[k];
    const Vec3 u = x0 - sx.z;
    const Vec3 ud = along_simplex(k, u);
    const Vec3 un = u - ud;
    const double a0 = norm(un), b0 = norm(ud);
    const double D = 0.5 * (t - sx.W), ab = a0 * b0;
    const double root = std::sqrt(D * D + 4 * ab * ab);
    // a² = (D + root)/2 and b² = (root − D)/2; the smaller of the two from the product when
    // D is large, to avoid cancellation.
    double a2 = D >= 0 ? 0.5 * (D + root) : 0.0, b2 = D < 0 ? 0.5 * (root - D) : 0.0;
    if (D >= 0) b2 = a2 > 0 ? ab * ab / a2 : 0.0;
    else a2 = ab * ab / b2;
    DYNMESH_CHECK(a0 > 0 || a2 == 0, "SkinFunction::flow_in_cell: the point is on the quadric's axis and cannot reach that level");
    DYNMESH_CHECK(b0 > 0 || b2 == 0, "SkinFunction::flow_in_cell: the point is on the quadric's axis and cannot reach that level");
    Point3 x = sx.z;
    if (a0 > 0) x = x + (std::sqrt(a2) / a0) * un;
    if (b0 > 0) x = x + (std::sqrt(b2) / b0) * ud;
    return x;
}

SkinEvaluation SkinFunction::evaluate(const Point3& x, std::size_t hint) const {
    DYNMESH_CHECK(is_finite(x), "SkinFunction::evaluate: the point is not finite");
    return evaluate_in(locate(x, hint), x);
}

}  // namespace dynmesh
