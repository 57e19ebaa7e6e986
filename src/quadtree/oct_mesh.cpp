#include "dynmesh/quadtree/oct_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/predicates.hpp"
#include "dynmesh/geometry/scaled_frame.hpp"
#include "dynmesh/geometry/format.hpp"
#include "leaf_mesh.hpp"

namespace dynmesh {

namespace {

using Lattice3 = detail::Lattice<3>;
using Tri = std::array<Lattice3, 3>;

/// Triangulates the faces of one leaf (spec §4.3) from its code.
class FaceTriangulator {
public:
    FaceTriangulator(const CellId<3>& leaf, detail::LeafCode code) : leaf_(leaf), code_(code) {}

    /// The facet triangles of face (axis, side) of the cell with lower corner x and size s.
    void face_triangles(const Lattice3& x, std::uint64_t s, std::size_t axis, int side,
                        std::vector<Tri>& out) const {
        Lattice3 lo = x;
        lo[axis] += side == 1 ? s : 0;
        const std::size_t b = (axis + 1) % 3, c = (axis + 2) % 3;
        const std::uint64_t h = s / 2;
        Lattice3 centre = lo;
        centre[b] += h;
        centre[c] += h;
        if (s >= 2 && has_vertex(centre)) {  // the leaf across is smaller
            for (int q = 0; q < 4; ++q) {
                Lattice3 sub = lo;
                sub[b] += (q & 1) ? h : 0;
                sub[c] += (q & 2) ? h : 0;
                square_triangles(sub, h, b, c, out);
            }
        } else {
            square_triangles(lo, s, b, c, out);
        }
    }

private:
    [[nodiscard]] bool has_vertex(const Lattice3& v) const {
        return detail::code_has_vertex<3>(leaf_, code_, v);
    }

    /// One facet: the square with lower corner lo and side s spanning axes b and c.
    void square_triangles(const Lattice3& lo, std::uint64_t s, std::size_t b, std::size_t c,
                          std::vector<Tri>& out) const {
        const auto at = [&](std::uint64_t db, std::uint64_t dc) {
            Lattice3 p = lo;
            p[b] += db;
            p[c] += dc;
            return p;
        };
        const std::uint64_t h = s / 2;
        const bool even = s >= 2 && s % 2 == 0;
        std::array<Lattice3, 8> cycle{};
        std::size_t m = 0;
        bool hanging = false;
        const auto push_side = [&](const Lattice3& corner, const Lattice3& mid) {
            cycle[m++] = corner;
            if (even && has_vertex(mid)) {
                cycle[m++] = mid;
                hanging = true;
            }
        };
        push_side(at(0, 0), at(h, 0));
        push_side(at(s, 0), at(s, h));
        push_side(at(s, s), at(h, s));
        push_side(at(0, s), at(0, h));
        if (!hanging) {
            // Diagonal from the lexicographically smallest corner at(0, 0) to at(s, s).
            out.push_back({cycle[0], cycle[1], cycle[2]});
            out.push_back({cycle[0], cycle[2], cycle[3]});
            return;
        }
        const Lattice3 centre = at(h, h);
        for (std::size_t k = 0; k < m; ++k) out.push_back({centre, cycle[k], cycle[(k + 1) % m]});
    }

    CellId<3> leaf_;
    detail::LeafCode code_;
};

/// 6·signed volume of (a, b, c, d), in long double.
long double six_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const long double ux = static_cast<long double>(b.x) - a.x, uy = static_cast<long double>(b.y) - a.y,
                      uz = static_cast<long double>(b.z) - a.z;
    const long double vx = static_cast<long double>(c.x) - a.x, vy = static_cast<long double>(c.y) - a.y,
                      vz = static_cast<long double>(c.z) - a.z;
    const long double wx = static_cast<long double>(d.x) - a.x, wy = static_cast<long double>(d.y) - a.y,
                      wz = static_cast<long double>(d.z) - a.z;
    return ux * (vy * wz - vz * wy) - uy * (vx * wz - vz * wx) + uz * (vx * wy - vy * wx);
}

}  // namespace

namespace detail {

template <>
void leaf_simplices<3>(const CellId<3>& leaf, LeafCode code,
                       std::vector<LatticeSimplex<3>>& out) {
    const auto [x, s] = cell_box(leaf);
    // Star cells are coned from the warped corner v, every other leaf from its centre.
    const bool is_star = code_is_star<3>(code);
    const Lattice3 apex =
        is_star ? code_apex<3>(leaf, code) : Lattice3{x[0] + s / 2, x[1] + s / 2, x[2] + s / 2};
    const FaceTriangulator faces(leaf, code);
    static thread_local std::vector<Tri> facets;
    facets.clear();
    for (std::size_t axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            // A star cell's faces through v are interior to the star: skip them.
            if (is_star && apex[axis] == x[axis] + (side == 1 ? s : 0)) continue;
            faces.face_triangles(x, s, axis, side, facets);
        }
    for (const Tri& t : facets) out.push_back({apex, t[0], t[1], t[2]});
}

}  // namespace detail

OctMesh3 oct_mesh(const DynQuadtree<3>& tree) { return detail::mesh_of_tree<3>(tree); }

CheckReport check_oct_mesh(const OctMesh3& mesh) {
    std::vector<std::string> bad;
    const auto n = mesh.points.size();
    std::vector<bool> used(n, false);
    // Sorted face -> parities; the face of a positive tet opposite its vertex i is outward
    // when i is even, so parity = [i odd] xor parity of the sorting permutation.
    std::vector<std::pair<std::array<std::uint32_t, 3>, bool>> faces;
    faces.reserve(4 * mesh.tets.size());
    long double volume6 = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const auto& tet = mesh.tets[t];
        const std::string name = "tetrahedron " + std::to_string(t);
        if (tet[0] >= n || tet[1] >= n || tet[2] >= n || tet[3] >= n) {
            bad.push_back(name + ": index out of range");
            continue;
        }
        bool distinct = true;
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) distinct = distinct && tet[i] != tet[j];
        if (!distinct) {
            bad.push_back(name + ": repeated vertex");
            continue;
        }
        for (int i = 0; i < 4; ++i) {
            used[tet[i]] = true;
            std::array<std::uint32_t, 3> f{};
            for (int j = 0, m = 0; j < 4; ++j)
                if (j != i) f[m++] = tet[j];
            bool parity = (i % 2) == 1;
            // Sort three values, tracking the permutation parity.
            for (const auto& [x, y] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{0, 1}}) {
                if (f[x] > f[y]) {
                    std::swap(f[x], f[y]);
                    parity = !parity;
                }
            }
            faces.emplace_back(f, parity);
        }
        const Vec3 &a = mesh.points[tet[0]], &b = mesh.points[tet[1]], &c = mesh.points[tet[2]],
                   &d = mesh.points[tet[3]];
        if (orient3d(a, b, c, d) != Sign::Positive)
            bad.push_back(name + " is not positively oriented");
        volume6 += six_volume(a, b, c, d);
    }
    // The box the vertices span: its far corner is origin + W rounded, as the mesh places it.
    const Vec3 lo = mesh.origin;
    const Vec3 hi{lo.x + mesh.width, lo.y + mesh.width, lo.z + mesh.width};
    const long double want = (static_cast<long double>(hi.x) - lo.x) *
                             (static_cast<long double>(hi.y) - lo.y) *
                             (static_cast<long double>(hi.z) - lo.z);
    if (std::fabs(volume6 / 6 - want) > 1e-12L * want)
        bad.push_back("total volume " + format_number(static_cast<double>(volume6 / 6)) +
                      " differs from the domain volume " + format_number(static_cast<double>(want)));
    std::sort(faces.begin(), faces.end());
    for (std::size_t i = 0; i < faces.size();) {
        std::size_t j = i + 1;
        while (j < faces.size() && faces[j].first == faces[i].first) ++j;
        const auto& f = faces[i].first;
        const std::string name = "triangle (" + std::to_string(f[0]) + ", " +
                                 std::to_string(f[1]) + ", " + std::to_string(f[2]) + ")";
        if (j - i == 1) {
            const Vec3 &p = mesh.points[f[0]], &q = mesh.points[f[1]], &r = mesh.points[f[2]];
            bool on_box = false;
            for (std::size_t d = 0; d < 3; ++d)
                on_box = on_box || (p[d] == lo[d] && q[d] == lo[d] && r[d] == lo[d]) ||
                         (p[d] == hi[d] && q[d] == hi[d] && r[d] == hi[d]);
            if (!on_box)
                bad.push_back(name + " has one tetrahedron but is not on the domain boundary");
        } else if (j - i == 2) {
            if (faces[i].second == faces[i + 1].second)
                bad.push_back(name + ": its two tetrahedra disagree in orientation");
        } else {
            bad.push_back(name + " is shared by " + std::to_string(j - i) + " tetrahedra");
        }
        i = j;
    }
    detail::append_vertex_problems<3>(mesh.points, used, bad);
    return CheckReport::of_problems(std::move(bad));
}

DihedralRangeDeg dihedral_range_deg(const OctMesh3& mesh) {
    DihedralRangeDeg r;
    constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                  {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    for (const auto& t : mesh.tets) {
        // Measured in the tetrahedron's exact unit frame (scaled_frame.hpp).
        const UnitPoints<4> c = to_unit(std::array<Point3, 4>{
            mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]});
        for (const auto& e : kEdges) {
            // The dihedral angle at edge pq is the angle between the components of
            // (a - p) and (b - p) orthogonal to q - p.
            const Vec3& p = c.p[e[0]];
            const Vec3 axis = normalized(c.p[e[1]] - p);
            Vec3 u = c.p[e[2]] - p, w = c.p[e[3]] - p;
            u -= dot(u, axis) * axis;
            w -= dot(w, axis) * axis;
            const double deg =
                std::atan2(norm(cross(u, w)), dot(u, w)) * 180.0 / std::numbers::pi;
            r.min = std::min(r.min, deg);
            r.max = std::max(r.max, deg);
        }
    }
    return r;
}

double min_dihedral_deg(const OctMesh3& mesh) { return dihedral_range_deg(mesh).min; }
double max_dihedral_deg(const OctMesh3& mesh) { return dihedral_range_deg(mesh).max; }

}  // namespace dynmesh
