// The rational and NURBS curves for Python (docs/python.md, "Rational Bézier and NURBS"; the math
// in docs/nurbs.md): RationalBezierCurve and NurbsCurve (2D and 3D), and the bridge between the
// document layer's objects and the Python objects (geometryObject, objectData) that
// Document.object / Document.add use. The surfaces, interpolate_nurbs / approximate_nurbs and
// RationalLattice (NFFD) with Lattice.deform_curve are in nurbs_surface.cpp; what both use, nurbs.h.
//
// Arrays as in the rest of the module: control points (n, D), weights (n,) (surfaces: (nu, nv, 3)
// and (nu, nv)), knots (m,); parameters (N,) or (N, 2); results are new float64 arrays. Knots,
// weights and points are checked by the library (freeform.Error with its message: the knot or
// weight by index); non-numeric arrays raise TypeError, wrong shapes and NaN points freeform.Error.

#include "lattice.h"
#include "nurbs.h"

#include <freeform/curve/nurbs_continuity.h>
#include <freeform/document/object_data.h>
#include <freeform/io/geometry_data.h>

#include <algorithm>
#include <optional>
#include <type_traits>
#include <vector>

namespace ffpy {

namespace {

template <typename C>
constexpr int dimOf = C::PointType::RowsAtCompileTime;

/// Parameters per batch call: the batch result (D x kChunk) stays in cache and is copied straight
/// into the (N, D) output (the same memory layout), instead of a full-size temporary.
constexpr std::size_t kChunk = 4096;

// ---------------------------------------------------------------- argument conversion

/// Closest points of a curve to one point (D,) -> (u, point, distance) or to (N, D) -> arrays.
template <typename C>
py::object closestPoints(const C& c, py::handle points)
{
    constexpr int D = dimOf<C>;
    py::array a = numericArray(points, "points");
    if (a.ndim() == 1) {
        const auto p = pointArg<D>(a, "point");
        typename C::Closest r;
        {
            py::gil_scoped_release release;
            r = c.closestPoint(p);
        }
        return py::make_tuple(r.u, fromVector(r.point), r.distance);
    }
    if (a.ndim() != 2 || a.shape(1) != D)
        throw freeform::Error("points: expected an array of shape (" + std::to_string(D) + ",) or (N, " + std::to_string(D) +
                              "), got shape " + shapeText(a));
    const freeform::PointMatrix<double, D> q = columns<D>(py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a), "points");
    const auto n = q.cols();
    py::array_t<double> u(n), dist(n);
    freeform::PointMatrix<double, D> pts(D, n);
    double* pu = u.mutable_data();
    double* pd = dist.mutable_data();
    {
        py::gil_scoped_release release;
        for (Eigen::Index i = 0; i < n; ++i) {
            const auto r = c.closestPoint(q.col(i));
            pu[i] = r.u;
            pd[i] = r.distance;
            pts.col(i) = r.point;
        }
    }
    return py::make_tuple(u, fromColumns(pts), dist);
}

// ---------------------------------------------------------------- data <-> geometry

py::object fromGeometry(const freeform::Geometry& g)
{
    return std::visit(
        [](const auto& v) -> py::object {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, Curve2> || std::is_same_v<V, Curve3>) return py::cast(PyCurve{v});
            else if constexpr (std::is_same_v<V, Spline2> || std::is_same_v<V, Spline3>) return py::cast(PySpline{v});
            else if constexpr (std::is_same_v<V, freeform::DeBoorSpline<2>> || std::is_same_v<V, freeform::DeBoorSpline<3>>)
                return py::cast(PySpline{v.bezier});
            else if constexpr (std::is_same_v<V, freeform::BezierSurface<double, 3>>) return py::cast(PyPatch{v});
            else if constexpr (std::is_same_v<V, freeform::Lattice>) return py::cast(PyLattice(v));
            else if constexpr (std::is_same_v<V, RCurve2> || std::is_same_v<V, RCurve3>) return py::cast(PyRationalCurve{v});
            else if constexpr (std::is_same_v<V, NCurve2> || std::is_same_v<V, NCurve3>) return py::cast(PyNurbsCurve{v});
            else if constexpr (std::is_same_v<V, RSurface>) return py::cast(PyRationalSurface{v});
            else if constexpr (std::is_same_v<V, NSurface>) return py::cast(PyNurbsSurface{v});
            else return py::none();
        },
        g);
}

/// A spline through the document layer's conversion (document/operations.h toNurbsData).
py::object splineToNurbs(const PySpline& s)
{
    freeform::BezierSplineData data;
    std::visit(
        [&](const auto& c) {
            data.degree = c.degree();
            data.closed = c.closed();
            data.points = c.controlPoints();
            data.intervals = c.intervals();
        },
        s.s);
    freeform::TypedDocument doc;
    doc.source = "Spline";
    doc.add("spline", data);
    const freeform::ObjectData nurbs = freeform::toNurbsData(doc, doc.objects().front());
    return fromGeometry(freeform::buildGeometry(nurbs, "", "NurbsCurve.from_spline"));
}

// Domain, closest point and tight box for both curve kinds (a rational Bézier curve through its
// one-piece NURBS form, which is the same curve on [0, 1]).
template <int D>
std::pair<double, double> domainOf(const freeform::RationalBezierCurve<double, D>&) { return {0.0, 1.0}; }
template <int D>
std::pair<double, double> domainOf(const freeform::NurbsCurve<double, D>& c) { return {c.domainStart(), c.domainEnd()}; }
template <int D>
py::object closest(const freeform::NurbsCurve<double, D>& c, py::handle p) { return closestPoints(c, p); }
template <int D>
py::object closest(const freeform::RationalBezierCurve<double, D>& c, py::handle p)
{
    return closestPoints(freeform::NurbsCurve<double, D>::fromRationalBezier(c), p);
}
template <int D>
freeform::Box<double, D> tightBox(const freeform::NurbsCurve<double, D>& c) { return c.boundingBox(); }
template <int D>
freeform::Box<double, D> tightBox(const freeform::RationalBezierCurve<double, D>& c)
{
    return freeform::NurbsCurve<double, D>::fromRationalBezier(c).boundingBox();
}

// ---------------------------------------------------------------- shared curve methods

/// Binds what RationalBezierCurve and NurbsCurve share over their 2D/3D variant member `c`.
template <typename Py>
void curveCommon(py::class_<Py>& cls, const char* name)
{
    const std::string n = name;
    cls.def_property_readonly("degree", [](const Py& s) { return std::visit([](const auto& c) { return c.degree(); }, s.c); })
        .def_property_readonly("dimension", [](const Py& s) { return s.c.index() == 0 ? 2 : 3; })
        .def_property_readonly(
            "control_points", [](const Py& s) { return std::visit([](const auto& c) { return fromColumns(c.controlPoints()); }, s.c); },
            "(n, D) float64: the control points P_i (a copy).")
        .def_property_readonly(
            "weights", [](const Py& s) { return std::visit([](const auto& c) { return fromVector(c.weights()); }, s.c); },
            "(n,) float64: the weights w_i (a copy).")
        .def(
            "derivatives",
            [n](const Py& s, py::handle t, int order) {
                if (order < 0) throw freeform::Error(n + ".derivatives: order " + std::to_string(order) + " is negative");
                const auto ts = vector(t, "t");
                return std::visit(
                    [&](const auto& c) {
                        using C = std::decay_t<decltype(c)>;
                        const auto [a, b] = domainOf(c);
                        requireInRange(ts, a, b, n + ".derivatives");
                        return sampleJets<dimOf<C>>(ts, order, false, [&](double x, int k) { return c.derivatives(x, k); });
                    },
                    s.c);
            },
            py::arg("t"), py::arg("order"),
            "(T, order+1, D): the point and the derivatives 1..order at each parameter (quotient rule on the "
            "homogeneous derivatives; with respect to the curve's own parameter).")
        .def(
            "evaluate",
            [n](const Py& s, py::handle t) {
                const auto ts = vector(t, "t");
                return std::visit(
                    [&](const auto& c) {
                        using C = std::decay_t<decltype(c)>;
                        const auto [a, b] = domainOf(c);
                        requireInRange(ts, a, b, n + ".evaluate");
                        return batchEvaluate<dimOf<C>>(c, ts);
                    },
                    s.c);
            },
            py::arg("t"), "Points at many parameters at once (the batch path): (T,) -> (T, D).")
        .def("__call__", [](py::object self, py::handle t) { return self.attr("evaluate")(t); }, py::arg("t"),
             "The same as evaluate(t).")
        .def("__copy__", [](const Py& s) { return s; })
        .def("__deepcopy__", [](const Py& s, py::handle) { return s; }, py::arg("memo"))
        .def(
            "closest_point", [](const Py& s, py::handle p) { return std::visit([&](const auto& c) { return closest(c, p); }, s.c); },
            py::arg("points"),
            "For a point (D,): (u, point (D,), distance); for (N, D): (u (N,), points (N, D), distances (N,)).")
        .def(
            "bounds", [](const Py& s) { return std::visit([](const auto& c) { return boxTuple(tightBox(c)); }, s.c); },
            "(min (D,), max (D,)): the tight axis-aligned box of the curve (NurbsCurve::boundingBox).")
        .def(
            "control_box", [](const Py& s) { return std::visit([](const auto& c) { return boxTuple(c.controlBox()); }, s.c); },
            "(min, max) of the control points (contains the curve: positive weights).");
}

/// The dimension (2 or 3) of pickled homogeneous points (n, 3) or (n, 4).
int homogeneousDim(py::handle h, const std::string& what)
{
    const py::array a = numericArray(h, what);
    if (a.ndim() != 2 || (a.shape(1) != 3 && a.shape(1) != 4))
        throw freeform::Error(what + ": expected an array of shape (n, 3) or (n, 4), got shape " + shapeText(a));
    return static_cast<int>(a.shape(1)) - 1;
}

/// A NURBS result of an operation on a polynomial curve stays polynomial: the operations act on
/// the homogeneous points linearly, and the weight row (all 1) can come back as 1 +- rounding,
/// which would make the result rational (is_rational True). The weight row is set back to 1; the
/// other rows are the operation's own result on the polynomial points.
template <int D>
freeform::NurbsCurve<double, D> keepPolynomial(const freeform::NurbsCurve<double, D>& in, freeform::NurbsCurve<double, D> out)
{
    if (in.isRational() || !out.isRational()) return out;
    auto h = out.homogeneousPoints();
    h.row(D).setOnes();
    return freeform::NurbsCurve<double, D>(out.knotVector(), std::move(h));
}

} // namespace

// ---------------------------------------------------------------- document bridge

py::object partObject(const freeform::Part& part);                          // part.cpp
py::object trimmedSurfaceObject(const freeform::TrimmedSurface& surface);   // part.cpp
std::optional<freeform::ObjectData> partData(py::handle h);                 // part.cpp

py::object geometryObject(const freeform::TypedDocument& doc, const freeform::TypedObject& object)
{
    if (const auto* part = std::get_if<freeform::Part>(&object.geometry())) return partObject(*part);
    if (const auto* t = std::get_if<freeform::TrimmedSurface>(&object.geometry())) return trimmedSurfaceObject(*t);
    py::object o = fromGeometry(object.geometry());
    if (o.is_none())
        throw freeform::Error(doc.what(object) + ": a " + object.type() +
                              " has no Python object (use Document.evaluate / tessellate on it)");
    if (py::isinstance<PyLattice>(o)) o.cast<PyLattice&>().name = object.name();
    return o;
}

freeform::ObjectData objectData(py::handle h)
{
    // The document layer's toData (document/object_data.h), the inverse of buildGeometry.
    const auto data = [](const auto& g) { return freeform::ObjectData(freeform::toData(g)); };
    if (py::isinstance<PyCurve>(h)) return std::visit(data, h.cast<const PyCurve&>().c);
    if (py::isinstance<PySpline>(h)) return std::visit(data, h.cast<const PySpline&>().s);
    if (py::isinstance<PyPatch>(h)) return data(h.cast<const PyPatch&>().p);
    if (py::isinstance<PyLattice>(h)) return data(h.cast<PyLattice&>().snapshot());
    if (py::isinstance<PyRationalCurve>(h)) return std::visit(data, h.cast<const PyRationalCurve&>().c);
    if (py::isinstance<PyNurbsCurve>(h)) return std::visit(data, h.cast<const PyNurbsCurve&>().c);
    if (py::isinstance<PyRationalSurface>(h)) return data(h.cast<const PyRationalSurface&>().s);
    if (py::isinstance<PyNurbsSurface>(h)) return data(h.cast<const PyNurbsSurface&>().s);
    if (auto part = partData(h)) return std::move(*part);
    throw py::type_error("expected a freeform geometry object (BezierCurve, Spline, Patch, Lattice, RationalBezierCurve, "
                         "NurbsCurve, RationalBezierSurface, NurbsSurface, Part, TrimmedSurface), got " +
                         std::string(py::str(py::type::handle_of(h).attr("__name__"))));
}

// ---------------------------------------------------------------- bindings

namespace {

template <int D>
py::object circleOf(py::handle center, double radius)
{
    return py::cast(PyNurbsCurve{freeform::NurbsCurve<double, D>::circle(pointArg<D>(center, "center"), radius)});
}

int centerDim(py::handle center)
{
    const auto v = vector(center, "center");
    if (v.size() != 2 && v.size() != 3)
        throw freeform::Error("center: expected 2 or 3 numbers, got " + std::to_string(v.size()));
    return static_cast<int>(v.size());
}

} // namespace

void bindNurbs(py::module_& m)
{
    // ------------------------------------------------------------ RationalBezierCurve
    py::class_<PyRationalCurve> rc(m, "RationalBezierCurve", R"doc(
A rational Bézier curve in 2D or 3D on [0, 1] (docs/nurbs.md):
f(t) = sum w_i P_i B_i^n(t) / sum w_i B_i^n(t), control points (n+1, D), weights (n+1,) positive.)doc");
    rc.def(py::init([](py::handle points, py::handle weights) {
               int dim = 0;
               py::array a = pointsAnyDim(points, "points", dim);
               const Eigen::VectorXd w = weightVector(weights, "weights");
               if (dim == 2) return PyRationalCurve{RCurve2(columns<2>(a, "points"), w)};
               return PyRationalCurve{RCurve3(columns<3>(a, "points"), w)};
           }),
           py::arg("points"), py::arg("weights"));
    rc.def(py::pickle(
        // The homogeneous points (w P, w) the curve is stored as: the same curve bit for bit.
        [](const PyRationalCurve& s) {
            return py::make_tuple(std::visit([](const auto& c) { return fromColumns(c.homogeneous().controlPoints()); }, s.c));
        },
        [](const py::tuple& t) {
            if (t.size() != 1) throw freeform::Error("RationalBezierCurve.__setstate__: expected 1 field");
            if (homogeneousDim(t[0], "homogeneous_points") == 2)
                return PyRationalCurve{RCurve2(RCurve2::Homogeneous(homogeneousArg<2>(t[0], "homogeneous_points")))};
            return PyRationalCurve{RCurve3(RCurve3::Homogeneous(homogeneousArg<3>(t[0], "homogeneous_points")))};
        }));
    curveCommon(rc, "RationalBezierCurve");
    rc.def_static(
          "circle_arc",
          [](py::handle center, double radius, double start, double sweep) {
              if (centerDim(center) == 2)
                  return PyRationalCurve{RCurve2::circleArc(pointArg<2>(center, "center"), radius, start, sweep)};
              return PyRationalCurve{RCurve3::circleArc(pointArg<3>(center, "center"), radius, start, sweep)};
          },
          py::arg("center"), py::arg("radius"), py::arg("start"), py::arg("sweep"),
          "The exact arc c + r (cos theta, sin theta) from `start` over `sweep` radians (|sweep| <= pi; "
          "quadratic up to 2 pi / 3, cubic beyond), in the plane of the first two coordinates.")
        .def_static(
            "ellipse_arc",
            [](py::handle center, py::handle a, py::handle b, double start, double sweep) {
                if (centerDim(center) == 2)
                    return PyRationalCurve{RCurve2::ellipseArc(pointArg<2>(center, "center"), pointArg<2>(a, "a"),
                                                               pointArg<2>(b, "b"), start, sweep)};
                return PyRationalCurve{RCurve3::ellipseArc(pointArg<3>(center, "center"), pointArg<3>(a, "a"),
                                                           pointArg<3>(b, "b"), start, sweep)};
            },
            py::arg("center"), py::arg("a"), py::arg("b"), py::arg("start"), py::arg("sweep"),
            "The exact elliptic arc c + cos(theta) a + sin(theta) b (|sweep| <= pi).")
        .def_property_readonly(
            "homogeneous_points",
            [](const PyRationalCurve& s) {
                return std::visit([](const auto& c) { return fromColumns(c.homogeneous().controlPoints()); }, s.c);
            },
            "(n+1, D+1): (w_i P_i, w_i).")
        .def(
            "split",
            [](const PyRationalCurve& s, double t) {
                if (!(t > 0 && t < 1)) throw freeform::Error("RationalBezierCurve.split: t " + num(t) + " is not inside (0, 1)");
                return std::visit([&](const auto& c) {
                    auto [a, b] = c.split(t);
                    return py::make_tuple(PyRationalCurve{a}, PyRationalCurve{b});
                }, s.c);
            },
            py::arg("t"), "The pieces over [0, t] and [t, 1], each on [0, 1].")
        .def(
            "elevated",
            [](const PyRationalCurve& s, int times) {
                if (times < 0) throw freeform::Error("RationalBezierCurve.elevated: times " + std::to_string(times) + " is negative");
                return std::visit([&](const auto& c) { return PyRationalCurve{c.elevated(times)}; }, s.c);
            },
            py::arg("times") = 1, "The same curve with the degree raised.")
        .def("reversed", [](const PyRationalCurve& s) { return std::visit([](const auto& c) { return PyRationalCurve{c.reversed()}; }, s.c); },
             "The same curve run backwards: g(t) = f(1 - t).")
        .def("standard_form",
             [](const PyRationalCurve& s) { return std::visit([](const auto& c) { return PyRationalCurve{c.standardForm()}; }, s.c); },
             "The same point set with w_0 = w_n = 1 (Möbius reparametrisation).")
        .def(
            "arc_length",
            [](const PyRationalCurve& s, double tolerance, double a, double b) {
                return std::visit([&](const auto& c) {
                    py::gil_scoped_release release;
                    return c.arcLength(tolerance, a, b);
                }, s.c);
            },
            py::arg("tolerance") = 1e-10, py::arg("start") = 0.0, py::arg("end") = 1.0, "Arc length over [start, end].")
        .def("to_nurbs",
             [](const PyRationalCurve& s) {
                 return std::visit([](const auto& c) {
                     using C = std::decay_t<decltype(c)>;
                     return PyNurbsCurve{freeform::NurbsCurve<double, dimOf<C>>::fromRationalBezier(c)};
                 }, s.c);
             },
             "The same curve as a NurbsCurve (clamped knots 0^(n+1) 1^(n+1)).")
        .def("__repr__", [](const PyRationalCurve& s) {
            return std::visit([&](const auto& c) {
                return "RationalBezierCurve(degree=" + std::to_string(c.degree()) + ", dimension=" +
                       std::to_string(s.c.index() == 0 ? 2 : 3) + ")";
            }, s.c);
        });

    // ------------------------------------------------------------ NurbsCurve
    py::class_<PyNurbsCurve> nc(m, "NurbsCurve", R"doc(
A NURBS curve in 2D or 3D (docs/nurbs.md): C(u) = sum w_i P_i N_(i,p)(u) / sum w_i N_(i,p)(u) on its
own domain [u_p, u_(n+1)] of a general knot vector (clamped, unclamped, periodic, multiple knots).
NurbsCurve(degree, knots (n+p+2,), points (n+1, D), weights (n+1,) or None = all 1).)doc");
    nc.def(py::init([](int degree, py::handle knots, py::handle points, py::handle weights) {
               int dim = 0;
               py::array a = pointsAnyDim(points, "points", dim);
               std::vector<double> k = numberList(knots, "knots");
               const Eigen::VectorXd w = weightVector(weights, "weights");
               if (dim == 2) return PyNurbsCurve{NCurve2(degree, std::move(k), columns<2>(a, "points"), w)};
               return PyNurbsCurve{NCurve3(degree, std::move(k), columns<3>(a, "points"), w)};
           }),
           py::arg("degree"), py::arg("knots"), py::arg("points"), py::arg("weights") = py::none());
    nc.def(py::pickle(
        [](const PyNurbsCurve& s) {
            return std::visit(
                [](const auto& c) { return py::make_tuple(c.degree(), c.knots(), fromColumns(c.homogeneousPoints())); }, s.c);
        },
        [](const py::tuple& t) {
            if (t.size() != 3) throw freeform::Error("NurbsCurve.__setstate__: expected 3 fields");
            const int degree = t[0].cast<int>();
            auto knots = t[1].cast<std::vector<double>>();
            if (homogeneousDim(t[2], "homogeneous_points") == 2)
                return PyNurbsCurve{NCurve2(NCurve2::Knots(std::move(knots), degree, "NurbsCurve"),
                                            homogeneousArg<2>(t[2], "homogeneous_points"))};
            return PyNurbsCurve{NCurve3(NCurve3::Knots(std::move(knots), degree, "NurbsCurve"),
                                        homogeneousArg<3>(t[2], "homogeneous_points"))};
        }));
    curveCommon(nc, "NurbsCurve");
    nc.def_static(
          "circle",
          [](py::handle center, double radius) {
              if (!(radius > 0) || !std::isfinite(radius)) throw freeform::Error("NurbsCurve.circle: radius must be positive and finite");
              return centerDim(center) == 2 ? circleOf<2>(center, radius) : circleOf<3>(center, radius);
          },
          py::arg("center") = std::vector<double>{0.0, 0.0}, py::arg("radius") = 1.0,
          "The exact full circle: quadratic, four quarter arcs on [0, 1] (weights 1 and sqrt(2)/2), in the "
          "plane of the first two coordinates; 2D or 3D as `center`.")
        .def_static(
            "periodic",
            [](int degree, py::handle points, py::handle weights) {
                int dim = 0;
                py::array a = pointsAnyDim(points, "points", dim);
                const Eigen::VectorXd w = weightVector(weights, "weights");
                if (dim == 2) return PyNurbsCurve{NCurve2::periodic(degree, columns<2>(a, "points"), w)};
                return PyNurbsCurve{NCurve3::periodic(degree, columns<3>(a, "points"), w)};
            },
            py::arg("degree"), py::arg("points"), py::arg("weights") = py::none(),
            "The closed C^(p-1) curve on the uniform knots 0..n+2p (the first p points repeated at the end).")
        .def_static(
            "from_bezier",
            [](py::handle curve) -> PyNurbsCurve {
                if (py::isinstance<PyCurve>(curve))
                    return std::visit([](const auto& c) {
                        using C = std::decay_t<decltype(c)>;
                        return PyNurbsCurve{freeform::NurbsCurve<double, C::PointType::RowsAtCompileTime>::fromBezier(c)};
                    }, curve.cast<const PyCurve&>().c);
                if (py::isinstance<PyRationalCurve>(curve))
                    return std::visit([](const auto& c) {
                        using C = std::decay_t<decltype(c)>;
                        return PyNurbsCurve{freeform::NurbsCurve<double, dimOf<C>>::fromRationalBezier(c)};
                    }, curve.cast<const PyRationalCurve&>().c);
                throw py::type_error("NurbsCurve.from_bezier: expected a BezierCurve or RationalBezierCurve");
            },
            py::arg("curve"), "A (rational) Bézier curve as a NURBS on [0, 1] (knots 0^(n+1) 1^(n+1)).")
        .def_static(
            "from_spline",
            [](py::handle spline) {
                if (!py::isinstance<PySpline>(spline)) throw py::type_error("NurbsCurve.from_spline: expected a Spline");
                return splineToNurbs(spline.cast<const PySpline&>());
            },
            py::arg("spline"),
            "A Bézier spline as a NURBS of its degree on [0, sum of intervals], every interior breakpoint d times "
            "(as `freeform convert --to nurbs_curve`; a closed spline's first point repeated at the end).")
        .def_property_readonly("knots", [](const PyNurbsCurve& s) {
            return std::visit([](const auto& c) { return py::array_t<double>(static_cast<py::ssize_t>(c.knots().size()), c.knots().data()); }, s.c);
        }, "(n+p+2,) float64: the knot vector (a copy).")
        .def_property_readonly("control_count", [](const PyNurbsCurve& s) { return std::visit([](const auto& c) { return c.controlCount(); }, s.c); })
        .def_property_readonly("is_rational", [](const PyNurbsCurve& s) { return std::visit([](const auto& c) { return c.isRational(); }, s.c); },
                               "False when every weight is 1 (a polynomial B-spline).")
        .def_property_readonly("domain", [](const PyNurbsCurve& s) {
            return std::visit([](const auto& c) { return py::make_tuple(c.domainStart(), c.domainEnd()); }, s.c);
        }, "(u_p, u_(n+1)).")
        .def_property_readonly("breakpoints", [](const PyNurbsCurve& s) { return std::visit([](const auto& c) { return c.breakpoints(); }, s.c); },
                               "The distinct knots of the domain (piece k of bezier_pieces() spans [b_k, b_(k+1)]).")
        .def_property_readonly(
            "homogeneous_points",
            [](const PyNurbsCurve& s) { return std::visit([](const auto& c) { return fromColumns(c.homogeneousPoints()); }, s.c); },
            "(n+1, D+1): (w_i P_i, w_i).")
        .def(
            "evaluate_with_derivative",
            [](const PyNurbsCurve& s, py::handle t) {
                const auto ts = vector(t, "t");
                return std::visit([&](const auto& c) {
                    using C = std::decay_t<decltype(c)>;
                    requireInRange(ts, c.domainStart(), c.domainEnd(), "NurbsCurve.evaluate_with_derivative");
                    constexpr int D = dimOf<C>;
                    const auto count = static_cast<std::size_t>(ts.size());
                    py::array_t<double> pos({static_cast<py::ssize_t>(count), py::ssize_t{D}});
                    py::array_t<double> d1({static_cast<py::ssize_t>(count), py::ssize_t{D}});
                    double* op = pos.mutable_data();
                    double* od = d1.mutable_data();
                    {
                        py::gil_scoped_release release;
                        typename C::Points bp, bd;
                        for (std::size_t start = 0; start < count; start += kChunk) {
                            const std::size_t len = std::min(kChunk, count - start);
                            c.evaluateManyWithDerivative(ts.data() + start, len, bp, bd);
                            std::copy(bp.data(), bp.data() + D * len, op + D * start);
                            std::copy(bd.data(), bd.data() + D * len, od + D * start);
                        }
                    }
                    return py::make_tuple(pos, d1);
                }, s.c);
            },
            py::arg("t"), "(points (T, D), first derivatives (T, D)) by the batch path.")
        .def(
            "insert_knot",
            [](const PyNurbsCurve& s, double u, int times) {
                return std::visit([&](const auto& c) {
                    py::gil_scoped_release release;
                    return PyNurbsCurve{keepPolynomial(c, c.insertKnot(u, times))};
                }, s.c);
            },
            py::arg("u"), py::arg("times") = 1, "Boehm's insertion of u, `times` times; the curve is unchanged.")
        .def(
            "refined",
            [](const PyNurbsCurve& s, py::handle knots) {
                const std::vector<double> k = numberList(knots, "knots");
                return std::visit([&](const auto& c) {
                    py::gil_scoped_release release;
                    return PyNurbsCurve{keepPolynomial(c, c.refined(k))};
                }, s.c);
            },
            py::arg("knots"), "Knot refinement (Oslo algorithm): every value added; the curve is unchanged.")
        .def(
            "remove_knot",
            [](const PyNurbsCurve& s, double u) {
                return std::visit([&](const auto& c) {
                    auto r = [&] {
                        py::gil_scoped_release release;
                        return c.removeKnot(u);
                    }();
                    return py::make_tuple(PyNurbsCurve{keepPolynomial(c, std::move(r.curve))}, r.error);
                }, s.c);
            },
            py::arg("u"),
            "(curve, error): one occurrence of the interior knot u removed; error bounds max |new - old| "
            "(homogeneous for rational curves), 0 up to rounding when u is removable. freeform.Error when u is "
            "not an interior knot, or (rational curves) when the removal would give a weight that is not "
            "positive: such a knot cannot be removed.")
        .def(
            "elevated",
            [](const PyNurbsCurve& s, int times) {
                return std::visit([&](const auto& c) {
                    py::gil_scoped_release release;
                    return PyNurbsCurve{keepPolynomial(c, c.elevated(times))};
                }, s.c);
            },
            py::arg("times") = 1, "The same curve with degree p + times (each interior knot's multiplicity + times).")
        .def(
            "reduced",
            [](const PyNurbsCurve& s, double tolerance) {
                return std::visit([&](const auto& c) {
                    auto r = [&] {
                        py::gil_scoped_release release;
                        return c.reduced(tolerance);
                    }();
                    return py::make_tuple(PyNurbsCurve{keepPolynomial(c, std::move(r.curve))}, r.error);
                }, s.c);
            },
            py::arg("tolerance") = 0.0,
            "(curve of degree p - 1, error bound); a polynomial curve gives a polynomial curve (is_rational "
            "False). freeform.Error for degree 1, a curve broken at a knot, or (rational curves) a reduced weight "
            "that is not positive.")
        .def(
            "split",
            [](const PyNurbsCurve& s, double u) {
                return std::visit([&](const auto& c) {
                    auto [a, b] = [&] {
                        py::gil_scoped_release release;
                        return c.split(u);
                    }();
                    return py::make_tuple(PyNurbsCurve{keepPolynomial(c, a)}, PyNurbsCurve{keepPolynomial(c, b)});
                }, s.c);
            },
            py::arg("u"), "The pieces over [start, u] and [u, end] (u strictly inside the domain).")
        .def("reversed", [](const PyNurbsCurve& s) { return std::visit([](const auto& c) { return PyNurbsCurve{c.reversed()}; }, s.c); },
             "The same curve run backwards on the same domain: D(u) = C(a + b - u).")
        .def(
            "bezier_pieces",
            [](const PyNurbsCurve& s) {
                py::list out;
                std::visit([&](const auto& c) {
                    const auto pieces = [&] {
                        py::gil_scoped_release release;
                        return c.bezierPieces();
                    }();
                    for (const auto& p : pieces) out.append(PyRationalCurve{p});
                }, s.c);
                return out;
            },
            "Bézier extraction: one RationalBezierCurve per non-empty knot span, each on [0, 1].")
        .def(
            "arc_length",
            [](const PyNurbsCurve& s, double tolerance, std::optional<double> a, std::optional<double> b) {
                return std::visit([&](const auto& c) {
                    const double lo = a.value_or(c.domainStart()), hi = b.value_or(c.domainEnd());
                    py::gil_scoped_release release;
                    return c.arcLength(tolerance, lo, hi);
                }, s.c);
            },
            py::arg("tolerance") = 1e-10, py::arg("start") = py::none(), py::arg("end") = py::none(),
            "Arc length over the domain or [start, end] (adaptive Gauss-Kronrod per knot span).")
        .def(
            "continuity",
            [](const PyNurbsCurve& s) { return continuityList(s.c); },
            "Per interior knot, measured from the geometry: {joint, t (the knot), C, G, jumps}.")
        .def("__repr__", [](const PyNurbsCurve& s) {
            return std::visit([&](const auto& c) {
                return "NurbsCurve(degree=" + std::to_string(c.degree()) + ", control_count=" + std::to_string(c.controlCount()) +
                       ", dimension=" + std::to_string(s.c.index() == 0 ? 2 : 3) + ", rational=" +
                       (c.isRational() ? "True" : "False") + ")";
            }, s.c);
        });
}

} // namespace ffpy
