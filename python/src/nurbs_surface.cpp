// The rational and NURBS types for Python after the curves (nurbs.cpp; docs/python.md, "Rational
// Bézier and NURBS"; the math in docs/nurbs.md): RationalBezierSurface and NurbsSurface (3D),
// interpolate_nurbs / approximate_nurbs, and RationalLattice (NFFD) with Lattice.deform_curve.
// module.cpp binds them after nurbs.cpp's curves (bindNurbsSurfaces after bindNurbs).
//
// Arrays as in nurbs.cpp: control points (nu, nv, 3), weights (nu, nv), knots (m,), parameters
// (N, 2); results are new float64 arrays; the library checks knots, weights and points
// (freeform.Error with its message).

#include "lattice.h"
#include "nurbs.h"

#include <freeform/curve/interpolation.h>
#include <freeform/curve/nurbs_interpolation.h>
#include <freeform/document/object_data.h>
#include <freeform/tessellate/tessellate_rational.h>
#include <freeform/volume/deform.h>
#include <freeform/volume/deform_rational.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace ffpy {

namespace {

// ---------------------------------------------------------------- argument conversion

/// An (a, b, 3) grid of points as a 3 x (a*b) matrix (point (i, j) at column i*b + j), finite.
freeform::PointMatrix<double, 3> gridPoints(py::handle h, const std::string& what, int& rows, int& cols)
{
    py::array a = numericArray(h, what);
    if (a.ndim() != 3 || a.shape(2) != 3)
        throw freeform::Error(what + ": expected an array of shape (nu, nv, 3), got shape " + shapeText(a));
    rows = static_cast<int>(a.shape(0));
    cols = static_cast<int>(a.shape(1));
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    requireFiniteRows(d.data(), static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols), 3, what);
    return Eigen::Map<const freeform::PointMatrix<double, 3>>(d.data(), 3, static_cast<Eigen::Index>(rows) * cols);
}

/// (N, 2) parameters as a float64 C-contiguous array, every (u, v) in the box, NaN refused.
py::array uvArg(py::handle h, const std::string& what, double u0, double u1, double v0, double v1)
{
    py::array a = rows(h, "uv", 2, false);
    const double* p = static_cast<const double*>(a.data());
    for (py::ssize_t i = 0; i < a.shape(0); ++i)
        if (!(p[2 * i] >= u0 && p[2 * i] <= u1 && p[2 * i + 1] >= v0 && p[2 * i + 1] <= v1))
            throw freeform::Error(what + ": uv row " + std::to_string(i) + " (" + num(p[2 * i]) + ", " +
                                  num(p[2 * i + 1]) + ") outside [" + num(u0) + ", " + num(u1) + "] x [" + num(v0) + ", " +
                                  num(v1) + "]");
    return a;
}

/// An (a*b) x D column block as an (a, b, D) array.
template <typename Derived>
py::array grid(const Eigen::MatrixBase<Derived>& m, int a, int b)
{
    return fromColumns(m).attr("reshape")(a, b, static_cast<int>(m.rows()));
}

/// Surface jets at many (u, v): (N, J, 3), J = (order+1)(order+2)/2, columns f, f_u, f_v, f_uu,
/// f_uv, f_vv, ... (BezierSurface::jetIndex order).
template <typename S>
py::array_t<double> surfaceJets(const S& s, const py::array& uv, int order)
{
    if (order < 0) throw freeform::Error("derivatives: order " + std::to_string(order) + " is negative");
    const auto n = uv.shape(0);
    const py::ssize_t J = static_cast<py::ssize_t>((order + 1) * (order + 2) / 2);
    py::array_t<double> out({n, J, py::ssize_t{3}});
    const double* p = static_cast<const double*>(uv.data());
    double* o = out.mutable_data();
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < n; ++i) {
            const Eigen::Matrix<double, 3, Eigen::Dynamic> j = s.jet(p[2 * i], p[2 * i + 1], order);
            std::copy(j.data(), j.data() + j.size(), o + i * J * 3);
        }
    }
    return out;
}

/// d^(a+b) S / du^a dv^b at many (u, v): (N, 3) (from the jet of order a + b).
template <typename S>
py::array_t<double> surfacePartial(const S& s, int a, int b, const py::array& uv)
{
    if (a < 0 || b < 0) throw freeform::Error("partial: orders (" + std::to_string(a) + ", " + std::to_string(b) + ") are negative");
    const auto n = uv.shape(0);
    const int order = a + b, col = order * (order + 1) / 2 + b;
    py::array_t<double> out({n, py::ssize_t{3}});
    const double* p = static_cast<const double*>(uv.data());
    double* o = out.mutable_data();
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < n; ++i) {
            const Eigen::Vector3d x = s.jet(p[2 * i], p[2 * i + 1], order).col(col);
            std::copy(x.data(), x.data() + 3, o + 3 * i);
        }
    }
    return out;
}

template <typename F>
py::array_t<double> surfaceMap(const py::array& uv, F&& f)
{
    const auto n = uv.shape(0);
    py::array_t<double> out({n, py::ssize_t{3}});
    const double* p = static_cast<const double*>(uv.data());
    double* o = out.mutable_data();
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < n; ++i) {
            const Eigen::Vector3d x = f(p[2 * i], p[2 * i + 1]);
            std::copy(x.data(), x.data() + 3, o + 3 * i);
        }
    }
    return out;
}

freeform::TessellationOptions tessellationOptions(int segments, double tolerance)
{
    if (segments < 1) throw freeform::Error("tessellate: segments " + std::to_string(segments) + " is less than 1");
    if (!(tolerance >= 0)) throw freeform::Error("tessellate: tolerance must be >= 0 (0: uniform segments)");
    freeform::TessellationOptions o;
    o.tolerance = tolerance;
    o.segmentsU = o.segmentsV = segments;
    return o;
}

struct PyRationalLattice {
    freeform::RationalLattice lattice;
    double strength = 1;
};

/// The 3D NURBS form of a curve argument for the exact lattice composition.
NCurve3 nurbs3(py::handle curve, const char* what)
{
    if (py::isinstance<PyNurbsCurve>(curve)) {
        const auto& c = curve.cast<const PyNurbsCurve&>().c;
        if (const auto* n = std::get_if<NCurve3>(&c)) return *n;
    } else if (py::isinstance<PyRationalCurve>(curve)) {
        const auto& c = curve.cast<const PyRationalCurve&>().c;
        if (const auto* r = std::get_if<RCurve3>(&c)) return NCurve3::fromRationalBezier(*r);
    } else if (py::isinstance<PyCurve>(curve)) {
        const auto& c = curve.cast<const PyCurve&>().c;
        if (const auto* b = std::get_if<Curve3>(&c)) return NCurve3::fromBezier(*b);
    } else {
        throw py::type_error(std::string(what) + ": expected a BezierCurve, RationalBezierCurve or NurbsCurve, got " +
                             std::string(py::str(py::type::handle_of(curve).attr("__name__"))));
    }
    throw freeform::Error(std::string(what) + ": the curve is 2D; lattices deform 3D curves");
}

/// Deforms a curve argument exactly through a (rational) lattice; the result keeps the argument's
/// kind (BezierCurve -> BezierCurve for a polynomial lattice, RationalBezierCurve ->
/// RationalBezierCurve, NurbsCurve -> NurbsCurve).
py::object deformCurveArg(const freeform::RationalLattice& lat, double strength, py::handle curve, const char* what)
{
    if (py::isinstance<PyCurve>(curve) && lat.isPolynomial()) {
        const auto& c = curve.cast<const PyCurve&>().c;
        if (const auto* b = std::get_if<Curve3>(&c)) {
            Curve3 out = *b;
            {
                py::gil_scoped_release release;
                out = freeform::deformCurve(lat.lattice(), *b, strength);
            }
            return py::cast(PyCurve{out});
        }
    }
    if (py::isinstance<PyRationalCurve>(curve)) {
        const auto& c = curve.cast<const PyRationalCurve&>().c;
        if (const auto* r = std::get_if<RCurve3>(&c)) {
            std::optional<RCurve3> out;
            {
                py::gil_scoped_release release;
                out = freeform::deformCurve(lat, *r, strength);
            }
            return py::cast(PyRationalCurve{*out});
        }
    }
    const NCurve3 n = nurbs3(curve, what);
    std::optional<NCurve3> out;
    {
        py::gil_scoped_release release;
        out = freeform::deformCurve(lat, n, strength);
    }
    return py::cast(PyNurbsCurve{*out});
}

template <int D>
freeform::NurbsFitOptions<double, D> fitOptions(const std::string& parametrization, py::handle params, py::handle start,
                                                py::handle end)
{
    freeform::NurbsFitOptions<double, D> o;
    o.parametrization = freeform::parseParametrization(parametrization, "parametrization");
    if (!params.is_none()) o.params = numberList(params, "params");
    if (!start.is_none()) o.startDerivative = pointArg<D>(start, "start_derivative");
    if (!end.is_none()) o.endDerivative = pointArg<D>(end, "end_derivative");
    return o;
}

} // namespace

void bindNurbsSurfaces(py::module_& m)
{
    // ------------------------------------------------------------ RationalBezierSurface
    py::class_<PyRationalSurface>(m, "RationalBezierSurface", R"doc(
A rational Bézier patch in 3D on [0, 1]^2 (docs/nurbs.md): control points (m+1, n+1, 3), weights
(m+1, n+1) positive.)doc")
        .def(py::init([](py::handle points, py::handle weights) {
                 int r = 0, c = 0;
                 const auto p = gridPoints(points, "points", r, c);
                 const Eigen::VectorXd w = weightVector(weights, "weights", true);
                 return PyRationalSurface{RSurface(r - 1, c - 1, p, w)};
             }),
             py::arg("points"), py::arg("weights"))
        .def(py::pickle(
            [](const PyRationalSurface& s) {
                const auto& h = s.s.homogeneous();
                return py::make_tuple(h.degreeU(), h.degreeV(), fromColumns(h.controlPoints()));
            },
            [](const py::tuple& t) {
                if (t.size() != 3) throw freeform::Error("RationalBezierSurface.__setstate__: expected 3 fields");
                return PyRationalSurface{RSurface(RSurface::Homogeneous(t[0].cast<int>(), t[1].cast<int>(),
                                                                        homogeneousArg<3>(t[2], "homogeneous_points")))};
            }))
        .def("__copy__", [](const PyRationalSurface& s) { return s; })
        .def("__deepcopy__", [](const PyRationalSurface& s, py::handle) { return s; }, py::arg("memo"))
        .def_property_readonly("degree", [](const PyRationalSurface& s) { return py::make_tuple(s.s.degreeU(), s.s.degreeV()); })
        .def_property_readonly("control_points", [](const PyRationalSurface& s) {
            const auto d = freeform::toData(s.s);
            return grid(d.points, s.s.degreeU() + 1, s.s.degreeV() + 1);
        }, "(m+1, n+1, 3) float64 (a copy).")
        .def_property_readonly("weights", [](const PyRationalSurface& s) {
            const auto d = freeform::toData(s.s);
            return py::array_t<double>({static_cast<py::ssize_t>(s.s.degreeU() + 1), static_cast<py::ssize_t>(s.s.degreeV() + 1)}, d.weights.data());
        }, "(m+1, n+1) float64 (a copy).")
        .def("evaluate", [](const PyRationalSurface& s, py::handle uv) {
            const py::array a = uvArg(uv, "RationalBezierSurface.evaluate", 0, 1, 0, 1);
            return surfaceMap(a, [&](double u, double v) { return s.s.evaluate(u, v); });
        }, py::arg("uv"), "Points at many (u, v) (N, 2): (N, 3).")
        .def("derivatives", [](const PyRationalSurface& s, py::handle uv, int order) {
            return surfaceJets(s.s, uvArg(uv, "RationalBezierSurface.derivatives", 0, 1, 0, 1), order);
        }, py::arg("uv"), py::arg("order"),
           "(N, J, 3), J = (order+1)(order+2)/2: f, f_u, f_v, f_uu, f_uv, f_vv, ... (Leibniz in two variables).")
        .def("partial", [](const PyRationalSurface& s, int a, int b, py::handle uv) {
            return surfacePartial(s.s, a, b, uvArg(uv, "RationalBezierSurface.partial", 0, 1, 0, 1));
        }, py::arg("a"), py::arg("b"), py::arg("uv"), "d^(a+b) f / du^a dv^b at many (u, v): (N, 3).")
        .def("normal", [](const PyRationalSurface& s, py::handle uv) {
            const py::array a = uvArg(uv, "RationalBezierSurface.normal", 0, 1, 0, 1);
            return surfaceMap(a, [&](double u, double v) { return s.s.normal(u, v); });
        }, py::arg("uv"), "Unit normals f_u x f_v / |f_u x f_v| (zero where they are parallel): (N, 3).")
        .def("split_u", [](const PyRationalSurface& s, double t) { auto [a, b] = s.s.splitU(t); return py::make_tuple(PyRationalSurface{a}, PyRationalSurface{b}); }, py::arg("t"))
        .def("split_v", [](const PyRationalSurface& s, double t) { auto [a, b] = s.s.splitV(t); return py::make_tuple(PyRationalSurface{a}, PyRationalSurface{b}); }, py::arg("t"))
        .def("elevated", [](const PyRationalSurface& s, int du, int dv) {
            if (du < 0 || dv < 0) throw freeform::Error("RationalBezierSurface.elevated: negative count");
            return PyRationalSurface{s.s.elevatedU(du).elevatedV(dv)};
        }, py::arg("du") = 1, py::arg("dv") = 1, "The same patch with the degrees raised.")
        .def("transposed", [](const PyRationalSurface& s) { return PyRationalSurface{s.s.transposed()}; }, "u and v swapped.")
        .def("control_box", [](const PyRationalSurface& s) { return boxTuple(s.s.controlBox()); },
             "(min, max) of the control points (contains the patch).")
        .def("to_nurbs", [](const PyRationalSurface& s) { return PyNurbsSurface{NSurface::fromBezier(s.s)}; },
             "The same patch as a NurbsSurface (clamped knots on [0, 1]^2).")
        .def("tessellate", [](const PyRationalSurface& s, int segments, double tolerance) {
            const auto o = tessellationOptions(segments, tolerance);
            freeform::PolygonMesh mesh;
            {
                py::gil_scoped_release release;
                mesh = freeform::tessellateRational({s.s}, 1, 1, o);
            }
            return meshArrays(mesh);
        }, py::arg("segments") = 8, py::arg("tolerance") = 0.0,
           "(V (n, 3), F (m, 3) int32, N (n, 3)): uniform `segments`, or certified to `tolerance` > 0 (docs/surfaces.md).")
        .def("__repr__", [](const PyRationalSurface& s) {
            return "RationalBezierSurface(degree=(" + std::to_string(s.s.degreeU()) + ", " + std::to_string(s.s.degreeV()) + "))";
        });

    // ------------------------------------------------------------ NurbsSurface
    py::class_<PyNurbsSurface>(m, "NurbsSurface", R"doc(
A tensor-product NURBS surface in 3D (docs/nurbs.md) on [u_p, u_(nu)] x [v_q, v_(nv)]:
NurbsSurface(degree (p, q) or p, knots_u, knots_v, points (nu, nv, 3), weights (nu, nv) or None).)doc")
        .def(py::init([](py::handle degree, py::handle knotsU, py::handle knotsV, py::handle points, py::handle weights) {
                 int p = 0, q = 0;
                 if (py::isinstance<py::int_>(degree)) {
                     p = q = degree.cast<int>();
                 } else {
                     const auto d = degree.cast<std::vector<int>>();
                     if (d.size() != 2) throw freeform::Error("degree: expected an int or (p, q)");
                     p = d[0];
                     q = d[1];
                 }
                 int r = 0, c = 0;
                 const auto pts = gridPoints(points, "points", r, c);
                 const Eigen::VectorXd w = weightVector(weights, "weights", true);
                 NSurface s(p, q, numberList(knotsU, "knots_u"), numberList(knotsV, "knots_v"), pts, w);
                 if (s.countU() != r || s.countV() != c)
                     throw freeform::Error("points: the knot vectors need a grid of " + std::to_string(s.countU()) + " x " +
                                           std::to_string(s.countV()) + " points, got " + std::to_string(r) + " x " +
                                           std::to_string(c));
                 return PyNurbsSurface{std::move(s)};
             }),
             py::arg("degree"), py::arg("knots_u"), py::arg("knots_v"), py::arg("points"), py::arg("weights") = py::none())
        .def(py::pickle(
            [](const PyNurbsSurface& s) {
                return py::make_tuple(s.s.degreeU(), s.s.degreeV(), s.s.knotsU().knots(), s.s.knotsV().knots(),
                                      fromColumns(s.s.homogeneousPoints()));
            },
            [](const py::tuple& t) {
                if (t.size() != 5) throw freeform::Error("NurbsSurface.__setstate__: expected 5 fields");
                return PyNurbsSurface{NSurface(NSurface::Knots(t[2].cast<std::vector<double>>(), t[0].cast<int>(), "NurbsSurface (knots in u)"),
                                               NSurface::Knots(t[3].cast<std::vector<double>>(), t[1].cast<int>(), "NurbsSurface (knots in v)"),
                                               homogeneousArg<3>(t[4], "homogeneous_points"))};
            }))
        .def("__copy__", [](const PyNurbsSurface& s) { return s; })
        .def("__deepcopy__", [](const PyNurbsSurface& s, py::handle) { return s; }, py::arg("memo"))
        .def_static("sphere", [](py::handle center, double radius) {
            if (!(radius > 0) || !std::isfinite(radius)) throw freeform::Error("NurbsSurface.sphere: radius must be positive and finite");
            return PyNurbsSurface{NSurface::sphere(pointArg<3>(center, "center"), radius)};
        }, py::arg("center") = std::vector<double>{0.0, 0.0, 0.0}, py::arg("radius") = 1.0,
           "The exact sphere: degree (2, 2), 9 x 5 points; u around z on [0, 1], v from the south to the north pole on [0, 1].")
        .def_static("from_bezier", [](py::handle patch) {
            if (py::isinstance<PyPatch>(patch)) return PyNurbsSurface{NSurface::fromBezier(RSurface(patch.cast<const PyPatch&>().p))};
            if (py::isinstance<PyRationalSurface>(patch)) return PyNurbsSurface{NSurface::fromBezier(patch.cast<const PyRationalSurface&>().s)};
            throw py::type_error("NurbsSurface.from_bezier: expected a Patch or RationalBezierSurface");
        }, py::arg("patch"), "A (rational) Bézier patch as a NURBS surface on [0, 1]^2.")
        .def_property_readonly("degree", [](const PyNurbsSurface& s) { return py::make_tuple(s.s.degreeU(), s.s.degreeV()); })
        .def_property_readonly("count", [](const PyNurbsSurface& s) { return py::make_tuple(s.s.countU(), s.s.countV()); },
                               "(nu, nv): control points along u and v.")
        .def_property_readonly("knots_u", [](const PyNurbsSurface& s) { return py::array_t<double>(static_cast<py::ssize_t>(s.s.knotsU().size()), s.s.knotsU().knots().data()); })
        .def_property_readonly("knots_v", [](const PyNurbsSurface& s) { return py::array_t<double>(static_cast<py::ssize_t>(s.s.knotsV().size()), s.s.knotsV().knots().data()); })
        .def_property_readonly("control_points", [](const PyNurbsSurface& s) { return grid(s.s.controlPoints(), s.s.countU(), s.s.countV()); },
                               "(nu, nv, 3) float64 (a copy).")
        .def_property_readonly("weights", [](const PyNurbsSurface& s) {
            const Eigen::VectorXd w = s.s.weights();
            return py::array_t<double>({static_cast<py::ssize_t>(s.s.countU()), static_cast<py::ssize_t>(s.s.countV())}, w.data());
        }, "(nu, nv) float64 (a copy).")
        .def_property_readonly("is_rational", [](const PyNurbsSurface& s) { return s.s.isRational(); })
        .def_property_readonly("domain", [](const PyNurbsSurface& s) {
            return py::make_tuple(py::make_tuple(s.s.knotsU().front(), s.s.knotsU().back()),
                                  py::make_tuple(s.s.knotsV().front(), s.s.knotsV().back()));
        }, "((u_start, u_end), (v_start, v_end)).")
        .def("evaluate", [](const PyNurbsSurface& s, py::handle uv) {
            const auto& S = s.s;
            const py::array a = uvArg(uv, "NurbsSurface.evaluate", S.knotsU().front(), S.knotsU().back(), S.knotsV().front(), S.knotsV().back());
            return surfaceMap(a, [&](double u, double v) { return S.evaluate(u, v); });
        }, py::arg("uv"), "Points at many (u, v) (N, 2): (N, 3).")
        .def("evaluate_grid", [](const PyNurbsSurface& s, py::handle us, py::handle vs, bool withDerivatives) -> py::object {
            const auto& S = s.s;
            const auto U = vector(us, "u"), V = vector(vs, "v");
            requireInRange(U, S.knotsU().front(), S.knotsU().back(), "NurbsSurface.evaluate_grid (u)");
            requireInRange(V, S.knotsV().front(), S.knotsV().back(), "NurbsSurface.evaluate_grid (v)");
            const std::vector<double> u(U.data(), U.data() + U.size()), v(V.data(), V.data() + V.size());
            freeform::PointMatrix<double, 3> pos, du, dv;
            {
                py::gil_scoped_release release;
                S.evaluateGrid(u, v, pos, withDerivatives ? &du : nullptr, withDerivatives ? &dv : nullptr);
            }
            const int a = static_cast<int>(u.size()), b = static_cast<int>(v.size());
            if (!withDerivatives) return grid(pos, a, b);
            return py::make_tuple(grid(pos, a, b), grid(du, a, b), grid(dv, a, b));
        }, py::arg("u"), py::arg("v"), py::arg("derivatives") = false,
           "The batch path on the grid u x v: (len(u), len(v), 3); with derivatives=True (S, S_u, S_v).")
        .def("derivatives", [](const PyNurbsSurface& s, py::handle uv, int order) {
            const auto& S = s.s;
            return surfaceJets(S, uvArg(uv, "NurbsSurface.derivatives", S.knotsU().front(), S.knotsU().back(), S.knotsV().front(), S.knotsV().back()), order);
        }, py::arg("uv"), py::arg("order"), "(N, J, 3), J = (order+1)(order+2)/2: S, S_u, S_v, S_uu, S_uv, S_vv, ...")
        .def("partial", [](const PyNurbsSurface& s, int a, int b, py::handle uv) {
            const auto& S = s.s;
            return surfacePartial(S, a, b, uvArg(uv, "NurbsSurface.partial", S.knotsU().front(), S.knotsU().back(), S.knotsV().front(), S.knotsV().back()));
        }, py::arg("a"), py::arg("b"), py::arg("uv"))
        .def("normal", [](const PyNurbsSurface& s, py::handle uv) {
            const auto& S = s.s;
            const py::array a = uvArg(uv, "NurbsSurface.normal", S.knotsU().front(), S.knotsU().back(), S.knotsV().front(), S.knotsV().back());
            return surfaceMap(a, [&](double u, double v) { return S.normal(u, v); });
        }, py::arg("uv"), "Unit normals (zero at poles where S_u x S_v vanishes): (N, 3).")
        .def("refined_u", [](const PyNurbsSurface& s, py::handle knots) {
            const auto k = numberList(knots, "knots");
            py::gil_scoped_release release;
            return PyNurbsSurface{s.s.refinedU(k)};
        },
             py::arg("knots"), "Knot refinement in u (Oslo); the surface is unchanged.")
        .def("refined_v", [](const PyNurbsSurface& s, py::handle knots) {
            const auto k = numberList(knots, "knots");
            py::gil_scoped_release release;
            return PyNurbsSurface{s.s.refinedV(k)};
        },
             py::arg("knots"), "Knot refinement in v (Oslo); the surface is unchanged.")
        .def("insert_knot_u", [](const PyNurbsSurface& s, double u, int times) {
            if (times < 0) throw freeform::Error("NurbsSurface.insert_knot_u: times " + std::to_string(times) + " is negative");
            py::gil_scoped_release release;
            return PyNurbsSurface{s.s.refinedU(std::vector<double>(static_cast<std::size_t>(times), u))};
        }, py::arg("u"), py::arg("times") = 1)
        .def("insert_knot_v", [](const PyNurbsSurface& s, double v, int times) {
            if (times < 0) throw freeform::Error("NurbsSurface.insert_knot_v: times " + std::to_string(times) + " is negative");
            py::gil_scoped_release release;
            return PyNurbsSurface{s.s.refinedV(std::vector<double>(static_cast<std::size_t>(times), v))};
        }, py::arg("v"), py::arg("times") = 1)
        .def("bezier_patches", [](const PyNurbsSurface& s) {
            py::list out;
            const auto patches = [&] {
                py::gil_scoped_release release;
                return s.s.bezierPatches();
            }();
            for (const auto& p : patches) out.append(PyRationalSurface{p});
            return out;
        }, "Bézier extraction: one RationalBezierSurface per pair of non-empty spans, patch (a, b) at a * (spans in v) + b.")
        .def("curve_at_u", [](const PyNurbsSurface& s, double u) { return PyNurbsCurve{s.s.curveAtU(u)}; }, py::arg("u"),
             "The isocurve u = const as a NurbsCurve in v.")
        .def("curve_at_v", [](const PyNurbsSurface& s, double v) { return PyNurbsCurve{s.s.curveAtV(v)}; }, py::arg("v"),
             "The isocurve v = const as a NurbsCurve in u.")
        .def("control_box", [](const PyNurbsSurface& s) { return boxTuple(s.s.controlBox()); })
        .def("tessellate", [](const PyNurbsSurface& s, int segments, double tolerance) {
            const auto o = tessellationOptions(segments, tolerance);
            freeform::PolygonMesh mesh;
            {
                py::gil_scoped_release release;
                mesh = freeform::tessellateNurbs(s.s, o);
            }
            return meshArrays(mesh);
        }, py::arg("segments") = 8, py::arg("tolerance") = 0.0,
           "(V, F, N) through the Bézier patches: uniform `segments` per patch, or certified to `tolerance` > 0.")
        .def("__repr__", [](const PyNurbsSurface& s) {
            return "NurbsSurface(degree=(" + std::to_string(s.s.degreeU()) + ", " + std::to_string(s.s.degreeV()) + "), count=(" +
                   std::to_string(s.s.countU()) + ", " + std::to_string(s.s.countV()) + "), rational=" +
                   (s.s.isRational() ? "True" : "False") + ")";
        });

    // ------------------------------------------------------------ interpolation, approximation
    m.def(
        "interpolate_nurbs",
        [](py::handle points, int degree, const std::string& parametrization, py::handle params, py::handle start, py::handle end) {
            int dim = 0;
            py::array a = pointsAnyDim(points, "points", dim);
            if (dim == 2) {
                const auto o = fitOptions<2>(parametrization, params, start, end);
                const auto p = columns<2>(a, "points");
                py::gil_scoped_release release;
                return PyNurbsCurve{freeform::interpolateNurbs<double, 2>(p, degree, o)};
            }
            const auto o = fitOptions<3>(parametrization, params, start, end);
            const auto p = columns<3>(a, "points");
            py::gil_scoped_release release;
            return PyNurbsCurve{freeform::interpolateNurbs<double, 3>(p, degree, o)};
        },
        py::arg("points"), py::arg("degree") = 3, py::arg("parametrization") = "chord", py::arg("params") = py::none(),
        py::arg("start_derivative") = py::none(), py::arg("end_derivative") = py::none(),
        R"doc(The degree-p B-spline through every point (N, D) on [0, 1] (as `freeform interpolate --degree P`):
parameters by 'uniform', 'chord' or 'centripetal' or given (params, strictly increasing, normalised
to [0, 1]); averaged knots. With start_derivative and end_derivative (both, degree >= 3; with
respect to the normalised parameter) two more control points fix the end tangents.)doc")
        .def(
            "approximate_nurbs",
            [](py::handle points, int controlCount, int degree, const std::string& parametrization, py::handle params) {
                int dim = 0;
                py::array a = pointsAnyDim(points, "points", dim);
                if (dim == 2) {
                    const auto o = fitOptions<2>(parametrization, params, py::none(), py::none());
                    const auto p = columns<2>(a, "points");
                    py::gil_scoped_release release;
                    return PyNurbsCurve{freeform::approximateNurbs<double, 2>(p, degree, controlCount, o)};
                }
                const auto o = fitOptions<3>(parametrization, params, py::none(), py::none());
                const auto p = columns<3>(a, "points");
                py::gil_scoped_release release;
                return PyNurbsCurve{freeform::approximateNurbs<double, 3>(p, degree, controlCount, o)};
            },
            py::arg("points"), py::arg("control_count"), py::arg("degree") = 3, py::arg("parametrization") = "chord",
            py::arg("params") = py::none(),
            R"doc(The degree-p B-spline with control_count control points closest in least squares to the
points (N, D), through the first and the last (degree + 1 <= control_count < N).)doc");

    // ------------------------------------------------------------ RationalLattice (NFFD)
    py::class_<PyRationalLattice>(m, "RationalLattice", R"doc(
A lattice whose control points carry weights (NFFD, docs/nurbs.md "Rational FFD"):
p' = p + w_s N / D with N = sum w_q B_q (P_q - R_q), D = sum w_q B_q. Built from a Lattice (its
control points, frame, outside policy and strength at the time of the call) and one positive weight
per control point (index as Lattice.control_points; None: all 1, the polynomial FFD bit for bit).)doc")
        .def(py::init([](PyLattice& lat, py::handle weights) {
                 freeform::Lattice l = lat.snapshot();
                 const Eigen::VectorXd w = weightVector(weights, "weights");
                 PyRationalLattice r{w.size() ? freeform::RationalLattice(std::move(l), w) : freeform::RationalLattice(std::move(l)),
                                     lat.strength};
                 return r;
             }),
             py::arg("lattice"), py::arg("weights") = py::none())
        .def(py::pickle(
            [](const PyRationalLattice& r) {
                PyLattice l(r.lattice.lattice());
                return py::make_tuple(py::cast(std::move(l)), fromVector(r.lattice.weights()), r.strength);
            },
            [](const py::tuple& t) {
                if (t.size() != 3) throw freeform::Error("RationalLattice.__setstate__: expected 3 fields");
                const freeform::Lattice l = t[0].cast<PyLattice&>().snapshot();
                const Eigen::VectorXd w = weightVector(t[1], "weights");
                PyRationalLattice r{freeform::RationalLattice(l, w), t[2].cast<double>()};
                return r;
            }))
        .def("__copy__", [](const PyRationalLattice& r) { return r; })
        .def("__deepcopy__", [](const PyRationalLattice& r, py::handle) { return r; }, py::arg("memo"))
        .def_property_readonly("weights", [](const PyRationalLattice& r) { return fromVector(r.lattice.weights()); },
                               "(K,) float64 (a copy).")
        .def_property_readonly("lattice", [](const PyRationalLattice& r) {
            PyLattice l(r.lattice.lattice());
            l.strength = r.strength;
            return l;
        }, "The underlying Lattice (a copy).")
        .def_readwrite("strength", &PyRationalLattice::strength)
        .def_property_readonly("is_polynomial", [](const PyRationalLattice& r) { return r.lattice.isPolynomial(); },
                               "True when every weight is exactly 1.")
        .def("deform", [](const PyRationalLattice& r, py::handle points, py::handle threadsArg) {
            const int threads = threadCount(threadsArg);
            Points3 p = toPoints(points, "points");
            if (!std::isfinite(r.strength)) throw freeform::Error("RationalLattice.strength: not finite");
            freeform::DeformOptions o;
            o.strength = r.strength;
            o.threads = threads;
            {
                py::gil_scoped_release release;
                freeform::deformPoints(r.lattice, p, o);
            }
            return fromColumns(p);
        }, py::arg("points"), py::arg("threads") = 0, "(N, 3) -> (N, 3) float64: the rational map, outside policy applied.")
        .def("jacobian", [](const PyRationalLattice& r, py::handle points) {
            const Points3 p = toPoints(points, "points");
            py::array_t<double> out({static_cast<py::ssize_t>(p.cols()), py::ssize_t{3}, py::ssize_t{3}});
            double* o = out.mutable_data();
            {
                py::gil_scoped_release release;
                for (Eigen::Index i = 0; i < p.cols(); ++i) {
                    const Eigen::Matrix3d J = r.lattice.deform(p.col(i), r.strength).jacobian;
                    for (int a = 0; a < 3; ++a)
                        for (int b = 0; b < 3; ++b) o[9 * i + 3 * a + b] = J(a, b);
                }
            }
            return out;
        }, py::arg("points"), "(N, 3, 3): J[i, a, b] = d p'_a / d p_b at each point (quotient rule).")
        .def("deform_curve", [](const PyRationalLattice& r, py::handle curve) {
            return deformCurveArg(r.lattice, r.strength, curve, "RationalLattice.deform_curve");
        }, py::arg("curve"),
           "The 3D curve pushed through the lattice exactly: a RationalBezierCurve or NurbsCurve (BezierCurve: as a "
           "NURBS) of degree d (1 + l + m + n), equal to point-wise deformation where the curve is in the box.")
        .def("__repr__", [](const PyRationalLattice& r) {
            const auto d = r.lattice.lattice().degrees();
            return "RationalLattice(degree=(" + std::to_string(d[0]) + ", " + std::to_string(d[1]) + ", " + std::to_string(d[2]) +
                   "), polynomial=" + (r.lattice.isPolynomial() ? "True" : "False") + ")";
        });

    // Lattice.deform_curve: the exact composition for curves on the polynomial lattice.
    auto lattice = py::reinterpret_borrow<py::class_<PyLattice>>(m.attr("Lattice"));
    lattice.def(
        "deform_curve",
        [](PyLattice& lat, py::handle curve) {
            return deformCurveArg(freeform::RationalLattice(lat.snapshot()), lat.strength, curve, "Lattice.deform_curve");
        },
        py::arg("curve"),
        "The 3D curve pushed through the lattice exactly (docs/ffd.md): a BezierCurve of degree d (l+m+n); a "
        "RationalBezierCurve or NurbsCurve of degree d (l+m+n) (the rational composition, whose denominator is "
        "then W^(l+m+n)).");
}

std::optional<freeform::RationalLattice> rationalLatticeArg(py::handle h)
{
    if (!py::isinstance<PyRationalLattice>(h)) return std::nullopt;
    return h.cast<const PyRationalLattice&>().lattice;
}

} // namespace ffpy
