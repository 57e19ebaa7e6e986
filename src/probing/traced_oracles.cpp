/// Torus and genus-2 surface: sphere tracing then bisection (probe_common.hpp).
#include <algorithm>
#include <cmath>

#include "dynmesh/error.hpp"
#include "dynmesh/probing/oracles.hpp"
#include "probe_common.hpp"

namespace dynmesh {
namespace {

/// Smallest tracing step: a chord inside O shorter than this penetrates less than τ
/// (depth ≤ chord² / (8 · reach)).
double min_step(double reach, double tau) { return std::sqrt(8 * reach * tau); }

/// Sphere tracing of `shape` (sd, value, closest, normal) under the shared conventions.
template <class Object, class Sd, class Value, class Closest, class Normal>
std::optional<ProbeHit> trace(const Object& self, const Point3& s, const Vec3& d, double t_max,
                              bool strict, Sd&& sd, Value&& value, Closest&& closest,
                              Normal&& normal, auto&& accept) {
    const double tau = self.tolerance();
    std::optional<ProbeHit> out;
    if (std::fabs(sd(s)) <= tau && dot(normal(s), d) < detail::kGrazingCos) {
        // On S and entering (or tangent): a hit at t = 0.
        ProbeHit hit{closest(s), 0, false};
        if (accept(hit, dot(normal(s), d), t_max, strict, false)) return hit;
    }
    const auto finish = [&](double t, bool stalled) {
        const Point3 x = s + t * d;
        ProbeHit hit{stalled ? closest(x) : x, t, false};
        if (!accept(hit, stalled ? 0.0 : dot(normal(x), d), t_max, strict, stalled)) return false;
        out = hit;
        return true;
    };
    detail::sphere_trace(s, d, t_max, tau, min_step(self.reach(), tau), sd, value, finish);
    return out;
}

}  // namespace

// ---- torus -------------------------------------------------------------------------------

TorusOracle::TorusOracle(const Torus& torus, OracleOptions options)
    : ProbeObject(torus.major_radius() + torus.minor_radius(), options), shape_(torus) {}

double TorusOracle::signed_distance(const Point3& p) const { return shape_.signed_distance(p); }

double TorusOracle::diameter() const {
    return 2 * (shape_.major_radius() + shape_.minor_radius());
}

std::vector<Point3> TorusOracle::sample_surface(double spacing) const {
    DYNMESH_CHECK(std::isfinite(spacing) && spacing > 0,
                  "GroundTruth::sample_surface: the spacing must be a positive number");
    const double n = std::ceil(area() / (spacing * spacing));
    DYNMESH_CHECK(n <= 1e8, "GroundTruth::sample_surface: spacing too small (more than 1e8 points)");
    return shape_.sample_uniform(static_cast<std::size_t>(std::max(n, 1.0)), 1);
}

std::optional<ProbeHit> TorusOracle::cast_checked(const Point3& s, const Vec3& d, double t_max,
                                                  bool strict) const {
    return trace(
        *this, s, d, t_max, strict, [&](const Point3& p) { return shape_.signed_distance(p); },
        [&](const Point3& p) { return shape_.value(p); },
        [&](const Point3& p) { return shape_.closest_point(p); },
        [&](const Point3& p) { return shape_.normal(p); },
        [&](ProbeHit& h, double c, double tm, bool st, bool stall) {
            return accept(h, c, tm, st, stall);
        });
}

// ---- genus 2 -----------------------------------------------------------------------------

namespace {
constexpr double kG2Offset = 1.25, kG2Major = 1.0, kG2Minor = 0.4, kG2Blend = 0.6;
}

Genus2Oracle::Genus2Oracle(OracleOptions options)
    : ProbeObject(kG2Offset + kG2Major + kG2Minor, options),
      left_({-kG2Offset, 0, 0}, kG2Major, kG2Minor),
      right_({kG2Offset, 0, 0}, kG2Major, kG2Minor) {}

Bbox3 Genus2Oracle::bbox() {
    // f ≥ min(a, b) − k/4: f < 0 only within k/4 of a torus.
    const double hx = kG2Offset + kG2Major + kG2Minor + kG2Blend / 4;
    const double hy = kG2Major + kG2Minor + kG2Blend / 4;
    const double hz = kG2Minor + kG2Blend / 4;
    return {{-hx, -hy, -hz}, {hx, hy, hz}};
}

double Genus2Oracle::value(const Point3& p) const {
    const double a = left_.signed_distance(p), b = right_.signed_distance(p);
    const double h = std::max(kG2Blend - std::fabs(a - b), 0.0) / kG2Blend;
    return std::min(a, b) - 0.25 * kG2Blend * h * h;
}

Vec3 Genus2Oracle::gradient(const Point3& p) const {
    const double a = left_.signed_distance(p), b = right_.signed_distance(p);
    const double h = std::max(kG2Blend - std::fabs(a - b), 0.0) / kG2Blend;
    const Vec3 na = left_.normal(p), nb = right_.normal(p);
    return a <= b ? (1 - 0.5 * h) * na + 0.5 * h * nb : (1 - 0.5 * h) * nb + 0.5 * h * na;
}

namespace {
/// Newton projection onto f = 0 along the gradient.
template <class F, class G>
Point3 project(Point3 p, F&& f, G&& g) {
    for (int i = 0; i < 50; ++i) {
        const double v = f(p);
        const Vec3 n = g(p);
        const double nn = sqnorm(n);
        if (nn == 0) break;
        const Vec3 step = n * (v / nn);
        p -= step;
        if (norm(step) < 1e-15) break;
    }
    return p;
}
}  // namespace

double Genus2Oracle::distance(const Point3& p) const {
    const auto f = [&](const Point3& q) { return value(q); };
    const auto g = [&](const Point3& q) { return gradient(q); };
    return std::max(std::fabs(value(p)), dynmesh::distance(p, project(p, f, g)));
}

double Genus2Oracle::area() const {
    // Coarea formula: area = ∫ |∇f| δ(f) dV, δ smoothed to a box of half-width w on a grid.
    const Bbox3 b = bbox();
    constexpr double g = 0.02, w = 0.02;
    double sum = 0;
    for (double x = b.min.x + g / 2; x < b.max.x; x += g)
        for (double y = b.min.y + g / 2; y < b.max.y; y += g)
            for (double z = b.min.z + g / 2; z < b.max.z; z += g) {
                const Point3 p{x, y, z};
                if (std::fabs(value(p)) < w) sum += norm(gradient(p));
            }
    return sum * g * g * g / (2 * w);
}

std::vector<Point3> Genus2Oracle::sample_surface(double spacing) const {
    DYNMESH_CHECK(std::isfinite(spacing) && spacing > 0,
                  "GroundTruth::sample_surface: the spacing must be a positive number");
    const Bbox3 b = bbox();
    const double cells = (b.max.x - b.min.x) * (b.max.y - b.min.y) * (b.max.z - b.min.z) /
                         (spacing * spacing * spacing);
    DYNMESH_CHECK(cells <= 1e8, "GroundTruth::sample_surface: spacing too small");
    std::vector<Point3> out;
    // Sign changes of f along the grid lines parallel to x, y and z, refined by bisection.
    for (int axis = 0; axis < 3; ++axis) {
        Vec3 e{};
        e[static_cast<std::size_t>(axis)] = spacing;
        for (double x = b.min.x; x <= b.max.x; x += spacing)
            for (double y = b.min.y; y <= b.max.y; y += spacing)
                for (double z = b.min.z; z <= b.max.z; z += spacing) {
                    const Point3 p{x, y, z}, q = p + e;
                    const double fp = value(p), fq = value(q);
                    if ((fp < 0) == (fq < 0)) continue;
                    double lo = 0, hi = 1;
                    for (int i = 0; i < 60; ++i) {
                        const double mid = 0.5 * (lo + hi);
                        ((value(p + mid * e) < 0) == (fp < 0) ? lo : hi) = mid;
                    }
                    out.push_back(p + 0.5 * (lo + hi) * e);
                }
    }
    return out;
}

std::optional<ProbeHit> Genus2Oracle::cast_checked(const Point3& s, const Vec3& d, double t_max,
                                                   bool strict) const {
    const auto f = [&](const Point3& p) { return value(p); };
    const auto g = [&](const Point3& p) { return gradient(p); };
    return trace(
        *this, s, d, t_max, strict, f, f, [&](const Point3& p) { return project(p, f, g); },
        [&](const Point3& p) { return normalized(gradient(p)); },
        [&](ProbeHit& h, double c, double tm, bool st, bool stall) {
            return accept(h, c, tm, st, stall);
        });
}

}  // namespace dynmesh
