#pragma once
// The batch evaluation path: one Bézier curve at many parameters.
//
// Algorithm (Volk and Schumaker's scaled Horner scheme, "VS"): for t <= 1/2
//     f(t) = (1-t)^n * sum_i C(n,i) b_i s^i,        s = t / (1-t)      in [0, 1],
// and for t > 1/2 the mirror image with s = (1-t)/t and the factor t^n. Each point costs n fused
// multiply-adds per coordinate plus one division and log2(n) multiplications, against n(n+1)/2
// convex combinations for de Casteljau. Because s never exceeds 1 and the scaled coefficients
// C(n,i) b_i enter with the non-negative weights s^i, the standard Horner error bound gives
// |error| <= ~2n eps * sum_i |b_i| B_i^n(t): the same bound as de Casteljau. A power-basis
// (monomial) Horner scheme has no such bound: its coefficients alternate and grow like 2^n, which
// is why Open CASCADE's cached evaluator loses digits at high degree and this path does not.
//
// For float and double, parameters are processed in blocks of one 256-bit register (4 doubles or 8
// floats) written with GCC vector extensions, so every statement is one SIMD operation across
// parameters; the library ships clones for x86-64-v3 (AVX2 + FMA) and the baseline, chosen at load
// time from the CPU (no -march=native). Other scalar types (long double) run the same scheme one
// parameter at a time.

#include <cstddef>
#include <type_traits>

#include "freeform/core/bernstein.h"

namespace freeform {

namespace detail {

/// One block of W parameters (SoA): out[d][w] = f(t[w]). Written with GCC vector extensions, so
/// each statement is one SIMD operation over the W lanes (two or four machine vectors).
template <typename Scalar, int Dim, int W>
inline __attribute__((always_inline)) void bezierBatchBlock(const Scalar* cbf, const Scalar* cbr, int n,
                                                            const Scalar* t, Scalar (*out)[W])
{
    typedef Scalar Lanes __attribute__((vector_size(W * sizeof(Scalar))));
    Lanes tv;
    __builtin_memcpy(&tv, t, sizeof(Lanes));
    const Lanes one = tv * Scalar(0) + Scalar(1);
    const Lanes uv = one - tv;
    const auto mirrored = tv > Scalar(0.5);          // lanes that run the reversed Horner scheme
    const Lanes lo = mirrored ? uv : tv;              // min(t, 1-t)
    const Lanes hi = mirrored ? tv : uv;              // max(t, 1-t) >= 1/2, never 0
    const Lanes s = lo / hi;
    Lanes base = hi, scale = one;
    for (int e = n; e > 0; e >>= 1) { // hi^n by repeated squaring
        if (e & 1) scale *= base;
        base *= base;
    }
    // Horner in s over the coefficients in the lane's own order: forward where t <= 1/2
    // (s = t/(1-t)), reversed where t > 1/2 (s = (1-t)/t).
    Lanes acc[Dim];
    for (int d = 0; d < Dim; ++d) {
        const Lanes f = one * cbf[n * Dim + d], r = one * cbr[n * Dim + d];
        acc[d] = mirrored ? r : f;
    }
    for (int i = n - 1; i >= 0; --i) {
        for (int d = 0; d < Dim; ++d) {
            const Lanes f = one * cbf[i * Dim + d], r = one * cbr[i * Dim + d];
            acc[d] = acc[d] * s + (mirrored ? r : f);
        }
    }
    for (int d = 0; d < Dim; ++d) {
        const Lanes v = acc[d] * scale;
        __builtin_memcpy(out[d], &v, sizeof(Lanes));
    }
}

/// The same for one parameter, in plain scalar code (long double and other scalar types).
template <typename Scalar, int Dim>
inline void bezierBatchOne(const Scalar* cbf, const Scalar* cbr, int n, Scalar t, Scalar* out)
{
    const bool mirrored = t > Scalar(0.5);
    const Scalar u = Scalar(1) - t;
    const Scalar s = mirrored ? u / t : t / u;
    const Scalar scale = powInt(mirrored ? t : u, n);
    const Scalar* c = mirrored ? cbr : cbf;
    for (int d = 0; d < Dim; ++d) {
        Scalar acc = c[n * Dim + d];
        for (int i = n - 1; i >= 0; --i) acc = acc * s + c[i * Dim + d];
        out[d] = acc * scale;
    }
}

/// ctrl: Dim x (n+1) column-major control points; ts: count parameters; out: Dim x count.
template <typename Scalar, int Dim>
inline __attribute__((always_inline)) void bezierBatchKernel(const Scalar* ctrl, int n, const Scalar* ts,
                                                             std::size_t count, Scalar* out)
{
    // Scaled coefficients C(n,i) b_i, forward and reversed (cbr[i] = cbf[n-i]).
    Scalar cbf[(kMaxDegree + 1) * Dim], cbr[(kMaxDegree + 1) * Dim];
    for (int i = 0; i <= n; ++i)
        for (int d = 0; d < Dim; ++d) {
            cbf[i * Dim + d] = Scalar(binomial(n, i)) * ctrl[i * Dim + d];
            cbr[(n - i) * Dim + d] = cbf[i * Dim + d];
        }
    if constexpr (!(std::is_same_v<Scalar, float> || std::is_same_v<Scalar, double>)) {
        for (std::size_t j = 0; j < count; ++j) bezierBatchOne<Scalar, Dim>(cbf, cbr, n, ts[j], out + j * Dim);
    } else {
        constexpr int W = int(32 / sizeof(Scalar)); // one 256-bit register of lanes
        Scalar block[Dim][W];
        std::size_t start = 0;
        for (; start + W <= count; start += W) {
            bezierBatchBlock<Scalar, Dim, W>(cbf, cbr, n, ts + start, block);
            for (int w = 0; w < W; ++w)
                for (int d = 0; d < Dim; ++d) out[(start + std::size_t(w)) * Dim + d] = block[d][w];
        }
        for (; start < count; ++start) bezierBatchOne<Scalar, Dim>(cbf, cbr, n, ts[start], out + start * Dim);
    }
}

} // namespace detail

/// f(ts[j]) for j < count into out (Dim x count, column-major). ctrl holds the n+1 control points
/// as Dim x (n+1) column-major. No checks: the caller (BezierCurve) has validated its data.
template <typename Scalar, int Dim>
void evaluateBezierBatch(const Scalar* ctrl, int n, const Scalar* ts, std::size_t count, Scalar* out)
{
    detail::bezierBatchKernel<Scalar, Dim>(ctrl, n, ts, count, out);
}

// Compiled with CPU dispatch in src/curve/batch.cpp.
template <> void evaluateBezierBatch<float, 2>(const float*, int, const float*, std::size_t, float*);
template <> void evaluateBezierBatch<float, 3>(const float*, int, const float*, std::size_t, float*);
template <> void evaluateBezierBatch<double, 2>(const double*, int, const double*, std::size_t, double*);
template <> void evaluateBezierBatch<double, 3>(const double*, int, const double*, std::size_t, double*);

} // namespace freeform
