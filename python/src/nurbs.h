#pragma once
// Shared by the bindings of the rational and NURBS types (docs/python.md, "Rational Bézier and
// NURBS"): nurbs.cpp (the curves and the document bridge) and nurbs_surface.cpp (the surfaces,
// interpolate_nurbs / approximate_nurbs and RationalLattice): the types' short names and the
// argument conversions both use.

#include "geometry.h"

#include <string>
#include <vector>

namespace ffpy {

using RCurve2 = freeform::RationalBezierCurve<double, 2>;
using RCurve3 = freeform::RationalBezierCurve<double, 3>;
using NCurve2 = freeform::NurbsCurve<double, 2>;
using NCurve3 = freeform::NurbsCurve<double, 3>;
using RSurface = freeform::RationalBezierSurface<double, 3>;
using NSurface = freeform::NurbsSurface<double, 3>;

/// A 1-D numeric array as a float64 std::vector (finiteness is the library's check).
inline std::vector<double> numberList(py::handle h, const std::string& what)
{
    py::array a = numericArray(h, what);
    if (a.ndim() != 1) throw freeform::Error(what + ": expected a 1-D array, got shape " + shapeText(a));
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    return std::vector<double>(d.data(), d.data() + d.size());
}

/// Weights (None: empty, all 1) as an Eigen vector: a 1-D array, or for surfaces (ndim2) a 2-D
/// (nu, nv) array flattened in C order (point (i, j) at i * nv + j, the library's layout). Count,
/// sign and finiteness are the library's checks (its message names the weight).
inline Eigen::VectorXd weightVector(py::handle h, const std::string& what, bool ndim2 = false)
{
    if (h.is_none()) return {};
    py::array a = numericArray(h, what);
    if (a.ndim() != (ndim2 ? 2 : 1))
        throw freeform::Error(what + ": expected a " + (ndim2 ? "2-D (nu, nv)" : "1-D (n,)") + " array, got shape " +
                              shapeText(a));
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    return Eigen::Map<const Eigen::VectorXd>(d.data(), d.size());
}

/// A point (D,) of a D-dimensional object.
template <int D>
freeform::Point<double, D> pointArg(py::handle h, const std::string& what)
{
    const auto v = vector(h, what);
    if (v.size() != D)
        throw freeform::Error(what + ": expected " + std::to_string(D) + " numbers, got " + std::to_string(v.size()));
    requireFiniteRows(v.data(), 1, D, what);
    return Eigen::Map<const freeform::Point<double, D>>(v.data());
}

template <int D>
py::tuple boxTuple(const freeform::Box<double, D>& b)
{
    return py::make_tuple(fromVector(b.min()), fromVector(b.max()));
}

/// Homogeneous points (n, D+1) of a pickled state as a (D+1) x n matrix, checked.
template <int D>
freeform::PointMatrix<double, D + 1> homogeneousArg(py::handle h, const std::string& what)
{
    const py::array a = rows(h, what, D + 1, false);
    const auto n = static_cast<std::size_t>(a.shape(0));
    const double* p = static_cast<const double*>(a.data());
    requireFiniteRows(p, n, D + 1, what);
    return Eigen::Map<const freeform::PointMatrix<double, D + 1>>(p, D + 1, static_cast<Eigen::Index>(n));
}

} // namespace ffpy
