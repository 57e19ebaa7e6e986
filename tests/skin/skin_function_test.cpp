#include "dynmesh/skin/skin_function.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"

namespace dynmesh {
namespace {

/// Φ(x) = min over λ in the simplex of ‖x − z_b‖²/s − w_b (§1.4), by brute force: the minimum
/// of this convex problem is a stationary point on some face of at most 4 balls (the objective
/// depends on λ only through (z_b, Σλ_i(‖z_i‖² − w_i)) in R⁴), so every face of up to four
/// balls is solved on its affine hull and the feasible (λ ≥ 0) stationary values compared.
double brute_force_phi(const std::vector<WeightedPoint>& B, double s, const Point3& x) {
    const std::size_t n = B.size();
    double best = std::numeric_limits<double>::infinity();
    const auto value = [&](const std::vector<int>& S, const std::vector<double>& lam) {
        Point3 zb{0, 0, 0};
        double c = 0;
        for (std::size_t i = 0; i < S.size(); ++i) {
            const WeightedPoint& b = B[std::size_t(S[i])];
            zb = zb + lam[i] * b.center;
            c += lam[i] * (sqnorm(b.center) - b.weight);
        }
        const double wb = sqnorm(zb) - c;
        return sqnorm(x - zb) / s - wb;
    };
    std::vector<int> S;
    const auto solve_face = [&]() {
        // λ = (1 − Σμ, μ_1..μ_d); f is quadratic in μ: f = (1/s − 1)‖z_b‖² − 2x·z_b/s + Σλ_i c_i + ‖x‖²/s.
        const std::size_t d = S.size() - 1;
        const Point3 z0 = B[std::size_t(S[0])].center;
        const double c0 = sqnorm(z0) - B[std::size_t(S[0])].weight;
        std::vector<Vec3> e(d);
        std::vector<double> dc(d);
        for (std::size_t i = 0; i < d; ++i) {
            e[i] = B[std::size_t(S[i + 1])].center - z0;
            dc[i] = sqnorm(B[std::size_t(S[i + 1])].center) - B[std::size_t(S[i + 1])].weight - c0;
        }
        // ∂f/∂μ_i = 2(1/s − 1) z_b·e_i − 2x·e_i/s + dc_i = 0 with z_b = z0 + Σ μ_j e_j.
        const double a = 1 / s - 1;
        std::vector<std::vector<double>> M(d, std::vector<double>(d + 1));
        for (std::size_t i = 0; i < d; ++i) {
            for (std::size_t j = 0; j < d; ++j) M[i][j] = 2 * a * dot(e[i], e[j]);
            M[i][d] = -(2 * a * dot(z0, e[i]) - 2 * dot(x, e[i]) / s + dc[i]);
        }
        for (std::size_t c = 0; c < d; ++c) {
            std::size_t p = c;
            for (std::size_t i = c + 1; i < d; ++i)
                if (std::fabs(M[i][c]) > std::fabs(M[p][c])) p = i;
            if (std::fabs(M[p][c]) < 1e-12) return;  // affinely dependent balls: skip
            std::swap(M[c], M[p]);
            for (std::size_t i = 0; i < d; ++i)
                if (i != c) {
                    const double f = M[i][c] / M[c][c];
                    for (std::size_t j = c; j <= d; ++j) M[i][j] -= f * M[c][j];
                }
        }
        std::vector<double> lam(d + 1);
        double sum = 0;
        for (std::size_t i = 0; i < d; ++i) {
            lam[i + 1] = M[i][d] / M[i][i];
            sum += lam[i + 1];
        }
        lam[0] = 1 - sum;
        for (double l : lam)
            if (l < -1e-12) return;
        best = std::min(best, value(S, lam));
    };
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i; j < n; ++j)
            for (std::size_t k = j; k < n; ++k)
                for (std::size_t l = k; l < n; ++l) {
                    S.clear();
                    for (std::size_t v : {i, j, k, l})
                        if (std::find(S.begin(), S.end(), int(v)) == S.end()) S.push_back(int(v));
                    solve_face();
                }
    return best;
}

std::vector<WeightedPoint> random_balls(Rng& rng, int n) {
    std::vector<WeightedPoint> B;
    for (int i = 0; i < n; ++i)
        B.push_back({{rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5)}, rng.uniform(0.3, 2.0)});
    return B;
}

/// §6.1 S1 (with §8 correction 4: the brute force includes the bounding points, and the
/// tolerance is absolute since Φ crosses 0).
TEST(SkinFunction, AgreesWithTheBruteForceMinimum) {
    Rng rng(11);
    for (double s : {0.5, 0.3, 0.8})
        for (int n : {1, 2, 3, 5}) {
            SCOPED_TRACE(testing::Message() << "s " << s << ", " << n << " balls");
            const SkinFunction phi(random_balls(rng, n), s);
            for (int q = 0; q < 200; ++q) {
                const Point3 x{rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3)};
                const double expect = brute_force_phi(phi.balls(), s, x);
                ASSERT_NEAR(phi.value(x), expect, 1e-8 * (1 + std::fabs(expect))) << x.x << " " << x.y << " " << x.z;
            }
        }
}

/// The mixed cells tile space: every point is in at least one, and the gradient is that of Φ
/// (finite differences), so Φ is C¹ across the cells' faces (§6.1 S2).
/// The walk (§1.5) ends in a cell that holds the point, with the value of the cell the scan
/// finds, from any start; on 200 balls it needs no fallback to the scan.
TEST(SkinFunction, WalkFindsTheCellOfThePoint) {
    Rng rng(17);
    std::vector<WeightedPoint> B;
    for (int i = 0; i < 200; ++i)
        B.push_back({{rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(-6, 6)}, rng.uniform(0.5, 3.0)});
    const SkinFunction phi(B, 0.5);
    std::size_t hint = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const Point3 x{rng.uniform(-9, 9), rng.uniform(-9, 9), rng.uniform(-9, 9)};
        const std::size_t start = trial % 2 ? hint : std::size_t(rng.uniform() * double(phi.simplices().size()));
        const std::size_t k = phi.locate(x, start);
        EXPECT_TRUE(phi.in_mixed_cell(k, x)) << trial;
        const std::size_t scan = phi.locate_by_scan(x);
        EXPECT_NEAR(phi.evaluate_in(k, x).value, phi.evaluate_in(scan, x).value, 1e-9 * (1 + std::fabs(phi.evaluate_in(scan, x).value)));
        hint = k;
    }
    EXPECT_EQ(phi.locate_fallbacks(), 0u);
    // The simplex index of ball sets.
    const SkinSimplex& sx = phi.simplices()[phi.simplices().size() / 2];
    std::array<int, 4> rev{sx.vertices[3], sx.vertices[2], sx.vertices[1], sx.vertices[0]};
    std::rotate(rev.begin(), rev.begin() + (3 - sx.dim), rev.end());
    EXPECT_EQ(phi.find_simplex(rev, sx.dim + 1), phi.simplices().size() / 2);
}

TEST(SkinFunction, GradientMatchesFiniteDifferencesEverywhere) {
    Rng rng(5);
    for (double s : {0.5, 0.3}) {
        const SkinFunction phi(random_balls(rng, 6), s);
        int checked = 0;
        for (int q = 0; q < 300; ++q) {
            const Point3 x{rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3)};
            const SkinEvaluation ev = phi.evaluate(x);
            ASSERT_TRUE(phi.in_mixed_cell(ev.simplex, x));
            const double h = 1e-6;
            const Vec3 fd{(phi.value(x + Vec3{h, 0, 0}) - phi.value(x - Vec3{h, 0, 0})) / (2 * h),
                          (phi.value(x + Vec3{0, h, 0}) - phi.value(x - Vec3{0, h, 0})) / (2 * h),
                          (phi.value(x + Vec3{0, 0, h}) - phi.value(x - Vec3{0, 0, h})) / (2 * h)};
            EXPECT_LT(norm(fd - ev.gradient), 1e-5 * (1 + norm(ev.gradient)));
            ++checked;
        }
        EXPECT_EQ(checked, 300);
    }
}

/// Two balls: the points of the shared face of two adjacent mixed cells get the same value and
/// gradient from both quadrics (C¹, S2), found by bisection between points of the two cells.
TEST(SkinFunction, AdjacentQuadricsAgreeOnTheirCommonFace) {
    Rng rng(8);
    const SkinFunction phi(random_balls(rng, 5), 0.5);
    int faces = 0;
    for (int q = 0; q < 400 && faces < 100; ++q) {
        Point3 a{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)};
        Point3 b = a + 0.3 * rng.unit_vector();
        const std::size_t ka = phi.evaluate(a).simplex, kb = phi.evaluate(b).simplex;
        if (ka == kb) continue;
        for (int it = 0; it < 60; ++it) {
            const Point3 m = 0.5 * (a + b);
            (phi.in_mixed_cell(ka, m) ? a : b) = m;
        }
        if (!phi.in_mixed_cell(ka, a) || !phi.in_mixed_cell(kb, b)) continue;
        const SkinEvaluation ea = phi.evaluate_in(ka, a), eb = phi.evaluate_in(kb, a);
        EXPECT_NEAR(ea.value, eb.value, 1e-9 * (1 + std::fabs(ea.value)));
        EXPECT_LT(norm(ea.gradient - eb.gradient), 1e-7 * (1 + norm(ea.gradient)));
        ++faces;
    }
    EXPECT_GT(faces, 20);
}

/// §1.6 at s = 1/2: ϱ(x) = ‖x − z_δ‖, 1-Lipschitz over random pairs; and ϱ is the inverse of the
/// largest normal curvature of the level set, measured by finite differences of the unit
/// normal along tangent directions (S4).
TEST(SkinFunction, LengthScaleIsLipschitzAndTheInverseCurvature) {
    Rng rng(3);
    const SkinFunction phi(random_balls(rng, 6), 0.5);
    for (int q = 0; q < 2000; ++q) {
        const Point3 x{rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3)};
        const Point3 y = x + rng.uniform(0, 1) * rng.unit_vector();
        const SkinEvaluation ex = phi.evaluate(x), ey = phi.evaluate(y);
        EXPECT_NEAR(ex.rho, norm(x - phi.simplices()[ex.simplex].z), 1e-9 * (1 + ex.rho));
        EXPECT_LE(std::fabs(ex.rho - ey.rho), distance(x, y) * (1 + 1e-9) + 1e-12);
    }
    for (double s : {0.5, 0.3})
        for (int q = 0; q < 200; ++q) {
            const SkinFunction f(random_balls(rng, 4), s);
            const Point3 x{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)};
            const SkinEvaluation ev = f.evaluate(x);
            const std::size_t k = ev.simplex;
            const Vec3 n = normalized(ev.gradient);
            const Vec3 a = std::fabs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
            const Vec3 t1 = normalized(a - dot(a, n) * n), t2 = cross(n, t1);
            // Shape operator S(t) = dn/dt (within the cell's quadric), by central differences.
            const double h = 1e-6 * std::max(ev.rho, 1e-3);
            const auto dn = [&](const Vec3& t) {
                return (normalized(f.evaluate_in(k, x + h * t).gradient) - normalized(f.evaluate_in(k, x - h * t).gradient)) /
                       (2 * h);
            };
            const Vec3 s1 = dn(t1), s2 = dn(t2);
            const double m11 = dot(s1, t1), m12 = 0.5 * (dot(s1, t2) + dot(s2, t1)), m22 = dot(s2, t2);
            const double mean = 0.5 * (m11 + m22), rad = std::hypot(0.5 * (m11 - m22), m12);
            const double kappa = std::max(std::fabs(mean + rad), std::fabs(mean - rad));
            EXPECT_NEAR(kappa * ev.rho, 1, 1e-4) << "s " << s;
        }
}

/// §6.1 S5: the closed-form trajectory stays on the level t of its quadric and matches RK4
/// integration of v = ∇Φ/‖∇Φ‖² (in the same cell's quadric).
TEST(SkinFunction, ClosedFormFlowMatchesRungeKutta) {
    Rng rng(21);
    const SkinFunction phi(random_balls(rng, 6), 0.5);
    int runs = 0;
    for (int q = 0; q < 300; ++q) {
        const Point3 x0{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)};
        const SkinEvaluation e0 = phi.evaluate(x0);
        const std::size_t k = e0.simplex;
        if (e0.rho < 0.2) continue;  // keep away from the quadric's centre, where the speed blows up
        const double t0 = e0.value, t1 = t0 + rng.uniform(-0.5, 0.5) * e0.rho * e0.rho;
        const Point3 x1 = phi.flow_in_cell(k, x0, t1);
        EXPECT_NEAR(phi.evaluate_in(k, x1).value, t1, 1e-12 * (1 + std::fabs(t1) + std::fabs(phi.simplices()[k].W)));
        // RK4 in t with 2000 steps.
        const auto v = [&](const Point3& x) {
            const Vec3 g = phi.evaluate_in(k, x).gradient;
            return g / sqnorm(g);
        };
        Point3 x = x0;
        const int steps = 2000;
        const double h = (t1 - t0) / steps;
        for (int i = 0; i < steps; ++i) {
            const Vec3 k1 = v(x), k2 = v(x + 0.5 * h * k1), k3 = v(x + 0.5 * h * k2), k4 = v(x + h * k3);
            x = x + (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4);
        }
        EXPECT_LT(distance(x, x1), 1e-8 * (1 + e0.rho)) << q;
        ++runs;
    }
    EXPECT_GT(runs, 100);
    const SkinFunction other({{{0, 0, 0}, 1}}, 0.3);
    EXPECT_THROW((void)other.flow_in_cell(0, {1, 0, 0}, 0), InvalidInput);
}

TEST(SkinFunction, OneBallIsItsShrunkSphereAndInputsAreChecked) {
    // One ball (z, w): Φ = ‖x − z‖²/s − w near it, so the skin at t = 0 is the sphere of radius
    // √(s·w) (the van der Waals sphere when w = r²/s), untouched by the bounding points.
    const double r = 1.7, s = 0.5;
    const SkinFunction phi({{{0.3, -0.2, 0.1}, r * r / s}}, s);
    Rng rng(2);
    for (int q = 0; q < 100; ++q) {
        const Point3 x = Point3{0.3, -0.2, 0.1} + r * rng.unit_vector();
        EXPECT_NEAR(phi.value(x), 0, 1e-12);
    }
    EXPECT_EQ(phi.input_balls(), 1u);
    EXPECT_EQ(phi.balls().size(), 7u);
    EXPECT_THROW(SkinFunction({}, 0.5), InvalidInput);
    EXPECT_THROW(SkinFunction({{{0, 0, 0}, 1}}, 1.0), InvalidInput);
    EXPECT_THROW(SkinFunction({{{0, 0, std::nan("")}, 1}}, 0.5), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
