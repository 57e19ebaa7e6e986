// The Python module `dynmesh`: meshes as NumPy arrays (vertices float64 (n, 3), faces int64
// (m, 3)) in and out, reports as dicts with the CLI's JSON field names, library errors as
// Python exceptions (InvalidInput and TopologyError: ValueError; IoError: OSError;
// InternalError: RuntimeError). Long calls release the GIL.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cstdint>
#include <string>

#include "dynmesh/error.hpp"
#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/flips/flip_smooth.hpp"
#include "dynmesh/flips/worsen.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/version.hpp"

namespace py = pybind11;
using namespace dynmesh;

namespace {

using Vertices = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Faces = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

/// An InvalidInput unless `a` has shape (rows, 3).
void require_rows_of_3(const py::array& a, const char* what, const char* rows) {
    if (a.ndim() == 2 && a.shape(1) == 3) return;
    throw InvalidInput(std::string(what) + " must be an array of shape (" + rows + ", 3), not of " + std::to_string(a.ndim()) +
                       " dimension(s)" + (a.ndim() == 2 ? " with " + std::to_string(a.shape(1)) + " columns" : ""));
}

/// The mesh of the arrays (checked: shapes, finite coordinates, indices in range, a manifold).
SurfaceMesh mesh_of(const Vertices& vertices, const Faces& faces) {
    require_rows_of_3(vertices, "vertices", "n");
    require_rows_of_3(faces, "faces", "m");
    TriangleSoup soup;
    const auto v = vertices.unchecked<2>();
    const auto f = faces.unchecked<2>();
    const py::ssize_t n = v.shape(0);
    soup.points.reserve(std::size_t(n));
    for (py::ssize_t i = 0; i < n; ++i) {
        const Point3 p{v(i, 0), v(i, 1), v(i, 2)};
        if (!is_finite(p)) throw InvalidInput("vertex " + std::to_string(i) + " has a coordinate that is not finite");
        soup.points.push_back(p);
    }
    soup.triangles.reserve(std::size_t(f.shape(0)));
    for (py::ssize_t i = 0; i < f.shape(0); ++i) {
        std::array<std::uint32_t, 3> t{};
        for (int k = 0; k < 3; ++k) {
            const std::int64_t idx = f(i, k);
            if (idx < 0 || idx >= n)
                throw InvalidInput("face " + std::to_string(i) + " refers to vertex " + std::to_string(idx) + ", not in [0, " +
                                   std::to_string(n) + ")");
            t[std::size_t(k)] = std::uint32_t(idx);
        }
        soup.triangles.push_back(t);
    }
    return SurfaceMesh::from_soup(soup);
}

/// The faces of a mesh without garbage, as a fresh array owned by Python, corners from the
/// tail of each face's halfedge: the order the faces were given in.
Faces faces_of(const SurfaceMesh& mesh) {
    Faces faces({py::ssize_t(mesh.n_faces()), py::ssize_t(3)});
    auto f = faces.mutable_unchecked<2>();
    for (Face x : mesh.faces()) {
        const Halfedge h = mesh.halfedge(x);
        f(x.idx(), 0) = mesh.from_vertex(h).idx();
        f(x.idx(), 1) = mesh.to_vertex(h).idx();
        f(x.idx(), 2) = mesh.to_vertex(mesh.next(h)).idx();
    }
    return faces;
}

/// The vertices of a mesh without garbage, as a fresh array owned by Python.
Vertices vertices_of(const SurfaceMesh& mesh) {
    Vertices vertices({py::ssize_t(mesh.n_vertices()), py::ssize_t(3)});
    auto v = vertices.mutable_unchecked<2>();
    for (Vertex x : mesh.vertices()) {
        const Point3& p = mesh.position(x);
        v(x.idx(), 0) = p.x;
        v(x.idx(), 1) = p.y;
        v(x.idx(), 2) = p.z;
    }
    return vertices;
}

}  // namespace

PYBIND11_MODULE(dynmesh, m) {
    m.doc() = "dynmesh: meshes that stay good while the thing they describe changes.\n\n"
              "Meshes are NumPy arrays: vertices float64 of shape (n, 3), faces int64 of shape (m, 3).";
    m.attr("__version__") = kVersion;

    // Most derived first: pybind11 tries the translators in reverse order of registration.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const IoError& e) {
            PyErr_SetString(PyExc_OSError, e.what());
        } catch (const InvalidInput& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const TopologyError& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const InternalError& e) {
            PyErr_SetString(PyExc_RuntimeError, e.what());
        }
    });

    m.def(
        "read_mesh",
        [](const std::string& path) {
            SurfaceMesh mesh;
            {
                py::gil_scoped_release unlocked;
                mesh = read_mesh(path);
            }
            mesh.garbage_collection();
            return py::make_tuple(vertices_of(mesh), faces_of(mesh));
        },
        py::arg("path"),
        "Reads a closed or open triangle mesh (.off .obj .ply .stl); returns (vertices, faces).\n"
        "Raises OSError when the file cannot be read, ValueError when it is malformed.");

    m.def(
        "write_mesh",
        [](const std::string& path, const Vertices& vertices, const Faces& faces) {
            const SurfaceMesh mesh = mesh_of(vertices, faces);
            py::gil_scoped_release unlocked;
            write_mesh(mesh, path);
        },
        py::arg("path"), py::arg("vertices"), py::arg("faces"),
        "Writes the mesh (.off .obj .ply .vtk .vtp, by the extension).");

    m.def(
        "flip",
        [](const Vertices& vertices, const Faces& faces, const std::string& criterion, double feature_angle_deg) {
            SurfaceMesh mesh = mesh_of(vertices, faces);
            const FlipRule rule = parse_flip_rule(criterion);
            FlipReport r;
            {
                py::gil_scoped_release unlocked;
                r = flip_all(mesh, {.rule = rule, .feature_angle_deg = feature_angle_deg});
            }
            py::dict report;
            report["criterion"] = std::string(to_string(rule));
            report["vertices"] = mesh.n_vertices();
            report["faces"] = mesh.n_faces();
            report["edges"] = mesh.n_edges();
            report["flips"] = r.flips;
            report["checks"] = r.checks;
            report["pushes"] = r.pushes;
            report["degenerate_tests"] = r.degenerate;
            report["not_improving_tests"] = r.not_improving;
            report["feature_angle_deg"] = feature_angle_deg;
            report["feature_locked_tests"] = r.feature_locked;
            report["converged"] = r.converged;
            report["renumbered"] = r.renumbered;
            report["seconds_flip"] = r.seconds;
            return py::make_tuple(faces_of(mesh), report);
        },
        py::arg("vertices"), py::arg("faces"), py::arg("criterion") = "angle", py::arg("feature_angle_deg") = 180.0,
        "Flips edges until none is flippable under the criterion ('angle': Definition 3 of the\n"
        "edge-flip paper; 'diametric': the diametric-ball rule; 'planar'); returns (faces, report).\n"
        "Vertices never move. The report has the field names of `dynmesh flip --report`.");

    m.def(
        "worsen",
        [](const Vertices& vertices, const Faces& faces, std::size_t rounds, double probability,
           double min_dihedral_deg, std::uint64_t seed) {
            SurfaceMesh mesh = mesh_of(vertices, faces);
            WorsenReport r;
            double seconds = 0;
            {
                py::gil_scoped_release unlocked;
                const auto t0 = std::chrono::steady_clock::now();
                r = worsen(mesh, {.rounds = rounds, .probability = probability, .min_dihedral_deg = min_dihedral_deg,
                                  .seed = seed});
                seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            }
            py::dict report;
            report["vertices"] = mesh.n_vertices();
            report["faces"] = mesh.n_faces();
            report["flips"] = r.flips;
            report["attempts"] = r.attempts;
            report["rejected"] = r.rejected;
            report["rounds"] = rounds;
            report["seed"] = seed;
            report["seconds_worsen"] = seconds;
            return py::make_tuple(faces_of(mesh), report);
        },
        py::arg("vertices"), py::arg("faces"), py::arg("rounds") = 5, py::arg("probability") = 0.5,
        py::arg("min_dihedral_deg") = 120.0, py::arg("seed") = 1,
        "Random edge flips (each edge tried with the given probability per round; a flip that\n"
        "makes a dihedral angle smaller than min_dihedral_deg is undone), reproducible by seed;\n"
        "returns (faces, report) with the field names of `dynmesh worsen --report`.");
}
