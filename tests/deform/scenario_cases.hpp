#pragma once
/// \file The scenarios shared by the tests of scenario.cpp, warp.cpp, sample_edits.cpp and
/// ground_truth.cpp (small sizes, each built once per test program), and their helpers.

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/deform/scenario.hpp"
#include "dynmesh/error.hpp"
#include "test_support.hpp"

namespace dynmesh::test {

inline constexpr std::size_t kSamples = 2000;
inline constexpr int kSteps = 20;

inline std::string blobby() { return shared_data("meshes/blobby.off").string(); }

/// Every scenario the tests build, once each (small sizes).
inline std::vector<std::string> all_cases() {
    return {"pulse",     "stretch",   "twist",     "bend",      "rotate",
            "dimple",    "mesh+bend", "mesh+twist", "mesh+pulse"};
}

/// The scenario of a case of all_cases(), built on first use.
inline const Scenario& cached(const std::string& key) {
    static std::map<std::string, std::unique_ptr<Scenario>> cache;
    auto it = cache.find(key);
    if (it != cache.end()) return *it->second;
    ScenarioOptions o;
    o.samples = kSamples;
    o.steps = kSteps;
    std::string name = key;
    if (key.rfind("mesh+", 0) == 0) {
        name = blobby();
        o.warp = key.substr(5);
    }
    auto s = std::make_unique<Scenario>(make_scenario(name, o));
    return *cache.emplace(key, std::move(s)).first->second;
}

/// The reference mesh of s carried to time t.
inline SurfaceMesh warped_reference(const Scenario& s, double t) {
    SurfaceMesh m = s.reference;
    warp_points(s, t, s.reference.positions(), m.positions());
    return m;
}

/// Every pool index of s.
inline std::vector<std::uint32_t> all_pool(const Scenario& s) {
    std::vector<std::uint32_t> v(s.pool_size());
    std::iota(v.begin(), v.end(), 0u);
    return v;
}

/// 0 .. vertices_size() - 1: vertex i as pool point i.
inline std::vector<std::uint32_t> identity_vertex_pool(const SurfaceMesh& m) {
    std::vector<std::uint32_t> v(m.vertices_size());
    std::iota(v.begin(), v.end(), 0u);
    return v;
}

/// f() throws InvalidInput with `needle` in its message.
template <class F>
void expect_invalid(F&& f, const std::string& needle) {
    try {
        f();
        ADD_FAILURE() << "no InvalidInput thrown (expected a message with '" << needle << "')";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
            << "message: " << e.what() << "\nexpected to contain: " << needle;
    }
}

}  // namespace dynmesh::test
