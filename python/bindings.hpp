#pragma once
// One function per capability adds its functions and classes to the module.
#include <pybind11/pybind11.h>

namespace dynmesh::python {

void bind_flips(pybind11::module_& m);      // flip, worsen, quality
void bind_deform(pybind11::module_& m);     // DeformingMesh
void bind_quadtree(pybind11::module_& m);   // DynQuadMesh2, DynQuadMesh3, DynOffCenterMesh2
void bind_probing(pybind11::module_& m);    // probe, probe_curve
void bind_skin(pybind11::module_& m);       // skin, grow_skin, read_molecule

}  // namespace dynmesh::python
