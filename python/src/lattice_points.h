#pragma once
// What freeform.Lattice computes on many points (lattice_points.cpp) and its bindings in lattice.cpp
// call: (N, 3) points read in place (PointsIn), the deformation in chunks and its checks of finite
// output; and the sensitivities (bindLatticeWeights). docs/python.md, "Arrays" and "Sensitivities".

#include "lattice.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace ffpy {

constexpr std::size_t kGrain = 2048; // points per chunk of the matrix-free products

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

PointsIn pointsIn(py::handle h, const std::string& what);

/// A non-finite output of the deformation: under outside='extrapolate' the polynomial far outside
/// the box overflows the output type (float64 near 1e308, float32 near 3e38).
template <typename Scalar>
[[noreturn]] void overflowError(const char* what, std::size_t row, const freeform::Lattice& lat)
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
                         const freeform::Lattice& lat)
{
    if (allFinite(v, rows * cols)) return;
    for (std::size_t i = 0; i < rows * cols; ++i)
        if (!std::isfinite(v[i])) overflowError<Scalar>(what, first + i / cols, lat);
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
void deformChunks(const freeform::Lattice& lat, const PointsIn& in, double strength, int threads, const ChunkOutputs<Scalar>& o,
                  std::vector<ChunkReport>* reports); // defined for double (lattice_points.cpp)

/// deform's positions (and the normals by cof(J) where normals is not None, det J where wantDet)
/// in the dtype of the points: float32 points give float32 arrays, the rest float64.
py::array deformAny(const freeform::Lattice& lat, const PointsIn& a, double strength, int threads, py::handle normals,
                    bool wantDet, py::array* normalsOut, py::array* detOut);

/// The rows of `a` as an (K, 3) float64 block checked against the lattice's K (lattice.cpp).
py::array_t<double, py::array::c_style> controlBlock(py::handle h, const freeform::Lattice& lat, const std::string& what);

/// Lattice.weights, weights_matvec and weights_rmatvec (docs/python.md, "Sensitivities"), added to
/// the class bindLattice made (module.cpp calls this right after bindLattice).
void bindLatticeWeights(py::module_& m);

} // namespace ffpy
