#pragma once
// The Bernstein basis B_i^n(t) = C(n,i) t^i (1-t)^(n-i), i = 0..n.
//
// Guarantees (tested in tests/test_bernstein.cpp):
//   - binomial(n, k) is exact for 0 <= k <= n <= kMaxDegree (64-bit integer table, no overflow);
//   - bernsteinAll() computes all n+1 values in O(n) with a relative error of at most about 2n ulps
//     per value (products of non-negative factors only, no cancellation);
//   - degrees above kMaxDegree are rejected with freeform::Error.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "freeform/core/error.h"

namespace freeform {

/// Highest degree the library accepts for curves, surfaces and volumes. C(67, 33) still fits in a
/// 64-bit unsigned integer; C(68, 34) does not, so every binomial below is exact.
inline constexpr int kMaxDegree = 67;

namespace detail {
inline constexpr auto kBinomialTable = [] {
    std::array<std::array<std::uint64_t, kMaxDegree + 1>, kMaxDegree + 1> table{};
    for (int n = 0; n <= kMaxDegree; ++n) {
        table[n][0] = table[n][n] = 1;
        for (int k = 1; k < n; ++k) table[n][k] = table[n - 1][k - 1] + table[n - 1][k];
    }
    return table;
}();
} // namespace detail

/// Throws Error naming `what` when degree is negative or above kMaxDegree.
inline void requireDegree(int degree, std::string_view what)
{
    if (degree < 0 || degree > kMaxDegree) {
        throw Error(std::string(what) + ": degree " + std::to_string(degree) + " is outside 0.." +
                    std::to_string(kMaxDegree));
    }
}

/// C(n, k), exact; 0 when k < 0 or k > n. Requires 0 <= n <= kMaxDegree.
constexpr std::uint64_t binomial(int n, int k)
{
    if (k < 0 || k > n) return 0;
    return detail::kBinomialTable[n][k];
}

/// C(n, k) as a long double for any n >= 0: exact from the table up to kMaxDegree, above by the
/// product formula (relative error about k ulps). For what passes the cap on its way down again:
/// a part's face composed with a lattice and then degree reduced (brep/part_deform.h).
inline long double binomialWide(int n, int k)
{
    if (k < 0 || k > n) return 0;
    if (n <= kMaxDegree) return static_cast<long double>(binomial(n, k));
    long double r = 1;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
}

/// t^e by repeated squaring (e >= 0); exact for e = 0, 1 and well defined for t = 0.
template <typename Scalar>
constexpr Scalar powInt(Scalar t, int e)
{
    Scalar result(1);
    while (e > 0) {
        if (e & 1) result *= t;
        t *= t;
        e >>= 1;
    }
    return result;
}

/// B_i^n(t); 0 for i outside 0..n.
template <typename Scalar>
Scalar bernstein(int n, int i, Scalar t)
{
    if (i < 0 || i > n) return Scalar(0);
    return Scalar(binomial(n, i)) * powInt(t, i) * powInt(Scalar(1) - t, n - i);
}

/// All n+1 values B_0^n(t) .. B_n^n(t) into out[0..n], in O(n).
template <typename Scalar>
void bernsteinAll(int n, Scalar t, Scalar* out)
{
    const Scalar s = Scalar(1) - t;
    // Forward: out[i] = C(n,i) t^i. Backward: multiply by (1-t)^(n-i).
    Scalar power(1);
    for (int i = 0; i <= n; ++i) {
        out[i] = Scalar(binomial(n, i)) * power;
        power *= t;
    }
    power = Scalar(1);
    for (int i = n; i >= 0; --i) {
        out[i] *= power;
        power *= s;
    }
}

/// k-th derivative of every basis function of degree n at t, into out[0..n]:
///   d^k/dt^k B_i^n = n!/(n-k)! * sum_{j=0..k} (-1)^(k-j) C(k,j) B_(i-j)^(n-k)(t).
/// Zero for k > n. `scratch` must hold n+1 values.
template <typename Scalar>
void bernsteinDerivativeAll(int n, int k, Scalar t, Scalar* out, Scalar* scratch)
{
    for (int i = 0; i <= n; ++i) out[i] = Scalar(0);
    if (k > n) return;
    const int m = n - k;
    bernsteinAll(m, t, scratch);
    Scalar factor(1);
    for (int r = 0; r < k; ++r) factor *= Scalar(n - r);
    for (int i = 0; i <= n; ++i) {
        Scalar sum(0);
        for (int j = 0; j <= k; ++j) {
            const int idx = i - j;
            if (idx < 0 || idx > m) continue;
            const Scalar term = Scalar(binomial(k, j)) * scratch[idx];
            sum += ((k - j) % 2 == 0) ? term : -term;
        }
        out[i] = factor * sum;
    }
}

/// All n+1 values B_0^n(t) .. B_n^n(t) into b[0..n] by de Casteljau's triangle: level r from level
/// r - 1 by b_i <- t b_(i-1) + (1-t) b_i, convex combinations only, so no value loses digits to
/// cancellation. The evaluation kernels' one basis (the lattice's sensitivities, the patch
/// tessellation's rows and their derivatives), so that they give the same bits. N > 0 fixes the
/// degree at compile time (the loops unrolled); always inlined, so a caller's b stays in registers.
template <int N = 0>
[[gnu::always_inline]] inline void bernsteinTriangle(int n, double t, double* b)
{
    if constexpr (N > 0) n = N;
    b[0] = 1;
    const double s = 1 - t;
    for (int r = 1; r <= n; ++r) {
        double carry = 0;
        for (int i = 0; i < r; ++i) {
            const double x = b[i];
            b[i] = carry + s * x;
            carry = t * x;
        }
        b[r] = carry;
    }
}

} // namespace freeform
