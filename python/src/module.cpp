// The Python module `freeform` (docs/python.md): freeform.Error, the kind table (kinds()) and the
// bindings of lattice.cpp and lattice_points.cpp, geometry.cpp, nurbs.cpp and nurbs_surface.cpp. A
// front end on the document layer (docs/architecture.md), like cli/.

#include "arrays.h"

#include <pybind11/pybind11.h>

#include <freeform/core/error.h>
#include <freeform/core/warning.h>
#include <freeform/document/kinds.h>

namespace ffpy {
void bindLattice(pybind11::module_& m);
void bindLatticeWeights(pybind11::module_& m);
void bindGeometry(pybind11::module_& m);
void bindNurbs(pybind11::module_& m);
void bindNurbsSurfaces(pybind11::module_& m);
void bindPart(pybind11::module_& m);
} // namespace ffpy

namespace {

/// One row of the kind table (document/kinds.h) as a dict.
pybind11::dict kindDict(const freeform::KindInfo& k)
{
    using Op = freeform::KindOperation;
    static const std::pair<Op, const char*> operations[] = {
        {Op::Evaluate, "evaluate"},   {Op::Polyline, "polyline"},         {Op::Tessellate, "tessellate"},
        {Op::Deform, "deform"},       {Op::Continuity, "continuity"},     {Op::ConvertSpline, "convert_spline"},
        {Op::ToNurbs, "to_nurbs"},    {Op::FromNurbs, "from_nurbs"},      {Op::DeformsOthers, "deforms_others"}};
    static const char* const natures[] = {"curve", "surface", "volume", "brep"}; // KindNature's order
    static const char* const parameters[] = {"t", "uv", "face_uv", "stu"};
    pybind11::list ops;
    for (const auto& [op, name] : operations)
        if (k.supports(op)) ops.append(name);
    pybind11::dict d;
    d["name"] = std::string(k.name);
    d["summary"] = std::string(k.summary);
    d["nature"] = natures[static_cast<int>(k.nature)];
    d["parameters"] = parameters[static_cast<int>(k.parameters)];
    d["dimension"] = k.dimension;
    d["rational"] = k.rational;
    d["knots"] = k.knots;
    d["pieces"] = k.pieces;
    d["operations"] = ops;
    return d;
}

} // namespace

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
    m.def(
        "kinds",
        [] {
            pybind11::list out;
            for (const freeform::KindInfo& k : freeform::objectKinds()) out.append(kindDict(k));
            return out;
        },
        "The kind table (docs/architecture.md): one dict per document object kind, in the format's order, with "
        "name, summary, nature ('curve', 'surface', 'volume'), parameters ('t', 'uv', 'face_uv', 'stu'), dimension "
        "(0: 2 or 3), rational, knots, pieces and the operations it supports.");
    ffpy::bindLattice(m);
    ffpy::bindLatticeWeights(m); // after bindLattice: adds Lattice.weights, weights_matvec, weights_rmatvec
    ffpy::bindGeometry(m);
    ffpy::bindNurbs(m);
    ffpy::bindNurbsSurfaces(m); // after bindNurbs and bindLattice: adds Lattice.deform_curve
    ffpy::bindPart(m); // after bindNurbs and bindNurbsSurfaces: returns their classes
    // For the tests of docs/python.md "Arrays": the array Lattice.bind, report and the other point
    // calls read for their points (ffpy::rows): the argument itself for float64/float32
    // C-contiguous (N, 3) arrays, a float64 copy made once otherwise. (deform, det_j and
    // deform_normals also read float64/float32 arrays of any strides in place, chunk by chunk.)
    m.def(
        "_points_as_read", [](pybind11::handle points) { return ffpy::rows(points, "points", 3); }, pybind11::arg("points"),
        "The array the deformation calls read for `points` (the argument itself when its layout allows).");
}
