#pragma once
/// \file Fixtures and checkers shared by the tests.

#include <cstdint>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh::test {

/// Path of a file in ../shared/data (the real inputs).
std::filesystem::path shared_data(const std::string& relative);
/// A fresh, empty scratch directory for one test.
std::filesystem::path scratch_dir(const std::string& name);
/// An octahedron (6 vertices, closed, outward oriented).
SurfaceMesh octahedron();
/// A closed icosphere of the given subdivision level (level 0: icosahedron), radius 1.
SurfaceMesh icosphere(int level);
/// Volume enclosed by a closed mesh (positive when outward oriented).
double signed_volume(const SurfaceMesh& mesh);
/// A planar square grid of n x n quads split into triangles (open, with boundary).
SurfaceMesh grid(int n);
/// Empty when a and b are the same mesh element for element (connectivity of every
/// halfedge, vertex and face, positions bit for bit, deletion flags); else the first
/// difference, in words.
std::string mesh_difference(const SurfaceMesh& a, const SurfaceMesh& b);
/// The mesh with its vertices, edges and faces renumbered at random (random_mesh_order).
SurfaceMesh shuffled(SurfaceMesh mesh, std::uint64_t seed);

/// The IoError message of `f()`, or a failure when it throws something else or nothing.
template <class F>
std::string io_error_of(F&& f) {
    try {
        f();
    } catch (const IoError& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected IoError, got another exception: " << e.what();
        return {};
    }
    ADD_FAILURE() << "expected IoError, nothing thrown";
    return {};
}

}  // namespace dynmesh::test
