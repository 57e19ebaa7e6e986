#include "surgery.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/skin/growth.hpp"

namespace dynmesh {

double mixed_cell_inradius(const SkinFunction& phi, std::size_t k) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const SkinSimplex& sx = phi.simplices().at(k);
    const auto& balls = phi.balls();
    const double s = phi.shrink();
    std::array<Point3, 4> p{};
    for (int i = 0; i <= sx.dim; ++i) p[i] = balls[sx.vertices[i]].center;
    const Point3 z = sx.z;
    double dd = inf;
    if (sx.dim == 1) {
        dd = std::min(norm(z - p[0]), norm(z - p[1]));
    } else if (sx.dim == 2) {
        for (int i = 0; i < 3; ++i) {
            const Point3 a = p[i], b = p[(i + 1) % 3];
            const Vec3 d = b - a;
            const double t = dot(z - a, d) / sqnorm(d);
            dd = std::min(dd, norm(z - (a + t * d)));
        }
    } else if (sx.dim == 3) {
        for (int i = 0; i < 4; ++i) {
            const Point3 a = p[(i + 1) % 4], b = p[(i + 2) % 4], c = p[(i + 3) % 4];
            const Vec3 n = normalized(cross(b - a, c - a));
            dd = std::min(dd, std::abs(dot(z - a, n)));
        }
    }
    double dn = inf;
    if (sx.dim < 3) {
        std::vector<Vec3> basis;  // orthonormal directions of aff δ
        for (int i = 1; i <= sx.dim; ++i) {
            Vec3 d = p[i] - p[0];
            for (const Vec3& b : basis) d = d - dot(d, b) * b;
            if (norm(d) > 0) basis.push_back(normalized(d));
        }
        const WeightedPoint& bi = balls[sx.vertices[0]];
        for (int j : sx.link) {
            const WeightedPoint& bj = balls[j];
            const double value = sqnorm(z - bj.center) - bj.weight - (sqnorm(z - bi.center) - bi.weight);
            Vec3 g = 2.0 * (bi.center - bj.center);
            for (const Vec3& b : basis) g = g - dot(g, b) * b;
            const double gn = norm(g);
            if (gn > 1e-300) dn = std::min(dn, value / gn);
        }
    }
    return std::max(0.0, std::min((1 - s) * dd, s * dn));
}

Surgery make_surgery(const SkinFunction& phi, const SkinEvent& ev, double inradius, double neighbourhood,
                     double inner) {
    Surgery s;
    s.simplex = ev.simplex;
    const SkinSimplex& sx = phi.simplices()[ev.simplex];
    s.dim = sx.dim;
    s.z = sx.z;
    s.W = ev.time;
    s.r = neighbourhood * inradius;
    const double half = 2 * inner * inner * s.r * s.r;
    s.t_on = s.W - half;
    s.t_off = s.W + half;
    const auto& balls = phi.balls();
    if (sx.dim == 1) {
        s.axis = normalized(balls[sx.vertices[1]].center - balls[sx.vertices[0]].center);
    } else if (sx.dim == 2) {
        s.axis = normalized(cross(balls[sx.vertices[1]].center - balls[sx.vertices[0]].center,
                                  balls[sx.vertices[2]].center - balls[sx.vertices[0]].center));
    }
    if (!is_finite(s.axis) || norm(s.axis) < 0.5) s.axis = Vec3{0, 0, 1};
    const Vec3 helper = std::abs(s.axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    s.e1 = normalized(cross(s.axis, helper));
    s.e2 = cross(s.axis, s.e1);
    return s;
}

bool boundary_loops(const SurfaceMesh& mesh, const std::vector<Face>& cut, std::vector<std::vector<Vertex>>& loops) {
    std::unordered_set<std::uint32_t> region;
    for (Face f : cut) region.insert(f.idx());
    std::unordered_map<std::uint32_t, Halfedge> from;  // vertex -> the boundary halfedge leaving it
    for (Face f : cut) {
        const Halfedge h0 = mesh.halfedge(f);
        Halfedge h = h0;
        do {
            const Face other = mesh.face(SurfaceMesh::twin(h));
            if (other.is_valid() && region.count(other.idx()) == 0)
                if (!from.emplace(mesh.from_vertex(h).idx(), h).second) return false;
            h = mesh.next(h);
        } while (h != h0);
    }
    loops.clear();
    std::unordered_set<std::uint32_t> used;
    for (const auto& [v, h0] : from) {
        if (used.count(v)) continue;
        std::vector<Vertex> loop;
        Halfedge h = h0;
        while (used.insert(mesh.from_vertex(h).idx()).second) {
            loop.push_back(mesh.from_vertex(h));
            const auto it = from.find(mesh.to_vertex(h).idx());
            if (it == from.end()) return false;
            h = it->second;
        }
        if (h != h0) return false;
        loops.push_back(std::move(loop));
    }
    return true;
}

namespace {

constexpr double kInfAngle = 1e300;

double wrap(double a) {
    while (a > kPi) a -= 2 * kPi;
    while (a <= -kPi) a += 2 * kPi;
    return a;
}

}  // namespace

bool plan_template(const Surgery& s, double at, const std::vector<std::vector<Vertex>>& loops,
                   const std::function<Point3(Vertex)>& position, TemplatePlan& plan) {
    if (loops.size() != 2) return false;
    plan = {};
    std::array<double, 2> side{};
    for (int k = 0; k < 2; ++k) {
        for (Vertex v : loops[k]) side[k] += dot(position(v) - s.z, s.axis);
        side[k] /= double(loops[k].size());
    }
    if (side[0] * side[1] >= 0) return false;
    const int plus = side[0] > 0 ? 0 : 1;
    const bool one_sheeted = s.dim == 1 ? at > s.W : at < s.W;
    const double d = std::sqrt(std::abs(at - s.W) / 2);
    const auto old_vertex = [](Vertex v) { return TemplateVertex{false, 0, v}; };
    const auto new_vertex = [](std::size_t i) { return TemplateVertex{true, static_cast<std::uint32_t>(i), Vertex()}; };
    if (!one_sheeted) {
        for (int k = 0; k < 2; ++k) {
            const std::size_t apex = plan.points.size();
            plan.points.push_back(s.z + (k == plus ? d : -d) * s.axis);
            const auto& loop = loops[k];
            for (std::size_t i = 0; i < loop.size(); ++i)
                plan.triangles.push_back({old_vertex(loop[i]), old_vertex(loop[(i + 1) % loop.size()]), new_vertex(apex)});
        }
        return true;
    }
    const std::size_t mean = (loops[0].size() + loops[1].size() + 1) / 2;
    const std::size_t n = std::clamp<std::size_t>(mean, 8, 64);
    for (std::size_t j = 0; j < n; ++j) {
        const double th = 2 * kPi * double(j) / double(n);
        plan.points.push_back(s.z + d * (std::cos(th) * s.e1 + std::sin(th) * s.e2));
    }
    const auto angle = [&](Vertex v) {
        const Vec3 u = position(v) - s.z;
        return std::atan2(dot(u, s.e2), dot(u, s.e1));
    };
    for (const auto& loop : loops) {
        const std::size_t m = loop.size();
        std::vector<double> phi(m + 1);
        phi[0] = angle(loop[0]);
        for (std::size_t i = 1; i <= m; ++i) phi[i] = phi[i - 1] + wrap(angle(loop[i % m]) - angle(loop[i - 1]));
        const double total = phi[m] - phi[0];
        if (std::abs(total) < kPi) return false;  // the loop does not go around the axis
        const int dir = total > 0 ? 1 : -1;
        // The ring vertex at or just behind the loop's start, in the loop's direction.
        std::size_t j0 = 0;
        double best = -1;
        for (std::size_t j = 0; j < n; ++j) {
            double delta = std::fmod(dir * (2 * kPi * double(j) / double(n) - phi[0]), 2 * kPi);
            if (delta < 0) delta += 2 * kPi;
            if (delta > best) {
                best = delta;
                j0 = j;
            }
        }
        const double r0 = best - 2 * kPi;
        const auto ring = [&](std::size_t j) {
            const long long idx = (static_cast<long long>(j0) + dir * static_cast<long long>(j % n)) % static_cast<long long>(n);
            return new_vertex(static_cast<std::size_t>((idx + static_cast<long long>(n)) % static_cast<long long>(n)));
        };
        std::size_t i = 0, j = 0;
        while (i < m || j < n) {
            const double pl = i < m ? dir * (phi[i + 1] - phi[0]) : kInfAngle;
            const double pr = j < n ? r0 + 2 * kPi * double(j + 1) / double(n) : kInfAngle;
            if (j == n || (i < m && pl <= pr)) {
                plan.triangles.push_back({old_vertex(loop[i]), old_vertex(loop[(i + 1) % m]), ring(j)});
                ++i;
            } else {
                plan.triangles.push_back({old_vertex(loop[i % m]), ring(j + 1), ring(j)});
                ++j;
            }
        }
    }
    return true;
}

}  // namespace dynmesh
