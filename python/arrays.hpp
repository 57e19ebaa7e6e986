#pragma once
// NumPy arrays in and out of the module: shapes checked with messages that name the argument,
// meshes built from (vertices, faces), and results handed to Python without a copy where the
// library's vector can be adopted (the array then owns it through a capsule).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh::python {

namespace py = pybind11;

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Indices = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

/// An InvalidInput unless `a` has shape (rows, cols).
void require_shape(const py::array& a, const char* what, const char* rows, py::ssize_t cols);

/// The points of an (n, 3) array; with `finite`, every coordinate must be finite (else the
/// library checks the points it uses).
[[nodiscard]] std::vector<Point3> points3_of(const Doubles& a, const char* what, bool finite = true);
/// The points of an (n, 2) array, as points3_of.
[[nodiscard]] std::vector<Vec2> points2_of(const Doubles& a, const char* what, bool finite = true);
/// One point of a sequence of `D` numbers, as points3_of.
[[nodiscard]] Point3 point3_of(const Doubles& a, const char* what, bool finite = true);
[[nodiscard]] Vec2 point2_of(const Doubles& a, const char* what, bool finite = true);

/// An integer array as int64 (a float array is refused rather than truncated).
[[nodiscard]] Indices indices_of(const py::array& a, const char* what);

/// The triangle soup of the arrays (checked: shapes, integer faces, indices in range).
[[nodiscard]] TriangleSoup soup_of(std::vector<Point3> points, const py::array& faces);

/// The mesh of the arrays (checked: shapes, finite coordinates, indices in range, a manifold).
[[nodiscard]] SurfaceMesh mesh_of(const Doubles& vertices, const py::array& faces);

/// The arrays of a mesh without garbage (vertices (n, 3), faces (m, 3), corners from the tail
/// of each face's halfedge: the order the faces were given in).
[[nodiscard]] Doubles vertices_of(const SurfaceMesh& mesh);
[[nodiscard]] Indices faces_of(const SurfaceMesh& mesh);

/// The live vertices and faces of a mesh that may hold garbage, numbered compactly in handle
/// order; `kept` receives the handle of each output vertex.
[[nodiscard]] py::tuple compact_arrays_of(const SurfaceMesh& mesh, std::vector<Vertex>* kept = nullptr);

/// An (n, K) array that owns `rows` (moved into a capsule: no copy). T is an arithmetic type or
/// a struct of K doubles laid out like double[K] (Vec2, Vec3).
template <class Scalar, std::size_t K, class T>
py::array_t<Scalar> adopt(std::vector<T>&& rows) {
    static_assert(sizeof(T) == K * sizeof(Scalar), "rows must be K scalars each");
    auto* owned = new std::vector<T>(std::move(rows));
    py::capsule base(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<Scalar>({py::ssize_t(owned->size()), py::ssize_t(K)},
                               {py::ssize_t(sizeof(T)), py::ssize_t(sizeof(Scalar))},
                               reinterpret_cast<const Scalar*>(owned->data()), base);
}

/// A 1-D array that owns `values` (no copy).
template <class T>
py::array_t<T> adopt_flat(std::vector<T>&& values) {
    auto* owned = new std::vector<T>(std::move(values));
    py::capsule base(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>({py::ssize_t(owned->size())}, {py::ssize_t(sizeof(T))}, owned->data(), base);
}

}  // namespace dynmesh::python
