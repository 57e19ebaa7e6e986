// The Python module `dynmesh`: meshes as NumPy arrays (vertices float64 (n, 3), faces int64
// (m, 3)) in and out, reports as dicts with the CLI's JSON field names, library errors as
// Python exceptions (InvalidInput and TopologyError: ValueError; IoError: OSError;
// InternalError: RuntimeError). Long calls release the GIL.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/version.hpp"

namespace py = pybind11;
using namespace dynmesh;
using namespace dynmesh::python;

PYBIND11_MODULE(dynmesh, m) {
    m.doc() = "dynmesh: meshes that stay good while the thing they describe changes.\n\n"
              "Surface meshes are NumPy arrays: vertices float64 of shape (n, 3), faces int64 of shape\n"
              "(m, 3). The dynamic meshes return their points as float64 and their simplices as uint32\n"
              "(the library's own storage, handed over without a copy). Reports are dicts with the\n"
              "field names of the command line's --report. Errors: ValueError for invalid input,\n"
              "OSError for files, RuntimeError for an internal error.";
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
        "Raises OSError when the file cannot be read or is malformed (naming the file and line),\n"
        "ValueError when its triangles do not form an oriented manifold.");

    m.def(
        "write_mesh",
        [](const std::string& path, const Doubles& vertices, const py::array& faces) {
            const SurfaceMesh mesh = mesh_of(vertices, faces);
            py::gil_scoped_release unlocked;
            write_mesh(mesh, path);
        },
        py::arg("path"), py::arg("vertices"), py::arg("faces"),
        "Writes the mesh (.off .obj .ply .stl .vtk .vtp, by the extension).");

    bind_flips(m);
    bind_deform(m);
    bind_quadtree(m);
    bind_probing(m);
    bind_skin(m);
}
