// freeform.Lattice: fit, load/save (the lattice object of a document), deform (N, 3) positions in
// place of the caller's dtype, normals by cof(J), det J, the fold-over certificate, direct
// manipulation; and freeform.Binding (Lattice.bind). The computations on the points and the
// sensitivities d out / d P = strength * W (docs/python.md, "Sensitivities"): lattice_points.cpp.

#include "lattice.h"
#include "lattice_points.h"

#include <pybind11/stl.h>

#include <freeform/core/parallel.h>
#include <freeform/document/document.h>
#include <freeform/io/document.h>
#include <freeform/io/geometry_data.h>
#include <freeform/volume/deform.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <limits>
#include <sstream>
#include <optional>
#include <variant>
#include <vector>

namespace ffpy {

namespace {

using freeform::Lattice;

py::array_t<double> pointArray(const Points3& p)
{
    py::array_t<double> out({static_cast<py::ssize_t>(p.cols()), py::ssize_t{3}});
    std::copy(p.data(), p.data() + p.size(), out.mutable_data());
    return out;
}

} // namespace

PyLattice::PyLattice(freeform::Lattice l, std::string n)
    : lattice(std::move(l)), points(pointArray(lattice.controlPoints())), name(std::move(n))
{
}

freeform::Lattice PyLattice::snapshot()
{
    if (points.ndim() != 2 || points.shape(1) != 3 || points.shape(0) != lattice.pointCount())
        throw freeform::Error("Lattice.control_points: expected shape (" + std::to_string(lattice.pointCount()) +
                              ", 3), got " + shapeText(points));
    const Eigen::Map<const Points3> p(points.data(), 3, points.shape(0));
    if (p != lattice.controlPoints()) {
        requireFiniteRows(points.data(), static_cast<std::size_t>(points.shape(0)), 3, "Lattice.control_points");
        lattice.setControlPoints(p);
    }
    if (!std::isfinite(strength)) throw freeform::Error("Lattice.strength: not finite");
    return lattice;
}

namespace {

py::dict certificateDict(const freeform::Certificate& c)
{
    py::dict d;
    d["verdict"] = freeform::toString(c.verdict);
    d["min_coefficient"] = c.minCoefficient;
    d["max_coefficient"] = c.maxCoefficient;
    d["witness"] = fromVector(c.witness);
    d["boxes"] = c.boxes;
    return d;
}

PyLattice load(const std::string& path, const std::optional<std::string>& name)
{
    freeform::Document doc;
    {
        py::gil_scoped_release release;
        doc = freeform::readDocument(path);
    }
    const freeform::DocumentObject& object = freeform::findLattice(doc, name, "give name=");
    const freeform::Geometry geometry =
        freeform::buildGeometry(object.data, "", doc.source + ": object \"" + object.name + "\"");
    return PyLattice(std::get<freeform::Lattice>(geometry), object.name);
}

std::array<int, 3> degreeOf(py::handle h)
{
    if (py::isinstance<py::int_>(h)) {
        const int d = h.cast<int>();
        return {d, d, d};
    }
    const auto v = h.cast<std::vector<int>>();
    if (v.size() != 3) throw freeform::Error("degree: expected an int or three ints, got " + std::to_string(v.size()));
    return {v[0], v[1], v[2]};
}

std::string repr(const PyLattice& l)
{
    std::ostringstream s;
    const auto& d = l.lattice.degrees();
    s << "Lattice(name='" << l.name << "', degree=(" << d[0] << ", " << d[1] << ", " << d[2]
      << "), control_points=" << l.lattice.pointCount() << ", outside='" << freeform::toString(l.lattice.outside())
      << "', strength=" << l.strength << ")";
    return s.str();
}

/// Points bound to a lattice's frame (FfdBinding): lattice coordinates computed once, deform()
/// re-evaluates only the deformation as control points move (an optimisation loop's inner call).
struct PyBinding {
    std::variant<freeform::FfdBinding<double>, freeform::FfdBinding<float>> binding;
    bool isFloat = false;
    std::size_t count = 0;
};

/// The state of a Lattice for pickling: its defining fields (the control points as edited).
py::tuple latticeState(PyLattice& l)
{
    const Lattice lat = l.snapshot();
    const auto& d = lat.degrees();
    py::array_t<double> axes({py::ssize_t{3}, py::ssize_t{3}});
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) axes.mutable_at(r, c) = lat.axes()(r, c);
    return py::make_tuple(py::make_tuple(d[0], d[1], d[2]), fromVector(lat.origin()), axes,
                          pointArray(lat.controlPoints()), freeform::toString(lat.outside()), l.strength, l.name);
}

/// The frame (origin, axes) of a Lattice call, checked before any element is read.
Eigen::Vector3d originArg(py::handle h)
{
    py::array a = numericArray(h, "origin");
    requireShape(a, "origin", {3});
    const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    requireFiniteRows(d.data(), 1, 3, "origin");
    return Eigen::Map<const Eigen::Vector3d>(d.data());
}

Eigen::Matrix3d axesArg(py::handle h)
{
    py::array a = numericArray(h, "axes");
    requireShape(a, "axes", {3, 3}, " (columns S, T, U)");
    const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    requireFiniteRows(d.data(), 3, 3, "axes");
    Eigen::Matrix3d m;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m(r, c) = d.data()[3 * r + c];
    return m;
}

PyLattice latticeFromState(const py::tuple& t)
{
    if (t.size() != 7) throw freeform::Error("Lattice.__setstate__: expected 7 fields, got " + std::to_string(t.size()));
    const auto d = degreeOf(t[0]);
    const Eigen::Vector3d o = originArg(t[1]);
    const Eigen::Matrix3d ax = axesArg(t[2]);
    const auto policy = freeform::parseOutsidePolicy(t[4].cast<std::string>(), "outside");
    PyLattice l(Lattice(d, o, ax, toPoints(t[3], "control_points"), policy), t[6].cast<std::string>());
    l.strength = t[5].cast<double>();
    if (!std::isfinite(l.strength)) throw freeform::Error("Lattice.strength: not finite");
    return l;
}

template <typename Scalar>
py::array bindingDeform(const freeform::FfdBinding<Scalar>& b, const Lattice& lat, double strength, int threads,
                        py::handle outArg)
{
    const auto n = static_cast<py::ssize_t>(b.size());
    py::array_t<Scalar> out;
    if (outArg.is_none()) {
        out = py::array_t<Scalar>({n, py::ssize_t{3}});
    } else {
        py::array a = py::array::ensure(outArg);
        if (!a || !py::isinstance<py::array_t<Scalar>>(a) || !isCContiguous(a) || a.ndim() != 2 || a.shape(0) != n ||
            a.shape(1) != 3 || !a.writeable())
            throw freeform::Error("out: expected a writable C-contiguous (" + std::to_string(n) + ", 3) array of " +
                                  std::string(py::str(py::dtype::of<Scalar>())));
        out = py::array_t<Scalar>(a);
    }
    freeform::FfdOutputs<Scalar> o;
    o.positions = out.mutable_data();
    freeform::DeformOptions options;
    options.strength = strength;
    options.threads = threads;
    {
        py::gil_scoped_release release;
        b.deform(lat, o, options);
        // Only extrapolation (or an enormous displacement) can overflow: check the output then,
        // not on every call of the fast path.
        const double limit = static_cast<double>(std::numeric_limits<Scalar>::max()) / 8;
        if (lat.outside() == freeform::OutsidePolicy::Extrapolate ||
            std::abs(strength) * lat.displacements().cwiseAbs().maxCoeff() > limit)
            freeform::parallelFor(0, b.size(), kGrain, threads, [&](int, std::size_t first, std::size_t last) {
                requireFiniteOutput(o.positions + 3 * first, last - first, 3, first, "the position", lat);
            });
    }
    return out;
}

template <typename Scalar>
py::tuple bindingState(const freeform::FfdBinding<Scalar>& b)
{
    const Lattice& lat = b.boundLattice();
    py::array_t<Scalar> positions({static_cast<py::ssize_t>(b.size()), py::ssize_t{3}});
    b.copyPositions(positions.mutable_data());
    PyLattice frame(lat);
    return py::make_tuple(latticeState(frame), positions);
}

} // namespace

/// The rows of `a` as an (K, 3) float64 block checked against the lattice's K.
py::array_t<double, py::array::c_style> controlBlock(py::handle h, const Lattice& lat, const std::string& what)
{
    py::array a = rows(h, what, 3, false);
    if (a.shape(0) != lat.pointCount())
        throw freeform::Error(what + ": expected " + std::to_string(lat.pointCount()) + " rows (one per control point), got " +
                              std::to_string(a.shape(0)));
    return py::array_t<double, py::array::c_style>(a);
}

void bindLattice(py::module_& m)
{
    py::class_<PyBinding>(m, "Binding", R"doc(
Points bound to a lattice (Lattice.bind): their lattice coordinates are computed once, and
deform(lattice) re-evaluates only the deformation, for any lattice with the same degrees, frame and
outside policy (control points and strength may change).)doc")
        .def_property_readonly("size", [](const PyBinding& b) { return b.count; })
        .def(py::pickle(
            [](const PyBinding& b) { return std::visit([](const auto& x) { return bindingState(x); }, b.binding); },
            [](const py::tuple& t) {
                if (t.size() != 2) throw freeform::Error("Binding.__setstate__: expected 2 fields");
                PyLattice frame = latticeFromState(t[0].cast<py::tuple>());
                const py::array a = t[1].cast<py::array>();
                if (a.ndim() != 2 || a.shape(1) != 3 || !isCContiguous(a) || (!isDouble(a) && !isFloat(a)))
                    throw freeform::Error("Binding.__setstate__: expected C-contiguous (N, 3) float64 or float32 positions");
                const auto n = static_cast<std::size_t>(a.shape(0));
                if (isFloat(a))
                    return PyBinding{freeform::FfdBinding<float>(frame.lattice, static_cast<const float*>(a.data()), n), true, n};
                return PyBinding{freeform::FfdBinding<double>(frame.lattice, static_cast<const double*>(a.data()), n), false, n};
            }))
        .def("__copy__", [](const PyBinding& b) { return b; })
        .def("__deepcopy__", [](const PyBinding& b, py::handle) { return b; }, py::arg("memo"))
        .def_property_readonly("dtype", [](const PyBinding& b) {
            return b.isFloat ? py::dtype::of<float>() : py::dtype::of<double>();
        })
        .def(
            "deform",
            [](const PyBinding& b, PyLattice& lat, py::handle threadsArg, py::handle out) {
                const int threads = threadCount(threadsArg);
                const Lattice l = lat.snapshot();
                return std::visit([&](const auto& x) { return bindingDeform(x, l, lat.strength, threads, out); },
                                  b.binding);
            },
            py::arg("lattice"), py::arg("threads") = 0, py::arg("out") = py::none(),
            "The bound points deformed through lattice (N, 3) in the bound dtype; out= a preallocated "
            "C-contiguous array of that shape and dtype to write into (no allocation). Error when the lattice's "
            "degrees, frame or outside policy differ from the bound one.")
        .def("__repr__", [](const PyBinding& b) {
            return "Binding(size=" + std::to_string(b.count) + ", dtype=" + (b.isFloat ? "float32" : "float64") + ")";
        });

    py::class_<PyLattice>(m, "Lattice", R"doc(
A free-form deformation lattice: a Bézier volume of degrees (l, m, n) placed in space by a frame
(origin X0 and edge vectors S, T, U). A point moves by p' = p + strength * sum_q B_q(s,t,u) (P_q - R_q)
(displacement form, docs/ffd.md), with the outside policy applied to points outside the box.

control_points is a writable (K, 3) float64 array, K = (l+1)(m+1)(n+1), row
i*(m+1)*(n+1) + j*(n+1) + k; edits are picked up (and checked) by the next call.)doc")
        .def(py::init([](py::handle degree, py::handle origin, py::handle axes, py::handle points,
                         const std::string& outside) {
                 const auto d = degreeOf(degree);
                 const Eigen::Vector3d o = originArg(origin);
                 const Eigen::Matrix3d ax = axesArg(axes);
                 const auto policy = freeform::parseOutsidePolicy(outside, "outside");
                 if (points.is_none()) return PyLattice(Lattice::identity(d, o, ax, policy));
                 return PyLattice(Lattice(d, o, ax, toPoints(points, "points"), policy));
             }),
             py::arg("degree"), py::arg("origin"), py::arg("axes"), py::arg("points") = py::none(),
             py::arg("outside") = "clamp",
             "Lattice(degree, origin (3,), axes (3, 3) with columns S, T, U, points (K, 3) or None for the rest "
             "lattice, outside='clamp').")
        .def_static(
            "fit",
            [](py::handle points, py::handle degree, double margin, const std::string& outside) {
                const Points3 p = toPoints(points, "points");
                if (p.cols() == 0) throw freeform::Error("points: no points to fit a lattice around");
                const auto d = degreeOf(degree);
                const auto policy = freeform::parseOutsidePolicy(outside, "outside");
                std::optional<Lattice> lat;
                {
                    py::gil_scoped_release release;
                    lat.emplace(Lattice::fit(p, d, margin, policy));
                }
                return PyLattice(std::move(*lat)); // makes NumPy arrays: with the GIL
            },
            py::arg("points"), py::arg("degree") = std::make_tuple(3, 3, 3), py::arg("margin") = 0.05,
            py::arg("outside") = "clamp",
            "The rest lattice around the bounding box of points (N, 3), each side pushed out by margin times "
            "the largest extent (as `freeform lattice --fit`).")
        .def_static("load", &load, py::arg("path"), py::arg("name") = py::none(),
                    "The lattice object of a document (as `freeform lattice` writes); name= picks one when "
                    "the document has several.")
        .def(
            "save",
            [](PyLattice& self, const std::string& path, const std::optional<std::string>& name) {
                freeform::Document doc;
                doc.objects.push_back({name.value_or(self.name), freeform::latticeToData(self.snapshot()), ""});
                py::gil_scoped_release release;
                freeform::writeDocument(doc, path);
            },
            py::arg("path"), py::arg("name") = py::none(),
            "Writes a document with this lattice as its one object (atomically; the name given at load, or 'lattice').")
        .def_property_readonly("degree", [](const PyLattice& s) {
            const auto& d = s.lattice.degrees();
            return py::make_tuple(d[0], d[1], d[2]);
        })
        .def_property_readonly("origin", [](const PyLattice& s) { return fromVector(s.lattice.origin()); })
        .def_property_readonly(
            "axes",
            [](const PyLattice& s) {
                py::array_t<double> out({py::ssize_t{3}, py::ssize_t{3}});
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 3; ++c) out.mutable_at(r, c) = s.lattice.axes()(r, c);
                return out;
            },
            "(3, 3) array whose columns are the edge vectors S, T, U.")
        .def_property(
            "control_points", [](const PyLattice& s) { return s.points; },
            [](PyLattice& s, py::handle v) {
                auto a = controlBlock(v, s.lattice, "control_points");
                std::copy(a.data(), a.data() + a.size(), s.points.mutable_data());
            },
            "(K, 3) float64, writable in place (a view of the lattice's own array, no copy).")
        .def_property_readonly(
            "rest_points", [](const PyLattice& s) { return pointArray(s.lattice.restPoints()); },
            "(K, 3) the undeformed control points X0 + (i/l) S + (j/m) T + (k/n) U.")
        .def_property(
            "outside", [](const PyLattice& s) { return freeform::toString(s.lattice.outside()); },
            [](PyLattice& s, const std::string& v) { s.lattice.setOutside(freeform::parseOutsidePolicy(v, "outside")); },
            "'keep', 'clamp' (default) or 'extrapolate' (docs/ffd.md).")
        .def_property(
            "strength", [](const PyLattice& s) { return s.strength; },
            [](PyLattice& s, double w) {
                if (!std::isfinite(w)) throw freeform::Error("strength: not finite");
                s.strength = w;
            },
            "w in p' = p + w sum B (P - R) (default 1).")
        .def_readwrite("name", &PyLattice::name, "The object name save() writes.")
        .def_property_readonly("point_count", [](const PyLattice& s) { return s.lattice.pointCount(); })
        .def(
            "index",
            [](const PyLattice& s, int i, int j, int k) {
                const auto& d = s.lattice.degrees();
                const int ijk[3] = {i, j, k};
                for (int a = 0; a < 3; ++a)
                    if (ijk[a] < 0 || ijk[a] > d[a])
                        throw freeform::Error("Lattice.index: " + std::string(1, "ijk"[a]) + " = " + std::to_string(ijk[a]) +
                                              " is outside [0, " + std::to_string(d[a]) + "] (degree (" +
                                              std::to_string(d[0]) + ", " + std::to_string(d[1]) + ", " +
                                              std::to_string(d[2]) + "))");
                return s.lattice.index(i, j, k);
            },
            py::arg("i"), py::arg("j"), py::arg("k"),
            "Row of control point (i, j, k) in control_points: i*(m+1)*(n+1) + j*(n+1) + k; freeform.Error when i, j "
            "or k is outside [0, degree].")
        .def("copy", [](PyLattice& s) {
            PyLattice c(s.snapshot(), s.name);
            c.strength = s.strength;
            return c;
        }, "An independent copy (control points, frame, outside policy, strength, name).")
        .def("__copy__", [](PyLattice& s) { PyLattice c(s.snapshot(), s.name); c.strength = s.strength; return c; })
        .def("__deepcopy__", [](PyLattice& s, py::handle) { PyLattice c(s.snapshot(), s.name); c.strength = s.strength; return c; },
             py::arg("memo"))
        .def(py::pickle([](PyLattice& s) { return latticeState(s); }, [](const py::tuple& t) { return latticeFromState(t); }))
        .def("__repr__", &repr)
        .def("is_rest", [](PyLattice& s) { return s.snapshot().isRest(); })
        .def(
            "to_lattice",
            [](PyLattice& self, py::handle points) {
                const Lattice lat = self.snapshot();
                const Points3 p = toPoints(points, "points");
                Points3 out(3, p.cols());
                {
                    py::gil_scoped_release release;
                    for (Eigen::Index i = 0; i < p.cols(); ++i) out.col(i) = lat.toLattice(p.col(i));
                }
                return fromColumns(out);
            },
            py::arg("points"), "Lattice coordinates (s, t, u) of world points (N, 3) (no outside policy).")
        .def(
            "deform",
            [](PyLattice& self, py::handle points, py::handle threadsArg) {
                const int threads = threadCount(threadsArg);
                const Lattice lat = self.snapshot();
                const PointsIn a = pointsIn(points, "points");
                return deformAny(lat, a, self.strength, threads, py::none(), false, nullptr, nullptr);
            },
            py::arg("points"), py::arg("threads") = 0,
            "The deformed points (N, 3), same dtype as points (float32 stays float32, any strides read in place; "
            "other dtypes are converted once to float64). threads=0: the library's default (hardware "
            "concurrency). freeform.Error when a result overflows (outside='extrapolate' far outside the box).")
        .def(
            "bind",
            [](PyLattice& self, py::handle points) {
                const Lattice lat = self.snapshot();
                const py::array a = rows(points, "points", 3);
                const auto n = static_cast<std::size_t>(a.shape(0));
                if (isFloat(a)) {
                    const auto* p = static_cast<const float*>(a.data());
                    py::gil_scoped_release release;
                    requireFiniteRows(p, n, 3, "points");
                    return PyBinding{freeform::FfdBinding<float>(lat, p, n), true, n};
                }
                const auto* p = static_cast<const double*>(a.data());
                py::gil_scoped_release release;
                requireFiniteRows(p, n, 3, "points");
                return PyBinding{freeform::FfdBinding<double>(lat, p, n), false, n};
            },
            py::arg("points"),
            "Binds points (N, 3) float64 or float32 to this lattice's frame: a Binding whose deform(lattice) "
            "skips the lattice coordinates (the fast path for loops that move control points).")
        .def(
            "deform_normals",
            [](PyLattice& self, py::handle points, py::handle normals, py::handle threadsArg) {
                const int threads = threadCount(threadsArg);
                const Lattice lat = self.snapshot();
                const PointsIn a = pointsIn(points, "points");
                py::array nOut;
                py::array out = deformAny(lat, a, self.strength, threads, normals, false, &nOut, nullptr);
                return py::make_tuple(out, nOut);
            },
            py::arg("points"), py::arg("normals"), py::arg("threads") = 0,
            "(deformed points, normals mapped by cof(J) and renormalised), both (N, 3) in the points' dtype.")
        .def(
            "det_j",
            [](PyLattice& self, py::handle points, py::handle threadsArg) {
                const int threads = threadCount(threadsArg);
                const Lattice lat = self.snapshot();
                const PointsIn a = pointsIn(points, "points");
                py::array det;
                deformAny(lat, a, self.strength, threads, py::none(), true, nullptr, &det);
                return det;
            },
            py::arg("points"), py::arg("threads") = 0,
            "det J of the deformation at each point (N,): the local volume ratio; <= 0 is a fold-over.")
        .def(
            "report",
            [](PyLattice& self, py::handle points) {
                const Lattice lat = self.snapshot();
                py::array a = rows(points, "points", 3, false); // float64, as `freeform ffd` computes
                const PointsIn in = pointsIn(a, "points");
                std::vector<ChunkReport> parts;
                {
                    py::gil_scoped_release release;
                    ChunkOutputs<double> o;
                    o.wantDet = true;
                    deformChunks<double>(lat, in, self.strength, 0, o, &parts);
                }
                // As FfdBinding::deform's report (volume/deform.h): 1 and 1 for no points.
                std::size_t outside = 0;
                double lo = 1, hi = 1;
                bool any = false;
                std::vector<int> folds;
                for (const auto& p : parts) {
                    outside += p.outside;
                    if (p.any) {
                        lo = any ? std::min(lo, p.lo) : p.lo;
                        hi = any ? std::max(hi, p.hi) : p.hi;
                        any = true;
                    }
                    folds.insert(folds.end(), p.folds.begin(), p.folds.end());
                }
                py::dict d;
                d["vertices"] = in.n;
                d["outside"] = outside;
                d["min_det_j"] = lo;
                d["max_det_j"] = hi;
                d["fold_count"] = folds.size();
                d["folds"] = folds;
                return d;
            },
            py::arg("points"),
            "What deforming points does (the fields of `freeform ffd`'s report): vertices, outside, min_det_j, "
            "max_det_j, fold_count, folds (det J <= 0). freeform.Error when det J or a position overflows "
            "(outside='extrapolate' far outside the box), instead of counting NaN as a fold.")
        .def(
            "certify",
            [](PyLattice& self, int maxDepth) {
                const Lattice lat = self.snapshot();
                freeform::Certificate c;
                {
                    py::gil_scoped_release release;
                    c = freeform::certify(lat, self.strength, maxDepth);
                }
                return certificateDict(c);
            },
            py::arg("max_depth") = 4,
            "The fold-over certificate of the whole box: verdict 'certified injective' (det J > 0 everywhere), "
            "'folds' (witness (s,t,u) with det J <= 0) or 'undecided'; min/max Bernstein coefficient of det J.")
        .def(
            "elevated",
            [](PyLattice& self, int dl, int dm, int dn) {
                PyLattice c(self.snapshot().elevated(dl, dm, dn), self.name);
                c.strength = self.strength;
                return c;
            },
            py::arg("dl"), py::arg("dm"), py::arg("dn"), "The same deformation with degrees raised.")
        .def(
            "direct_manipulation",
            [](PyLattice& self, py::handle points, py::handle targets) {
                const Lattice lat = self.snapshot();
                const Points3 p = toPoints(points, "points");
                const Points3 t = toPoints(targets, "targets");
                if (p.cols() != t.cols())
                    throw freeform::Error("targets: " + std::to_string(t.cols()) + " rows for " +
                                          std::to_string(p.cols()) + " points");
                freeform::DirectManipulation r = [&] {
                    py::gil_scoped_release release;
                    return freeform::directManipulation(lat, p, t, self.strength);
                }();
                PyLattice moved(r.lattice, self.name);
                moved.strength = self.strength;
                py::dict d;
                d["lattice"] = py::cast(std::move(moved));
                d["change"] = fromColumns(r.change);
                d["residual"] = r.residual;
                d["rank"] = r.rank;
                return d;
            },
            py::arg("points"), py::arg("targets"),
            "Hsu-Hughes-Kaufman direct manipulation: the smallest control-point change moving the deformed "
            "points (N, 3) to targets (N, 3). Returns {lattice (a new Lattice), change (K, 3), residual, rank}.");
}

} // namespace ffpy
