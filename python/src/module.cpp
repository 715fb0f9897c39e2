// The Python module `freeform` (docs/python.md): freeform.Error and the bindings of lattice.cpp
// and geometry.cpp. A front end on the document layer (docs/architecture.md), like cli/.

#include "arrays.h"

#include <pybind11/pybind11.h>

#include <freeform/core/error.h>
#include <freeform/core/warning.h>

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
    // The library's warnings (freeform/core/warning.h) become Python warnings (UserWarning), so
    // `warnings` filters and pytest see them. The GIL is taken here: library code may warn while a
    // call has released it. A filter that turns the warning into an error cannot raise through
    // the library (it may be inside an OpenSubdiv callback), so that error is reported as
    // unraisable instead.
    freeform::setWarningHandler([](const std::string& message) {
        if (!Py_IsInitialized()) return;
        pybind11::gil_scoped_acquire gil;
        if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) != 0) PyErr_WriteUnraisable(nullptr);
    });
    ffpy::bindLattice(m);
    ffpy::bindGeometry(m);
    ffpy::bindNurbs(m); // after bindLattice: adds Lattice.deform_curve
    // For the tests of docs/python.md "Arrays": the array Lattice.bind, report and the other point
    // calls read for their points (ffpy::rows): the argument itself for float64/float32
    // C-contiguous (N, 3) arrays, a float64 copy made once otherwise. (deform, det_j and
    // deform_normals also read float64/float32 arrays of any strides in place, chunk by chunk.)
    m.def(
        "_points_as_read", [](pybind11::handle points) { return ffpy::rows(points, "points", 3); }, pybind11::arg("points"),
        "The array the deformation calls read for `points` (the argument itself when its layout allows).");
}
