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
// Parameters are processed in blocks of 8 lanes in structure-of-arrays form so the compiler
// vectorises across parameters; for float and double in 2D and 3D the library ships clones for
// x86-64-v3 (AVX2 + FMA) and the baseline, chosen at load time from the CPU (no -march=native).

#include <cstddef>

#include "freeform/core/bernstein.h"

namespace freeform {

namespace detail {

inline constexpr int kBatchLanes = 8;

/// ctrl: Dim x (n+1) column-major control points; ts: count parameters; out: Dim x count.
template <typename Scalar, int Dim>
inline __attribute__((always_inline)) void bezierBatchKernel(const Scalar* ctrl, int n, const Scalar* ts,
                                                             std::size_t count, Scalar* out)
{
    constexpr int W = kBatchLanes;
    // Scaled coefficients C(n,i) b_i, coordinate-major so lanes read one scalar each.
    Scalar cb[(kMaxDegree + 1) * Dim];
    for (int i = 0; i <= n; ++i)
        for (int d = 0; d < Dim; ++d) cb[i * Dim + d] = Scalar(binomial(n, i)) * ctrl[i * Dim + d];

    std::size_t start = 0;
    while (start < count) {
        const std::size_t lanes = (count - start < std::size_t(W)) ? count - start : std::size_t(W);
        Scalar t[W], s[W], scale[W], acc[Dim][W];
        bool mirrored[W];
        for (int w = 0; w < W; ++w) t[w] = ts[start + (std::size_t(w) < lanes ? std::size_t(w) : 0)];
        for (int w = 0; w < W; ++w) {
            const Scalar u = Scalar(1) - t[w];
            mirrored[w] = t[w] > Scalar(0.5);
            const Scalar num = mirrored[w] ? u : t[w];
            const Scalar den = mirrored[w] ? t[w] : u;
            s[w] = num / den;
            // den^n by repeated squaring, lane-wise.
            Scalar base = den, result = Scalar(1);
            for (int e = n; e > 0; e >>= 1) {
                if (e & 1) result *= base;
                base *= base;
            }
            scale[w] = result;
        }
        for (int d = 0; d < Dim; ++d)
            for (int w = 0; w < W; ++w) acc[d][w] = mirrored[w] ? cb[d] : cb[n * Dim + d];
        for (int i = n - 1; i >= 0; --i) {
            const Scalar* fwd = cb + i * Dim;
            const Scalar* rev = cb + (n - i) * Dim;
            for (int d = 0; d < Dim; ++d)
                for (int w = 0; w < W; ++w) acc[d][w] = acc[d][w] * s[w] + (mirrored[w] ? rev[d] : fwd[d]);
        }
        for (std::size_t w = 0; w < lanes; ++w)
            for (int d = 0; d < Dim; ++d) out[(start + w) * Dim + d] = acc[d][w] * scale[w];
        start += lanes;
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
