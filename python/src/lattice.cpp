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

/// Points (N, 3) as the deformation calls read them: float64 or float32 with any strides (read
/// chunk by chunk, no copy of the whole array), anything else converted once to float64.
struct PointsIn {
    py::array array; // keeps the data alive
    const char* data = nullptr;
    py::ssize_t rowStride = 0, colStride = 0;
    std::size_t n = 0;
    bool isFloat = false;
    bool contiguous = false;
};

PointsIn pointsIn(py::handle h, const std::string& what)
{
    py::array a = numericArray(h, what);
    if (a.ndim() != 2 || a.shape(1) != 3)
        throw freeform::Error(what + ": expected an array of shape (N, 3), got shape " + shapeText(a));
    if (!isDouble(a) && !isFloat(a)) a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    PointsIn p;
    p.array = a;
    p.data = static_cast<const char*>(a.data());
    p.rowStride = a.strides(0);
    p.colStride = a.strides(1);
    p.n = static_cast<std::size_t>(a.shape(0));
    p.isFloat = isFloat(a);
    p.contiguous = isCContiguous(a);
    return p;
}

/// A non-finite output of the deformation: under outside='extrapolate' the polynomial far outside
/// the box overflows the output type (float64 near 1e308, float32 near 3e38).
template <typename Scalar>
[[noreturn]] void overflowError(const char* what, std::size_t row, const Lattice& lat)
{
    throw freeform::Error(std::string("deform: ") + what + " of point row " + std::to_string(row) +
                          " is not finite: the deformation overflows " +
                          (sizeof(Scalar) == 4 ? "float32" : "float64") +
                          (lat.outside() == freeform::OutsidePolicy::Extrapolate
                               ? " (outside='extrapolate' continues the lattice polynomial, which grows as the cube of "
                                 "the distance for a cubic lattice: use 'clamp', or points nearer the box)"
                               : ""));
}

/// Whether v[0..count) are all finite: one branch-free pass the compiler vectorises (the slow
/// scan for the row runs only when one is not).
template <typename Scalar>
bool allFinite(const Scalar* v, std::size_t count)
{
    // Not finite <=> every exponent bit set: integer compares, which vectorise (a floating-point
    // compare with an early exit does not).
    using Bits = std::conditional_t<sizeof(Scalar) == 8, std::uint64_t, std::uint32_t>;
    constexpr Bits kExponent = sizeof(Scalar) == 8 ? Bits(0x7ff0000000000000ull) : Bits(0x7f800000u);
    Bits bad = 0;
    for (std::size_t i = 0; i < count; ++i) {
        Bits b;
        std::memcpy(&b, v + i, sizeof b);
        bad |= Bits((b & kExponent) == kExponent);
    }
    return bad == 0;
}

template <typename Scalar>
void requireFiniteOutput(const Scalar* v, std::size_t rows, std::size_t cols, std::size_t first, const char* what,
                         const Lattice& lat)
{
    if (allFinite(v, rows * cols)) return;
    for (std::size_t i = 0; i < rows * cols; ++i)
        if (!std::isfinite(v[i])) overflowError<Scalar>(what, first + i / cols, lat);
}

/// Error naming the first row of a block that is not finite (global row numbers).
template <typename Scalar>
void requireFiniteInput(const Scalar* v, std::size_t rows, std::size_t first, const char* what)
{
    if (allFinite(v, 3 * rows)) return;
    for (std::size_t i = 0; i < 3 * rows; ++i)
        if (!std::isfinite(v[i]))
            throw freeform::Error(std::string(what) + ": row " + std::to_string(first + i / 3) + " is not finite (" +
                                  num(static_cast<double>(v[i])) + ")");
}

/// What deformChunks fills (null: not wanted); arrays of n rows, C order.
template <typename Scalar>
struct ChunkOutputs {
    Scalar* positions = nullptr;     // (n, 3); null: a per-thread scratch (report only)
    const Scalar* normalsIn = nullptr;
    Scalar* normalsOut = nullptr;
    Scalar* determinants = nullptr;  // (n,)
    bool wantDet = false;            // det J into a scratch when determinants is null (report)
};

/// Per-chunk results for report(): outside count, det J range and folds.
struct ChunkReport {
    std::size_t outside = 0;
    double lo = 1, hi = 1;
    bool any = false;
    std::vector<int> folds;
};

/// The one-call deformation without a binding of all points: the points are bound and deformed
/// in chunks of kChunk (the library's FfdBinding and kernel on each chunk, one chunk per thread at
/// a time, so its 48 bytes per point of lattice coordinates stay in cache and only kChunk of them
/// exist per thread), written straight into the output arrays. Results equal one FfdBinding of
/// all points bit for bit (the kernel is point by point). Every output is checked finite.
template <typename Scalar>
void deformChunks(const Lattice& lat, const PointsIn& in, double strength, int threads, const ChunkOutputs<Scalar>& o,
                  std::vector<ChunkReport>* reports)
{
    // 256 blocks: the binding's own parallel grain, so binding a chunk never starts a thread.
    constexpr std::size_t kChunk = 256 * static_cast<std::size_t>(freeform::FfdBinding<Scalar>::kLanes);
    const std::size_t n = in.n;
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    if (reports) reports->assign(chunks, ChunkReport{});
    freeform::parallelFor(0, chunks, 1, threads, [&](int, std::size_t firstChunk, std::size_t lastChunk) {
        std::vector<Scalar> gathered, scratchPos, scratchDet;
        freeform::DeformOptions options;
        options.strength = strength;
        options.threads = 1;
        for (std::size_t c = firstChunk; c < lastChunk; ++c) {
            const std::size_t first = c * kChunk, len = std::min(kChunk, n - first);
            const Scalar* p;
            if (in.contiguous) {
                p = reinterpret_cast<const Scalar*>(in.data) + 3 * first;
            } else {
                gathered.resize(3 * len);
                for (std::size_t i = 0; i < len; ++i)
                    for (int x = 0; x < 3; ++x)
                        gathered[3 * i + std::size_t(x)] = *reinterpret_cast<const Scalar*>(
                            in.data + static_cast<py::ssize_t>(first + i) * in.rowStride + x * in.colStride);
                p = gathered.data();
            }
            if (o.normalsIn) requireFiniteInput(o.normalsIn + 3 * first, len, first, "normals");
            // Binding checks the points (one pass over them instead of two); its message counts
            // from the chunk's start, so a failure is reported again here with the row in the array.
            const freeform::FfdBinding<Scalar> binding = [&] {
                try {
                    return freeform::FfdBinding<Scalar>(lat, p, len);
                } catch (const freeform::Error&) {
                    requireFiniteInput(p, len, first, "points");
                    throw;
                }
            }();
            freeform::FfdOutputs<Scalar> out;
            if (o.positions) {
                out.positions = o.positions + 3 * first;
            } else {
                scratchPos.resize(3 * len);
                out.positions = scratchPos.data();
            }
            if (o.normalsOut) {
                out.normalsIn = o.normalsIn + 3 * first;
                out.normalsOut = o.normalsOut + 3 * first;
            }
            if (o.determinants) {
                out.determinants = o.determinants + first;
            } else if (o.wantDet) {
                scratchDet.resize(len);
                out.determinants = scratchDet.data();
            }
            binding.deform(lat, out, options);
            requireFiniteOutput(out.positions, len, 3, first, "the position", lat);
            if (out.normalsOut) requireFiniteOutput(out.normalsOut, len, 3, first, "the normal", lat);
            if (out.determinants) requireFiniteOutput(out.determinants, len, 1, first, "det J", lat);
            if (reports) {
                ChunkReport& r = (*reports)[c];
                r.outside = binding.outsideVertices().size();
                for (std::size_t i = 0; i < len; ++i) {
                    const double det = static_cast<double>(out.determinants[i]);
                    if (!r.any) r.lo = r.hi = det, r.any = true;
                    r.lo = std::min(r.lo, det);
                    r.hi = std::max(r.hi, det);
                    if (!(det > 0)) r.folds.push_back(static_cast<int>(first + i));
                }
            }
        }
    });
}

template <typename Scalar>
py::array deformTyped(const Lattice& lat, const PointsIn& in, double strength, int threads, const py::handle normals,
                      bool wantDet, py::array* normalsOut, py::array* detOut)
{
    const std::size_t n = in.n;
    py::array_t<Scalar> out({static_cast<py::ssize_t>(n), py::ssize_t{3}});
    ChunkOutputs<Scalar> o;
    o.positions = out.mutable_data();
    py::array_t<Scalar, py::array::c_style> nin;
    if (!normals.is_none()) {
        py::array a = numericArray(normals, "normals");
        if (a.ndim() != 2 || a.shape(1) != 3)
            throw freeform::Error("normals: expected an array of shape (N, 3), got shape " + shapeText(a));
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
        deformChunks<Scalar>(lat, in, strength, threads, o, nullptr);
    }
    return out;
}

py::array deformAny(const Lattice& lat, const PointsIn& a, double strength, int threads, py::handle normals,
                    bool wantDet, py::array* normalsOut, py::array* detOut)
{
    if (a.isFloat) return deformTyped<float>(lat, a, strength, threads, normals, wantDet, normalsOut, detOut);
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
            [](PyLattice& self, py::handle points, py::handle dP, py::handle threadsArg) {
                const int threads = threadCount(threadsArg);
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
            [](PyLattice& self, py::handle points, py::handle g, py::handle threadsArg) {
                const int threads = threadCount(threadsArg);
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
