// The rational and NURBS types for Python (docs/python.md, "Rational Bézier and NURBS"; the math in
// docs/nurbs.md): RationalBezierCurve, NurbsCurve (2D and 3D), RationalBezierSurface, NurbsSurface
// (3D), interpolate_nurbs / approximate_nurbs, RationalLattice (NFFD) and Lattice.deform_curve, and
// the bridge between the document layer's objects and the Python objects (geometryObject,
// objectData) that Document.object / Document.add use.
//
// Arrays as in the rest of the module: control points (n, D), weights (n,) (surfaces: (nu, nv, 3)
// and (nu, nv)), knots (m,); parameters (N,) or (N, 2); results are new float64 arrays. Knots,
// weights and points are checked by the library (freeform.Error with its message: the knot or
// weight by index); non-numeric arrays raise TypeError, wrong shapes and NaN points freeform.Error.

#include "geometry.h"
#include "lattice.h"

#include <freeform/curve/interpolation.h>
#include <freeform/curve/nurbs_continuity.h>
#include <freeform/curve/nurbs_interpolation.h>
#include <freeform/document/object_data.h>
#include <freeform/io/geometry_data.h>
#include <freeform/tessellate/tessellate_rational.h>
#include <freeform/volume/deform.h>
#include <freeform/volume/deform_rational.h>

#include <algorithm>
#include <optional>
#include <type_traits>
#include <vector>

namespace ffpy {

namespace {

using RCurve2 = freeform::RationalBezierCurve<double, 2>;
using RCurve3 = freeform::RationalBezierCurve<double, 3>;
using NCurve2 = freeform::NurbsCurve<double, 2>;
using NCurve3 = freeform::NurbsCurve<double, 3>;
using RSurface = freeform::RationalBezierSurface<double, 3>;
using NSurface = freeform::NurbsSurface<double, 3>;

template <typename C>
constexpr int dimOf = C::PointType::RowsAtCompileTime;

/// Parameters per batch call: the batch result (D x kChunk) stays in cache and is copied straight
/// into the (N, D) output (the same memory layout), instead of a full-size temporary.
constexpr std::size_t kChunk = 4096;

// ---------------------------------------------------------------- argument conversion

/// A 1-D numeric array as a float64 std::vector (finiteness is the library's check).
std::vector<double> numberList(py::handle h, const std::string& what)
{
    py::array a = numericArray(h, what);
    if (a.ndim() != 1) throw freeform::Error(what + ": expected a 1-D array, got shape " + shapeText(a));
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    return std::vector<double>(d.data(), d.data() + d.size());
}

/// Weights (None: empty, all 1) as an Eigen vector: a 1-D array, or for surfaces (ndim2) a 2-D
/// (nu, nv) array flattened in C order (point (i, j) at i * nv + j, the library's layout). Count,
/// sign and finiteness are the library's checks (its message names the weight).
Eigen::VectorXd weightVector(py::handle h, const std::string& what, bool ndim2 = false)
{
    if (h.is_none()) return {};
    py::array a = numericArray(h, what);
    if (a.ndim() != (ndim2 ? 2 : 1))
        throw freeform::Error(what + ": expected a " + (ndim2 ? "2-D (nu, nv)" : "1-D (n,)") + " array, got shape " +
                              shapeText(a));
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    return Eigen::Map<const Eigen::VectorXd>(d.data(), d.size());
}

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

template <int D>
py::tuple boxTuple(const freeform::Box<double, D>& b)
{
    return py::make_tuple(fromVector(b.min()), fromVector(b.max()));
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

py::object geometryObject(const freeform::TypedDocument& doc, const freeform::TypedObject& object)
{
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
    throw py::type_error("expected a freeform geometry object (BezierCurve, Spline, Patch, Lattice, RationalBezierCurve, "
                         "NurbsCurve, RationalBezierSurface, NurbsSurface), got " +
                         std::string(py::str(py::type::handle_of(h).attr("__name__"))));
}

// ---------------------------------------------------------------- bindings

namespace {

struct PyRationalLattice {
    freeform::RationalLattice lattice;
    double strength = 1;
};

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
            const auto d = freeform::rationalSurfaceData(s.s);
            return grid(d.points, s.s.degreeU() + 1, s.s.degreeV() + 1);
        }, "(m+1, n+1, 3) float64 (a copy).")
        .def_property_readonly("weights", [](const PyRationalSurface& s) {
            const auto d = freeform::rationalSurfaceData(s.s);
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
        "RationalBezierCurve or NurbsCurve of degree d (1 + l+m+n) (the rational composition with unit weights).");
}

} // namespace ffpy
