// The Python module `freeform` (docs/python.md): freeform.Error and the bindings of lattice.cpp
// and geometry.cpp. A front end on the document layer (docs/architecture.md), like cli/.

#include "arrays.h"

#include <pybind11/pybind11.h>

#include <freeform/core/error.h>

namespace ffpy {
void bindLattice(pybind11::module_& m);
void bindGeometry(pybind11::module_& m);
void bindNurbs(pybind11::module_& m);
} // namespace ffpy

PYBIND11_MODULE(freeform, m)
{
    m.doc() = "freeform: Bézier, rational Bézier and NURBS curves and surfaces, splines, meshes and free-form deformation lattices "
              "on NumPy arrays (docs/python.md).";
    // freeform::Error -> freeform.Error (a ValueError, carrying the library's message as is).
    pybind11::register_exception<freeform::Error>(m, "Error", PyExc_ValueError);
    m.attr("__version__") = "0.1.0";
    ffpy::bindLattice(m);
    ffpy::bindGeometry(m);
    ffpy::bindNurbs(m); // after bindLattice: adds Lattice.deform_curve
    // For the tests of docs/python.md "Arrays": the array Lattice.deform / bind / det_j /
    // deform_normals read for their points (ffpy::rows, the helper they call): the argument itself
    // for float64/float32 C-contiguous (N, 3) arrays, a float64 copy made once otherwise.
    m.def(
        "_points_as_read", [](pybind11::handle points) { return ffpy::rows(points, "points", 3); }, pybind11::arg("points"),
        "The array the deformation calls read for `points` (the argument itself when its layout allows).");
}
