// Bernstein basis: exact binomials, partition of unity, non-negativity, maxima, derivatives.

#include <catch2/catch.hpp>

#include <freeform/core/bernstein.h>

#include <cmath>
#include <vector>

namespace test_bernstein {

using namespace freeform;

__extension__ typedef unsigned __int128 U128; // exact reference arithmetic

TEST_CASE("binomials are exact up to the maximum degree", "[bernstein]")
{
    // Independent computation in 128-bit integers: C(n,k) = C(n,k-1) (n-k+1) / k.
    for (int n = 0; n <= kMaxDegree; ++n) {
        U128 c = 1;
        for (int k = 0; k <= n; ++k) {
            if (k > 0) c = c * static_cast<unsigned>(n - k + 1) / static_cast<unsigned>(k);
            INFO("n = " << n << ", k = " << k);
            REQUIRE(binomial(n, k) == static_cast<std::uint64_t>(c));
        }
    }
    CHECK(binomial(67, 33) == 14226520737620288370ull);
    CHECK(binomial(4, 2) == 6);
    CHECK(binomial(5, -1) == 0);
    CHECK(binomial(5, 6) == 0);
}

TEST_CASE("degrees beyond the maximum are rejected", "[bernstein]")
{
    CHECK_NOTHROW(requireDegree(kMaxDegree, "test"));
    CHECK_THROWS_AS(requireDegree(kMaxDegree + 1, "test"), Error);
    CHECK_THROWS_WITH(requireDegree(-1, "curve \"c\""), Catch::Contains("curve \"c\"") && Catch::Contains("degree -1"));
}

TEST_CASE("hand-computed Bernstein values", "[bernstein]")
{
    // Cubic at t = 1/2: (1, 3, 3, 1) / 8; at t = 1/4: (27, 27, 9, 1) / 64. Both exact in binary.
    double b[4];
    bernsteinAll(3, 0.5, b);
    CHECK(b[0] == 0.125);
    CHECK(b[1] == 0.375);
    CHECK(b[2] == 0.375);
    CHECK(b[3] == 0.125);
    bernsteinAll(3, 0.25, b);
    CHECK(b[0] == 27.0 / 64);
    CHECK(b[1] == 27.0 / 64);
    CHECK(b[2] == 9.0 / 64);
    CHECK(b[3] == 1.0 / 64);
    CHECK(bernstein(3, 1, 0.25) == 27.0 / 64);
    CHECK(bernstein(3, 4, 0.25) == 0.0);
    CHECK(bernstein(0, 0, 0.7) == 1.0);
}

TEST_CASE("partition of unity, non-negativity and endpoint values for degrees 0..67", "[bernstein]")
{
    std::vector<double> b(kMaxDegree + 1);
    for (int n = 0; n <= kMaxDegree; ++n) {
        for (int s = 0; s <= 200; ++s) {
            const double t = s / 200.0;
            bernsteinAll(n, t, b.data());
            double sum = 0;
            for (int i = 0; i <= n; ++i) {
                INFO("n = " << n << ", i = " << i << ", t = " << t);
                REQUIRE(b[i] >= 0.0);
                // The O(n) values agree with the single-value formula.
                REQUIRE(std::abs(b[i] - bernstein(n, i, t)) <= 1e-15 * (1 + b[i]) * n);
                sum += b[i];
            }
            INFO("n = " << n << ", t = " << t);
            REQUIRE(std::abs(sum - 1.0) <= 4e-16 * (n + 1));
        }
        bernsteinAll(n, 0.0, b.data());
        CHECK(b[0] == 1.0);
        bernsteinAll(n, 1.0, b.data());
        CHECK(b[n] == 1.0);
    }
}

TEST_CASE("B_i^n has its single maximum at t = i/n", "[bernstein]")
{
    for (int n = 1; n <= 20; ++n) {
        for (int i = 0; i <= n; ++i) {
            const double peak = bernstein(n, i, double(i) / n);
            for (int s = 0; s <= 1000; ++s) {
                const double t = s / 1000.0;
                INFO("n = " << n << ", i = " << i << ", t = " << t);
                REQUIRE(bernstein(n, i, t) <= peak * (1 + 1e-14));
            }
            // Strictly smaller a little to each side (single maximum).
            if (i > 0) CHECK(bernstein(n, i, double(i) / n - 1e-3) < peak);
            if (i < n) CHECK(bernstein(n, i, double(i) / n + 1e-3) < peak);
        }
    }
}

TEST_CASE("basis derivatives: d/dt B_i^n = n (B_(i-1)^(n-1) - B_i^(n-1)) and finite differences", "[bernstein]")
{
    std::vector<long double> d(kMaxDegree + 1), scratch(kMaxDegree + 1), lo(kMaxDegree + 1), hi(kMaxDegree + 1);
    for (int n = 1; n <= 20; ++n) {
        for (long double t : {0.0L, 0.1L, 0.37L, 0.5L, 0.93L, 1.0L}) {
            bernsteinDerivativeAll(n, 1, t, d.data(), scratch.data());
            for (int i = 0; i <= n; ++i) {
                const long double expected = n * (bernstein(n - 1, i - 1, t) - bernstein(n - 1, i, t));
                INFO("n = " << n << ", i = " << i << ", t = " << double(t));
                REQUIRE(std::abs(double(d[i] - expected)) <= 1e-15 * std::pow(2.0, n / 2.0));
            }
            // Second derivative against a central difference of the first (interior t only).
            if (t <= 0.0L || t >= 1.0L) continue;
            const long double h = 1e-5L;
            bernsteinDerivativeAll(n, 2, t, d.data(), scratch.data());
            bernsteinDerivativeAll(n, 1, t - h, lo.data(), scratch.data());
            bernsteinDerivativeAll(n, 1, t + h, hi.data(), scratch.data());
            for (int i = 0; i <= n; ++i) {
                const long double fd = (hi[i] - lo[i]) / (2 * h);
                INFO("n = " << n << ", i = " << i << ", t = " << double(t));
                REQUIRE(std::abs(double(d[i] - fd)) <= 1e-6 * std::pow(double(n), 4));
            }
        }
        // Orders above the degree vanish.
        bernsteinDerivativeAll(n, n + 1, 0.3L, d.data(), scratch.data());
        for (int i = 0; i <= n; ++i) CHECK(d[i] == 0.0L);
    }
}

} // namespace test_bernstein
