#pragma once
// Seeded random control points for property tests: every run draws the same numbers, and a
// failure names the seed and degree through Catch2's INFO/CAPTURE.

#include <Eigen/Core>

#include <cstdint>
#include <random>

namespace freeform::test {

/// Dim x count points with coordinates uniform in [lo, hi].
template <typename Scalar, int Dim>
Eigen::Matrix<Scalar, Dim, Eigen::Dynamic> randomPoints(int count, std::uint32_t seed, double lo = -1, double hi = 1)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(lo, hi);
    Eigen::Matrix<Scalar, Dim, Eigen::Dynamic> p(Dim, count);
    for (int i = 0; i < count; ++i)
        for (int k = 0; k < Dim; ++k) p(k, i) = static_cast<Scalar>(u(rng));
    return p;
}

} // namespace freeform::test
