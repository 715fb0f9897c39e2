#pragma once
// Scalar polynomials in Bernstein form on [0, 1]: evaluation, subdivision, products and all real
// roots. Used by the tight bounding box (roots of each coordinate of the hodograph) and by the
// global closest point (roots of (f(t) - p) . f'(t)).
//
// Root isolation works by subdivision and the variation-diminishing property: a Bernstein
// polynomial has at most as many roots in its interval as its coefficient sequence has sign
// changes, and an odd number when the end values differ in sign. An interval with exactly one
// sign change therefore holds exactly one simple root, which is refined by safeguarded bisection
// (regula falsi, Illinois variant) to full precision.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace freeform {

/// Value of sum c_i B_i^n(t) by de Casteljau; n = c.size() - 1.
template <typename Scalar>
Scalar bernsteinPolyValue(const std::vector<Scalar>& c, Scalar t)
{
    std::vector<Scalar> w(c);
    const Scalar s = Scalar(1) - t;
    for (std::size_t r = 1; r < w.size(); ++r) {
        for (std::size_t i = 0; i + r < w.size(); ++i) w[i] = s * w[i] + t * w[i + 1];
    }
    return w.empty() ? Scalar(0) : w[0];
}

/// Splits the polynomial at t into the coefficients over [0, t] and over [t, 1].
template <typename Scalar>
void bernsteinPolySplit(const std::vector<Scalar>& c, Scalar t, std::vector<Scalar>& left,
                        std::vector<Scalar>& right)
{
    const std::size_t n1 = c.size();
    std::vector<Scalar> w(c);
    left.resize(n1);
    right.resize(n1);
    const Scalar s = Scalar(1) - t;
    left[0] = w[0];
    right[n1 - 1] = w[n1 - 1];
    for (std::size_t r = 1; r < n1; ++r) {
        for (std::size_t i = 0; i + r < n1; ++i) w[i] = s * w[i] + t * w[i + 1];
        left[r] = w[0];
        right[n1 - 1 - r] = w[n1 - 1 - r];
    }
}

/// Coefficients of the product of two Bernstein polynomials (degrees a and b) as one of degree a+b:
///   (pq)_k = sum_{i+j=k} C(a,i) C(b,j) / C(a+b,k) p_i q_j.
/// Binomials are formed in long double, so degrees up to a+b = 1000 neither overflow nor lose
/// more than a few ulps.
template <typename Scalar>
std::vector<Scalar> bernsteinPolyProduct(const std::vector<Scalar>& p, const std::vector<Scalar>& q)
{
    const int a = static_cast<int>(p.size()) - 1;
    const int b = static_cast<int>(q.size()) - 1;
    auto lbinom = [](int n, int k) {
        long double r = 1;
        for (int i = 1; i <= k; ++i) r = r * static_cast<long double>(n - k + i) / i;
        return r;
    };
    std::vector<Scalar> out(static_cast<std::size_t>(a + b + 1), Scalar(0));
    for (int k = 0; k <= a + b; ++k) {
        const long double denom = lbinom(a + b, k);
        long double sum = 0;
        for (int i = std::max(0, k - b); i <= std::min(a, k); ++i) {
            sum += lbinom(a, i) * lbinom(b, k - i) / denom * static_cast<long double>(p[i]) *
                   static_cast<long double>(q[k - i]);
        }
        out[static_cast<std::size_t>(k)] = static_cast<Scalar>(sum);
    }
    return out;
}

namespace detail {

template <typename Scalar>
int signChanges(const std::vector<Scalar>& c)
{
    int changes = 0;
    int last = 0;
    for (const Scalar& v : c) {
        const int s = (v > 0) - (v < 0);
        if (s == 0) continue;
        if (last != 0 && s != last) ++changes;
        last = s;
    }
    return changes;
}

template <typename Scalar>
Scalar refineSimpleRoot(const std::vector<Scalar>& c, Scalar lo, Scalar hi, Scalar flo, Scalar fhi)
{
    // Illinois regula falsi on the global polynomial, bracket kept.
    int side = 0;
    for (int iter = 0; iter < 200 && hi - lo > std::numeric_limits<Scalar>::epsilon() * 4; ++iter) {
        Scalar x = (lo * fhi - hi * flo) / (fhi - flo);
        if (!(x > lo && x < hi)) x = (lo + hi) / 2;
        const Scalar fx = bernsteinPolyValue(c, x);
        if (fx == 0) return x;
        if ((fx > 0) == (fhi > 0)) {
            hi = x;
            fhi = fx;
            if (side == -1) flo /= 2;
            side = -1;
        } else {
            lo = x;
            flo = fx;
            if (side == +1) fhi /= 2;
            side = +1;
        }
    }
    return (lo + hi) / 2;
}

template <typename Scalar>
void isolateRoots(const std::vector<Scalar>& global, const std::vector<Scalar>& local, Scalar lo,
                  Scalar hi, int depth, std::vector<Scalar>& roots)
{
    const int changes = signChanges(local);
    if (changes == 0) {
        // An all-zero coefficient list means the polynomial vanishes here: report the midpoint.
        if (std::all_of(local.begin(), local.end(), [](Scalar v) { return v == 0; }))
            roots.push_back((lo + hi) / 2);
        return;
    }
    const Scalar f0 = local.front(), f1 = local.back();
    if (changes == 1 && f0 != 0 && f1 != 0) {
        roots.push_back(refineSimpleRoot(global, lo, hi, f0, f1));
        return;
    }
    const Scalar width = hi - lo;
    if (depth > 60 || width < std::sqrt(std::numeric_limits<Scalar>::epsilon()) * Scalar(1e-4)) {
        roots.push_back((lo + hi) / 2); // a multiple root or a cluster: its location to ~1e-12
        return;
    }
    std::vector<Scalar> left, right;
    bernsteinPolySplit(local, Scalar(0.5), left, right);
    const Scalar mid = (lo + hi) / 2;
    isolateRoots(global, left, lo, mid, depth + 1, roots);
    isolateRoots(global, right, mid, hi, depth + 1, roots);
}

} // namespace detail

/// All roots in [0, 1] of the Bernstein polynomial with coefficients c, sorted. Simple roots are
/// found to full precision; multiple roots and tight clusters to about sqrt(eps) * 1e-4.
template <typename Scalar>
std::vector<Scalar> bernsteinPolyRoots(const std::vector<Scalar>& c)
{
    std::vector<Scalar> roots;
    if (c.empty()) return roots;
    detail::isolateRoots(c, c, Scalar(0), Scalar(1), 0, roots);
    std::sort(roots.begin(), roots.end());
    // Roots at a subdivision point can be reported by both halves.
    roots.erase(std::unique(roots.begin(), roots.end(),
                            [](Scalar x, Scalar y) {
                                return std::abs(x - y) < Scalar(64) * std::numeric_limits<Scalar>::epsilon();
                            }),
                roots.end());
    return roots;
}

} // namespace freeform
