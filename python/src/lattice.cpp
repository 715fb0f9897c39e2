// freeform.Lattice: fit, load/save (the lattice object of a document), deform (N, 3) positions in
// place of the caller's dtype, normals by cof(J), det J, the fold-over certificate, direct
// manipulation, and the sensitivities d out / d P = strength * W (docs/python.md, "Sensitivities").

#include "lattice.h"

#include <pybind11/stl.h>

#include <freeform/core/parallel.h>
#include <freeform/document/document.h>
#include <freeform/io/document.h>
#include <freeform/io/geometry_data.h>
#include <freeform/volume/deform.h>

#include <algorithm>
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

// ---------------------------------------------------------------- basis weights

/// Bernstein values B_0^d(x) .. B_d^d(x) (the triangle of de Casteljau's recurrence).
inline void bernstein(int d, double x, double* b)
{
    b[0] = 1;
    const double y = 1 - x;
    for (int r = 1; r <= d; ++r) {
        double saved = 0;
        for (int i = 0; i < r; ++i) {
            const double t = b[i];
            b[i] = saved + y * t;
            saved = x * t;
        }
        b[r] = saved;
    }
}

/// Per-point weights of the control points after the outside policy: the lattice coordinates of p
/// (clamped to the box under clamp, as they are under extrapolate); false when p is outside under
/// keep (p does not move: no control point acts on it).
struct WeightEvaluator {
    explicit WeightEvaluator(const Lattice& lat) : lat(lat), d(lat.degrees()) {}

    bool coordinates(const Eigen::Vector3d& p, Eigen::Vector3d& stu) const
    {
        stu = lat.toLattice(p);
        if (Lattice::insideBox(stu)) return true;
        switch (lat.outside()) {
        case freeform::OutsidePolicy::Keep: return false;
        case freeform::OutsidePolicy::Clamp: stu = stu.cwiseMax(0.0).cwiseMin(1.0); return true;
        case freeform::OutsidePolicy::Extrapolate: return true;
        }
        return true;
    }

    /// w * B_ijk(stu(p)) of every control point into out[0..K) (zero when p does not move).
    void weights(const Eigen::Vector3d& p, double w, double* out) const
    {
        const int K = lat.pointCount();
        Eigen::Vector3d stu;
        if (!coordinates(p, stu)) {
            std::fill(out, out + K, 0.0);
            return;
        }
        double bs[freeform::kMaxDegree + 1], bt[freeform::kMaxDegree + 1], bu[freeform::kMaxDegree + 1];
        bernstein(d[0], stu[0], bs);
        bernstein(d[1], stu[1], bt);
        bernstein(d[2], stu[2], bu);
        int q = 0;
        for (int i = 0; i <= d[0]; ++i)
            for (int j = 0; j <= d[1]; ++j) {
                const double a = w * bs[i] * bt[j];
                for (int k = 0; k <= d[2]; ++k) out[q++] = a * bu[k];
            }
    }

    static constexpr int kLanes = 8; ///< points per block of the matrix-free products

    /// The weights of up to kLanes points p[0..count) lane by lane: out[q * kLanes + lane]
    /// (zero for lanes past count and for points that do not move), strength included. The loops
    /// over lanes have a fixed length, so the compiler vectorises them.
    void blockWeights(const double* p, std::size_t count, double w, double* out) const
    {
        constexpr int L = kLanes;
        constexpr int M = freeform::kMaxDegree + 1;
        alignas(64) double bs[M][L], bt[M][L], bu[M][L];
        double tmp[M];
        for (int lane = 0; lane < L; ++lane) {
            Eigen::Vector3d stu = Eigen::Vector3d::Zero();
            double scale = 0;
            if (static_cast<std::size_t>(lane) < count &&
                coordinates(Eigen::Vector3d(p[3 * lane], p[3 * lane + 1], p[3 * lane + 2]), stu))
                scale = w;
            bernstein(d[0], stu[0], tmp);
            for (int i = 0; i <= d[0]; ++i) bs[i][lane] = scale * tmp[i];
            bernstein(d[1], stu[1], tmp);
            for (int i = 0; i <= d[1]; ++i) bt[i][lane] = tmp[i];
            bernstein(d[2], stu[2], tmp);
            for (int i = 0; i <= d[2]; ++i) bu[i][lane] = tmp[i];
        }
        int q = 0;
        for (int i = 0; i <= d[0]; ++i)
            for (int j = 0; j <= d[1]; ++j) {
                alignas(64) double a[L];
                for (int lane = 0; lane < L; ++lane) a[lane] = bs[i][lane] * bt[j][lane];
                for (int k = 0; k <= d[2]; ++k, ++q)
                    for (int lane = 0; lane < L; ++lane) out[q * L + lane] = a[lane] * bu[k][lane];
            }
    }

    const Lattice& lat;
    std::array<int, 3> d;
};

constexpr std::size_t kGrain = 2048; // points per chunk of the matrix-free products

// ---------------------------------------------------------------- deform

template <typename Scalar>
py::array deformTyped(const Lattice& lat, const py::array& in, double strength, int threads, const py::handle normals,
                      bool wantDet, py::array* normalsOut, py::array* detOut)
{
    const auto n = static_cast<std::size_t>(in.shape(0));
    const auto* p = static_cast<const Scalar*>(in.data());
    py::array_t<Scalar> out({static_cast<py::ssize_t>(n), py::ssize_t{3}});
    freeform::FfdOutputs<Scalar> o;
    o.positions = out.mutable_data();
    py::array_t<Scalar, py::array::c_style> nin;
    if (!normals.is_none()) {
        py::array a = rows(normals, "normals", 3);
        if (static_cast<std::size_t>(a.shape(0)) != n)
            throw freeform::Error("normals: " + std::to_string(a.shape(0)) + " rows for " + std::to_string(n) +
                                  " points");
        nin = py::array_t<Scalar, py::array::c_style | py::array::forcecast>::ensure(a);
        *normalsOut = py::array_t<Scalar>({static_cast<py::ssize_t>(n), py::ssize_t{3}});
        o.normalsIn = nin.data();
        o.normalsOut = static_cast<Scalar*>(normalsOut->mutable_data());
    }
    if (wantDet) {
        *detOut = py::array_t<Scalar>(static_cast<py::ssize_t>(n));
        o.determinants = static_cast<Scalar*>(detOut->mutable_data());
    }
    {
        py::gil_scoped_release release;
        requireFiniteRows(p, n, 3, "points");
        if (o.normalsIn) requireFiniteRows(o.normalsIn, n, 3, "normals");
        freeform::FfdBinding<Scalar> binding(lat, p, n);
        freeform::DeformOptions options;
        options.strength = strength;
        options.threads = threads;
        binding.deform(lat, o, options);
    }
    return out;
}

py::array deformAny(const Lattice& lat, const py::array& a, double strength, int threads, py::handle normals,
                    bool wantDet, py::array* normalsOut, py::array* detOut)
{
    if (isFloat(a)) return deformTyped<float>(lat, a, strength, threads, normals, wantDet, normalsOut, detOut);
    return deformTyped<double>(lat, a, strength, threads, normals, wantDet, normalsOut, detOut);
}

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
    freeform::TypedDocument doc;
    {
        py::gil_scoped_release release;
        doc = freeform::TypedDocument::read(path);
    }
    const freeform::TypedObject* object = nullptr;
    if (name) {
        object = &doc.object(*name);
        if (!std::holds_alternative<Lattice>(object->geometry()))
            throw freeform::Error(doc.what(*object) + ": is a " + object->type() + ", not a lattice");
    } else {
        std::vector<std::string> names;
        for (const auto& o : doc.objects())
            if (std::holds_alternative<Lattice>(o.geometry())) {
                if (!object) object = &o;
                names.push_back(o.name());
            }
        if (!object) throw freeform::Error(path + ": no lattice object");
        if (names.size() > 1) {
            std::string list;
            for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
            throw freeform::Error(path + ": several lattice objects (" + list + "): give name=");
        }
    }
    return PyLattice(std::get<Lattice>(object->geometry()), object->name());
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

/// The rows of `a` as an (K, 3) float64 block checked against the lattice's K.
py::array_t<double, py::array::c_style> controlBlock(py::handle h, const Lattice& lat, const std::string& what)
{
    py::array a = rows(h, what, 3, false);
    if (a.shape(0) != lat.pointCount())
        throw freeform::Error(what + ": expected " + std::to_string(lat.pointCount()) + " rows (one per control point), got " +
                              std::to_string(a.shape(0)));
    return py::array_t<double, py::array::c_style>(a);
}

/// Points bound to a lattice's frame (FfdBinding): lattice coordinates computed once, deform()
/// re-evaluates only the deformation as control points move (an optimisation loop's inner call).
struct PyBinding {
    std::variant<freeform::FfdBinding<double>, freeform::FfdBinding<float>> binding;
    bool isFloat = false;
    std::size_t count = 0;
};

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
        if (!a || !a.dtype().is(py::dtype::of<Scalar>()) || !isCContiguous(a) || a.ndim() != 2 || a.shape(0) != n ||
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
    }
    return out;
}

} // namespace

void bindLattice(py::module_& m)
{
    py::class_<PyBinding>(m, "Binding", R"doc(
Points bound to a lattice (Lattice.bind): their lattice coordinates are computed once, and
deform(lattice) re-evaluates only the deformation, for any lattice with the same degrees, frame and
outside policy (control points and strength may change).)doc")
        .def_property_readonly("size", [](const PyBinding& b) { return b.count; })
        .def_property_readonly("dtype", [](const PyBinding& b) {
            return b.isFloat ? py::dtype::of<float>() : py::dtype::of<double>();
        })
        .def(
            "deform",
            [](const PyBinding& b, PyLattice& lat, int threads, py::handle out) {
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
                 Eigen::Vector3d o = toPoints(numericArray(origin, "origin").attr("reshape")(1, 3), "origin").col(0);
                 const Points3 ax = toPoints(numericArray(axes, "axes").attr("T"), "axes");
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
        .def("index", [](const PyLattice& s, int i, int j, int k) { return s.lattice.index(i, j, k); },
             "Row of control point (i, j, k).")
        .def("copy", [](PyLattice& s) {
            PyLattice c(s.snapshot(), s.name);
            c.strength = s.strength;
            return c;
        })
        .def("__copy__", [](PyLattice& s) { PyLattice c(s.snapshot(), s.name); c.strength = s.strength; return c; })
        .def("__deepcopy__", [](PyLattice& s, py::dict) { PyLattice c(s.snapshot(), s.name); c.strength = s.strength; return c; })
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
            [](PyLattice& self, py::handle points, int threads) {
                const Lattice lat = self.snapshot();
                const py::array a = rows(points, "points", 3);
                return deformAny(lat, a, self.strength, threads, py::none(), false, nullptr, nullptr);
            },
            py::arg("points"), py::arg("threads") = 0,
            "The deformed points (N, 3), same dtype as points (float32 stays float32; other dtypes and layouts "
            "are converted once to float64). threads=0: the library's default (hardware concurrency).")
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
            [](PyLattice& self, py::handle points, py::handle normals, int threads) {
                const Lattice lat = self.snapshot();
                const py::array a = rows(points, "points", 3);
                py::array nOut;
                py::array out = deformAny(lat, a, self.strength, threads, normals, false, &nOut, nullptr);
                return py::make_tuple(out, nOut);
            },
            py::arg("points"), py::arg("normals"), py::arg("threads") = 0,
            "(deformed points, normals mapped by cof(J) and renormalised), both (N, 3) in the points' dtype.")
        .def(
            "det_j",
            [](PyLattice& self, py::handle points, int threads) {
                const Lattice lat = self.snapshot();
                const py::array a = rows(points, "points", 3);
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
                Points3 p = toPoints(points, "points");
                freeform::DeformOptions options;
                options.strength = self.strength;
                freeform::DeformReport r;
                {
                    py::gil_scoped_release release;
                    r = freeform::deformPoints(lat, p, options);
                }
                py::dict d;
                d["vertices"] = r.vertices;
                d["outside"] = r.outside;
                d["min_det_j"] = r.minDetJ;
                d["max_det_j"] = r.maxDetJ;
                d["fold_count"] = r.foldCount;
                d["folds"] = r.folds;
                return d;
            },
            py::arg("points"),
            "What deforming points does (the fields of `freeform ffd`'s report): vertices, outside, min_det_j, "
            "max_det_j, fold_count, folds.")
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
            "points (N, 3) to targets (N, 3). Returns {lattice (a new Lattice), change (K, 3), residual, rank}.")
        .def(
            "weights",
            [](PyLattice& self, py::handle points) {
                const Lattice lat = self.snapshot();
                const py::array a = rows(points, "points", 3, false);
                const auto n = static_cast<std::size_t>(a.shape(0));
                const auto K = static_cast<std::size_t>(lat.pointCount());
                if (n * K > (std::size_t{1} << 31))
                    throw freeform::Error("weights: " + std::to_string(n) + " x " + std::to_string(K) +
                                          " is too large to form; use weights_matvec / weights_rmatvec");
                py::array_t<double> W({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(K)});
                const double* p = static_cast<const double*>(a.data());
                double* w = W.mutable_data();
                const double strength = self.strength;
                {
                    py::gil_scoped_release release;
                    requireFiniteRows(p, n, 3, "points");
                    const WeightEvaluator e(lat);
                    freeform::parallelFor(0, n, kGrain, 0, [&](int, std::size_t first, std::size_t last) {
                        for (std::size_t i = first; i < last; ++i)
                            e.weights(Eigen::Vector3d(p[3 * i], p[3 * i + 1], p[3 * i + 2]), strength, w + i * K);
                    });
                }
                return W;
            },
            py::arg("points"),
            "W (N, K) float64: d deform(points)[i, c] / d control_points[q, c] = W[i, q] for each coordinate c "
            "(the same for x, y and z; strength and outside policy included).")
        .def(
            "weights_matvec",
            [](PyLattice& self, py::handle points, py::handle dP, int threads) {
                const Lattice lat = self.snapshot();
                const py::array a = rows(points, "points", 3, false);
                const auto d = controlBlock(dP, lat, "dP");
                const auto n = static_cast<std::size_t>(a.shape(0));
                const auto K = static_cast<std::size_t>(lat.pointCount());
                py::array_t<double> out({static_cast<py::ssize_t>(n), py::ssize_t{3}});
                const double* p = static_cast<const double*>(a.data());
                const double* dp = d.data();
                double* o = out.mutable_data();
                const double strength = self.strength;
                {
                    py::gil_scoped_release release;
                    requireFiniteRows(p, n, 3, "points");
                    requireFiniteRows(dp, K, 3, "dP");
                    const WeightEvaluator e(lat);
                    constexpr int L = WeightEvaluator::kLanes;
                    freeform::parallelFor(0, n, kGrain, threads, [&](int, std::size_t first, std::size_t last) {
                        std::vector<double> w(K * L);
                        for (std::size_t i0 = first; i0 < last; i0 += L) {
                            const std::size_t count = std::min<std::size_t>(L, last - i0);
                            e.blockWeights(p + 3 * i0, count, strength, w.data());
                            alignas(64) double x[L] = {}, y[L] = {}, z[L] = {};
                            for (std::size_t q = 0; q < K; ++q) {
                                const double* wq = w.data() + q * L;
                                for (int lane = 0; lane < L; ++lane) {
                                    x[lane] += wq[lane] * dp[3 * q];
                                    y[lane] += wq[lane] * dp[3 * q + 1];
                                    z[lane] += wq[lane] * dp[3 * q + 2];
                                }
                            }
                            for (std::size_t lane = 0; lane < count; ++lane) {
                                o[3 * (i0 + lane)] = x[lane];
                                o[3 * (i0 + lane) + 1] = y[lane];
                                o[3 * (i0 + lane) + 2] = z[lane];
                            }
                        }
                    });
                }
                return out;
            },
            py::arg("points"), py::arg("dP"), py::arg("threads") = 0,
            "W @ dP (N, 3) for a control-point change dP (K, 3), without forming W: the first-order change of "
            "deform(points).")
        .def(
            "weights_rmatvec",
            [](PyLattice& self, py::handle points, py::handle g, int threads) {
                const Lattice lat = self.snapshot();
                const py::array a = rows(points, "points", 3, false);
                const py::array gb = rows(g, "g", 3, false);
                const auto n = static_cast<std::size_t>(a.shape(0));
                if (static_cast<std::size_t>(gb.shape(0)) != n)
                    throw freeform::Error("g: " + std::to_string(gb.shape(0)) + " rows for " + std::to_string(n) +
                                          " points");
                const auto K = static_cast<std::size_t>(lat.pointCount());
                const double* p = static_cast<const double*>(a.data());
                const double* gp = static_cast<const double*>(gb.data());
                const double strength = self.strength;
                py::array_t<double> out({static_cast<py::ssize_t>(K), py::ssize_t{3}});
                double* o = out.mutable_data();
                {
                    py::gil_scoped_release release;
                    requireFiniteRows(p, n, 3, "points");
                    requireFiniteRows(gp, n, 3, "g");
                    const WeightEvaluator e(lat);
                    // Fixed blocks of kGrain points, summed in block order: the result does not
                    // depend on the thread count.
                    const std::size_t blocks = (n + kGrain - 1) / kGrain;
                    std::vector<double> partial(blocks * 3 * K, 0.0);
                    constexpr int L = WeightEvaluator::kLanes;
                    freeform::parallelFor(0, blocks, 1, threads, [&](int, std::size_t first, std::size_t last) {
                        std::vector<double> w(K * L);
                        for (std::size_t b = first; b < last; ++b) {
                            double* acc = partial.data() + b * 3 * K;
                            const std::size_t end = std::min(n, (b + 1) * kGrain);
                            for (std::size_t i0 = b * kGrain; i0 < end; i0 += L) {
                                const std::size_t count = std::min<std::size_t>(L, end - i0);
                                e.blockWeights(p + 3 * i0, count, strength, w.data());
                                alignas(64) double gx[L] = {}, gy[L] = {}, gz[L] = {};
                                for (std::size_t lane = 0; lane < count; ++lane) {
                                    gx[lane] = gp[3 * (i0 + lane)];
                                    gy[lane] = gp[3 * (i0 + lane) + 1];
                                    gz[lane] = gp[3 * (i0 + lane) + 2];
                                }
                                for (std::size_t q = 0; q < K; ++q) {
                                    const double* wq = w.data() + q * L;
                                    double sx = 0, sy = 0, sz = 0;
                                    for (int lane = 0; lane < L; ++lane) {
                                        sx += wq[lane] * gx[lane];
                                        sy += wq[lane] * gy[lane];
                                        sz += wq[lane] * gz[lane];
                                    }
                                    acc[3 * q] += sx;
                                    acc[3 * q + 1] += sy;
                                    acc[3 * q + 2] += sz;
                                }
                            }
                        }
                    });
                    std::fill(o, o + 3 * K, 0.0);
                    for (std::size_t b = 0; b < blocks; ++b)
                        for (std::size_t c = 0; c < 3 * K; ++c) o[c] += partial[b * 3 * K + c];
                }
                return out;
            },
            py::arg("points"), py::arg("g"), py::arg("threads") = 0,
            "W^T @ g (K, 3) for a gradient g (N, 3) of an objective with respect to the deformed points, without "
            "forming W: the gradient with respect to the control points (what an adjoint solver needs).");
}

} // namespace ffpy
