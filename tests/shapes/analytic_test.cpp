#include "dynmesh/shapes/analytic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/random.hpp"
#include "dynmesh/geometry/triangle.hpp"

namespace dynmesh {
namespace {

struct Case {
    std::string name;
    std::shared_ptr<const ImplicitSurface> surface;
};

std::vector<Case> cases() {
    return {
        {"sphere", std::make_shared<Sphere>(Point3{1, -2, 0.5}, 2.5)},
        {"ellipsoid 3,1,2", std::make_shared<Ellipsoid>(Point3{0.3, 0.1, -0.2}, 3, 1, 2)},
        {"oblate 2,2,1", std::make_shared<Ellipsoid>(Point3{}, 2, 2, 1)},
        {"prolate 1,3,1", std::make_shared<Ellipsoid>(Point3{-1, 0, 0}, 1, 3, 1)},
        {"ellipsoid 1,1,1", std::make_shared<Ellipsoid>(Point3{0, 0, 1}, 1, 1, 1)},
        {"torus 5,3", std::make_shared<Torus>(Point3{0, 0, 1}, 5, 3)},
        {"torus 2,0.5", std::make_shared<Torus>(Point3{1, 2, 3}, 2, 0.5)},
    };
}

/// A length scale of the surface (half the bbox diagonal) for relative tolerances.
double scale_of(const ImplicitSurface& s) { return 0.5 * s.bbox().diagonal(); }

/// Uniform random point in the surface's bounding box grown by half its size on each side.
Point3 random_query(const ImplicitSurface& s, Rng& rng) {
    const Bbox3 b = s.bbox();
    const Vec3 ext = b.max - b.min;
    return {rng.uniform(b.min.x - 0.5 * ext.x, b.max.x + 0.5 * ext.x),
            rng.uniform(b.min.y - 0.5 * ext.y, b.max.y + 0.5 * ext.y),
            rng.uniform(b.min.z - 0.5 * ext.z, b.max.z + 0.5 * ext.z)};
}

Vec3 numeric_gradient(const ImplicitSurface& s, const Point3& p, double h) {
    Vec3 g;
    for (std::size_t k = 0; k < 3; ++k) {
        Vec3 e;
        e[k] = h;
        g[k] = (s.value(p + e) - s.value(p - e)) / (2 * h);
    }
    return g;
}

TEST(AnalyticSurface, ClosestPointIsOnTheSurfaceAndNearest) {
    for (const auto& [name, s] : cases()) {
        const double scale = scale_of(*s);
        const std::size_t n_dense = 60000;
        const auto dense = s->sample_uniform(n_dense, 99);
        // Largest empty patch among uniform samples is a few times the mean spacing.
        const double spacing = std::sqrt(s->area() / static_cast<double>(n_dense));
        Rng rng(5);
        for (int q = 0; q < 120; ++q) {
            const Point3 x = random_query(*s, rng);
            const Point3 cp = s->closest_point(x);
            const double d = distance(x, cp);
            EXPECT_LT(std::abs(s->value(cp)), 1e-13 * scale) << name << " query " << q;
            EXPECT_NEAR(std::abs(s->signed_distance(x)), d, 1e-13 * scale) << name;
            EXPECT_EQ(s->signed_distance(x) < 0, s->value(x) < 0) << name;
            double brute = std::numeric_limits<double>::infinity();
            for (const Point3& p : dense) brute = std::min(brute, distance(x, p));
            EXPECT_GE(brute, d - 1e-12 * scale) << name << ": a sample is nearer than cp";
            EXPECT_LE(brute, d + 4 * spacing) << name << ": cp is not the nearest point";
        }
    }
}

TEST(AnalyticSurface, NormalIsTheGradientDirection) {
    for (const auto& [name, s] : cases()) {
        const double scale = scale_of(*s);
        Rng rng(11);
        for (int q = 0; q < 200; ++q) {
            const Point3 x = random_query(*s, rng);
            const Point3 cp = s->closest_point(x);
            const Vec3 n = s->normal(x);
            EXPECT_NEAR(norm(n), 1.0, 1e-14) << name;
            const Vec3 g = numeric_gradient(*s, cp, 1e-6 * scale);
            EXPECT_LT(angle_between(n, g), 1e-6) << name << " query " << q;
            // x - cp runs along the normal, with the signed distance as its length.
            const Vec3 off = x - cp;
            EXPECT_LT(norm(off - s->signed_distance(x) * n), 1e-11 * scale) << name;
        }
    }
}

TEST(AnalyticSurface, OffsetsAlongTheNormalProjectBack) {
    // p + t n(p) has nearest point p and signed distance t while |t| < lfs(p); outside a
    // sphere or ellipsoid any t > 0 works. This pins the closest point to ~1e-12 relative.
    for (const auto& [name, s] : cases()) {
        const double scale = scale_of(*s);
        const bool convex = name.find("torus") == std::string::npos;
        Rng rng(3);
        double worst = 0;
        for (const Point3& p : s->sample_uniform(500, 17)) {
            const Vec3 n = s->normal(p);
            const double lfs = s->local_feature_size(p);
            const double hi = convex ? 3 * scale : 0.95 * lfs;
            for (double t : {-0.95 * lfs, -0.5 * lfs, -1e-9 * scale, 1e-9 * scale,
                             rng.uniform(-0.95 * lfs, hi), hi}) {
                const Point3 x = p + t * n;
                worst = std::max(worst, distance(s->closest_point(x), p) / scale);
                EXPECT_NEAR(s->signed_distance(x), t, 1e-12 * scale) << name << " t=" << t;
            }
        }
        EXPECT_LT(worst, 1e-12) << name;
    }
}

TEST(AnalyticSurface, ReachAndLocalFeatureSize) {
    const Sphere sphere({1, 1, 1}, 2);
    EXPECT_DOUBLE_EQ(sphere.reach(), 2);
    const Torus t53({0, 0, 0}, 5, 3), t205({0, 0, 0}, 2, 0.5);
    EXPECT_DOUBLE_EQ(t53.reach(), 2);  // the z-axis is 5 - 3 from the inner equator
    EXPECT_DOUBLE_EQ(t205.reach(), 0.5);
    EXPECT_DOUBLE_EQ(t53.local_feature_size({2, 0, 0}), 2);
    EXPECT_DOUBLE_EQ(t53.local_feature_size({8, 0, 0}), 3);
    EXPECT_DOUBLE_EQ(t53.local_feature_size({5, 0, 3}), 3);
    const Ellipsoid e({0, 0, 0}, 3, 1, 2);
    EXPECT_DOUBLE_EQ(e.reach(), 1.0 / 3.0);  // smallest radius of curvature b^2 / a
    EXPECT_NEAR(e.local_feature_size({3, 0, 0}), 1.0 / 3.0, 1e-15);
    EXPECT_NEAR(e.local_feature_size({0, 1, 0}), 1.0, 1e-15);  // medial region ends at z=0
    for (const auto& [name, s] : cases()) {
        double lo = std::numeric_limits<double>::infinity();
        for (const Point3& p : s->sample_uniform(20000, 4)) {
            const double lfs = s->local_feature_size(p);
            EXPECT_GE(lfs, s->reach() * (1 - 1e-12)) << name;
            lo = std::min(lo, lfs);
        }
        EXPECT_NEAR(lo, s->reach(), 0.05 * s->reach()) << name;  // attained somewhere
    }
}

TEST(AnalyticSurface, EllipsoidMedialAxisIsTheFocalRegion) {
    // Semi-axes 3 (x), 1 (y), 2 (z): the medial axis lies in the plane y = 0, inside the
    // ellipse with semi-axes (9 - 1) / 3 along x and (4 - 1) / 2 along z.
    const Ellipsoid e({0, 0, 0}, 3, 1, 2);
    const double mx = 8.0 / 3.0, mz = 1.5;
    Rng rng(8);
    std::vector<Point3> medial;
    while (medial.size() < 4000) {
        const double u = rng.uniform(-1, 1), w = rng.uniform(-1, 1);
        if (u * u + w * w <= 1) medial.push_back({mx * u, 0, mz * w});
    }
    for (const Point3& q : medial) {
        // Two nearest points, mirror images in the plane y = 0.
        const Point3 a = e.closest_point(q + Vec3{0, 1e-9, 0});
        const Point3 b = e.closest_point(q - Vec3{0, 1e-9, 0});
        EXPECT_GT(distance(a, b), 1e-3 * (1 - std::hypot(q.x / mx, q.z / mz))) << q.x;
    }
    for (int k = 0; k < 200; ++k) {  // just outside the region, nearest points stay in-plane
        const double phi = rng.uniform(0, 2 * kPi), grow = rng.uniform(1.01, 1.1);
        const Point3 q{grow * mx * std::cos(phi), 0, grow * mz * std::sin(phi)};
        EXPECT_LT(std::abs(e.closest_point(q + Vec3{0, 1e-9, 0}).y), 1e-6);
    }
    // lfs(p) is the distance from p to this region.
    for (const Point3& p : e.sample_uniform(200, 2)) {
        double best = std::numeric_limits<double>::infinity();
        for (const Point3& q : medial) best = std::min(best, distance(p, q));
        const double lfs = e.local_feature_size(p);
        EXPECT_LE(lfs, best + 1e-12);
        EXPECT_LE(best, lfs + 0.1);
    }
}

/// Area by the midpoint rule on u = z / c in [-1, 1], phi in [0, 2 pi).
double ellipsoid_band_area(double a, double b, double c, double u0, double u1, int nu, int nphi) {
    double sum = 0;
    for (int i = 0; i < nu; ++i) {
        const double u = u0 + (u1 - u0) * (i + 0.5) / nu, s2 = 1 - u * u;
        for (int j = 0; j < nphi; ++j) {
            const double phi = 2 * kPi * (j + 0.5) / nphi;
            const double cp = std::cos(phi), sp = std::sin(phi);
            sum += std::sqrt(b * b * c * c * s2 * cp * cp + a * a * c * c * s2 * sp * sp +
                             a * a * b * b * u * u);
        }
    }
    return sum * (u1 - u0) / nu * 2 * kPi / nphi;
}

TEST(AnalyticSurface, Area) {
    EXPECT_DOUBLE_EQ(Sphere({}, 2).area(), 16 * kPi);
    EXPECT_DOUBLE_EQ(Torus({}, 5, 3).area(), 4 * kPi * kPi * 15);
    EXPECT_NEAR(Ellipsoid({}, 1.5, 1.5, 1.5).area(), 9 * kPi, 1e-13);
    // Spheroids in closed form.
    {
        const double a = 2, c = 1, ecc = std::sqrt(1 - c * c / (a * a));
        const double oblate = 2 * kPi * a * a * (1 + (1 - ecc * ecc) / ecc * std::atanh(ecc));
        EXPECT_NEAR(Ellipsoid({}, a, a, c).area() / oblate, 1, 1e-13);
        EXPECT_NEAR(Ellipsoid({}, c, a, a).area() / oblate, 1, 1e-13);  // any axis order
    }
    {
        const double a = 3, b = 1, ecc = std::sqrt(1 - b * b / (a * a));
        const double prolate = 2 * kPi * b * b * (1 + a / (b * ecc) * std::asin(ecc));
        EXPECT_NEAR(Ellipsoid({}, b, a, b).area() / prolate, 1, 1e-13);
    }
    for (const auto& abc :
         {Vec3{3, 1, 2}, Vec3{1, 2, 3}, Vec3{10, 1, 0.1}, Vec3{1, 1 + 1e-9, 1 - 1e-9}}) {
        const double q = ellipsoid_band_area(abc.x, abc.y, abc.z, -1, 1, 2000, 2000);
        EXPECT_NEAR(Ellipsoid({}, abc.x, abc.y, abc.z).area() / q, 1, 2e-6)
            << abc.x << "," << abc.y << "," << abc.z;
    }
}

TEST(AnalyticSurface, BboxAndInteriorPoint) {
    for (const auto& [name, s] : cases()) {
        const Bbox3 b = s->bbox();
        EXPECT_LT(s->value(s->interior_point()), 0) << name;
        Bbox3 seen;
        for (const Point3& p : s->sample_uniform(20000, 6)) {
            seen.extend(p);
            for (std::size_t k = 0; k < 3; ++k) {
                EXPECT_GE(p[k], b.min[k] - 1e-12 * b.diagonal()) << name;
                EXPECT_LE(p[k], b.max[k] + 1e-12 * b.diagonal()) << name;
            }
        }
        for (std::size_t k = 0; k < 3; ++k) {  // tight: samples reach near every face
            EXPECT_LT(seen.min[k] - b.min[k], 0.02 * b.diagonal()) << name;
            EXPECT_LT(b.max[k] - seen.max[k], 0.02 * b.diagonal()) << name;
        }
        // Far outside the box the value is positive.
        EXPECT_GT(s->value(b.max + (b.max - b.min)), 0) << name;
    }
}

TEST(AnalyticSurface, SamplingIsReproducibleAndOnTheSurface) {
    for (const auto& [name, s] : cases()) {
        const auto a = s->sample_uniform(1000, 7), b = s->sample_uniform(1000, 7);
        ASSERT_EQ(a.size(), 1000u);
        EXPECT_TRUE(a == b) << name;  // bit-identical
        const auto prefix = s->sample_uniform(10, 7);
        EXPECT_TRUE(std::equal(prefix.begin(), prefix.end(), a.begin())) << name;
        const auto c = s->sample_uniform(1000, 8);
        EXPECT_FALSE(a == c) << name;
        for (const Point3& p : a) EXPECT_LT(std::abs(s->signed_distance(p)), 1e-14 * scale_of(*s));
        EXPECT_TRUE(s->sample_uniform(0, 1).empty());
    }
}

/// Pearson's chi-square of observed counts against expected probabilities.
double chi_square(const std::vector<double>& observed, const std::vector<double>& prob) {
    double n = 0;
    for (double o : observed) n += o;
    double chi2 = 0;
    for (std::size_t k = 0; k < observed.size(); ++k) {
        const double e = n * prob[k];
        chi2 += (observed[k] - e) * (observed[k] - e) / e;
    }
    return chi2;
}

// With 40 bins (39 degrees of freedom) chi-square has mean 39 and standard deviation ~8.8;
// 90 is beyond the 99.999% quantile. The seeds are fixed, so the outcome is too.
constexpr double kChi2Bound = 90;

TEST(AnalyticSurface, TorusSamplingIsAreaUniform) {
    const double R = 5, r = 3;
    const Torus torus({1, -1, 2}, R, r);
    const int bins = 40;
    std::vector<double> counts(bins, 0), prob(bins), flat(bins, 1.0 / bins);
    for (const Point3& p : torus.sample_uniform(200000, 21)) {
        const Vec3 d = p - torus.center();
        const double v = std::atan2(d.z, std::hypot(d.x, d.y) - R);  // tube angle
        const int k = std::clamp(static_cast<int>((v + kPi) / (2 * kPi) * bins), 0, bins - 1);
        counts[static_cast<std::size_t>(k)] += 1;
    }
    for (int k = 0; k < bins; ++k) {  // density (R + r cos v) / (2 pi R) in v
        const double v0 = -kPi + 2 * kPi * k / bins, v1 = -kPi + 2 * kPi * (k + 1) / bins;
        prob[static_cast<std::size_t>(k)] =
            (R * (v1 - v0) + r * (std::sin(v1) - std::sin(v0))) / (2 * kPi * R);
    }
    EXPECT_LT(chi_square(counts, prob), kChi2Bound);
    EXPECT_GT(chi_square(counts, flat), 1000);  // the test can tell uniform-in-angle apart
}

TEST(AnalyticSurface, EllipsoidSamplingIsAreaUniform) {
    const double a = 3, b = 1, c = 2;
    const Ellipsoid e({0.5, 0, 0}, a, b, c);
    const int bins = 40;
    std::vector<double> counts(bins, 0), prob(bins), sphere_like(bins, 1.0 / bins);
    for (const Point3& p : e.sample_uniform(200000, 22)) {
        const double u = p.z / c;  // uniform on the unit sphere would give flat counts
        const int k = std::clamp(static_cast<int>((u + 1) / 2 * bins), 0, bins - 1);
        counts[static_cast<std::size_t>(k)] += 1;
    }
    for (int k = 0; k < bins; ++k) {
        const double u0 = -1 + 2.0 * k / bins, u1 = -1 + 2.0 * (k + 1) / bins;
        prob[static_cast<std::size_t>(k)] =
            ellipsoid_band_area(a, b, c, u0, u1, 50, 400) / e.area();
    }
    EXPECT_LT(chi_square(counts, prob), kChi2Bound);
    EXPECT_GT(chi_square(counts, sphere_like), 1000);
}

TEST(AnalyticSurface, SphereSamplingIsAreaUniform) {
    const Sphere s({0, 0, -3}, 2);
    const int bins = 40;
    std::vector<double> counts(bins, 0), prob(bins, 1.0 / bins);  // Archimedes: z is uniform
    for (const Point3& p : s.sample_uniform(200000, 23)) {
        const double u = (p.z + 3) / 2;
        const int k = std::clamp(static_cast<int>((u + 1) / 2 * bins), 0, bins - 1);
        counts[static_cast<std::size_t>(k)] += 1;
    }
    EXPECT_LT(chi_square(counts, prob), kChi2Bound);
}

TEST(AnalyticSurface, ConstructorsRejectBadParameters) {
    const double nan = std::nan("");
    EXPECT_THROW(Sphere({}, 0), InvalidInput);
    EXPECT_THROW(Sphere({}, -1), InvalidInput);
    EXPECT_THROW(Sphere({}, nan), InvalidInput);
    EXPECT_THROW(Sphere({nan, 0, 0}, 1), InvalidInput);
    EXPECT_THROW(Ellipsoid({}, 1, 0, 1), InvalidInput);
    EXPECT_THROW(Ellipsoid({}, 1, 1, INFINITY), InvalidInput);
    EXPECT_THROW(Torus({}, 3, 3), InvalidInput);
    EXPECT_THROW(Torus({}, 3, 5), InvalidInput);
    EXPECT_THROW(Torus({}, 3, 0), InvalidInput);
    EXPECT_THROW(Torus({}, -3, -5), InvalidInput);
    EXPECT_NO_THROW(Torus({}, 1, 0.999));
}

TEST(AnalyticSurface, MedialAxisQueriesReturnASurfacePoint) {
    const Sphere s({1, 2, 3}, 2);
    EXPECT_EQ(s.closest_point({1, 2, 3}), (Point3{3, 2, 3}));
    const Torus t({0, 0, 0}, 5, 3);
    // On the z-axis: the nearest circle's point in direction +x.
    EXPECT_NEAR(
        distance(t.closest_point({0, 0, 7}), Point3{5, 0, 0} + 3 * normalized(Vec3{-5, 0, 7})), 0,
        1e-14);
    EXPECT_EQ(t.closest_point({0, 5, 0}), (Point3{0, 8, 0}));  // on the core circle
    const Ellipsoid e({0, 0, 0}, 3, 1, 2);
    EXPECT_NEAR(distance(e.closest_point({0, 0, 0}), {0, 1, 0}), 0, 1e-15);
    EXPECT_NEAR(e.signed_distance({0, 0, 0}), -1, 1e-15);
}

}  // namespace
}  // namespace dynmesh
