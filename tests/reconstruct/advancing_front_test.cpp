#include "dynmesh/reconstruct/advancing_front.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/mesh/check.hpp"
#include "dynmesh/shapes/analytic.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

void expect_vertices_are_samples(const AdvancingFrontResult& r, std::span<const Point3> samples) {
    ASSERT_EQ(r.report.vertex_sample.size(), r.mesh.n_vertices());
    EXPECT_TRUE(std::is_sorted(r.report.vertex_sample.begin(), r.report.vertex_sample.end()));
    for (Vertex v : r.mesh.vertices()) {
        const Point3& p = r.mesh.position(v);
        const Point3& s = samples[r.report.vertex_sample[v.idx()]];
        ASSERT_TRUE(p.x == s.x && p.y == s.y && p.z == s.z) << "vertex " << v.idx();
    }
    EXPECT_EQ(r.report.vertices_used + r.report.unused_samples, samples.size());
}

/// The first three columns of a whitespace-separated text file.
std::vector<Point3> read_xyz(const std::string& path) {
    std::ifstream in(path);
    std::vector<Point3> out;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        Point3 p;
        if (ls >> p.x >> p.y >> p.z) out.push_back(p);
    }
    return out;
}

TEST(AdvancingFront, SphereSamples) {
    const Sphere sphere({1, 2, 3}, 2);
    for (std::uint64_t seed : {1u, 2u}) {
        const auto samples = sphere.sample_uniform(4000, seed);
        const auto r = reconstruct_advancing_front_with_report(samples);
        const auto check = check_mesh(r.mesh, {.require_closed = true});
        EXPECT_TRUE(check.ok()) << check.summary("  ");
        EXPECT_EQ(check.integer("euler"), 2);
        EXPECT_TRUE(r.report.closed);
        EXPECT_GT(test::signed_volume(r.mesh), 0);
        EXPECT_NEAR(test::signed_volume(r.mesh) / (4 * kPi / 3 * 8), 1, 0.02);
        expect_vertices_are_samples(r, samples);
    }
}

TEST(AdvancingFront, Kitten) {
    const auto samples = read_xyz(test::shared_data("points3d/kitten.xyz").string());
    ASSERT_GT(samples.size(), 5000u);
    const auto r = reconstruct_advancing_front_with_report(samples);
    const auto check = check_mesh(r.mesh, {.require_closed = true});
    EXPECT_TRUE(check.ok()) << check.summary("  ");
    EXPECT_EQ(check.integer("components"), 1);
    EXPECT_EQ(check.integer("euler"), 0);  // the kitten's tail makes a handle: genus 1
    EXPECT_EQ(r.report.unused_samples, 0u);
    EXPECT_GT(test::signed_volume(r.mesh), 0);
    expect_vertices_are_samples(r, samples);
}

TEST(AdvancingFront, OpenSurfaceNeedsRequireClosedFalse) {
    const Sphere sphere({0, 0, 0}, 1);
    std::vector<Point3> cap;  // the upper half of a sphere: a disc
    for (const Point3& p : sphere.sample_uniform(3000, 4))
        if (p.z > 0) cap.push_back(p);
    try {
        (void)reconstruct_advancing_front(cap);
        ADD_FAILURE() << "open surface accepted";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("boundary edges"), std::string::npos) << e.what();
    }
    const auto r = reconstruct_advancing_front_with_report(cap, {.require_closed = false});
    const auto check = check_mesh(r.mesh);
    EXPECT_TRUE(check.ok()) << check.summary("  ");
    EXPECT_FALSE(r.report.closed);
    EXPECT_GT(r.report.boundary_edges, 0u);
    EXPECT_LE(check.integer("euler"), 1);  // a disc, or an annulus when CGAL leaves a hole at the rim
    expect_vertices_are_samples(r, cap);
}

TEST(AdvancingFront, RejectsBadInput) {
    std::vector<Point3> flat;
    for (int k = 0; k < 30; ++k) flat.push_back({std::cos(k * 0.2), std::sin(k * 0.2), 0});
    EXPECT_THROW((void)reconstruct_advancing_front(flat), InvalidInput);
    auto samples = Sphere({0, 0, 0}, 1).sample_uniform(100, 1);
    samples[9] = samples[2];
    EXPECT_THROW((void)reconstruct_advancing_front(samples), InvalidInput);
    EXPECT_THROW((void)reconstruct_advancing_front(std::vector<Point3>(3)), InvalidInput);
}

}  // namespace
}  // namespace dynmesh
