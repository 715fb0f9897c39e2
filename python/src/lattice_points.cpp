// What freeform.Lattice computes on many points (docs/python.md): the deformation of (N, 3) points of
// float64 or float32 with any strides, chunk by chunk, in place of the caller's dtype (deform,
// deform_normals, det_j and report, which lattice.cpp binds), and the sensitivities d out / d P =
// strength * W (weights; weights_matvec and weights_rmatvec without forming W), bound here
// (docs/python.md, "Sensitivities").

#include "lattice_points.h"

#include <freeform/core/parallel.h>
#include <freeform/volume/deform.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace ffpy {

namespace {

using freeform::Lattice;

// ---------------------------------------------------------------- basis weights

/// The sensitivities of points, from the library (Lattice::sensitivities and sensitivityBlock:
/// the outside policy and the Bernstein values are the library's).
struct WeightEvaluator {
    explicit WeightEvaluator(const Lattice& lat) : lat(lat) {}

    /// w * B_ijk(stu(p)) of every control point into out[0..K) (zero when p does not move).
    void weights(const Eigen::Vector3d& p, double w, double* out) const { lat.sensitivities(p, w, out); }

    static constexpr int kLanes = Lattice::kSensitivityLanes; ///< points per block of the matrix-free products

    /// The weights of up to kLanes points p[0..count) lane by lane: out[q * kLanes + lane].
    void blockWeights(const double* p, std::size_t count, double w, double* out) const { lat.sensitivityBlock(p, count, w, out); }

    const Lattice& lat;
};

} // namespace

// ---------------------------------------------------------------- deform

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

namespace {

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

} // namespace

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

template void deformChunks<double>(const Lattice& lat, const PointsIn& in, double strength, int threads,
                                  const ChunkOutputs<double>& o, std::vector<ChunkReport>* reports);

namespace {

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

} // namespace

py::array deformAny(const Lattice& lat, const PointsIn& a, double strength, int threads, py::handle normals,
                    bool wantDet, py::array* normalsOut, py::array* detOut)
{
    if (a.isFloat) return deformTyped<float>(lat, a, strength, threads, normals, wantDet, normalsOut, detOut);
    return deformTyped<double>(lat, a, strength, threads, normals, wantDet, normalsOut, detOut);
}

void bindLatticeWeights(py::module_& m)
{
    auto lattice = py::reinterpret_borrow<py::class_<PyLattice>>(m.attr("Lattice"));
    lattice
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
