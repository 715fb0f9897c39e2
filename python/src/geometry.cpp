// Curves, splines, patches, documents and mesh files for Python (docs/python.md). Many parameters
// at once: a 1-D array of t gives an (T, D) array; derivatives an (T, K+1, D) array.

#include "geometry.h"
#include "lattice.h"

#include <pybind11/stl.h>

#include <map>

#include <freeform/curve/continuity.h>
#include <freeform/curve/interpolation.h>
#include <freeform/document/document.h>
#include <freeform/io/document.h>
#include <freeform/io/deform_file.h>
#include <freeform/io/mesh_io.h>
#include <freeform/mesh/topology.h>
#include <freeform/tessellate/tessellate.h>

#include <sstream>
#include <type_traits>
#include <variant>

namespace ffpy {

namespace {

py::dict evaluationDict(const freeform::Evaluation& e)
{
    py::dict d;
    d["point"] = fromVector(e.point);
    py::list der;
    for (const auto& v : e.derivatives) der.append(fromVector(v));
    d["derivatives"] = der;
    d["keys"] = e.keys;
    if (e.normal) d["normal"] = fromVector(*e.normal);
    if (e.det) d["det"] = *e.det;
    if (e.face >= 0) d["face"] = e.face;
    if (e.trim) d["trim"] = *e.trim == freeform::TrimClass::Inside ? "inside" : *e.trim == freeform::TrimClass::Outside ? "outside" : "boundary";
    return d;
}

struct PyMesh {
    freeform::MeshFile file;
};

/// A (cols, rows) float64 view of a mesh file's column-major matrix: no copy, `owner` (the Python
/// MeshFile) keeps the data alive.
template <class Matrix>
py::array_t<double> columnsView(py::object owner, Matrix& m)
{
    return py::array_t<double>({static_cast<py::ssize_t>(m.cols()), static_cast<py::ssize_t>(m.rows())}, m.data(), owner);
}

/// Copies an (n, cols) array of a pickled MeshFile's state into `into` (cols x n), which must keep
/// its column count: the file read back from its bytes has as many as the one pickled.
template <class Matrix>
void restoreColumns(Matrix& into, py::handle value, const std::string& what)
{
    const py::array a = rows(value, "MeshFile.__setstate__: " + what, into.rows(), false);
    if (a.shape(0) != into.cols())
        throw freeform::Error("MeshFile.__setstate__: " + what + ": expected " + std::to_string(into.cols()) + " rows, got " +
                              std::to_string(a.shape(0)));
    std::copy(static_cast<const double*>(a.data()), static_cast<const double*>(a.data()) + a.size(), into.data());
}

freeform::MeshFile meshFromBytes(const std::string& path, py::bytes data, py::handle companionsArg)
{
    std::string bytes = data;
    std::map<std::string, std::string> companions;
    if (!companionsArg.is_none())
        for (const auto& [key, value] : companionsArg.cast<py::dict>())
            companions.emplace(key.cast<std::string>(), std::string(value.cast<py::bytes>()));
    py::gil_scoped_release release;
    return freeform::MeshFile::readBytes(path, std::move(bytes), companions);
}

} // namespace

void bindGeometry(py::module_& m)
{
    // ------------------------------------------------------------ BezierCurve
    py::class_<PyCurve>(m, "BezierCurve", "A Bézier curve in 2D or 3D on [0, 1] (control points (n+1, D)).")
        .def(py::init([](py::handle points) {
                 int dim = 0;
                 py::array a = pointsAnyDim(points, "points", dim);
                 if (dim == 2) return PyCurve{Curve2(columns<2>(a, "points"))};
                 return PyCurve{Curve3(columns<3>(a, "points"))};
             }),
             py::arg("points"))
        .def(py::pickle(
            [](const PyCurve& s) {
                return py::make_tuple(std::visit([](const auto& c) { return fromColumns(c.controlPoints()); }, s.c));
            },
            [](const py::tuple& t) {
                if (t.size() != 1) throw freeform::Error("BezierCurve.__setstate__: expected 1 field");
                int dim = 0;
                py::array a = pointsAnyDim(t[0], "points", dim);
                if (dim == 2) return PyCurve{Curve2(columns<2>(a, "points"))};
                return PyCurve{Curve3(columns<3>(a, "points"))};
            }))
        .def("__copy__", [](const PyCurve& s) { return s; })
        .def("__deepcopy__", [](const PyCurve& s, py::handle) { return s; }, py::arg("memo"))
        .def_property_readonly("degree", [](const PyCurve& s) { return std::visit([](const auto& c) { return c.degree(); }, s.c); })
        .def_property_readonly("dimension", [](const PyCurve& s) { return s.c.index() == 0 ? 2 : 3; })
        .def_property_readonly(
            "control_points",
            [](const PyCurve& s) { return std::visit([](const auto& c) { return fromColumns(c.controlPoints()); }, s.c); },
            "(n+1, D) float64 (a copy).")
        .def(
            "evaluate",
            [](const PyCurve& s, py::handle t) {
                const auto ts = vector(t, "t");
                requireInDomain(ts, 1.0, "BezierCurve.evaluate");
                return std::visit(
                    [&](const auto& c) {
                        using C = std::decay_t<decltype(c)>;
                        return batchEvaluate<C::PointType::RowsAtCompileTime>(c, ts);
                    },
                    s.c);
            },
            py::arg("t"), "Points at many parameters t in [0, 1] at once (SIMD batch de Casteljau): (T, D).")
        .def("__call__", [](py::object self, py::handle t) { return self.attr("evaluate")(t); }, py::arg("t"),
             "The same as evaluate(t).")
        .def(
            "derivatives",
            [](const PyCurve& s, py::handle t, int order) {
                if (order < 0) throw freeform::Error("BezierCurve.derivatives: order " + std::to_string(order) + " is negative");
                const auto ts = vector(t, "t");
                requireInDomain(ts, 1.0, "BezierCurve.derivatives");
                return std::visit(
                    [&](const auto& c) {
                        using C = std::decay_t<decltype(c)>;
                        constexpr int D = C::PointType::RowsAtCompileTime;
                        return sampleJets<D>(ts, order, false, [&](double x, int k) { return c.derivatives(x, k); });
                    },
                    s.c);
            },
            py::arg("t"), py::arg("order"), "(T, order+1, D): the point and derivatives 1..order at each t.")
        .def(
            "split",
            [](const PyCurve& s, double t) {
                return std::visit(
                    [&](const auto& c) {
                        auto [a, b] = c.split(t);
                        return py::make_tuple(PyCurve{a}, PyCurve{b});
                    },
                    s.c);
            },
            py::arg("t"), "The pieces on [0, t] and [t, 1].")
        .def(
            "elevated",
            [](const PyCurve& s, int times) { return std::visit([&](const auto& c) { return PyCurve{c.elevated(times)}; }, s.c); },
            py::arg("times") = 1, "The same curve with the degree raised.")
        .def("__repr__", [](const PyCurve& s) {
            return "BezierCurve(degree=" + std::to_string(std::visit([](const auto& c) { return c.degree(); }, s.c)) +
                   ", dimension=" + std::to_string(s.c.index() == 0 ? 2 : 3) + ")";
        });

    // ------------------------------------------------------------ Spline
    py::class_<PySpline>(m, "Spline", R"doc(
A piecewise Bézier spline (2D or 3D): degree, closed, Bézier points (as the bezier_spline format
stores them, docs/splines.md) and intervals; global parameter T in [0, sum of intervals].)doc")
        .def(py::init([](int degree, py::handle points, bool closed, std::optional<std::vector<double>> intervals) {
                 int dim = 0;
                 py::array a = pointsAnyDim(points, "points", dim);
                 const auto iv = intervals.value_or(std::vector<double>{});
                 if (dim == 2) return PySpline{Spline2(degree, closed, columns<2>(a, "points"), iv)};
                 return PySpline{Spline3(degree, closed, columns<3>(a, "points"), iv)};
             }),
             py::arg("degree"), py::arg("points"), py::arg("closed") = false, py::arg("intervals") = py::none())
        .def(py::pickle(
            [](const PySpline& s) {
                return std::visit(
                    [](const auto& c) {
                        return py::make_tuple(c.degree(), fromColumns(c.controlPoints()), c.closed(), c.intervals());
                    },
                    s.s);
            },
            [](const py::tuple& t) {
                if (t.size() != 4) throw freeform::Error("Spline.__setstate__: expected 4 fields");
                const int degree = t[0].cast<int>();
                const bool closed = t[2].cast<bool>();
                const auto iv = t[3].cast<std::vector<double>>();
                int dim = 0;
                py::array a = pointsAnyDim(t[1], "points", dim);
                if (dim == 2) return PySpline{Spline2(degree, closed, columns<2>(a, "points"), iv)};
                return PySpline{Spline3(degree, closed, columns<3>(a, "points"), iv)};
            }))
        .def("__copy__", [](const PySpline& s) { return s; })
        .def("__deepcopy__", [](const PySpline& s, py::handle) { return s; }, py::arg("memo"))
        .def_static(
            "interpolate",
            [](py::handle points, const std::string& end, const std::string& parametrization, py::handle params,
               py::handle startDerivative, py::handle endDerivative) {
                int dim = 0;
                py::array a = pointsAnyDim(points, "points", dim);
                const auto e = freeform::parseInterpolationEnd(end, "end");
                const auto p = freeform::parseParametrization(parametrization, "parametrization");
                if (e != freeform::InterpolationEnd::Clamped && (!startDerivative.is_none() || !endDerivative.is_none()))
                    throw freeform::Error("start_derivative / end_derivative: only with end='clamped'");
                std::vector<double> given;
                if (!params.is_none()) {
                    const auto v = vector(params, "params");
                    given.assign(v.data(), v.data() + v.size());
                }
                auto solve = [&](auto tag) {
                    constexpr int D = decltype(tag)::value;
                    freeform::InterpolationOptions<double, D> o;
                    o.end = e;
                    o.parametrization = p;
                    o.params = given;
                    auto derivative = [&](py::handle h, const char* what) {
                        freeform::Point<double, D> d = freeform::Point<double, D>::Zero();
                        if (h.is_none()) return d;
                        const auto v = vector(h, what);
                        if (v.size() != D)
                            throw freeform::Error(std::string(what) + ": expected " + std::to_string(D) + " numbers, got " +
                                                  std::to_string(v.size()));
                        for (int i = 0; i < D; ++i) d[i] = v.data()[i];
                        return d;
                    };
                    o.startDerivative = derivative(startDerivative, "start_derivative");
                    o.endDerivative = derivative(endDerivative, "end_derivative");
                    return PySpline{freeform::interpolateCubic<double, D>(columns<D>(a, "points"), o)};
                };
                if (dim == 2) return solve(std::integral_constant<int, 2>{});
                return solve(std::integral_constant<int, 3>{});
            },
            py::arg("points"), py::arg("end") = "natural", py::arg("parametrization") = "chord",
            py::arg("params") = py::none(), py::arg("start_derivative") = py::none(),
            py::arg("end_derivative") = py::none(),
            "The C2 cubic spline through points (N, D) (as `freeform interpolate`); end 'natural', 'clamped' "
            "(f' at the ends: start_derivative, end_derivative, zero when not given) or 'periodic'; "
            "parametrization 'uniform', 'chord' or 'centripetal', or the parameter values params (strictly "
            "increasing; for 'periodic' one more than the points).")
        .def_property_readonly("degree", [](const PySpline& s) { return std::visit([](const auto& c) { return c.degree(); }, s.s); })
        .def_property_readonly("dimension", [](const PySpline& s) { return s.s.index() == 0 ? 2 : 3; })
        .def_property_readonly("closed", [](const PySpline& s) { return std::visit([](const auto& c) { return c.closed(); }, s.s); })
        .def_property_readonly("segment_count", [](const PySpline& s) { return std::visit([](const auto& c) { return c.segmentCount(); }, s.s); })
        .def_property_readonly("domain_end", [](const PySpline& s) { return std::visit([](const auto& c) { return c.domainEnd(); }, s.s); })
        .def_property_readonly("knots", [](const PySpline& s) { return std::visit([](const auto& c) { return c.knots(); }, s.s); })
        .def_property_readonly("intervals", [](const PySpline& s) { return std::visit([](const auto& c) { return c.intervals(); }, s.s); })
        .def_property_readonly(
            "control_points",
            [](const PySpline& s) { return std::visit([](const auto& c) { return fromColumns(c.controlPoints()); }, s.s); })
        .def(
            "evaluate",
            [](const PySpline& s, py::handle t) {
                const auto ts = vector(t, "T");
                return std::visit(
                    [&](const auto& c) {
                        using C = std::decay_t<decltype(c)>;
                        constexpr int D = C::PointType::RowsAtCompileTime;
                        requireInDomain(ts, c.domainEnd(), "Spline.evaluate");
                        return sampleJets<D>(ts, 0, true, [&](double x, int k) { return c.derivatives(x, k); });
                    },
                    s.s);
            },
            py::arg("T"), "Points at many global parameters: (T, D).")
        .def("__call__", [](py::object self, py::handle t) { return self.attr("evaluate")(t); }, py::arg("T"),
             "The same as evaluate(T).")
        .def(
            "derivatives",
            [](const PySpline& s, py::handle t, int order) {
                if (order < 0) throw freeform::Error("Spline.derivatives: order " + std::to_string(order) + " is negative");
                const auto ts = vector(t, "T");
                return std::visit(
                    [&](const auto& c) {
                        using C = std::decay_t<decltype(c)>;
                        constexpr int D = C::PointType::RowsAtCompileTime;
                        requireInDomain(ts, c.domainEnd(), "Spline.derivatives");
                        return sampleJets<D>(ts, order, false, [&](double x, int k) { return c.derivatives(x, k); });
                    },
                    s.s);
            },
            py::arg("T"), py::arg("order"), "(T, order+1, D).")
        .def(
            "segment", [](const PySpline& s, int i) {
                return std::visit([&](const auto& c) {
                    if (i < 0 || i >= c.segmentCount()) throw freeform::Error("Spline.segment: no segment " + std::to_string(i));
                    return PyCurve{c.segment(i)};
                }, s.s);
            },
            py::arg("i"), "Segment i as a BezierCurve on [0, 1].")
        .def(
            "split_segment",
            [](const PySpline& s, int i, double t) {
                return std::visit([&](const auto& c) {
                    if (i < 0 || i >= c.segmentCount()) throw freeform::Error("Spline.split_segment: no segment " + std::to_string(i));
                    return PySpline{c.splitSegment(i, t)};
                }, s.s);
            },
            py::arg("i"), py::arg("t"), "The same spline with segment i split at local t (one more joint).")
        .def(
            "elevated", [](const PySpline& s, int times) { return std::visit([&](const auto& c) { return PySpline{c.elevated(times)}; }, s.s); },
            py::arg("times") = 1)
        .def(
            "continuity",
            [](const PySpline& s) { return continuityList(s.s); },
            "Per joint: {joint, t, C (parametric, -1..n), G (geometric, -1..2), jumps}.")
        .def("__repr__", [](const PySpline& s) {
            return std::visit([&](const auto& c) {
                return "Spline(degree=" + std::to_string(c.degree()) + ", segments=" + std::to_string(c.segmentCount()) +
                       ", closed=" + (c.closed() ? "True" : "False") + ", dimension=" +
                       std::to_string(s.s.index() == 0 ? 2 : 3) + ")";
            }, s.s);
        });

    // ------------------------------------------------------------ Patch
    py::class_<PyPatch>(m, "Patch", "A Bézier patch in 3D of degrees (p, q): control points (p+1, q+1, 3) on [0,1]^2.")
        .def(py::init([](py::handle points) {
                 py::array a = numericArray(points, "points");
                 if (a.ndim() != 3 || a.shape(2) != 3)
                     throw freeform::Error("points: expected an array of shape (p+1, q+1, 3), got shape " + shapeText(a));
                 const int p = static_cast<int>(a.shape(0)) - 1, q = static_cast<int>(a.shape(1)) - 1;
                 auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
                 requireFiniteRows(d.data(), static_cast<std::size_t>((p + 1) * (q + 1)), 3, "points");
                 freeform::PointMatrix<double, 3> cols = Eigen::Map<const freeform::PointMatrix<double, 3>>(d.data(), 3, (p + 1) * (q + 1));
                 return PyPatch{freeform::BezierSurface<double, 3>(p, q, cols)};
             }),
             py::arg("points"))
        .def(py::pickle(
            [](const PyPatch& s) {
                return py::make_tuple(s.p.degreeU(), s.p.degreeV(), fromColumns(s.p.controlPoints()));
            },
            [](const py::tuple& t) {
                if (t.size() != 3) throw freeform::Error("Patch.__setstate__: expected 3 fields");
                const int p = t[0].cast<int>(), q = t[1].cast<int>();
                const py::array a = rows(t[2], "points", 3, false);
                return PyPatch{freeform::BezierSurface<double, 3>(p, q, columns<3>(a, "points"))};
            }))
        .def("__copy__", [](const PyPatch& s) { return s; })
        .def("__deepcopy__", [](const PyPatch& s, py::handle) { return s; }, py::arg("memo"))
        .def_property_readonly("degree", [](const PyPatch& s) { return py::make_tuple(s.p.degreeU(), s.p.degreeV()); })
        .def_property_readonly("control_points", [](const PyPatch& s) {
            return fromColumns(s.p.controlPoints()).attr("reshape")(s.p.degreeU() + 1, s.p.degreeV() + 1, 3);
        })
        .def(
            "evaluate",
            [](const PyPatch& s, py::handle uv) {
                const py::array a = rows(uv, "uv", 2, false);
                const auto n = a.shape(0);
                const double* p = static_cast<const double*>(a.data());
                for (py::ssize_t i = 0; i < 2 * n; ++i)
                    if (!(p[i] >= 0 && p[i] <= 1))
                        throw freeform::Error("Patch.evaluate: uv row " + std::to_string(i / 2) + " outside [0, 1]^2");
                py::array_t<double> out({n, py::ssize_t{3}});
                double* o = out.mutable_data();
                {
                    py::gil_scoped_release release;
                    for (py::ssize_t i = 0; i < n; ++i) {
                        const Eigen::Vector3d x = s.p.evaluate(p[2 * i], p[2 * i + 1]);
                        o[3 * i] = x[0];
                        o[3 * i + 1] = x[1];
                        o[3 * i + 2] = x[2];
                    }
                }
                return out;
            },
            py::arg("uv"), "Points at many (u, v) (N, 2): (N, 3).")
        .def(
            "partial",
            [](const PyPatch& s, int a, int b, py::handle uv) {
                const py::array arr = rows(uv, "uv", 2, false);
                const auto n = arr.shape(0);
                const double* p = static_cast<const double*>(arr.data());
                py::array_t<double> out({n, py::ssize_t{3}});
                double* o = out.mutable_data();
                py::gil_scoped_release release;
                for (py::ssize_t i = 0; i < n; ++i) {
                    const Eigen::Vector3d x = s.p.partial(a, b, p[2 * i], p[2 * i + 1]);
                    o[3 * i] = x[0];
                    o[3 * i + 1] = x[1];
                    o[3 * i + 2] = x[2];
                }
                return out;
            },
            py::arg("a"), py::arg("b"), py::arg("uv"), "d^(a+b) f / du^a dv^b at many (u, v): (N, 3).")
        .def(
            "normal",
            [](const PyPatch& s, py::handle uv) {
                const py::array arr = rows(uv, "uv", 2, false);
                const auto n = arr.shape(0);
                const double* p = static_cast<const double*>(arr.data());
                Points3 out(3, n);
                {
                    py::gil_scoped_release release;
                    for (py::ssize_t i = 0; i < n; ++i) out.col(i) = s.p.normal(p[2 * i], p[2 * i + 1]);
                }
                return fromColumns(out);
            },
            py::arg("uv"))
        .def("split_u", [](const PyPatch& s, double t) { auto [a, b] = s.p.splitU(t); return py::make_tuple(PyPatch{a}, PyPatch{b}); },
             py::arg("t"), "The pieces over [0, t] and [t, 1] in u, each on [0, 1]^2.")
        .def("split_v", [](const PyPatch& s, double t) { auto [a, b] = s.p.splitV(t); return py::make_tuple(PyPatch{a}, PyPatch{b}); },
             py::arg("t"), "The pieces over [0, t] and [t, 1] in v, each on [0, 1]^2.")
        .def("elevated", [](const PyPatch& s, int du, int dv) { return PyPatch{s.p.elevatedU(du).elevatedV(dv)}; },
             py::arg("du") = 1, py::arg("dv") = 1)
        .def(
            "tessellate",
            [](const PyPatch& s, int segments) {
                freeform::PatchComplex c;
                c.patches.push_back(s.p);
                freeform::TessellationOptions o;
                o.segmentsU = o.segmentsV = segments;
                freeform::PolygonMesh mesh;
                {
                    py::gil_scoped_release release;
                    mesh = freeform::tessellate(c, o);
                }
                return meshArrays(mesh);
            },
            py::arg("segments") = 8, "(V (n, 3), F (m, 3) int32, N (n, 3)).")
        .def("__repr__", [](const PyPatch& s) {
            return "Patch(degree=(" + std::to_string(s.p.degreeU()) + ", " + std::to_string(s.p.degreeV()) + "))";
        });

    // ------------------------------------------------------------ Document
    py::class_<freeform::TypedDocument>(m, "Document", R"doc(
A freeform document (docs/format.md) read through the document layer: every object's geometry built
and validated on load (freeform.Error with the library's message otherwise).)doc")
        .def_static(
            "load",
            [](const std::string& path) {
                py::gil_scoped_release release;
                return freeform::TypedDocument::read(path);
            },
            py::arg("path"))
        .def(py::init([]() { return freeform::TypedDocument(); }), "An empty document (add objects, then save).")
        .def(py::pickle(
            // Its defining fields: the document as its own JSON text (every number in shortest
            // round-trip form, so the objects come back bit for bit; editor settings kept), the
            // source name and the folder that resolves relative mesh paths.
            [](const freeform::TypedDocument& d) {
                return py::make_tuple(freeform::formatDocument(d.toDocument()), d.source, d.directory);
            },
            [](const py::tuple& t) {
                if (t.size() != 3) throw freeform::Error("Document.__setstate__: expected 3 fields");
                const auto source = t[1].cast<std::string>();
                freeform::Document doc = freeform::parseDocument(t[0].cast<std::string>(), source);
                doc.source = source;
                freeform::TypedDocument typed(doc, t[2].cast<std::string>());
                typed.source = source;
                return typed;
            }))
        .def("__copy__", [](const freeform::TypedDocument& d) { return d; })
        .def("__deepcopy__", [](const freeform::TypedDocument& d, py::handle) { return d; }, py::arg("memo"))
        .def(
            "save",
            [](const freeform::TypedDocument& d, const std::string& path) {
                const freeform::Document doc = d.toDocument();
                py::gil_scoped_release release;
                freeform::writeDocument(doc, path);
            },
            py::arg("path"), "Writes the document (atomically).")
        .def_property_readonly("names", [](const freeform::TypedDocument& d) {
            std::vector<std::string> n;
            for (const auto& o : d.objects()) n.push_back(o.name());
            return n;
        })
        .def("type", [](const freeform::TypedDocument& d, const std::string& name) { return d.object(name).type(); },
             py::arg("name"), "The object's type string ('bezier_curve', 'lattice', ...).")
        .def("__len__", [](const freeform::TypedDocument& d) { return d.objects().size(); })
        .def("__contains__", [](const freeform::TypedDocument& d, const std::string& n) { return d.find(n) != nullptr; },
             py::arg("name"), "Whether the document has an object called name.")
        .def(
            "evaluate",
            [](const freeform::TypedDocument& d, const std::string& name, std::vector<double> at, int order) {
                const auto& o = d.object(name);
                freeform::Evaluation e;
                {
                    py::gil_scoped_release release;
                    e = freeform::evaluate(d, o, at, order);
                }
                return evaluationDict(e);
            },
            py::arg("name"), py::arg("at"), py::arg("order") = 0,
            "As `freeform eval`: at = [t], [u, v], [s, t, u] or [face, u, v] (subdivision limit surface); "
            "returns {point, derivatives, keys, normal?, det?, face?}.")
        .def(
            "continuity",
            [](const freeform::TypedDocument& d, const std::string& name) {
                const auto& o = d.object(name);
                const auto report = [&] {
                    py::gil_scoped_release release;
                    return freeform::continuity(d, o);
                }();
                py::list out;
                for (const auto& j : report) out.append(continuityDict(j));
                return out;
            },
            py::arg("name"))
        .def(
            "curve",
            [](const freeform::TypedDocument& d, const std::string& name) -> py::object {
                const auto& o = d.object(name);
                auto c = freeform::AnyCurve::of(o);
                if (!c) throw freeform::Error(d.what(o) + ": is a " + o.type() + ", not a curve or spline");
                if (c->isRational()) return geometryObject(d, o); // RationalBezierCurve, NurbsCurve
                return std::visit(
                    [](const auto& v) -> py::object {
                        using V = std::decay_t<decltype(v)>;
                        if constexpr (std::is_same_v<V, Curve2> || std::is_same_v<V, Curve3>) return py::cast(PyCurve{v});
                        else if constexpr (std::is_same_v<V, freeform::BezierSpline<double, 2>> ||
                                           std::is_same_v<V, freeform::BezierSpline<double, 3>>)
                            return py::cast(PySpline{v});
                        else return py::none(); // the rational forms: above
                    },
                    c->variant());
            },
            py::arg("name"),
            "A curve object as a BezierCurve, a spline (bezier or de Boor) as a Spline (Bézier form), a "
            "rational_bezier_curve as a RationalBezierCurve, a nurbs_curve as a NurbsCurve.")
        .def(
            "object", [](const freeform::TypedDocument& d, const std::string& name) { return geometryObject(d, d.object(name)); },
            py::arg("name"),
            "The object's geometry as its Python type: BezierCurve, Spline (bezier_spline, deboor_spline in Bézier "
            "form), Patch, Lattice, RationalBezierCurve, NurbsCurve, RationalBezierSurface, NurbsSurface "
            "(freeform.Error for deboor_surface and subdivision_surface, which have none).")
        .def(
            "add",
            [](freeform::TypedDocument& d, const std::string& name, py::handle object) {
                if (d.find(name)) throw freeform::Error(d.source + ": an object named \"" + name + "\" exists already (use replace)");
                d.add(name, objectData(object));
            },
            py::arg("name"), py::arg("object"),
            "Appends a geometry object (any type Document.object returns) under a new name, validated by the "
            "document layer as on load.")
        .def(
            "replace",
            [](freeform::TypedDocument& d, const std::string& name, py::handle object) {
                d.replace(d.object(name).id(), objectData(object));
            },
            py::arg("name"), py::arg("object"), "Replaces an object's geometry (its name, place and editor settings kept).")
        .def(
            "remove", [](freeform::TypedDocument& d, const std::string& name) { d.remove(d.object(name).id()); }, py::arg("name"))
        .def(
            "convert",
            [](freeform::TypedDocument& d, const std::string& name, const std::string& to, std::optional<std::string> end) {
                const auto& o = d.object(name);
                const freeform::KindInfo* target = freeform::findKind(to);
                const bool spline = target && target->supports(freeform::KindOperation::ConvertSpline);
                if (!spline && end) throw freeform::Error("end: goes with to='deboor_spline' only");
                // An object of the requested kind already: nothing to convert, the object is kept
                // as it is (bit for bit), as converting a bezier_spline to bezier_spline does.
                if (!spline && o.type() == to) return to;
                std::optional<freeform::EndCondition> e;
                if (end) e = freeform::parseEndCondition(*end, "end");
                freeform::convertObject(d, o.id(), to, e); // the route is the kind table's
                return to;
            },
            py::arg("name"), py::arg("to"), py::arg("end") = py::none(),
            "As `freeform convert --object NAME --to TO`: bezier_spline <-> deboor_spline (end for de Boor), "
            "curves/splines/patches -> nurbs_curve / nurbs_surface, a nurbs object -> its Bézier form "
            "(bezier_spline, rational_bezier_curve, bezier_surface, rational_bezier_surface). Returns the new type. "
            "An object already of type `to` is left as it is (no error).")
        .def(
            "patch",
            [](const freeform::TypedDocument& d, const std::string& name) {
                const auto& o = d.object(name);
                const auto* s = std::get_if<freeform::BezierSurface<double, 3>>(&o.geometry());
                if (!s) throw freeform::Error(d.what(o) + ": is a " + o.type() + ", not a bezier_surface");
                return PyPatch{*s};
            },
            py::arg("name"))
        .def(
            "lattice",
            [](const freeform::TypedDocument& d, const std::string& name) {
                const auto& o = d.object(name);
                const auto* l = std::get_if<freeform::Lattice>(&o.geometry());
                if (!l) throw freeform::Error(d.what(o) + ": is a " + o.type() + ", not a lattice");
                return PyLattice(*l, o.name());
            },
            py::arg("name"))
        .def(
            "tessellate",
            [](const freeform::TypedDocument& d, const std::string& name, int segments, double tolerance) {
                const auto& o = d.object(name);
                freeform::ObjectTessellation t;
                t.segments = segments;
                t.tolerance = tolerance;
                std::optional<freeform::PolygonMesh> mesh;
                {
                    py::gil_scoped_release release;
                    mesh = freeform::tessellateObject(o, t);
                }
                if (!mesh) throw freeform::Error(d.what(o) + ": a " + o.type() + " is not tessellated (surfaces and subdivision surfaces are)");
                return meshArrays(*mesh);
            },
            py::arg("name"), py::arg("segments") = 8, py::arg("tolerance") = 0.0,
            "A surface (its patches) or subdivision surface (its limit surface, `segments` the level) as "
            "(V (n, 3), F (m, 3) int32, N (n, 3) or None).")
        .def(
            "deform",
            [](freeform::TypedDocument& d, PyLattice& lat) {
                const freeform::Lattice l = lat.snapshot();
                freeform::DeformDocumentOptions o;
                o.strength = lat.strength;
                freeform::DeformDocumentReport r;
                {
                    py::gil_scoped_release release;
                    r = freeform::deformDocument(d, l, o);
                }
                py::list objects, skipped;
                for (const auto& x : r.objects) {
                    py::dict e;
                    e["name"] = x.name; e["from"] = x.from; e["type"] = x.type; e["degree"] = x.degree;
                    e["inside"] = x.inside; e["exact"] = x.exact; e["note"] = x.note;
                    objects.append(e);
                }
                for (const auto& x : r.skipped) {
                    py::dict e;
                    e["name"] = x.name; e["type"] = x.type; e["reason"] = x.reason;
                    skipped.append(e);
                }
                py::dict out;
                out["objects"] = objects;
                out["skipped"] = skipped;
                out["certificate"] = freeform::toString(r.certificate.verdict);
                return out;
            },
            py::arg("lattice"), "Deforms every object in place, one rule per type (docs/ffd.md, as `freeform ffd DOC`).")
        .def("__repr__", [](const freeform::TypedDocument& d) {
            return "Document(source='" + d.source + "', objects=" + std::to_string(d.objects().size()) + ")";
        });

    // ------------------------------------------------------------ MeshFile
    py::class_<PyMesh>(m, "MeshFile", R"doc(
A mesh file read losslessly (OBJ, PLY, STL, OFF, glTF/GLB; docs/mesh-io.md): positions (and
normals) are writable (P, 3) float64 views of the file's own numbers; write() keeps everything
else of the file as read.)doc")
        .def_static(
            "read",
            [](const std::string& path) {
                py::gil_scoped_release release;
                return PyMesh{freeform::MeshFile::read(path)};
            },
            py::arg("path"))
        .def_static(
            "read_bytes",
            [](const std::string& path, py::bytes data, py::handle companions) {
                return PyMesh{meshFromBytes(path, data, companions)};
            },
            py::arg("path"), py::arg("data"), py::arg("companions") = py::none(),
            "The file's bytes already in memory, read as read(path) reads the file (path gives the format by its "
            "extension and names the file; the disk is never touched). companions: a .gltf's external buffers, "
            "{path relative to the file's folder, as the uri names it: bytes}.")
        .def("file_bytes", [](const PyMesh& m) { return py::bytes(m.file.bytes()); },
             "The file as read, byte for byte (not as write() would write it now).")
        .def_property_readonly(
            "companions",
            [](const PyMesh& m) {
                py::dict d;
                for (const auto& [name, bytes] : m.file.companions()) d[py::str(name)] = py::bytes(bytes);
                return d;
            },
            "A .gltf's external buffers as read, {relative path: bytes}; empty for the other formats.")
        .def("__copy__", [](const PyMesh& m) { return m; })
        .def("__deepcopy__", [](const PyMesh& m, py::handle) { return m; }, py::arg("memo"))
        .def(py::pickle(
            // Its defining fields: the file as read (and a .gltf's external buffers), which hold
            // everything a write keeps, and the editable numbers as they are now. Unpickling
            // reads the bytes from memory (never the disk), then puts the numbers back.
            [](const PyMesh& m) {
                py::dict companions;
                for (const auto& [name, bytes] : m.file.companions()) companions[py::str(name)] = py::bytes(bytes);
                return py::make_tuple(m.file.path(), py::bytes(m.file.bytes()), companions, fromColumns(m.file.positions()),
                                      fromColumns(m.file.normals()), fromColumns(m.file.tangents()));
            },
            [](const py::tuple& t) {
                if (t.size() != 6) throw freeform::Error("MeshFile.__setstate__: expected 6 fields, got " + std::to_string(t.size()));
                PyMesh m{meshFromBytes(t[0].cast<std::string>(), t[1].cast<py::bytes>(), t[2])};
                restoreColumns(m.file.positions(), t[3], "positions");
                restoreColumns(m.file.normals(), t[4], "normals");
                restoreColumns(m.file.tangents(), t[5], "tangents");
                return m;
            }))
        .def_property(
            "positions",
            [](py::object self) { return columnsView(self, self.cast<PyMesh&>().file.positions()); },
            [](PyMesh& self, py::handle v) {
                const py::array a = rows(v, "positions", 3, false);
                if (a.shape(0) != self.file.positions().cols())
                    throw freeform::Error("positions: expected " + std::to_string(self.file.positions().cols()) + " rows, got " +
                                          std::to_string(a.shape(0)));
                std::copy(static_cast<const double*>(a.data()), static_cast<const double*>(a.data()) + a.size(),
                          self.file.positions().data());
            },
            "(P, 3) float64 view of the file's positions (no copy; in file order).")
        .def_property_readonly(
            "normals",
            [](py::object self) { return columnsView(self, self.cast<PyMesh&>().file.normals()); },
            "(N, 3) float64 view of the file's normal records (may be empty).")
        .def_property_readonly("normal_anchors", [](const PyMesh& m) { return m.file.normalAnchors(); })
        .def_property_readonly(
            "tangents",
            [](py::object self) { return columnsView(self, self.cast<PyMesh&>().file.tangents()); },
            "(T, 4) float64 view of the file's tangents (xyz and handedness w; glTF only, may be empty).")
        .def_property_readonly("format", [](const PyMesh& m) { return m.file.format(); })
        .def_property_readonly("path", [](const PyMesh& m) { return m.file.path(); })
        .def(
            "write",
            [](const PyMesh& m, const std::string& path) {
                py::gil_scoped_release release;
                m.file.write(path);
            },
            py::arg("path"), "Writes the file back (same format: only positions/normals/tangents changed; atomic).")
        .def("to_arrays", [](const PyMesh& m) {
                freeform::PolygonMesh mesh;
                {
                    py::gil_scoped_release release;
                    mesh = m.file.toPolygonMesh();
                }
                return meshArrays(mesh);
            },
             "(V (n, 3), faces ((F, k) int32 when every face has k corners, else a list), normals or None).")
        .def(
            "deform",
            [](PyMesh& m, PyLattice& lat, const std::string& normals, py::handle threadsArg) {
                const int threads = threadCount(threadsArg);
                const freeform::Lattice l = lat.snapshot();
                const auto mode = freeform::parseNormalMode(normals, "normals");
                freeform::DeformOptions opt;
                opt.strength = lat.strength;
                opt.threads = threads;
                freeform::MeshFileDeformation r;
                {
                    py::gil_scoped_release release;
                    r = freeform::deformMeshFile(l, m.file, opt, mode);
                }
                py::dict d;
                d["vertices"] = r.report.vertices;
                d["outside"] = r.report.outside;
                d["min_det_j"] = r.report.minDetJ;
                d["max_det_j"] = r.report.maxDetJ;
                d["fold_count"] = r.report.foldCount;
                d["folds"] = r.report.folds;
                return d;
            },
            py::arg("lattice"), py::arg("normals") = "jacobian", py::arg("threads") = 0,
            "Deforms the file in place as `freeform ffd MESH` does (io/deform_file.h): positions through the "
            "lattice, normals by cof(J) ('jacobian') or recomputed ('recompute'), tangents by J; returns the report.")
        .def("info", [](const PyMesh& m) {
            freeform::PolygonMesh mesh;
            {
                py::gil_scoped_release release;
                mesh = m.file.toPolygonMesh();
            }
            py::dict d;
            d["format"] = m.file.format();
            d["positions"] = m.file.positions().cols();
            d["normals"] = m.file.normals().cols();
            d["tangents"] = m.file.tangents().cols();
            d["faces"] = mesh.faceCount();
            // The topology counts of `freeform info` (docs/cli.md), same keys, of the file at path() as
            // that command reads it (readPolygonMesh: STL corners welded, which MeshFile never does).
            freeform::MeshReport r;
            {
                py::gil_scoped_release release;
                r = freeform::meshReport(freeform::readPolygonMesh(m.file.path()));
            }
            d["vertices"] = r.vertices;
            d["edges"] = r.edges;
            d["boundary_edges"] = r.boundaryEdges;
            d["boundary_loops"] = r.boundaryLoops;
            d["components"] = r.components;
            d["manifold"] = r.manifold;
            d["closed"] = r.closed;
            d["euler"] = r.euler;
            d["genus"] = r.genus ? py::object(py::int_(*r.genus)) : py::object(py::none());
            return d;
        }, "Counts: format, positions, normals, tangents, faces, and the topology of `freeform info` "
           "(vertices, edges, boundary_edges, boundary_loops, components, manifold, closed, euler, genus) of the file "
           "at path as that command reads it (STL corners welded).")
        .def("__repr__", [](const PyMesh& m) {
            return "MeshFile(path='" + m.file.path() + "', format='" + m.file.format() + "', positions=" +
                   std::to_string(m.file.positions().cols()) + ")";
        });
}

} // namespace ffpy
