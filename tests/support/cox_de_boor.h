#pragma once
// Independent B-spline references for the NURBS tests: the Cox-de Boor recursion and the recursive
// derivative formula in long double, and seeded random knot vectors with multiple knots.

#include <random>
#include <vector>

namespace freeform::test {

using LD = long double;

/// N_(i,p)(u) by the Cox-de Boor recursion (0/0 = 0), right-continuous, except that at the right
/// end of the domain the last non-empty span is used (as the library does).
inline LD coxDeBoor(const std::vector<LD>& U, int i, int p, LD u, int span)
{
    if (p == 0) return i == span ? 1.0L : 0.0L;
    LD r = 0;
    if (U[i + p] != U[i]) r += (u - U[i]) / (U[i + p] - U[i]) * coxDeBoor(U, i, p - 1, u, span);
    if (U[i + p + 1] != U[i + 1]) r += (U[i + p + 1] - u) / (U[i + p + 1] - U[i + 1]) * coxDeBoor(U, i + 1, p - 1, u, span);
    return r;
}

/// d^k/du^k N_(i,p)(u) by N'_(i,p) = p (N_(i,p-1)/(u_(i+p)-u_i) - N_(i+1,p-1)/(u_(i+p+1)-u_(i+1))).
inline LD coxDeBoorDerivative(const std::vector<LD>& U, int i, int p, int k, LD u, int span)
{
    if (k == 0) return coxDeBoor(U, i, p, u, span);
    if (p == 0) return 0;
    LD r = 0;
    if (U[i + p] != U[i]) r += p / (U[i + p] - U[i]) * coxDeBoorDerivative(U, i, p - 1, k - 1, u, span);
    if (U[i + p + 1] != U[i + 1]) r -= p / (U[i + p + 1] - U[i + 1]) * coxDeBoorDerivative(U, i + 1, p - 1, k - 1, u, span);
    return r;
}

/// The span (index i with U[i] <= u < U[i+1]) the reference uses: the last non-empty one at the end.
inline int referenceSpan(const std::vector<LD>& U, int p, int n, LD u)
{
    if (u >= U[n + 1]) {
        int i = n;
        while (U[i] == U[i + 1]) --i;
        return i;
    }
    int i = p;
    while (!(U[i] <= u && u < U[i + 1])) ++i;
    return i;
}

/// A random knot vector of degree p for `count` control points: clamped or not, with interior
/// knots of random multiplicity 1..p on a grid (so that repeated knots are exact).
inline std::vector<double> randomKnots(int p, int count, bool clamped, std::mt19937& rng)
{
    std::uniform_int_distribution<int> mult(1, p), step(1, 3);
    std::vector<double> k;
    const int total = count + p + 1;
    double x = 0;
    if (clamped) k.assign(static_cast<std::size_t>(p + 1), 0.0);
    while (static_cast<int>(k.size()) < total - (clamped ? p + 1 : 0)) {
        x += 0.125 * step(rng);
        const int m = clamped || k.empty() ? mult(rng) : 1;
        for (int r = 0; r < m && static_cast<int>(k.size()) < total - (clamped ? p + 1 : 0); ++r) k.push_back(x);
    }
    if (clamped) {
        x += 0.125 * step(rng);
        k.insert(k.end(), static_cast<std::size_t>(p + 1), x);
    }
    return k;
}

} // namespace freeform::test
