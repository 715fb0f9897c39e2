#pragma once
// Shared by the geometry bindings (geometry.cpp: curves, splines, patches, documents, meshes;
// nurbs.cpp and nurbs_surface.cpp: the rational and NURBS types): the Python-side object structs
// and the array helpers for many parameters at once (docs/python.md).

#include "arrays.h"

#include <pybind11/stl.h>

#include <freeform/curve/bezier_curve.h>
#include <freeform/curve/bezier_spline.h>
#include <freeform/curve/continuity.h>
#include <freeform/curve/nurbs_continuity.h>
#include <freeform/curve/nurbs_curve.h>
#include <freeform/curve/rational_bezier_curve.h>
#include <freeform/document/document.h>
#include <freeform/mesh/polygon_mesh.h>
#include <freeform/surface/bezier_surface.h>
#include <freeform/surface/nurbs_surface.h>
#include <freeform/surface/rational_bezier_surface.h>

#include <algorithm>
#include <string>
#include <variant>

namespace ffpy {

using Curve2 = freeform::BezierCurve<double, 2>;
using Curve3 = freeform::BezierCurve<double, 3>;
using Spline2 = freeform::BezierSpline<double, 2>;
using Spline3 = freeform::BezierSpline<double, 3>;

struct PyCurve {
    std::variant<Curve2, Curve3> c;
};
struct PySpline {
    std::variant<Spline2, Spline3> s;
};
struct PyPatch {
    freeform::BezierSurface<double, 3> p;
};

/// (N, D) array of control points (D = 2 or 3) as a D x N matrix.
template <int D>
inline freeform::PointMatrix<double, D> columns(const py::array& a, const std::string& what)
{
    const auto n = static_cast<std::size_t>(a.shape(0));
    const double* p = static_cast<const double*>(a.data());
    requireFiniteRows(p, n, D, what);
    return Eigen::Map<const freeform::PointMatrix<double, D>>(p, D, static_cast<Eigen::Index>(n));
}

inline py::array pointsAnyDim(py::handle h, const std::string& what, int& dim)
{
    py::array a = numericArray(h, what);
    if (a.ndim() != 2 || (a.shape(1) != 2 && a.shape(1) != 3))
        throw freeform::Error(what + ": expected an array of shape (N, 2) or (N, 3), got shape " + shapeText(a));
    dim = static_cast<int>(a.shape(1));
    return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
}

/// f(t) -> Dim x (K+1) for every t: an (T, K+1, D) array (or (T, D) when K is None).
template <int D, typename F>
py::array_t<double> sampleJets(const py::array_t<double, py::array::c_style>& ts, int order, bool squeeze, F&& f)
{
    const auto n = static_cast<py::ssize_t>(ts.size());
    py::array_t<double> out = squeeze ? py::array_t<double>({n, py::ssize_t{D}})
                                      : py::array_t<double>({n, py::ssize_t{order + 1}, py::ssize_t{D}});
    const double* t = ts.data();
    double* o = out.mutable_data();
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < n; ++i) {
            const Eigen::Matrix<double, D, Eigen::Dynamic> j = f(t[i], order);
            std::copy(j.data(), j.data() + j.size(), o + i * D * (order + 1));
        }
    }
    return out;
}

inline void requireInDomain(const py::array_t<double, py::array::c_style>& ts, double end, const std::string& what)
{
    for (py::ssize_t i = 0; i < ts.size(); ++i) {
        const double t = ts.data()[i];
        if (!(t >= 0 && t <= end))
            throw freeform::Error(what + ": parameter " + num(t) + " (index " + std::to_string(i) + ") outside [0, " +
                                  num(end) + "]");
    }
}

inline py::dict continuityDict(const freeform::JointContinuity<double>& j)
{
    py::dict d;
    d["joint"] = j.joint;
    d["t"] = j.t;
    d["C"] = j.C;
    d["G"] = j.G;
    d["jumps"] = j.jumps;
    return d;
}

/// The continuity report of the 2D or 3D curve held in `curves` (a spline or a NURBS curve),
/// computed without the GIL, one continuityDict per joint.
template <typename Variant>
py::list continuityList(const Variant& curves)
{
    py::list out;
    std::visit(
        [&](const auto& c) {
            const auto report = [&] {
                py::gil_scoped_release release;
                return freeform::continuityReport(c);
            }();
            for (const auto& j : report) out.append(continuityDict(j));
        },
        curves);
    return out;
}

inline py::tuple meshArrays(const freeform::PolygonMesh& mesh)
{
    // Faces: (F, k) int32 when every face has k corners, else a list of lists.
    py::object faces;
    bool uniform = mesh.faceCount() > 0;
    for (int f = 1; f < mesh.faceCount() && uniform; ++f) uniform = mesh.faceSize(f) == mesh.faceSize(0);
    if (uniform) {
        const int k = mesh.faceSize(0);
        py::array_t<int> F({static_cast<py::ssize_t>(mesh.faceCount()), static_cast<py::ssize_t>(k)});
        std::copy(mesh.faceVertices.begin(), mesh.faceVertices.end(), F.mutable_data());
        faces = F;
    } else {
        py::list l;
        for (int f = 0; f < mesh.faceCount(); ++f)
            l.append(std::vector<int>(mesh.face(f), mesh.face(f) + mesh.faceSize(f)));
        faces = l;
    }
    py::object normals = mesh.normals.cols() ? py::object(fromColumns(mesh.normals)) : py::object(py::none());
    return py::make_tuple(fromColumns(mesh.positions), faces, normals);
}

/// c.evaluateMany at every parameter into a new (N, D) array, in chunks: each chunk's D x len
/// result (column-major, the same layout as len rows of the output) stays in cache and is copied
/// straight into the output, instead of a full-size temporary and a second pass (GIL released).
template <int D, typename C>
py::array_t<double> batchEvaluate(const C& c, const py::array_t<double, py::array::c_style>& ts)
{
    constexpr std::size_t chunk = 4096;
    const auto count = static_cast<std::size_t>(ts.size());
    py::array_t<double> out({static_cast<py::ssize_t>(count), py::ssize_t{D}});
    double* o = out.mutable_data();
    {
        py::gil_scoped_release release;
        typename C::Points buf;
        for (std::size_t start = 0; start < count; start += chunk) {
            const std::size_t len = std::min(chunk, count - start);
            c.evaluateMany(ts.data() + start, len, buf);
            std::copy(buf.data(), buf.data() + D * len, o + D * start);
        }
    }
    return out;
}

/// [start, end] version of requireInDomain (NaN is outside).
inline void requireInRange(const py::array_t<double, py::array::c_style>& ts, double start, double end,
                           const std::string& what)
{
    for (py::ssize_t i = 0; i < ts.size(); ++i) {
        const double t = ts.data()[i];
        if (!(t >= start && t <= end))
            throw freeform::Error(what + ": parameter " + num(t) + " (index " + std::to_string(i) + ") outside [" +
                                  num(start) + ", " + num(end) + "]");
    }
}

// ------------------------------------------------- rational and NURBS (nurbs.cpp, nurbs_surface.cpp)

struct PyRationalCurve {
    std::variant<freeform::RationalBezierCurve<double, 2>, freeform::RationalBezierCurve<double, 3>> c;
};
struct PyNurbsCurve {
    std::variant<freeform::NurbsCurve<double, 2>, freeform::NurbsCurve<double, 3>> c;
};
struct PyRationalSurface {
    freeform::RationalBezierSurface<double, 3> s;
};
struct PyNurbsSurface {
    freeform::NurbsSurface<double, 3> s;
};

/// The geometry of a document object as its Python object (BezierCurve, Spline, Patch, Lattice,
/// RationalBezierCurve, NurbsCurve, RationalBezierSurface, NurbsSurface); Error naming the object
/// for the types without one (deboor_surface, subdivision_surface).
py::object geometryObject(const freeform::TypedDocument& doc, const freeform::TypedObject& object);

/// A Python geometry object as the document's plain data (Error/TypeError for other objects).
freeform::ObjectData objectData(py::handle object);

void bindNurbs(py::module_& m);
void bindNurbsSurfaces(py::module_& m);

} // namespace ffpy
